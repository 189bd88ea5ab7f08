"""An arm's joints along a 3-D path, for the path program's joint-speed limits.

The export's IK (`sloshkit.plan.path.result.JointSpeedCheck.joint_positions`, which
``sloshkit export`` uses too) is solved once along the untilted path, every `JOINT_GRID_M` of
the path parameter, and q(s) is the cubic spline through it (`JointMap`): the programs of
`sloshkit.plan.path.cone` then limit (q(s_k+1) - q(s_k)) / h for every joint. When the
programs tilt the container, the IK is also solved along the path tilted by +-`TILT_PROBE_RAD`
about each horizontal axis and by `TILT_PROBE_RAD` about both (the tilt convention of
`sloshkit.plan.path.samples.sample_poses`), and the joints become the quadratic model
q(s) + G(s) r + r^T H(s) r / 2 in the tilt r = (r_x, r_y), G and H the central and mixed
differences of those solutions (Nocedal & Wright, *Numerical Optimization*, 2nd ed. (2006)
§8.1; `JointMap.at`). On the example arm it predicts the IK of a 17 deg tilt to 0.004 rad,
where the first-order model errs by 0.05 rad; the export's IK verifies every plan.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
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
    tilt_gradient : numpy.ndarray, optional
        G = dq/dr at the IK samples (M, dof, 2) [rad/rad] for the tilt r = (r_x, r_y) about the
        tilt centre; None when the programs do not tilt.
    tilt_hessian : numpy.ndarray, optional
        H = d2q/dr2 there (M, dof, 2, 2) [rad/rad^2]; None when the programs do not tilt.

    Examples
    --------
    >>> import numpy as np
    >>> s = np.linspace(0.0, 0.1, 11)
    >>> joints = JointMap(s, np.column_stack((10 * s, -5 * s)), np.array([3.14, 3.14]))
    >>> joints.joints_rad.shape
    (11, 2)
    """

    s_m: FloatArray
    joints_rad: FloatArray
    limits_rad_s: FloatArray
    tilt_gradient: FloatArray | None = None
    tilt_hessian: FloatArray | None = None

    def model(self) -> Any:
        """The joints as a function of the path parameter and the tilt (`JointModel`).

        Returns
        -------
        JointModel

        Examples
        --------
        >>> import numpy as np
        >>> s = np.linspace(0.0, 0.1, 11)
        >>> gradient = np.broadcast_to([[1.0, 0.0], [0.0, -1.0]], (11, 2, 2))
        >>> hessian = np.broadcast_to(np.eye(2), (11, 2, 2, 2))
        >>> joints = JointMap(s, np.column_stack((s, s)), np.ones(2), gradient, hessian)
        >>> q, dq_ds, dq_dr = joints.model().at(np.array([0.05]), np.array([[0.1, 0.2]]))
        >>> q.round(6).tolist(), dq_ds.round(6).tolist(), dq_dr.round(6).tolist()
        ([[0.175, -0.125]], [[1.0, 1.0]], [[[1.1, 0.2], [0.1, -0.8]]])
        """
        return JointModel(self)

    def scaled(self, fraction: float) -> JointMap:
        """The same joints with their speed limits times ``fraction``.

        Parameters
        ----------
        fraction : float
            The fraction of the speed limits the programs impose.

        Returns
        -------
        JointMap

        Examples
        --------
        >>> import numpy as np
        >>> joints = JointMap(np.array([0.0, 0.1]), np.zeros((2, 1)), np.array([3.0]))
        >>> joints.scaled(0.9).limits_rad_s.tolist()
        [2.7]
        """
        return replace(self, limits_rad_s=fraction * self.limits_rad_s)


