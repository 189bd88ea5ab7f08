"""The minimum-time problem on the controller's export grid, as linear programs (HiGHS).

The move is a piecewise-constant jerk on the export grid t_k = k Ts: N - 1 full steps and a
last, shorter step of length tau in (0, Ts], so that T = (N - 1) Ts + tau is continuous. The
slosh is what the verification simulates: the exported velocity samples v_k = v(k Ts) (v_N = 0,
the move is over at the last sample) drive the exact first-order-hold discretisation of each
pendulum (Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998)
§6.3.2): z_{k+1} = Phi z_k + Gamma v_k, theta_k = z_k + g1 v_k. The pendulums run on the slosh
check grid (each step split into ``Limits.substeps`` sub-steps no longer than the finest
controller period, 2 ms; `sloshkit.plan.line.verification.slosh_substeps`), driven by the exact
velocity of the piecewise-constant-jerk move at the sub-samples (linear in the step's node
velocity, node acceleration and jerk), so that the limits also hold when the plan is resampled
for a 2 ms controller. The slosh limits are imposed at exactly the samples the verification
checks, so the planned move passes it without tightening and solving again.

For a fixed duration every constraint is linear in the jerks and homogeneous (the move scaled
by c in [0, 1] still meets every limit), except the residual circle, which is replaced by an
inscribed-facet polygon (`FACETS` tangent lines, the amplitude checked afterwards and the move
scaled down when the polygon's corners let it exceed the circle, at most
1/cos(pi/FACETS) - 1 = 7.5e-5 relative). So the longest distance a move of duration T can
travel, ``D*(T)``, is one sparse linear program (states and jerks as variables: Boyd &
Vandenberghe, *Convex Optimization*, Cambridge (2004) §4.3; solved by HiGHS, Huangfu & Hall,
Math. Prog. Comput. 10 (2018) 119-142, doi:10.1007/s12532-017-0130-5), and the minimum time
is the root of D*(T) = D (`sloshkit.plan.line.optimal`). The move of distance D at that duration is
the longest move scaled by D / D*.

The smooth variant at a fixed, slightly longer duration minimises the total variation of the
jerk (the L1 norm of its rate, sum |u_k - u_{k-1}|) over the same constraints with the
distance fixed: another linear program (HiGHS's quadratic solver took seconds on the squared
rate), started from the optimal basis of the longest move at that duration (dual feasible for
it: its costs are on the jerk jumps only).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from sloshkit.highs import new_highs
from sloshkit.plan.line.grid_moves import Limits, Move, Pendulum, measure, steps_for_duration

FloatArray = NDArray[np.float64]

__all__ = ["ExportGrid", "Limits", "Move", "Pendulum", "measure", "steps_for_duration"]

#: Relative margin every move keeps from every limit, so that rounding in the verification
#: (which allows 1e-7) never flags it.
SAFETY_MARGIN = 1e-6

#: Relative margin of the smooth variant from every limit (it is not scaled after the solve).
SMOOTH_MARGIN = 1e-4

#: Tangent lines of the residual polygon.
FACETS = 256

#: Steps x pendulums above which the first solve is HiGHS's interior-point method with
#: crossover (measured on the benchmark's problems: 0.67 s against the dual simplex's 1.0 s at
#: 830 steps x 3 pendulums, 0.23 against 0.29 s at 441 x 3, 0.09 against 0.06 s at 392 x 1).
IPM_SIZE = 1000


class Triplets(NamedTuple):
    """A sparse matrix as (row, column, value) entries, duplicates summed.

    Parameters
    ----------
    rows, columns : ndarray of int
        Entry positions.
    values : ndarray
        Entry values.
    shape : tuple of int
        (rows, columns) of the matrix.

    Examples
    --------
    >>> import numpy as np
    >>> m = Triplets.summed(np.array([0, 0]), np.array([1, 1]), np.array([2.0, 3.0]), (1, 2))
    >>> m.values.tolist(), m.shape
    ([5.0], (1, 2))
    """

    rows: NDArray[np.int64]
    columns: NDArray[np.int64]
    values: FloatArray
    shape: tuple[int, int]

    @classmethod
    def summed(
        cls,
        rows: NDArray[np.int64],
        columns: NDArray[np.int64],
        values: FloatArray,
        shape: tuple[int, int],
    ) -> Triplets:
        """The entries sorted by column, then row, with duplicate positions summed."""
        order = np.lexsort((rows, columns))
        rows, columns, values = rows[order], columns[order], values[order]
        first = np.ones(rows.size, dtype=bool)
        first[1:] = (rows[1:] != rows[:-1]) | (columns[1:] != columns[:-1])
        starts = np.flatnonzero(first)
        return cls(rows[starts], columns[starts], np.add.reduceat(values, starts), shape)

    def compressed_columns(self) -> tuple[NDArray[np.int32], NDArray[np.int32], FloatArray]:
        """(start, index, value): the column-wise layout HiGHS takes (the entries are sorted
        by column)."""
        counts = np.bincount(self.columns, minlength=self.shape[1])
        start = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        return start, self.rows.astype(np.int32), np.asarray(self.values, dtype=float)


class ExportGrid:
    """The linear program of one problem on its export grid, built once and re-solved.

    One HiGHS model of ``steps`` steps serves every duration up to ``steps`` sample periods:
    the first steps are held at rest (the pendulums start from rest, so a delay changes
    nothing else) and only the last step's few coefficients depend on tau. Each solve changes
    those bounds and coefficients and restarts the simplex from the previous basis.

    The pendulum states (theta, theta' + v / L) at the controller's nodes are variables (their
    angle limits are bounds); the slosh check grid's sub-samples inside a step are rows over the
    step's first node state, v, a and jerk (a state and an equality per sub-sample would make
    the programs a third larger and, measured, slower), except in the last step, whose
    sub-samples are variables because their coefficients change with tau. A solution is never
    trusted as it stands: its end state is projected onto rest (the solver meets equalities to
    1e-7 only), and the move is simulated again with the verification's discretisation; its
    reach is the distance divided by the largest ratio of any quantity to its limit (every
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
        self.programs = 0
        self.iterations = 0
        self._highs: Any = None
        self._state: tuple[int, float] = (-1, -1.0)
        self._matrix, self._row_lower, self._row_upper, self._cost = self._assemble(
            limits.sample_period_s
        )

    # Layout: u (jerk / jmax) 0..N-1, a (/ amax) and v (/ vmax) at nodes 1..N, then per
    # pendulum its states (theta / theta_max, y / (vmax / L)) at nodes 1..N (`_state_base`),
    # then per pendulum its states at the last step's sub-samples 1..m-1 (`_end_base`).
    def _columns(self) -> tuple[Any, Any, Any]:
        n = self.steps
        steps = np.arange(n)
        return steps, n + steps, 2 * n + steps

    def _assemble(self, tau: float) -> tuple[Triplets, FloatArray, FloatArray, FloatArray]:
        """Constraint matrix, row bounds and the distance / D per variable."""
        lim, ts, n = self.limits, self.limits.sample_period_s, self.steps
        h = np.full(n, ts)
        h[-1] = tau
        jmax, amax, vmax = lim.max_jerk_m_s3, lim.max_acceleration_m_s2, lim.max_velocity_m_s
        width = self._end_base(len(self.pendulums))
        steps = np.arange(n)
        inner = steps[1:]
        iu, ia, iv = self._columns()
        rows: list[Any] = []
        cols: list[Any] = []
        vals: list[Any] = []

        def put(row: Any, col: Any, val: Any) -> None:
            row = np.asarray(row, dtype=np.int64)
            rows.append(row)
            cols.append(np.asarray(col, dtype=np.int64))
            vals.append(np.broadcast_to(np.asarray(val, dtype=float), row.shape).copy())

        # Kinematics, step k from node k to k + 1 (node 0 at rest: its terms drop).
        put(steps, ia, 1.0)
        put(inner, ia[:-1], -1.0)
        put(steps, iu, -jmax * h / amax)
        put(n + steps, iv, 1.0)
        put(n + inner, iv[:-1], -1.0)
        put(n + inner, ia[:-1], -amax * h[1:] / vmax)
        put(n + steps, iu, -jmax * h**2 / (2 * vmax))
        row = 2 * n
        # Pendulums: the state s = (theta, y) at the nodes 1..N are variables, each node the
        # previous one propagated over the step's m sub-steps of the slosh check grid
        # (m = limits.substeps; `_substep_maps`). The sub-samples inside a step are
        # combinations of the step's first node state and its v, a and jerk, so their angle
        # limits are rows, not variables and equalities; only the last step's sub-samples
        # (their coefficients change with tau) are variables (`_end_base`), for the residual.
        full = [self._substep_maps(pend, None) for pend in self.pendulums]
        end = [self._substep_maps(pend, tau) for pend in self.pendulums]
        m = lim.substeps
        self._node_rows, self._end_rows = [], []
        for index in range(len(self.pendulums)):
            base = self._state_base(index)
            self._node_rows.append(row)
            for c in range(2):
                node = row + 2 * steps + c  # node k + 1, reached by step k
                put(node, base + 2 * steps + c, 1.0)
                for d in range(2):
                    put(node[1:], base + 2 * (inner - 1) + d, -full[index][0][m, c, d])
                put(node[:-1], iu[:-1], -full[index][1][m, c, 2])
                put(node[1:-1], iv[: n - 2], -full[index][1][m, c, 0])
                put(node[1:-1], ia[: n - 2], -full[index][1][m, c, 1])
            row += 2 * n
        for index in range(len(self.pendulums)):
            self._end_rows.append(row)
            for sub in range(1, m):
                for c in range(2):
                    put([row], [self._end_base(index) + 2 * (sub - 1) + c], 1.0)
                    if n > 1:
                        for d in range(2):
                            put(
                                [row],
                                [self._state_base(index) + 2 * (n - 2) + d],
                                -full[index][0][sub, c, d],
                            )
                    row += 1
        for r, column, value in self._last_step_entries(tau, end):
            put([r], [column], value)
        equalities = row
        # Two-sided rows |row| <= 1: the velocity within each step (its Bernstein midpoint
        # v_k + a_k h_k / 2 bounds the quadratic with v_k and v_{k+1}), the angle at the
        # sub-samples inside the steps but the last, the wall elevation.
        self._bernstein = row
        mid = np.arange(n - 1)
        put(row + mid, iv[mid], 1.0)
        put(row + mid, ia[mid], amax * h[1:] / (2 * vmax))
        row += n - 1
        for index, pend in enumerate(self.pendulums):
            if pend.limited:
                for sub in range(1, m):
                    row = self._put_inside(put, row, [(index, 1.0)], full, sub)
        if lim.max_wall_elevation_m is not None:
            for model in sorted({p.model for p in self.pendulums}):
                members = [
                    (index, pend.wall_factor_m * lim.max_angle_rad / lim.max_wall_elevation_m)
                    for index, pend in enumerate(self.pendulums)
                    if pend.model == model
                ]
                for index, factor in members:  # at the nodes 1..N
                    put(row + steps, self._state_base(index) + 2 * steps, factor)
                row += n
                for sub in range(1, m):  # inside the steps but the last
                    row = self._put_inside(put, row, members, full, sub)
                for sub in range(1, m):  # inside the last step
                    for index, factor in members:
                        put([row], [self._end_base(index) + 2 * (sub - 1)], factor)
                    row += 1
        two_sided = row
        # Residual polygon: cos(p) theta_j + sin(p) B_j <= r, B = (theta' + zeta w theta) / w_d
        # (theta' = y where v = 0), at each sub-sample of the last step; those before T are
        # released (`_residual_active`), so it binds at the first sub-sample at or after T.
        phases = np.linspace(0.0, 2 * math.pi, FACETS, endpoint=False)
        self._facets: list[tuple[int, int]] = []
        for index, pend in enumerate(self.pendulums):
            if pend.limited:
                damped = pend.omega_rad_s * math.sqrt(1.0 - pend.damping_ratio**2)
                zeta_w = pend.damping_ratio * pend.omega_rad_s / damped
                theta = lim.max_angle_rad / lim.max_residual_rad
                rate = vmax / pend.length_m / lim.max_residual_rad / damped
                for sub in range(1, m + 1):
                    last = (
                        self._state_base(index) + 2 * (n - 1)
                        if sub == m
                        else self._end_base(index) + 2 * (sub - 1)
                    )
                    facet = row + np.arange(FACETS)
                    put(
                        facet,
                        np.full(FACETS, last),
                        theta * (np.cos(phases) + zeta_w * np.sin(phases)),
                    )
                    put(facet, np.full(FACETS, last + 1), rate * np.sin(phases))
                    self._facets.append((row, sub))
                    row += FACETS
        # Distance travelled / D: sum over steps of v_k h + a_k h^2 / 2 + u_k h^3 / 6.
        cost = np.zeros(width)
        cost[iu] = jmax * h**3 / 6
        cost[ia[:-1]] = amax * h[1:] ** 2 / 2
        cost[iv[:-1]] = vmax * h[1:]
        cost /= lim.distance_m
        put(np.full(width, row), np.arange(width), cost)
        row += 1
        matrix = Triplets.summed(
            np.concatenate(rows), np.concatenate(cols), np.concatenate(vals), (row, width)
        )
        bound = 1.0 - SAFETY_MARGIN
        lower = np.zeros(row)
        upper = np.zeros(row)
        lower[equalities:two_sided], upper[equalities:two_sided] = -bound, bound
        lower[two_sided:], upper[two_sided:] = -np.inf, bound
        upper[-1] = np.inf
        for start, sub in self._facets:
            if not self._residual_active(sub, tau):
                upper[start : start + FACETS] = np.inf
        return matrix, lower, upper, cost

    def _residual_active(self, sub: int, tau: float) -> bool:
        """Whether sub-sample ``sub`` (1..m) of the last step is at or after the end T."""
        return sub * self.limits.slosh_period_s >= tau - 1e-12

    def _state_base(self, index: int) -> int:
        """First column of pendulum ``index``'s node states (theta, y at nodes 1..N)."""
        return 3 * self.steps + 2 * self.steps * index

    def _end_base(self, index: int) -> int:
        """First column of pendulum ``index``'s states at the last step's inner sub-samples
        (theta, y at sub-samples 1..m-1); ``index`` = the number of pendulums: the width."""
        m = self.limits.substeps
        return 3 * self.steps + 2 * self.steps * len(self.pendulums) + 2 * (m - 1) * index

    def _substep_maps(self, pend: Pendulum, tau: float | None) -> tuple[FloatArray, FloatArray]:
        """(P, q), shapes (m + 1, 2, 2) and (m + 1, 2, 3): the pendulum's scaled state at
        sub-sample i of a step is P[i] s_k + q[i] (v_k, a_k, jerk_k) (scaled variables, s_k
        the state at the step's first node), by the check grid's recursion in s = z + g1 v:
        s_{i+1} = Phi s_i + g1 v_{i+1} + (Gamma - Phi g1) v_i, v_i = v_k + a_k o + j o^2 / 2 at
        the offset o = i Ts / m (Franklin, Powell & Workman (1998) §6.3.2). ``tau``: the last
        step, ``tau`` long, at rest from its end on; None: a full step."""
        lim, m = self.limits, self.limits.substeps
        state = np.array([lim.max_angle_rad, lim.max_velocity_m_s / pend.length_m])
        inputs = np.array([lim.max_velocity_m_s, lim.max_acceleration_m_s2, lim.max_jerk_m_s3])
        before = pend.gamma - pend.phi @ pend.g1

        def velocity(sub: int) -> FloatArray:  # v at sub-sample ``sub`` per (v_k, a_k, j_k)
            offset = sub * lim.slosh_period_s
            if tau is not None and offset >= tau - 1e-12:
                return np.zeros(3)
            return np.array([1.0, offset, offset**2 / 2])

        propagate = np.zeros((m + 1, 2, 2))
        inject = np.zeros((m + 1, 2, 3))
        propagate[0] = np.eye(2)
        for sub in range(m):
            propagate[sub + 1] = pend.phi @ propagate[sub]
            inject[sub + 1] = (
                pend.phi @ inject[sub]
                + np.outer(pend.g1, velocity(sub + 1))
                + np.outer(before, velocity(sub))
            )
        scaled_propagate = propagate * state[None, None, :] / state[None, :, None]
        scaled_inject = inject * inputs[None, None, :] / state[None, :, None]
        return scaled_propagate, scaled_inject

    def _put_inside(
        self,
        put: Any,
        row: int,
        members: list[tuple[int, float]],
        maps: list[tuple[FloatArray, FloatArray]],
        sub: int,
    ) -> int:
        """Rows sum_p weight_p theta_p at sub-sample ``sub`` of every step but the last (one
        row per step, from ``row``); returns the next free row."""
        n = self.steps
        iu, ia, iv = self._columns()
        here = row + np.arange(n - 1)
        for index, weight in members:
            propagate, inject = maps[index]
            base = self._state_base(index)
            for d in range(2):
                put(here[1:], base + 2 * np.arange(n - 2) + d, weight * propagate[sub, 0, d])
            put(here, iu[: n - 1], weight * inject[sub, 0, 2])
            put(here[1:], iv[: n - 2], weight * inject[sub, 0, 0])
            put(here[1:], ia[: n - 2], weight * inject[sub, 0, 1])
        return row + n - 1

    def _solver(self, smooth: bool) -> Any:
        """A HiGHS instance holding the program: the longest move, or (``smooth``) the move
        over the distance with the least total variation of the jerk, sum |u_k - u_{k-1}|
        (jerk 0 before and after the move), through n + 1 extra variables d_k >= |u_k -
        u_{k-1}| (an L1 cost on the jerk rate keeps the program linear)."""
        import highspy

        n = self.steps
        matrix, row_lower, row_upper = self._matrix, self._row_lower.copy(), self._row_upper.copy()
        width = matrix.shape[1]
        bound = self._bound(smooth)
        limited = np.isfinite(row_upper) & (row_upper > 0)  # limits (not equalities, distance)
        row_upper[limited] *= bound / (1.0 - SAFETY_MARGIN)
        row_lower[limited & np.isfinite(row_lower)] *= bound / (1.0 - SAFETY_MARGIN)
        col_lower = np.full(width, -np.inf)
        col_lower[: 3 * n] = -bound
        for index, pend in enumerate(self.pendulums):
            if pend.limited:  # |theta| <= theta_max at the nodes and the last step's samples
                base, inner = self._state_base(index), self._end_base(index)
                col_lower[base : base + 2 * n : 2] = -bound
                col_lower[inner : inner + 2 * (self.limits.substeps - 1) : 2] = -bound
        col_upper = -col_lower
        _, ia, iv = self._columns()
        col_lower[[ia[-1], iv[-1]]] = col_upper[[ia[-1], iv[-1]]] = 0.0  # at rest at node N
        cost = self._cost
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
        n = self.steps
        if not 1 <= effective_steps <= n:
            raise ValueError(f"effective_steps must be in 1..{n}")
        idle = n - effective_steps
        iu, ia, iv = self._columns()
        if idle != state[0]:
            low = np.where(iu < idle, 0.0, -bound)
            solver.changeColsBounds(n, iu.astype(np.int32), low, -low)
        if tau != state[1]:
            lim = self.limits
            jmax, amax, vmax = lim.max_jerk_m_s3, lim.max_acceleration_m_s2, lim.max_velocity_m_s
            last, before, distance_row = n - 1, n - 2, self._matrix.shape[0] - 1
            bernstein = self._bernstein + before
            entries = [
                (last, iu[last], -jmax * tau / amax),
                (n + last, iu[last], -jmax * tau**2 / (2 * vmax)),
            ]
            costs = [(iu[last], jmax * tau**3 / 6)]
            if n > 1:
                entries += [
                    (n + last, ia[before], -amax * tau / vmax),
                    (bernstein, ia[before], amax * tau / (2 * vmax)),
                ]
                costs += [(ia[before], amax * tau**2 / 2), (iv[before], vmax * tau)]
            for column, value in costs:
                entries.append((distance_row, column, value / lim.distance_m))
                if solver is self._highs:  # the longest move: the distance is the objective
                    solver.changeColCost(int(column), value / lim.distance_m)
            if lim.substeps > 1:
                entries += self._last_step_entries(tau)
                smooth = solver is not self._highs
                facet_upper = bound * (math.cos(math.pi / FACETS) if smooth else 1.0)
                for start, sub in self._facets:
                    upper = facet_upper if self._residual_active(sub, tau) else np.inf
                    rows = np.arange(start, start + FACETS, dtype=np.int32)
                    solver.changeRowsBounds(
                        FACETS, rows, np.full(FACETS, -np.inf), np.full(FACETS, upper)
                    )
            for r, column, value in entries:
                solver.changeCoeff(int(r), int(column), value)

    def _last_step_entries(
        self, tau: float, maps: list[tuple[FloatArray, FloatArray]] | None = None
    ) -> list[tuple[int, int, float]]:
        """The coefficients of the last step's v, a and jerk in the rows of node N and of the
        last step's inner sub-samples, for a last step ``tau`` (the sub-samples at or after T
        drop their velocity terms): (row, column, value), zeros included."""
        n, m = self.steps, self.limits.substeps
        iu, ia, iv = self._columns()
        columns = [(int(iu[n - 1]), 2)] + (
            [(int(iv[n - 2]), 0), (int(ia[n - 2]), 1)] if n > 1 else []
        )
        if maps is None:
            maps = [self._substep_maps(pend, tau) for pend in self.pendulums]
        entries = []
        for index, (_, inject) in enumerate(maps):
            for c in range(2):
                for column, which in columns:
                    node = self._node_rows[index] + 2 * (n - 1) + c
                    entries.append((node, column, -float(inject[m, c, which])))
                    for sub in range(1, m):
                        inner = self._end_rows[index] + 2 * (sub - 1) + c
                        entries.append((inner, column, -float(inject[sub, c, which])))
        return entries

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
