"""The rows of the path planner's cone programs (`sloshkit.plan.path.cone`): a builder of
sparse conic rows b - A x in a cone (Clarabel's standard form: Goulart & Chen,
arXiv:2405.12762 (2024)) that also solves them, the finite-difference weights the kinematic
rows use, and the tilt's rows (its norm, rate and acceleration as second-order cones, and its
trust region).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import sparse

#: Forward-difference weights of orders 0..3 (the finite differences of the padded samples:
#: a difference of order p over p + 1 consecutive samples, divided by h^p).
DIFFERENCE_WEIGHTS = {0: (1.0,), 1: (-1.0, 1.0), 2: (1.0, -2.0, 1.0), 3: (-1.0, 3.0, -3.0, 1.0)}


class ConeRows:
    """Rows b - A x in a cone, gathered by kind: equalities (``"zero"``), inequalities
    (``"nonneg"``) and second-order cones (``"soc"``), assembled in that order.

    Examples
    --------
    >>> rows = ConeRows()
    >>> rows.add("zero", [0], [0], [1.0], [2.0])  # 2 - x0 = 0
    >>> rows.add("soc", [0, 1, 2], [2, 0, 1], [-1.0, -1.0, -1.0], [0.0, 0.0, 0.0], [3])
    >>> matrix, rhs, cones = rows.assemble(3)  # -(t, x0, x1) in the cone |(x0, x1)| <= t
    >>> matrix.shape, [type(cone).__name__ for cone in cones]
    ((4, 3), ['ZeroConeT', 'SecondOrderConeT'])
    """

    def __init__(self) -> None:
        self.parts: dict[str, list[tuple[Any, Any, Any, Any]]] = {
            "zero": [],
            "nonneg": [],
            "soc": [],
        }
        self.soc_dims: list[int] = []

    def add(self, kind: str, r: Any, c: Any, v: Any, b: Any, dims: list[int] | None = None) -> None:
        """Rows with local indices r: b_r - sum A_rc x_c in the cone (``dims``: the sizes of
        consecutive second-order cones)."""
        self.parts[kind].append(
            (
                np.asarray(r, dtype=int),
                np.asarray(c, dtype=int),
                np.asarray(v, dtype=float),
                np.asarray(b, dtype=float),
            )
        )
        if dims is not None:
            self.soc_dims += dims

    def assemble(self, columns: int) -> tuple[Any, Any, list[Any]]:
        """The sparse matrix A (CSC, ``columns`` wide), b and Clarabel's cones."""
        import clarabel

        rows, cols, vals, rhs, cones = [], [], [], [], []
        offset = 0
        for kind in ("zero", "nonneg", "soc"):
            count = 0
            for r, c, v, b in self.parts[kind]:
                rows.append(r + offset + count)
                cols.append(c)
                vals.append(v)
                rhs.append(b)
                count += b.size
            if count:
                if kind == "zero":
                    cones.append(clarabel.ZeroConeT(count))
                elif kind == "nonneg":
                    cones.append(clarabel.NonnegativeConeT(count))
            offset += count
        cones += [clarabel.SecondOrderConeT(d) for d in self.soc_dims]
        matrix = sparse.coo_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(offset, columns),
        ).tocsc()
        return matrix, np.concatenate(rhs), cones

    def solve(self, objective: Any) -> Any:
        """Minimise objective . x over the rows (Clarabel, gap tolerances 1e-6, feasibility
        1e-7: the linearisation is re-evaluated exactly after each solve).

        Parameters
        ----------
        objective : numpy.ndarray
            The linear cost, one entry per column.

        Returns
        -------
        clarabel.DefaultSolution or None
            The solution, None unless Clarabel solved or almost solved the program (the
            searches then shrink their trust region).

        Examples
        --------
        >>> rows = ConeRows()
        >>> rows.add("nonneg", [0, 1], [0, 0], [-1.0, 1.0], [-1.0, 3.0])  # 1 <= x0 <= 3
        >>> round(rows.solve(np.array([1.0])).x[0], 6)
        1.0
        """
        import clarabel

        columns = len(objective)
        matrix, rhs, cones = self.assemble(columns)
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        settings.tol_gap_abs = settings.tol_gap_rel = 1e-6
        settings.tol_feas = 1e-7
        quadratic = sparse.csc_matrix((columns, columns))
        result = clarabel.DefaultSolver(quadratic, objective, matrix, rhs, cones, settings).solve()
        return result if str(result.status) in ("Solved", "AlmostSolved") else None


