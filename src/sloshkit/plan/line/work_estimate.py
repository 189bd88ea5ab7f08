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
from sloshkit.plan.line.problem import PAPER_LAWS, SHAPERS, PlanProblem

#: Environment variable for the largest planner work (pendulum updates).
WORK_VARIABLE = "SLOSHKIT_MAX_PLAN_WORK"

#: Default work limit: about 60 times the seed paper's planning problem.
DEFAULT_MAX_WORK = 5e8

#: Environment variable for the largest optimal-method program (samples x pendulums).
OPTIMAL_WORK_VARIABLE = "SLOSHKIT_MAX_OPTIMAL_WORK"

#: Default limit of the optimal method: samples of the shortest possible move times the
#: pendulums of its program. The programs' cost grows faster than their size: 830 samples x 3
#: pendulums take about 1 s, 3,824 x 1 about 13 s; the bound below is about 0.7 of the
#: minimum time, so 2,200 keeps the optimal method within a few seconds.
DEFAULT_MAX_OPTIMAL_WORK = 2200.0

#: The CLI's default controller period [s]: a shorter one is named when it is what makes the
#: optimal method expensive.
DEFAULT_SAMPLE_PERIOD_S = 4e-3

#: Candidates screened per paper law (scan grid) and per shaper (acceleration x jerk grid).
LAW_CANDIDATES = 400
SHAPED_CANDIDATES = 120


