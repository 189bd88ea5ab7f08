"""Joint paths: inverse kinematics of a sampled tip path, checked sample by sample.

Each sample's IK (ikpy, bounded least squares on the tip frame, with the analytic Jacobian of
its residual) starts from the previous sample's solution, extrapolated linearly from the two
before, so the arm stays on one branch; the first sample starts from the arm's home
configuration (and, if that misses, from `FIRST_SAMPLE_SEEDS` around it). The joint path is
then checked, in this order, and the first failure raises `InputError` naming the sample
(index and time) and the joint:

1. reach: the IK tip frame must match the target within `REACH_TOLERANCE_M` and
   `REACH_TOLERANCE_RAD` (a joint stuck on a position limit is named as the cause);
2. joint position limits (URDF ``lower``/``upper``);
3. continuity: no joint may move more than `MAX_JOINT_STEP_RAD` in one sample (a branch change);
4. singularity: the Jacobian's condition number must stay below `MAX_CONDITION_NUMBER`
   (the joint named is the one that dominates the lost direction);
5. joint velocity limits (URDF ``velocity``), on velocities from the samples.

Joint velocities and accelerations are the derivatives, at the samples, of the quintic spline
through the joint samples that is at rest at both ends (`joint_derivatives`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.frames import rotation_angle_rad
from sloshkit.export.kinematics import (
    MAX_CONDITION_NUMBER,
    MAX_JOINT_STEP_RAD,
    REACH_TOLERANCE_M,
    REACH_TOLERANCE_RAD,
    Arm,
)
from sloshkit.results import ResultMixin

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class JointPath(ResultMixin):
    """Joint samples of an arm on a uniform time grid.

    Attributes
    ----------
    time_s : sample times [s], uniform step `sample_period_s`
    position_rad, velocity_rad_s, acceleration_rad_s2 : (samples, joints) [rad, rad/s, rad/s^2]
    joint_names : the joints, base to tip
    max_condition_number : largest Jacobian condition number along the path [-]
    max_tip_error_m : largest distance between the IK tip and its target [m]

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(3) * 0.004
    >>> path = JointPath(t, np.zeros((3, 1)), np.zeros((3, 1)), np.zeros((3, 1)), ("j1",))
    >>> path.sample_period_s, sorted(path.columns())[:2]
    (0.004, ['j1_rad', 'j1_rad_s'])
    """

    time_s: FloatArray
    position_rad: FloatArray
    velocity_rad_s: FloatArray
    acceleration_rad_s2: FloatArray
    joint_names: tuple[str, ...]
    max_condition_number: float = float("nan")
    max_tip_error_m: float = float("nan")

    @property
    def sample_period_s(self) -> float:
        """The sample period [s]."""
        return float(self.time_s[1] - self.time_s[0]) if self.time_s.size > 1 else 0.0

    def columns(self) -> dict[str, FloatArray]:
        """Named columns: ``t_s``, then ``<joint>_rad``, ``<joint>_rad_s``, ``<joint>_rad_s2``."""
        data: dict[str, FloatArray] = {"t_s": self.time_s}
        for suffix, values in (
            ("rad", self.position_rad),
            ("rad_s", self.velocity_rad_s),
            ("rad_s2", self.acceleration_rad_s2),
        ):
            for index, name in enumerate(self.joint_names):
                data[f"{name}_{suffix}"] = values[:, index]
        return data

    def to_dict(self) -> dict[str, Any]:
        """Summary with unit-suffixed keys."""
        return {
            "joint_names": list(self.joint_names),
            "samples": int(self.time_s.size),
            "sample_period_s": self.sample_period_s,
            "peak_joint_velocity_rad_s": np.max(np.abs(self.velocity_rad_s), axis=0).tolist(),
            "peak_joint_acceleration_rad_s2": np.max(
                np.abs(self.acceleration_rad_s2), axis=0
            ).tolist(),
            "max_condition_number": self.max_condition_number,
            "max_tip_error_m": self.max_tip_error_m,
        }


def joint_derivatives(
    position_rad: FloatArray, sample_period_s: float
) -> tuple[FloatArray, FloatArray]:
    """Velocities and accelerations of rest-to-rest joint samples (samples on axis 0).

    The samples, at t_k = k Ts, are interpolated by a quintic spline with zero velocity and
    acceleration at both ends (the move starts and ends at rest, as every sloshkit plan does;
    the same interpolation as `sloshkit.motion.laws.from_samples`), and the spline's first and
    second derivatives are taken at the samples: exact for joint motions that are quintic
    polynomials, and at rest at both ends.

    Parameters
    ----------
    position_rad : (samples, joints) joint positions [rad]
    sample_period_s : sample period [s]

    Returns
    -------
    tuple of numpy.ndarray
        (velocity [rad/s], acceleration [rad/s^2]), shaped like the input.

    References
    ----------
    C. de Boor, *A Practical Guide to Splines*, Springer (2001), ch. XIII (spline
    interpolation with end derivatives); scipy ``make_interp_spline``.

    Examples
    --------
    >>> t = np.arange(11) * 0.1
    >>> s = t / t[-1]
    >>> velocity, acceleration = joint_derivatives((s**3 * (10 - 15 * s + 6 * s**2))[:, None], 0.1)
    >>> bool(np.allclose(velocity[:, 0], 30 * s**2 * (1 - s) ** 2, atol=1e-9))
    True
    """
    from scipy.interpolate import make_interp_spline

    if position_rad.shape[0] < 3:
        raise InputError("samples", position_rad.shape[0], "need at least 3 samples")
    time = np.arange(position_rad.shape[0], dtype=float) * sample_period_s
    rest = np.zeros(position_rad.shape[1:])
    spline = make_interp_spline(
        time, position_rad, k=5, bc_type=([(1, rest), (2, rest)], [(1, rest), (2, rest)])
    )
    velocity = np.asarray(spline(time, 1), dtype=float)
    acceleration = np.asarray(spline(time, 2), dtype=float)
    return velocity, acceleration


def solve_joint_path(
    arm: Arm,
    tip_frames: FloatArray,
    time_s: FloatArray,
    *,
    seed_rad: FloatArray | None = None,
    max_condition_number: float = MAX_CONDITION_NUMBER,
) -> JointPath:
    """Joint samples that put the arm's tip on ``tip_frames``, checked (see the module).

    Parameters
    ----------
    arm : the arm (`sloshkit.export.kinematics.load_arm`)
    tip_frames : (N, 4, 4) target tip frames in the arm's base frame
    time_s : (N,) uniform sample times [s]
    seed_rad : IK seed of the first sample (default ``arm.home_rad``)
    max_condition_number : singularity threshold on the Jacobian's condition number

    Returns
    -------
    JointPath

    References
    ----------
    ikpy ``Chain.inverse_kinematics_frame``; T. Yoshikawa, "Manipulability of robotic
    mechanisms", Int. J. Robotics Research 4(2) (1985) 3-9, doi:10.1177/027836498500400201
    (singular configurations, where the Jacobian loses rank).

    Examples
    --------
    >>> from sloshkit.export.kinematics import load_arm
    >>> arm = load_arm("ur5e")
    >>> q = arm.home_rad + np.linspace(0.0, 0.05, 4)[:, None]
    >>> path = solve_joint_path(arm, arm.forward(q), np.arange(4) * 0.04)
    >>> bool(np.allclose(path.position_rad, q, atol=1e-6))
    True
    """
    targets = np.asarray(tip_frames, dtype=float)
    times = np.asarray(time_s, dtype=float)
    count = targets.shape[0]
    if count < 3 or times.shape != (count,):
        raise InputError("samples", count, "need at least 3 tip frames, one per time")
    period = float(times[1] - times[0])
    if period <= 0.0 or not np.allclose(np.diff(times), period, rtol=1e-6, atol=1e-12):
        raise InputError("time", "non-uniform", "the samples must be uniform in time")
    previous = np.asarray(arm.home_rad if seed_rad is None else seed_rad, dtype=float)
    solution = np.empty((count, arm.dof))
    worst_error = 0.0
    for index in range(count):
        # Seed: the previous solution, extrapolated linearly once two are known; the first
        # sample also tries `FIRST_SAMPLE_SEEDS` starts around the seed if that one misses.
        guess = 2.0 * previous - solution[index - 2] if index >= 2 else previous
        if index == 0:  # the seed's configuration, its base turned towards the first pose
            guess = facing_seed(arm, targets[0], guess)
        guess = np.clip(guess, arm.lower_rad, arm.upper_rad)
        joints, distance, angle = _solve_and_measure(arm, targets[index], guess)
        if index == 0 and not _reached(distance, angle):
            joints, distance, angle = _solve_and_measure(arm, targets[index], previous)
        if index == 0 and not _reached(distance, angle):
            for seed in _first_sample_seeds(arm, guess):
                candidate = _solve_and_measure(arm, targets[index], seed)
                if _reached(candidate[1], candidate[2]):
                    joints, distance, angle = candidate
                    break
        if not _reached(distance, angle):
            raise _unreachable(arm, index, times[index], joints, distance, angle)
        worst_error = max(worst_error, distance)
        solution[index] = joints
        previous = joints
    _check_limits(arm, solution, times)
    _check_steps(arm, solution, times)
    worst_condition = _check_singularity(arm, solution, times, max_condition_number)
    velocity, acceleration = joint_derivatives(solution, period)
    _check_velocity(arm, velocity, times)
    return JointPath(
        time_s=times,
        position_rad=solution,
        velocity_rad_s=velocity,
        acceleration_rad_s2=acceleration,
        joint_names=arm.joint_names,
        max_condition_number=worst_condition,
        max_tip_error_m=worst_error,
    )


#: Extra IK starts tried for the first sample when the seed misses: the seed with each joint
#: in turn moved by +-pi/2 (clipped to its range), in a fixed order.
FIRST_SAMPLE_SEEDS = "each joint +-pi/2"


#: A seed whose tip is within this azimuth of the first pose is used as it is (a local solve
#: from it stays in its configuration); farther, its first joint is turned (`facing_seed`).
FACING_TOLERANCE_RAD = math.pi / 4


def facing_seed(arm: Arm, target: FloatArray, seed: FloatArray) -> FloatArray:
    """The seed with its first joint turned so that its tip faces the target's azimuth about
    the base z axis, when it is more than `FACING_TOLERANCE_RAD` away (the direction, + or -,
    that lands nearer): the seed's configuration (elbow up, wrist not flipped for the UR5e's
    default) carried to where the target is, so that a local IK from it stays in that
    configuration instead of reaching over the shoulder.

    Parameters
    ----------
    arm : Arm
        The arm.
    target : numpy.ndarray
        The first tip frame (4, 4) in the base frame.
    seed : numpy.ndarray
        The configured seed [rad].

    Returns
    -------
    numpy.ndarray
        The turned seed (clipped to the joint limits) [rad].

    Examples
    --------
    >>> from sloshkit.export.kinematics import load_arm
    >>> arm = load_arm("ur5e")
    >>> tip = arm.forward(arm.home_rad[None])[0]
    >>> behind = tip.copy()
    >>> behind[:2, 3] *= -1.0  # the same pose on the other side of the base
    >>> turned = facing_seed(arm, behind, arm.home_rad)
    >>> round(abs(math.degrees(turned[0] - arm.home_rad[0])), 1)
    180.0
    """

    def azimuth(frame: FloatArray) -> float:
        return math.atan2(float(frame[1, 3]), float(frame[0, 3]))

    aim = azimuth(target)
    turn = aim - azimuth(arm.forward(np.asarray(seed, dtype=float)[None])[0])
    turn = (turn + math.pi) % (2 * math.pi) - math.pi
    best, miss = np.asarray(seed, dtype=float), math.inf
    if abs(turn) <= FACING_TOLERANCE_RAD:
        return best
    for sign in (1.0, -1.0):
        moved = np.asarray(seed, dtype=float).copy()
        moved[0] += sign * turn
        moved = np.clip(moved, arm.lower_rad, arm.upper_rad)
        off = abs((azimuth(arm.forward(moved[None])[0]) - aim + math.pi) % (2 * math.pi) - math.pi)
        if off < miss:
            best, miss = moved, off
    return best


def _first_sample_seeds(arm: Arm, seed: FloatArray) -> list[FloatArray]:
    seeds = []
    for joint in range(arm.dof):
        for step in (math.pi / 2, -math.pi / 2):
            moved = seed.copy()
            moved[joint] += step
            seeds.append(np.clip(moved, arm.lower_rad, arm.upper_rad))
    return seeds


def _reached(distance: float, angle: float) -> bool:
    return distance <= REACH_TOLERANCE_M and angle <= REACH_TOLERANCE_RAD


def _solve_and_measure(
    arm: Arm, target: FloatArray, seed: FloatArray
) -> tuple[FloatArray, float, float]:
    """IK from ``seed``, and how far the solution's tip is from the target [m, rad]."""
    joints = _solve_one(arm, target, seed)
    reached = arm.forward(joints[None])[0]
    distance = float(np.linalg.norm(reached[:3, 3] - target[:3, 3]))
    return joints, distance, float(rotation_angle_rad(reached, target))


