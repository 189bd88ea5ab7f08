"""``sloshkit cfd``: the volume-of-fluid step with OpenFOAM (generate, run, analyse, validate)."""

from __future__ import annotations

import contextlib
import dataclasses
import json
import math
from collections.abc import Iterator
from contextlib import nullcontext
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cfd.pipeline import (
    RECOMMENDED,
    analyse,
    case_spec,
    describe,
    excitation_from_options,
    validate,
)
from sloshkit.cfd.pipeline import run as run_cfd
from sloshkit.cfd.run import CfdError, CfdInterrupted, interruptible
from sloshkit.cli import display, signals
from sloshkit.cli.app import app, stderr, stdout
from sloshkit.cli.moves import Distance, Duration, MoveRequest
from sloshkit.cli.options import Json, print_json, with_model_options, with_options
from sloshkit.errors import InputError
from sloshkit.files import write_columns_csv
from sloshkit.io.checks import naming
from sloshkit.io.models import write_model_file
from sloshkit.io.outputs import check_file, check_folder
from sloshkit.io.poses import read_pose_file
from sloshkit.io.units import parse_bounded, parse_quantity
from sloshkit.model.modal import SloshModel
from sloshkit.plotting import plot_cfd_validation

cfd_app = typer.Typer(
    help="The volume-of-fluid step with OpenFOAM (interFoam): generate, run, analyse, validate.",
    no_args_is_help=True,
)
app.add_typer(cfd_app, name="cfd")


CaseDir = Annotated[Path, typer.Option("--case", help="Case folder.")]


def cfd_options(excitation: str, end_time: str) -> dict[str, tuple[Any, Any]]:
    """The case options shared by the cfd commands (with their command's defaults)."""
    return {
        "excitation": (
            Annotated[
                str,
                typer.Option(
                    "--excitation",
                    help="free-decay (tilted surface), harmonic, law, or poses (--pose-file).",
                ),
            ],
            excitation,
        ),
        "tilt": (
            Annotated[str, typer.Option("--tilt", help="Initial tilt for free-decay.")],
            "3deg",
        ),
        "amplitude": (
            Annotated[str, typer.Option("--amplitude", help="Harmonic amplitude.")],
            "10mm",
        ),
        "frequency": (
            Annotated[str, typer.Option("--frequency", help="Harmonic frequency.")],
            "1Hz",
        ),
        "excite_time": (
            Annotated[str, typer.Option("--excite-time", help="Harmonic duration.")],
            "2s",
        ),
        "law": (
            Annotated[str | None, typer.Option("--law", help="Motion law for --excitation law.")],
            None,
        ),
        "distance": (Distance, "0.1m"),
        "duration": (Duration, None),
        "pose_file": (
            Annotated[
                Path | None,
                typer.Option(
                    "--pose-file",
                    help="Pose trajectory for --excitation poses (t, x, y, z and qx, qy, qz, qw "
                    "or roll, pitch, yaw; units in the header).",
                ),
            ],
            None,
        ),
        "probe_angles": (
            Annotated[
                int | None,
                typer.Option(
                    "--probe-angles",
                    help="Probe columns around the wall (default 2 on the x axis; 12 for poses).",
                ),
            ],
            None,
        ),
        "cells_per_radius": (
            Annotated[int, typer.Option("--cells-per-radius", help="Mesh resolution.")],
            RECOMMENDED["cells_per_radius"],
        ),
        "end_time": (Annotated[str, typer.Option("--end-time", help="Simulated time.")], end_time),
        "delta_t": (
            Annotated[
                str,
                typer.Option(
                    "--delta-t", help="Largest time step (the step itself with --fixed-step)."
                ),
            ],
            f"{RECOMMENDED['delta_t_s'] * 1e3:g}ms",
        ),
        "max_courant": (
            Annotated[
                float,
                typer.Option(
                    "--max-courant",
                    help="Courant and interface-Courant limit of the adaptive time step.",
                ),
            ],
            RECOMMENDED["max_courant"],
        ),
        "fixed_step": (
            Annotated[
                bool, typer.Option("--fixed-step", help="A fixed step of --delta-t (no Courant).")
            ],
            False,
        ),
        "ddt": (
            Annotated[str, typer.Option("--ddt", help="Euler, 'CrankNicolson 0.9' or backward.")],
            "Euler",
        ),
        "np_": (
            Annotated[
                int | None,
                typer.Option(
                    "--np",
                    help="MPI processes (default 1, serial; with --resume, the case's own).",
                ),
            ],
            None,
        ),
        "cfd_surface_tension": (
            Annotated[
                bool,
                typer.Option("--cfd-surface-tension", help="Include surface tension in the CFD."),
            ],
            False,
        ),
    }


