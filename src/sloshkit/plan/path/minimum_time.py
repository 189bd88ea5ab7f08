"""The minimum time of a path program on the export grid, by sequential second-order-cone
programming (`sloshkit.plan.path.cone.cone_step`, one program of `sloshkit.plan.path.program`).

The minimum time comes from programs whose sample period is a variable too (`_dilated_search`):
first on a grid four times coarser than the export's (programs a quarter the size; a bracketed
search over N finds its start, `_minimum_time`), then on the export's period from that timing
spread by a cubic B-spline, then on the export grid itself (`free_time`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from sloshkit.plan.path.cone import PENALTY, PROGRAM_MARGIN, cone_step
from sloshkit.plan.path.program import PathProgram, ProgramIterate
from sloshkit.plan.path.samples import PathSamples, rescaled, smoothed

#: Relative width of the bracket on N at which the search stops (the smallest feasible N is kept).
SEARCH_TOLERANCE = 2e-3
#: Durations solved per search, at most.
MAX_SEARCH = 14


def _margin_at(
    program: PathProgram,
    start: PathSamples,
    trust: float = 0.1,
    iterations: int = 8,
    tolerance: float = 2e-3,
    enough: float = 0.0,
) -> tuple[ProgramIterate, float]:
    """The samples of N steps (N from ``start``) whose largest ratio to a limit is least:
    cone programs (`cone_step`) from ``start``, a step kept when its exact evaluation is
    better (the trust region then grows by half, else it halves). The residual's own trust
    region halves when its prediction missed the exact residual by more than a quarter of the
    predicted change (and 0.02), else grows by half. Stops when a step gains less than a
    quarter of ``tolerance`` and its prediction was right to ``tolerance``, or as soon as the
    largest ratio is at most ``enough``.
    Returns the best iterate and its largest ratio."""
    current = program.iterate(start)
    residual_trust = 1.0
    for _ in range(iterations):
        if current.excess <= enough:
            break
        step = cone_step(program, current.samples, current.evaluation, trust, residual_trust)
        if step is None:
            trust *= 0.5
            continue
        trial = program.iterate(step.samples)
        before, after = current.ratios["residual slosh"], trial.ratios["residual slosh"]
        if abs(after - step.residual) > max(0.25 * abs(step.residual - before), 0.02):
            residual_trust *= 0.5
        else:
            residual_trust = min(1.5 * residual_trust, 2.0)
        if trial.excess < current.excess:
            gain = current.excess - trial.excess
            current = trial
            trust = min(trust * 1.5, 1.0)
            if (
                gain < 0.25 * tolerance
                and abs(trial.excess - (1.0 - PROGRAM_MARGIN + step.sigma)) < tolerance
            ):
                break
        else:
            trust *= 0.5
            if trust < 1e-3:
                break
    return current, current.excess


def _dilated_search(
    program: PathProgram,
    start: PathSamples,
    iterations: int = 12,
    trust: float = 0.1,
    dilation_trust: float = 0.05,
    tolerance: float = 1e-3,
) -> ProgramIterate:
    """The shortest samples of N steps (N from ``start``) whose period is free: cone programs
    (`cone_step` with ``dilation_trust``) from ``start``, a step kept when its exact merit
    ln h + `PENALTY` max(0, ratio - 1 + `PROGRAM_MARGIN`) falls (the trust regions of the
    speed and of epsilon then grow by half, else they halve). Stops when a kept step shortens
    the period by less than ``tolerance`` with every limit met."""
    keep = 1.0 - PROGRAM_MARGIN

    def merit(iterate: ProgramIterate) -> float:
        return math.log(iterate.samples.period_s) + PENALTY * max(0.0, iterate.excess - keep)

    current = program.iterate(start)
    for _ in range(iterations):
        # the residual's own trust region stays open: the penalty must be able to remove an
        # excess residual, and the merit test rejects a step that mispredicted it
        step = cone_step(program, current.samples, current.evaluation, trust, 1.0, dilation_trust)
        if step is None:
            trust, dilation_trust = 0.5 * trust, 0.5 * dilation_trust
            continue
        trial = program.iterate(step.samples)
        gain = merit(current) - merit(trial)
        if gain > 0.0:
            shortened = current.samples.period_s - trial.samples.period_s
            current = trial
            trust, dilation_trust = min(1.5 * trust, 1.0), min(1.5 * dilation_trust, 0.2)
            if current.feasible and shortened < tolerance * current.samples.period_s:
                break
        else:
            trust, dilation_trust = 0.5 * trust, 0.5 * dilation_trust
            if trust < 1e-3:
                break
    return current


#: Sample period of the first, coarse free-time search [s] (about 20 samples per period of
#: the fundamental mode of a vial; the export grid then refines it).
COARSE_PERIOD_S = 0.016
#: Programs of the coarse grid's free-period search, at most (it ends earlier when a kept step
#: shortens the period by less than 0.1 %: on TRD_2D after 25-40).
COARSE_ITERATIONS = 60
#: Export-grid durations tried after the free-time searches, at most.
EXPORT_TRIES = 4


def _length(iterate: ProgramIterate) -> float:
    """The duration of an iterate's samples [s]."""
    return iterate.samples.steps * iterate.samples.period_s


