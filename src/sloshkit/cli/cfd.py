"""``sloshkit cfd``: the volume-of-fluid step with OpenFOAM (generate, run, analyse, validate)."""

from __future__ import annotations

import contextlib
import dataclasses
from collections.abc import Iterator
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cfd.pipeline import (
    analyse,
    describe,
    validate,
)
from sloshkit.cfd.pipeline import run as run_cfd
from sloshkit.cfd.prepare import check_case_path
from sloshkit.cfd.requests import require_cylinder
from sloshkit.cfd.run import CfdError, CfdInterrupted, interruptible
from sloshkit.cfd.summary import read_case_summary
from sloshkit.cfd.validation import CfdValidation
from sloshkit.cli import display, messages, signals
from sloshkit.cli.app import app, stderr, stdout
from sloshkit.cli.cfd_options import CaseDir, cfd_options, spec_from_options
from sloshkit.cli.options import Json, print_json, with_cylinder_model_options, with_options
from sloshkit.errors import InputError
from sloshkit.files import write_columns_csv
from sloshkit.io.models import write_model_file
from sloshkit.io.outputs import check_file, check_folder
from sloshkit.io.units import parse_quantity
from sloshkit.model.modal import SloshModel

cfd_app = typer.Typer(
    help="The volume-of-fluid step with OpenFOAM (interFoam): generate, run, analyse, validate.",
    no_args_is_help=True,
    rich_markup_mode=None,
)
app.add_typer(cfd_app, name="cfd")


def run_with_progress(spec: Any, case: Path, resume: bool, overwrite: bool) -> Any:
    """Run a CFD case with a progress bar on stderr; a failed or interrupted run ends the
    command.

    A `CfdError` prints one ``error:`` line and exits with 1; an interruption prints where it
    stopped and how to resume, and exits with 128 + the signal number.

    Parameters
    ----------
    spec : CaseSpec
        The case to run.
    case : pathlib.Path
        Its folder.
    resume : bool
        Continue the case in ``case`` from its latest complete time folder.
    overwrite : bool
        Replace a sloshkit case already in ``case``.

    Returns
    -------
    RunResult
        What `sloshkit.cfd.pipeline.run` returns.

    Examples
    --------
    Bad input is refused before any process starts:

    >>> from pathlib import Path
    >>> import sloshkit as sk
    >>> from sloshkit.cfd.case import FreeDecay
    >>> from sloshkit.cfd.pipeline import case_spec
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> run_with_progress(case_spec(model, FreeDecay()), Path("no-case"), True, False)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: case = 'no-case' is invalid: has no sloshkit case to resume
    """
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
            messages.error(stderr, error)
            raise typer.Exit(1) from None
        except CfdInterrupted as stop:
            bar.stop()
            signals.reported()  # the resume hint below is the one line
            messages.error(  # the documented "error: interrupted ..." line
                stderr,
                f"interrupted (exit {128 + int(stop.signum)}) at t = {stop.simulated_s:.4g} s "
                f"of {spec.end_time_s:g} s; continue with: sloshkit cfd run --case {case} "
                "--resume",
            )
            raise typer.Exit(128 + int(stop.signum)) from None


