"""The minimum-time problem's linear program on the controller's export grid, assembled.

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
inscribed-facet polygon (`FACETS` tangent lines, at most 1/cos(pi/FACETS) - 1 = 7.5e-5 relative
outside the circle at its corners). So the program has the states and jerks as variables
(Boyd & Vandenberghe, *Convex Optimization*, Cambridge (2004) §4.3), and its objective row is
the distance travelled. This module writes that program once, as sparse triplets, row bounds
and costs (`GridProgram`), and the few coefficients that change with the last step;
`sloshkit.plan.line.export_grid` hands it to HiGHS and solves it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.plan.line.grid_moves import Limits, Pendulum
from sloshkit.plan.line.triplets import Triplets

FloatArray = NDArray[np.float64]

#: Relative margin every move keeps from every limit, so that rounding in the verification
#: (which allows 1e-7) never flags it.
SAFETY_MARGIN = 1e-6

#: Tangent lines of the residual polygon.
FACETS = 256


class GridProgram:
    """The linear program of one problem on its export grid: variables, rows, bounds, costs.

    One program of ``steps`` steps serves every duration up to ``steps`` sample periods: the
    first steps are held at rest by their jerk bounds (the pendulums start from rest, so a
    delay changes nothing else) and only the last step's few coefficients depend on tau
    (`retimed`). It is assembled for a full last step, tau = Ts.

    The pendulum states (theta, theta' + v / L) at the controller's nodes are variables (their
    angle limits are bounds); the slosh check grid's sub-samples inside a step are rows over the
    step's first node state, v, a and jerk (a state and an equality per sub-sample would make
    the programs a third larger and, measured, slower), except in the last step, whose
    sub-samples are variables because their coefficients change with tau. Every variable is
    scaled by its limit, so every limit is a bound of 1 - `SAFETY_MARGIN`; the jerks
    u_k / jmax are the first N columns.

    Parameters
    ----------
    limits : Limits
        Distance, limits and sample period.
    pendulums : list of Pendulum
        The modes kept (the first mode of each model carries the angle and residual limits;
        the others only enter the wall elevation).
    steps : int
        Largest number of steps N (the program's shape).

    Attributes
    ----------
    matrix : Triplets
        The constraint rows, the distance / D last.
    row_lower, row_upper : ndarray
        Their bounds (the residual facets before T released, the distance row free).
    cost : ndarray
        The distance / D per variable.

    Returns
    -------
    GridProgram

    Examples
    --------
    >>> from sloshkit.sim.discretisation import velocity_driven_discretisation
    >>> matrices = velocity_driven_discretisation(29.66, 0.03, 0.01115, 2e-3)
    >>> program = GridProgram(Limits(0.05, 1.5, 20.0, 500.0, 0.0873, 0.00436, None, 4e-3, 2),
    ...                       [Pendulum(*matrices, 29.66, 0.03, 0.01115, 0.0, True, 0)], 10)
    >>> program.matrix.shape, float(program.row_upper[-1])
    ((573, 52), inf)
    """

    def __init__(self, limits: Limits, pendulums: list[Pendulum], steps: int) -> None:
        self.limits, self.pendulums, self.steps = limits, pendulums, steps
        self.matrix, self.row_lower, self.row_upper, self.cost = self._assemble(
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

    def column_bounds(self, bound: float) -> tuple[FloatArray, FloatArray]:
        """The variables' bounds: every scaled jerk, acceleration, velocity and limited angle
        within ``bound``, the move at rest at node N, the other states free.

        Parameters
        ----------
        bound : float
            The scaled limit (1 less the margin kept from every limit).

        Returns
        -------
        tuple of ndarray
            (lower, upper) per column.

        Examples
        --------
        >>> from sloshkit.sim.discretisation import velocity_driven_discretisation
        >>> matrices = velocity_driven_discretisation(29.66, 0.03, 0.01115, 2e-3)
        >>> program = GridProgram(Limits(0.05, 1.5, 20.0, 500.0, 0.0873, 0.00436, None, 4e-3, 2),
        ...                       [Pendulum(*matrices, 29.66, 0.03, 0.01115, 0.0, True, 0)], 3)
        >>> lower, upper = program.column_bounds(0.5)
        >>> lower[:9].tolist(), upper[9:11].tolist()
        ([-0.5, -0.5, -0.5, -0.5, -0.5, 0.0, -0.5, -0.5, 0.0], [0.5, inf])
        """
        n = self.steps
        col_lower = np.full(self.matrix.shape[1], -np.inf)
        col_lower[: 3 * n] = -bound
        for index, pend in enumerate(self.pendulums):
            if pend.limited:  # |theta| <= theta_max at the nodes and the last step's samples
                base, inner = self._state_base(index), self._end_base(index)
                col_lower[base : base + 2 * n : 2] = -bound
                col_lower[inner : inner + 2 * (self.limits.substeps - 1) : 2] = -bound
        col_upper = -col_lower
        _, ia, iv = self._columns()
        col_lower[[ia[-1], iv[-1]]] = col_upper[[ia[-1], iv[-1]]] = 0.0  # at rest at node N
        return col_lower, col_upper

    def retimed(
        self, tau: float
    ) -> tuple[list[tuple[int, int, float]], list[tuple[int, float]], list[tuple[int, bool]]]:
        """What changes with the last step's length: the kinematics of step N - 1 (its constant
        jerk integrated exactly: a_N = a_{N-1} + j tau, v_N = v_{N-1} + a_{N-1} tau + j tau^2 /
        2), its Bernstein midpoint, the distance it adds (v tau + a tau^2 / 2 + j tau^3 / 6,
        over D), the pendulums' exact response to it (`_substep_maps`, Franklin, Powell &
        Workman (1998) §6.3.2) and which residual facets bind (those at or after T).

        Parameters
        ----------
        tau : float
            The last step's length [s], in (0, Ts].

        Returns
        -------
        entries : list of tuple
            (row, column, value) of the matrix, zeros included.
        costs : list of tuple
            (column, value) of the distance / D.
        facets : list of tuple
            (first row, binds) of each block of `FACETS` residual rows.

        Examples
        --------
        >>> from sloshkit.sim.discretisation import velocity_driven_discretisation
        >>> matrices = velocity_driven_discretisation(29.66, 0.03, 0.01115, 2e-3)
        >>> program = GridProgram(Limits(0.05, 1.5, 20.0, 500.0, 0.0873, 0.00436, None, 4e-3, 2),
        ...                       [Pendulum(*matrices, 29.66, 0.03, 0.01115, 0.0, True, 0)], 3)
        >>> entries, costs, facets = program.retimed(3e-3)
        >>> entries[0] == (2, 2, -500.0 * 3e-3 / 20.0), costs[0] == (2, 500.0 * 3e-3**3 / 6 / 0.05)
        (True, True)
        >>> [binds for _, binds in facets]
        [False, True]
        """
        lim, n = self.limits, self.steps
        jmax, amax, vmax = lim.max_jerk_m_s3, lim.max_acceleration_m_s2, lim.max_velocity_m_s
        iu, ia, iv = self._columns()
        last, before, distance_row = n - 1, n - 2, self.matrix.shape[0] - 1
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
        costs = [(column, value / lim.distance_m) for column, value in costs]
        entries += [(distance_row, column, value) for column, value in costs]
        if lim.substeps > 1:
            entries += self._last_step_entries(tau)
        facets = [(start, self._residual_active(sub, tau)) for start, sub in self._facets]
        return entries, costs, facets
