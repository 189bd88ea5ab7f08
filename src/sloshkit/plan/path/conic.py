"""The path programs' second-order cones: groups of vector rows that a linearised program keeps
within a limit, and the program itself assembled from them for Clarabel.

A group of rows (`NormRows`) is one limited quantity at every sample, a vector v_k + D_k z
(for example the acceleration at sample k, linear in the variables z), held within
``limit`` (keep + sigma) by the second-order cone (keep + sigma, (v_k + D_k z) / limit)
(Boyd & Vandenberghe, *Convex Optimization* (2004) §4.4.2). `ConicProgram` gathers such
cones, equality and inequality rows as COO triplets in Clarabel's form b - A x in a cone and
solves the program with Clarabel (Goulart & Chen, arXiv:2405.12762 (2024)).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import sparse

FloatArray = NDArray[np.float64]

#: A row is in the first program when it is a local peak above this fraction of its limit
#: (the rest enter when a solution breaks them).
ACTIVE_FRACTION = 0.6
#: Clarabel's gap tolerances (its feasibility tolerance a tenth of them): a program's
#: solution is a trust-region step, re-evaluated exactly before it is kept.
SOLVER_GAP = 1e-6


@dataclass(frozen=True, eq=False)
class NormRows:
    """Vector rows |values + Dz z + Dx x_seg| / limit <= keep + sigma, one per sample.

    Parameters
    ----------
    values : numpy.ndarray
        (rows, d): the vectors at the current point.
    dz : numpy.ndarray
        (rows, d, nz): their derivatives in the first nz variables (the splines).
    limit : float
        The limit of their norm.
    dx : numpy.ndarray, optional
        (rows, d, w): their derivatives in the start states of each row's segment.
    first : numpy.ndarray, optional
        (rows,): the column of each row's first start state (negative: none, the first
        segment starts at rest).

    Examples
    --------
    >>> import numpy as np
    >>> rows = NormRows(np.array([[3.0, 4.0], [0.0, 1.0]]), np.zeros((2, 2, 1)), 5.0)
    >>> rows.predicted(np.zeros(1), 1)
    array([1. , 0.2])
    """

    values: FloatArray
    dz: FloatArray
    limit: float
    dx: FloatArray | None = None
    first: NDArray[np.int64] | None = None

    def predicted(self, x: FloatArray, nz: int) -> FloatArray:
        """The rows' linearised norms over the limit at the solution ``x``."""
        vector = self.values + self.dz @ x[:nz]
        if self.dx is not None and self.first is not None:
            has = self.first >= 0
            columns = self.first[has, None] + np.arange(self.dx.shape[2])[None]
            vector[has] += np.einsum("rdw,rw->rd", self.dx[has], x[columns])
        return np.asarray(np.linalg.norm(vector, axis=1) / self.limit)

    def initial(self, keep: float) -> NDArray[np.bool_]:
        """The rows of the first program: local peaks above `ACTIVE_FRACTION` and their
        neighbours, and every row above 0.97 ``keep``."""
        norms = np.linalg.norm(self.values, axis=1) / self.limit
        peak = np.zeros(norms.size, dtype=bool)
        peak[1:-1] = (norms[1:-1] >= norms[:-2]) & (norms[1:-1] >= norms[2:])
        peak |= norms >= 0.97 * keep
        peak &= norms >= ACTIVE_FRACTION * keep
        return np.asarray(peak | np.roll(peak, 1) | np.roll(peak, -1))


