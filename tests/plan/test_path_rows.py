"""The cone programs' rows and their solution (`sloshkit.plan.path.rows.ConeRows`): a small
program against its closed-form optimum, and the second solve with more regularisation when
Clarabel ends in a numerical error (the failure seen on tilted programs with an arm's joints)."""

from __future__ import annotations

from typing import ClassVar

import clarabel
import numpy as np

from sloshkit.plan.path.rows import RETRY_REGULARIZATION, ConeRows

CLARABEL_SOLVER = clarabel.DefaultSolver


def disc_program() -> ConeRows:
    """max x0 + x1 with |(x0, x1)| <= 2: the optimum is (sqrt 2, sqrt 2)."""
    rows = ConeRows()
    rows.add("soc", [1, 2], [0, 1], [1.0, 1.0], [2.0, 0.0, 0.0], [3])  # (2, -x0, -x1) in SOC
    return rows


def test_a_small_program_reaches_its_closed_form_optimum() -> None:
    result, solves = disc_program().solve(np.array([-1.0, -1.0]))
    assert solves == 1 and str(result.status) == "Solved"
    np.testing.assert_allclose(result.x, [np.sqrt(2.0), np.sqrt(2.0)], atol=1e-6)


class FailsFirst:
    """Clarabel's solver whose first solve reports a numerical error."""

    regularizations: ClassVar[list[float]] = []

    def __init__(self, *args) -> None:
        self.solver = CLARABEL_SOLVER(*args)
        self.regularization = args[-1].static_regularization_constant

    def solve(self):
        FailsFirst.regularizations.append(self.regularization)
        result = self.solver.solve()
        if len(FailsFirst.regularizations) == 1:
            return type("Failed", (), {"status": "NumericalError", "x": result.x})()
        return result


def test_a_numerical_error_is_solved_again_with_more_regularization(monkeypatch) -> None:
    FailsFirst.regularizations = []
    monkeypatch.setattr(clarabel, "DefaultSolver", FailsFirst)
    result, solves = disc_program().solve(np.array([-1.0, -1.0]))
    assert solves == 2
    assert FailsFirst.regularizations[1] == RETRY_REGULARIZATION
    assert FailsFirst.regularizations[0] < RETRY_REGULARIZATION
    np.testing.assert_allclose(result.x, [np.sqrt(2.0), np.sqrt(2.0)], atol=1e-6)


def test_an_infeasible_program_is_not_solved_twice() -> None:
    rows = ConeRows()
    rows.add("nonneg", [0, 1], [0, 0], [1.0, -1.0], [-1.0, -1.0])  # x0 <= -1 and x0 >= 1
    result, solves = rows.solve(np.array([1.0]))
    assert result is None and solves == 1


def test_two_numerical_errors_give_no_solution(monkeypatch) -> None:
    class AlwaysFails(FailsFirst):
        def solve(self):
            return type("Failed", (), {"status": "NumericalError", "x": None})()

    monkeypatch.setattr(clarabel, "DefaultSolver", AlwaysFails)
    result, solves = disc_program().solve(np.array([-1.0, -1.0]))
    assert result is None and solves == 2