def _solve_one(arm: Arm, target: FloatArray, seed: FloatArray) -> FloatArray:
    full = np.zeros(len(arm.chain.links))
    active = np.asarray(arm.chain.active_links_mask, dtype=bool)
    full[active] = seed
    result = arm.chain.inverse_kinematics_frame(
        target,
        initial_position=full,
        orientation_mode="all",
        tol=1e-15,
        optimizer_kwargs={"jac": lambda x: _residual_jacobian(arm, x)},
    )
    solution: FloatArray = np.asarray(result, dtype=float)[active]
    return solution


def _residual_jacobian(arm: Arm, joints_rad: FloatArray) -> FloatArray:
    """Jacobian of ikpy's "all"-orientation residual [p - p*; vec(R - R*)] (12, dof): rows
    of the geometric Jacobian for p, and dR/dq_i = [a_i]x R for a revolute joint with world
    axis a_i (Siciliano et al. 2009, §3.1), replacing ikpy's finite differences."""
    jacobian, tip = arm.jacobian_and_tip(joints_rad)
    rotation = tip[:3, :3]
    rows = np.empty((12, jacobian.shape[1]))
    rows[:3] = jacobian[:3]
    for column in range(jacobian.shape[1]):
        wx, wy, wz = jacobian[3:, column]
        skew = np.array([[0.0, -wz, wy], [wz, 0.0, -wx], [-wy, wx, 0.0]])
        rows[3:, column] = (skew @ rotation).ravel()
    return rows


