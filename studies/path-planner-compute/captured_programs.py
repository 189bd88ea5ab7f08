"""Solve the cone programs of one optimal path plan again, offline, with other solvers.

Usage (from the repository root, in the project's venv)::

    python studies/path-planner-compute/captured_programs.py capture OUT_DIR -- PLAN_ARGS...
    python studies/path-planner-compute/captured_programs.py highs PROGRAM.pkl [PROGRAM.pkl ...]
    python studies/path-planner-compute/captured_programs.py generate PROGRAM.pkl [SPACING]
    python studies/path-planner-compute/captured_programs.py spline PROGRAM.pkl [SPACING ...]
    python studies/path-planner-compute/captured_programs.py scs PROGRAM.pkl [PROGRAM.pkl ...]

``capture`` runs ``sloshkit plan PLAN_ARGS`` with Clarabel wrapped, and pickles every program
of the export's period (more than 5,000 columns) that it solves. ``highs`` solves each program
as a linear program with HiGHS's dual simplex, each from the previous one's basis (the first
cold; with the first also by HiGHS's interior point), each cone replaced by an outer polytope:
16 half-planes for a two-vector and 32 for a three-vector. ``generate`` condenses the pendulum
states out (the dynamics equalities are block-triangular in them) and solves with only the
state-dependent cones that are within 30 % of binding at the linearisation point, adding the
violated ones until none is (with SPACING, on the program of ``spline``). ``spline`` writes the
timing's deviations as a cubic B-spline of control points SPACING samples apart (2, 4 and 8 by
default) and solves that program sparse and condensed. ``scs`` solves each program with SCS,
warm-started from the previous one (session 17). Each prints its solve times against
Clarabel's on the same program. The figures are in this folder's README.
"""

from __future__ import annotations

import contextlib
import pickle
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
from scipy import sparse
from scipy.sparse.linalg import splu

#: Columns above which a captured program is one of the export's period.
EXPORT_COLUMNS = 5000
#: Half-planes of the outer polytope of a two-vector cone; points on the sphere for three.
CIRCLE_FACETS, SPHERE_FACETS = 16, 32
#: A state-dependent cone within this fraction of binding enters the first program.
NEAR_BINDING = 0.3


def capture(out: Path, arguments: list[str]) -> None:
    """Run ``sloshkit plan`` with Clarabel's solver wrapped; pickle the export-period programs."""
    import clarabel

    from sloshkit.entry import main

    real = clarabel.DefaultSolver
    out.mkdir(parents=True, exist_ok=True)
    count = [0]

    def spy(P: Any, q: Any, A: Any, b: Any, cones: Any, settings: Any) -> Any:
        if A.shape[1] > EXPORT_COLUMNS:
            count[0] += 1
            with (out / f"program{count[0]:03d}.pkl").open("wb") as stream:
                pickle.dump((P, np.asarray(q), A, np.asarray(b), [repr(c) for c in cones]), stream)
        return real(P, q, A, b, cones, settings)

    clarabel.DefaultSolver = spy
    sys.argv = ["sloshkit", "plan", *arguments]
    with contextlib.suppress(SystemExit):  # the CLI exits; the count still prints
        main()
    print(f"{count[0]} programs in {out}", file=sys.stderr)


def _load(
    path: str,
) -> tuple[Any, np.ndarray, sparse.csr_matrix, np.ndarray, list[tuple[str, int]]]:
    with open(path, "rb") as stream:
        P, q, A, b, *_, reprs = pickle.load(stream)  # (older captures: a field more)
    cones = [(r.split("(")[0], int(r.split("(")[1].rstrip(")"))) for r in reprs]
    return P, q, sparse.csr_matrix(A), b, cones


def _clarabel(A: Any, b: np.ndarray, q: np.ndarray, cones: list[tuple[str, int]]) -> Any:
    import clarabel

    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.tol_gap_abs = settings.tol_gap_rel = 1e-6
    settings.tol_feas = 1e-7
    objects = [getattr(clarabel, name)(dim) for name, dim in cones]
    zero = sparse.csc_matrix((A.shape[1], A.shape[1]))
    started = time.perf_counter()
    result = clarabel.DefaultSolver(zero, q, sparse.csc_matrix(A), b, objects, settings).solve()
    return result, time.perf_counter() - started


def _directions(width: int) -> np.ndarray:
    if width == 2:
        angle = np.linspace(0.0, 2.0 * np.pi, CIRCLE_FACETS, endpoint=False)
        return np.column_stack((np.cos(angle), np.sin(angle)))
    k = np.arange(SPHERE_FACETS) + 0.5  # a Fibonacci sphere
    polar, azimuth = np.arccos(1.0 - 2.0 * k / SPHERE_FACETS), np.pi * (1.0 + 5**0.5) * k
    return np.column_stack(
        (np.cos(azimuth) * np.sin(polar), np.sin(azimuth) * np.sin(polar), np.cos(polar))
    )


