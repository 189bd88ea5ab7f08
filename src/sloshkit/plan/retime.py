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
slosh: `fastest_capped` bisects on A until the linear slosh screen passes. A uniform stretch in
time t -> c t (`stretch_until`) is the naive alternative it is compared with.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicHermiteSpline, CubicSpline

from sloshkit.errors import InputError
from sloshkit.motion.shaping import Shaper, zv, zvd
from sloshkit.plan.path import Path
from sloshkit.plan.spatial import (
    PathProblem,
    PoseSamples,
    _continuous,
    linear_screen,
    machine_violations,
    sample_path,
    screen_ok,
)

FloatArray = NDArray[np.float64]
#: Resolution of the fine time grid the composed timings are tabulated on [s].
FINE_STEP_S = 5e-4
#: Grid spacing of the speed-profile integration [m].
PROFILE_STEP_M = 1e-3


@dataclass(frozen=True, eq=False)
class Timing:
    """A rest-to-rest timing s(t) [m] of a path on [0, ``duration_s``], tabulated on a fine grid
    and interpolated by a cubic spline (held at 0 before and at ``length_m`` after).

    Examples
    --------
    >>> timing = Timing.from_samples("ramp", np.linspace(0, 1, 11), np.linspace(0, 1, 11) ** 2)
    >>> round(float(timing.position(0.5)), 3), timing.duration_s
    (0.25, 1.0)
    """

    name: str
    time_s: FloatArray
    s_m: FloatArray

    @classmethod
    def from_samples(cls, name: str, time_s: ArrayLike, s_m: ArrayLike) -> Timing:
        """A timing through the samples (times increasing from 0)."""
        t = np.asarray(time_s, dtype=float)
        s = np.asarray(s_m, dtype=float)
        if t.ndim != 1 or t.size < 2 or t[0] != 0.0 or np.any(np.diff(t) <= 0):
            raise InputError("timing", t.size, "needs increasing times from 0")
        return cls(name, t, s)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_spline", CubicSpline(self.time_s, self.s_m))

    @property
    def duration_s(self) -> float:
        """Duration T [s]."""
        return float(self.time_s[-1])

    @property
    def length_m(self) -> float:
        """Final s [m]."""
        return float(self.s_m[-1])

    def position(self, time_s: ArrayLike) -> FloatArray:
        """s(t) [m]."""
        spline: CubicSpline = self._spline  # type: ignore[attr-defined]
        t = np.asarray(time_s, dtype=float)
        inside = np.asarray(spline(np.clip(t, 0.0, self.duration_s)), dtype=float)
        return np.where(t <= 0.0, 0.0, np.where(t >= self.duration_s, self.length_m, inside))

    def derivative(self, time_s: ArrayLike, order: int) -> FloatArray:
        """d^k s / dt^k (0 outside the move)."""
        spline: CubicSpline = self._spline  # type: ignore[attr-defined]
        t = np.asarray(time_s, dtype=float)
        inside = (t > 0.0) & (t < self.duration_s)
        return np.where(inside, spline(np.clip(t, 0.0, self.duration_s), order), 0.0)

    def velocity(self, time_s: ArrayLike) -> FloatArray:
        """s' [m/s]."""
        return self.derivative(time_s, 1)

    def acceleration(self, time_s: ArrayLike) -> FloatArray:
        """s'' [m/s^2]."""
        return self.derivative(time_s, 2)

    def jerk(self, time_s: ArrayLike) -> FloatArray:
        """s''' [m/s^3]."""
        return self.derivative(time_s, 3)

    def stretched(self, factor: float) -> Timing:
        """s(t / c): speeds / c, accelerations / c^2, jerks / c^3."""
        return Timing(self.name, self.time_s * factor, self.s_m)


def _fine_grid(duration_s: float) -> FloatArray:
    count = max(8, math.ceil(duration_s / FINE_STEP_S))
    return np.linspace(0.0, duration_s, count + 1)


def box_smoothed(timing: Timing, width_s: float) -> Timing:
    """(1/tau) integral_{t-tau}^{t} s(u) du: a jerk-limited timing, tau longer [s]."""
    if width_s <= 0.0:
        return timing
    grid = _fine_grid(timing.duration_s + width_s)
    step = grid[1] - grid[0]
    values = timing.position(grid)
    integral = np.concatenate(([0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * step)))
    before = np.interp(grid - width_s, grid, integral, left=0.0)
    smoothed = (integral - before) / width_s
    smoothed[-1] = timing.length_m
    return Timing(timing.name, grid, smoothed)


def shaped_timing(timing: Timing, shaper: Shaper) -> Timing:
    """sum_i A_i s(t - t_i) (duration T + t_N)."""
    grid = _fine_grid(timing.duration_s + float(shaper.times_s[-1]))
    values = sum(
        amplitude * timing.position(grid - delay)
        for amplitude, delay in zip(shaper.amplitudes, shaper.times_s, strict=True)
    )
    values = np.asarray(values, dtype=float)
    values[-1] = timing.length_m
    return Timing(timing.name, grid, values)


