"""``ros2``: a ``trajectory_msgs/msg/JointTrajectory`` message as YAML.

Layout of the ROS 2 message (trajectory_msgs/msg/JointTrajectory.msg and
JointTrajectoryPoint.msg, https://docs.ros2.org/latest/api/trajectory_msgs/): ``header``
(``std_msgs/Header``: ``stamp {sec, nanosec}``, ``frame_id``), ``joint_names`` (string[]),
``points`` (JointTrajectoryPoint[]: ``positions``, ``velocities``, ``accelerations``, ``effort``
(float64[]) and ``time_from_start`` (``builtin_interfaces/Duration``: ``sec`` int32, ``nanosec``
uint32)). The YAML is the message's ROS 2 YAML form, so ``ros2 topic pub`` loads it, and its
``points`` fit a ``control_msgs/action/FollowJointTrajectory`` goal. A zero ``stamp`` means
"start now" for ``joint_trajectory_controller``.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from sloshkit.errors import InputError
from sloshkit.export.formats.common import header_lines, number
from sloshkit.export.ik import JointPath
from sloshkit.files import atomic_open

NANOSECONDS = 1_000_000_000


def duration(time_s: float) -> tuple[int, int]:
    """``builtin_interfaces/Duration`` (sec, nanosec) of a non-negative time, to the nearest
    nanosecond.

    Parameters
    ----------
    time_s : float
        Time from the trajectory's start [s].

    Returns
    -------
    tuple of int
        (sec, nanosec).

    Examples
    --------
    >>> duration(1.004)
    (1, 4000000)
    """
    total = round(float(time_s) * NANOSECONDS)
    if total < 0:
        raise InputError("time_from_start", time_s, "must be >= 0 s")
    seconds, nanoseconds = divmod(total, NANOSECONDS)
    return int(seconds), int(nanoseconds)


def _flow(values: np.ndarray) -> str:
    return "[" + ", ".join(number(value) for value in values) + "]"


def write_ros2_yaml(
    path: str | Path, joints: JointPath, frame_id: str, metadata: Mapping[str, object]
) -> Path:
    """Write a joint path as a ``trajectory_msgs/msg/JointTrajectory`` YAML document.

    Parameters
    ----------
    path : output file
    joints : the joint samples (positions, velocities, accelerations)
    frame_id : the header's frame (the arm's base link)
    metadata : written as ``#`` comment lines first

    Returns
    -------
    pathlib.Path

    References
    ----------
    ROS 2 message definitions trajectory_msgs/msg/JointTrajectory, JointTrajectoryPoint,
    std_msgs/msg/Header, builtin_interfaces/msg/Duration.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.5
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_ros2_yaml(pathlib.Path(tempfile.mkdtemp()) / "t.yaml", path, "base", {})
    >>> out.read_text().splitlines()[-1]
    '    time_from_start: {sec: 1, nanosec: 0}'
    """
    lines = [
        header_lines(metadata),
        "header:\n",
        "  stamp: {sec: 0, nanosec: 0}\n",
        f"  frame_id: '{frame_id}'\n",
        "joint_names: [" + ", ".join(f"'{name}'" for name in joints.joint_names) + "]\n",
        "points:\n",
    ]
    for index, time in enumerate(joints.time_s):
        seconds, nanoseconds = duration(time)
        lines += [
            f"  - positions: {_flow(joints.position_rad[index])}\n",
            f"    velocities: {_flow(joints.velocity_rad_s[index])}\n",
            f"    accelerations: {_flow(joints.acceleration_rad_s2[index])}\n",
            "    effort: []\n",
            f"    time_from_start: {{sec: {seconds}, nanosec: {nanoseconds}}}\n",
        ]
    with atomic_open(path) as handle:
        handle.write("".join(lines))
    return Path(path)


def read_ros2_yaml(path: str | Path) -> tuple[JointPath, str]:
    """The joint path and header frame of a ``JointTrajectory`` YAML file (PyYAML).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    tuple
        (`JointPath`, the header's frame_id).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.5
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_ros2_yaml(pathlib.Path(tempfile.mkdtemp()) / "t.yaml", path, "base", {})
    >>> read_ros2_yaml(out)[0].time_s
    array([0. , 0.5, 1. ])
    """
    import yaml

    try:
        message = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except yaml.YAMLError as error:
        raise InputError("file", str(path), f"is not valid YAML ({error})") from None
    try:
        names = tuple(str(name) for name in message["joint_names"])
        points = message["points"]
        time = np.array(
            [
                point["time_from_start"]["sec"] + point["time_from_start"]["nanosec"] / NANOSECONDS
                for point in points
            ]
        )
        arrays = [
            np.array([point[key] for point in points], dtype=float)
            for key in ("positions", "velocities", "accelerations")
        ]
        frame = str(message["header"]["frame_id"])
    except (KeyError, TypeError, ValueError) as error:
        raise InputError("file", str(path), f"is not a JointTrajectory message ({error})") from None
    if any(array.shape != (time.size, len(names)) for array in arrays):
        raise InputError("file", str(path), "every point needs one value per joint")
    return JointPath(time, arrays[0], arrays[1], arrays[2], names), frame