class JointModel:
    """q(s, r) = q(s) + G(s) r + r^T H(s) r / 2 from a `JointMap` (module docstring), by cubic
    splines of its samples in s; without tilt data, q(s).

    Parameters
    ----------
    joints : JointMap
        The IK samples.

    Examples
    --------
    >>> import numpy as np
    >>> s = np.linspace(0.0, 0.1, 11)
    >>> model = JointModel(JointMap(s, np.column_stack((10 * s, -5 * s)), np.ones(2)))
    >>> model.tilts
    False
    >>> model.at(np.array([0.05]), np.zeros((1, 2)))[1].round(6).tolist()  # dq/ds
    [[10.0, -5.0]]
    """

    def __init__(self, joints: JointMap) -> None:
        from scipy.interpolate import CubicSpline

        self.joints = joints
        self._q = CubicSpline(joints.s_m, joints.joints_rad, axis=0)
        self.tilts = joints.tilt_gradient is not None and joints.tilt_hessian is not None
        if self.tilts:
            self._g = CubicSpline(joints.s_m, joints.tilt_gradient, axis=0)
            self._h = CubicSpline(joints.s_m, joints.tilt_hessian, axis=0)

    def at(self, s_m: FloatArray, tilt_rad: FloatArray) -> tuple[FloatArray, ...]:
        """The joints, their derivative in s and their derivative in the tilt.

        Parameters
        ----------
        s_m : numpy.ndarray
            Path parameter (N,) [m].
        tilt_rad : numpy.ndarray
            Tilt (r_x, r_y) there (N, 2) [rad]; ignored without tilt data.

        Returns
        -------
        tuple of numpy.ndarray
            q (N, dof) [rad], dq/ds (N, dof) [rad/m] and dq/dr (N, dof, 2) [rad/rad] (zero
            without tilt data).
        """
        q, dq_ds = self._q(s_m), self._q(s_m, 1)
        dof = q.shape[1]
        if not self.tilts:
            return q, dq_ds, np.zeros((s_m.size, dof, 2))
        r = np.asarray(tilt_rad, dtype=float)
        g, h = self._g(s_m), self._h(s_m)
        g_s, h_s = self._g(s_m, 1), self._h(s_m, 1)
        h_r = np.einsum("kjab,kb->kja", h, r)
        q = q + np.einsum("kja,ka->kj", g + 0.5 * h_r, r)
        dq_ds = dq_ds + np.einsum("kja,ka->kj", g_s + 0.5 * np.einsum("kjab,kb->kja", h_s, r), r)
        return q, dq_ds, g + h_r


#: Spacing of the path parameter at which the arm's IK is solved for the programs [m].
JOINT_GRID_M = 0.005

#: Tilt of the IK probes whose differences give dq/dr and d2q/dr2 [rad] (11.5 deg, within
#: the range a tilt compensation uses; on the example arm 0.1 and 0.3 rad predicted a
#: 17-20 deg tilt as well).
TILT_PROBE_RAD = 0.2


