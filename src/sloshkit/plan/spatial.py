"""3-D path planning: the problem, sampled pose exports, a fast linear screen and verification.

The planner's methods (`sloshkit.plan.retime`, `sloshkit.plan.tilt`) search with a fast linear
model of the lateral modes along the sampled export (`linear_screen`); nothing is called
feasible before the export has been simulated with the nonlinear 3-D model of
`sloshkit.sim.spatial` for every frequency of the robustness band
(`sloshkit.plan.path_result.verify`).

Linear screen (Abramson, NASA SP-106 (1966) ch. 6; Dodge (2000) ch. 3): each mode n is a
spherical pendulum of length L_n whose small deflection phi_n (2-vector, relative to the
container axis) obeys phi'' + 2 zeta w phi' + w^2 phi = f_lat / L_n, with f = g - a_B the
specific force at the container-fixed point B_n where the bob rests (its acceleration includes
the Euler and centripetal terms of the container's rotation), taken in the container's frame
with its spin about the own axis removed (an ideal liquid does not spin with the container).
A static tilt psi gives phi = sin(psi): the surface stays level. Wall height: |sum_n e_n phi_n|,
e_n = 2R/(xi_n^2 - 1) (the model's ``wall_elevation_factor_m``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sloshkit.errors import require_in_range, require_positive
from sloshkit.plan.path import Path

FloatArray = NDArray[np.float64]
GRAVITY = np.array([0.0, 0.0, -9.80665])
#: Relative margin the searches keep from each slosh limit (the export is verified exactly).
SEARCH_MARGIN = 0.03


@dataclass(frozen=True)
class CartesianLimits:
    """Limits of the container's reference point and rotation.

    Parameters
    ----------
    max_velocity_m_s : float
        Path speed [m/s].
    max_acceleration_m_s2 : float
        Acceleration, tangential and centripetal together [m/s^2].
    max_jerk_m_s3 : float
        Jerk [m/s^3].
    max_angular_velocity_rad_s : float, optional
        Angular speed of the container [rad/s] (None: no limit).
    max_angular_acceleration_rad_s2 : float, optional
        Angular acceleration of the container [rad/s^2] (None: no limit).

    Examples
    --------
    >>> CartesianLimits(2.0, 10.0, 100.0, max_angular_velocity_rad_s=3.14).max_jerk_m_s3
    100.0
    """

    max_velocity_m_s: float
    max_acceleration_m_s2: float
    max_jerk_m_s3: float
    max_angular_velocity_rad_s: float | None = None
    max_angular_acceleration_rad_s2: float | None = None

    def __post_init__(self) -> None:
        require_positive("vmax", self.max_velocity_m_s, "m/s")
        require_positive("amax", self.max_acceleration_m_s2, "m/s^2")
        require_positive("jmax", self.max_jerk_m_s3, "m/s^3")
        for name in ("max_angular_velocity_rad_s", "max_angular_acceleration_rad_s2"):
            if getattr(self, name) is not None:
                require_positive(name, getattr(self, name))


@dataclass(frozen=True)
class SpatialSloshLimits:
    """Slosh limits of a 3-D move.

    Parameters
    ----------
    max_height_m : float
        Peak slosh height during the move [m].
    max_residual_height_m : float
        Residual slosh height after it [m].
    max_surface_angle_rad : float, optional
        Peak first-mode surface angle [rad].
    robustness : float
        Relative frequency band over which the limits must hold (0.1 for +-10 %).

    Examples
    --------
    >>> SpatialSloshLimits(0.015, 0.002, robustness=0.1).robustness
    0.1
    """

    max_height_m: float
    max_residual_height_m: float
    max_surface_angle_rad: float | None = None
    robustness: float = 0.0

    def __post_init__(self) -> None:
        require_positive("max_slosh_height", self.max_height_m, "m")
        require_positive("max_residual_height", self.max_residual_height_m, "m")
        if self.max_surface_angle_rad is not None:
            require_positive("max_surface_angle", self.max_surface_angle_rad, "rad")
        require_in_range("robust", self.robustness, 0.0, 0.5)


@dataclass(frozen=True, eq=False)
class PathProblem:
    """A path, its limits, the container model and the controller's sample period.

    Parameters
    ----------
    path : Path
        The geometry (`sloshkit.plan.path`).
    machine : CartesianLimits
        Cartesian and angular limits.
    slosh : SpatialSloshLimits
        Slosh limits.
    model : SloshModel
        The container model (any object with ``modes`` and ``radius_m``).
    sample_period_s : float
        Controller sample period of the export [s].
    max_tilt_rad : float
        Largest tilt from vertical the ``tilt`` method may use [rad].
    tilt_centre_height_m : float
        Height of the tilt's rotation centre above the container bottom, on its axis [m].
    max_path_deviation_m : float
        Largest distance from the path the ``shaped`` method may leave [m] (per-axis shaping
        cuts corners).

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> problem.sample_period_s, round(problem.path.length_m, 3)
    (0.004, 0.3)
    """

    path: Path
    machine: CartesianLimits
    slosh: SpatialSloshLimits
    model: Any
    sample_period_s: float = 4e-3
    max_tilt_rad: float = math.radians(30.0)
    tilt_centre_height_m: float = 0.0
    max_path_deviation_m: float = 5e-3

    def __post_init__(self) -> None:
        require_in_range("sample_period", self.sample_period_s, 1e-4, 0.05, "s")
        require_in_range("max_tilt", self.max_tilt_rad, 0.0, math.radians(80.0), "rad")

    def models(self) -> list[Any]:
        """The model at the band's low edge, nominal and high edge (all modes scaled)."""
        band = self.slosh.robustness
        if band == 0.0:
            return [self.model]
        return [_scaled(self.model, factor) for factor in (1.0 - band, 1.0, 1.0 + band)]