def _where(times: FloatArray, index: int) -> str:
    return f"sample {index} (t = {times[index]:.4f} s)"


def _unreachable(
    arm: Arm, index: int, time: float, joints: FloatArray, distance: float, angle: float
) -> InputError:
    margin = 1e-6
    stuck = [
        name
        for name, value, low, high in zip(
            arm.joint_names, joints, arm.lower_rad, arm.upper_rad, strict=True
        )
        if value <= low + margin or value >= high - margin
    ]
    cause = (
        "joint " + ", ".join(stuck) + " at its position limit"
        if stuck
        else "pose out of reach of the arm"
    )
    return InputError(
        "pose",
        f"sample {index} (t = {time:.4f} s)",
        f"{arm.name} cannot reach it: {cause}; closest tip misses by {1e3 * distance:.3g} mm "
        f"and {math.degrees(angle):.3g} deg",
        "move the path with --base-pose or change the mounting",
    )


def _check_limits(arm: Arm, position: FloatArray, times: FloatArray) -> None:
    tolerance = 1e-9
    below = position < arm.lower_rad - tolerance
    above = position > arm.upper_rad + tolerance
    bad = below | above
    if bad.any():
        index, joint = np.argwhere(bad)[0]
        raise InputError(
            arm.joint_names[joint],
            f"{position[index, joint]:.4f} rad at {_where(times, int(index))}",
            f"beyond its limits [{arm.lower_rad[joint]:.4f}, {arm.upper_rad[joint]:.4f}] rad",
        )


