"""Plan the fastest rest-to-rest move that keeps the slosh within limits.

Methods (all verified the same way, see `verify`):

- the seed paper's laws (``trapezoidal``, ``cubic``, ``quintic``, ``septic``) at their shortest
  duration that meets the limits, found by a scan on the fast path and a bisection;
- ``shaped``: a time-optimal jerk-limited S-curve (ruckig) convolved with an input shaper (ZV,
  ZVD, EI on the first mode, or ZV on modes 1 and 2), whose acceleration and jerk limits are
  searched so that the shaped move meets every limit (a vectorised grid, then a bisection);
- ``optimal``: minimum-time control as linear programs (HiGHS), transcribed on the controller's
  export grid (piecewise-constant jerk per sample period, the pendulums' exact discretisation, the
  slosh limits at every exported sample, for each frequency of the robustness band); by default
  its smooth variant (`sloshkit.plan.line.optimal.SMOOTH_PRICE` = 0.5 % longer than the minimum
  time, least total variation of the jerk), with ``smooth=False`` the bang-bang time-optimal move;
  large-angle pendulums (time-optimal only) by multiple shooting (Betts, *Practical Methods for
  Optimal Control*, 2nd ed., SIAM (2010) ch. 4);
- ``auto``: all of the above, the fastest that passes verification.

Verification never trusts a planner's internal model: the motion is sampled at the controller's
period, and the exported velocity samples (linear between samples) are simulated again with the
exact discretisation of every mode, for every frequency of the robustness band.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.motion.sampling import export_samples
from sloshkit.plan.line.optimal import plan_optimal
from sloshkit.plan.line.problem import PAPER_LAWS, Candidate, PlanProblem
from sloshkit.plan.line.searches import plan_paper_law, plan_shaped
from sloshkit.plan.line.work_estimate import check_cost
from sloshkit.results import ResultMixin
from sloshkit.sim.discretisation import linear_response

FloatArray = NDArray[np.float64]


METHODS: tuple[str, ...] = ("auto", "paper", *PAPER_LAWS, "fast", "shaped", "optimal")


@dataclass(frozen=True, eq=False)
class PlanResult(ResultMixin):
    """The chosen motion and every candidate tried.

    Follows the result protocol (`sloshkit.results.ResultMixin`): ``to_csv`` writes the chosen
    motion's controller samples, ``to_dict`` the plan command's JSON.

    Parameters
    ----------
    problem : PlanProblem
        The problem solved.
    chosen : Candidate or None
        The fastest verified candidate (or the fastest at all when none is feasible).
    candidates : tuple of Candidate
        Every method's result.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(
    ...     0.1,
    ...     sk.MachineLimits(1.0, 5.0, 200.0),
    ...     sk.SloshLimits(max_angle_rad=0.1, max_residual_rad=0.01),
    ...     model,
    ... )
    >>> result = sk.plan(problem, "quintic")
    >>> result.feasible, result.chosen.method
    (True, 'quintic')
    """

    problem: PlanProblem
    chosen: Candidate | None
    candidates: tuple[Candidate, ...]

    @property
    def feasible(self) -> bool:
        """True when some method met every limit."""
        return self.chosen is not None and self.chosen.feasible

    def samples(self) -> dict[str, FloatArray]:
        """The chosen motion sampled at the controller period (see `export_samples`)."""
        if self.chosen is None or self.chosen.motion is None:
            raise InputError("plan", "infeasible", "no motion to export")
        return export_samples(self.chosen.motion, self.problem.sample_period_s)

    def columns(self) -> dict[str, FloatArray]:
        """The controller samples of the chosen motion (`samples`): the CSV columns."""
        return self.samples()

    def histories(self) -> list[dict[str, Any]]:
        """Per verified candidate: its exported samples and the first mode's angle re-simulated
        from them (nominal model), for figures.

        Returns
        -------
        list of dict
            Keys ``method``, ``duration_s``, ``chosen``, ``t_s``, ``velocity_m_s``,
            ``acceleration_m_s2`` and ``angle_1_rad``.
        """
        histories = []
        for candidate in self.candidates:
            if candidate.motion is None or not candidate.feasible:
                continue
            samples = export_samples(candidate.motion, self.problem.sample_period_s)
            angle, _ = linear_response(
                self.problem.model, samples["velocity_m_s"], self.problem.sample_period_s
            )
            histories.append(
                {
                    "method": candidate.method,
                    "duration_s": candidate.duration_s,
                    "chosen": candidate is self.chosen,
                    "t_s": samples["t_s"],
                    "velocity_m_s": samples["velocity_m_s"],
                    "acceleration_m_s2": samples["acceleration_m_s2"],
                    "angle_1_rad": angle[0],
                }
            )
        return histories

    def to_dict(self) -> dict[str, Any]:
        """The plan command's JSON."""
        chosen = (
            self.chosen.to_dict()
            if self.chosen is not None
            else {"method": None, "feasible": False}
        )
        paper = [c for c in self.candidates if c.method in PAPER_LAWS and c.feasible]
        best_paper = min((c.duration_s for c in paper), default=None)
        variant = None if self.chosen is None else self.chosen.detail.get("variant")
        return {
            **chosen,
            # "time-optimal" or "smooth" when the optimal method was chosen, else null.
            "variant": variant,
            "sample_period_s": self.problem.sample_period_s,
            "speed_up_over_best_paper_law": None
            if best_paper is None or self.chosen is None or not self.chosen.feasible
            else best_paper / self.chosen.duration_s,
            "candidates": [c.to_dict() for c in self.candidates],
        }