def free_time(
    program: PathProgram,
    start: PathSamples,
    log: Any = None,
    coarse: bool = True,
    seeds: Sequence[PathSamples] = (),
    longest_s: float = math.inf,
) -> tuple[ProgramIterate, list[tuple[int, float]]] | None:
    """The fewest export samples whose timing meets every limit.

    1. When ``coarse``, on a grid of `COARSE_PERIOD_S` (its programs a quarter the size), or
       on the export's period when that is longer than half of it: the bracketed search over
       N (`_minimum_time`), then the same N with the period free (`_dilated_search`): the
       coarse minimum time. Each of ``seeds`` (verified plans of other methods) gives one more
       coarse minimum, its period free from the seed's own duration, and the shortest
       feasible one goes on (the searches are local: on RD_2D, tilted, the capped timing's
       ends at 5.5 s and ``tilt``'s plan's at 2.8 s).
    2. On the export's period Ts (when step 1 ran on a coarser grid or not at all): that
       timing spread (`smoothed`) over the steps of its
       duration, the period free again (the finer grid sees the higher modes' residual the
       coarse one smooths away).
    3. On the export grid: N, the steps of that duration
       (`sloshkit.motion.sampling.steps_to_reach`); its best margin (`_margin_at`, ended when
       every limit is met with half `PROGRAM_MARGIN` to spare), N increased while a limit is
       still exceeded (at most `EXPORT_TRIES`), each N from the last one's samples.

    Parameters
    ----------
    program : PathProgram
        The problem's model.
    start : PathSamples
        The first timing, on the export grid.
    log : callable, optional
        Receives one line per search.
    coarse : bool
        Whether to start on the coarse grid (False: ``start`` is already near the optimum).
    seeds : sequence of PathSamples
        More starts of the coarse grid's search, on the export grid, each meeting the limits
        (used only when ``coarse``).
    longest_s : float
        A coarse minimum that meets the limits and is longer than this [s] ends the search
        (None is returned): the finer grids would not bring it below a plan already found.

    Returns
    -------
    tuple or None
        The feasible iterate (`ProgramIterate`) and the (N, r) pairs tried on the export grid;
        None when the coarse minimum is longer than ``longest_s``.

    Raises
    ------
    RuntimeError
        When no export-grid duration met the limits.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.program import ProgramLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> program = PathProgram(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model], limits, 0.01)
    >>> t = np.arange(61) / 60  # a quintic rest-to-rest timing of 0.6 s
    >>> start = PathSamples(0.1 * t**3 * (10 - 15 * t + 6 * t**2), np.zeros((61, 2)), 0.01)
    >>> best, tried = free_time(program, start)
    >>> best.feasible, best.samples.steps < 60
    (True, True)
    """
    from sloshkit.motion.sampling import steps_to_reach

    ts = start.period_s
    duration = start.steps * ts
    factor = max(1, int(COARSE_PERIOD_S / ts + 1e-9)) if coarse else 1

    def free(samples: PathSamples, steps: int, iterations: int, trust: float) -> ProgramIterate:
        length = samples.steps * samples.period_s
        spread = smoothed if steps > samples.steps else rescaled
        found = _dilated_search(
            program, spread(samples, steps, length / steps), iterations, trust, 0.5 * trust
        )
        if log:
            log(
                f"free period at N = {steps}: {found.samples.steps * found.samples.period_s:.4f}"
                f" s, largest ratio {found.excess:.4f} ({program.programs} programs)"
            )
        return found

    current = start
    if coarse:
        # the bracket over N first, also when the export's period is the coarse one: the
        # free-period search from the capped timing itself diverges (a 0.27 m corner at
        # 10 ms: no plan up to 5.8 s without the bracket)
        coarse_steps = steps_to_reach(duration, factor * ts)
        found, _ = _minimum_time(program, rescaled(start, coarse_steps, factor * ts), log)
        # the coarse grid's own minimum, its period free
        found = free(found.samples, found.samples.steps, COARSE_ITERATIONS, 0.1)
        for seed in seeds:
            # a verified plan needs no bracket: its period free from its own duration
            other = free(seed, steps_to_reach(seed.steps * ts, factor * ts), COARSE_ITERATIONS, 0.1)
            if other.feasible and (not found.feasible or _length(other) < _length(found)):
                found = other
                if log:
                    log(f"the search from a {seed.steps * ts:.3f} s plan goes on")
        current = found.samples
        if found.feasible and _length(found) > longest_s:
            if log:
                log(f"coarse minimum {_length(found):.4f} s: longer than {longest_s:.4f} s")
            return None
    if factor > 1 or not coarse:
        # on the export's period; it starts near its optimum: a quarter of the trust regions
        duration = current.steps * current.period_s
        found = free(current, steps_to_reach(duration, ts), 8, 0.025)
    current, duration = found.samples, found.samples.steps * found.samples.period_s
    steps = steps_to_reach(duration, ts)
    history: list[tuple[int, float, ProgramIterate]] = []
    for _ in range(EXPORT_TRIES):
        # enough margin that the verification's finer checks pass as well
        iterate, ratio = _margin_at(
            program, rescaled(current, steps, ts), iterations=4, enough=1.0 - 0.5 * PROGRAM_MARGIN
        )
        history.append((steps, ratio, iterate))
        if log:
            log(f"N = {steps}: largest ratio to a limit {ratio:.4f} ({program.programs} programs)")
        if ratio <= 1.0:
            return iterate, [(h[0], h[1]) for h in history]
        current = iterate.samples
        # half the step of r ~ (N0 / N)^2: near r = 1 the margin program, not the duration,
        # is what fell short
        steps += max(1, math.ceil(0.5 * steps * (math.sqrt(ratio) - 1.0)))
    worst = min(history, key=lambda h: h[1])[2]
    binding = max(worst.ratios, key=lambda key: worst.ratios[key])
    raise RuntimeError(f"no timing up to {steps * ts:.3g} s meets the limits (binding: {binding})")