def _cfd_spec(slosh_model: SloshModel, options: dict[str, Any]) -> Any:

    motion = poses = None
    if options["excitation"] == "poses":
        if options["pose_file"] is None:
            raise InputError("pose-file", None, "is needed with --excitation poses")
        poses = read_pose_file(options["pose_file"])
    if options["excitation"] == "law":
        request = MoveRequest.parse(
            options["distance"], options["duration"], None, None, None, None, None
        )
        motion = request.law(options["law"] or "quintic")
    if options["np_"] is not None and options["np_"] < 1:
        raise InputError("np", options["np_"], "must be at least 1 (1 runs serially)")
    # ranges that keep a case meaningful: a tilt below 45 deg, an amplitude below 10 m
    tilt = parse_bounded(options["tilt"], "angle", "tilt", 0.0, math.radians(45.0))
    amplitude = parse_bounded(options["amplitude"], "length", "amplitude", 0.0, 10.0)
    frequency = parse_bounded(options["frequency"], "frequency", "frequency", 0.0, 1e3)
    excite_time = parse_bounded(options["excite_time"], "time", "excite_time", 0.0, 1e5)
    with naming("pose_file", options["pose_file"]) if poses is not None else nullcontext():
        chosen = excitation_from_options(
            options["excitation"], tilt, amplitude, frequency, excite_time, motion, poses
        )
    angles = options["probe_angles"]
    if angles is None:
        angles = 12 if poses is not None else 0
    end_time_s = parse_quantity(options["end_time"], "time", "end_time")
    delta_t_s = parse_quantity(options["delta_t"], "time", "delta_t")
    # a pose file too short or too long for the case's grid names --pose-file
    with naming("pose_file", options["pose_file"]) if poses is not None else nullcontext():
        return case_spec(
            slosh_model,
            chosen,
            cells_per_radius=options["cells_per_radius"],
            end_time_s=end_time_s,
            delta_t_s=delta_t_s,
            ddt_scheme=options["ddt"],
            processes=options["np_"] or 1,
            surface_tension=options["cfd_surface_tension"],
            max_courant=options["max_courant"],
            max_alpha_courant=options["max_courant"],
            adjust_time_step=not options["fixed_step"],
            probe_angles=angles,
        )


def _run_with_progress(spec: Any, case: Path, resume: bool, overwrite: bool) -> Any:
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    with Progress(
        TextColumn("interFoam"),
        BarColumn(),
        TextColumn("t = {task.completed:.3f}/{task.total:g} s"),
        TextColumn("Co {task.fields[courant]}"),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=stderr,
        transient=True,
    ) as bar:
        task = bar.add_task("run", total=spec.end_time_s, courant="-")

        def advance(simulated: float, end: float, courant: float | None) -> None:
            bar.update(
                task,
                completed=simulated,
                total=end,
                courant="-" if courant is None else f"{courant:.2f}",
            )

        try:
            return run_cfd(spec, case, resume=resume, overwrite=overwrite, progress=advance)
        except CfdError as error:
            stderr.print(Text("error: ", style="red") + Text(str(error)), highlight=False)
            raise typer.Exit(1) from None
        except CfdInterrupted as stop:
            bar.stop()
            signals.reported()  # the resume hint below is the one line
            stderr.print(
                Text(
                    f"interrupted at t = {stop.simulated_s:.4g} s of {spec.end_time_s:g} s; "
                    f"continue with: sloshkit cfd run --case {case} --resume"
                ),
                highlight=False,
            )
            raise typer.Exit(128 + int(stop.signum)) from None


