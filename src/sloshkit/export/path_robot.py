"""A robot's joint-speed check for the 3-D path planner's verification.

The 3-D planner (`sloshkit.plan.path.planner`) knows Cartesian and angular limits only; a plan
that meets them may still need joint speeds the arm does not have (a tilted container near a
wrist singularity, for instance). `robot_verifier` wraps the planner's verification: every
export is also solved for the arm's joints, exactly as ``sloshkit export`` solves it
(`sloshkit.export.ik.solve_joint_path`: container poses placed in the robot base by the
mounting, the flange frames through the tool transform, IK sample by sample, reach, position
limits, continuity and singularity checked), and its joint velocities are compared with the
arm's limits. A plan whose joints are too fast is not feasible; the ratio of the fastest joint
to its limit is the uniform slow-down (``required_stretch``) the planner's verification loop
applies before it verifies again. Any other IK failure (out of reach, joint limit, branch
change, singularity) makes the plan infeasible with the exporter's message.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.frames import Mounting, invert, poses_to_matrices
from sloshkit.export.ik import solve_joint_path
from sloshkit.export.kinematics import Arm
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.problem import PathProblem
from sloshkit.plan.path.result import Verification, Verifier, verify

FloatArray = NDArray[np.float64]


def _joint_path(arm: Arm, mounting: Mounting, poses: PoseTrajectory) -> Any:
    """`sloshkit.export.ik.solve_joint_path` of the export's container poses, placed as
    ``sloshkit export`` places them, without its velocity check."""
    container = mounting.base_to_path[None] @ poses_to_matrices(
        poses.position_m, poses.quaternion_xyzw
    )
    flange = container @ invert(mounting.flange_to_container)[None]
    unlimited = dataclasses.replace(arm, velocity_limit_rad_s=np.full(arm.dof, np.inf))
    return solve_joint_path(unlimited, flange, poses.time_s)


def joint_speed_ratio(arm: Arm, mounting: Mounting, poses: PoseTrajectory) -> tuple[float, str]:
    """Largest joint speed over its limit along the export, and that joint's description.

    Parameters
    ----------
    arm : Arm
        The arm (`sloshkit.export.kinematics.load_arm`).
    mounting : Mounting
        Container in the flange, path in the robot base (as ``sloshkit export`` uses it).
    poses : PoseTrajectory
        The planner's export (container bottom centre, path frame).

    Returns
    -------
    tuple
        (max over samples and joints of |q'| / limit, ``"<joint> <speed> > <limit> rad/s"``).

    Raises
    ------
    InputError
        When the IK fails (reach, joint position limit, branch change, singularity).

    References
    ----------
    `sloshkit.export.ik.solve_joint_path` (ikpy IK, checks, quintic-spline joint velocities).

    Examples
    --------
    >>> from sloshkit.export.kinematics import load_arm
    >>> arm = load_arm("ur5e")
    >>> t = np.arange(11) * 0.1
    >>> x = -0.4 + 0.1 * (t / t[-1]) ** 2 * (3 - 2 * t / t[-1])
    >>> poses = PoseTrajectory(t, np.c_[x, -0.13 + 0 * t, 0.3 + 0 * t],
    ...                        np.tile([0.0, 0.0, 0.0, 1.0], (t.size, 1)))
    >>> ratio, joint = joint_speed_ratio(arm, Mounting(), poses)
    >>> ratio < 1.0
    True
    """
    joints = _joint_path(arm, mounting, poses)
    ratio = np.abs(joints.velocity_rad_s) / arm.velocity_limit_rad_s
    index, joint = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    speed = float(np.abs(joints.velocity_rad_s[index, joint]))
    limit = float(arm.velocity_limit_rad_s[joint])
    return float(ratio[index, joint]), f"{arm.joint_names[joint]} {speed:.3g} > {limit:.3g} rad/s"


@dataclasses.dataclass(frozen=True, eq=False)
class RobotVerifier:
    """The planner's verification plus an arm's joint-speed check (module docstring); also a
    `sloshkit.plan.path.result.JointSpeedCheck`, so that ``--method optimal`` limits the joint
    speeds in its programs.

    Parameters
    ----------
    arm : Arm
        The arm.
    mounting : Mounting
        Container in the flange and path in the base.
    base : callable
        The verification it extends (default the nonlinear 3-D model).

    References
    ----------
    `sloshkit.export.ik.solve_joint_path`.

    Examples
    --------
    >>> from sloshkit.export.kinematics import load_arm
    >>> from sloshkit.plan.path.result import JointSpeedCheck, linear_verifier
    >>> check = RobotVerifier(load_arm("ur5e"), Mounting(), linear_verifier)
    >>> callable(check), isinstance(check, JointSpeedCheck)
    (True, True)
    """

    arm: Arm
    mounting: Mounting
    base: Verifier = verify

    def __call__(self, problem: PathProblem, poses: PoseTrajectory, tilted: bool) -> Verification:
        """The base verification with ``joint speed ...`` or ``robot: ...`` violations added
        and ``required_stretch`` set to the joint-speed ratio."""
        found = self.base(problem, poses, tilted)
        extra: list[str] = []
        stretch = 1.0
        try:
            ratio, joint = joint_speed_ratio(self.arm, self.mounting, poses)
        except InputError as error:
            extra.append(f"robot: {error}")
        else:
            if ratio > 1.0:
                extra.append(f"joint speed {joint}")
                stretch = ratio
        changes: dict[str, Any] = {
            "violations": found.violations + tuple(extra),
            "required_stretch": max(found.required_stretch, stretch),
        }
        return dataclasses.replace(found, **changes)

    def joint_positions(self, poses: PoseTrajectory) -> FloatArray:
        """The arm's joints at the poses (n, dof) [rad], as ``sloshkit export`` solves them;
        raises `sloshkit.errors.InputError` when the IK fails."""
        return np.asarray(_joint_path(self.arm, self.mounting, poses).position_rad)

    @property
    def joint_speed_limits_rad_s(self) -> FloatArray:
        """The arm's joint speed limits [rad/s]."""
        return np.asarray(self.arm.velocity_limit_rad_s, dtype=float)


def robot_verifier(arm: Arm, mounting: Mounting, base: Verifier = verify) -> RobotVerifier:
    """`RobotVerifier` of an arm and its mounting.

    Parameters
    ----------
    arm : Arm
        The arm.
    mounting : Mounting
        Container in the flange and path in the base.
    base : callable
        The verification it extends (default the nonlinear 3-D model).

    Returns
    -------
    RobotVerifier
        (problem, poses, tilted) -> Verification.

    Examples
    --------
    >>> from sloshkit.export.kinematics import load_arm
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> check = robot_verifier(load_arm("ur5e"), Mounting(), linear_verifier)
    >>> callable(check)
    True
    """
    return RobotVerifier(arm, mounting, base)


__all__ = ["RobotVerifier", "joint_speed_ratio", "robot_verifier"]
