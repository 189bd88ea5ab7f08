"""The cone programs' rows and their solution (`sloshkit.plan.path.rows.ConeRows`): small
programs against their closed-form optimum, and no solution for an infeasible one."""

from __future__ import annotations

import numpy as np

from sloshkit.plan.path.rows import ConeRows


def test_a_disc_program_reaches_its_closed_form_optimum() -> None:
    """max x0 + x1 with |(x0, x1)| <= 2: the optimum is (sqrt 2, sqrt 2)."""
    rows = ConeRows()
    rows.add("soc", [1, 2], [0, 1], [1.0, 1.0], [2.0, 0.0, 0.0], [3])  # (2, -x0, -x1) in SOC
    result = rows.solve(np.array([-1.0, -1.0]))
    assert result is not None
    np.testing.assert_allclose(result.x, [np.sqrt(2.0), np.sqrt(2.0)], atol=1e-6)


def test_equalities_inequalities_and_cones_together() -> None:
    """min t with x0 = 3, x1 >= 4 and |(x0, x1)| <= t: t = 5 at (3, 4)."""
    rows = ConeRows()
    rows.add("zero", [0], [0], [1.0], [3.0])  # 3 - x0 = 0
    rows.add("nonneg", [0], [1], [-1.0], [-4.0])  # -4 + x1 >= 0
    rows.add("soc", [0, 1, 2], [2, 0, 1], [-1.0, -1.0, -1.0], [0.0, 0.0, 0.0], [3])
    result = rows.solve(np.array([0.0, 0.0, 1.0]))
    assert result is not None
    np.testing.assert_allclose(result.x, [3.0, 4.0, 5.0], atol=1e-5)


def test_an_infeasible_program_has_no_solution() -> None:
    rows = ConeRows()
    rows.add("nonneg", [0, 1], [0, 0], [1.0, -1.0], [-1.0, -1.0])  # x0 <= -1 and x0 >= 1
    assert rows.solve(np.array([1.0])) is None
