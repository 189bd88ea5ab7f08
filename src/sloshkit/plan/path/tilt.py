"""The ``tilt`` method of the 3-D path planner: tilt compensation combined with re-timing.

First the family's cap search (`plan_tilt`): the largest acceleration cap of the timing family
whose tilted export passes the linear screen and the tilt and angular limits, verified. Then
(`improved_tilt`) the timing is improved with the local searches of ``retime``
(`sloshkit.plan.path.improve.warped_candidates`: pattern search and trust-region SLP on a
speed-scaling warp, and the SLP polishing against the nonlinear model) run on the TILTED
export: every screened, linearised and verified pose set is the sampled timing after
`sloshkit.plan.path.tilt_compensation.tilt_compensated`, with the tilt limit. The seeds are the
family's verified member and the other timings of the path given (in ``auto`` ``retime``'s result:
tilting a good timing is a natural seed), each slowed uniformly until its tilted export
passes the screen and then verified. The improvement runs on its own, smaller budget
(`TILT_SAMPLE_BUDGET`) and is skipped on long moves, where that budget would buy fewer
than `sloshkit.plan.path.improve.LADDER_MIN_SCREENS` screens of the move
(`sloshkit.plan.path.improve.ladder_affordable`); the fastest verified candidate wins, so
the improved plan is never slower than the family's.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import replace

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.shaping import Shaper
from sloshkit.plan.path.improve import ladder_affordable, warped_candidates
from sloshkit.plan.path.ladder import method_timing
from sloshkit.plan.path.limits import machine_stretch, machine_violations
from sloshkit.plan.path.problem import PathProblem, sample_path
from sloshkit.plan.path.result import PathCandidate, Verifier, verified_candidate, verify
from sloshkit.plan.path.retime import ShaperFactory, curve_shaper, first_mode_shaper
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import fastest_capped, lowest_cap_failure, slowed_until, stretcher
from sloshkit.plan.path.tilt_compensation import tilt_compensated
from sloshkit.plan.path.timing import Timing

#: Screened samples the searches of `improved_tilt` share (1-2 s of CPU on the measured
#: series' moves; ``retime``'s budget is 800 000 plus its continuation's).
TILT_SAMPLE_BUDGET = 200_000


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


def tilt_transform(
    problem: PathProblem,
) -> tuple[Callable[[PoseTrajectory], PoseTrajectory], float]:
    """The tilt compensation of the ``tilt`` method
    (`sloshkit.plan.path.tilt_compensation.tilt_compensated` with the first mode's bob height,
    ``max_tilt_rad`` and ``tilt_centre_height_m``) and its
    smoothing: a fifth of the first mode's period (the tilt's angular acceleration excites the
    liquid; 0.01-0.06 s were compared on a straight move, longer is calmer).

    Parameters
    ----------
    problem : PathProblem
        Limits and model.

    Returns
    -------
    tuple
        (PoseTrajectory -> tilted PoseTrajectory, the smoothing [s]).

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> tilted, smoothing = tilt_transform(_example_problem())
    >>> round(smoothing, 3)
    0.066
    """
    bob = problem.model.modes[0].bob_height_m
    smoothing = 2.0 * math.pi / problem.model.modes[0].omega_rad_s / 5.0

    def tilted(poses: PoseTrajectory) -> PoseTrajectory:
        return tilt_compensated(
            poses, bob, problem.max_tilt_rad, problem.tilt_centre_height_m, smoothing
        )

    return tilted, smoothing


def plan_tilt(
    problem: PathProblem,
    verifier: Verifier = verify,
    seeds: Sequence[Timing] = (),
    improve: bool = True,
) -> PathCandidate:
    """Tilt compensation of the family: the largest cap whose tilted export passes the screen
    and the tilt and angular limits, verified; with ``improve`` then improved by
    `improved_tilt` (seeded also from ``seeds``).

    Parameters
    ----------
    problem : PathProblem
        Path, limits (``max_tilt_rad``, ``tilt_centre_height_m``), model.
    verifier : callable
        Verification of an export.
    seeds : sequence of Timing
        Other timings of the path to tilt and improve (e.g. ``retime``'s).
    improve : bool
        Run the local searches on the tilted export (`improved_tilt`).

    Returns
    -------
    PathCandidate

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> problem = _example_problem()
    >>> found = plan_tilt(problem, linear_verifier, improve=False)
    >>> found.feasible, found.verification.peak_tilt_rad > 0.0
    (True, True)
    """
    started = time.perf_counter()
    models = problem.models()
    tilted, smoothing = tilt_transform(problem)

    def passes(poses: PoseTrajectory) -> bool:
        candidate = tilted(poses)
        return screen_ok(problem, linear_screen(models, candidate)) and not machine_violations(
            problem, candidate, True
        )

    best: tuple[float, float, Callable[[float], PoseTrajectory], str] | None = None
    # The curve shaper is not tried: tilting removes the turning forcing it is for (on the
    # series' paths it never gave a faster tilted plan and cost a third more compute).
    for name, shaper in timing_shapers(problem)[:2]:
        found = fastest_capped(problem, passes, shaper)
        if found is None:
            continue
        cap, member = found
        plain = stretcher(problem, member)
        duration = tilted(plain(1.0)).duration_s
        if best is None or duration < best[0]:
            best = (duration, cap, plain, name)
    if best is None:
        failure = lowest_cap_failure(
            problem,
            lambda member: tilted(sample_path(problem.path, member, problem.sample_period_s)),
            True,
        )
        message = f"no tilted timing meets the limits: at the lowest cap, {failure}"
        family = PathCandidate("tilt", None, None, time.perf_counter() - started, message)
    else:
        _, cap, plain, shaper_name = best
        detail = {
            "acceleration_cap_m_s2": cap,
            "tilt_smoothing_s": smoothing,
            "shaper": shaper_name,
            "rotation_centre_height_m": problem.tilt_centre_height_m,
        }
        family = verified_candidate(
            "tilt", problem, lambda f: tilted(plain(f)), 1.0, started, verifier, True, detail
        )
    return improved_tilt(problem, family, seeds, verifier) if improve else family


def improved_tilt(
    problem: PathProblem,
    family: PathCandidate,
    seeds: Sequence[Timing] = (),
    verifier: Verifier = verify,
) -> PathCandidate:
    """The ``tilt`` family candidate improved by the local searches of ``retime`` on the tilted
    export (module docstring), seeded from its own timing and from ``seeds``; never slower than
    ``family``. ``family`` itself when it is infeasible or the move too long for the budget.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    family : PathCandidate
        `plan_tilt`'s candidate without improvement (its compute time is counted in).
    seeds : sequence of Timing
        Other timings of the path (untilted), tilted and slowed until they pass.
    verifier : callable
        Verification of an export.

    Returns
    -------
    PathCandidate
        The fastest verified one; improvements carry ``search`` and, from ``seeds``, ``seed``
        in their detail.

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711; Fletcher (1987) ch. 14 (SLP).

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> from sloshkit.plan.path.retime import family_member
    >>> problem = _example_problem()
    >>> family = plan_tilt(problem, linear_verifier, improve=False)
    >>> slow = family_member(problem, 1.0, None)
    >>> found = improved_tilt(problem, family, [slow], linear_verifier)
    >>> found.feasible, found.duration_s <= family.duration_s
    (True, True)
    """
    started = time.perf_counter() - family.compute_time_s
    if not family.feasible or not ladder_affordable(problem, family.duration_s, TILT_SAMPLE_BUDGET):
        return family
    tilted, smoothing = tilt_transform(problem)
    pool = [(family, method_timing(problem, family, dict(timing_shapers(problem)))[1])]
    detail = {
        "tilt_smoothing_s": smoothing,
        "rotation_centre_height_m": problem.tilt_centre_height_m,
        "seed": "retime",
    }
    for timing in seeds:
        plain = stretcher(problem, timing)

        def poses_for(
            factor: float, plain: Callable[[float], PoseTrajectory] = plain
        ) -> PoseTrajectory:
            return tilted(plain(factor))

        slowed = slowed_until(problem, poses_for, machine_stretch(problem, poses_for(1.0)))
        if slowed is None:
            continue
        found = verified_candidate(
            "tilt", problem, poses_for, slowed[0], started, verifier, True, detail
        )
        if found.feasible:
            pool.append((found, timing.stretched(float(found.detail["stretch"]))))
    chosen = warped_candidates(
        problem, pool, verifier, started, transform=tilted, budget=TILT_SAMPLE_BUDGET
    )
    return replace(chosen, method="tilt")


__all__ = ["TILT_SAMPLE_BUDGET", "improved_tilt", "plan_tilt", "tilt_transform", "timing_shapers"]