def polyhedral(path: str) -> Any:
    """The program as a HiGHS linear program: s = b - A x in each cone; t >= d . u for the
    polytope's directions d of a cone (t, u)."""
    import highspy

    _, q, A, b, cones = _load(path)
    blocks, lower, upper, starts = [], [], [], []
    row = 0
    for name, dim in cones:
        if name == "ZeroConeT":
            blocks.append(A[row : row + dim])
            lower.append(b[row : row + dim])
            upper.append(b[row : row + dim])
        elif name == "NonnegativeConeT":
            blocks.append(A[row : row + dim])
            lower.append(np.full(dim, -np.inf))
            upper.append(b[row : row + dim])
        else:
            starts.append((row, dim))
        row += dim
    for width in (2, 3):
        heads = [start for start, dim in starts if dim == width + 1]
        if not heads:
            continue
        for direction in _directions(width):
            tail = [[start + 1 + j for start in heads] for j in range(width)]
            rows_u = sum(direction[j] * A[tail[j]] for j in range(width))
            b_u = sum(direction[j] * b[tail[j]] for j in range(width))
            blocks.append(A[heads] - rows_u)
            lower.append(np.full(len(heads), -np.inf))
            upper.append(b[heads] - b_u)
    matrix = sparse.vstack(blocks).tocsc()
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = matrix.shape[1], matrix.shape[0]
    inf = highspy.kHighsInf
    lp.col_cost_ = q
    lp.col_lower_ = np.full(matrix.shape[1], -inf)
    lp.col_upper_ = np.full(matrix.shape[1], inf)
    low = np.concatenate(lower)
    lp.row_lower_ = np.where(np.isinf(low), -inf, low)
    lp.row_upper_ = np.concatenate(upper)
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.start_ = matrix.indptr
    lp.a_matrix_.index_ = matrix.indices
    lp.a_matrix_.value_ = matrix.data
    return lp


def highs(paths: list[str]) -> None:
    """Each program by HiGHS's dual simplex from the previous basis (the first cold, and by
    HiGHS's interior point too), against Clarabel on the exact cones."""
    import highspy

    basis = None
    for index, path in enumerate(paths):
        _, q, A, b, cones = _load(path)
        reference, elapsed = _clarabel(A, b, q, cones)
        lp = polyhedral(path)
        print(f"{path}: polytope {lp.num_row_} rows; Clarabel {elapsed:.2f} s", flush=True)
        print(f"  Clarabel {reference.iterations} iterations", flush=True)
        for solver in ("simplex", "ipm") if index == 0 else ("simplex",):
            model = highspy.Highs()  # type: ignore[no-untyped-call]
            model.setOptionValue("output_flag", False)
            model.setOptionValue("solver", solver)
            model.passModel(lp)
            if solver == "simplex" and basis is not None:
                model.setBasis(basis)
            started = time.perf_counter()
            model.run()
            info = model.getInfo()
            start = "warm" if solver == "simplex" and basis is not None else "cold"
            print(
                f"  HiGHS {solver} ({start}): {time.perf_counter() - started:.2f} s, "
                f"{info.simplex_iteration_count} pivots, {info.ipm_iteration_count} IPM iterations",
                flush=True,
            )
            if solver == "simplex":
                basis = model.getBasis()


