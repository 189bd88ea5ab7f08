"""Searches over the timing family of `sloshkit.plan.path.retime`: the largest acceleration cap
whose member passes a test, and the smallest uniform slow-down of a timing that does.

Slosh is not monotone in the cap A (the residual oscillates with the move's duration), so
`fastest_capped` scans 20 log-spaced caps downwards from amax, refines the first passing one by
bisection towards the next larger (failing) grid value, also bisects over the whole range (it
can land in a passing pocket between grid values), and keeps the larger passing cap. A uniform
stretch in time t -> c t (`stretch_until`: doubling, then bisection) is the naive alternative
the planner compares with (`plan_uniform`). The members found here are ``retime``'s and
``tilt``'s plans where their programs (`sloshkit.plan.path.optimal`) do not run or verify
nothing, and ``auto``'s on long moves.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.shaping import Shaper
from sloshkit.plan.path.limits import machine_stretch, machine_violations, path_deviation
from sloshkit.plan.path.problem import PathProblem, sample_path
from sloshkit.plan.path.result import PathCandidate, Verifier, verified_candidate, verify
from sloshkit.plan.path.retime import (
    ShaperFactory,
    curve_shaper,
    family_member,
    first_mode_shaper,
)
from sloshkit.plan.path.screen import binding_slosh, linear_screen, screen_ok
from sloshkit.plan.path.timing import Timing

FloatArray = NDArray[np.float64]


def stretcher(problem: PathProblem, timing: Timing) -> Callable[[float], PoseTrajectory]:
    """Sampled poses of ``timing`` stretched uniformly in time by a factor c.

    Parameters
    ----------
    problem : PathProblem
        Path and sample period.
    timing : Timing
        The timing.

    Returns
    -------
    callable
        c -> PoseTrajectory of s(t / c).

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None, sample_period_s=0.01)
    >>> ramp = Timing.from_samples("ramp", np.linspace(0, 1, 11), np.linspace(0, 0.3, 11))
    >>> stretcher(problem, ramp)(2.0).duration_s
    2.0
    """

    def poses_for(factor: float) -> PoseTrajectory:
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
    """Smallest stretch c >= ``start`` with ok(c): doubling, then bisection (ok assumed
    monotone).

    Parameters
    ----------
    ok : callable
        c -> bool.
    start : float
        First stretch tried.
    limit : float
        Largest stretch tried.

    Returns
    -------
    float or None
        None when nothing up to ``limit`` passes.

    Examples
    --------
    >>> round(stretch_until(lambda c: c >= 3.0), 2)
    3.0
    """
    if ok(start):
        return start
    low, high = start, 2.0 * start
    while not ok(high):
        low, high = high, 2.0 * high
        if high > limit:
            return None
    return _bisect(ok, low, high)


def slowed_until(
    problem: PathProblem, poses_for: Callable[[float], PoseTrajectory], start: float = 1.0
) -> tuple[float, PoseTrajectory] | None:
    """Smallest uniform stretch c >= ``start`` at which ``poses_for(c)`` passes the linear
    slosh screen, and its poses.

    Parameters
    ----------
    problem : PathProblem
        Limits and model.
    poses_for : callable
        c -> PoseTrajectory (e.g. `stretcher`).
    start : float
        First stretch tried.

    Returns
    -------
    tuple or None
        (c, poses), None when nothing up to 64x passes.

    Examples
    --------
    >>> from sloshkit.motion.laws import s_curve
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> problem = _example_problem()  # 0.3 m straight, limits 10 mm / 2 mm
    >>> move = s_curve(0.3, 1.0, 3.0, 30.0)
    >>> ramp = Timing.from_samples("s", np.linspace(0, move.duration_s, 201),
    ...                            move.position(np.linspace(0, move.duration_s, 201)))
    >>> factor, poses = slowed_until(problem, stretcher(problem, ramp))
    >>> factor > 1.0
    True
    """
    models = problem.models()
    factor = stretch_until(lambda c: screen_ok(problem, linear_screen(models, poses_for(c))), start)
    return None if factor is None else (factor, poses_for(factor))


#: Smallest acceleration cap the cap search tries, as a fraction of amax.
LOWEST_CAP_FRACTION = 1e-3


def fastest_capped(
    problem: PathProblem,
    passes: Callable[[PoseTrajectory], bool],
    shaper: Shaper | ShaperFactory | None,
    low_fraction: float = LOWEST_CAP_FRACTION,
    sampler: Callable[[Timing], PoseTrajectory] | None = None,
) -> tuple[float, Timing] | None:
    """The largest acceleration cap A between ``low_fraction`` amax and amax whose family
    member's export passes ``passes`` (module docstring).

    Parameters
    ----------
    problem : PathProblem
        Path and limits.
    passes : callable
        PoseTrajectory -> bool.
    shaper : Shaper, callable or None
        Shaper of the family's timings (or a function of the cap giving it).
    low_fraction : float
        Smallest cap tried, as a fraction of amax.
    sampler : callable, optional
        Timing -> PoseTrajectory (default `sloshkit.plan.path.problem.sample_path`).

    Returns
    -------
    tuple or None
        (A [m/s^2], the member's timing), None when no cap passes.

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.limits import kinematics
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None, sample_period_s=0.01)
    >>> cap, _ = fastest_capped(problem, lambda p: kinematics(p)["acceleration"] < 2.0, None)
    >>> 1.9 < cap < 2.0
    True
    """
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
    return bisected if scanned is None or (bisected and bisected[0] > scanned[0]) else scanned


def lowest_cap_failure(
    problem: PathProblem,
    sampler: Callable[[Timing], PoseTrajectory] | None = None,
    tilted: bool = False,
    deviation: bool = False,
) -> str:
    """What the slowest member that `fastest_capped` tries (cap `LOWEST_CAP_FRACTION` amax, no
    shaper) breaks, for the message of a method that found no cap: the first Cartesian or
    angular limit it breaks, else (with ``deviation``) the path deviation when it exceeds
    ``problem.max_path_deviation_m``, else the slosh limit its linear screen comes closest to
    or exceeds most (`sloshkit.plan.path.screen.binding_slosh`).

    Parameters
    ----------
    problem : PathProblem
        Path and limits.
    sampler : callable, optional
        Timing -> PoseTrajectory, the method's export (default `sample_path`).
    tilted : bool
        Whether the export tilts the container (the tilt's limits apply).
    deviation : bool
        Whether the export may leave the path (per-axis shaping) by at most
        ``problem.max_path_deviation_m``.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(1e-7, 0.002),
    ...                       model, sample_period_s=0.01)
    >>> lowest_cap_failure(problem).split(" against ")[0].startswith("peak slosh height")
    True
    """
    poses = slowest_member(problem, sampler)
    broken = machine_violations(problem, poses, tilted)
    if broken:
        return broken[0]
    off = path_deviation(problem.path, poses) if deviation else 0.0
    if off > problem.max_path_deviation_m:
        return (
            f"path deviation {off * 1e3:.3g} mm against its "
            f"{problem.max_path_deviation_m * 1e3:.3g} mm limit"
        )
    return binding_slosh(problem, linear_screen(problem.models(), poses))


def slowest_member(
    problem: PathProblem, sampler: Callable[[Timing], PoseTrajectory] | None = None
) -> PoseTrajectory:
    """The export of the slowest member that `fastest_capped` tries: cap
    `LOWEST_CAP_FRACTION` amax, unshaped (a quasi-static move).

    Parameters
    ----------
    problem : PathProblem
        Path, limits.
    sampler : callable, optional
        Timing -> PoseTrajectory, the method's export (default `sample_path`).

    Returns
    -------
    PoseTrajectory

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> slowest_member(_example_problem()).duration_s > 10.0
    True
    """
    amax = problem.machine.max_acceleration_m_s2
    member = family_member(problem, LOWEST_CAP_FRACTION * amax, None)
    if sampler is not None:
        return sampler(member)
    return sample_path(problem.path, member, problem.sample_period_s)


def _refine(
    problem: PathProblem,
    ok: Callable[[Timing], bool],
    shaper: Shaper | ShaperFactory | None,
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


def plan_uniform(
    problem: PathProblem, reference: Timing, verifier: Verifier = verify
) -> PathCandidate:
    """The reference timing slowed uniformly until it meets the Cartesian and angular limits
    and then the slosh screen (the naive fix), then verified.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    reference : Timing
        The timing to slow down (e.g. the pose file's own).
    verifier : callable
        Verification of an export.

    Returns
    -------
    PathCandidate

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> from sloshkit.plan.path.retime import capped_timing
    >>> problem = _example_problem()
    >>> found = plan_uniform(problem, capped_timing(problem, 10.0), linear_verifier)
    >>> found.feasible, found.detail["stretch"] > 1.0
    (True, True)
    """
    started = time.perf_counter()

    poses_for = stretcher(problem, reference)
    found = slowed_until(problem, poses_for, machine_stretch(problem, poses_for(1.0)))
    if found is None:
        message = "no uniform stretch up to 64x meets the slosh limits"
        return PathCandidate("uniform", None, None, time.perf_counter() - started, message)
    return verified_candidate("uniform", problem, poses_for, found[0], started, verifier, False, {})


def timing_shapers(problem: PathProblem) -> list[tuple[str, Shaper | ShaperFactory | None]]:
    """The timing shapers the cap searches try: the first-mode ZV (ZVD), none, and on a path
    that turns the curve shaper (`sloshkit.plan.path.retime.curve_shaper`).

    Parameters
    ----------
    problem : PathProblem
        Path, limits and model.

    Returns
    -------
    list of (str, Shaper, factory or None)
        The shapers by name.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> [name for name, _ in timing_shapers(_example_problem())]
    ['zv', 'none']
    """
    first = first_mode_shaper(problem)
    shapers: list[tuple[str, Shaper | ShaperFactory | None]] = [(first.name, first), ("none", None)]
    curve = curve_shaper(problem)
    if curve(problem.machine.max_acceleration_m_s2).amplitudes.size > 3:
        shapers.append(("curve", curve))
    return shapers


def upright_family(problem: PathProblem, verifier: Verifier = verify) -> PathCandidate:
    """The fastest acceleration cap of the family under the slosh screen, with each of
    `timing_shapers`, verified: ``retime``'s plan where its programs do not run or verify
    nothing (`sloshkit.plan.path.planner`).

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    verifier : callable
        Verification of an export.

    Returns
    -------
    PathCandidate
        Method ``retime``, ``detail["source"]`` ``family``; when no cap down to
        `LOWEST_CAP_FRACTION` of amax passes, failed with the limit that binds at that cap.

    References
    ----------
    Bobrow, Dubowsky & Gibson (1985), doi:10.1177/027836498500400301.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> found = upright_family(_example_problem(), linear_verifier)
    >>> found.feasible, found.detail["shaper"]
    (True, 'zv')
    """
    started = time.perf_counter()
    models = problem.models()
    best: tuple[float, float, Timing, str] | None = None
    for name, shaper in timing_shapers(problem):
        found = fastest_capped(
            problem,
            lambda poses: screen_ok(problem, linear_screen(models, poses)),
            shaper,
        )
        if found is None:
            continue
        cap, member = found
        duration = sample_path(problem.path, member, problem.sample_period_s).duration_s
        if best is None or duration < best[0]:
            best = (duration, cap, member, name)
    if best is None:
        message = (
            f"no acceleration cap down to {100 * LOWEST_CAP_FRACTION:g} % of amax meets the slosh "
            f"limits: at that cap, {lowest_cap_failure(problem)}"
        )
        return PathCandidate("retime", None, None, time.perf_counter() - started, message)
    _, cap, member, name = best
    detail = {"source": "family", "acceleration_cap_m_s2": cap, "shaper": name}
    poses_for = stretcher(problem, member)
    return verified_candidate("retime", problem, poses_for, 1.0, started, verifier, False, detail)


__all__ = [
    "LOWEST_CAP_FRACTION",
    "fastest_capped",
    "lowest_cap_failure",
    "plan_uniform",
    "slowed_until",
    "slowest_member",
    "stretch_until",
    "stretcher",
    "timing_shapers",
    "upright_family",
]
