"""Local improvement of verified ``retime`` timings: the searches of `sloshkit.plan.path.search` and
`sloshkit.plan.path.slp` run from verified seeds, each result verified again.

Two kinds of search are combined (`warped_candidates`):

- **screened chains** (`SEARCH_CHAINS`): the pattern search
  (`sloshkit.plan.path.search.warp_search`) alone, followed by the SLP
  (`sloshkit.plan.path.slp.slp_search`), and after it, under the linear screen, from every
  verified seed;
  the result is verified, and when the nonlinear model exceeds a limit the screen passed, the
  screen's limit is tightened and the chain repeated from the seed slowed until it passes the
  tighter screen (a bounded verify-and-tighten loop);
- **polishing**: the SLP with the nonlinear model as its reference (every accepted step is
  simulated with it and the LP's limits corrected by the gap between the two models), from
  every verified seed and from the fastest verified result of the chains, so each of its steps
  is a verified improvement.

All these searches share one budget of screened samples (`IMPROVE_SAMPLE_BUDGET`, so long
moves get fewer screens; the order above is the order of priority). Then the
**continuation**: seeds found under stricter internal targets and the other methods'
timings of the path (`sloshkit.plan.path.ladder`, which says why: the residual's basins) are
polished against the true limits, by successive halving of their own budget
(`LADDER_SAMPLE_BUDGET`; `ladder_affordable` says when a move is short enough for it). The
fastest verified candidate wins, so ``retime`` is never slower than its seeds.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import replace

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.ladder import targeted
from sloshkit.plan.path.limits import machine_violations
from sloshkit.plan.path.problem import SEARCH_MARGIN, PathProblem
from sloshkit.plan.path.result import PathCandidate, Verifier, verified_candidate, verify
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import (
    WARP_KNOTS,
    WARP_ROUNDS,
    WARP_SAMPLE_BUDGET,
    WARP_SCREENS,
    slowed_until,
    stretcher,
    warp_search,
)
from sloshkit.plan.path.slp import SLP_KNOTS, slp_search
from sloshkit.plan.path.timing import Timing

#: The screened search chains `warped_candidates` runs from every verified seed, each search
#: continued from the previous one's result (``warp8``: the pattern search on 8 coefficients;
#: on the measured series each chain won some cases).
SEARCH_CHAINS: tuple[tuple[str, ...], ...] = (("warp8",), ("warp", "slp"), ("slp", "warp"))
#: Screened samples all searches of one `warped_candidates` share, for moves of up to
#: `IMPROVE_LONG_MOVE` samples; longer moves get fewer, in proportion to the square of
#: their sample count (the 20-waypoint case of the benchmark must plan in under 5 s CPU).
IMPROVE_SAMPLE_BUDGET = 800_000
#: Sample count of a move above which the shared budget shrinks.
IMPROVE_LONG_MOVE = 1500

#: Screened samples the polishing of the ladder's seeds shares (on top of what the searches
#: of `IMPROVE_SAMPLE_BUDGET` left; shrinking like it on long moves).
LADDER_SAMPLE_BUDGET = 800_000
#: Fewest screens of the move the ladder's budget must buy for the continuation to run (on
#: long moves the budget shrinks, and the ladder's seeding alone would cost more).
LADDER_MIN_SCREENS = 100

Seeded = tuple[PathCandidate, Timing]

#: Largest number of steps (each a linear screen or a nonlinear simulation) of one polishing.
POLISH_SCREENS = 400

Transform = Callable[[PoseTrajectory], PoseTrajectory] | None


def _exporter(
    problem: PathProblem, timing: Timing, transform: Transform
) -> Callable[[float], PoseTrajectory]:
    """The export of ``timing`` stretched by a factor, through ``transform`` when given."""
    plain = stretcher(problem, timing)
    if transform is None:
        return plain
    return lambda factor: transform(plain(factor))


def _budget(problem: PathProblem, timing: Timing, most: int, left: list[float]) -> int:
    """Screens one search may spend: at most ``most``, `WARP_SAMPLE_BUDGET` samples and what
    is ``left`` of the shared budget of samples (0 when fewer than 20 screens are left)."""
    samples = timing.duration_s / problem.sample_period_s
    screens = min(most, int(WARP_SAMPLE_BUDGET / samples), int(left[0] / samples))
    return screens if screens >= 20 else 0


def _spend(problem: PathProblem, timing: Timing, screens: int, left: list[float]) -> None:
    """Take ``screens`` screens of ``timing``'s length from the shared budget ``left``."""
    left[0] -= screens * timing.duration_s / problem.sample_period_s