def axis_shaped_samples(
    path: Path, timing: Timing, shaper: Shaper, sample_period_s: float
) -> PoseSamples:
    """Per-axis input shaping: positions sum_i A_i p(s(t - t_i)) (each Cartesian axis shaped,
    so the lateral forcing of every direction is shaped and the residual of the shaped mode
    cancels in the linear model), orientation R(sum_i A_i s(t - t_i)). Corners are cut: the
    positions leave the path by up to about kappa (v t_N)^2 / 8."""
    count = math.ceil((timing.duration_s + float(shaper.times_s[-1])) / sample_period_s - 1e-9)
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
    return PoseSamples(t, positions, _continuous(quaternions))


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
    """Fastest s' (s) [m/s] with total acceleration <= ``acceleration_cap`` [m/s^2] (module
    docstring, step 1), on a grid of s [m]; returns (s, s')."""
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
    """The speed profile of `speed_profile` as a timing (C1 Hermite in time)."""
    s, rate = speed_profile(problem.path, problem, acceleration_cap)
    durations = 2.0 * np.diff(s) / np.maximum(rate[1:] + rate[:-1], 1e-12)
    t = np.concatenate(([0.0], np.cumsum(durations)))
    spline = CubicHermiteSpline(t, s, rate)
    grid = _fine_grid(float(t[-1]))
    return Timing("capped", grid, np.asarray(spline(grid), dtype=float))


def first_mode_shaper(problem: PathProblem) -> Shaper:
    """ZV on the nominal first mode, ZVD when a robustness band is asked for."""
    first = problem.model.modes[0]
    make = zvd if problem.slosh.robustness > 0 else zv
    return make(first.omega_rad_s, first.damping_ratio)


def family_member(problem: PathProblem, acceleration_cap: float, shaper: Shaper | None) -> Timing:
    """The family member with cap A: the box width is the shortest of 2 A / jmax * 1.25^k
    (k = 0..8) whose export meets every Cartesian and angular limit."""
    base = capped_timing(problem, acceleration_cap)
    width = 2.0 * acceleration_cap / problem.machine.max_jerk_m_s3
    timing = base
    for _ in range(9):
        timing = box_smoothed(base, width)
        if shaper is not None:
            timing = shaped_timing(timing, shaper)
        poses = sample_path(problem.path, timing, problem.sample_period_s)
        if not machine_violations(problem, poses, False):
            break
        width *= 1.25
    return timing


def stretcher(problem: PathProblem, timing: Timing) -> Callable[[float], PoseSamples]:
    """Sampled poses of ``timing`` stretched uniformly by a factor c."""

    def poses_for(factor: float) -> PoseSamples:
        return sample_path(problem.path, timing.stretched(factor), problem.sample_period_s)

    return poses_for


def _bisect(ok: Callable[[float], bool], low: float, high: float, steps: int = 14) -> float:
    """Smallest c in [low, high] with ok(c) (ok assumed monotone; ok(high) True)."""
    for _ in range(steps):
        middle = math.sqrt(low * high)
        if ok(middle):
            high = middle
        else:
            low = middle
        if high / low < 1.0 + 1e-3:
            break
    return high


def stretch_until(
    ok: Callable[[float], bool], start: float = 1.0, limit: float = 64.0
) -> float | None:
    """Smallest stretch c >= ``start`` with ok(c): doubling, then bisection; None when nothing
    up to ``limit`` passes."""
    if ok(start):
        return start
    low, high = start, 2.0 * start
    while not ok(high):
        low, high = high, 2.0 * high
        if high > limit:
            return None
    return _bisect(ok, low, high)


def slowed_until(
    problem: PathProblem, poses_for: Callable[[float], PoseSamples], start: float = 1.0
) -> tuple[float, PoseSamples] | None:
    """Smallest uniform stretch c >= ``start`` at which ``poses_for(c)`` passes the linear
    slosh screen, and its poses (None when none up to 64x passes)."""
    models = problem.models()
    factor = stretch_until(lambda c: screen_ok(problem, linear_screen(models, poses_for(c))), start)
    return None if factor is None else (factor, poses_for(factor))


def fastest_capped(
    problem: PathProblem,
    passes: Callable[[PoseSamples], bool],
    shaper: Shaper | None,
    low_fraction: float = 1e-3,
    sampler: Callable[[Timing], PoseSamples] | None = None,
) -> tuple[float, Timing] | None:
    """The largest acceleration cap A between ``low_fraction`` amax and amax whose family
    member's export (``sampler``, default `sample_path`) passes ``passes``: a descending scan
    of 20 log-spaced caps, then a bisection; (A, the member's timing) or None."""
    amax = problem.machine.max_acceleration_m_s2

    def ok(member: Timing) -> bool:
        if sampler is not None:
            return passes(sampler(member))
        return passes(sample_path(problem.path, member, problem.sample_period_s))

    # Slosh is not monotone in A (the residual oscillates with the move's duration): a
    # descending scan finds the largest passing grid cap and a bisection towards the next
    # larger (failing) grid value refines it; a plain bisection over the whole range can land
    # in a passing pocket between grid values; the larger of the two caps wins.
    caps = np.geomspace(amax, low_fraction * amax, 20)
    passing = None
    for position, cap in enumerate(caps):
        member = family_member(problem, float(cap), shaper)
        if ok(member):
            passing = position
            break
    if passing is None:
        return None
    scanned = _refine(
        problem, ok, shaper, float(caps[passing]), member, float(caps[max(passing - 1, 0)])
    )
    bisected = _refine(problem, ok, shaper, float(caps[-1]), None, amax)
    if scanned is None or (bisected is not None and bisected[0] > scanned[0]):
        return bisected
    return scanned


def _refine(
    problem: PathProblem,
    ok: Callable[[Timing], bool],
    shaper: Shaper | None,
    low: float,
    member: Timing | None,
    high: float,
) -> tuple[float, Timing] | None:
    """Bisection in log A between a passing ``low`` (its member, if known) and ``high``."""
    if member is None:
        member = family_member(problem, low, shaper)
        if not ok(member):
            return None
    found = (low, member)
    for _ in range(10):
        if high / low < 1.02:
            break
        middle = math.sqrt(low * high)
        candidate = family_member(problem, middle, shaper)
        if ok(candidate):
            low, found = middle, (middle, candidate)
        else:
            high = middle
    return found
