"""Exported files read back: container poses and joint samples, for the round trip."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.formats.vendors import PROGRAM_FORMATS, read_interpolated
from sloshkit.export.frames import Mounting, poses_to_matrices
from sloshkit.export.kinematics import Arm

FloatArray = NDArray[np.float64]

#: The formats that hold joint positions (read back through forward kinematics).
JOINT_FORMATS = ("joint-csv", "ros2", "ros2-bag", "urscript", *PROGRAM_FORMATS)


def rebuild_container_poses(
    fmt: str,
    path: str | Path,
    arm: Arm | None,
    mounting: Mounting,
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0),
) -> tuple[FloatArray, FloatArray]:
    """Times [s] and container poses in the base frame (N, 4, 4) parsed back from a file
    (forward kinematics and the mounting for joint formats; a cam table is put on ``axis``
    of the path frame from the path origin, upright).

    Parameters
    ----------
    fmt : str
        The file's format (`FORMATS`).
    path : str or pathlib.Path
        The file.
    arm : Arm or None
        The arm, for joint formats.
    mounting : Mounting
        Where the container sits in the flange and the path in the base.
    axis : tuple of float
        Direction of a cam table's move in the path frame.

    Returns
    -------
    tuple of numpy.ndarray
        Times (N,) [s] and poses (N, 4, 4).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit.export.plans import PoseStream
    >>> t = np.arange(4) * 0.1
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> stream = PoseStream(PoseTrajectory(t, np.ones((4, 3)), np.tile([0, 0, 0, 1.0], (4, 1))))
    >>> from sloshkit.export.formats.pose_csv import write_pose_csv
    >>> out = write_pose_csv(pathlib.Path(tempfile.mkdtemp()) / "p.csv", stream, {})
    >>> rebuild_container_poses("pose-csv", out, None, Mounting())[1][3, :3, 3]
    array([1., 1., 1.])
    """
    from sloshkit.export.formats import cam_table, pose_csv

    if fmt == "pose-csv":
        stream = pose_csv.read_pose_csv(path)
        return stream.time_s, poses_to_matrices(stream.position_m, stream.quaternion_xyzw)
    if fmt == "cam-table":
        line = cam_table.read_cam_table(path)
        poses = np.broadcast_to(np.eye(4), (line.time_s.size, 4, 4)).copy()
        direction = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
        poses[:, :3, 3] = np.outer(line.position_m - line.position_m[0], direction)
        return line.time_s, mounting.base_to_path[None] @ poses
    if arm is None:
        raise InputError("robot", None, f"format {fmt} needs an arm (--robot or --urdf)")
    time, position = read_joint_samples(fmt, path)
    if position.shape[1] != arm.dof:
        raise InputError("file", str(path), f"has {position.shape[1]} joints, the arm {arm.dof}")
    flange = arm.forward(position)
    return time, flange @ mounting.flange_to_container[None]


def read_joint_samples(fmt: str, path: str | Path) -> tuple[FloatArray, FloatArray]:
    """Times [s] and joint positions (samples, joints) [rad] of a joint-format file.

    Parameters
    ----------
    fmt : str
        joint-csv, ros2, ros2-bag, urscript, or a robot program (fanuc-ls, abb-rapid, kuka-krl:
        its points joined by the spline on the round trip's 2 ms grid).
    path : str or pathlib.Path
        The file.

    Returns
    -------
    tuple of numpy.ndarray
        Times [s] and joint positions [rad].

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit.export.formats.joint_csv import write_joint_csv
    >>> from sloshkit.export.ik import JointPath
    >>> t = np.arange(3) * 0.1
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_joint_csv(pathlib.Path(tempfile.mkdtemp()) / "j.csv", path, {})
    >>> read_joint_samples("joint-csv", out)[1][:, 0]
    array([0. , 0.1, 0.2])
    """
    from sloshkit.export.formats import joint_csv, ros2, urscript

    if fmt == "joint-csv":
        joints = joint_csv.read_joint_csv(path)
        return joints.time_s, joints.position_rad
    if fmt == "ros2":
        joints, _ = ros2.read_ros2_yaml(path)
        return joints.time_s, joints.position_rad
    if fmt == "ros2-bag":
        from sloshkit.export.formats.ros2_bag import read_ros2_bag

        joints, _ = read_ros2_bag(path)
        return joints.time_s, joints.position_rad
    if fmt == "urscript":
        return urscript.read_urscript(path)
    if fmt in PROGRAM_FORMATS:  # the points joined at the controller's interpolation period
        return read_interpolated(fmt, path)
    raise InputError("format", fmt, "is not a joint format: " + ", ".join(JOINT_FORMATS))