def joint_map(problem: Any, check: Any, tilt: bool = False) -> JointMap | str:
    """The arm's joints along the path every `JOINT_GRID_M` (at least 50 points), and with
    ``tilt`` their first-order change with the tilt (module docstring).

    Parameters
    ----------
    problem : PathProblem
        The path.
    check : JointSpeedCheck
        The verifier that solves the arm (`sloshkit.plan.path.result.JointSpeedCheck`).
    tilt : bool
        Also solve the path tilted by +-`TILT_PROBE_RAD` about x and y and by it about both
        (about ``problem.tilt_centre_height_m``) for `JointMap.tilt_gradient` and
        `JointMap.tilt_hessian`.

    Returns
    -------
    JointMap or str
        The joints q(s), or the IK's message when it fails on the untilted path: its poses
        are the path's whatever the timing, so no plan can pass. When only a tilted probe
        fails, the map has no tilt data (the programs then plan upright).

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

    The quadratic model predicts the IK of the path tilted by 0.3 rad about x and -0.3 rad
    about y (24 deg), which moves a joint by 0.38 rad, to within 0.01 rad:

    >>> from sloshkit.plan.path.samples import PathSamples, sample_poses
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> mounting = Mounting(base_xyz_m=(-0.45, -0.13, 0.3))
    >>> tilted_map = joint_map(problem, RobotVerifier(arm, mounting), tilt=True)
    >>> tilt = np.tile([0.3, -0.3], (50, 1))
    >>> position, rotation = sample_poses(
    ...     problem.path, PathSamples(tilted_map.s_m, tilt, 1e-3), problem.tilt_centre_height_m)
    >>> solved = RobotVerifier(arm, mounting).joint_positions(
    ...     PoseTrajectory(np.arange(50) * 1e-3, position, rotation.as_quat()))
    >>> predicted = tilted_map.model().at(tilted_map.s_m, tilt)[0]
    >>> float(np.max(np.abs(solved - tilted_map.joints_rad))) > 0.3
    True
    >>> bool(np.max(np.abs(predicted - solved)) < 0.01)
    True
    """
    from sloshkit.errors import InputError
    from sloshkit.motion.poses import PoseTrajectory
    from sloshkit.plan.path.samples import PathSamples, sample_poses

    length = problem.path.length_m
    count = max(50, math.ceil(length / JOINT_GRID_M) + 1)
    s = np.linspace(0.0, length, count)

    def solved(tilt_rad: FloatArray) -> FloatArray:
        samples = PathSamples(s, np.broadcast_to(tilt_rad, (count, 2)), 1e-3)
        position, rotation = sample_poses(problem.path, samples, problem.tilt_centre_height_m)
        poses = PoseTrajectory(np.arange(count) * 1e-3, position, rotation.as_quat())
        return np.asarray(check.joint_positions(poses), dtype=float)

    try:
        joints = solved(np.zeros(2))
    except InputError as error:
        return f"robot: {error}"
    limits = np.asarray(check.joint_speed_limits_rad_s, dtype=float)
    if not tilt:
        return JointMap(s, joints, limits)
    d = TILT_PROBE_RAD
    try:
        plus = [solved(d * axis) for axis in np.eye(2)]
        minus = [solved(-d * axis) for axis in np.eye(2)]
        both = solved(np.array([d, d]))
    except InputError:
        return JointMap(s, joints, limits)
    gradient = np.stack([(p - m) / (2.0 * d) for p, m in zip(plus, minus, strict=True)], -1)
    curvature = [(p - 2.0 * joints + m) / d**2 for p, m in zip(plus, minus, strict=True)]
    # q(d, d) - q(0) = d (G_x + G_y) + d^2 (H_xx + H_yy) / 2 + d^2 H_xy
    mixed = (
        both - joints - d * gradient.sum(-1) - 0.5 * d**2 * (curvature[0] + curvature[1])
    ) / d**2
    hessian = np.stack(
        (np.stack((curvature[0], mixed), -1), np.stack((mixed, curvature[1]), -1)), -2
    )
    return JointMap(s, joints, limits, gradient, hessian)


def joint_excess(check: Any) -> float:
    """The largest joint speed over its limit in a verification with an arm's joint check
    (`sloshkit.export.path_robot.RobotVerifier`: its ``required_stretch``) when it breaks a
    joint speed limit, else 1.

    Parameters
    ----------
    check : Verification
        A verification.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.plan.path.result import Verification
    >>> over = ("joint speed wrist_3_joint 3.28 > 3.14 rad/s",)
    >>> joint_excess(Verification(0.014, 0.002, 0.0, 0.0, over, required_stretch=1.043))
    1.043
    >>> joint_excess(Verification(0.016, 0.002, 0.0, 0.0, ("peak slosh",), required_stretch=1.1))
    1.0
    """
    broken = any(violation.startswith("joint speed") for violation in check.violations)
    return float(check.required_stretch) if broken else 1.0


__all__ = ["JOINT_GRID_M", "TILT_PROBE_RAD", "JointMap", "JointModel", "joint_excess", "joint_map"]
