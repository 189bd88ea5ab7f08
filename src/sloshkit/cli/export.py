"""``sloshkit export``: a plan in a controller's format, with the round-trip check.

The export options (arm, mounting, servoj parameters, check) form one group, shared with
``sloshkit plan --export``.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cli import messages, signals
from sloshkit.cli.app import app, stderr, stdout

# The option group (``plan --export`` imports it from here too).
from sloshkit.cli.export_options import FORMAT_HELP
from sloshkit.cli.export_options import with_export_options as with_export_options
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.cli.sweep import MaxAngle, MaxResidual
from sloshkit.errors import InputError
from sloshkit.export.settings import ExportSettings
from sloshkit.io.checks import naming
from sloshkit.io.outputs import all_or_nothing, check_file
from sloshkit.io.plan_requests import slosh_limits_request
from sloshkit.io.units import parse_quantity
from sloshkit.model.modal import SloshModel


def _model_line(model: SloshModel | None) -> str:
    if model is None:
        return "none (no round trip)"
    first = model.modes[0]
    return (
        f"radius {1e3 * model.radius_m:.4g} mm, fill {1e3 * model.fill_height_m:.4g} mm, "
        f"{model.liquid.name}, f1 {first.frequency_hz:.4g} Hz, damping {first.damping_ratio:.3g}"
    )


def run_export(
    plan: Any,
    fmt: str,
    out: Path,
    settings: ExportSettings,
    model: SloshModel | None,
    limits: Any,
    sample_period_s: float | None,
) -> Any:
    """Export with the parsed settings (progress on stderr); returns the `ExportResult`.

    Parameters
    ----------
    plan : LinePlan or PoseStream
        The plan to export.
    fmt : str
        The format (`sloshkit.export.exporter.FORMATS`).
    out : pathlib.Path
        The file to write.
    settings : ExportSettings
        The parsed export options.
    model : SloshModel or None
        The model the round trip re-simulates (None only without the check).
    limits : SloshLimits or None
        Limits the round trip checks.
    sample_period_s : float or None
        Controller period [s] (default: the plan's).

    Returns
    -------
    ExportResult

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> from sloshkit.export.frames import Mounting
    >>> from sloshkit.export.plans import LinePlan
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> t = np.arange(126) * 0.008
    >>> s = t / t[-1]
    >>> x = 0.1 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> v = 0.2 / t[-1] * 30 * s**2 * (1 - s) ** 2
    >>> a = 0.2 / t[-1] ** 2 * 60 * s * (1 - s) * (1 - 2 * s)
    >>> plan = LinePlan(t, x, v, a)
    >>> settings = ExportSettings(None, None, None, None, None, Mounting(), (1.0, 0.0, 0.0),
    ...                           0.1, 300.0, True)
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "move.cam.csv"
    >>> result = run_export(plan, "cam-table", out, settings, model, None, None)
    >>> result.samples, result.round_trip.passed
    (126, True)
    """
    from sloshkit.export.exporter import FORMATS, export_plan

    if fmt not in FORMATS:
        raise InputError("format", fmt, "must be one of " + ", ".join(FORMATS))
    existed = out.exists()
    try:
        with stderr.status(f"exporting {fmt}"), all_or_nothing(out, before_keeping=signals.check):
            result = export_plan(
                plan,
                fmt,
                out,
                arm=settings.arm(fmt),
                mounting=settings.mounting,
                axis=settings.axis,
                sample_period_s=sample_period_s,
                model=model,
                limits=limits,
                check=settings.check,
                lookahead_time_s=settings.lookahead_time_s,
                gain=settings.gain,
            )
            if not result.passed:
                raise RoundTripFailed(result)  # all_or_nothing removes (or restores) the file
    except RoundTripFailed as failure:
        _remove_folder(out, existed)
        return dataclasses.replace(failure.result, written=False)
    except BaseException:
        _remove_folder(out, existed)
        raise
    return result


def _remove_folder(out: Path, existed: bool) -> None:
    """Remove a folder output (a rosbag2) the export created; files are all_or_nothing's."""
    import shutil

    if not existed and out.is_dir() and not out.is_symlink():
        shutil.rmtree(out, ignore_errors=True)


class RoundTripFailed(Exception):
    """Raised inside an all-or-nothing block when an export's round trip fails, so that the
    file is not left behind; carries the `ExportResult`.

    Parameters
    ----------
    result : ExportResult
        The failed export.

    Examples
    --------
    >>> from pathlib import Path
    >>> from sloshkit.export.exporter import ExportResult
    >>> RoundTripFailed(ExportResult("cam-table", Path("move.cam.csv"), 3, 0.004)).result.samples
    3
    """

    def __init__(self, result: Any) -> None:
        super().__init__("round trip failed")
        self.result = result


def show_export(result: Any) -> None:
    """The export's outcome as a table and a verdict line (stdout).

    Parameters
    ----------
    result : ExportResult
        The export.

    Examples
    --------
    >>> from pathlib import Path
    >>> from sloshkit.export.exporter import ExportResult
    >>> show_export(ExportResult("cam-table", Path("move.cam.csv"), 126, 0.008))
    wrote move.cam.csv (cam-table, 126 samples every 8 ms)
    """
    stdout.print(
        ("wrote " if result.written else "did not write (the round trip failed) ")
        + f"{result.path} ({result.format}, {result.samples} samples every "
        f"{1e3 * result.sample_period_s:g} ms)"
    )
    if result.joints is not None:
        summary = result.joints.to_dict()
        stdout.print(
            "joints: peak |q'| "
            + ", ".join(f"{v:.3g}" for v in summary["peak_joint_velocity_rad_s"])
            + f" rad/s; Jacobian condition number <= {summary['max_condition_number']:.3g}"
        )
    for note in result.notes:
        stdout.print(f"note: {note}")
    trip = result.round_trip
    if trip is None:
        return
    table = Table(title=f"Round trip: plan vs exported file, re-simulated ({trip.method})")
    for header in ("metric", "plan", "export", "difference"):
        table.add_column(Text(header), justify="right")
    labels = {
        "peak_angle_deg": ("peak θ₁ [deg]", 1.0),
        "residual_angle_deg": ("residual θ₁ [deg]", 1.0),
        "peak_wall_elevation_m": ("peak wall elevation [mm]", 1e3),
        "residual_wall_elevation_m": ("residual wall elevation [mm]", 1e3),
        "peak_slosh_height_m": ("peak slosh height [mm]", 1e3),
        "residual_slosh_height_m": ("residual slosh height [mm]", 1e3),
    }
    for key in trip.plan_metrics:
        label, scale = labels.get(key, (key, 1.0))
        table.add_row(
            Text(label),
            f"{scale * trip.plan_metrics[key]:.5g}",
            f"{scale * trip.export_metrics[key]:.5g}",
            f"{100 * trip.relative_differences[key]:.3g} %",
        )
    stdout.print(table)
    stdout.print(
        f"path deviation: {1e3 * trip.max_position_error_m:.3g} mm, "
        f"orientation {math.degrees(trip.max_orientation_error_rad):.3g} deg"
    )
    if trip.passed:
        stdout.print("round trip: passed (within 2 %, no limit broken)")
    else:
        messages.error(stderr, "round trip failed: " + "; ".join(trip.violations))


def check_export_request(
    fmt: str,
    target: Path,
    settings: ExportSettings,
    option: str = "format",
    inputs: tuple[tuple[str, Path | None], ...] = (),
    chosen: bool = True,
) -> Any:
    """Check an export before any work: the format, the output file, the arm (robot or URDF).

    Parameters
    ----------
    fmt : str
        The format name (`sloshkit.export.exporter.FORMATS`).
    target : Path
        The file the export will write.
    settings : ExportSettings
        The parsed export options.
    option : str
        The option that named the format (``format``; ``export`` for ``plan --export``).
    inputs : tuple of (str, Path) pairs
        The command's input files (the output never replaces one, `check_file`).
    chosen : bool
        The user named ``target`` (False: the default beside the plan).

    Returns
    -------
    Arm or None
        The arm for joint formats (loaded once here), else None.

    Examples
    --------
    >>> from sloshkit.export.frames import Mounting
    >>> settings = ExportSettings(None, None, None, None, None, Mounting(), (1.0, 0.0, 0.0),
    ...                           0.05, 500.0, True)
    >>> check_export_request("pose-csv", Path("plan.poses.csv"), settings) is None
    True
    """
    from sloshkit.export.exporter import FORMATS

    if fmt not in FORMATS:
        raise InputError(option, fmt, "must be one of " + ", ".join(FORMATS))
    check_file(target, "out", inputs=inputs, chosen=chosen)
    return settings.arm(fmt)


def check_output_period(plan: Any, period_s: float, text: str) -> None:
    """Refuse an output sample period that is not positive, leaves fewer than 3 samples of
    the plan, or needs more memory than the limit (`sloshkit.budget`).

    Parameters
    ----------
    plan : LinePlan or PoseStream
        The plan read from its file.
    period_s : float
        The requested period [s].
    text : str
        The period as typed (for the message).

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.export.plans import LinePlan
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 251)
    >>> check_output_period(LinePlan(t, t, t, t), 0.004, "4ms")
    """
    from sloshkit.budget import require_samples

    if not period_s > 0.0:
        raise InputError("sample_period", text, "must be > 0 s")
    duration = float(plan.time_s[-1] - plan.time_s[0])
    if period_s > duration / 2.0:
        raise InputError(
            "sample_period", text, f"must leave at least 3 samples of the {duration:.4g} s plan"
        )
    # poses, joints and the round-trip re-simulation: about 64 float64 columns per sample
    require_samples("sample_period", text, duration / period_s, 64, "exported samples")


@app.command("export")
@with_model_options
@with_export_options
def export_command(
    context: typer.Context,
    slosh_model: SloshModel,
    export_settings: ExportSettings,
    plan_file: Annotated[
        Path, typer.Argument(help="Plan CSV: 1-D (t_s, position_m, ...) or poses.")
    ],
    fmt: Annotated[str, typer.Option("--format", help=FORMAT_HELP)] = "pose-csv",
    out: Annotated[
        Path | None, typer.Option("--out", help="Output file (default beside the plan).")
    ] = None,
    sample_period: Annotated[
        str | None,
        typer.Option("--sample-period", help="Output sample period (default the plan's)."),
    ] = None,
    max_angle: MaxAngle = None,
    max_residual: MaxResidual = None,
    json_output: Json = False,
) -> None:
    """Write a plan in a controller's format and check the round trip.

    The file is parsed back, the container's motion rebuilt (forward kinematics for joint
    formats) and the slosh re-simulated; exit code 1 (and no file written) when peak or
    residual slosh differ from the plan's by more than 2 % or a limit is broken. The model and
    the limits come from the plan file's '# sloshkit-plan:' header (written by 'sloshkit plan
    --out'); model options and --max-angle/--max-residual given here override it, with a
    warning when they differ. Without that header give the model options (or --no-check).
    The plan must start and end at rest.

    Example:

      sloshkit export plan.csv --format urscript --robot ur5e --base-pose=-0.5m,-0.13m,0.39m
    """
    from sloshkit.cli.plan_files import export_limits, export_model
    from sloshkit.export.exporter import path_beside

    target = out if out is not None else path_beside(plan_file, fmt)
    inputs = (("plan_file", plan_file), ("urdf", export_settings.urdf))
    check_export_request(fmt, target, export_settings, inputs=inputs, chosen=out is not None)
    from sloshkit.export.headers import read_plan_header
    from sloshkit.export.plans import read_plan

    command_limits = slosh_limits_request(max_angle, max_residual)
    with naming("plan_file", plan_file):
        plan = read_plan(plan_file)
    period = None
    if sample_period is not None:
        period = parse_quantity(sample_period, "time", "sample_period")
        check_output_period(plan, period, sample_period)
    header = read_plan_header(plan.metadata, str(plan_file))
    model, model_source = export_model(
        context, header, slosh_model, export_settings.check, plan_file
    )
    limits = export_limits(header, command_limits)
    result = run_export(plan, fmt, target, export_settings, model, limits, period)
    if json_output:
        from sloshkit.export.headers import limits_document

        payload = result.to_dict()
        payload["model_source"] = model_source
        payload["limits"] = None if limits is None else limits_document(limits)
        print_json(payload)
    else:
        stdout.print(f"model: {_model_line(model)} (from the {model_source})")
        show_export(result)
    if not result.passed:
        raise typer.Exit(1)
