"""``sloshkit calibrate``: frequency and damping from a record (free decay or forced response)."""

from __future__ import annotations

import math
import typing
import warnings
from pathlib import Path
from typing import Annotated

import numpy as np
import typer
from rich.table import Table
from rich.text import Text

from sloshkit.calibration import (
    METHODS,
    SIGNAL_KINDS,
    calibrate,
    identify_forced,
)
from sloshkit.calibration.model_in_loop import identify_line, identify_spatial
from sloshkit.cli.app import app, stdout
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.io.calibration_requests import applied_motion_request, record_request
from sloshkit.io.models import write_model_file
from sloshkit.io.outputs import check_file
from sloshkit.io.units import parse_quantity
from sloshkit.model.modal import SloshModel


@app.command("calibrate")
@with_model_options
def calibrate_command(
    slosh_model: SloshModel,
    data: Annotated[Path, typer.Argument(help="CSV or whitespace table; '#' lines skipped.")],
    time_column: Annotated[str, typer.Option("--time-column", help="Name or 0-based index.")] = "0",
    signal_column: Annotated[
        str, typer.Option("--signal-column", help="Name or 0-based index.")
    ] = "1",
    time_unit: Annotated[
        str | None,
        typer.Option(
            "--time-unit", help="Unit of the time column (default: from its header, else s)."
        ),
    ] = None,
    start: Annotated[
        str | None,
        typer.Option("--start", help="Window start (default: found after the forcing)."),
    ] = None,
    end: Annotated[
        str | None, typer.Option("--end", help="Window end (default: last sample).")
    ] = None,
    method: Annotated[
        str | None,
        typer.Option(
            "--method",
            help="Reported estimator: fit, logdec, fft, logdec-2peak, backbone, forced "
            "(default: forced with --motion-file, else fit).",
        ),
    ] = None,
    motion_file: Annotated[
        Path | None,
        typer.Option(
            "--motion-file",
            help="The applied motion (motion or pose file, same clock as the record): "
            "forced-response identification, and the decay window after its end.",
        ),
    ] = None,
    motion_axis: Annotated[
        str | None,
        typer.Option("--motion-axis", help="Pose files: x, y or z (default: main direction)."),
    ] = None,
    signal_kind: Annotated[
        str, typer.Option("--signal-kind", help="force, height or angle (for --motion-file).")
    ] = "height",
    clock_offset: Annotated[
        str,
        typer.Option("--clock-offset", help="Record time minus motion-file time, e.g. 8.1s."),
    ] = "0s",
    fit_clock_offset: Annotated[
        bool,
        typer.Option(
            "--fit-clock-offset", help="Fit the clock offset within 0.5 s (height, angle)."
        ),
    ] = False,
    settle: Annotated[
        str | None,
        typer.Option("--settle", help="Margin after the forcing (default: one period)."),
    ] = None,
    detrend: Annotated[str, typer.Option("--detrend", help="mean, linear or none.")] = "linear",
    lowpass: Annotated[
        str | None, typer.Option("--lowpass", help="Zero-phase low-pass cut-off, e.g. 20Hz.")
    ] = None,
    model_file_out: Annotated[
        Path | None,
        typer.Option("--model-file-out", help="Write the calibrated model (TOML/JSON)."),
    ] = None,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="Figure like the paper's Fig. 5b.")
    ] = None,
    backbone_plot: Annotated[
        Path | None,
        typer.Option("--backbone-plot", help="Figure of frequency and damping vs amplitude."),
    ] = None,
    json_output: Json = False,
) -> None:
    """Natural frequency and damping from a record (camera, force sensor, CFD probe).

    Without window options the free decay is found after the forced motion. With
    --motion-file the model is also fitted to the whole record (forced-response
    identification, no free decay needed); a pose file with a height signal drives the 3-D
    model (slosh height), --motion-axis the 1-D one. The model options describe the container,
    for the comparison with theory, the identification and the calibrated model file.

    Examples:

      sloshkit calibrate decay.csv --time-column t --signal-column eta --start 4s --plot fig.png

      sloshkit calibrate record.csv --time-column t --signal-column fy

      sloshkit calibrate record.csv --time-column t --signal-column fy --signal-kind force
      --motion-file move.csv --radius 40mm --fill-height 60mm

      sloshkit calibrate heights.csv --time-column t_s --signal-column slosh_height_m
      --motion-file poses.csv --clock-offset 9.36s --fit-clock-offset --radius 49mm
      --fill-height 80mm
    """
    check_file(model_file_out, "model_file_out", "model")
    check_file(plot, "plot", "figure")
    check_file(backbone_plot, "backbone_plot", "figure")
    methods = (*METHODS, "forced")
    if method is None:
        method = "forced" if motion_file is not None else "fit"
    if method not in methods:
        raise InputError("method", method, "must be one of " + ", ".join(methods))
    if method == "forced" and motion_file is None:
        raise InputError("method", method, "needs --motion-file (the applied motion)")
    if detrend not in ("mean", "linear", "none"):
        raise InputError("detrend", detrend, "must be mean, linear or none")
    if signal_kind not in SIGNAL_KINDS:
        raise InputError("signal_kind", signal_kind, "must be one of " + ", ".join(SIGNAL_KINDS))
    time, values = record_request(data, time_column, signal_column, time_unit, signal_kind)
    lowpass_hz = None if lowpass is None else parse_quantity(lowpass, "frequency", "lowpass")
    offset = parse_quantity(clock_offset, "time", "clock_offset")
    applied, poses = (
        (None, None)
        if motion_file is None
        else applied_motion_request(motion_file, motion_axis, offset)
    )
    if (
        applied is not None
        and time.size
        and not (
            applied.start_s < float(np.nanmax(time)) and applied.end_s > float(np.nanmin(time))
        )
    ):
        raise InputError(
            "clock_offset",
            clock_offset,
            f"puts the motion at [{applied.start_s:.4g}, {applied.end_s:.4g}] s, outside the "
            f"record [{float(np.nanmin(time)):.4g}, {float(np.nanmax(time)):.4g}] s",
        )
    spatial = poses is not None and motion_axis is None and signal_kind == "height"
    if fit_clock_offset and (applied is None or signal_kind == "force"):
        raise InputError(
            "fit_clock_offset", True, "needs --motion-file and a height or angle signal"
        )
    forced = None
    if fit_clock_offset and not spatial and applied is not None:
        forced = identify_line(
            slosh_model,
            applied,
            time,
            values,
            delay_s=offset,
            signal_kind=signal_kind,
            require_constrained=method == "forced",
            source=str(data),
        )
    elif spatial and poses is not None:
        forced = identify_spatial(
            slosh_model,
            poses,
            time,
            values,
            delay_s=offset,
            fit_delay=fit_clock_offset,
            require_constrained=method == "forced",
            source=str(data),
        )
    elif applied is not None:
        forced = identify_forced(
            slosh_model,
            applied,
            time,
            values,
            signal_kind=typing.cast(typing.Any, signal_kind),
            lowpass_hz=lowpass_hz,
            require_constrained=method == "forced",
            source=str(data),
        )
    if forced is not None:
        for message in forced.warnings:
            warnings.warn(message, ValidityWarning, stacklevel=1)
    decay = None
    decay_failure = None
    try:
        decay = calibrate(
            time,
            values,
            method=typing.cast(typing.Any, "fit" if method == "forced" else method),
            start_s=None if start is None else parse_quantity(start, "time", "start"),
            end_s=None if end is None else parse_quantity(end, "time", "end"),
            detrend=typing.cast(typing.Any, detrend),
            lowpass_hz=lowpass_hz,
            source=str(data),
            forcing_end_s=None if applied is None else applied.end_s,
            settle_s=None if settle is None else parse_quantity(settle, "time", "settle"),
        )
    except InputError as error:
        if forced is None:
            raise
        decay_failure = str(error)
    reported: typing.Any = forced if method == "forced" else decay
    payload = reported.to_dict()
    payload["signal_kind"] = signal_kind
    if forced is not None:
        payload["forced"] = forced.to_dict()
        payload["motion_file"] = str(motion_file)
    if method == "forced":
        payload["decay"] = None if decay is None else decay.to_dict()
        payload["decay_failure"] = decay_failure
    theory = slosh_model.modes[0]
    payload["theory"] = {
        "omega_n_rad_s": theory.omega_rad_s,
        "frequency_hz": theory.frequency_hz,
        "damping_ratio": theory.damping_ratio,
        "damping_source": slosh_model.provenance.get("damping_ratio", ""),
    }
    if model_file_out is not None:
        write_model_file(model_file_out, reported.calibrated_model(slosh_model))
        payload["model_file"] = str(model_file_out)
        payload["model_file_provenance"] = reported.provenance()
    if plot is not None:
        reported.plot(plot)
    if backbone_plot is not None:
        if decay is None or decay.backbone is None:
            raise InputError("backbone_plot", str(backbone_plot), "no backbone in this record")
        decay.backbone.plot(backbone_plot)
    if json_output:
        print_json(payload)
        return
    _print_calibration(data, payload, decay, forced, theory)
    if model_file_out is not None:
        stdout.print(f"wrote {model_file_out}")