def _polished(
    problem: PathProblem,
    seed: Seeded,
    verifier: Verifier,
    left: list[float],
    transform: Transform = None,
) -> Seeded | None:
    """The SLP from a verified seed with the nonlinear model as its reference (module
    docstring), verified again; None when it found no shorter timing."""
    candidate, timing = seed
    tilted = transform is not None

    def machine(poses: PoseTrajectory) -> bool:
        return not machine_violations(problem, poses, tilted)

    def reference(poses: PoseTrajectory) -> tuple[float, float]:
        check = verify(problem, poses, tilted)
        return check.peak_height_m, check.residual_height_m

    budget = _budget(problem, timing, POLISH_SCREENS, left)
    if not budget:
        return None
    polished, steps = slp_search(
        problem, timing, machine, SLP_KNOTS, budget, SEARCH_MARGIN, reference, transform
    )
    _spend(problem, timing, steps, left)
    if polished is timing:
        return None
    poses = _exporter(problem, polished, transform)(1.0)
    check = verifier(problem, poses, tilted)
    message = "verified" if check.feasible else "violates " + "; ".join(check.violations)
    search = candidate.detail.get("search")
    detail = {
        **candidate.detail,
        "search": "slp-nonlinear" if search is None else f"{search}+slp-nonlinear",
        "polish_steps": steps,
        "stretch": 1.0,
    }
    return PathCandidate(candidate.method, poses, check, 0.0, message, detail), polished