def _scaled(model: Any, factor: float) -> Any:
    modes = tuple(replace(mode, omega_rad_s=mode.omega_rad_s * factor) for mode in model.modes)
    return replace(model, modes=modes)


@dataclass(frozen=True, eq=False)
class PoseSamples:
    """A sampled pose trajectory on a uniform grid, at rest at both ends.

    Parameters
    ----------
    time_s : ndarray
        Sample times [s] from 0, uniform.
    position_m : ndarray, shape (n, 3)
        Reference-point (container bottom centre) positions, world frame [m].
    quaternion_xyzw : ndarray, shape (n, 4)
        Container-to-world unit quaternions, scalar last.

    Examples
    --------
    >>> t = np.arange(3) * 0.1
    >>> poses = PoseSamples(t, np.zeros((3, 3)), np.tile([0.0, 0.0, 0.0, 1.0], (3, 1)))
    >>> poses.duration_s, sorted(poses.columns())[:3]
    (0.2, ['qw', 'qx', 'qy'])
    """

    time_s: FloatArray
    position_m: FloatArray
    quaternion_xyzw: FloatArray

    @property
    def duration_s(self) -> float:
        """Time of the last sample [s]."""
        return float(self.time_s[-1])

    @property
    def rotation(self) -> Rotation:
        """Container-to-world rotations."""
        return Rotation.from_quat(self.quaternion_xyzw)

    def columns(self) -> dict[str, FloatArray]:
        """``t,x,y,z,qx,qy,qz,qw`` columns (the pose-file format)."""
        names = ("x", "y", "z")
        quaternions = ("qx", "qy", "qz", "qw")
        return {
            "t": self.time_s,
            **{n: self.position_m[:, i] for i, n in enumerate(names)},
            **{n: self.quaternion_xyzw[:, i] for i, n in enumerate(quaternions)},
        }

    def to_pose_trajectory(self, name: str = "plan") -> Any:
        """The same samples as a `sloshkit.motion.poses.PoseTrajectory`."""
        from sloshkit.motion.poses import PoseTrajectory

        return PoseTrajectory(self.time_s, self.position_m, self.quaternion_xyzw, name=name)


def sample_path(path: Path, timing: Any, sample_period_s: float) -> PoseSamples:
    """Sample ``path`` along the timing s(t) at t = k Ts until the first sample at or after the
    end; quaternions sign-continuous.

    Parameters
    ----------
    path : Path
        The geometry.
    timing : Timing or Motion
        Anything with ``duration_s`` and ``position(t)`` giving s [m].
    sample_period_s : float
        Ts [s].

    Returns
    -------
    PoseSamples
        The export, ending exactly on the path's last pose.

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> from sloshkit.motion.laws import s_curve
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> poses = sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> poses.position_m[-1].tolist()
    [0.5, 0.0, 0.0]
    """
    count = math.ceil(timing.duration_s / sample_period_s - 1e-9)
    t = np.arange(count + 1, dtype=float) * sample_period_s
    s = np.clip(timing.position(np.minimum(t, timing.duration_s)), 0.0, path.length_m)
    s[-1] = path.length_m
    quaternions = path.orientation(s).as_quat()
    return PoseSamples(t, path.position(s), _continuous(quaternions))


