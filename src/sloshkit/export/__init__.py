"""Export plans to robot and drive controllers, with a round-trip check.

`export_plan` writes a 1-D plan or a pose stream as ``pose-csv``, ``joint-csv``, ``ros2``
(``trajectory_msgs/JointTrajectory`` YAML), ``urscript`` (``servoj`` at 2 ms), ``cam-table``,
or an industrial-robot program of timed joint moves: ``fanuc-ls`` (FANUC TP), ``abb-rapid``
(RAPID ``MoveAbsJ \\T``) or ``kuka-krl`` (a KRL ``TIME_BLOCK`` spline);
joint formats go through inverse kinematics (`load_arm`, ikpy) with the container's mounting
(`Mounting`). The round trip (`check_round_trip`) parses the file back, rebuilds the motion and
re-simulates the slosh. See ``docs/export.md``.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

#: Where each public name lives: imported on first use (PEP 562), so that a command that only
#: needs one submodule (the plan command's option parsing needs `frames`) does not import them
#: all (the pose path and its spline library among them).
_API = {
    "FORMATS": "sloshkit.export.exporter",
    "ExportResult": "sloshkit.export.exporter",
    "check_round_trip": "sloshkit.export.exporter",
    "export_plan": "sloshkit.export.exporter",
    "Mounting": "sloshkit.export.frames",
    "JointPath": "sloshkit.export.ik",
    "solve_joint_path": "sloshkit.export.ik",
    "Arm": "sloshkit.export.kinematics",
    "load_arm": "sloshkit.export.kinematics",
    "robot_names": "sloshkit.export.kinematics",
    "LinePlan": "sloshkit.export.plans",
    "PoseStream": "sloshkit.export.plans",
    "line_to_poses": "sloshkit.export.plans",
    "read_plan": "sloshkit.export.plans",
    "rebuild_container_poses": "sloshkit.export.readback",
    "RoundTrip": "sloshkit.export.roundtrip",
}


def __getattr__(name: str) -> Any:
    """Import a public name from its module on first use (PEP 562)."""
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from sloshkit.export.exporter import FORMATS, ExportResult, check_round_trip, export_plan
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
