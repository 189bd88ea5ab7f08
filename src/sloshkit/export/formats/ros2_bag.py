"""``ros2-bag``: the joint trajectory as a rosbag2 that ``ros2 bag play`` publishes.

A rosbag2 folder (``metadata.yaml`` and one SQLite3 file, bag format version 8: ROS 2 Iron and
later, Jazzy included) holding one ``trajectory_msgs/msg/JointTrajectory`` message on
`TOPIC` (the ``joint_trajectory_controller``'s command topic; ``ros2 bag play --remap`` sends it
elsewhere), serialised as CDR with the message definitions of ROS 2 Jazzy (rosbags' typestore).
A bag has no argument-length limit: ``ros2 topic pub ... "$(cat file.yaml)"`` fails past about
0.6 s of trajectory at 4 ms, a bag carries any length. The metadata (sloshkit version, model,
limits, mounting) is in the bag's ``custom_data``.

The message is the one the ``ros2`` YAML format writes (`sloshkit.export.formats.ros2`):
header stamp zero ("start now"), ``frame_id`` the base link, one point per sample with
positions, velocities, accelerations and ``time_from_start``.

References
----------
rosbags (Ternaris), https://ternaris.gitlab.io/rosbags/ (``rosbags.rosbag2.Writer``,
``rosbags.typesys.get_typestore``); ROS 2 message definitions trajectory_msgs/msg/
JointTrajectory and JointTrajectoryPoint; rosbag2 metadata format (ros2/rosbag2, version 8).
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Final

import numpy as np

from sloshkit.errors import InputError
from sloshkit.export.formats.ros2 import NANOSECONDS, duration
from sloshkit.export.ik import JointPath

#: The topic of the message: ``joint_trajectory_controller``'s command topic.
TOPIC = "/joint_trajectory_controller/joint_trajectory"
MESSAGE_TYPE = "trajectory_msgs/msg/JointTrajectory"
#: rosbag2 metadata version written (8: ROS 2 Iron and later).
BAG_VERSION: Final = 8


def _typestore() -> Any:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_JAZZY)


def write_ros2_bag(
    path: str | Path,
    joints: JointPath,
    frame_id: str,
    metadata: Mapping[str, object],
    topic: str = TOPIC,
) -> Path:
    """Write a joint path as a one-message rosbag2 folder (written beside, then renamed).

    Parameters
    ----------
    path : str or pathlib.Path
        The bag folder (must not exist).
    joints : JointPath
        The joint samples.
    frame_id : str
        The header's frame (the arm's base link).
    metadata : mapping
        Stored as the bag's ``custom_data`` (text values).
    topic : str
        The topic of the message.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.5
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_ros2_bag(pathlib.Path(tempfile.mkdtemp()) / "move.bag", path, "base", {})
    >>> sorted(p.suffix for p in out.iterdir())
    ['.db3', '.yaml']
    """
    from rosbags.rosbag2 import Writer

    target = Path(path)
    if target.exists() or target.is_symlink():
        raise InputError(
            "out", str(target), "exists: a rosbag2 is a new folder; remove it or choose another"
        )
    store = _typestore()
    types = store.types
    points = []
    for index, time in enumerate(joints.time_s):
        seconds, nanoseconds = duration(time)
        points.append(
            types["trajectory_msgs/msg/JointTrajectoryPoint"](
                positions=np.asarray(joints.position_rad[index], dtype=np.float64),
                velocities=np.asarray(joints.velocity_rad_s[index], dtype=np.float64),
                accelerations=np.asarray(joints.acceleration_rad_s2[index], dtype=np.float64),
                effort=np.zeros(0, dtype=np.float64),
                time_from_start=types["builtin_interfaces/msg/Duration"](
                    sec=seconds, nanosec=nanoseconds
                ),
            )
        )
    message = types[MESSAGE_TYPE](
        header=types["std_msgs/msg/Header"](
            stamp=types["builtin_interfaces/msg/Time"](sec=0, nanosec=0), frame_id=frame_id
        ),
        joint_names=list(joints.joint_names),
        points=points,
    )
    staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=target.parent or "."))
    folder = staging / "bag"
    try:
        with Writer(folder, version=BAG_VERSION) as writer:
            for key, value in metadata.items():
                writer.set_custom_data(str(key), " ".join(str(value).split()))
            connection = writer.add_connection(topic, MESSAGE_TYPE, typestore=store)
            writer.write(connection, 0, store.serialize_cdr(message, MESSAGE_TYPE))
        os.replace(folder, target)
    finally:
        with contextlib.suppress(OSError):
            shutil.rmtree(staging)
    return target


def read_ros2_bag(path: str | Path) -> tuple[JointPath, str]:
    """The joint path and header frame of the first ``JointTrajectory`` message of a bag,
    deserialised with the real message type (rosbags' typestore).

    Parameters
    ----------
    path : str or pathlib.Path
        The bag folder.

    Returns
    -------
    tuple
        (`JointPath`, the header's frame_id).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.5
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_ros2_bag(pathlib.Path(tempfile.mkdtemp()) / "move.bag", path, "base", {})
    >>> joints, frame = read_ros2_bag(out)
    >>> joints.time_s.tolist(), frame
    ([0.0, 0.5, 1.0], 'base')
    """
    from rosbags.rosbag2 import Reader

    store = _typestore()
    try:
        with Reader(Path(path)) as reader:
            connections = [c for c in reader.connections if c.msgtype == MESSAGE_TYPE]
            if not connections:
                raise InputError("file", str(path), f"holds no {MESSAGE_TYPE} message")
            _, _, raw = next(iter(reader.messages(connections=connections)))
    except InputError:
        raise
    except Exception as error:  # rosbags raises its own errors for unreadable bags
        raise InputError("file", str(path), f"is not a readable rosbag2 ({error})") from None
    message = store.deserialize_cdr(raw, MESSAGE_TYPE)
    points = message.points
    time = np.array(
        [p.time_from_start.sec + p.time_from_start.nanosec / NANOSECONDS for p in points]
    )
    arrays = [
        np.array([getattr(p, key) for p in points], dtype=float)
        for key in ("positions", "velocities", "accelerations")
    ]
    names = tuple(str(name) for name in message.joint_names)
    return JointPath(time, arrays[0], arrays[1], arrays[2], names), str(message.header.frame_id)
