"""Export plans to robot and drive controllers, with a round-trip check.

`export_plan` writes a 1-D plan or a pose stream as ``pose-csv``, ``joint-csv``, ``ros2``
(``trajectory_msgs/JointTrajectory`` YAML), ``urscript`` (``servoj`` at 2 ms), ``cam-table``,
or an industrial-robot program of timed joint moves: ``fanuc-ls`` (FANUC TP), ``abb-rapid``
(RAPID ``MoveAbsJ \\T``) or ``kuka-krl`` (a KRL ``TIME_BLOCK`` spline);
joint formats go through inverse kinematics (`load_arm`, ikpy) with the container's mounting
(`Mounting`). The round trip (`check_round_trip`) parses the file back, rebuilds the motion and
re-simulates the slosh. See ``docs/export.md``.
"""

from sloshkit.export.exporter import (
    FORMATS,
    ExportResult,
    check_round_trip,
    export_plan,
)
from sloshkit.export.frames import Mounting
from sloshkit.export.ik import JointPath, solve_joint_path
from sloshkit.export.kinematics import Arm, load_arm, robot_names
from sloshkit.export.plans import LinePlan, PoseStream, line_to_poses, read_plan
from sloshkit.export.readback import rebuild_container_poses
from sloshkit.export.roundtrip import RoundTrip

__all__ = [
    "FORMATS",
    "Arm",
    "ExportResult",
    "JointPath",
    "LinePlan",
    "Mounting",
    "PoseStream",
    "RoundTrip",
    "check_round_trip",
    "export_plan",
    "line_to_poses",
    "load_arm",
    "read_plan",
    "rebuild_container_poses",
    "robot_names",
    "solve_joint_path",
]
