"""Requests of ``sloshkit calibrate`` built from its arguments: the record (time and signal in
SI, from the units its header or the options name) and the applied motion of
``--motion-file`` (a motion or pose file on the record's clock)."""

from __future__ import annotations

import contextlib
import typing
from dataclasses import replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.io.checks import naming, require_finite_rows
from sloshkit.io.tables import (
    TIME_NAMES,
    column_name,
    column_si,
    find_column,
    read_table,
    select_column,
    unit_from_name,
)
from sloshkit.io.units import parse_quantity

FloatArray = NDArray[np.float64]

if typing.TYPE_CHECKING:  # imported where used: the calibration stack is not start-up's
    from sloshkit.calibration import AppliedMotion
    from sloshkit.motion.poses import PoseTrajectory


def applied_motion_request(
    path: Path, axis: str | None, offset_s: float
) -> tuple[AppliedMotion, PoseTrajectory | None]:
    """The applied motion of ``calibrate --motion-file``: a pose file (t,x,y,z,qx,qy,qz,qw) or
    a motion file, shifted by the clock offset; the poses too when the file has them.

    Parameters
    ----------
    path : pathlib.Path
        ``--motion-file``.
    axis : str or None
        ``--motion-axis`` (pose files only; default: the travel direction).
    offset_s : float
        ``--clock-offset`` [s]: the motion's time on the record's clock.

    Returns
    -------
    tuple
        (AppliedMotion, PoseTrajectory or None).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> move = pathlib.Path(tempfile.mkdtemp()) / "move.csv"
    >>> s = [i / 100 for i in range(101)]  # a quintic rest-to-rest move over 1 s
    >>> rows = "".join(f"{u},{0.1 * u**3 * (10 - 15 * u + 6 * u * u)}\\n" for u in s)
    >>> _ = move.write_text("t,x\\n" + rows)
    >>> applied, poses = applied_motion_request(move, None, 2.0)
    >>> applied.start_s, poses is None
    (2.0, True)
    """
    from sloshkit.calibration import AppliedMotion, applied_from_poses  # not start-up's
    from sloshkit.io.motions import read_motion_file
    from sloshkit.io.poses import read_pose_file
    from sloshkit.motion.poses import POSE_COLUMNS

    with naming("motion_file", path):
        header, data = read_table(path)
    index = [find_column(header, (name,)) for name in POSE_COLUMNS]
    if all(i is not None for i in index):
        # the pose-file reader checks rows, units, time and quaternions, naming --motion-file
        poses = read_pose_file(path, name=str(path), parameter="motion_file")
        time, position = poses.time_s, poses.position_m
        with naming("motion_file", path, keep=("motion_axis",)):
            applied = applied_from_poses(
                time, position, poses.quaternion_xyzw, axis, name=str(path)
            )
        return replace(applied, start_s=applied.start_s + offset_s), poses
    if axis is not None:
        raise InputError("motion_axis", axis, "applies to pose files (t,x,y,z,qx,qy,qz,qw) only")
    with naming("motion_file", path):
        time_index = find_column(header, TIME_NAMES)
        time_column = 0 if time_index is None else time_index
        require_finite_rows(data, {header[time_column]: time_column}, "motion_file", path)
        start = float(column_si(header, data, time_column, "time")[0])
        motion = read_motion_file(path)
    return AppliedMotion(motion, start + offset_s, (f"motion file {path}",)), None


def record_request(
    data: Path,
    time_column: str,
    signal_column: str,
    time_unit: str | None,
    signal_kind: str,
) -> tuple[FloatArray, FloatArray]:
    """Time [s] and signal of a calibration record (``calibrate DATA``): the time unit from
    ``--time-unit`` or the column's header (``t [ms]``, ``t_ms``; seconds otherwise), a height
    or angle signal in SI when its header names a unit (``eta [mm]``; any other signal as it is,
    the estimators are scale-free).

    Parameters
    ----------
    data : pathlib.Path
        The record (CSV or whitespace table).
    time_column, signal_column : str
        Column names or 0-based indices.
    time_unit : str or None
        ``--time-unit``.
    signal_kind : str
        ``--signal-kind`` (force, height or angle).

    Returns
    -------
    tuple of numpy.ndarray
        Time [s] and signal.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> record = pathlib.Path(tempfile.mkdtemp()) / "decay.csv"
    >>> rows = "".join(f"{i},{(-1) ** i}\\n" for i in range(2000))
    >>> _ = record.write_text("t [ms],eta [mm]\\n" + rows)
    >>> time, eta = record_request(record, "t [ms]", "eta [mm]", None, "height")
    >>> float(time[1]), float(eta[0])
    (0.001, 0.001)
    """
    from sloshkit.io.motions import check_plausible_record  # the motion stack: not start-up's

    header, table = read_table(data)
    select_column(header, table, time_column, "time_column")  # a missing column first
    if time_unit is None:
        time_unit = unit_from_name(column_name(header, time_column)) or "s"
    time_scale = parse_quantity(f"1 {time_unit}", "time", "time_unit")
    time = select_column(header, table, time_column, "time_column") * time_scale
    check_plausible_record(time, str(data))
    values = select_column(header, table, signal_column, "signal_column")
    signal_unit = unit_from_name(column_name(header, signal_column))
    signal_quantity = {"height": "length", "angle": "angle"}.get(signal_kind)
    if signal_unit is not None and signal_quantity is not None:  # e.g. 'eta [mm]' -> metres
        with contextlib.suppress(InputError):  # another dimension: the estimators are scale-free
            values = values * parse_quantity(f"1 {signal_unit}", signal_quantity, "signal_column")
    return time, values
