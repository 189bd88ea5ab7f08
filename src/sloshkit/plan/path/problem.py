"""3-D path planning: the problem (path, limits, model) and its sampled pose export.

The export of every method is a `sloshkit.motion.poses.PoseTrajectory` on the controller's
grid t = k Ts (`sample_path`), at rest at both ends.

The planner's methods (`sloshkit.plan.path.retime`, `sloshkit.plan.path.tilt_compensation`)
search with a fast linear model of the lateral modes along the sampled export
(`sloshkit.plan.path.screen`) and check
the kinematic limits (`sloshkit.plan.path.limits`); nothing is called feasible before the
export has been simulated with the nonlinear 3-D model of `sloshkit.sim.spatial` for every
frequency of the robustness band (`sloshkit.plan.path.result.verify`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import require_in_range, require_positive
from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.sampling import steps_to_reach
from sloshkit.plan.path.geometry import Path, generalised_arc_length
from sloshkit.plan.path.timing import Timing

FloatArray = NDArray[np.float64]
#: Gravity in the world frame (z up) [m/s^2], from the model's constant.
GRAVITY = np.array([0.0, 0.0, -GRAVITY_M_S2])
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
        The geometry (`sloshkit.plan.path.geometry`).
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
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
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


def sample_path(path: Path, timing: Any, sample_period_s: float) -> PoseTrajectory:
    """Sample ``path`` along the timing s(t) at t = k Ts until the first sample at or after the
    end; quaternions sign-continuous (`sloshkit.motion.poses.PoseTrajectory` makes them so).

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
    PoseTrajectory
        The export, ending exactly on the path's last pose.

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.motion.laws import s_curve
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> poses = sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> poses.position_m[-1].tolist()
    [0.5, 0.0, 0.0]
    """
    count = steps_to_reach(timing.duration_s, sample_period_s)
    t = np.arange(count + 1, dtype=float) * sample_period_s
    s = np.clip(timing.position(np.minimum(t, timing.duration_s)), 0.0, path.length_m)
    s[-1] = path.length_m
    quaternions = path.orientation(s).as_quat()
    return PoseTrajectory(t, path.position(s), quaternions)


def reference_timing(poses: PoseTrajectory, path: Path) -> Timing:
    """The poses' own timing s(t) along ``path`` (made from them, `path_from_poses`), from
    their first moving sample on (the rest before it dropped).

    s is the generalised arc length of the poses
    (`sloshkit.plan.path.geometry.generalised_arc_length`), scaled to the path's length;
    samples where it does not grow are dropped, so the timing is
    strictly increasing.

    Parameters
    ----------
    poses : PoseTrajectory
        The poses (e.g. of a pose file).
    path : Path
        The path through them.

    Returns
    -------
    Timing
        s(t) from t = 0 at the last rest sample before the motion.

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_poses
    >>> t = np.arange(6) * 0.1
    >>> x = np.array([0.0, 0.0, 0.1, 0.2, 0.3, 0.3])
    >>> poses = PoseTrajectory(t, np.c_[x, 0 * t, 0 * t], np.tile([0, 0, 0, 1.0], (6, 1)))
    >>> timing = reference_timing(poses, path_from_poses(poses.position_m, poses.quaternion_xyzw))
    >>> round(timing.duration_s, 3), round(float(timing.position(timing.duration_s)), 3)
    (0.3, 0.3)
    """
    rotation = poses.rotation
    s = generalised_arc_length(poses.position_m, rotation)
    start = max(int(np.argmax(s > 1e-9)) - 1, 0)
    moving = np.concatenate(([True], np.diff(s[start:]) > 0.0))
    t = (poses.time_s[start:] - poses.time_s[start])[moving]
    return Timing.from_samples("pose file", t, s[start:][moving] / s[-1] * path.length_m)


def second_difference(values: FloatArray, step: float) -> FloatArray:
    """Central second difference along axis 0 with the ends held at rest (the first and last
    rows repeated), as the export's acceleration is measured (`sloshkit.plan.path.limits`).

    Parameters
    ----------
    values : numpy.ndarray
        Samples (N, ...) of one sample period apart.
    step : float
        Sample period [s].

    Returns
    -------
    numpy.ndarray
        (values[k+1] - 2 values[k] + values[k-1]) / step^2, (N, ...).

    Examples
    --------
    >>> import numpy as np
    >>> second_difference(np.array([0.0, 0.0, 1.0, 4.0, 9.0]), 1.0).tolist()
    [0.0, 1.0, 2.0, 2.0, -5.0]
    """
    padded = np.concatenate((values[:1], values, values[-1:]))
    return np.asarray((padded[2:] - 2 * padded[1:-1] + padded[:-2]) / step**2)