def _continuous(quaternions: FloatArray) -> FloatArray:
    flips = np.sign(np.sum(quaternions[1:] * quaternions[:-1], axis=1))
    flips[flips == 0] = 1.0
    signs = np.concatenate(([1.0], np.cumprod(flips)))
    return np.asarray(quaternions * signs[:, None])


def _qmul(a: FloatArray, b: FloatArray) -> FloatArray:
    """Hamilton product of quaternion arrays (scalar last), the rotation a * b."""
    ax, ay, az, aw = np.moveaxis(a, -1, 0)
    bx, by, bz, bw = np.moveaxis(b, -1, 0)
    return np.stack(
        (
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ),
        axis=-1,
    )


def _qconj(q: FloatArray) -> FloatArray:
    """Inverse of unit quaternions (scalar last)."""
    return np.asarray(q * np.array([-1.0, -1.0, -1.0, 1.0]))


def _qrotvec(q: FloatArray) -> FloatArray:
    """Rotation vectors of unit quaternions (scalar last), angle in [0, pi]."""
    q = np.where(q[..., 3:4] < 0.0, -q, q)
    sine = np.linalg.norm(q[..., :3], axis=-1)
    angle = 2.0 * np.arctan2(sine, q[..., 3])
    # angle / sin(angle / 2), -> 2 for small angles (series 2 + angle^2 / 12)
    scale = np.where(sine > 1e-6, angle / np.maximum(sine, 1e-300), 2.0 + angle**2 / 12.0)
    return np.asarray(q[..., :3] * scale[..., None])


def _qaxis(q: FloatArray) -> FloatArray:
    """The rotated z axis R e_z of unit quaternions (scalar last)."""
    x, y, z, w = np.moveaxis(q, -1, 0)
    return np.stack((2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)), axis=-1)


def _qapply_inverse(q: FloatArray, v: FloatArray) -> FloatArray:
    """R^T v for unit quaternions q and vectors v (rows)."""
    u = -q[..., :3]
    w = q[..., 3:4]
    t = 2.0 * np.cross(u, v)
    return np.asarray(v + w * t + np.cross(u, t))


def _second_difference(values: FloatArray, step: float) -> FloatArray:
    """Central second difference along axis 0, the ends held at rest."""
    padded = np.concatenate((values[:1], values, values[-1:]))
    return np.asarray((padded[2:] - 2 * padded[1:-1] + padded[:-2]) / step**2)


@dataclass(frozen=True)
class ScreenResult:
    """Linear-screen metrics, the worst over the band.

    Parameters
    ----------
    peak_height_m : float
        Peak slosh height at the wall [m].
    residual_height_m : float
        Bound of the residual slosh height [m].
    peak_angle_rad : float
        Peak first-mode surface angle [rad].

    Examples
    --------
    >>> ScreenResult(0.01, 0.001, 0.05).residual_height_m
    0.001
    """

    peak_height_m: float
    residual_height_m: float
    peak_angle_rad: float