@contextlib.contextmanager
def _clean_interruption(case: Path) -> Iterator[None]:
    """SIGINT, SIGTERM or SIGHUP anywhere in a cfd command (not only while OpenFOAM runs):
    the tools are stopped, one line says how to continue, exit 128 + the signal number. The
    same advice goes to the entry point, for a signal that lands outside this block (while it
    restores the handlers, or on the way out of the command)."""
    signals.set_hint(f"continue with: sloshkit cfd run --case {case} --resume")
    try:
        with interruptible([], [0.0]):
            yield
    except CfdInterrupted as stop:
        signals.reported()  # the resume hint below is the one line
        messages.error(
            stderr,
            f"interrupted (exit {128 + int(stop.signum)}); continue with: "
            f"sloshkit cfd run --case {case} --resume",
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
    stdout.print(_signal_line(payload.get("damping_signal"), payload.get("force_noise_ratio")))
    line = describe(analysis.run_record)
    if line:
        stdout.print(line)


def _signal_line(signal: str | None, noise: float | None = None) -> str:
    """The text output's line naming the signal frequency and damping came from."""
    if signal == "wall_force":
        extra = "" if noise is None else f"; high-frequency noise ratio {noise:.2f}"
        return f"frequency and damping from the wall force{extra}"
    return "frequency and damping from the probe wall elevation (the wall force was not usable)"


def _resumed_spec(spec: Any, case: Path, processes: int | None) -> Any:
    """A resumed case keeps its own end time and (unless --np is given) its process count."""
    if not (case / "sloshkit-case.json").is_file():
        raise InputError("case", str(case), "has no sloshkit case to resume")
    summary = read_case_summary(case)
    return dataclasses.replace(
        spec,
        end_time_s=float(summary["end_time_s"]),
        processes=processes or int(summary.get("processes", 1)),
    )


@cfd_app.command("run")
@with_cylinder_model_options
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

    \f
    Parameters
    ----------
    slosh_model : SloshModel
        The container, fill and liquid (the model options).
    case_options : dict
        The values of `sloshkit.cli.cfd_options.cfd_options`.
    case : Path
        The case folder.
    resume : bool
        Continue an interrupted run.
    overwrite : bool
        Replace an existing sloshkit case.
    model_file_out : Path, optional
        Write the calibrated model.
    plot : Path, optional
        Calibration figure.
    json_output : bool
        Print JSON.

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.cli.app import run
    >>> run(["cfd", "run", "--case", "c", "--cells-per-radius", "2"])  # refused: nothing written
    2
    """
    require_cylinder(slosh_model)
    check_file(model_file_out, "model_file_out", "model")
    check_file(plot, "plot", "figure")
    check_case_path(case)  # characters OpenFOAM refuses: refused before anything is written
    check_folder(case, "case", overwrite=True)  # a file, /proc, no permission: refused now
    with _clean_interruption(case):
        spec = spec_from_options(slosh_model, case_options)
        if resume:
            spec = _resumed_spec(spec, case, case_options["np_"])
        result = run_with_progress(spec, case, resume, overwrite)
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
    """Frequency and damping from a finished case's wall force, or its wall elevation when it
    has no usable force output (calibrate's JSON keys plus cells, simulated_s, wall_clock_s,
    damping_signal, force_noise_ratio).

    Example:

      sloshkit cfd analyse vial-decay --json

    \f
    Parameters
    ----------
    case : Path
        A finished case.
    method : str
        The estimator reported.
    start : str, optional
        Window start (with its unit).
    plot : Path, optional
        Calibration figure.
    csv : Path, optional
        The CFD signals as CSV.
    json_output : bool
        Print JSON.

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.cli.app import run
    >>> run(["cfd", "analyse", "no-such-case"])  # one line on stderr
    2
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


def _validate(case: Path, slosh_model: SloshModel) -> CfdValidation:
    """The 1-D comparison, or the 3-D one for a case driven by a pose trajectory."""
    if (case / "sloshkit-case.json").is_file():
        summary = read_case_summary(case)
        if summary["excitation"]["type"] == "PoseExcitation":
            from sloshkit.cfd.pose_validation import validate_poses

            return validate_poses(slosh_model, case)
    return validate(slosh_model, case)


@cfd_app.command("validate")
@with_cylinder_model_options
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

    \f
    Parameters
    ----------
    slosh_model : SloshModel
        The container, fill and liquid (the model options).
    case_options : dict
        The values of `sloshkit.cli.cfd_options.cfd_options`.
    case : Path
        The case folder.
    reuse : bool
        Compare the case's existing results (no run).
    overwrite : bool
        Replace an existing sloshkit case.
    plot : Path, optional
        CFD against the model (Fig. 9).
    json_output : bool
        Print JSON (the keys of `sloshkit.cfd.validation.CfdValidation.to_dict`).

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.cli.app import run
    >>> run(["cfd", "validate", "--case", "no-such-case", "--reuse"])  # one line on stderr
    2
    """
    require_cylinder(slosh_model)
    check_file(plot, "plot", "figure")
    if not reuse:
        check_case_path(case)
        check_folder(case, "case", overwrite=True)
    with _clean_interruption(case):
        if not reuse:
            spec = spec_from_options(slosh_model, case_options)
            run_with_progress(spec, case, False, overwrite)
        result = _validate(case, slosh_model)
        if plot is not None:
            result.plot(path=plot)
        summary = result.to_dict()
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
        if summary.get("damping_signal") is not None:
            stdout.print(f"CFD {_signal_line(summary['damping_signal'])}")
        if summary["correlation"] is not None:
            what = "slosh-height" if summary.get("kind") == "poses" else "wall-elevation"
            stdout.print(f"correlation of the {what} signals: {summary['correlation']:.4f}")
        if summary.get("wall_correlation") is not None:
            stdout.print(
                "correlation of the wall elevations of every probe column: "
                f"{summary['wall_correlation']:.4f}"
            )