def _check_steps(arm: Arm, position: FloatArray, times: FloatArray) -> None:
    steps = np.abs(np.diff(position, axis=0))
    bad = steps > MAX_JOINT_STEP_RAD
    if bad.any():
        index, joint = np.argwhere(bad)[0]
        raise InputError(
            arm.joint_names[joint],
            f"a jump of {steps[index, joint]:.3f} rad at {_where(times, int(index) + 1)}",
            f"joint motion must be continuous (<= {MAX_JOINT_STEP_RAD} rad per sample); the IK "
            "changed branch, usually near a singularity or a limit",
        )


def _check_singularity(
    arm: Arm, position: FloatArray, times: FloatArray, max_condition: float
) -> float:
    worst = 0.0
    for index, joints in enumerate(position):
        jacobian = arm.jacobian(joints)
        _, singular, right = np.linalg.svd(jacobian)
        condition = math.inf if singular[-1] <= 0.0 else float(singular[0] / singular[-1])
        if condition > max_condition:
            joint = int(np.argmax(np.abs(right[-1])))
            raise InputError(
                arm.joint_names[joint],
                f"{_where(times, index)} (Jacobian condition number {condition:.3g})",
                f"the path passes a singularity (condition number must stay <= {max_condition:g})",
                "move the path with --base-pose or change the mounting",
            )
        worst = max(worst, condition)
    return worst