@contextlib.contextmanager
def _clean_interruption(case: Path) -> Iterator[None]:
    """SIGINT, SIGTERM or SIGHUP anywhere in a cfd command (not only while OpenFOAM runs):
    the tools are stopped, one line says how to continue, exit 128 + the signal number."""
    try:
        with interruptible([], [0.0]):
            yield
    except CfdInterrupted as stop:
        signals.reported()  # the resume hint below is the one line
        stderr.print(
            Text(
                f"interrupted (signal {int(stop.signum)}); continue with: "
                f"sloshkit cfd run --case {case} --resume"
            ),
            highlight=False,
        )
        raise typer.Exit(128 + int(stop.signum)) from None


def _print_analysis(
    analysis: Any,
    json_output: bool,
    model_file_out: Path | None,
    plot: Path | None,
    slosh_model: SloshModel | None,
) -> None:

    payload = analysis.to_dict()
    if slosh_model is not None:
        payload["theory"] = {
            "omega_n_rad_s": slosh_model.modes[0].omega_rad_s,
            "frequency_hz": slosh_model.modes[0].frequency_hz,
        }
        if model_file_out is not None:
            write_model_file(model_file_out, analysis.calibration.calibrated_model(slosh_model))
            payload["model_file"] = str(model_file_out)
    if plot is not None:
        analysis.calibration.plot(plot)
    if json_output:
        print_json(payload)
        return
    table = Table(title=f"CFD calibration: {analysis.case} ({payload['cells']} cells)")
    for header_text in ("estimator", "ω_n [rad/s]", "f_n [Hz]", "ζ [-]"):
        table.add_column(Text(header_text), justify="right")
    for name, estimate in payload["estimates"].items():
        table.add_row(
            name,
            *(
                ("-" if estimate[k] is None else f"{estimate[k]:.4g}")
                for k in ("omega_n_rad_s", "frequency_hz", "damping_ratio")
            ),
        )
    if "theory" in payload:
        table.add_row(
            "linear theory",
            f"{payload['theory']['omega_n_rad_s']:.4g}",
            f"{payload['theory']['frequency_hz']:.4g}",
            "",
        )
    stdout.print(table)
    line = describe(analysis.run_record)
    if line:
        stdout.print(line)


def _resumed_spec(spec: Any, case: Path, processes: int | None) -> Any:
    """A resumed case keeps its own end time and (unless --np is given) its process count."""
    summary_path = case / "sloshkit-case.json"
    if not summary_path.is_file():
        raise InputError("case", str(case), "has no sloshkit case to resume")
    summary = json.loads(summary_path.read_text(encoding="utf-8"))
    return dataclasses.replace(
        spec,
        end_time_s=float(summary["end_time_s"]),
        processes=processes or int(summary.get("processes", 1)),
    )


@cfd_app.command("run")
@with_model_options
@with_options(cfd_options("free-decay", "3s"), "case_options", dict)
def cfd_run_command(
    slosh_model: SloshModel,
    case_options: dict[str, Any],
    case: CaseDir,
    resume: Annotated[
        bool, typer.Option("--resume", help="Continue from the last written time.")
    ] = False,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace an existing case.")
    ] = False,
    model_file_out: Annotated[
        Path | None, typer.Option("--model-file-out", help="Write the calibrated model.")
    ] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Calibration figure.")] = None,
    json_output: Json = False,
) -> None:
    """Generate and run an interFoam case of the container, then calibrate from it.

    Example:

      sloshkit cfd run --case vial-decay --excitation free-decay --cells-per-radius 10 --np 2
    """
    check_file(model_file_out, "model_file_out", "model")
    check_file(plot, "plot", "figure")
    check_folder(case, "case", overwrite=True)  # a file, /proc, no permission: refused now
    with _clean_interruption(case):
        spec = _cfd_spec(slosh_model, case_options)
        if resume:
            spec = _resumed_spec(spec, case, case_options["np_"])
        result = _run_with_progress(spec, case, resume, overwrite)
        try:
            analysis = analyse(case)
        except InputError as error:
            # The run itself succeeded; a record too short to calibrate is not a failed run.
            if json_output:
                print_json(
                    {
                        "case": str(case),
                        "simulated_s": result.simulated_s,
                        "wall_clock_s": result.wall_clock_s,
                        "processes": result.processes,
                        "cells": result.cells,
                        "calibration_error": str(error),
                    }
                )
            else:
                stdout.print(Text(f"{result.simulated_s:g} s simulated in {case}"))
            stderr.print(Text(f"warning: no calibration: {error}", style="yellow"), highlight=False)
            return
        _print_analysis(analysis, json_output, model_file_out, plot, slosh_model)