@dataclass(frozen=True)
class PlanCost:
    """Estimated planner work.

    Parameters
    ----------
    floor_s : float
        Lower bound on the move duration (`duration_floor`: the machine's S-curve bound or
        the slosh bound, whichever is larger) [s].
    terms : dict of str to float
        Its parts per option [s].
    samples : float
        Controller samples of that move.
    work : float
        Pendulum updates of the whole search.

    Returns
    -------
    PlanCost

    Examples
    --------
    >>> PlanCost(1.0, {"distance": 0.7, "amax": 0.3}, 250.0, 1e6).dominant
    'distance'
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
    """The current limit on planner work (``SLOSHKIT_MAX_PLAN_WORK`` or the default).

    Returns
    -------
    float
        Pendulum updates.

    Examples
    --------
    >>> work_limit() > 0
    True
    """
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


@dataclass(frozen=True)
class DurationFloor:
    """A lower bound on the duration of any move that meets the limits.

    Parameters
    ----------
    duration_s : float
        The bound [s]: the larger of the machine's and the slosh limits' bounds.
    terms : dict of str to float
        Each bound [s] by the limit that sets it (``distance``, ``amax``, ``jmax`` for the
        machine, ``max_angle`` for the slosh).

    Returns
    -------
    DurationFloor

    Examples
    --------
    >>> DurationFloor(2.0, {"max_angle": 2.0, "amax": 0.1}).dominant
    'max_angle'
    """

    duration_s: float
    terms: dict[str, float]

    @property
    def dominant(self) -> str:
        """The option that sets the bound."""
        return max(self.terms, key=lambda name: self.terms[name])

    def shown(self, problem: PlanProblem) -> str:
        """The dominant option's value with its unit, as the CLI takes it.

        Parameters
        ----------
        problem : PlanProblem
            The problem the bound belongs to.

        Returns
        -------
        str
            E.g. ``0.05 deg``.

        Examples
        --------
        >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
        >>> from sloshkit.plan.line.problem import MachineLimits, SloshLimits
        >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
        >>> problem = PlanProblem(0.5, MachineLimits(1.5, 20, 500), SloshLimits(1e-3, 1e-4),
        ...                       model)
        >>> duration_floor(problem).shown(problem)
        '0.0573 deg'
        """
        return _shown(self.dominant, problem)


def _shown(name: str, problem: PlanProblem) -> str:
    return {
        "distance": f"{problem.distance_m:.4g} m",
        "amax": f"{problem.machine.max_acceleration_m_s2:.4g} m/s^2",
        "jmax": f"{problem.machine.max_jerk_m_s3:.4g} m/s^3",
        "max_angle": f"{math.degrees(problem.slosh.max_angle_rad):.4g} deg",
    }[name]


def slosh_floor_s(problem: PlanProblem) -> float:
    """Lower bound on the duration of a move whose first-mode angle stays within the limit.

    Integrating the linear pendulum theta'' + 2 zeta w theta' + w^2 theta = -x'' / L twice
    from rest gives, at the end of the move (x = D, rest),
    D / L = -theta(T) - 2 zeta w int theta dt - w^2 int (T - s) theta(s) ds, so with
    |theta| <= theta_max during the move and |theta(T)| <= the residual limit r:
    D / L <= r + 2 zeta w theta_max T + w^2 theta_max T^2 / 2. The bound is the positive root
    (the largest over the models of the robustness band). The angle is limited at the
    controller's samples only, so a sampled move can beat it by a fraction of (w Ts)^2 / 8.
    It is the quasi-static bound a = g theta_max (w^2 L = g) held over the whole move, within
    a factor sqrt(2): a slow move's slosh cannot be below what its mean acceleration needs.

    Parameters
    ----------
    problem : PlanProblem
        Distance, slosh limits, model and band.

    Returns
    -------
    float
        The bound [s] (0 when the residual limit alone allows the distance).

    References
    ----------
    Ibrahim, *Liquid Sloshing Dynamics*, Cambridge (2005) ch. 3 (the equivalent pendulum);
    the double integration is elementary.

    Examples
    --------
    >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import MachineLimits, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> tight = PlanProblem(0.5, MachineLimits(1.5, 20, 500),
    ...                     SloshLimits(math.radians(0.05), math.radians(0.001)), model)
    >>> round(slosh_floor_s(tight), 1)
    10.8
    """
    slosh = problem.slosh
    floor = 0.0
    for model in problem.models():
        mode = model.modes[0]
        w, zeta = mode.omega_rad_s, mode.damping_ratio
        need = problem.distance_m / mode.length_m - slosh.max_residual_rad
        if need <= 0.0:
            continue
        a, b = w * w * slosh.max_angle_rad / 2.0, 2.0 * zeta * w * slosh.max_angle_rad
        floor = max(floor, (-b + math.sqrt(b * b + 4.0 * a * need)) / (2.0 * a))
    return floor


def duration_floor(problem: PlanProblem) -> DurationFloor:
    """The larger of the machine's and the slosh limits' lower bounds on the move duration.

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits and model.

    Returns
    -------
    DurationFloor
        The bound and its parts (the machine's parts add up: see `_duration_terms`).

    Examples
    --------
    >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import MachineLimits, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> problem = PlanProblem(0.5, MachineLimits(1.5, 20, 500),
    ...                       SloshLimits(math.radians(0.05), math.radians(0.001)), model)
    >>> duration_floor(problem).dominant
    'max_angle'
    """
    machine = problem.machine
    terms = _duration_terms(
        problem.distance_m,
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
    )
    slosh = slosh_floor_s(problem)
    if slosh > sum(terms.values()):
        return DurationFloor(slosh, {**dict.fromkeys(terms, 0.0), "max_angle": slosh})
    return DurationFloor(sum(terms.values()), {**terms, "max_angle": slosh})


def estimate_cost(problem: PlanProblem, method: str = "auto") -> PlanCost:
    """Estimate the work of `sloshkit.plan.line.planner.plan` for ``problem`` and ``method``.

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
    >>> from sloshkit.plan.line.problem import MachineLimits, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> problem = PlanProblem(0.5, MachineLimits(1.5, 20, 500), SloshLimits(0.09, 0.004), model)
    >>> estimate_cost(problem).work < DEFAULT_MAX_WORK
    True
    """
    machine = problem.machine
    dt = problem.sample_period_s
    bound = duration_floor(problem)
    floor, terms = bound.duration_s, bound.terms
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
    limit, and says what would make it cheaper. With ``method="optimal"``, `optimal_refusal`
    is raised too.

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model and sample period.
    method : str
        The planner method.

    Returns
    -------
    PlanCost
        The estimate, when within the limits.

    Examples
    --------
    >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import MachineLimits, SloshLimits
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
    if method == "optimal":
        optimal_refusal(problem, raise_error=True)
    if cost.work > limit:
        name = cost.dominant
        shown = _shown(name, problem)
        raise InputError(
            name,
            shown,
            f"makes the plan expensive: the fastest move the machine allows lasts "
            f"{cost.floor_s:.4g} s ({cost.samples:,.0f} samples at "
            f"{problem.sample_period_s:.3g} s), and the search would screen about "
            f"{cost.work:.2g} pendulum updates, above the limit {limit:.2g}",
            "plan the acceleration and braking segments separately, use a longer "
            "--sample-period or method 'fast'"
            + (", or a larger --max-angle" if name == "max_angle" else "")
            + f", or raise {WORK_VARIABLE}",
        )
    return cost


def optimal_refusal(problem: PlanProblem, raise_error: bool = False) -> str | None:
    """Why the optimal method would be too expensive for ``problem`` (None when it is not).

    Its programs have a variable per export sample and pendulum; their size is estimated
    from `duration_floor` (a lower bound on the move, so on the samples) times the pendulums
    (the first mode of each model of the band, every mode when the wall elevation is limited)
    and compared with ``SLOSHKIT_MAX_OPTIMAL_WORK`` (default `DEFAULT_MAX_OPTIMAL_WORK`).

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model and sample period.
    raise_error : bool
        Raise the reason as an `InputError` (the optimal method was asked for by name).

    Returns
    -------
    str or None
        A one-line reason naming the option that makes it expensive, or None.

    Examples
    --------
    >>> from sloshkit.model import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import MachineLimits, SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> tight = PlanProblem(0.5, MachineLimits(1.5, 20, 500),
    ...                     SloshLimits(math.radians(0.05), math.radians(0.001)), model)
    >>> optimal_refusal(tight).split(":")[0]
    'max_angle = 0.05 deg makes the optimal method expensive'
    """
    limit = _positive_variable(OPTIMAL_WORK_VARIABLE, DEFAULT_MAX_OPTIMAL_WORK)
    floor = duration_floor(problem)
    samples = floor.duration_s / problem.sample_period_s
    per_model = len(problem.model.modes) if problem.slosh.max_wall_elevation_m else 1
    pendulums = per_model * len(problem.models())
    if samples * pendulums <= limit:
        return None
    name, shown = floor.dominant, floor.shown(problem)
    if problem.sample_period_s < DEFAULT_SAMPLE_PERIOD_S and (
        floor.duration_s / DEFAULT_SAMPLE_PERIOD_S * pendulums <= limit
    ):  # the short controller period is what makes it expensive
        name, shown = "sample_period", f"{problem.sample_period_s:.4g} s"
    why = (
        f"no move within the limits is shorter than {floor.duration_s:.4g} s "
        f"({samples:,.0f} samples at {problem.sample_period_s:.3g} s x {pendulums} pendulum"
        f"{'s' if pendulums > 1 else ''}, above the limit {limit:,.0f})"
    )
    hint = (
        "use --method auto or fast, a longer --sample-period"
        + (", a larger --max-angle" if name == "max_angle" else "")
        + (", no --max-wall-elevation (it needs every mode)" if per_model > 1 else "")
        + f", or raise {OPTIMAL_WORK_VARIABLE}"
    )
    if raise_error:
        raise InputError(name, shown, "makes the optimal method expensive: " + why, hint)
    return f"{name} = {shown} makes the optimal method expensive: {why} ({hint})"


def _positive_variable(name: str, default: float) -> float:
    text = os.environ.get(name)
    if not text:
        return default
    try:
        value = float(text)
    except ValueError:
        raise InputError(name, text, "must be a number, e.g. 1e4") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(name, text, "must be finite and > 0")
    return value