def _check_velocity(arm: Arm, velocity: FloatArray, times: FloatArray) -> None:
    ratio = np.abs(velocity) / arm.velocity_limit_rad_s
    if np.any(ratio > 1.0):
        index, joint = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
        raise InputError(
            arm.joint_names[joint],
            f"{velocity[index, joint]:.4g} rad/s at {_where(times, int(index))}",
            f"beyond its velocity limit {arm.velocity_limit_rad_s[joint]:.4g} rad/s",
            "slow the plan down or move the path away from singularities",
        )


def joint_limit_violations(arm: Arm, time_s: FloatArray, position_rad: FloatArray) -> list[str]:
    """The joint checks of `solve_joint_path` (position limits, jumps, velocity limits) on
    joint samples read back from a file, as sentences instead of errors (empty if all hold).

    Parameters
    ----------
    arm : the arm the samples are for
    time_s : uniform sample times [s]
    position_rad : (samples, joints) joint positions [rad]

    Returns
    -------
    list of str

    Examples
    --------
    >>> from sloshkit.export.kinematics import load_arm
    >>> arm = load_arm("ur5e")
    >>> q = arm.home_rad + np.outer(np.linspace(0.0, 1.0, 5), [0, 0, 0, 0, 0, 1.0])
    >>> joint_limit_violations(arm, np.arange(5) * 0.01, q)[0][:13]
    'wrist_3_joint'
    """
    times = np.asarray(time_s, dtype=float)
    position = np.asarray(position_rad, dtype=float)
    found = []
    for check in (_check_limits, _check_steps):
        try:
            check(arm, position, times)
        except InputError as error:
            found.append(str(error))
    try:
        velocity, _ = joint_derivatives(position, float(times[1] - times[0]))
        _check_velocity(arm, velocity, times)
    except InputError as error:
        found.append(str(error))
    return found
