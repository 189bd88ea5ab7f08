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
from sloshkit.io.checks import (
    naming,
    require_bounded_rows,
    require_finite_rows,
    require_increasing_rows,
)
from sloshkit.io.tables import base_name, read_table, unit_from_name
from sloshkit.io.units import parse_quantity
from sloshkit.motion.poses import POSE_COLUMNS, PoseTrajectory, poses_from_rpy

FloatArray = NDArray[np.float64]

_TIME_NAMES = ("t", "time")
_QUATERNION = POSE_COLUMNS[4:]
_RPY = ("roll", "pitch", "yaw")

#: Largest position a pose file may hold [m]: beyond it the units are surely wrong, and the
#: differentiation (squares of positions over squared steps) would overflow.
MAX_POSITION_M = 1e6


def split_column_name(name: str) -> tuple[str, str | None]:
    """(base name, unit) of a header cell: ``"x [mm]"`` -> ("x", "mm"), ``"t_ms"`` -> ("t", "ms").

    Parameters
    ----------
    name : str
        A header cell.

    Returns
    -------
    tuple of (str, str or None)

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
    path: str | Path,
    *,
    tool_offset_m: Sequence[float] | None = None,
    name: str | None = None,
    parameter: str = "pose_file",
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
    parameter : str
        The option that named the file; every error names it (``pose_file``,
        ``motion_file``, ``path_from_poses``).

    Returns
    -------
    PoseTrajectory

    Raises
    ------
    InputError
        Missing file or columns, non-numeric cells, NaN or infinite values, bad units, fewer
        than 2 rows, time not strictly increasing, positions beyond `MAX_POSITION_M`,
        quaternions that are not unit (zero ones included); the message names ``parameter``,
        the row and the column.

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
    with naming(parameter, path):
        return _read_poses(path, tool_offset_m, name, parameter)


def _read_poses(
    path: str | Path, tool_offset_m: Sequence[float] | None, name: str | None, parameter: str
) -> PoseTrajectory:
    header, data = read_table(path)
    return _poses_from_table(path, header, data, tool_offset_m, name, parameter)


def _poses_from_table(
    path: str | Path,
    header: list[str],
    data: FloatArray,
    tool_offset_m: Sequence[float] | None,
    name: str | None,
    parameter: str,
) -> PoseTrajectory:
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
                require_finite_rows(data, {header[index]: index}, parameter, path)
                values = np.asarray(data[:, index], dtype=float) * _scale(unit, kind, header[index])
                if kind == "length":
                    require_bounded_rows(
                        values, header[index], MAX_POSITION_M, "m", parameter, path
                    )
                return values
        raise InputError(
            "pose_file",
            str(path),
            f"has no column {names[0]!r}; columns are " + ", ".join(header),
        )

    time = column(_TIME_NAMES, "time")
    time_name = header[columns[next(n for n in _TIME_NAMES if n in columns)][0]]
    require_increasing_rows(time, time_name, parameter, path)
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


#: Columns of a 1-D plan (`sloshkit plan --out`): unit-free name -> (quantity kind, SI key).
PLAN_COLUMNS: dict[str, tuple[str, str]] = {
    "t": ("time", "t_s"),
    "position": ("length", "position_m"),
    "velocity": ("velocity", "velocity_m_s"),
    "acceleration": ("acceleration", "acceleration_m_s2"),
}


def read_plan_file(
    path: str | Path, *, parameter: str = "plan"
) -> PoseTrajectory | dict[str, FloatArray]:
    """A plan file for export: a pose stream, or a 1-D plan's columns in SI.

    The one reader of pose and plan files: the same table reader, bounds
    (`sloshkit.io.tables.MAX_TABLE_ROWS`, the memory limit), units in the header, finite
    values, `MAX_POSITION_M` and quaternion tolerance
    (`sloshkit.motion.poses.QUATERNION_NORM_TOLERANCE`) as `read_pose_file`. A file with
    columns x, y, z is a pose stream (`read_pose_file`); one with ``t`` and ``position``
    (``t_s, position_m[, velocity_m_s, acceleration_m_s2]``, or with units such as
    ``position [mm]``) is a 1-D plan.

    Parameters
    ----------
    path : str or Path
        The file.
    parameter : str
        The option that named the file (in every error).

    Returns
    -------
    PoseTrajectory or dict of str to ndarray
        The poses, or the 1-D plan's columns keyed ``t_s``, ``position_m`` and, when present,
        ``velocity_m_s``, ``acceleration_m_s2``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "plan.csv").write_text("t [ms],position [mm]\\n0,0\\n4,1\\n8,2\\n")
    >>> read_plan_file(folder / "plan.csv")["position_m"].tolist()
    [0.0, 0.001, 0.002]
    """
    with naming(parameter, path):
        header, data = read_table(path)
        bases = [base_name(cell) for cell in header]
        if all(axis in bases for axis in "xyz"):
            return _poses_from_table(path, header, data, None, None, parameter)
        if "position" not in bases or not any(name in bases for name in _TIME_NAMES):
            raise InputError(
                parameter,
                str(path),
                "needs columns t_s, position_m[, velocity_m_s, acceleration_m_s2] (a 1-D plan) "
                "or t, x, y, z, qx, qy, qz, qw (a pose stream); found " + ", ".join(header),
            )
        columns: dict[str, FloatArray] = {}
        time_header = header[0]
        for base, (kind, key) in PLAN_COLUMNS.items():
            names = _TIME_NAMES if base == "t" else (base,)
            index = next((bases.index(name) for name in names if name in bases), None)
            if index is None:
                continue
            require_finite_rows(data, {header[index]: index}, parameter, path)
            _, unit = split_column_name(header[index])
            time_header = header[index] if base == "t" else time_header
            columns[key] = np.asarray(data[:, index], dtype=float) * _scale(
                unit, kind, header[index]
            )
        require_increasing_rows(columns["t_s"], time_header, parameter, path)
        require_bounded_rows(
            columns["position_m"], "position", MAX_POSITION_M, "m", parameter, path
        )
        return columns


def parse_tool_offset(text: str) -> tuple[float, float, float]:
    """``"X,Y,Z"`` with optional units per component (``"0,0,120mm"``) -> metres.

    Parameters
    ----------
    text : str
        Three lengths separated by commas (bare numbers are metres).

    Returns
    -------
    tuple of 3 floats
        The offset [m].

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
