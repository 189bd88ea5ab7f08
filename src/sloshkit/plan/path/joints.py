"""An arm's joints along a 3-D path, for the path program's joint-speed limits.

The export's IK (`sloshkit.plan.path.result.JointSpeedCheck.joint_positions`, which
``sloshkit export`` uses too) is solved once along the untilted path, every `JOINT_GRID_M` of
the path parameter, and q(s) is the cubic spline through it (`JointMap`): the programs of
`sloshkit.plan.path.cone` then limit (q(s_k+1) - q(s_k)) / h for every joint.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class JointMap:
    """An arm's joints along the (untilted) path.

    Parameters
    ----------
    s_m : numpy.ndarray
        Path parameter of the IK samples (M,) [m].
    joints_rad : numpy.ndarray
        The joints there (M, dof) [rad], as the export solves them.
    limits_rad_s : numpy.ndarray
        Each joint's speed limit (dof,) [rad/s].

    Examples
    --------
    >>> import numpy as np
    >>> s = np.linspace(0.0, 0.1, 11)
    >>> joints = JointMap(s, np.column_stack((10 * s, -5 * s)), np.array([3.14, 3.14]))
    >>> joints.spline()(0.05, 1).round(6).tolist()  # dq/ds
    [10.0, -5.0]
    """

    s_m: FloatArray
    joints_rad: FloatArray
    limits_rad_s: FloatArray

    def spline(self) -> Any:
        """q(s): the cubic spline through the samples (call it with ``(s, 1)`` for dq/ds).

        Returns
        -------
        scipy.interpolate.CubicSpline
        """
        from scipy.interpolate import CubicSpline

        return CubicSpline(self.s_m, self.joints_rad, axis=0)


#: Spacing of the path parameter at which the arm's IK is solved for the programs [m].
JOINT_GRID_M = 0.005


def joint_map(problem: Any, check: Any) -> JointMap | str:
    """The arm's joints along the path every `JOINT_GRID_M` (at least 50 points).

    Parameters
    ----------
    problem : PathProblem
        The path.
    check : JointSpeedCheck
        The verifier that solves the arm (`sloshkit.plan.path.result.JointSpeedCheck`).

    Returns
    -------
    JointMap or str
        The joints q(s), or the IK's message when it fails: the untilted poses are the path's
        whatever the timing, so no plan can pass.

    Examples
    --------
    >>> from sloshkit.export.frames import Mounting
    >>> from sloshkit.export.kinematics import load_arm
    >>> from sloshkit.export.path_robot import RobotVerifier
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.015, 0.002), model)
    >>> arm = load_arm("ur5e")
    >>> reached = joint_map(problem, RobotVerifier(arm, Mounting(base_xyz_m=(-0.45, -0.13, 0.3))))
    >>> reached.joints_rad.shape
    (50, 6)
    >>> joint_map(problem, RobotVerifier(arm, Mounting(base_xyz_m=(3.0, 0.0, 0.0))))[:7]
    'robot: '
    """
    from sloshkit.errors import InputError
    from sloshkit.motion.poses import PoseTrajectory

    length = problem.path.length_m
    count = max(50, math.ceil(length / JOINT_GRID_M) + 1)
    s = np.linspace(0.0, length, count)
    rotation = problem.path.orientation(s)
    poses = PoseTrajectory(np.arange(count) * 1e-3, problem.path.position(s), rotation.as_quat())
    try:
        joints = check.joint_positions(poses)
    except InputError as error:
        return f"robot: {error}"
    return JointMap(s, joints, np.asarray(check.joint_speed_limits_rad_s, dtype=float))


__all__ = ["JOINT_GRID_M", "JointMap", "joint_map"]
