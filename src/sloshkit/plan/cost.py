"""The planner's work, estimated before it starts (bounded time, and why a request is slow).

The searches screen many candidate moves sample by sample on the controller grid: each paper
law on a grid of 400 durations from its machine floor to 4x it, and each shaped S-curve family
on 120 (acceleration, jerk) settings down to 1/1000 of the acceleration limit. Their cost is the
number of pendulum updates: samples x candidates x modes x models of the robustness band. A long
distance, a small acceleration or jerk limit or a short sample period multiply it. `check_cost`
refuses requests above ``SLOSHKIT_MAX_PLAN_WORK`` updates (default `DEFAULT_MAX_WORK`, about
a minute on one core) with the estimate and the parameter that makes it expensive.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from sloshkit.errors import InputError
from sloshkit.plan.problem import PAPER_LAWS, SHAPERS, PlanProblem

#: Environment variable for the largest planner work (pendulum updates).
WORK_VARIABLE = "SLOSHKIT_MAX_PLAN_WORK"

#: Default work limit: about 60 times the seed paper's planning problem.
DEFAULT_MAX_WORK = 5e8

#: Candidates screened per paper law (scan grid) and per shaper (acceleration x jerk grid).
LAW_CANDIDATES = 400
SHAPED_CANDIDATES = 120


@dataclass(frozen=True)
class PlanCost:
    """Estimated planner work.

    Attributes: ``floor_s`` the fastest rest-to-rest move the machine limits allow (a
    trapezoid-like S-curve bound); ``terms`` its parts per parameter [s]; ``samples`` controller
    samples of that move; ``work`` pendulum updates of the whole search.
    """

    floor_s: float
    terms: dict[str, float]
    samples: float
    work: float

    @property
    def dominant(self) -> str:
        """The limit or distance that contributes most to the duration (and so to the work)."""
        return max(self.terms, key=lambda name: self.terms[name])


def work_limit() -> float:
    """The current limit on planner work (``SLOSHKIT_MAX_PLAN_WORK`` or the default)."""
    text = os.environ.get(WORK_VARIABLE)
    if not text:
        return DEFAULT_MAX_WORK
    try:
        value = float(text)
    except ValueError:
        raise InputError(WORK_VARIABLE, text, "must be a number of updates, e.g. 1e9") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(WORK_VARIABLE, text, "must be finite and > 0")
    return value


def _duration_terms(
    distance: float, velocity: float, acceleration: float, jerk: float
) -> dict[str, float]:
    """Parts of a lower bound on the S-curve time: cruise D/v, ramps v/a (or 2 sqrt(D/a) when
    the velocity limit is not reached) and jerk phases a/j (Biagiotti & Melchiorri, Trajectory
    Planning for Automatic Machines and Robots, Springer (2008), sec. 3.4)."""
    if velocity * velocity / acceleration < distance:
        terms = {"distance": distance / velocity, "amax": velocity / acceleration}
    else:
        terms = {"distance": 0.0, "amax": 2.0 * math.sqrt(distance / acceleration)}
    terms["jmax"] = acceleration / jerk
    return terms


def estimate_cost(problem: PlanProblem, method: str = "auto") -> PlanCost:
    """Estimate the work of `sloshkit.plan.planner.plan` for ``problem`` and ``method``.

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model and sample period.
    method : str
        The planner method (``auto``, ``paper``, a law, ``fast``, ``shaped``, ``optimal``).

    Returns
    -------
    PlanCost
        The floor duration, its parts, the samples and the work (pendulum updates).

    References
    ----------
    L. Biagiotti, C. Melchiorri, Trajectory Planning for Automatic Machines and Robots,
    Springer (2008), sec. 3.4 (double-S minimum time).

    Examples
    --------
    >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.problem import MachineLimits, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> problem = PlanProblem(0.5, MachineLimits(1.5, 20, 500), SloshLimits(0.09, 0.004), model)
    >>> estimate_cost(problem).work < DEFAULT_MAX_WORK
    True
    """
    machine = problem.machine
    dt = problem.sample_period_s
    terms = _duration_terms(
        problem.distance_m,
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
    )
    floor = sum(terms.values())
    updates_per_sample = len(problem.model.modes) * len(problem.models())
    work = 0.0
    if method in ("auto", "paper", *PAPER_LAWS):
        laws = len(PAPER_LAWS) if method in ("auto", "paper") else 1
        work += laws * LAW_CANDIDATES * 4.0 * floor / dt
    if method in ("auto", "shaped", "optimal", "fast"):
        shapers = 1 if method == "fast" else len(SHAPERS)
        slowest = sum(
            _duration_terms(
                problem.distance_m,
                machine.max_velocity_m_s,
                1e-3 * machine.max_acceleration_m_s2,
                0.04 * machine.max_jerk_m_s3,
            ).values()
        )
        work += shapers * SHAPED_CANDIDATES * slowest / dt
    return PlanCost(floor, terms, floor / dt, work * updates_per_sample)


def check_cost(problem: PlanProblem, method: str = "auto") -> PlanCost:
    """`estimate_cost`, refusing (`InputError`) work above `work_limit`.

    The message names the parameter that makes the request expensive, the estimate and the
    limit, and says what would make it cheaper.

    Examples
    --------
    >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.problem import MachineLimits, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> far = PlanProblem(1000, MachineLimits(1.5, 20, 500), SloshLimits(0.09, 0.004), model)
    >>> try:
    ...     check_cost(far)
    ... except InputError as error:
    ...     print(error.parameter)
    distance
    """
    cost = estimate_cost(problem, method)
    limit = work_limit()
    if cost.work > limit:
        name = cost.dominant
        shown = {
            "distance": f"{problem.distance_m:.4g} m",
            "amax": f"{problem.machine.max_acceleration_m_s2:.4g} m/s^2",
            "jmax": f"{problem.machine.max_jerk_m_s3:.4g} m/s^3",
        }[name]
        raise InputError(
            name,
            shown,
            f"makes the plan expensive: the fastest move the machine allows lasts "
            f"{cost.floor_s:.4g} s ({cost.samples:,.0f} samples at "
            f"{problem.sample_period_s:.3g} s), and the search would screen about "
            f"{cost.work:.2g} pendulum updates, above the limit {limit:.2g}",
            f"plan the acceleration and braking segments separately, use a longer "
            f"--sample-period or method 'fast', or raise {WORK_VARIABLE}",
        )
    return cost