class ConicProgram:
    """Rows b - A x in Clarabel's zero, nonnegative and second-order cones, gathered as COO
    triplets (local row indices, columns, values, b) and solved by `solve`.

    Examples
    --------
    >>> import numpy as np
    >>> program = ConicProgram()  # minimise -x0 - x1 with |(x0, x1)| <= 1
    >>> program.add_soc([1, 2], [0, 1], [-1.0, -1.0], [1.0, 0.0, 0.0], [3])
    >>> np.round(program.solve(np.array([-1.0, -1.0])), 4)
    array([0.7071, 0.7071])
    """

    def __init__(self) -> None:
        self.parts: dict[str, list[tuple[Any, Any, Any, Any]]] = {"zero": [], "nonneg": []}
        self.soc: list[tuple[Any, Any, Any, Any]] = []
        self.soc_dims: list[int] = []

    def add(self, kind: str, r: Any, c: Any, v: Any, b: Any) -> None:
        """Rows (local indices r) of ``kind`` "zero" or "nonneg"."""
        self.parts[kind].append(
            (np.asarray(r, int), np.asarray(c, int), np.asarray(v, float), np.asarray(b, float))
        )

    def add_soc(self, r: Any, c: Any, v: Any, b: Any, dims: list[int]) -> None:
        """Consecutive second-order cones of sizes ``dims``."""
        self.soc.append(
            (np.asarray(r, int), np.asarray(c, int), np.asarray(v, float), np.asarray(b, float))
        )
        self.soc_dims += dims

    def add_rows(self, rows: NormRows, use: NDArray[np.bool_], slack: int, keep: float) -> None:
        """The cones of the selected rows: (keep + sigma, (values + D x) / limit), sigma the
        column ``slack``."""
        index = np.flatnonzero(use)
        if not index.size:
            return
        d = rows.values.shape[1]
        width = d + 1
        base = np.arange(index.size) * width
        r = [base]
        c = [np.full(index.size, slack)]
        v = [-np.ones(index.size)]
        dz = rows.dz[index] / rows.limit
        local, comp, col = np.nonzero(dz)
        r.append(base[local] + 1 + comp)
        c.append(col)
        v.append(-dz[local, comp, col])
        if rows.dx is not None and rows.first is not None:
            dx = rows.dx[index] / rows.limit
            first = rows.first[index]
            local, comp, col = np.nonzero(dx * (first >= 0)[:, None, None])
            r.append(base[local] + 1 + comp)
            c.append(first[local] + col)
            v.append(-dx[local, comp, col])
        b = np.zeros((index.size, width))
        b[:, 0] = keep
        b[:, 1:] = rows.values[index] / rows.limit
        self.add_soc(
            np.concatenate(r), np.concatenate(c), np.concatenate(v), b.ravel(), [width] * index.size
        )

    def solve(
        self,
        objective: FloatArray,
        extra: Sequence[ConicProgram] = (),
        scale: FloatArray | None = None,
    ) -> FloatArray | None:
        """Minimise objective . x over these rows and ``extra``'s (Clarabel, `SOLVER_GAP`),
        the columns solved in units of ``scale`` (x = scale y, so that every variable is of
        order one); None unless solved."""
        import clarabel

        columns = objective.size
        rows, cols, vals, rhs, cones = [], [], [], [], []
        offset = 0
        for kind in ("zero", "nonneg"):
            count = 0
            for part in [self, *extra]:
                for r, c, v, b in part.parts[kind]:
                    rows.append(r + offset + count)
                    cols.append(c)
                    vals.append(v)
                    rhs.append(b)
                    count += b.size
            if count:
                cone = clarabel.ZeroConeT if kind == "zero" else clarabel.NonnegativeConeT
                cones.append(cone(count))
            offset += count
        for part in [self, *extra]:
            for r, c, v, b in part.soc:
                rows.append(r + offset)
                cols.append(c)
                vals.append(v)
                rhs.append(b)
                offset += b.size
            cones += [clarabel.SecondOrderConeT(d) for d in part.soc_dims]
        matrix = sparse.coo_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(offset, columns),
        ).tocsc()
        if scale is not None:
            matrix = (matrix @ sparse.diags(scale)).tocsc()
            objective = objective * scale
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        settings.tol_gap_abs = settings.tol_gap_rel = SOLVER_GAP
        settings.tol_feas = 0.1 * SOLVER_GAP
        # without iterative refinement of the KKT solves: the same optima to 6e-8 on the 66
        # programs of a tilted TRD_2D plan, in 28 % less time (docs/planning-3d.md, "Compute")
        settings.iterative_refinement_enable = False
        quadratic = sparse.csc_matrix((columns, columns))
        solver = clarabel.DefaultSolver(
            quadratic, objective, matrix, np.concatenate(rhs), cones, settings
        )
        result = solver.solve()
        if str(result.status) not in ("Solved", "AlmostSolved"):
            return None
        solution = np.asarray(result.x)
        return solution * scale if scale is not None else solution


__all__ = ["ACTIVE_FRACTION", "SOLVER_GAP", "ConicProgram", "NormRows"]