def _minimum_time(
    program: PathProgram, start: PathSamples, log: Any = None
) -> tuple[ProgramIterate, list[tuple[int, float]]]:
    """The fewest steps N whose best samples (`_margin_at`) meet every limit.

    r(N), the largest ratio to a limit, falls about as (N0 / N)^2 when the slosh or the
    acceleration binds: the next N solves r = 1 on the secant of log r against log N through the
    last two, kept inside the bracket of solved N (the largest infeasible, the smallest
    feasible) and within 20 % of the last; the search stops when the bracket is
    `SEARCH_TOLERANCE` wide. Each r(N) starts from the nearest feasible samples rescaled
    (from the start while none is).

    Returns the best feasible iterate and the (N, r) pairs tried; raises `RuntimeError` when
    no N up to four times the start's meets the limits."""
    history: list[tuple[int, float, ProgramIterate]] = []
    steps = start.steps
    guess = start
    for _ in range(MAX_SEARCH):
        steps_now = rescaled(guess, steps)
        iterate, ratio = _margin_at(program, steps_now)
        history.append((steps, ratio, iterate))
        if log:
            log(
                f"N = {steps} of {steps_now.period_s * 1e3:.4g} ms: largest ratio to a limit "
                f"{ratio:.4f} ({program.programs} programs)"
            )
        feasible = [h for h in history if h[1] <= 1.0]
        infeasible = [h for h in history if h[1] > 1.0]
        low = max((h[0] for h in infeasible), default=0)
        high = min((h[0] for h in feasible), default=None)
        if high is not None and high - low <= max(1, int(SEARCH_TOLERANCE * high)):
            break
        if len(history) == 1 or abs(math.log(history[-1][1] / history[-2][1])) < 1e-9:
            target = steps * math.sqrt(ratio)
        else:
            (n1, r1, _), (n2, r2, _) = history[-2], history[-1]
            slope = math.log(r2 / r1) / math.log(n2 / n1)
            target = n2 * (r2 ** (-1.0 / slope) if slope < -0.1 else math.sqrt(r2))
        target = min(max(target, 0.8 * steps), 1.25 * steps)
        new = math.ceil(target)
        upper = high - 1 if high is not None else 4 * start.steps
        new = min(max(new, low + 1), upper)
        if any(h[0] == new for h in history):
            new = (low + upper + 1) // 2
        if any(h[0] == new for h in history) or new > 4 * start.steps:
            break
        # from the nearest feasible samples: stretching an infeasible iterate carries its
        # broken residual along (from none yet, the start stretched)
        solved = [h for h in history if h[1] <= 1.0]
        guess = min(solved, key=lambda h: abs(h[0] - new))[2].samples if solved else start
        steps = new
    feasible = [h for h in history if h[1] <= 1.0]
    if not feasible:
        worst = min(history, key=lambda h: h[1])
        binding = max(worst[2].ratios, key=lambda key: worst[2].ratios[key])
        raise RuntimeError(
            f"no timing up to {max(h[0] for h in history) * program.ts:.3g} s meets the limits "
            f"(binding: {binding})"
        )
    best = min(feasible, key=lambda h: h[0])
    return best[2], [(h[0], h[1]) for h in history]


__all__ = [
    "COARSE_ITERATIONS",
    "COARSE_PERIOD_S",
    "EXPORT_TRIES",
    "MAX_SEARCH",
    "SEARCH_TOLERANCE",
    "free_time",
]