def _halving(
    problem: PathProblem, entrants: list[Seeded], verifier: Verifier, left: list[float]
) -> list[Seeded]:
    """Successive halving of the polishing over ``entrants`` (Jamieson & Talwalkar 2016): each
    round polishes every entrant from its latest result with an equal share of its part of
    ``left`` and keeps the faster half (at least one) for the next round, whose entrants get
    twice the share; a round's part is what is left over the rounds still to run, weighted
    equally."""
    found: list[Seeded] = []
    rounds = max(1, math.ceil(math.log2(max(len(entrants), 1))) + 1)
    for round_ in range(rounds):
        if not entrants:
            break
        share = left[0] / (rounds - round_) / len(entrants)
        latest = []
        for entrant in entrants:
            part = [share]
            polished = _polished(problem, entrant, verifier, part)
            left[0] -= share - part[0]
            if polished is not None and polished[0].feasible:
                found.append(polished)
                entrant = polished
            latest.append(entrant)
        latest.sort(key=lambda item: item[0].duration_s)
        entrants = latest[: max(1, len(latest) // 2)]
    return found


def _listed(found: Seeded | None) -> list[Seeded]:
    return [] if found is None else [found]


def _chain(
    problem: PathProblem,
    seed: Timing,
    passes: Callable[[PoseTrajectory], bool],
    chain: tuple[str, ...],
    budget: int,
    transform: Transform = None,
) -> tuple[Timing, int]:
    """Run the searches of ``chain`` in turn, each from the previous one's result (``warp`` or
    ``slp``, optionally followed by the number of warp coefficients, e.g. ``warp8``)."""
    screens = 0
    timing = seed

    def screened(poses: PoseTrajectory) -> bool:
        return passes(poses if transform is None else transform(poses))

    for search in chain:
        if search.startswith("slp"):
            knots = int(search[3:] or SLP_KNOTS)
            timing, spent = slp_search(problem, timing, passes, knots, budget, transform=transform)
        else:
            knots = int(search[4:] or WARP_KNOTS)
            timing, spent = warp_search(problem, timing, screened, knots, budget)
        screens += spent
    return timing, screens


def _tightened(limit: float, current: float, nonlinear: float, screen: float) -> float:
    """The screen's next limit when the nonlinear model gave ``nonlinear`` against the screen's
    ``screen`` (``current`` the screen's limit so far, ``limit`` the true one, 2 % kept): the
    mean of the limit scaled by the excess and the limit lowered by the gap between the two
    models (for the residual of large slosh the gap is nearly additive, so scaling alone takes
    several rounds), not below half the scaled one; unchanged when the limit holds."""
    target = 0.98 * limit
    if nonlinear <= target:
        return current
    scaled = current * target / nonlinear
    shifted = (target - nonlinear + screen) / (1.0 - SEARCH_MARGIN)
    return min(current, max(0.5 * (scaled + shifted), 0.5 * scaled))


def _screened(
    problem: PathProblem,
    seed: Seeded,
    chain: tuple[str, ...],
    verifier: Verifier,
    best: float,
    started: float,
    left: list[float],
    transform: Transform = None,
) -> list[Seeded]:
    """The verified results of one screened chain from one seed, with the verify-and-tighten
    rounds (module docstring); the last failing improvement slowed uniformly when every round
    fails (`sloshkit.plan.path.result.verified_candidate`)."""
    models = problem.models()
    candidate, timing = seed
    peak, residual_share = candidate.detail.get("target", (1.0, 1.0))
    limits = targeted(problem, (peak, residual_share)).slosh
    height, residual = limits.max_height_m, limits.max_residual_height_m
    results: list[Seeded] = []
    improved: tuple[Timing, int] | None = None
    tilted = transform is not None
    for _ in range(WARP_ROUNDS):
        budget = _budget(problem, timing, WARP_SCREENS, left)
        if not budget:
            break
        tight = replace(
            problem, slosh=replace(limits, max_height_m=height, max_residual_height_m=residual)
        )

        def passes(poses: PoseTrajectory, tight: PathProblem = tight) -> bool:
            return screen_ok(tight, linear_screen(models, poses)) and not machine_violations(
                problem, poses, tilted
            )

        start = timing
        if (height, residual) != (limits.max_height_m, limits.max_residual_height_m):
            # A tightened screen: start from the seed slowed uniformly until it passes.
            slowed = slowed_until(tight, _exporter(problem, timing, transform))
            if slowed is None:
                break
            start = timing.stretched(slowed[0])
        warped, screens = _chain(tight, start, passes, chain, budget, transform)
        _spend(problem, timing, screens, left)
        if warped is start or warped.duration_s >= best:
            break
        poses = _exporter(problem, warped, transform)(1.0)
        check = verifier(problem, poses, tilted)
        message = "verified" if check.feasible else "violates " + "; ".join(check.violations)
        detail = {**candidate.detail, "warp_screens": screens, "search": "+".join(chain)}
        detail["stretch"] = 1.0
        results.append(
            (PathCandidate(candidate.method, poses, check, 0.0, message, detail), warped)
        )
        if check.feasible:
            return results
        improved = (warped, screens)
        # The nonlinear model exceeds what the screen predicted: tighten the screen's limit
        # and search again.
        screen = linear_screen(models, poses)
        tighter = (
            _tightened(limits.max_height_m, height, check.peak_height_m, screen.peak_height_m),
            _tightened(
                limits.max_residual_height_m,
                residual,
                check.residual_height_m,
                screen.residual_height_m,
            ),
        )
        if tighter == (height, residual):
            break
        height, residual = tighter
    if improved is not None:
        detail = {**candidate.detail, "warp_screens": improved[1], "search": "+".join(chain)}
        poses_for = _exporter(problem, improved[0], transform)
        found = verified_candidate(
            candidate.method, problem, poses_for, 1.0, started, verifier, tilted, detail
        )
        results.append((found, improved[0].stretched(float(found.detail["stretch"]))))
    return results


def warped_candidates(
    problem: PathProblem,
    pool: Sequence[Seeded],
    verifier: Verifier,
    started: float,
    chains: Sequence[tuple[str, ...]] | None = None,
    polish: bool = True,
    ladder: Sequence[Seeded] = (),
    transform: Transform = None,
    budget: float | None = None,
) -> PathCandidate:
    """The fastest of verified candidates and of their improvements (module docstring): the
    screened chains (`SEARCH_CHAINS`) from every verified seed of ``pool`` and with ``polish``
    the nonlinear-referenced SLP from each of them and from the chains' fastest result, then
    the polishing of the ``ladder``'s seeds by successive halving. Every result is verified
    against the true limits. Never slower than the fastest feasible candidate of ``pool``
    and ``ladder``.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    pool : sequence of (PathCandidate, Timing)
        Verified candidates (at least one) and the timings of their exports.
    verifier : callable
        Verification of an export.
    started : float
        ``time.perf_counter()`` when the method started.
    chains : sequence of tuple of str, optional
        The screened searches run in turn (``"warp"``, ``"slp"``; default `SEARCH_CHAINS`).
    polish : bool
        Also run the SLP with the nonlinear model as its reference.
    ladder : sequence of (PathCandidate, Timing)
        Further verified seeds (`sloshkit.plan.path.ladder.ladder_seeds`), polished with
        ``polish`` on their own budget (`LADDER_SAMPLE_BUDGET`, and what the searches above
        left).
    transform : callable, optional
        PoseTrajectory -> PoseTrajectory turning a sampled timing into the export (e.g. ``tilt``'s
        tilt compensation, `sloshkit.plan.path.tilt`): every search screens, and every
        verification checks, the transformed poses, with the tilt limit when given.
    budget : float, optional
        Screened samples the searches share (default `IMPROVE_SAMPLE_BUDGET`).

    Returns
    -------
    PathCandidate
        The fastest feasible one (the fastest at all when none is feasible); improvements carry
        ``search`` (which searches made them) and ``warp_screens`` or ``polish_steps`` in
        their detail.

    References
    ----------
    Hooke & Jeeves (1961), doi:10.1145/321062.321069; Fletcher (1987) ch. 14 (SLP).

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> from sloshkit.plan.path.search import stretcher
    >>> from sloshkit.plan.path.retime import family_member
    >>> problem = _example_problem()
    >>> slow = family_member(problem, 0.5, None).stretched(2.0)
    >>> seed = verified_candidate("retime", problem, stretcher(problem, slow), 1.0,
    ...                           time.perf_counter(), linear_verifier, False, {})
    >>> found = warped_candidates(problem, [(seed, slow)], linear_verifier, time.perf_counter(),
    ...                           chains=(("warp",),), polish=False)
    >>> found.feasible, found.duration_s < seed.duration_s
    (True, True)
    """
    chosen = fastest_improved(
        problem, pool, verifier, started, chains, polish, ladder, transform, budget
    )[0]
    return replace(chosen, compute_time_s=time.perf_counter() - started)


def fastest_improved(
    problem: PathProblem,
    pool: Sequence[Seeded],
    verifier: Verifier,
    started: float,
    chains: Sequence[tuple[str, ...]] | None = None,
    polish: bool = True,
    ladder: Sequence[Seeded] = (),
    transform: Transform = None,
    budget: float | None = None,
) -> Seeded:
    """`warped_candidates` with the timing of the chosen candidate's export (before
    ``transform``).

    Parameters
    ----------
    problem, pool, verifier, started, chains, polish, ladder, transform, budget
        As for `warped_candidates`.

    Returns
    -------
    tuple
        (the chosen PathCandidate, its Timing).

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> from sloshkit.plan.path.search import stretcher
    >>> from sloshkit.plan.path.retime import family_member
    >>> problem = _example_problem()
    >>> slow = family_member(problem, 0.5, None).stretched(2.0)
    >>> seed = verified_candidate("retime", problem, stretcher(problem, slow), 1.0,
    ...                           time.perf_counter(), linear_verifier, False, {})
    >>> found, timing = fastest_improved(problem, [(seed, slow)], linear_verifier,
    ...                                  time.perf_counter(), (("warp",),), False)
    >>> timing.duration_s < slow.duration_s
    True
    """
    results: list[Seeded] = [*pool, *ladder]
    seeds = sorted((item for item in pool if item[0].feasible), key=lambda item: item[0].duration_s)
    chains = chains or SEARCH_CHAINS

    def fastest() -> float:
        return min(found.duration_s for found, _ in results if found.feasible)

    samples = seeds[0][1].duration_s / problem.sample_period_s if seeds else 1.0
    shrink = min(1.0, IMPROVE_LONG_MOVE / samples) ** 2
    left = [(IMPROVE_SAMPLE_BUDGET if budget is None else budget) * shrink]
    for seed in seeds:
        if polish:
            results += _listed(_polished(problem, seed, verifier, left, transform))
        for chain in chains:
            results += _screened(
                problem, seed, chain, verifier, fastest(), started, left, transform
            )
    if polish:
        names = {"+".join(chain) for chain in chains}
        chained = [
            item for item in results if item[0].feasible and item[0].detail.get("search") in names
        ]
        if chained:
            best = min(chained, key=lambda item: item[0].duration_s)
            results += _listed(_polished(problem, best, verifier, left, transform))
        # The continuation: polish every seed of the ladder (stricter targets, other methods'
        # timings) against the true limits, with equal shares of its own budget.
        others = sorted(
            (item for item in ladder if item[0].feasible), key=lambda item: item[0].duration_s
        )
        left[0] += LADDER_SAMPLE_BUDGET * shrink
        results += _halving(problem, others, verifier, left)
    feasible = [item for item in results if item[0].feasible]
    chosen = min(feasible or results, key=lambda item: item[0].duration_s)
    return replace(chosen[0], compute_time_s=time.perf_counter() - started), chosen[1]


def ladder_affordable(problem: PathProblem, duration_s: float, budget: float | None = None) -> bool:
    """Whether the continuation (`sloshkit.plan.path.ladder.ladder_seeds`,
    `LADDER_SAMPLE_BUDGET`) runs for a move of
    about ``duration_s``: its budget, shrunk like `IMPROVE_SAMPLE_BUDGET` above
    `IMPROVE_LONG_MOVE` samples, must buy `LADDER_MIN_SCREENS` screens of the move.

    Parameters
    ----------
    problem : PathProblem
        Sample period.
    duration_s : float
        Duration of the move [s].
    budget : float, optional
        The screened samples (default `LADDER_SAMPLE_BUDGET`; ``tilt`` passes its own).

    Returns
    -------
    bool

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> problem = _example_problem()  # a 10 ms sample period
    >>> ladder_affordable(problem, 2.0), ladder_affordable(problem, 60.0)
    (True, False)
    """
    samples = max(duration_s / problem.sample_period_s, 1.0)
    shrink = min(1.0, IMPROVE_LONG_MOVE / samples) ** 2
    budget = LADDER_SAMPLE_BUDGET if budget is None else budget
    return budget * shrink / samples >= LADDER_MIN_SCREENS


__all__ = [
    "IMPROVE_LONG_MOVE",
    "IMPROVE_SAMPLE_BUDGET",
    "LADDER_MIN_SCREENS",
    "LADDER_SAMPLE_BUDGET",
    "POLISH_SCREENS",
    "SEARCH_CHAINS",
    "fastest_improved",
    "ladder_affordable",
    "warped_candidates",
]