def linear_screen(models: list[Any], poses: PoseSamples) -> ScreenResult:
    """Slosh of the sampled ``poses`` by the linear spherical-pendulum model (module docstring).

    The liquid starts in equilibrium with the first pose; the residual height is the bound
    sum_n e_n sqrt(|A_n|^2 + |B_n|^2) of the free oscillation about the last pose's equilibrium
    (A_n, B_n: the cosine and sine amplitude vectors of mode n).

    Parameters
    ----------
    models : list of SloshModel
        The models of the band (`PathProblem.models`).
    poses : PoseSamples
        The export.

    Returns
    -------
    ScreenResult
        The worst over the models.

    References
    ----------
    Abramson, NASA SP-106 (1966) ch. 6; Dodge, *The New "Dynamic Behavior of Liquids in
    Moving Containers"*, SwRI (2000) ch. 3.

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> from sloshkit.motion.laws import s_curve
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> poses = sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> round(linear_screen([model], poses).peak_height_m * 1e3)  # [mm]
    24
    """
    from sloshkit.sim.discretisation import linear_mode_response

    ts = float(poses.time_s[1] - poses.time_s[0])
    quaternion = poses.quaternion_xyzw
    spin_rate = _qrotvec(_qmul(_qconj(quaternion[:-1]), quaternion[1:]))[:, 2]
    spin = np.concatenate(([0.0], np.cumsum(spin_rate)))
    unspin = np.zeros((spin.size, 4))
    unspin[:, 2], unspin[:, 3] = np.sin(-0.5 * spin), np.cos(-0.5 * spin)
    frame = _qmul(quaternion, unspin)
    axis = _qaxis(quaternion)
    peak = residual = angle = 0.0
    for model in models:
        wall = np.zeros((poses.time_s.size, 2))
        bound = 0.0
        for index, mode in enumerate(model.modes):
            point = poses.position_m + mode.bob_height_m * axis
            force = _qapply_inverse(frame, GRAVITY - _second_difference(point, ts))[:, :2]
            rest = force / (mode.length_m * mode.omega_rad_s**2)
            # Equivalent velocity w with w' = -(f - f_0): linear_mode_response solves
            # theta'' + 2 zeta w theta' + w^2 theta = -w'/L.
            excess = force - force[0]
            equivalent = -np.concatenate(
                (np.zeros((1, 2)), np.cumsum(0.5 * (excess[1:] + excess[:-1]) * ts, axis=0))
            )
            theta, rate = linear_mode_response(
                equivalent.T, ts, mode.omega_rad_s, mode.damping_ratio, mode.length_m
            )
            phi = theta.T + rest[0]
            wall += mode.wall_elevation_factor_m * phi
            if index == 0:
                angle = max(angle, float(np.max(np.linalg.norm(phi, axis=1))))
            damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
            cosine = phi[-1] - rest[-1]
            sine = (rate.T[-1] + mode.damping_ratio * mode.omega_rad_s * cosine) / damped
            bound += mode.wall_elevation_factor_m * math.sqrt(cosine @ cosine + sine @ sine)
        peak = max(peak, float(np.max(np.linalg.norm(wall, axis=1))))
        residual = max(residual, bound)
    return ScreenResult(peak, residual, angle)


def screen_ok(problem: PathProblem, result: ScreenResult, margin: float = SEARCH_MARGIN) -> bool:
    """True when the screen meets every slosh limit with the relative ``margin``.

    Parameters
    ----------
    problem : PathProblem
        The limits.
    result : ScreenResult
        The screen of an export.
    margin : float
        Relative margin kept from each limit.

    Returns
    -------
    bool

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> [screen_ok(problem, ScreenResult(peak, 0.001, 0.0)) for peak in (0.0099, 0.009)]
    [False, True]
    """
    slosh = problem.slosh
    keep = 1.0 - margin
    ok = result.peak_height_m <= slosh.max_height_m * keep
    ok &= result.residual_height_m <= slosh.max_residual_height_m * keep
    if slosh.max_surface_angle_rad is not None:
        ok &= result.peak_angle_rad <= slosh.max_surface_angle_rad * keep
    return bool(ok)


def kinematics(poses: PoseSamples) -> dict[str, float]:
    """Peaks of the sampled export by finite differences (the ends held at rest).

    Parameters
    ----------
    poses : PoseSamples
        The export.

    Returns
    -------
    dict
        ``velocity`` [m/s], ``acceleration`` [m/s^2], ``jerk`` [m/s^3], ``angular_velocity``
        [rad/s], ``angular_acceleration`` [rad/s^2], ``tilt`` (from vertical) [rad].

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> from sloshkit.motion.laws import s_curve
    >>> poses = sample_path(path_from_waypoints([[0, 0, 0], [0.5, 0, 0]]),
    ...                     s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> round(kinematics(poses)["acceleration"], 1), kinematics(poses)["tilt"]
    (2.0, 0.0)
    """
    ts = float(poses.time_s[1] - poses.time_s[0])
    rest = np.concatenate(
        (poses.position_m[:1],) * 2 + (poses.position_m,) + (poses.position_m[-1:],) * 2
    )
    velocity = np.diff(rest, axis=0) / ts
    acceleration = np.diff(velocity, axis=0) / ts
    jerk = np.diff(acceleration, axis=0) / ts
    quaternion = poses.quaternion_xyzw
    omega = _qrotvec(_qmul(quaternion[1:], _qconj(quaternion[:-1]))) / ts
    omega = np.concatenate((np.zeros((1, 3)), omega, np.zeros((1, 3))))
    alpha = np.diff(omega, axis=0) / ts
    axis = _qaxis(quaternion)
    return {
        "velocity": float(np.max(np.linalg.norm(velocity, axis=1))),
        "acceleration": float(np.max(np.linalg.norm(acceleration, axis=1))),
        "jerk": float(np.max(np.linalg.norm(jerk, axis=1))),
        "angular_velocity": float(np.max(np.linalg.norm(omega, axis=1))),
        "angular_acceleration": float(np.max(np.linalg.norm(alpha, axis=1))),
        "tilt": float(np.max(np.arccos(np.clip(axis[:, 2], -1.0, 1.0)))),
    }


