"""The polishing of ``retime``'s (and ``tilt``'s) verified timings: the SLP
(`sloshkit.plan.path_slp.slp_search`) with the nonlinear model as its reference, every
accepted step simulated with it, and its successive halving over many seeds (the
continuation of `sloshkit.plan.path_ladder`); the shared budget of screened samples of
`sloshkit.plan.path_improve`, and the export of a timing through an optional pose transform
(``tilt``'s tilt compensation).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from sloshkit.plan.path_limits import machine_violations
from sloshkit.plan.path_result import PathCandidate, Verifier, verify
from sloshkit.plan.path_search import WARP_SAMPLE_BUDGET, stretcher
from sloshkit.plan.path_slp import SLP_KNOTS, slp_search
from sloshkit.plan.spatial import SEARCH_MARGIN, PathProblem, PoseSamples
from sloshkit.plan.timing import Timing

#: Largest number of steps (each a linear screen or a nonlinear simulation) of one polishing.
POLISH_SCREENS = 400

Seeded = tuple[PathCandidate, Timing]
Transform = Callable[[PoseSamples], PoseSamples] | None


def _exporter(
    problem: PathProblem, timing: Timing, transform: Transform
) -> Callable[[float], PoseSamples]:
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

    def machine(poses: PoseSamples) -> bool:
        return not machine_violations(problem, poses, tilted)

    def reference(poses: PoseSamples) -> tuple[float, float]:
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
