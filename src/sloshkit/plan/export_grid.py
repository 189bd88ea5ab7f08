"""The minimum-time problem on the controller's export grid, as linear programs (HiGHS).

The move is a piecewise-constant jerk on the export grid t_k = k Ts: N - 1 full steps and a
last, shorter step of length tau in (0, Ts], so that T = (N - 1) Ts + tau is continuous. The
slosh is what the verification simulates: the exported velocity samples v_k = v(k Ts) (v_N = 0,
the move is over at the last sample) drive the exact first-order-hold discretisation of each
pendulum (Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998)
§6.3.2): z_{k+1} = Phi z_k + Gamma v_k, theta_k = z_k + g1 v_k. The pendulums run on the slosh
check grid (each step split into ``Limits.substeps`` sub-steps no longer than the finest
controller period, 2 ms; `sloshkit.plan.verification.slosh_substeps`), driven by the exact
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
is the root of D*(T) = D (`sloshkit.plan.optimal`). The move of distance D at that duration is
the longest move scaled by D / D*.

The smooth variant at a fixed, slightly longer duration minimises the total variation of the
jerk (the L1 norm of its rate, sum |u_k - u_{k-1}|) over the same constraints with the
distance fixed: another linear program (HiGHS's quadratic solver took seconds on the squared
rate).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from sloshkit.highs import new_highs
from sloshkit.plan.grid_moves import Limits, Move, Pendulum, measure, steps_for_duration

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
    """A sparse matrix as (row, column, value) entries, duplicates summed."""

    rows: NDArray[np.int64]
    columns: NDArray[np.int64]
    values: FloatArray
    shape: tuple[int, int]

    @classmethod
    def summed(
        cls, rows: NDArray[np.int64], columns: NDArray[np.int64], values: FloatArray,
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

    The pendulum states (theta, theta' + v / L) at the samples are variables, so the angle
    limits are bounds, not rows. A solution is never trusted as it stands: its end state is
    projected onto rest (the solver meets equalities to 1e-7 only), and the move is simulated
    again with the verification's discretisation; its reach is the distance divided by the
    largest ratio of any quantity to its limit (every constraint is homogeneous).

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
        self._fine = steps * limits.substeps  # slosh check sub-samples 1..M
        self.programs = 0
        self.iterations = 0
        self._highs: Any = None
        self._state: tuple[int, float] = (-1, -1.0)
        self._matrix, self._row_lower, self._row_upper, self._cost = self._assemble(
            limits.sample_period_s
        )

    # Layout: u (jerk / jmax) 0..N-1, a (/ amax) and v (/ vmax) at nodes 1..N, then per
    # pendulum its states (theta / theta_max, y / (vmax / L)) at samples 1..N.
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
        width = 3 * n + 2 * len(self.pendulums) * self._fine
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
        # Pendulums on the slosh check grid (m sub-samples per step, m = limits.substeps), in
        # s = z + g1 v: s_{j+1} = Phi s_j + g1 v_{j+1} + (Gamma - Phi g1) v_j, v_j the velocity
        # at sub-sample j (a combination of its step's node v, a and jerk; 0 from T on).
        fine = self._fine
        listed = self._velocity_terms(tau)
        terms = (
            np.array([t[0] for t in listed], dtype=np.int64),
            np.array([t[1] for t in listed], dtype=np.int64),
            np.array([t[2] for t in listed], dtype=float),
        )
        for index, pend in enumerate(self.pendulums):
            scale = np.array([lim.max_angle_rad, vmax / pend.length_m])
            phi = pend.phi * scale[None, :] / scale[:, None]
            now = pend.g1 * vmax / scale
            before = (pend.gamma - pend.phi @ pend.g1) * vmax / scale
            base = 3 * n + 2 * fine * index
            samples = np.arange(fine)  # sub-samples 1..M at positions 0..M-1
            for c in range(2):
                here = row + 2 * samples + c
                put(here, base + 2 * samples + c, 1.0)
                for d in range(2):
                    put(here[1:], base + 2 * samples[:-1] + d, -phi[c, d])
            sample, column, weight = terms
            later = sample < fine
            for c in range(2):
                put(row + 2 * (sample - 1) + c, column, -now[c] * weight)
                put(row + 2 * sample[later] + c, column[later], -before[c] * weight[later])
            row += 2 * fine
        equalities = row
        # Two-sided rows |row| <= 1: the velocity within each step (its Bernstein midpoint
        # v_k + a_k h_k / 2 bounds the quadratic with v_k and v_{k+1}), the wall elevation.
        mid = np.arange(n - 1)
        put(row + mid, iv[mid], 1.0)
        put(row + mid, ia[mid], amax * h[1:] / (2 * vmax))
        row += n - 1
        if lim.max_wall_elevation_m is not None:
            samples = np.arange(fine)
            for model in sorted({p.model for p in self.pendulums}):
                for index, pend in enumerate(self.pendulums):
                    if pend.model == model:
                        base = 3 * n + 2 * fine * index
                        factor = pend.wall_factor_m * lim.max_angle_rad / lim.max_wall_elevation_m
                        put(row + samples, base + 2 * samples, factor)
                row += fine
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
                for sub in range(1, lim.substeps + 1):
                    last = 3 * n + 2 * fine * index + 2 * (fine - lim.substeps + sub - 1)
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

    def _velocity_terms(self, tau: float) -> list[tuple[int, int, float]]:
        """(sub-sample j in 1..M, column, weight): the velocity at j / vmax as a combination
        of the node velocity, node acceleration and step jerk (scaled variables); the
        sub-samples of the last step at or after T (offset >= tau) have none (at rest)."""
        lim, n, m = self.limits, self.steps, self.limits.substeps
        iu, ia, iv = self._columns()
        vmax = lim.max_velocity_m_s
        terms: list[tuple[int, int, float]] = []
        for j in range(1, self._fine + 1):
            step, sub = divmod(j, m)
            if sub == 0:  # a node (node n is fixed at rest)
                terms.append((j, int(iv[step - 1]), 1.0))
                continue
            offset = sub * lim.slosh_period_s
            if step == n - 1 and offset >= tau - 1e-12:
                continue
            if step >= 1:
                terms.append((j, int(iv[step - 1]), 1.0))
                terms.append((j, int(ia[step - 1]), lim.max_acceleration_m_s2 * offset / vmax))
            terms.append((j, int(iu[step]), lim.max_jerk_m_s3 * offset**2 / (2 * vmax)))
        return terms

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
            if pend.limited:  # |theta| <= theta_max at samples 1..N
                fine = self._fine
                col_lower[3 * n + 2 * fine * index : 3 * n + 2 * fine * (index + 1) : 2] = -bound
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
        lp.a_matrix_.start_, lp.a_matrix_.index_, lp.a_matrix_.value_ = (
            matrix.compressed_columns()
        )
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
            bernstein = 2 * n + 2 * len(self.pendulums) * self._fine + before
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

    def _last_step_entries(self, tau: float) -> list[tuple[int, int, float]]:
        """The recursion coefficients of the last step's sub-samples for a last step ``tau``
        (those at or after T drop their velocity terms): (row, column, value), every entry of
        those rows on the last step's columns, zeros included."""
        lim, n, m, fine = self.limits, self.steps, self.limits.substeps, self._fine
        iu, ia, iv = self._columns()
        columns = [int(iu[n - 1])] + ([int(iv[n - 2]), int(ia[n - 2])] if n > 1 else [])
        first = (n - 1) * m + 1
        weights: dict[int, dict[int, float]] = {}
        for j, column, weight in self._velocity_terms(tau):
            if j >= first - 1 and column in columns:
                weights.setdefault(j, {})[column] = weight
        entries = []
        for index, pend in enumerate(self.pendulums):
            scale = np.array([lim.max_angle_rad, lim.max_velocity_m_s / pend.length_m])
            now = pend.g1 * lim.max_velocity_m_s / scale
            before = (pend.gamma - pend.phi @ pend.g1) * lim.max_velocity_m_s / scale
            row = 2 * n + 2 * fine * index
            for j in range(first, fine + 1):
                for c in range(2):
                    for column in columns:
                        value = -now[c] * weights.get(j, {}).get(column, 0.0)
                        value -= before[c] * weights.get(j - 1, {}).get(column, 0.0)
                        entries.append((row + 2 * (j - 1) + c, column, float(value)))
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
        if self.steps * len(self.pendulums) > IPM_SIZE:
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
