"""The export option group of the command line (arm, mounting, servoj parameters, check),
parsed to SI once: ``sloshkit export`` and ``sloshkit plan --export`` share it. The settings
they build, and their limits, are `sloshkit.export.settings`'s."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any

import typer

from sloshkit.cli.options import with_options
from sloshkit.errors import InputError
from sloshkit.export.settings import LOOKAHEAD_TIME_RANGE_S, ExportSettings, export_settings
from sloshkit.io.units import parse_bounded, parse_number, parse_quantity

FORMAT_HELP = (
    "pose-csv, joint-csv, ros2, ros2-bag (rosbag2 folder), urscript, cam-table, or a robot "
    "program: fanuc-ls, abb-rapid, kuka-krl."
)

Robot = Annotated[
    str | None,
    typer.Option(
        "--robot",
        help="Built-in arm for joint formats: ur5e (the default), lrmate200id (fanuc-ls), "
        "irb120 (abb-rapid), kr6r900 (kuka-krl), tx2_60.",
    ),
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


def parse_vector(text: str, kinds: tuple[str, ...], parameter: str) -> tuple[float, ...]:
    """Comma-separated quantities with units (``0,0,100mm``; bare numbers in SI, radians).

    Parameters
    ----------
    text : str
        The option's value.
    kinds : tuple of str
        The quantity kind of each cell (length, angle, ...).
    parameter : str
        The option's name, for messages.

    Returns
    -------
    tuple of float
        SI values.

    Examples
    --------
    >>> [round(v, 6) for v in parse_vector("0,0,100mm", ("length",) * 3, "tool_offset")]
    [0.0, 0.0, 0.1]
    >>> round(parse_vector("180deg", ("angle",), "roll")[0], 6)
    3.141593
    """
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
    base = values["base_pose"].split(",")
    if len(base) not in (3, 6):
        raise InputError("base_pose", values["base_pose"], "needs x,y,z or x,y,z,roll,pitch,yaw")
    base_values = parse_vector(
        values["base_pose"], ("length",) * 3 + ("angle",) * (len(base) - 3), "base_pose"
    )
    offset = parse_vector(values["tool_offset"], ("length",) * 3, "tool_offset")
    rotation = parse_vector(values["tool_rotation"], ("angle",) * 3, "tool_rotation")
    seed = values["seed_joints"]
    low, high = LOOKAHEAD_TIME_RANGE_S
    return export_settings(
        robot=values["robot"],
        urdf=values["urdf"],
        base_link=values["base_link"],
        tip_link=values["tip_link"],
        seed_rad=None
        if seed is None
        else tuple(parse_quantity(cell, "angle", "seed_joints") for cell in seed.split(",")),
        tool_offset_m=(offset[0], offset[1], offset[2]),
        tool_rpy_rad=(rotation[0], rotation[1], rotation[2]),
        base_xyz_m=(base_values[0], base_values[1], base_values[2]),
        base_rpy_rad=(base_values[3], base_values[4], base_values[5])
        if len(base_values) == 6
        else (0.0, 0.0, 0.0),
        axis=_parse_axis(values["axis"]),
        # the range again in the typed unit, so that the message quotes what was typed
        lookahead_time_s=parse_bounded(
            values["lookahead_time"], "time", "lookahead_time", low, high, low_open=False
        ),
        gain=values["gain"],
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
