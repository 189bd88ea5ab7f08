"""``sloshkit export``: a plan in a controller's format, with the round-trip check.

The export options (arm, mounting, servoj parameters, check) form one group, shared with
``sloshkit plan --export``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cli import messages
from sloshkit.cli.app import app, stderr, stdout
from sloshkit.cli.options import Json, print_json, with_model_options, with_options
from sloshkit.cli.sweep import MaxAngle, MaxResidual
from sloshkit.errors import InputError, require_in_range
from sloshkit.io.checks import naming
from sloshkit.io.outputs import all_or_nothing, check_file
from sloshkit.io.units import parse_bounded, parse_number, parse_quantity
from sloshkit.model.modal import SloshModel

FORMAT_HELP = "pose-csv, joint-csv, ros2, urscript or cam-table."

Robot = Annotated[
    str | None,
    typer.Option("--robot", help="Built-in arm for joint formats: ur5e (the default)."),
]
Urdf = Annotated[Path | None, typer.Option("--urdf", help="URDF of the arm (instead of --robot).")]
BaseLink = Annotated[str | None, typer.Option("--base-link", help="URDF link the chain starts at.")]
TipLink = Annotated[str | None, typer.Option("--tip-link", help="URDF link of the flange.")]
SeedJoints = Annotated[
    str | None,
    typer.Option("--seed-joints", help="IK start for the first sample, e.g. 0,-90deg,90deg,..."),
]
ToolOffset = Annotated[
    str,
    typer.Option("--tool-offset", help="Container bottom centre in the flange frame: x,y,z."),
]
ToolRotation = Annotated[
    str,
    typer.Option(
        "--tool-rotation", help="Container frame in the flange frame: roll,pitch,yaw (xyz fixed)."
    ),
]
BasePose = Annotated[
    str,
    typer.Option("--base-pose", help="Path frame in the robot base: x,y,z[,roll,pitch,yaw]."),
]
Axis = Annotated[str, typer.Option("--axis", help="Direction of a 1-D plan: x, y, z or vx,vy,vz.")]
Lookahead = Annotated[
    str, typer.Option("--lookahead-time", help="urscript servoj lookahead_time (30ms..200ms).")
]
Gain = Annotated[float, typer.Option("--gain", help="urscript servoj gain (100..2000).")]
Check = Annotated[
    bool,
    typer.Option("--check/--no-check", help="Parse the file back and re-simulate the slosh."),
]


@dataclass(frozen=True)
class ExportSettings:
    """The export option group, parsed (SI): how to reach the controller."""

    robot: str | None
    urdf: Path | None
    base_link: str | None
    tip_link: str | None
    seed_rad: tuple[float, ...] | None
    mounting: Any
    axis: tuple[float, float, float]
    lookahead_time_s: float
    gain: float
    check: bool

    def arm(self, fmt: str) -> Any:
        """The arm for joint formats (UR5e unless ``--urdf`` or ``--robot`` says otherwise)."""
        from sloshkit.export.exporter import JOINT_FORMATS
        from sloshkit.export.kinematics import load_arm

        if fmt not in JOINT_FORMATS:
            return None
        robot = self.robot if self.robot is not None or self.urdf is not None else "ur5e"
        seed = None if self.seed_rad is None else tuple(self.seed_rad)
        import numpy as np

        return load_arm(
            robot,
            self.urdf,
            self.base_link,
            self.tip_link,
            None if seed is None else np.asarray(seed),
        )


def parse_vector(text: str, kinds: tuple[str, ...], parameter: str) -> tuple[float, ...]:
    """Comma-separated quantities with units (``0,0,100mm``; bare numbers in SI, radians)."""
    cells = [cell.strip() for cell in text.split(",")]
    if len(cells) != len(kinds):
        raise InputError(parameter, text, f"needs {len(kinds)} comma-separated values")
    return tuple(
        parse_quantity(cell, kind, parameter) for cell, kind in zip(cells, kinds, strict=True)
    )


def _parse_axis(text: str) -> tuple[float, float, float]:
    named = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
    if text.strip().lower() in named:
        return named[text.strip().lower()]
    cells = text.split(",")
    if len(cells) != 3:
        raise InputError("axis", text, "must be x, y, z or three numbers vx,vy,vz")
    values = tuple(parse_number(cell, "axis") for cell in cells)
    if not math.hypot(*values) > 0.0:
        raise InputError("axis", text, "must be a non-zero direction")
    return (values[0], values[1], values[2])


def _settings(values: dict[str, Any]) -> ExportSettings:
    from sloshkit.export.frames import Mounting

    base = values["base_pose"].split(",")
    if len(base) not in (3, 6):
        raise InputError("base_pose", values["base_pose"], "needs x,y,z or x,y,z,roll,pitch,yaw")
    base_values = parse_vector(
        values["base_pose"], ("length",) * 3 + ("angle",) * (len(base) - 3), "base_pose"
    )
    offset = parse_vector(values["tool_offset"], ("length",) * 3, "tool_offset")
    rotation = parse_vector(values["tool_rotation"], ("angle",) * 3, "tool_rotation")
    seed = values["seed_joints"]
    return ExportSettings(
        robot=values["robot"],
        urdf=values["urdf"],
        base_link=values["base_link"],
        tip_link=values["tip_link"],
        seed_rad=None
        if seed is None
        else tuple(parse_quantity(cell, "angle", "seed_joints") for cell in seed.split(",")),
        mounting=Mounting(
            tool_offset_m=(offset[0], offset[1], offset[2]),
            tool_rpy_rad=(rotation[0], rotation[1], rotation[2]),
            base_xyz_m=(base_values[0], base_values[1], base_values[2]),
            base_rpy_rad=(base_values[3], base_values[4], base_values[5])
            if len(base_values) == 6
            else (0.0, 0.0, 0.0),
        ),
        axis=_parse_axis(values["axis"]),
        lookahead_time_s=parse_bounded(
            values["lookahead_time"], "time", "lookahead_time", 0.03, 0.2, low_open=False
        ),
        gain=require_in_range("gain", values["gain"], 100.0, 2000.0),
        check=bool(values["check"]),
    )


EXPORT_OPTIONS: dict[str, tuple[Any, Any]] = {
    "robot": (Robot, None),
    "urdf": (Urdf, None),
    "base_link": (BaseLink, None),
    "tip_link": (TipLink, None),
    "seed_joints": (SeedJoints, None),
    "tool_offset": (ToolOffset, "0,0,100mm"),
    "tool_rotation": (ToolRotation, "180deg,0deg,0deg"),
    "base_pose": (BasePose, "0,0,0"),
    "axis": (Axis, "x"),
    "lookahead_time": (Lookahead, "50ms"),
    "gain": (Gain, 500.0),
    "check": (Check, True),
}

#: Give a command the export options; it receives the parsed ``export_settings``.
with_export_options = with_options(EXPORT_OPTIONS, "export_settings", _settings)


def run_export(
    plan: Any,
    fmt: str,
    out: Path,
    settings: ExportSettings,
    model: SloshModel,
    limits: Any,
    sample_period_s: float | None,
) -> Any:
    """Export with the parsed settings (progress on stderr); returns the `ExportResult`."""
    from sloshkit.export.exporter import FORMATS, export_plan

    if fmt not in FORMATS:
        raise InputError("format", fmt, "must be one of " + ", ".join(FORMATS))
    with stderr.status(f"exporting {fmt}"), all_or_nothing(out):
        return export_plan(
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


def show_export(result: Any) -> None:
    """The export's outcome as a table and a verdict line (stdout)."""
    stdout.print(
        f"wrote {result.path} ({result.format}, {result.samples} samples every "
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
    fmt: str, target: Path, settings: ExportSettings, option: str = "format"
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

    Returns
    -------
    Arm or None
        The arm for joint formats (loaded once here), else None.

    Examples
    --------
    >>> settings = _settings({**{k: v for k, (_, v) in EXPORT_OPTIONS.items()}})
    >>> check_export_request("pose-csv", Path("plan.poses.csv"), settings) is None
    True
    """
    from sloshkit.export.exporter import FORMATS

    if fmt not in FORMATS:
        raise InputError(option, fmt, "must be one of " + ", ".join(FORMATS))
    check_file(target, "out")
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


def slosh_limits(max_angle: str | None, max_residual: str | None) -> Any:
    """`SloshLimits` from the two options, None when neither is given."""
    from sloshkit.plan.problem import SloshLimits

    if max_angle is None and max_residual is None:
        return None
    if max_angle is None or max_residual is None:
        raise InputError("max_angle", max_angle, "give both --max-angle and --max-residual")
    return SloshLimits(
        parse_quantity(max_angle, "angle", "max_angle"),
        parse_quantity(max_residual, "angle", "max_residual"),
    )


@app.command("export")
@with_model_options
@with_export_options
def export_command(
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
    formats) and the slosh re-simulated; exit code 1 when peak or residual slosh differ from
    the plan's by more than 2 % or a given limit is broken.

    Example:

      sloshkit export plan.csv --format urscript --robot ur5e --base-pose=-0.5m,-0.13m,0.39m
    """
    from sloshkit.export.exporter import SUFFIXES

    target = out if out is not None else plan_file.with_name(plan_file.stem + SUFFIXES.get(fmt, ""))
    check_export_request(fmt, target, export_settings)
    from sloshkit.export.plans import read_plan

    limits = slosh_limits(max_angle, max_residual)
    with naming("plan_file", plan_file):
        plan = read_plan(plan_file)
    period = None
    if sample_period is not None:
        period = parse_quantity(sample_period, "time", "sample_period")
        check_output_period(plan, period, sample_period)
    result = run_export(plan, fmt, target, export_settings, slosh_model, limits, period)
    if json_output:
        print_json(result.to_dict())
    else:
        show_export(result)
    if not result.passed:
        raise typer.Exit(1)