def plan(
    problem: PlanProblem,
    method: str = "auto",
    nonlinear_optimal: bool = False,
    progress: Callable[[str], None] | None = None,
    smooth: bool = True,
) -> PlanResult:
    """Run the requested method(s) and return the fastest verified candidate.

    Every candidate is verified from its sampled export (`sloshkit.plan.line.verification.verify`).

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model and controller period.
    method : str
        ``auto`` (everything), ``paper`` (the four laws), one law name, ``fast`` (a ZV-shaped
        S-curve only), ``shaped`` (all shapers) or ``optimal`` (linear programs on the export
        grid, started from the shaped result).
    nonlinear_optimal : bool
        Optimise (and verify) with the large-angle pendulums.
    progress : callable, optional
        Called with a short message before each method.
    smooth : bool
        The optimal method returns its smooth variant (the default: `sloshkit.plan.line.optimal.
        SMOOTH_PRICE` longer than the minimum time, least total variation of the jerk, no
        chattering); False returns the bang-bang time-optimal move (always so with
        ``nonlinear_optimal``). ``PlanResult.to_dict()["variant"]`` says which.

    Returns
    -------
    PlanResult
        The chosen motion and every candidate.

    References
    ----------
    Singer, N. C., W. P. Seering, J. Dyn. Syst. Meas. Control 112 (1990) 76-82,
    doi:10.1115/1.2894142; Betts, J. T., *Practical Methods for Optimal Control and Estimation
    Using Nonlinear Programming*, 2nd ed., SIAM (2010), ch. 4, doi:10.1137/1.9780898718577.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(
    ...     0.1,
    ...     sk.MachineLimits(1.0, 5.0, 200.0),
    ...     sk.SloshLimits(max_angle_rad=0.1, max_residual_rad=0.01),
    ...     model,
    ... )
    >>> result = sk.plan(problem, "paper")
    >>> sorted(c.method for c in result.candidates)
    ['cubic', 'quintic', 'septic', 'trapezoidal']
    """
    if method not in METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(METHODS))
    say = progress or (lambda _: None)
    check_cost(problem, method)  # refuse a search that would take minutes, before it starts
    if nonlinear_optimal and not problem.nonlinear:
        problem = replace(problem, nonlinear=True)  # verify everything with the same model
    candidates: list[Candidate] = []
    laws = PAPER_LAWS if method in ("auto", "paper") else (method,) if method in PAPER_LAWS else ()
    for law in laws:
        say(f"searching the shortest {law} move")
        candidates.append(plan_paper_law(law, problem))
    shaped: Candidate | None = None
    if method == "fast":
        say("searching a ZV-shaped S-curve")
        candidates.append(replace(plan_shaped(problem, ("zv",)), method="fast"))
    if method in ("auto", "shaped", "optimal"):
        say("searching shaped S-curves (ZV, ZVD, EI, two-mode ZV)")
        shaped = plan_shaped(problem)
        if method != "optimal":
            candidates.append(shaped)
    if method in ("auto", "optimal"):
        say("solving the time-optimal control problem (linear programs, HiGHS)")
        warm = _fastest(candidates + ([shaped] if shaped else []))
        candidates.append(
            plan_optimal(
                problem,
                warm.motion if warm else None,
                nonlinear=nonlinear_optimal,
                smooth=smooth and not nonlinear_optimal,
            )
        )
    chosen = _fastest(candidates)
    if chosen is None:
        chosen = min(candidates, key=lambda c: c.duration_s) if candidates else None
    return PlanResult(problem, chosen, tuple(candidates))


def _fastest(candidates: Sequence[Candidate]) -> Candidate | None:
    feasible = [c for c in candidates if c.feasible and c.motion is not None]
    return min(feasible, key=lambda c: c.duration_s) if feasible else None