def generate(path: str, spacing: int = 0) -> None:
    """Constraint generation on the condensed program (module docstring); with ``spacing``,
    on the program whose timing deviations are the B-spline of `spline`."""
    _, q, A, b, cones = _load(path)
    steps = int(np.flatnonzero(q)[0])  # the objective's first column follows the timing's
    first = steps + 1
    if spacing:
        A, q, first = _on_spline(A, q, steps, spacing)
    started = time.perf_counter()
    dense, rhs, kinds, kept = _condensed(A, b, cones, first, steps)
    dense[np.abs(dense) < 1e-12 * np.abs(dense).max()] = 0.0
    built = time.perf_counter() - started
    units: list[tuple[str, int, int]] = []
    row = 0
    for name, dim in kinds:
        if name == "NonnegativeConeT":
            units += [(name, row + j, 1) for j in range(dim)]
        else:
            units.append((name, row, dim))
        row += dim
    width = (dense != 0).sum(axis=1)
    on_slosh = {u for u in units if u[0] != "ZeroConeT" and width[u[1] : u[1] + u[2]].max() > 60}
    rest = [u for u in units if u not in on_slosh]

    def program(selected: list[tuple[str, int, int]]) -> tuple[Any, np.ndarray, list[Any]]:
        first = {"ZeroConeT": 0, "NonnegativeConeT": 1}
        ordered = sorted(selected, key=lambda u: (first.get(u[0], 2), u[1]))
        rows = np.concatenate([np.arange(u[1], u[1] + u[2]) for u in ordered])
        kinds = [(u[0], u[2]) for u in ordered]
        return dense[rows], rhs[rows], kinds

    def slack(unit: tuple[str, int, int], x: np.ndarray) -> float:
        s = rhs[unit[1] : unit[1] + unit[2]] - dense[unit[1] : unit[1] + unit[2]] @ x
        return float(s[0] if unit[0] == "NonnegativeConeT" else s[0] - np.linalg.norm(s[1:]))

    whole, elapsed = _clarabel(*program(units)[:2], q[kept], program(units)[2])
    print(
        f"{path}: condensed {dense.shape[0]} rows x {dense.shape[1]} columns ({built:.2f} s); "
        f"{len(on_slosh)} cones on the states; whole: {elapsed:.2f} s, "
        f"{whole.iterations} iterations",
        flush=True,
    )
    x = np.zeros(kept.size)
    active = [u for u in on_slosh if slack(u, x) < NEAR_BINDING * max(abs(rhs[u[1]]), 1e-12)]
    total = 0.0
    for round_ in range(10):
        matrix, vector, kinds = program(rest + active)
        result, elapsed = _clarabel(matrix, vector, q[kept], kinds)
        total += elapsed
        x = np.asarray(result.x)
        chosen = set(active)
        violated = [u for u in on_slosh if u not in chosen and slack(u, x) < -1e-7 * abs(rhs[u[1]])]
        print(
            f"  round {round_}: {len(active)} cones on the states, {elapsed:.2f} s, "
            f"{result.iterations} iterations, objective {q[kept] @ x:.6g}; "
            f"violated {len(violated)}",
            flush=True,
        )
        if not violated:
            break
        active += violated
    print(
        f"  constraint generation: {total:.2f} s in all; "
        f"whole objective {q[kept] @ np.asarray(whole.x):.6g}"
    )


def _spline_basis(steps: int, spacing: int) -> sparse.csr_matrix:
    """The cubic B-spline design matrix of the timing's deviations: samples 1..steps (rows)
    against control points (columns) on uniform knots ``spacing`` samples apart, the samples'
    range covered."""
    from scipy.interpolate import BSpline

    count = int(np.ceil((steps - 1) / spacing)) + 3  # control points of a clamped-free cover
    knots = spacing * (np.arange(count + 4) - 3.0)
    design = BSpline.design_matrix(np.arange(steps, dtype=float), knots, 3, extrapolate=True)
    matrix = sparse.csr_matrix(design)
    return matrix[:, np.flatnonzero(np.asarray(abs(matrix).sum(axis=0)).ravel() > 0)]


def _on_spline(
    A: sparse.csr_matrix, q: np.ndarray, steps: int, spacing: int
) -> tuple[sparse.csr_matrix, np.ndarray, int]:
    """The program with its timing deviations d = B c (`_spline_basis`): its matrix and
    objective in c and the other columns, and the first state column."""
    basis = _spline_basis(steps, spacing)
    rest = sparse.identity(A.shape[1] - steps, format="csr")
    substitution = sparse.block_diag((basis, rest), format="csc")
    return sparse.csr_matrix(A @ substitution), substitution.T @ q, basis.shape[1] + 1


def _condensed(
    A: sparse.csr_matrix, b: np.ndarray, cones: list[tuple[str, int]], first: int, steps: int
) -> tuple[np.ndarray, np.ndarray, list[tuple[str, int]], np.ndarray]:
    """The program with the pendulum states (columns from ``first``, 18 per sample of a move
    of ``steps`` and its rest samples) eliminated through its dynamics equalities (they are
    block-triangular in them): dense rows in the other columns, their cones, the kept columns."""
    states = np.arange(first, first + 18 * (steps + 5))
    kept = np.setdiff1d(np.arange(A.shape[1]), states)
    zero = cones[0][1]
    on_states = A[:, states]
    dynamics = np.arange(zero)[np.diff(on_states[:zero].indptr) > 0]
    others = np.setdiff1d(np.arange(A.shape[0]), dynamics)
    gain = splu(on_states[dynamics].tocsc()).solve(
        np.column_stack((A[dynamics][:, kept].toarray(), b[dynamics]))
    )
    through = on_states[others] @ gain
    dense = A[others][:, kept].toarray() - through[:, :-1]
    kinds = [(n, d - dynamics.size if n == "ZeroConeT" else d) for n, d in cones]
    return dense, b[others] - through[:, -1], [k for k in kinds if k[1] > 0], kept


