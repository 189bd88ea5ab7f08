"""``sloshkit calibrate``: frequency and damping from a measured free decay."""

from __future__ import annotations

import math
import typing
from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.calibration import METHODS, calibrate
from sloshkit.cli.app import app, stdout
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.errors import InputError
from sloshkit.io.models import write_model_file
from sloshkit.io.tables import column_name, read_table, select_column, unit_from_name
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
        str | None, typer.Option("--start", help="Window start (default: largest peak).")
    ] = None,
    end: Annotated[
        str | None, typer.Option("--end", help="Window end (default: last sample).")
    ] = None,
    method: Annotated[
        str, typer.Option("--method", help="Reported estimator: fit, logdec, fft.")
    ] = "fit",
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
    json_output: Json = False,
) -> None:
    """Natural frequency and damping from a free-decay record (camera, sensor, CFD probe).

    The model options describe the container, for the comparison with theory and for the
    calibrated model file.

    Examples:

      sloshkit calibrate decay.csv --time-column t --signal-column eta --start 4s --plot fig.png

      sloshkit calibrate probes.dat --signal-column 2 --method logdec --model-file-out vial.toml
    """

    if method not in METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(METHODS))
    if detrend not in ("mean", "linear", "none"):
        raise InputError("detrend", detrend, "must be mean, linear or none")
    header, table = read_table(data)
    if time_unit is None:
        time_unit = unit_from_name(column_name(header, time_column)) or "s"
    time_scale = parse_quantity(f"1 {time_unit}", "time", "time_unit")
    time = select_column(header, table, time_column, "time_column") * time_scale
    values = select_column(header, table, signal_column, "signal_column")
    result = calibrate(
        time,
        values,
        method=typing.cast(typing.Any, method),
        start_s=None if start is None else parse_quantity(start, "time", "start"),
        end_s=None if end is None else parse_quantity(end, "time", "end"),
        detrend=typing.cast(typing.Any, detrend),
        lowpass_hz=None if lowpass is None else parse_quantity(lowpass, "frequency", "lowpass"),
        source=str(data),
    )
    payload = result.to_dict()
    theory = slosh_model.modes[0]
    payload["theory"] = {
        "omega_n_rad_s": theory.omega_rad_s,
        "frequency_hz": theory.frequency_hz,
        "damping_ratio": theory.damping_ratio,
        "damping_source": slosh_model.provenance.get("damping_ratio", ""),
    }
    if model_file_out is not None:
        write_model_file(model_file_out, result.calibrated_model(slosh_model))
        payload["model_file"] = str(model_file_out)
    if plot is not None:
        result.plot(plot)
    if json_output:
        print_json(payload)
        return
    table_out = Table(
        title=f"Calibration of {data} ({method}), window "
        f"{payload['window_s'][0]:.3f}-{payload['window_s'][1]:.3f} s"
    )
    table_out.add_column("estimator")
    for header_text in ("ω_n [rad/s]", "f_n [Hz]", "ζ [-]", "δ [-]"):
        table_out.add_column(Text(header_text), justify="right")

    def cell(value: float | None, fmt: str) -> str:
        return "n/a" if value is None else format(value, fmt)

    for name, estimate in result.estimates.items():
        omega = estimate.omega_n_rad_s
        table_out.add_row(
            name + (" (reported)" if name == method else ""),
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
    fit = result.estimates["fit"]
    if fit.omega_n_interval and fit.damping_ratio_interval:
        stdout.print(
            f"fit 95 % intervals: ω_n {fit.omega_n_interval[0]:.3f}…{fit.omega_n_interval[1]:.3f} "
            f"rad/s, ζ {fit.damping_ratio_interval[0]:.4f}…{fit.damping_ratio_interval[1]:.4f}; "
            f"residual RMS {fit.residual_rms:.3g}"
        )
    for note in payload["notes"]:
        stdout.print(f"note: {note}")
    if model_file_out is not None:
        stdout.print(f"wrote {model_file_out}")