@cfd_app.command("analyse")
def cfd_analyse_command(
    case: Annotated[Path, typer.Argument(help="A case run by sloshkit cfd run.")],
    method: Annotated[str, typer.Option("--method", help="fit, logdec or fft.")] = "fit",
    start: Annotated[str | None, typer.Option("--start", help="Window start.")] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Calibration figure.")] = None,
    csv: Annotated[Path | None, typer.Option("--csv", help="Write the CFD signals as CSV.")] = None,
    json_output: Json = False,
) -> None:
    """Frequency and damping from a finished case's wall elevation (calibrate's JSON keys plus
    cells, simulated_s, wall_clock_s).

    Example:

      sloshkit cfd analyse vial-decay --json
    """
    check_file(plot, "plot", "figure")
    check_file(csv, "csv")

    if not (case / "sloshkit-case.json").is_file():
        raise InputError("case", str(case), "is not a sloshkit CFD case")
    analysis = analyse(
        case, method, None if start is None else parse_quantity(start, "time", "start")
    )
    if csv is not None:
        write_columns_csv(csv, analysis.signals.columns())
    _print_analysis(analysis, json_output, None, plot, None)


def _validate(case: Path, slosh_model: SloshModel) -> dict[str, Any]:
    """The 1-D comparison, or the 3-D one for a case driven by a pose trajectory."""
    summary_path = case / "sloshkit-case.json"
    if summary_path.is_file():
        summary = json.loads(summary_path.read_text(encoding="utf-8"))
        if summary.get("excitation", {}).get("type") == "PoseExcitation":
            from sloshkit.cfd.spatial import validate_poses

            return validate_poses(case, slosh_model)
    return validate(case, slosh_model)


@cfd_app.command("validate")
@with_model_options
@with_options(cfd_options("harmonic", "4s"), "case_options", dict)
def cfd_validate_command(
    slosh_model: SloshModel,
    case_options: dict[str, Any],
    case: CaseDir,
    reuse: Annotated[
        bool, typer.Option("--reuse", help="Use the case's existing results.")
    ] = False,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace an existing sloshkit case.")
    ] = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="CFD vs pendulum (Fig. 9).")] = None,
    json_output: Json = False,
) -> None:
    """Run the CFD and the pendulum model on the same motion and report how far apart they
    are (frequency, damping, peak and residual wall elevation; for a pose trajectory, the peak
    and residual slosh height against the 3-D model).

    Example:

      sloshkit cfd validate --case vial-harmonic --excitation harmonic --np 2 --plot fig9.png

      sloshkit cfd validate --case vial-3d --excitation poses --pose-file move.csv --np 2
    """
    check_file(plot, "plot", "figure")
    if not reuse:
        check_folder(case, "case", overwrite=True)
    with _clean_interruption(case):
        if not reuse:
            spec = _cfd_spec(slosh_model, case_options)
            _run_with_progress(spec, case, False, overwrite)
        result = _validate(case, slosh_model)
        if plot is not None:
            plot_cfd_validation(result, plot)
        summary = {
            k: v
            for k, v in result.items()
            if k not in ("time_s", "cfd_elevation_m", "model_elevation_m")
        }
        if json_output:
            print_json(summary)
            return
        table = Table(title=f"CFD against the pendulum model: {case}")
        for header_text in ("quantity", "CFD", "model", "difference"):
            table.add_column(Text(header_text), justify="right")
        for key, row in summary["comparison"].items():
            table.add_row(
                Text(display.label(key)),
                *(display.value(key, row[k]) for k in ("cfd", "model")),
                "-"
                if row["relative_difference"] is None
                else f"{100 * row['relative_difference']:+.1f} %",
            )
        stdout.print(table)
        if summary["correlation"] is not None:
            what = "slosh-height" if summary.get("kind") == "poses" else "wall-elevation"
            stdout.print(f"correlation of the {what} signals: {summary['correlation']:.4f}")
        if summary.get("wall_correlation") is not None:
            stdout.print(
                "correlation of the wall elevations of every probe column: "
                f"{summary['wall_correlation']:.4f}"
            )
