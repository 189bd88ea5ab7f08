"""Timings s(t) along a 3-D path: a jerk-limited, slosh-aware parametric family.

A timing of the family is built in three steps:

1. **acceleration-capped time-optimal speed profile** (numerical TOPP: Bobrow, Dubowsky &
   Gibson, Int. J. Robotics Research 4(3) (1985) 3-17, doi:10.1177/027836498500400301; Pham,
   IEEE T-RO 30(6) (2014) 1533-1540, doi:10.1109/TRO.2014.2351113): the fastest speed v(s)
   with the total acceleration of the reference point, tangential and centripetal,
   a_t^2 + (kappa v^2)^2 <= A^2 (a "friction circle"), under the speed and angular-speed limits,
   by a forward and a backward integration on a grid of s;
2. **jerk limit**: the timing is averaged over a sliding window of width tau (a box FIR filter
   of s(t)), which turns acceleration jumps into ramps of jerk <= 2 A / tau and keeps the path
   (the timing changes, the geometry does not) (Biagiotti & Melchiorri, *Trajectory Planning
   for Automatic Machines and Robots*, Springer (2008) ch. 4, FIR-filter trajectories);
3. **input shaping** of the timing on the first slosh mode: ZV, or ZVD with a robustness band
   (Singer & Seering, ASME J. Dyn. Syst. Meas. Control 112 (1990) 76-82,
   doi:10.1115/1.2894142), which cancels the residual oscillation the timing leaves.

The quasi-static slosh height grows with the acceleration the liquid feels (about
0.94 R |a| / g for three modes), so the cap A is the one parameter that trades duration for
slosh: `sloshkit.plan.path.search.fastest_capped` searches A until the linear slosh screen passes;
a uniform stretch in time t -> c t (`sloshkit.plan.path.search.stretch_until`) is the naive
alternative it is compared with.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import CubicHermiteSpline

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.sampling import steps_to_reach
from sloshkit.motion.shaping import Shaper, zv, zvd
from sloshkit.plan.path.geometry import Path
from sloshkit.plan.path.limits import machine_violations
from sloshkit.plan.path.problem import PathProblem, sample_path
from sloshkit.plan.path.timing import Timing, box_smoothed, fine_grid, shaped_timing

FloatArray = NDArray[np.float64]
#: Grid spacing of the speed-profile integration [m].
PROFILE_STEP_M = 1e-3


def axis_shaped_samples(
    path: Path, timing: Timing, shaper: Shaper, sample_period_s: float
) -> PoseTrajectory:
    """Per-axis input shaping: positions sum_i A_i p(s(t - t_i)) (each Cartesian axis shaped,
    so the lateral forcing of every direction is shaped and the residual of the shaped mode
    cancels in the linear model), orientation R(sum_i A_i s(t - t_i)). Corners are cut: the
    positions leave the path by up to about kappa (v t_N)^2 / 8.

    Parameters
    ----------
    path : Path
        The geometry.
    timing : Timing
        The timing before shaping.
    shaper : Shaper
        The shaper.
    sample_period_s : float
        Sample period of the export [s].

    Returns
    -------
    PoseTrajectory

    References
    ----------
    Singer & Seering (1990), doi:10.1115/1.2894142.

    Examples
    --------
    >>> from sloshkit.motion.shaping import zv
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> ramp = Timing.from_samples("ramp", np.linspace(0, 1, 101), np.linspace(0, 0.3, 101))
    >>> poses = axis_shaped_samples(path, ramp, zv(2 * np.pi, 0.0), 0.01)
    >>> poses.duration_s, poses.position_m[-1].tolist()
    (1.5, [0.3, 0.0, 0.0])
    """
    count = steps_to_reach(timing.duration_s + float(shaper.times_s[-1]), sample_period_s)
    t = np.arange(count + 1, dtype=float) * sample_period_s
    positions = np.zeros((t.size, 3))
    mean_s = np.zeros(t.size)
    for amplitude, delay in zip(shaper.amplitudes, shaper.times_s, strict=True):
        s = timing.position(t - delay)
        positions += amplitude * path.position(s)
        mean_s += amplitude * s
    mean_s[-1] = path.length_m
    positions[-1] = path.position(path.length_m)
    quaternions = path.orientation(np.clip(mean_s, 0.0, path.length_m)).as_quat()
    return PoseTrajectory(t, positions, quaternions)


def _profile_geometry(path: Path) -> tuple[FloatArray, ...]:
    """s grid, |p'|, curvature, |omega_s|, |omega_s'| on the profile grid (cached per path)."""
    cache: dict[str, tuple[FloatArray, ...]] = path.__dict__.setdefault("_profile", {})
    if not cache:
        count = max(50, math.ceil(path.length_m / PROFILE_STEP_M))
        s = np.linspace(0.0, path.length_m, count + 1)
        speed = np.maximum(np.linalg.norm(path.position(s, 1), axis=1), 1e-9)
        curvature = np.linalg.norm(path.position(s, 2), axis=1) / speed**2
        turn = np.linalg.norm(path.angular_rate(s, 1), axis=1)
        turn_rate = np.linalg.norm(path.angular_rate(s, 2), axis=1)
        cache["arrays"] = (s, speed, curvature, turn, turn_rate)
    return cache["arrays"]


def speed_profile(
    path: Path, problem: PathProblem, acceleration_cap: float
) -> tuple[FloatArray, FloatArray]:
    """Fastest s'(s) [m/s] with total acceleration <= ``acceleration_cap`` under the speed and
    angular limits (module docstring, step 1).

    Parameters
    ----------
    path : Path
        The geometry.
    problem : PathProblem
        The Cartesian and angular limits.
    acceleration_cap : float
        Cap A on the total acceleration [m/s^2] (at most amax).

    Returns
    -------
    tuple of ndarray
        (s grid [m], s' [m/s]), zero at both ends.

    References
    ----------
    Bobrow et al. (1985), doi:10.1177/027836498500400301; Pham (2014),
    doi:10.1109/TRO.2014.2351113.

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> path = path_from_waypoints([[0, 0, 0], [1.0, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(0.5, 10.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), None)
    >>> s, rate = speed_profile(path, problem, 1.0)
    >>> round(float(rate.max()), 3)  # the speed limit
    0.5
    """
    machine = problem.machine
    s, speed, curvature, turn, turn_rate = _profile_geometry(path)
    step = s[1] - s[0]
    limit = np.full(s.size, machine.max_velocity_m_s) / speed
    cap = min(acceleration_cap, machine.max_acceleration_m_s2)
    limit = np.minimum(limit, np.sqrt(cap / np.maximum(curvature, 1e-12)) / speed)
    if machine.max_angular_velocity_rad_s is not None:
        limit = np.minimum(limit, machine.max_angular_velocity_rad_s / np.maximum(turn, 1e-12))
    tangential = np.full(s.size, cap)
    if machine.max_angular_acceleration_rad_s2 is not None:
        half = 0.5 * machine.max_angular_acceleration_rad_s2
        limit = np.minimum(limit, np.sqrt(half / np.maximum(turn_rate, 1e-12)))
        tangential = np.minimum(tangential, half / np.maximum(turn, 1e-12) * speed)

    profile = _integrate_profile(
        np.ascontiguousarray(limit, dtype=float),
        np.ascontiguousarray(tangential, dtype=float),
        np.ascontiguousarray(curvature, dtype=float),
        np.ascontiguousarray(speed, dtype=float),
        float(step),
    )
    return s, profile


def _passes(
    limit: FloatArray, tangential: FloatArray, curvature: FloatArray, speed: FloatArray, step: float
) -> FloatArray:
    """Forward then backward integration of s' under the limit curve and the friction circle:
    the usable tangential acceleration is sqrt(a_t,max^2 - (kappa |p'|^2 s'^2)^2) / |p'|."""
    size = limit.size
    forward = np.zeros(size)
    for i in range(size - 1):
        lateral = curvature[i] * (speed[i] * forward[i]) ** 2
        usable = math.sqrt(max(tangential[i] ** 2 - lateral**2, 0.0)) / speed[i]
        forward[i + 1] = min(limit[i + 1], math.sqrt(forward[i] ** 2 + 2.0 * usable * step))
    profile = forward.copy()
    profile[-1] = 0.0
    for i in range(size - 2, -1, -1):
        lateral = curvature[i + 1] * (speed[i + 1] * profile[i + 1]) ** 2
        usable = math.sqrt(max(tangential[i + 1] ** 2 - lateral**2, 0.0)) / speed[i + 1]
        profile[i] = min(profile[i], math.sqrt(profile[i + 1] ** 2 + 2.0 * usable * step))
    profile[0] = 0.0
    return profile


def _compiled_passes() -> Callable[..., FloatArray]:
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - numba is a dependency
        return _passes
    compiled: Callable[..., FloatArray] = njit(cache=True)(_passes)
    return compiled


_integrate_profile = _compiled_passes()


def capped_timing(problem: PathProblem, acceleration_cap: float) -> Timing:
    """The speed profile of `speed_profile` as a timing (C1 Hermite in time).

    Parameters
    ----------
    problem : PathProblem
        Path and limits.
    acceleration_cap : float
        Cap A on the total acceleration [m/s^2].

    Returns
    -------
    Timing

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [1.0, 0, 0]]),
    ...                       CartesianLimits(0.5, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> round(capped_timing(problem, 1.0).duration_s, 2)  # 1 m at 0.5 m/s + 0.5 s ramps
    2.5
    """
    s, rate = speed_profile(problem.path, problem, acceleration_cap)
    durations = 2.0 * np.diff(s) / np.maximum(rate[1:] + rate[:-1], 1e-12)
    t = np.concatenate(([0.0], np.cumsum(durations)))
    spline = CubicHermiteSpline(t, s, rate)
    grid = fine_grid(float(t[-1]))
    return Timing("capped", grid, np.asarray(spline(grid), dtype=float))


def first_mode_shaper(problem: PathProblem) -> Shaper:
    """ZV on the nominal first mode, ZVD when a robustness band is asked for.

    Parameters
    ----------
    problem : PathProblem
        Model and slosh limits.

    Returns
    -------
    Shaper

    References
    ----------
    Singer & Seering (1990), doi:10.1115/1.2894142.

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       model)
    >>> first_mode_shaper(problem).name
    'zv'
    """
    first = problem.model.modes[0]
    make = zvd if problem.slosh.robustness > 0 else zv
    return make(first.omega_rad_s, first.damping_ratio)


#: Largest notch offset of `curve_shaper`, as a fraction of the first mode's frequency.
CURVE_SHAPER_MAX_OFFSET = 0.5
ShaperFactory = Callable[[float], Shaper]


def curve_shaper(problem: PathProblem) -> ShaperFactory:
    """Timing shapers for curved paths: ZV notches at w and w (1 -+ r), r = Omega / w.

    On a curve the direction of the lateral forcing turns at Omega = kappa v. Writing the
    forcing as F(t) e^{i Phi(t)} (F in the path's own frame, Phi the heading), its spectrum at
    the slosh frequency w comes from F at w - Omega and w + Omega, so a shaper that notches
    only w (ZV on the timing) leaves a residual that grows with the turning rate (measured on
    the series' paths: ZV on the timing leaves 4-7 mm where it cancels a straight move). Three
    ZV shapers in series, at w and at w (1 -+ r), notch the band the turning spreads the
    forcing over; with a cap A the centripetal acceleration kappa v^2 <= A bounds the turning
    rate by Omega <= sqrt(kappa_max A), so r = min(`CURVE_SHAPER_MAX_OFFSET`,
    sqrt(kappa_max A) / w). With a robustness band the centre notch is a ZVD. The result
    depends on A, so this returns a function of the cap.

    Parameters
    ----------
    problem : PathProblem
        Path (its largest curvature), model (first mode), robustness band.

    Returns
    -------
    callable
        A [m/s^2] -> Shaper (named ``curve``).

    References
    ----------
    Singer & Seering (1990), doi:10.1115/1.2894142 (ZV shapers; shapers in series notch every
    frequency of each); the spectral argument is this library's (docs/planning-3d.md).

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0], [0.3, 0.3, 0]], blend_radius_m=0.1)
    >>> problem = PathProblem(path, CartesianLimits(2.0, 10.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), model)
    >>> shaper = curve_shaper(problem)(2.0)  # sqrt(10 /m * 2 m/s^2) = 4.5 rad/s
    >>> shaper.name, shaper.amplitudes.size, round(float(shaper.times_s[-1]), 3)
    ('curve', 8, 0.511)
    """
    first = problem.model.modes[0]
    omega, zeta = first.omega_rad_s, first.damping_ratio
    curvature = float(np.max(_profile_geometry(problem.path)[2]))
    centre = (zvd if problem.slosh.robustness > 0 else zv)(omega, zeta)

    def shaper(acceleration_cap: float) -> Shaper:
        offset = min(CURVE_SHAPER_MAX_OFFSET, math.sqrt(curvature * acceleration_cap) / omega)
        if offset < 1e-3:
            return Shaper("curve", centre.amplitudes, centre.times_s)
        amplitudes, times = centre.amplitudes, centre.times_s
        for side in (zv(omega * (1.0 - offset), zeta), zv(omega * (1.0 + offset), zeta)):
            amplitudes = np.outer(amplitudes, side.amplitudes).ravel()
            times = np.add.outer(times, side.times_s).ravel()
        order = np.argsort(times, kind="stable")
        return Shaper("curve", amplitudes[order], times[order])

    return shaper


def family_member(
    problem: PathProblem, acceleration_cap: float, shaper: Shaper | ShaperFactory | None
) -> Timing:
    """The family member with cap A: capped profile, box filter, optional timing shaper.

    The box width is the shortest of 2 A / jmax * 1.25^k (k = 0..8) whose export meets every
    Cartesian and angular limit.

    Parameters
    ----------
    problem : PathProblem
        Path and limits.
    acceleration_cap : float
        Cap A [m/s^2].
    shaper : Shaper, callable or None
        Shaper of the timing, or a function of the cap A giving it (`curve_shaper`); None:
        unshaped.

    Returns
    -------
    Timing

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [1.0, 0, 0]]),
    ...                       CartesianLimits(0.5, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> round(family_member(problem, 1.0, None).duration_s, 2)  # + the 20 ms box
    2.52
    """
    base = capped_timing(problem, acceleration_cap)
    width = 2.0 * acceleration_cap / problem.machine.max_jerk_m_s3
    timing = base
    for _ in range(9):
        timing = box_smoothed(base, width)
        if shaper is not None:
            timing = shaped_timing(
                timing, shaper if isinstance(shaper, Shaper) else shaper(acceleration_cap)
            )
        poses = sample_path(problem.path, timing, problem.sample_period_s)
        if not machine_violations(problem, poses, False):
            break
        width *= 1.25
    return timing
