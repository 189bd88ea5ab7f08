"""Read pose-trajectory files: ``t,x,y,z,qx,qy,qz,qw`` or roll/pitch/yaw columns.

The table is read by `sloshkit.io.tables.read_table` (comma, semicolon or whitespace separated,
``#`` comments). Units written in a column header are honoured (``t [ms]``, ``x [mm]``,
``roll [deg]``, also ``t(ms)`` or the suffixes ``_ms``/``_mm``/``_deg``); without a unit the
values are SI (seconds, metres, radians). The pose is that of the container's bottom centre
in a world frame with z up, orientation container -> world, quaternion scalar last; when the
file gives another tool point (e.g. the flange), ``tool_offset_m`` is the bottom centre in
that point's frame.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.io.tables import base_name, read_table, unit_from_name
from sloshkit.io.units import parse_quantity
from sloshkit.motion.poses import PoseTrajectory, poses_from_rpy

FloatArray = NDArray[np.float64]

_TIME_NAMES = ("t", "time")
_QUATERNION = ("qx", "qy", "qz", "qw")
_RPY = ("roll", "pitch", "yaw")


def split_column_name(name: str) -> tuple[str, str | None]:
    """(base name, unit) of a header cell: ``"x [mm]"`` -> ("x", "mm"), ``"t_ms"`` -> ("t", "ms").

    Examples
    --------
    >>> split_column_name("t [ms]"), split_column_name("roll_deg"), split_column_name("qw")
    (('t', 'ms'), ('roll', 'deg'), ('qw', None))
    """
    return base_name(name), unit_from_name(name)


def _scale(unit: str | None, kind: str, column: str) -> float:
    """SI value of one ``unit`` (1.0 without a unit)."""
    if unit is None or kind == "none":
        return 1.0
    return parse_quantity(f"1 {unit}", kind, f"unit of column {column!r}")


def read_pose_file(
    path: str | Path, *, tool_offset_m: Sequence[float] | None = None, name: str | None = None
) -> PoseTrajectory:
    """Read a pose trajectory from a table with a header.

    Parameters
    ----------
    path : str or Path
        The file: columns ``t, x, y, z`` and either ``qx, qy, qz, qw`` (unit quaternion,
        container -> world, scalar last) or ``roll, pitch, yaw`` (fixed-axis x-y-z angles,
        R = Rz(yaw) Ry(pitch) Rx(roll)); other columns are ignored.
    tool_offset_m : sequence of 3 floats, optional
        The container's bottom centre in the frame of the point the file gives [m]
        (`sloshkit.motion.poses.PoseTrajectory.with_tool_offset`).
    name : str, optional
        Label of the trajectory (default: the file name without suffix).

    Returns
    -------
    PoseTrajectory

    Raises
    ------
    InputError
        Missing file or columns, non-numeric cells, bad units, time not increasing, quaternions
        that are not unit.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "move.csv").write_text("t [ms];x [mm];y;z;roll [deg];pitch;yaw\\n"
    ...                                      "0;0;0;0;0;0;0\\n500;100;0;0;10;0;0\\n")
    >>> poses = read_pose_file(folder / "move.csv")
    >>> poses.time_s.tolist(), poses.position_m[1].tolist()
    ([0.0, 0.5], [0.1, 0.0, 0.0])
    """
    header, data = read_table(path)
    if all(cell.isdigit() for cell in header):
        raise InputError(
            "pose_file", str(path), "needs a header naming t, x, y, z and qx, qy, qz, qw"
        )
    columns: dict[str, tuple[int, str | None]] = {}
    for index, cell in enumerate(header):
        base, unit = split_column_name(cell)
        columns.setdefault(base, (index, unit))

    def column(names: Sequence[str], kind: str) -> FloatArray:
        for candidate in names:
            if candidate in columns:
                index, unit = columns[candidate]
                return np.asarray(data[:, index], dtype=float) * _scale(unit, kind, header[index])
        raise InputError(
            "pose_file",
            str(path),
            f"has no column {names[0]!r}; columns are " + ", ".join(header),
        )

    time = column(_TIME_NAMES, "time")
    position = np.column_stack([column((axis,), "length") for axis in "xyz"])
    label = name if name is not None else Path(path).stem
    if all(key in columns for key in _QUATERNION):
        quaternion = np.column_stack([column((key,), "none") for key in _QUATERNION])
        poses = PoseTrajectory(time, position, quaternion, label)
    elif all(key in columns for key in _RPY):
        roll, pitch, yaw = (column((key,), "angle") for key in _RPY)
        poses = poses_from_rpy(time, position, roll, pitch, yaw, label)
    else:
        raise InputError(
            "pose_file",
            str(path),
            "needs orientation columns qx, qy, qz, qw or roll, pitch, yaw; columns are "
            + ", ".join(header),
        )
    if tool_offset_m is not None:
        poses = poses.with_tool_offset(tool_offset_m)
    return poses


def parse_tool_offset(text: str) -> tuple[float, float, float]:
    """``"X,Y,Z"`` with optional units per component (``"0,0,120mm"``) -> metres.

    Examples
    --------
    >>> parse_tool_offset("0, 0, 120mm")
    (0.0, 0.0, 0.12)
    """
    parts = [part.strip() for part in text.split(",")]
    if len(parts) != 3 or not all(parts):
        raise InputError("tool_offset", text, "must be three lengths X,Y,Z, e.g. 0,0,120mm")
    x, y, z = (parse_quantity(part, "length", "tool_offset") for part in parts)
    return (x, y, z)
