"""The fewest export samples whose timing meets every limit of a path program.

At a fixed number N of export samples, sequential cone programs of the spline transcription
(`sloshkit.plan.path.transcription.SplineTranscription.step`) minimise the largest ratio r(N)
of a limited quantity to its limit, from the best timing found so far scaled to N
(`at_duration`). N itself is found by a safeguarded secant iteration on ln r(N) = 0 in ln N: a
ratio scales with the duration as T^-p, so N r^(1/p) is the next guess, p the secant slope
through the last two durations when they are close (near the optimum the slosh ratios fall as
T^-3.3 on pick-and-place), else the order of the binding quantity (1 for a speed, 2 for an
acceleration or a slosh height, 3 for a jerk); the guess is kept strictly inside the bracket of
the smallest N that met every limit and the largest shorter one that did not, else its midpoint
(bisection); after a met duration it is at least the bracket's tolerance shorter (`TOLERANCE`
of N; the first ratio that met the limits bounds the least one from above, and the secant's
step from a ratio just below 1 would creep down a sample at a time). It ends when the bracket
is one sample (or `TOLERANCE` of N) wide (`shortest`), unless the best splines scaled to the
missed N would have met the limits with a margin and that N started from other splines: it is
then tried once more from the best ones (a sample's change of N turns the residual's phases,
and programs from a far start can lose their way). While none has met the limits, a longer
missed duration is tried once more from the start stretched to it, with the first trust region
`FIRST_TRUST`: a missed plan's residual cancels at its own timing only, and the carried region
can be too small. Each duration's programs stop as soon as they decide it: at the first splines
that meet every limit, or when the programs' predicted least ratio stalls above them
(`at_duration`'s ``decide``). Where several quantities tie at the largest ratio, as a min-max
program leaves them, the binding one is the one uniform time scaling would need most
(`sloshkit.plan.path.scaling.binding`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from sloshkit.plan.path.program import ProgramIterate
from sloshkit.plan.path.scaling import EXPONENTS, binding, exponent
from sloshkit.plan.path.splines import SplineTiming, fit_timing
from sloshkit.plan.path.transcription import KNOT_SPACING_S, SplineTranscription

#: The bracket's relative width at which the search over N stops.
TOLERANCE = 5e-3
#: Programs per duration, at most.
ITERATIONS = 8
#: The first trust region, a fraction of the path's length per coefficient; the largest one a
#: duration starts from.
FIRST_TRUST = 0.02
#: With ``decide``, `at_duration` calls N too short when two successive programs, not held
#: back by the trust region, predict a least ratio above 1 + UNMET_MARGIN that fell by less
#: than STALLED (the programs' prediction agrees with the exact ratio to about 1e-3 near the
#: optimum since the drive's linearisation includes N's turn about the axis,
#: `sloshkit.plan.path.axial_turn`).
UNMET_MARGIN = 0.005
STALLED = 0.01
#: With ``decide``, `at_duration` also calls N too short after this many successive rejected
#: steps above 1 + UNMET_MARGIN: the start lies far outside the linearisation (the upright
#: decision below a tilted TRD_2D plan, 27.7 times the limits, spent eight programs shrinking
#: its trust region to 1e-5).
REJECTED = 3
#: Durations tried, at most.
MAX_DURATIONS = 16


@dataclass(frozen=True, eq=False)
class Trial:
    """One duration of the search.

    Parameters
    ----------
    steps : int
        N, the export sample periods.
    excess : float
        The least largest ratio to a limit found at N (when N met the limits, the first
        found below 1; when the programs stalled above them, their prediction).
    binding : str
        The quantity of that ratio.
    programs : int
        The programs solved at N.

    Examples
    --------
    >>> Trial(500, 0.99, "peak slosh", 3).met
    True
    """

    steps: int
    excess: float
    binding: str
    programs: int

    @property
    def met(self) -> bool:
        """Every limit met."""
        return self.excess <= 1.0 + 1e-9


def knot_count(duration_s: float, spacing_s: float = KNOT_SPACING_S) -> int:
    """The number of spline coefficients for a move: knots every ``spacing_s``
    (`sloshkit.plan.path.transcription.KNOT_SPACING_S`).

    Parameters
    ----------
    duration_s : float
        The move's duration [s].
    spacing_s : float
        The knots' spacing [s].

    Returns
    -------
    int
        K, at least 8.

    Examples
    --------
    >>> knot_count(2.0), knot_count(2.0, 0.0125)
    (83, 163)
    """
    return max(8, round(duration_s / spacing_s) + 3)


def respaced(timing: SplineTiming, count: int) -> SplineTiming:
    """A timing refitted with another number of coefficients (least squares on 8 points a
    knot).

    Parameters
    ----------
    timing : SplineTiming
        The timing (and tilt).
    count : int
        K of the result.

    Returns
    -------
    SplineTiming
        ``timing`` itself when it has ``count`` coefficients.

    Examples
    --------
    >>> import numpy as np
    >>> tau = np.linspace(0.0, 1.0, 101)
    >>> timing = fit_timing(tau, tau**2 * (3 - 2 * tau), 20, 100)
    >>> respaced(timing, 10).count
    10
    """
    if count == timing.count:
        return timing
    tau = np.linspace(0.0, 1.0, 8 * max(count, timing.count) + 1)
    return fit_timing(
        tau,
        timing.path_parameter(tau),
        count,
        timing.steps,
        timing.basis(tau) @ timing.tilt_rad,
    )


def at_duration(
    transcription: SplineTranscription,
    timing: SplineTiming,
    iterations: int = ITERATIONS,
    trust: float = FIRST_TRUST,
    log: Callable[[str], Any] | None = None,
    decide: bool = False,
) -> tuple[SplineTiming, ProgramIterate, int, float, float]:
    """The splines of ``timing``'s N whose largest ratio to a limit is least: cone programs
    in a trust region (kept when the exact largest ratio falls by at least a tenth of the
    predicted fall; the region then doubles when the prediction was good, up to 0.2 S, else
    shrinks to 0.4 of the step's size). Stops when a kept step was predicted to gain less than
    0.2 %, or after ``iterations`` programs. With ``decide`` it answers only whether N meets
    the limits, which is all the search over N needs: it stops at the first splines that meet
    them, when two successive programs whose steps stayed well inside the trust region
    (so that the region did not hold them back) predict a least ratio above 1 +
    `UNMET_MARGIN` that fell by less than `STALLED`, and after `REJECTED` successive
    rejected steps above that ratio.

    Parameters
    ----------
    transcription : SplineTranscription
        The program.
    timing : SplineTiming
        The start, on the N to solve.
    iterations : int
        Programs at most.
    trust : float
        The first trust region, a fraction of the path's length per coefficient.
    log : callable, optional
        Receives one line per program.
    decide : bool
        Whether to stop as soon as N is decided (above).

    Returns
    -------
    tuple
        The best splines, their exact iterate (`ProgramIterate`), the programs solved, the
        last trust region (the next duration starts from four times it) and the least largest
        ratio: the iterate's, or, when the programs stalled above the limits, the least of it
        and their prediction.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.program import PathProgram, ProgramLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> program = PathProgram(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model], limits,
    ...                       0.01)
    >>> tau = np.linspace(0.0, 1.0, 101)
    >>> start = fit_timing(tau, 0.1 * tau**3 * (10 - 15 * tau + 6 * tau**2), 10, 45)
    >>> transcription = SplineTranscription(program)
    >>> timing, best, programs, trust, _ = at_duration(transcription, start)
    >>> bool(best.excess < transcription.iterate(start).excess), timing.steps
    (True, 45)
    """
    current = transcription.iterate(timing)
    programs = 0
    stalled: float | None = None
    previous = math.inf
    rejected = 0
    for _ in range(iterations):
        step = transcription.step(timing, current, trust)
        programs += 1
        if step is None:
            trust *= 0.4
            continue
        inside = step.size < 0.5 * trust
        if (
            decide
            and inside
            and step.predicted > 1.0 + UNMET_MARGIN
            and previous > 1.0 + UNMET_MARGIN
            and step.predicted > (1.0 - STALLED) * previous
        ):
            # the linearised least ratio, not held back by the trust region, stalls above the
            # limits: N is too short, by about that ratio
            stalled = min(current.excess, step.predicted)
            break
        previous = step.predicted if inside else math.inf
        if step.size > 0.0:
            trust = min(trust, 1.01 * step.size)
        trial = transcription.iterate(step.timing)
        predicted = current.excess - step.predicted
        actual = current.excess - trial.excess
        if log:
            log(
                f"  N {timing.steps}: ratio {current.excess:.4f} -> {trial.excess:.4f} "
                f"(predicted {step.predicted:.4f}), trust {trust:.3g}"
            )
        if actual > 0.0 and actual >= 0.1 * predicted:
            rejected = 0
            timing, current = step.timing, trial
            if actual >= 0.7 * predicted:
                trust = min(2.0 * trust, 0.2)
            if predicted < 2e-3 or (decide and current.feasible):
                break
        else:
            # a step that made things worse than it promised to improve them was far outside
            # the linearisation's reach
            trust *= 0.15 if -actual > predicted else 0.4
            rejected += 1
            if trust < 1e-5 or (
                decide and rejected >= REJECTED and current.excess > 1.0 + UNMET_MARGIN
            ):
                break
    return timing, current, programs, trust, current.excess if stalled is None else stalled


#: Uniform stretches of the start tried by `stretched_start`: 1.03^k, k = 0..STRETCHES - 1.
STRETCHES = 48


def stretched_start(
    transcription: SplineTranscription, timing: SplineTiming
) -> tuple[SplineTiming, ProgramIterate]:
    """The shortest uniform stretch 1.03^k of a timing whose samples meet every limit (exact
    evaluations only, no program), else the stretch closest to meeting them: the search over
    N then starts from a duration that meets the limits.

    Parameters
    ----------
    transcription : SplineTranscription
        The program (its exact evaluation).
    timing : SplineTiming
        The timing to stretch.

    Returns
    -------
    tuple
        The stretched splines and their exact iterate.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.program import PathProgram, ProgramLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> program = PathProgram(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model], limits,
    ...                       0.01)
    >>> tau = np.linspace(0.0, 1.0, 101)
    >>> fast = fit_timing(tau, 0.1 * tau**3 * (10 - 15 * tau + 6 * tau**2), 10, 20)
    >>> timing, iterate = stretched_start(SplineTranscription(program), fast)
    >>> iterate.feasible, timing.steps > 20
    (True, True)
    """
    best: tuple[SplineTiming, ProgramIterate] | None = None
    for k in range(STRETCHES):
        candidate = timing.on_steps(math.ceil(timing.steps * 1.03**k))
        iterate = transcription.iterate(candidate)
        if best is None or iterate.excess < best[1].excess:
            best = (candidate, iterate)
        if iterate.feasible:
            break
    assert best is not None
    return best


def shortest(
    transcription: SplineTranscription,
    start: SplineTiming,
    log: Callable[[str], Any] | None = None,
    stretch: bool = False,
    give_up: int = MAX_DURATIONS,
    minimise_first: bool = False,
    longest: int | None = None,
) -> tuple[SplineTiming, ProgramIterate, list[Trial]]:
    """The fewest samples whose splines meet every limit (module docstring), from ``start``.

    Parameters
    ----------
    transcription : SplineTranscription
        The program.
    start : SplineTiming
        The first timing; it need not meet the limits.
    log : callable, optional
        Receives one line per program and per duration.
    stretch : bool
        Whether to start from the shortest stretch of ``start`` that meets the limits
        (`stretched_start`) instead of ``start``'s own duration.
    give_up : int
        The search fails when none of its first ``give_up`` durations met the limits.
    minimise_first : bool
        Whether the first duration's programs minimise its largest ratio instead of only
        deciding it: a start that met the limits of another program (the upright plan, for
        a tilted one) has a ratio of about 1, which says nothing of the slack the new
        freedom gives, and the secant's first step is that ratio's.
    longest : int, optional
        The search ends before a longer duration (a plan meeting the limits there is known).

    Returns
    -------
    tuple
        The splines, their exact iterate and the durations tried.

    Raises
    ------
    RuntimeError
        When no duration met the limits.

    Examples
    --------
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> from sloshkit.plan.path.program import PathProgram, ProgramLimits
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> path = sk.path_from_waypoints([[0, 0, 0], [0.1, 0, 0]])
    >>> program, tau = PathProgram(path, [model], limits, 0.01), np.linspace(0.0, 1.0, 101)
    >>> start = fit_timing(tau, 0.1 * tau**3 * (10 - 15 * tau + 6 * tau**2), 10, 60)
    >>> timing, best, trials = shortest(SplineTranscription(program), start)
    >>> best.feasible, timing.steps < 60, trials[-1].steps - trials[-2].steps in (-1, 1)
    (True, True, True)
    """
    trials: list[Trial] = []
    timing = start
    best: tuple[SplineTiming, ProgramIterate] | None = None
    if stretch:
        timing, iterate = stretched_start(transcription, start)
        best = (timing, iterate) if iterate.feasible else None
    # the durations that did not meet the limits, each with the N of the splines it started
    # from
    unmet: dict[int, int] = {}
    steps = timing.steps
    trust = FIRST_TRUST
    for tried in range(MAX_DURATIONS):
        if best is None and tried >= give_up:
            break
        ts = transcription.program.ts
        base = best[0] if best is not None else timing
        region, programs = trust, 0
        while True:
            spacing = transcription.knot_spacing_s
            warm = respaced(base.on_steps(steps), knot_count(steps * ts, spacing))
            decide = not (minimise_first and not tried)
            timing, current, solved, trust, estimate = at_duration(
                transcription, warm, trust=region, log=log, decide=decide
            )
            trust = min(max(4.0 * trust, 1e-3), FIRST_TRUST)
            bound = binding(current.ratios)
            if log:
                how = "again from the start" if programs else f"({steps * ts:.3f} s)"
                log(f"N {steps} {how}: ratio {current.excess:.4f} ({bound})")
            programs += solved
            # while none has met the limits, a longer missed duration is tried again from the
            # start, with the first trust region (module docstring)
            if (
                current.feasible
                or best is not None
                or steps <= start.steps
                or (base.coefficients_m is start.coefficients_m and region == FIRST_TRUST)
            ):
                break
            base, region = start, FIRST_TRUST
        trial = Trial(steps, estimate, bound, programs)
        trials.append(trial)
        if current.feasible:
            if best is None or steps < best[0].steps:
                best = (timing, current)
        else:
            unmet[steps] = base.steps
        highest_met = best[0].steps if best is not None else None
        # a duration longer than one that met the limits did too: its programs lost their way
        lowest_unmet = max((n for n in unmet if highest_met is None or n < highest_met), default=0)
        if highest_met is not None and highest_met - lowest_unmet <= max(
            1, math.floor(TOLERANCE * highest_met)
        ):
            assert best is not None
            if (
                lowest_unmet
                and unmet[lowest_unmet] != highest_met
                and best[1].excess * (highest_met / lowest_unmet) ** 2 < 1.0 - UNMET_MARGIN
            ):
                # the best splines scaled to the unmet N would nearly meet the limits: that N
                # is tried again from them before the search ends
                steps = lowest_unmet
                del unmet[steps]
                continue
            break
        slope = exponent(trials[-2:], EXPONENTS.get(bound, 2.0))
        ratio = min(max(trial.excess, 0.6), 1.6)
        guess = round(steps * ratio ** (1.0 / slope))
        if guess == steps:
            guess = steps + (1 if not trial.met else -1)
        width = max(1, math.floor(TOLERANCE * steps))
        if trial.met and steps - width > lowest_unmet and steps - guess < width:
            # a met duration's ratio is the first that met the limits, an upper bound of the
            # least one at N: a step shorter than the bracket's tolerance would creep down a
            # sample at a time
            guess = steps - width
        upper = highest_met if highest_met is not None else math.inf
        if not lowest_unmet < guess < upper:
            guess = (lowest_unmet + upper) // 2 if upper < math.inf else int(1.25 * steps) + 1
        if longest is not None and guess > longest:
            break
        steps = int(guess)
    if best is None and not trials:
        raise RuntimeError("no duration was tried")
    if best is None:
        raise RuntimeError(
            f"no duration up to {max(t.steps for t in trials) * transcription.program.ts:.3f} s "
            f"met the limits: {trials[-1].binding} at {trials[-1].excess:.3g} times its limit"
        )
    return best[0], best[1], trials


__all__ = [
    "FIRST_TRUST",
    "ITERATIONS",
    "MAX_DURATIONS",
    "REJECTED",
    "STALLED",
    "STRETCHES",
    "TOLERANCE",
    "UNMET_MARGIN",
    "Trial",
    "at_duration",
    "knot_count",
    "respaced",
    "shortest",
    "stretched_start",
]
