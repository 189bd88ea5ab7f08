"""The samples of the 3-D path program: the path parameter and the tilt at a uniform grid
(`PathSamples`), the poses they describe (`sample_poses`, `export_poses`), and their transfer
to another grid (`rescaled`: the same timing on other samples; `smoothed`: a cubic B-spline of
it, for a finer grid).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class PathSamples:
    """Path parameter [m] and tilt rotation vector [rad] at uniform samples.

    Parameters
    ----------
    s_m : numpy.ndarray
        Path parameter s_k at the samples, (N + 1,) [m], from 0 to the path's length.
    tilt_rad : numpy.ndarray
        Tilt rotation vector (r_x, r_y) at the samples, (N + 1, 2) [rad].
    period_s : float
        Sample period h [s]: the export's, or a dilated one while the duration is free
        (`sloshkit.plan.path.minimum_time.free_time`).

    Examples
    --------
    >>> import numpy as np
    >>> PathSamples(np.linspace(0.0, 0.1, 11), np.zeros((11, 2)), 0.004).steps
    10
    """

    s_m: FloatArray
    tilt_rad: FloatArray
    period_s: float

    @property
    def steps(self) -> int:
        """N, the number of sample periods."""
        return int(self.s_m.size - 1)


def sample_poses(
    path: Any, samples: PathSamples, centre_height_m: float
) -> tuple[FloatArray, Rotation]:
    """Reference-point positions and container orientations of the samples.

    The tilt rotation R_t = exp([r_x, r_y, 0]) acts on the path's orientation R_p(s) about the
    tilt centre c = (0, 0, h_c) of the container frame: q = R_t R_p, P = p(s) + R_p c - q c
    (the centre stays on the path; `sloshkit.plan.path.tilt_compensation` uses the same
    convention).

    Parameters
    ----------
    path : Path
        The path (`sloshkit.plan.path.geometry.Path`).
    samples : PathSamples
        Path parameter and tilt at the samples.
    centre_height_m : float
        The tilt centre's height h_c above the reference point [m].

    Returns
    -------
    tuple
        Positions (N + 1, 3) [m] and orientations (`scipy.spatial.transform.Rotation`).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> path = path_from_waypoints([[0, 0, 0], [0.1, 0, 0]])
    >>> tilted = PathSamples(np.array([0.0, 0.05]), np.array([[0.0, 0.0], [0.0, 0.2]]), 0.004)
    >>> position, rotation = sample_poses(path, tilted, 0.05)  # tilted about 50 mm up
    >>> (position[1] + rotation[1].apply([0, 0, 0.05])).round(6).tolist()  # the centre: on
    [0.05, 0.0, 0.05]
    """
    base = path.orientation(samples.s_m)
    position = path.position(samples.s_m)
    if not np.any(samples.tilt_rad):
        return position, base
    rotvec = np.column_stack((samples.tilt_rad, np.zeros(samples.s_m.size)))
    rotation = Rotation.from_rotvec(rotvec) * base
    if centre_height_m:
        centre = np.array([0.0, 0.0, centre_height_m])
        position = position + base.apply(centre) - rotation.apply(centre)
    return position, rotation


def rescaled(samples: PathSamples, steps: int, period_s: float | None = None) -> PathSamples:
    """The same timing shape on another number of samples.

    s and the tilt over normalised time by the clamped cubic spline through the samples (C2
    and at rest at both ends; de Boor, *A Practical Guide to Splines* (1978) ch. IV), s kept
    monotone on [0, S].

    Parameters
    ----------
    samples : PathSamples
        The timing.
    steps : int
        Sample periods of the result.
    period_s : float, optional
        Its sample period [s] (default: the samples' own).

    Returns
    -------
    PathSamples

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(11) / 10
    >>> timing = PathSamples(t**2 * (3 - 2 * t), np.zeros((11, 2)), 0.1)
    >>> longer = rescaled(timing, 20, 0.05)
    >>> longer.steps, float(longer.s_m[10]), float(longer.s_m[-1])
    (20, 0.5, 1.0)
    """
    s = _on_steps(samples.s_m, steps)
    s = np.clip(np.maximum.accumulate(s), samples.s_m[0], samples.s_m[-1])
    s[-1] = samples.s_m[-1]
    period = samples.period_s if period_s is None else period_s
    return PathSamples(s, _on_steps(samples.tilt_rad, steps), period)


def _on_steps(values: FloatArray, steps: int) -> FloatArray:
    """``values`` (one row per sample) over normalised time on ``steps`` periods: the cubic
    spline clamped at rest at both ends (zero first derivative), as `rescaled` carries a timing
    and a tilt."""
    from scipy.interpolate import CubicSpline

    old = values.shape[0] - 1
    u_old, u_new = np.arange(old + 1) / old, np.arange(steps + 1) / steps
    return np.asarray(CubicSpline(u_old, values, axis=0, bc_type="clamped")(u_new))


def smoothed(samples: PathSamples, steps: int, period_s: float) -> PathSamples:
    """A coarse timing on a finer grid, its jerk kept.

    The uniform cubic B-spline whose control points are the samples (each end repeated twice
    more, so the curve starts and ends at rest), its parameter spread over the same duration.
    The B-spline's third derivative on each segment is the third difference of its control
    points, so the finer grid sees no more jerk (in s) than the coarse one (de Boor, *A
    Practical Guide to Splines* (1978) ch. IX); an interpolating spline amplifies the coarse
    grid's alternating jerk up to threefold.

    Parameters
    ----------
    samples : PathSamples
        The coarse timing.
    steps : int
        Sample periods of the result.
    period_s : float
        Its sample period [s].

    Returns
    -------
    PathSamples

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(11) / 10
    >>> coarse = PathSamples(t**2 * (3 - 2 * t), np.zeros((11, 2)), 0.1)
    >>> fine = smoothed(coarse, 40, 0.025)
    >>> fine.steps, float(fine.s_m[0]), float(fine.s_m[-1]), bool(np.all(np.diff(fine.s_m) >= 0))
    (40, 0.0, 1.0, True)
    """
    points = np.concatenate((samples.s_m[:1].repeat(2), samples.s_m, samples.s_m[-1:].repeat(2)))
    parameter = 1.0 + np.arange(steps + 1) / steps * (points.size - 3)
    index = np.clip(np.floor(parameter).astype(int), 1, points.size - 3)
    t = parameter - index
    weights = (
        (1.0 - t) ** 3 / 6.0,
        (3.0 * t**3 - 6.0 * t**2 + 4.0) / 6.0,
        (-3.0 * t**3 + 3.0 * t**2 + 3.0 * t + 1.0) / 6.0,
        t**3 / 6.0,
    )
    s = sum(w * points[index + j - 1] for j, w in enumerate(weights))
    s = np.clip(np.maximum.accumulate(s), samples.s_m[0], samples.s_m[-1])
    s[-1] = samples.s_m[-1]
    tilt = _on_steps(samples.tilt_rad, steps)
    return PathSamples(s, tilt, period_s)


def export_poses(problem: Any, samples: PathSamples) -> Any:
    """The samples as the export.

    Parameters
    ----------
    problem : PathProblem
        The path, its export period and tilt centre.
    samples : PathSamples
        The timing on the export grid.

    Returns
    -------
    PoseTrajectory
        The container's poses at the samples (`sloshkit.motion.poses.PoseTrajectory`, which
        makes the quaternions sign-continuous).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.015, 0.002), model)
    >>> samples = PathSamples(np.linspace(0.0, 0.1, 6), np.zeros((6, 2)), 0.004)
    >>> poses = export_poses(problem, samples)
    >>> float(poses.duration_s), poses.position_m[-1].round(3).tolist()
    (0.02, [0.1, 0.0, 0.0])
    """
    from sloshkit.motion.poses import PoseTrajectory

    position, rotation = sample_poses(problem.path, samples, problem.tilt_centre_height_m)
    time_s = np.arange(samples.s_m.size) * problem.sample_period_s
    return PoseTrajectory(time_s, position, rotation.as_quat())


#: How far an export may lie from the path, and turn about the container's axis, for
#: `samples_from_poses` to read it as samples of the path [m], [rad].
ON_PATH_M = 1e-3
ON_AXIS_RAD = 1e-2


def samples_from_poses(problem: Any, poses: Any) -> PathSamples:
    """The path parameter and tilt of an export of the path: the inverse of `export_poses`.

    Each pose's tilt centre, P + q c, lies on the centre's curve p(s) + R_p(s) c of the path
    (`sample_poses`'s convention): s is its nearest point, searched forward from the last
    sample's within the distance the speed limit allows (so a path that crosses itself is
    read in order), then refined by two Gauss-Newton steps; the tilt is the rotation vector
    of q R_p(s)^-1 (its component about the container's axis dropped). Used to start the
    path program from another method's verified plan.

    Parameters
    ----------
    problem : PathProblem
        The path, its export period, speed limit and tilt centre.
    poses : PoseTrajectory
        An export of the path on the problem's period (e.g. a ``retime`` or ``tilt`` plan).

    Returns
    -------
    PathSamples
        On the problem's period, s monotone from 0 to the path's length.

    Raises
    ------
    ValueError
        When the poses are not on the problem's period, lie more than `ON_PATH_M` from the
        path or turn more than `ON_AXIS_RAD` about the container's axis (a ``shaped`` plan,
        which cuts corners).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.015, 0.002), model)
    >>> t = np.linspace(0.0, 1.0, 51)
    >>> tilt = np.column_stack((np.zeros(51), 0.1 * np.sin(np.pi * t)))
    >>> samples = PathSamples(0.1 * t**2 * (3 - 2 * t), tilt, problem.sample_period_s)
    >>> read = samples_from_poses(problem, export_poses(problem, samples))
    >>> bool(np.allclose(read.s_m, samples.s_m, atol=1e-9)), bool(np.allclose(read.tilt_rad, tilt))
    (True, True)
    """
    path, ts = problem.path, problem.sample_period_s
    if poses.time_s.size < 2 or not np.allclose(np.diff(poses.time_s), ts, rtol=1e-6, atol=0.0):
        raise ValueError(f"the poses are not on the export period of {ts * 1e3:g} ms")
    offset = np.array([0.0, 0.0, problem.tilt_centre_height_m])
    rotation = Rotation.from_quat(poses.quaternion_xyzw)
    target = poses.position_m + rotation.apply(offset)
    length = path.length_m

    def centre(s: FloatArray) -> FloatArray:
        return np.asarray(path.position(s) + path.orientation(s).apply(offset))

    spacing = min(1e-3, length / 1000.0)
    grid = np.linspace(0.0, length, math.ceil(length / spacing) + 1)
    dense = centre(grid)
    reach = math.ceil(2.0 * problem.machine.max_velocity_m_s * ts / spacing) + 2
    index = np.empty(target.shape[0], dtype=int)
    last = 0
    for k, point in enumerate(target):
        window = dense[last : last + reach]
        last += int(np.argmin(np.einsum("ij,ij->i", window - point, window - point)))
        index[k] = last
    s = grid[index]
    step = 1e-6 * max(length, 1e-3)
    for _ in range(2):
        slope = (centre(s + step) - centre(s - step)) / (2.0 * step)
        gain = np.einsum("ij,ij->i", target - centre(s), slope)
        s = np.clip(s + gain / np.maximum(np.einsum("ij,ij->i", slope, slope), 1e-12), 0.0, length)
    s = np.maximum.accumulate(s)
    s[0], s[-1] = 0.0, length
    away = float(np.max(np.linalg.norm(centre(s) - target, axis=1)))
    if away > ON_PATH_M:
        raise ValueError(f"the poses lie up to {away * 1e3:.3g} mm from the path")
    rotvec = (rotation * path.orientation(s).inv()).as_rotvec()
    turn = float(np.max(np.abs(rotvec[:, 2])))
    if turn > ON_AXIS_RAD:
        raise ValueError(f"the poses turn up to {turn:.3g} rad about the container's axis")
    return PathSamples(s, np.ascontiguousarray(rotvec[:, :2]), ts)


__all__ = [
    "ON_AXIS_RAD",
    "ON_PATH_M",
    "PathSamples",
    "export_poses",
    "rescaled",
    "sample_poses",
    "samples_from_poses",
    "smoothed",
]