def spline(path: str, spacings: list[int]) -> None:
    """The timing's deviations d (the program's first columns, samples 1..N) as a cubic
    B-spline of control points ``spacing`` samples apart, d = B c: the program in c, with the
    pendulum states as variables (sparse) and eliminated (condensed), against the program
    itself. Prints the solve time, iterations and objective (the predicted margin) of each."""
    _, q, A, b, cones = _load(path)
    steps = int(np.flatnonzero(q)[0])
    reference, elapsed = _clarabel(A, b, q, cones)
    best = float(q @ np.asarray(reference.x))
    print(
        f"{path}: {A.shape[0]} rows x {A.shape[1]} columns, {steps} timing columns; "
        f"Clarabel {elapsed:.2f} s, {reference.iterations} iterations, objective {best:.6g}",
        flush=True,
    )
    for spacing in spacings:
        reduced, q_reduced, first = _on_spline(A, q, steps, spacing)
        result, elapsed = _clarabel(reduced, b, q_reduced, cones)
        objective = float(q_reduced @ np.asarray(result.x))
        dense, rhs, kinds, kept = _condensed(reduced, b, cones, first, steps)
        folded, folded_time = _clarabel(sparse.csr_matrix(dense), rhs, q_reduced[kept], kinds)
        print(
            f"  every {spacing} samples ({first - 1} control points): sparse "
            f"{reduced.shape[0]} x {reduced.shape[1]}, {elapsed:.2f} s, {result.iterations} "
            f"iterations, objective {objective:.6g} ({result.status}); condensed "
            f"{dense.shape[0]} x {dense.shape[1]}, {folded_time:.2f} s, {folded.iterations} "
            f"iterations, objective {float(q_reduced[kept] @ np.asarray(folded.x)):.6g}",
            flush=True,
        )


def first_order(paths: list[str]) -> None:
    """Each program by SCS (``pip install scs``; not a dependency of sloshkit) at 1e-4 and
    1e-5, warm-started from the previous program's solution, against Clarabel's defaults."""
    import clarabel
    import scs

    previous: tuple[Any, Any, Any] | None = None
    for path in paths:
        _, q, A, b, cones = _load(path)
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        objects = [getattr(clarabel, name)(dim) for name, dim in cones]
        zero = sparse.csc_matrix((A.shape[1], A.shape[1]))
        started = time.perf_counter()
        exact = clarabel.DefaultSolver(zero, q, sparse.csc_matrix(A), b, objects, settings).solve()
        clarabel_s = time.perf_counter() - started
        # SCS wants the rows ordered zero, nonnegative, second-order cones
        rows: dict[str, list[np.ndarray]] = {k: [] for k in _SCS_ORDER}
        start = 0
        for name, dim in cones:
            rows[name].append(np.arange(start, start + dim))
            start += dim
        order = np.concatenate([np.concatenate(rows[k]) for k in _SCS_ORDER if rows[k]])
        data = {"A": sparse.csc_matrix(A[order]), "b": np.asarray(b)[order], "c": np.asarray(q)}
        cone = {
            "z": sum(d for n, d in cones if n == "ZeroConeT"),
            "l": sum(d for n, d in cones if n == "NonnegativeConeT"),
            "q": [d for n, d in cones if n == "SecondOrderConeT"],
        }
        for eps in (1e-4, 1e-5):
            started = time.perf_counter()
            solver = scs.SCS(data, cone, eps_abs=eps, eps_rel=eps, verbose=False, max_iters=20000)
            warm = previous is not None and previous[0].shape == (A.shape[1],)
            out = (
                solver.solve(warm_start=True, x=previous[0], y=previous[1], s=previous[2])
                if warm and previous is not None
                else solver.solve()
            )
            print(
                f"{Path(path).name} SCS {eps:g}: {time.perf_counter() - started:.2f} s, "
                f"{out['info']['iter']} iterations, objective {out['info']['pobj']:.5e}; "
                f"Clarabel {clarabel_s:.2f} s, {exact.iterations}, {exact.obj_val:.5e}",
                flush=True,
            )
        previous = (out["x"], out["y"], out["s"])


_SCS_ORDER = ("ZeroConeT", "NonnegativeConeT", "SecondOrderConeT")


if __name__ == "__main__":
    command, rest = sys.argv[1], sys.argv[2:]
    if command == "capture":
        capture(Path(rest[0]), rest[2:] if rest[1:2] == ["--"] else rest[1:])
    elif command == "highs":
        highs(rest)
    elif command == "generate":
        generate(rest[0], int(rest[1]) if rest[1:] else 0)
    elif command == "spline":
        spline(rest[0], [int(k) for k in rest[1:]] or [2, 4, 8])
    elif command == "scs":
        first_order(rest)
    else:
        sys.exit(f"unknown command {command!r}: capture, highs, generate, spline or scs")