def vector_cones(
    conic: ConeRows,
    r_idx: list[Any],
    c_idx: list[Any],
    v_idx: list[Any],
    scaled: Any,
    keep: float,
) -> None:
    """One cone per row of ``scaled`` (vectors over their limit, (rows, n)): the linearised
    vector within keep + sigma, the entries of its rows gathered in the index lists (cone row
    (n + 1) i is the bound, the next n the vector's components).

    Parameters
    ----------
    conic : ConeRows
        Receives the cones.
    r_idx, c_idx, v_idx : list of array_like
        Local rows, columns and values of -A.
    scaled : ndarray
        The current values over their limit, (rows, n).
    keep : float
        The bound at zero margin (1 - the program's margin).

    Examples
    --------
    >>> conic = ConeRows()
    >>> vector_cones(conic, [[0]], [[0]], [[-1.0]], np.array([[0.5, 0.0, 0.0]]), 1.0)
    >>> matrix, rhs, cones = conic.assemble(1)
    >>> rhs.tolist(), matrix.toarray().ravel().tolist()  # 1 - (-x) in the cone's bound
    ([1.0, 0.5, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0])
    """
    rows, width = scaled.shape[0], scaled.shape[1] + 1
    b = np.zeros((rows, width))
    b[:, 0] = keep
    b[:, 1:] = scaled
    conic.add(
        "soc",
        np.concatenate(r_idx),
        np.concatenate(c_idx),
        np.concatenate(v_idx),
        b.ravel(),
        [width] * rows,
    )


def tilt_rows(
    conic: ConeRows,
    tilt_rad: Any,
    period_s: float,
    lim: Any,
    base: int,
    scale: float,
    sigma: int,
    keep: float,
    trust: float,
    dilation: int,
    dilate: bool,
) -> None:
    """The tilt's cones: |r_k|, |r_k+1 - r_k| / h and |r_k+1 - 2 r_k + r_k-1| / h^2 within
    keep + sigma of their limits (exact: linear in the deviations; a free period scales the
    differences of order p as h^-p), and its trust region |change| <= min(trust, 1) max_tilt.

    Parameters
    ----------
    conic : ConeRows
        Receives the rows.
    tilt_rad : ndarray
        The current tilt (r_x, r_y) of samples 0..N, (N + 1, 2); r_0 = r_N = 0 and the rest
        samples hold r_N.
    period_s : float
        The sample period h [s].
    lim : ProgramLimits
        ``max_tilt_rad``, ``max_tilt_rate_rad_s``, ``max_tilt_acceleration_rad_s2``.
    base : int
        The column of sample 1's r_x deviation (then r_y, then sample 2's, ...).
    scale : float
        The unit of the deviations [rad].
    sigma : int
        The margin's column.
    keep : float
        The bound at zero margin.
    trust : float
        The step's trust region in m/s, read as a fraction of the tilt range per program.
    dilation : int
        The period's relative change's column (used when ``dilate``).
    dilate : bool
        Whether the period is free.

    Examples
    --------
    >>> from sloshkit.plan.path.program import ProgramLimits
    >>> lim = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002, max_tilt_rad=0.5,
    ...     max_tilt_rate_rad_s=3.0, max_tilt_acceleration_rad_s2=20.0)
    >>> conic = ConeRows()
    >>> tilt = np.array([[0.0, 0.0], [0.1, 0.0], [0.0, 0.0]])  # N = 2: one free sample
    >>> tilt_rows(conic, tilt, 0.1, lim, 1, 1.0, 0, 1.0, 0.1, 3, False)
    >>> matrix, rhs, cones = conic.assemble(3)
    >>> rhs[4:10].round(3).tolist()  # the tilt 0.1 of 0.5 rad, the first rate 1 of 3 rad/s
    [1.0, 0.2, 0.0, 1.0, 0.333, 0.0]
    """
    tilt, ts = np.asarray(tilt_rad, dtype=float), period_s
    last = tilt.shape[0] - 1

    def column(k: Any, c: int) -> Any:
        return base + (np.asarray(k) - 1) * 2 + c

    for order, limit, first, rows in (
        (0, lim.max_tilt_rad, 1, last - 1),
        (1, lim.max_tilt_rate_rad_s, 0, last),
        (2, lim.max_tilt_acceleration_rad_s2, 0, last + 1),
    ):
        row = np.arange(rows)
        values = np.zeros((rows, 2))
        r_idx, c_idx, v_idx = [row * 3], [np.full(rows, sigma)], [np.full(rows, -1.0)]
        # row i of order p differences the samples i + first - (p == 2) ... onwards
        start = row + first - (1 if order == 2 else 0)
        for j, weight in enumerate(DIFFERENCE_WEIGHTS[order]):
            k = start + j
            values += weight * tilt[np.clip(k, 0, last)] / ts**order
            free = (k >= 1) & (k <= last - 1)
            for c in (0, 1):
                r_idx.append(row[free] * 3 + 1 + c)
                c_idx.append(column(k[free], c))
                v_idx.append(np.full(int(free.sum()), -weight * scale / ts**order / limit))
        if dilate and order:
            for c in (0, 1):
                r_idx.append(row * 3 + 1 + c)
                c_idx.append(np.full(rows, dilation))
                v_idx.append(order * values[:, c] / limit)
        vector_cones(conic, r_idx, c_idx, v_idx, values / limit, keep)
    inner = np.arange(2 * (last - 1))
    bound = np.full(inner.size, min(trust, 1.0) * lim.max_tilt_rad / scale)
    conic.add("nonneg", inner, base + inner, np.ones(inner.size), bound)
    conic.add("nonneg", inner, base + inner, -np.ones(inner.size), bound)


__all__ = ["DIFFERENCE_WEIGHTS", "ConeRows", "tilt_rows", "vector_cones"]