def machine_violations(problem: PathProblem, poses: PoseSamples, tilted: bool) -> list[str]:
    """Names and values of the Cartesian, angular and tilt limits the export breaks.

    Parameters
    ----------
    problem : PathProblem
        The limits.
    poses : PoseSamples
        The export.
    tilted : bool
        Whether the tilt limit applies.

    Returns
    -------
    list of str
        One sentence per limit broken (empty when all hold).

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> from sloshkit.motion.laws import s_curve
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(2.0, 1.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), None)
    >>> machine_violations(problem, sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3), False)
    ['acceleration 2 > 1 m/s^2']
    """
    peaks = kinematics(poses)
    machine = problem.machine
    checks = [
        ("velocity", peaks["velocity"], machine.max_velocity_m_s, "m/s"),
        ("acceleration", peaks["acceleration"], machine.max_acceleration_m_s2, "m/s^2"),
        ("jerk", peaks["jerk"], machine.max_jerk_m_s3, "m/s^3"),
    ]
    if machine.max_angular_velocity_rad_s is not None:
        checks.append(
            (
                "angular velocity",
                peaks["angular_velocity"],
                machine.max_angular_velocity_rad_s,
                "rad/s",
            )
        )
    if machine.max_angular_acceleration_rad_s2 is not None:
        checks.append(
            (
                "angular acceleration",
                peaks["angular_acceleration"],
                machine.max_angular_acceleration_rad_s2,
                "rad/s^2",
            )
        )
    if tilted:
        checks.append(("tilt", peaks["tilt"], problem.max_tilt_rad, "rad"))
    return [
        f"{name} {value:.4g} > {limit:.4g} {unit}"
        for name, value, limit, unit in checks
        if value > limit * (1.0 + 1e-6)
    ]


def machine_stretch(problem: PathProblem, poses: PoseSamples) -> float:
    """Smallest uniform stretch in time c >= 1 after which the export meets the Cartesian and
    angular limits (speeds scale as 1/c, accelerations 1/c^2, jerks 1/c^3).

    Parameters
    ----------
    problem : PathProblem
        The limits.
    poses : PoseSamples
        The export.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> from sloshkit.motion.laws import s_curve
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(0.5, 10.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), None)
    >>> poses = sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> speed = kinematics(poses)["velocity"]  # 0.9 m/s against 0.5 m/s
    >>> bool(np.isclose(machine_stretch(problem, poses), speed / 0.5))
    True
    """
    peaks = kinematics(poses)
    machine = problem.machine
    needs = [
        peaks["velocity"] / machine.max_velocity_m_s,
        math.sqrt(peaks["acceleration"] / machine.max_acceleration_m_s2),
        (peaks["jerk"] / machine.max_jerk_m_s3) ** (1.0 / 3.0),
    ]
    if machine.max_angular_velocity_rad_s is not None:
        needs.append(peaks["angular_velocity"] / machine.max_angular_velocity_rad_s)
    if machine.max_angular_acceleration_rad_s2 is not None:
        needs.append(
            math.sqrt(peaks["angular_acceleration"] / machine.max_angular_acceleration_rad_s2)
        )
    return float(max(1.0, *needs))


def path_deviation(path: Path, poses: PoseSamples) -> float:
    """Largest distance [m] of the exported positions from the path (`Path.distance_to`).

    Parameters
    ----------
    path : Path
        The geometry.
    poses : PoseSamples
        The export.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> poses = PoseSamples(np.arange(2) * 0.1, np.array([[0.1, 0.002, 0], [0.3, 0, 0]]),
    ...                     np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)))
    >>> round(path_deviation(path, poses), 6)
    0.002
    """
    return float(np.max(path.distance_to(poses.position_m)))
