"""Minimum-time control on the controller's export grid (linear programs), and a smooth variant.

The linear problem is transcribed exactly on the grid the verification simulates (see
`sloshkit.plan.line.export_grid`), so the move returned meets the limits at every exported sample
without tightening and solving again. For a duration T the longest feasible move D*(T) is one
linear program (one HiGHS model per problem, re-solved from the previous basis with new bounds
and coefficients); the minimum time is the root of D*(T) = D, found by a safeguarded secant on
log D* against log T (the slosh of a time-scaled move grows like 1/T^2, the reach of a
kinematic move like T to T^2), typically in 3 to 5 programs. The move of distance D is the
longest move at that duration scaled by D / D* (every constraint is homogeneous).

The smooth variant (the planner's default) takes a stated small price in time (`SMOOTH_PRICE`)
and spends it on the least total variation of the jerk (sum of |jerk jumps|, a linear program
over the same constraints): a few jerk levels instead of bang-bang chattering, no notches in the
velocity.

Modes: the angle and residual limits concern the first mode only; higher modes enter the
problem only through the wall elevation. Without a wall-elevation limit they are dropped (they
cannot change any constrained quantity); the verification still simulates every mode.

The large-angle (nonlinear) pendulums are planned by `sloshkit.plan.line.optimal_nonlinear`.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

from sloshkit.errors import warn_validity
from sloshkit.motion.laws import s_curve
from sloshkit.motion.profile import Motion, piecewise_constant_jerk
from sloshkit.plan.line.problem import Candidate, PlanProblem, PlanStatus
from sloshkit.plan.line.verification import checked_candidate
from sloshkit.plan.line.work_estimate import duration_floor, optimal_refusal

#: Relative price in time of the smooth variant: its duration is (1 + price) times the minimum.
#: Measured on the paper's vial (0.5 m, 5 deg, 0.25 deg, 4 ms; benchmarks/bench_plan.py), with
#: the slosh checked on the controller grid alone: the time-optimal move's sum of jerk jumps is
#: 275,000 m/s^3 (360 reversals of the acceleration; 13,900 with the 2 ms check grid); at
#: +0.25 % the smooth move's is 4,100 (14), at +0.5 % 3,100 (12; 3,100 with the check grid), at
#: +1 % 2,000 (10), at +2 % 900 (8). Every price from 0.25 % on removes the chattering; 0.5 %
#: is half the 1 % the default move may cost and still leaves jerk at most 0.9 jmax there.
SMOOTH_PRICE = 0.005

#: Longest move the search may try (export samples). Requests whose shortest possible move is
#: already too long for the programs are refused earlier
#: (`sloshkit.plan.line.work_estimate.optimal_refusal`).
MAX_STEPS = 8000

#: The search stops when the longest move at the feasible end of the bracket exceeds the
#: distance by less than this (relative): the duration is then within about half of it of the
#: root.
DISTANCE_TOLERANCE = 4e-5


def exact_grid_for(problem: PlanProblem, steps: int, substeps: int | None = None) -> Any:
    """The `ExportGrid` program of ``problem`` with room for ``steps`` steps, its slosh checked
    on ``substeps`` sub-samples per step (default `sloshkit.plan.line.verification.slosh_substeps`,
    the verification's check grid).

    The first mode of every model of the band carries the angle and residual limits; the
    other modes are kept only when the wall elevation is limited (it sums every mode).

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model, band and sample period.
    steps : int
        Largest number of export steps.
    substeps : int, optional
        Slosh sub-samples per step (1 for the coarse first pass, whose root is only a guess).

    Returns
    -------
    sloshkit.plan.line.export_grid.ExportGrid
        The program, built once, re-solved for every duration up to ``steps`` periods.

    Examples
    --------
    >>> import math
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> problem = PlanProblem(0.1, MachineLimits(1.0, 10.0, 200.0),
    ...     SloshLimits(math.radians(5), math.radians(0.5)), model, 4e-3)
    >>> len(exact_grid_for(problem, 200).pendulums)
    1
    """
    from sloshkit.plan.line.export_grid import ExportGrid, Limits, Pendulum
    from sloshkit.plan.line.verification import slosh_substeps
    from sloshkit.sim.discretisation import velocity_driven_discretisation

    slosh, machine, ts = problem.slosh, problem.machine, problem.sample_period_s
    substeps = slosh_substeps(ts) if substeps is None else substeps
    keep_all = slosh.max_wall_elevation_m is not None
    pendulums = []
    for index, model in enumerate(problem.models()):
        for order, mode in enumerate(model.modes if keep_all else model.modes[:1]):
            phi, gamma, g1 = velocity_driven_discretisation(
                mode.omega_rad_s, mode.damping_ratio, mode.length_m, ts / substeps
            )
            pendulums.append(
                Pendulum(
                    phi,
                    gamma,
                    g1,
                    mode.omega_rad_s,
                    mode.damping_ratio,
                    mode.length_m,
                    mode.wall_elevation_factor_m,
                    order == 0,
                    index,
                )
            )
    limits = Limits(
        problem.distance_m,
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
        slosh.max_angle_rad,
        slosh.max_residual_rad,
        slosh.max_wall_elevation_m,
        ts,
        substeps,
    )
    return ExportGrid(limits, pendulums, steps)


def plan_optimal(
    problem: PlanProblem,
    warm_start: Motion | None = None,
    nonlinear: bool = False,
    intervals: int | None = None,
    smooth: bool = False,
) -> Candidate:
    """Minimum-time move (or its smooth variant) on the export grid, verified.

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model, sample period.
    warm_start : Motion, optional
        A feasible move (e.g. the shaped S-curve): its duration is the first guess.
    nonlinear : bool
        Plan with the large-angle pendulums (`sloshkit.plan.line.optimal_nonlinear`).
    intervals : int, optional
        Only for ``nonlinear``: its number of shooting intervals.
    smooth : bool
        Return the smooth variant ((1 + `SMOOTH_PRICE`) times the minimum time, least total
        variation of the jerk) instead of the time-optimal move.

    Returns
    -------
    Candidate
        ``optimal`` (time-optimal) or ``optimal-smooth``; ``detail`` has ``variant``,
        ``steps``, ``programs`` (linear programs solved), ``simplex_iterations``,
        ``minimum_duration_s`` and ``solver``.

    References
    ----------
    Betts, *Practical Methods for Optimal Control*, 2nd ed., SIAM (2010) ch. 4,
    doi:10.1137/1.9780898718577; Huangfu & Hall, Math. Prog. Comput. 10 (2018) 119-142,
    doi:10.1007/s12532-017-0130-5 (HiGHS dual simplex).

    Examples
    --------
    >>> import math
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> problem = PlanProblem(0.1, MachineLimits(1.0, 10.0, 200.0),
    ...     SloshLimits(math.radians(5), math.radians(0.5)), model, 4e-3)
    >>> best = plan_optimal(problem)
    >>> best.feasible, round(best.duration_s, 2)
    (True, 0.73)
    """
    if nonlinear:
        from sloshkit.plan.line.optimal_nonlinear import plan_optimal_nonlinear

        return plan_optimal_nonlinear(problem, warm_start, True, intervals)
    started = time.perf_counter()
    ts = problem.sample_period_s
    floor = duration_floor(problem)
    refusal = optimal_refusal(problem)
    if refusal is not None:
        warn_validity("optimal method skipped: " + refusal)
        return _failed(started, refusal)
    machine = problem.machine
    if warm_start is None:
        from sloshkit.plan.line.searches import plan_shaped

        warm_start = plan_shaped(problem, ("zv",)).motion
    if warm_start is not None and warm_start.duration_s / ts <= MAX_STEPS:
        guess = warm_start.duration_s
    else:
        kinematic = s_curve(
            problem.distance_m,
            machine.max_velocity_m_s,
            machine.max_acceleration_m_s2,
            machine.max_jerk_m_s3,
        ).duration_s
        guess = max(kinematic, floor.duration_s) * 1.3
    guess = min(guess, MAX_STEPS * ts)
    # A coarse grid first (up to 4 sample periods per step, at least 100 steps: a small fraction
    # of the work per program): its minimum time is within about a percent of the export
    # grid's, so the programs on the export grid start next to the root.
    factor = int(min(4, max(1, guess / ts // 100)))
    programs = iterations = 0
    if factor > 1:
        coarse_problem = replace(problem, sample_period_s=factor * ts)
        coarse = exact_grid_for(coarse_problem, math.ceil(guess / (factor * ts)) + 2, 1)
        found = _minimum_time(coarse, guess, floor.duration_s, 1e-3)
        programs, iterations = coarse.programs, coarse.iterations
        if found is not None:
            guess = found.duration_s
    fastest = None
    for margin in (1.02, 1.5):  # the second only when the first range held no feasible move
        # Room for the smooth variant in both: the same program for both variants, so that
        # the smooth move's price is taken from the very minimum the time-optimal search finds.
        longest = guess * margin * (1 + SMOOTH_PRICE)
        shape = min(MAX_STEPS, math.ceil(longest / ts) + 4)
        grid = exact_grid_for(problem, shape)
        fastest = _minimum_time(grid, guess, floor.duration_s, DISTANCE_TOLERANCE)
        programs, iterations = programs + grid.programs, iterations + grid.iterations
        if fastest is not None or shape == MAX_STEPS:
            break
    if fastest is None:
        return _failed(started, f"no feasible move up to {shape * ts:.4g} s ({shape:,} samples)")
    scale = problem.distance_m / fastest.distance_m
    jerks, last, variant = fastest.jerks_m_s3 * scale, fastest.last_step_s, "time-optimal"
    status = fastest.status
    note = {}
    if smooth:
        duration = fastest.duration_s * (1.0 + SMOOTH_PRICE)
        needed = math.ceil(duration / ts) + 1
        if needed > grid.steps:
            grid = exact_grid_for(problem, needed)
        before = grid.programs, grid.iterations
        smoothed = grid.smoothest(duration)
        # Its warm start (the longest move at that duration) and its own program.
        programs += grid.programs - before[0]
        iterations += grid.iterations - before[1]
        if smoothed is None:
            note = {
                "note": "the smooth program failed its check: the time-optimal move is returned"
            }
        else:
            jerks, last, variant, status = (
                smoothed.jerks_m_s3,
                smoothed.last_step_s,
                "smooth",
                smoothed.status,
            )
    name = "optimal" if variant == "time-optimal" else "optimal-smooth"
    durations = [ts] * (jerks.size - 1) + [last]
    motion = Motion(name, piecewise_constant_jerk(name, durations, list(jerks)).position_pp)
    return checked_candidate(
        name,
        motion,
        problem,
        started,
        variant=variant,
        minimum_duration_s=fastest.duration_s,
        steps=int(jerks.size),
        programs=programs,
        simplex_iterations=iterations,
        solver="HiGHS " + status,
        model="linear",
        **note,
    )


def _minimum_time(grid: Any, guess_s: float, floor_s: float, tolerance: float) -> Any:
    """The longest move at the shortest duration T with D*(T) >= D (or None).

    A safeguarded secant on log D* against log T, bracketed by the infeasible and feasible
    durations found so far; without a lower bracket, the slosh-limited exponent 2 (a time-
    scaled move's slosh grows like 1/T^2) gives the next guess, which lands beyond the root
    whenever the true exponent is smaller. Stops when the feasible end's reach exceeds the
    distance by less than ``tolerance`` (relative) or the bracket is that narrow.
    """
    target = grid.limits.distance_m
    ts = grid.limits.sample_period_s
    longest_s = grid.steps * ts
    low: Any = None
    high: Any = None
    duration = min(guess_s, longest_s)
    for _ in range(40):
        move = grid.longest(duration)
        if move.distance_m >= target:
            high = move if high is None or move.duration_s < high.duration_s else high
        elif low is None or move.duration_s > low.duration_s:
            low = move
        if high is not None and (
            high.distance_m <= target * (1 + tolerance)
            or (low is not None and high.duration_s - low.duration_s <= 1e-6 * high.duration_s)
        ):
            return high
        duration = _next_duration(low, high, target * (1 + 0.5 * tolerance), floor_s, longest_s)
        if duration is None:
            return high
    return high


def _next_duration(low: Any, high: Any, aim: float, floor_s: float, longest_s: float) -> Any:
    """The next duration to try from the bracket, aiming at the reach ``aim`` (None: nothing
    left to try)."""
    if high is None:  # every duration tried so far is too short
        if low.duration_s >= longest_s:
            return None
        reach = max(low.distance_m, 1e-12 * aim)
        return min(longest_s, low.duration_s * min(4.0, (aim / reach) ** 0.5) * 1.001)
    if low is None:
        step = (aim / high.distance_m) ** 0.5
        return max(high.duration_s * step, 0.9 * floor_s, 1e-3 * high.duration_s)
    if low.distance_m <= 0.0:
        return 0.5 * (low.duration_s + high.duration_s)
    # Secant on the logarithms, kept inside the bracket (at least 10 % from either end once
    # the bracket is narrow enough that the secant is nearly exact).
    slope = math.log(high.distance_m / low.distance_m) / math.log(high.duration_s / low.duration_s)
    guess = high.duration_s * (aim / high.distance_m) ** (1.0 / max(slope, 0.5))
    width = high.duration_s - low.duration_s
    return min(max(guess, low.duration_s + 0.02 * width), high.duration_s - 0.02 * width)


def _failed(started: float, message: str) -> Candidate:
    return Candidate(
        "optimal", PlanStatus.FAILED, None, None, time.perf_counter() - started, message
    )
