"""The minimum-time problem on the controller's export grid, solved as linear programs (HiGHS).

The program (`sloshkit.plan.line.grid_program`: a piecewise-constant jerk on the export grid,
the pendulums' exact discretisation at the slosh check grid's samples as linear rows, the
residual circle as an inscribed polygon) is linear and homogeneous for a fixed duration (the
move scaled by c in [0, 1] still meets every limit). So the longest distance a move of duration
T can travel, ``D*(T)``, is one sparse linear program (Boyd & Vandenberghe, *Convex
Optimization*, Cambridge (2004) §4.3; solved by HiGHS, Huangfu & Hall, Math. Prog. Comput. 10
(2018) 119-142, doi:10.1007/s12532-017-0130-5), the amplitude checked afterwards and the move
scaled down when the polygon's corners let it exceed the circle (at most 1/cos(pi/FACETS) - 1 =
7.5e-5 relative), and the minimum time is the root of D*(T) = D
(`sloshkit.plan.line.optimal`). The move of distance D at that duration is the longest move
scaled by D / D*.

The smooth variant at a fixed, slightly longer duration minimises the total variation of the
jerk (the L1 norm of its rate, sum |u_k - u_{k-1}|) over the same constraints with the
distance fixed: another linear program (HiGHS's quadratic solver took seconds on the squared
rate), started from the optimal basis of the longest move at that duration (dual feasible for
it: its costs are on the jerk jumps only).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from sloshkit.highs import new_highs
from sloshkit.plan.line.grid_moves import Limits, Move, Pendulum, measure, steps_for_duration
from sloshkit.plan.line.grid_program import FACETS, SAFETY_MARGIN, GridProgram
from sloshkit.plan.line.triplets import Triplets

__all__ = ["ExportGrid", "Limits", "Move", "Pendulum", "measure", "steps_for_duration"]

#: Relative margin of the smooth variant from every limit (it is not scaled after the solve).
SMOOTH_MARGIN = 1e-4

#: Steps x pendulums above which the first solve is HiGHS's interior-point method with
#: crossover (measured on the benchmark's problems: 0.67 s against the dual simplex's 1.0 s at
#: 830 steps x 3 pendulums, 0.23 against 0.29 s at 441 x 3, 0.09 against 0.06 s at 392 x 1).
IPM_SIZE = 1000


class ExportGrid:
    """The linear program of one problem on its export grid, built once and re-solved.

    One HiGHS model of ``steps`` steps (its `sloshkit.plan.line.grid_program.GridProgram`, the
    attribute ``program``) serves every duration up to ``steps`` sample periods: the first
    steps are held at rest (the pendulums start from rest, so a delay changes nothing else) and
    only the last step's few coefficients depend on tau. Each solve changes those bounds and
    coefficients and restarts the simplex from the previous basis. A solution is never trusted
    as it stands: its end state is projected onto rest (the solver meets equalities to 1e-7
    only), and the move is simulated again with the verification's discretisation; its reach
    is the distance divided by the largest ratio of any quantity to its limit (every
    constraint is homogeneous).

    Parameters
    ----------
    limits : Limits
        Distance, limits and sample period.
    pendulums : list of Pendulum
        The modes kept (the first mode of each model carries the angle and residual limits;
        the others only enter the wall elevation).
    steps : int
        Largest number of steps N (the model's shape).

    Returns
    -------
    ExportGrid

    Examples
    --------
    >>> from sloshkit.sim.discretisation import velocity_driven_discretisation
    >>> matrices = velocity_driven_discretisation(29.66, 0.03, 0.01115, 4e-3)
    >>> grid = ExportGrid(Limits(0.05, 1.5, 20.0, 500.0, 0.0873, 0.00436, None, 4e-3),
    ...                   [Pendulum(*matrices, 29.66, 0.03, 0.01115, 0.0, True, 0)], 100)
    >>> round(grid.longest(0.4).distance_m, 4)
    0.028
    """

    def __init__(self, limits: Limits, pendulums: list[Pendulum], steps: int) -> None:
        self.limits, self.pendulums, self.steps = limits, pendulums, steps
        self.program = GridProgram(limits, pendulums, steps)
        self.programs = 0
        self.iterations = 0
        self._highs: Any = None
        self._state: tuple[int, float] = (-1, -1.0)

    def _solver(self, smooth: bool) -> Any:
        """A HiGHS instance holding the program: the longest move, or (``smooth``) the move
        over the distance with the least total variation of the jerk, sum |u_k - u_{k-1}|
        (jerk 0 before and after the move), through n + 1 extra variables d_k >= |u_k -
        u_{k-1}| (an L1 cost on the jerk rate keeps the program linear)."""
        import highspy

        n, program = self.steps, self.program
        matrix = program.matrix
        row_lower, row_upper = program.row_lower.copy(), program.row_upper.copy()
        width = matrix.shape[1]
        bound = self._bound(smooth)
        limited = np.isfinite(row_upper) & (row_upper > 0)  # limits (not equalities, distance)
        row_upper[limited] *= bound / (1.0 - SAFETY_MARGIN)
        row_lower[limited & np.isfinite(row_lower)] *= bound / (1.0 - SAFETY_MARGIN)
        col_lower, col_upper = program.column_bounds(bound)
        cost = program.cost
        if smooth:
            row_lower[-1] = row_upper[-1] = 1.0  # the distance is fixed
            # The polygon inscribed in the residual circle (nothing is scaled afterwards).
            row_upper[np.isneginf(row_lower)] *= math.cos(math.pi / FACETS)
            jumps = n + 1
            # Rows d_k - (u_k - u_{k-1}) >= 0 and d_k + (u_k - u_{k-1}) >= 0 (u_n = u_{-1} = 0).
            k = np.arange(jumps)
            rows_d, cols_d, vals_d = [matrix.rows], [matrix.columns], [matrix.values]
            for block, sign in ((0, -1.0), (1, 1.0)):
                first = matrix.shape[0] + block * jumps
                now, before = k[k < n], k[k >= 1]
                rows_d += [first + now, first + before, first + k]
                cols_d += [now, before - 1, width + k]
                vals_d += [np.full(now.size, sign), np.full(before.size, -sign), np.ones(jumps)]
            matrix = Triplets.summed(
                np.concatenate(rows_d),
                np.concatenate(cols_d),
                np.concatenate(vals_d),
                (matrix.shape[0] + 2 * jumps, width + jumps),
            )
            row_lower = np.concatenate((row_lower, np.zeros(2 * jumps)))
            row_upper = np.concatenate((row_upper, np.full(2 * jumps, np.inf)))
            col_lower = np.concatenate((col_lower, np.zeros(jumps)))
            col_upper = np.concatenate((col_upper, np.full(jumps, np.inf)))
            cost = np.concatenate((np.zeros(width), np.ones(jumps)))
            width += jumps
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = width, matrix.shape[0]
        lp.col_cost_ = cost
        lp.col_lower_, lp.col_upper_ = col_lower, col_upper
        lp.row_lower_, lp.row_upper_ = row_lower, row_upper
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.start_, lp.a_matrix_.index_, lp.a_matrix_.value_ = matrix.compressed_columns()
        lp.sense_ = highspy.ObjSense.kMinimize if smooth else highspy.ObjSense.kMaximize
        solver = new_highs(threads=1)
        solver.setOptionValue("solver", "simplex")
        solver.passModel(lp)
        return solver

    @staticmethod
    def _bound(smooth: bool) -> float:
        """Scaled limit of every quantity: the smooth move keeps `SMOOTH_MARGIN` (it cannot
        be scaled afterwards, so the solver's 1e-7 tolerances must stay inside it)."""
        return 1.0 - (SMOOTH_MARGIN if smooth else SAFETY_MARGIN)

    def _set(
        self, solver: Any, effective_steps: int, tau: float, state: tuple[int, float], bound: float
    ) -> None:
        """Hold the first steps at rest and set the last step's coefficients (only what
        changed since ``state``); ``bound`` is the jerk bound of the moving steps."""
        n, program = self.steps, self.program
        if not 1 <= effective_steps <= n:
            raise ValueError(f"effective_steps must be in 1..{n}")
        idle = n - effective_steps
        iu = np.arange(n)  # the jerks: the program's first columns
        if idle != state[0]:
            low = np.where(iu < idle, 0.0, -bound)
            solver.changeColsBounds(n, iu.astype(np.int32), low, -low)
        if tau != state[1]:
            entries, costs, facets = program.retimed(tau)
            if solver is self._highs:  # the longest move: the distance is the objective
                for column, value in costs:
                    solver.changeColCost(int(column), value)
            if self.limits.substeps > 1:
                smooth = solver is not self._highs
                facet_upper = bound * (math.cos(math.pi / FACETS) if smooth else 1.0)
                for start, binds in facets:
                    upper = facet_upper if binds else np.inf
                    rows = np.arange(start, start + FACETS, dtype=np.int32)
                    solver.changeRowsBounds(
                        FACETS, rows, np.full(FACETS, -np.inf), np.full(FACETS, upper)
                    )
            for r, column, value in entries:
                solver.changeCoeff(int(r), int(column), value)

    def longest(self, duration_s: float) -> Move:
        """The longest move of ``duration_s`` that meets every limit at every exported sample.

        Parameters
        ----------
        duration_s : float
            T [s], at most ``steps`` sample periods.

        Returns
        -------
        Move
            Its jerks and the distance D*(T) it travels (measured by simulating it again).
        """
        if self._highs is None:
            self._highs = self._solver(smooth=False)
        solver = self._highs
        effective, tau = steps_for_duration(duration_s, self.limits.sample_period_s)
        self._set(solver, effective, tau, self._state, self._bound(False))
        self._state = (self.steps - effective, tau)
        if self.programs == 0 and self.steps * len(self.pendulums) > IPM_SIZE:
            solver.setOptionValue("solver", "ipm")  # then crossover to a basis
        solver.run()
        if self.programs == 0:
            # Later solves start from the first one's basis, where the primal simplex needs a
            # few hundred cheap iterations (the dual simplex as many, each several times
            # dearer, on these programs).
            solver.setOptionValue("solver", "simplex")
            solver.setOptionValue("presolve", "off")
            solver.setOptionValue("simplex_strategy", 4)
        self.programs += 1
        self.iterations += int(solver.getInfo().simplex_iteration_count)
        status = solver.modelStatusToString(solver.getModelStatus())
        if status != "Optimal":
            return Move(np.zeros(effective), duration_s, tau, 0.0, status)
        x = np.asarray(solver.getSolution().col_value, dtype=float)
        jerks = x[self.steps - effective : self.steps] * self.limits.max_jerk_m_s3
        jerks, distance, ratio = measure(jerks, tau, self.limits, self.pendulums)
        factor = (1.0 - SAFETY_MARGIN) / ratio
        return Move(jerks * factor, duration_s, tau, distance * factor, status)

    def _smooth_start(self, duration_s: float) -> Any:
        """A starting basis for the smooth program at ``duration_s``: the longest move's
        optimal basis at that duration (one more, warm, program), the jerk-jump variables at
        zero and their rows basic. Dual feasible for the smooth program (its costs are on the
        jerk jumps only), it halves the dual simplex's work there against a start from
        scratch (measured on the benchmark's problems: 0.13 against 0.29 s on the paper's).
        None when that program does not solve."""
        import highspy

        if self.longest(duration_s).status != "Optimal":
            return None
        basis = self._highs.getBasis()
        if not basis.valid:
            return None
        jumps = self.steps + 1
        start = highspy.HighsBasis()
        start.col_status = [*basis.col_status, *[highspy.HighsBasisStatus.kLower] * jumps]
        start.row_status = [*basis.row_status, *[highspy.HighsBasisStatus.kBasic] * (2 * jumps)]
        start.valid = True
        return start

    def smoothest(self, duration_s: float) -> Move | None:
        """The move of ``duration_s`` over the distance with the least total variation of the
        jerk that meets every limit (None when the solver or the check fails).

        Parameters
        ----------
        duration_s : float
            T [s], at most ``steps`` sample periods.

        Returns
        -------
        Move or None
            Its jerks (ending exactly at rest on the target).
        """
        solver = self._solver(smooth=True)
        basis = self._smooth_start(duration_s)
        if basis is not None:
            solver.setBasis(basis)
            solver.setOptionValue("presolve", "off")
            solver.setOptionValue("simplex_strategy", 1)  # the dual simplex
        elif self.steps * len(self.pendulums) > IPM_SIZE:
            solver.setOptionValue("solver", "ipm")
        effective, tau = steps_for_duration(duration_s, self.limits.sample_period_s)
        self._set(solver, effective, tau, (-1, -1.0), self._bound(True))
        solver.run()
        self.programs += 1
        status = solver.modelStatusToString(solver.getModelStatus())
        if status != "Optimal":
            return None
        x = np.asarray(solver.getSolution().col_value, dtype=float)
        jerks = x[self.steps - effective : self.steps] * self.limits.max_jerk_m_s3
        jerks, distance, ratio = measure(jerks, tau, self.limits, self.pendulums)
        jerks *= self.limits.distance_m / distance
        if ratio * self.limits.distance_m / distance > 1.0 - SAFETY_MARGIN:
            return None
        return Move(jerks, duration_s, tau, self.limits.distance_m, status)