def _print_calibration(
    data: Path,
    payload: dict[str, typing.Any],
    decay: typing.Any,
    forced: typing.Any,
    theory: typing.Any,
) -> None:
    def cell(value: float | None, fmt: str) -> str:
        return "n/a" if value is None else format(value, fmt)

    if decay is not None:
        window = decay.signal.window_s
        table_out = Table(title=f"Free decay of {data}, window {window[0]:.3f}-{window[1]:.3f} s")
        table_out.add_column("estimator")
        for header_text in ("ω_n [rad/s]", "f_n [Hz]", "ζ [-]", "δ [-]"):
            table_out.add_column(Text(header_text), justify="right")
        for name, estimate in decay.estimates.items():
            omega = estimate.omega_n_rad_s
            reported = name == payload["method"]
            table_out.add_row(
                name
                + (" (reported)" if reported else "")
                + (" failed" if estimate.failure else ""),
                cell(omega, ".3f"),
                cell(None if omega is None else omega / (2 * math.pi), ".4f"),
                cell(estimate.damping_ratio, ".4f"),
                cell(estimate.log_decrement, ".4f"),
            )
        table_out.add_row(
            "theory (model)",
            f"{theory.omega_rad_s:.3f}",
            f"{theory.frequency_hz:.4f}",
            f"{theory.damping_ratio:.4f}",
            "",
        )
        stdout.print(table_out)
        if decay.window is not None:
            stdout.print(f"window: {decay.window.reason}")
        fit = decay.estimates["fit"]
        if fit.omega_n_interval and fit.damping_ratio_interval:
            stdout.print(
                f"fit 95 % intervals: ω_n {fit.omega_n_interval[0]:.3f}…"
                f"{fit.omega_n_interval[1]:.3f} rad/s, ζ {fit.damping_ratio_interval[0]:.4f}…"
                f"{fit.damping_ratio_interval[1]:.4f}; residual RMS {fit.residual_rms:.3g}"
            )
        for note in decay.signal.notes:
            stdout.print(f"note: {note}")
    if forced is not None:
        stdout.print(
            f"forced-response identification ({forced.signal_kind})"
            + (" (reported)" if payload["method"] == "forced" else "")
            + f": ω_n {forced.omega_n_rad_s:.3f} rad/s ({forced.omega_n_interval[0]:.3f}…"
            f"{forced.omega_n_interval[1]:.3f}), ζ {forced.damping_ratio:.4f} "
            f"({forced.damping_ratio_interval[0]:.4f}…{forced.damping_ratio_interval[1]:.4f}), "
            f"R² {forced.r2:.4f}, NRMSE {forced.nrmse:.3g}"
        )
        if forced.delay_s is not None and forced.delay_interval_s is not None:
            low, high = forced.delay_interval_s
            stdout.print(f"clock offset {forced.delay_s:.3f} s ({low:.3f}…{high:.3f})")
        if forced.slosh_mass_kg is not None:
            stdout.print(
                f"slosh mass {1e3 * forced.slosh_mass_kg:.2f} g, rigid mass "
                f"{1e3 * forced.linear['rigid_mass_kg']:.1f} g"
            )
    if payload.get("decay_failure"):
        stdout.print(f"note: no free-decay estimate: {payload['decay_failure']}")
