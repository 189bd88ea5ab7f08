"""Minimum-time control on the controller's export grid (casadi/IPOPT), and a smooth variant.

The linear problem is transcribed exactly on the grid the verification simulates (see
`sloshkit.plan.export_grid`), so the move IPOPT returns meets the limits at every exported
sample without tightening and solving again. The number of steps is searched with the margin
problem (the largest uniform margin from every limit, a convex problem, bracketed by a secant
on the number of steps), then the last step is shortened to the minimum time. The smooth
variant takes a stated small price in time (`SMOOTH_PRICE`) and spends it on the least
integrated squared jerk rate: no bang-bang jerk, no notches in the velocity.

Modes: the angle and residual limits concern the first mode only; higher modes enter the
problem only through the wall elevation. Without a wall-elevation limit they are dropped (they
cannot change any constrained quantity); the verification still simulates every mode.

The large-angle (nonlinear) pendulums are planned by `sloshkit.plan.optimal_nonlinear`.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

import numpy as np

from sloshkit.motion.laws import s_curve
from sloshkit.motion.profile import Motion, _piecewise_constant_jerk
from sloshkit.plan.problem import Candidate, PlanProblem, PlanStatus
from sloshkit.plan.verification import _candidate

#: Relative price in time of the smooth variant: its duration is (1 + price) times the minimum.
SMOOTH_PRICE = 0.02

#: Largest shape planned at once (steps); longer moves fall back to a coarser grid is not done:
#: the search reports failure instead.
MAX_STEPS = 4000


def exact_grid_for(problem: PlanProblem, steps: int) -> Any:
    """The `ExactGrid` solver of ``problem`` with room for ``steps`` steps (mode-1 pendulums
    of every model of the band, all modes when the wall elevation is limited)."""
    from sloshkit.plan.export_grid import ExactGrid, Limits, Pendulum
    from sloshkit.sim.discretisation import velocity_driven_discretisation

    slosh, machine, ts = problem.slosh, problem.machine, problem.sample_period_s
    models = problem.models()
    keep_all = slosh.max_wall_elevation_m is not None
    pendulums = []
    for model in models:
        for mode in model.modes if keep_all else model.modes[:1]:
            phi, gamma, g1 = velocity_driven_discretisation(
                mode.omega_rad_s, mode.damping_ratio, mode.length_m, ts
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
    )
    return ExactGrid(limits, pendulums, len(models), steps)


def _shape(steps: int) -> int:
    """Round a shape up (to a power of two times 1, 1.25, 1.5 or 1.75) so that problems of
    similar duration share one compiled solver."""
    power = 2 ** max(4, math.floor(math.log2(max(steps, 1))) - 2)
    return int(power * math.ceil(steps / power))


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
        A feasible move (e.g. the shaped S-curve): its duration brackets the search.
    nonlinear : bool
        Plan with the large-angle pendulums (`sloshkit.plan.optimal_nonlinear`).
    intervals : int, optional
        Only for ``nonlinear``: its number of shooting intervals.
    smooth : bool
        Return the smooth variant ((1 + `SMOOTH_PRICE`) times the minimum time, least squared
        jerk rate) instead of the time-optimal move.

    Returns
    -------
    Candidate
        ``optimal`` (time-optimal) or ``optimal-smooth``; ``detail`` has ``variant``,
        ``steps``, ``solves``, ``minimum_duration_s`` and IPOPT's status.

    References
    ----------
    Betts, *Practical Methods for Optimal Control*, 2nd ed., SIAM (2010) ch. 4,
    doi:10.1137/1.9780898718577.

    Examples
    --------
    >>> import math
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.problem import MachineLimits, PlanProblem, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> problem = PlanProblem(0.1, MachineLimits(1.0, 10.0, 200.0),
    ...     SloshLimits(math.radians(5), math.radians(0.5)), model, 4e-3)
    >>> best = plan_optimal(problem)
    >>> best.feasible, round(best.duration_s, 2)
    (True, 0.73)
    """
    if nonlinear:
        from sloshkit.plan.optimal_nonlinear import plan_optimal_nonlinear

        return plan_optimal_nonlinear(problem, warm_start, True, intervals)
    started = time.perf_counter()
    try:
        import casadi  # noqa: F401
    except ImportError:  # pragma: no cover - casadi is a dependency
        return Candidate(
            "optimal", PlanStatus.FAILED, message="casadi is not installed: pip install casadi"
        )
    from sloshkit.plan.export_grid import steps_for_duration

    machine, ts = problem.machine, problem.sample_period_s
    if warm_start is None:
        from sloshkit.plan.searches import plan_shaped

        warm_start = plan_shaped(problem, ("zv",)).motion
    kinematic = s_curve(
        problem.distance_m,
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
    ).duration_s
    upper = warm_start.duration_s if warm_start is not None else 4.0 * kinematic
    # A coarse grid (a few times the sample period) first: its minimum time is a cheap and
    # close guess of the number of steps on the export grid.
    factor = int(np.clip(steps_for_duration(upper, ts)[0] // 80, 1, 4))
    guess_s = upper
    solves = 0
    if factor > 1:
        coarse_problem = replace(problem, sample_period_s=factor * ts)
        coarse_steps = steps_for_duration(upper, factor * ts)[0] + 1
        coarse = exact_grid_for(coarse_problem, _shape(coarse_steps + 2))
        found, count = _search(coarse, math.floor(0.9 * coarse_steps))
        solves += count
        if found is not None:
            guess_s = found.duration_s
    steps = steps_for_duration(guess_s, ts)[0]
    shape = _shape(math.ceil(max(steps * (1.0 + 2 * SMOOTH_PRICE), steps + 8)))
    if shape > MAX_STEPS:
        return _failed(started, f"the move needs more than {MAX_STEPS} samples")
    grid = exact_grid_for(problem, shape)
    fastest, count = _search(grid, steps - 1 if factor > 1 else math.floor(0.9 * steps))
    solves += count
    if fastest is None:
        return _failed(started, "no feasible number of steps found")
    chosen, variant = fastest, "time-optimal"
    if smooth:
        steps, last = steps_for_duration(fastest.duration_s * (1.0 + SMOOTH_PRICE), ts)
        smoothed = grid.solve(steps, "smooth", last_step_s=last)
        solves += 1
        if smoothed.success:
            chosen, variant = smoothed, "smooth"
    name = "optimal" if variant == "time-optimal" else "optimal-smooth"
    count = chosen.jerks_m_s3.size
    durations = [ts] * (count - 1) + [chosen.last_step_s]
    motion = Motion(
        name, _piecewise_constant_jerk(name, durations, list(chosen.jerks_m_s3)).position_pp
    )
    return _candidate(
        name,
        motion,
        problem,
        started,
        variant=variant,
        minimum_duration_s=fastest.duration_s,
        steps=count,
        solves=solves,
        ipopt_status=chosen.status,
        model="linear",
    )


def _search(grid: Any, steps: int) -> tuple[Any, int]:
    """The shortest move on ``grid``: (its solution or None, number of solves).

    A "time" solve at N steps either finds the shortest last step (done), needs no last step
    at all (the move fits in fewer steps) or violates the limits by a relative slack s (too
    few steps; the slosh of a time-scaled move grows like 1/T^2, so sqrt(1 + s) times as many
    steps is the next guess).
    """
    from sloshkit.plan.export_grid import SAFETY_MARGIN

    tried: dict[int, Any] = {}
    shape, ts = grid.steps, grid.limits.sample_period_s
    steps = int(np.clip(steps, 2, shape))
    for _ in range(16):
        if steps not in tried:
            tried[steps] = grid.solve(steps, "time")
        result = tried[steps]
        if not result.success and result.slack <= 0:
            return None, len(tried)
        if result.slack > SAFETY_MARGIN:  # too few steps
            if steps == shape:
                return None, len(tried)
            above = [k for k, r in tried.items() if k > steps and r.slack <= 0]
            if steps + 1 in above:
                return tried[steps + 1], len(tried)
            grown = math.ceil(steps * math.sqrt(1.0 + result.slack))
            steps = min(min(above, default=shape), max(steps + 1, grown))
        elif result.last_step_s <= 1e-6 * ts:  # the move fits in fewer steps
            below = [k for k, r in tried.items() if k < steps and r.slack > SAFETY_MARGIN]
            if steps - 1 in below:
                return result, len(tried)
            floor = max(below, default=math.floor(0.8 * steps))
            steps = max(floor + 1, min(steps - 1, (floor + steps) // 2))
        else:
            return result, len(tried)
    return None, len(tried)


def _failed(started: float, message: str) -> Candidate:
    return Candidate(
        "optimal", PlanStatus.FAILED, None, None, time.perf_counter() - started, message
    )
