"""Richardson study of the CFD damping of the seed paper's vial in mesh AND time step.

Runs 2 s of free decay (3 deg tilt, fixed Euler step, serial) on three uniform O-grids
(`MESHES` cells per radius, refinement ratio about 1.37) at three steps (`STEPS`), one row per
run in data/cfd-damping-study.json (resumable: finished rows are kept). ``--analyse`` then
extrapolates (`convergence`) and writes the damping section of README.md
between its markers, and the figure figures/cfd_damping_study.png.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_damping_study.py [--analyse-only]
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

# bench_cfd_speed (the benchmark every run of the study is) lives in benchmarks/.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from bench_cfd_speed import bench

from sloshkit.cfd.state import CfdError

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
MESHES = (8, 11, 15)
STEPS_MS = (2.0, 1.0, 0.5)
#: cheapest first, so that an interrupted study has complete coarse levels
PLAN = sorted(((n, dt) for n in MESHES for dt in STEPS_MS), key=lambda row: row[0] ** 2 / row[1])


#: Wall-graded meshes (data/cfd-wall-grading.json): a wall annulus of `radial_cells` graded
#: 0.1 (wall cells 0.105, 0.093, 0.069 mm; the Stokes layer is 0.25 mm). The 9-cell level
#: (0.121 mm, aspect ratio 30) was run first and replaced: stable at rest, but its two-phase
#: runs kept Courant numbers of 1-3 from parasitic currents (kept in the JSON, excluded).
GRADED_WALL = 0.1
GRADED_MESHES = {9: 6, 10: 7, 12: 8, 16: 11}  # cells per radius -> annulus cells
#: (cells per radius, step [ms]), in the order run
GRADED_PLAN = [(12, 2.0), (12, 1.0), (9, 2.0), (10, 2.0), (10, 1.0), (16, 2.0), (12, 0.5)]
#: Run one plan entry only (parallel processes): ``--only 16 2``.


#: Graded meshes that failed with a fixed step, run with sloshkit's default adaptive step
#: (Courant limits 0.5, largest step 2 ms): does the Courant limit keep them stable?
ADAPTIVE_PLAN = [(10, 2.0), (16, 2.0)]
#: The coarse uniform mesh with the second-order backward scheme for U (Euler for alpha).
BACKWARD_PLAN = [(8, 2.0), (8, 1.0)]


def run_plan(
    out: Path,
    work: Path,
    end_time_s: float,
    graded: bool = False,
    backward: bool = False,
    only: tuple[int, float] | None = None,
    adaptive: bool = False,
) -> None:
    """Run every (mesh, step) of `PLAN` (or of the graded family, or `BACKWARD_PLAN`) not in
    ``out`` yet."""
    rows = json.loads(out.read_text()) if out.is_file() else []
    done = {(r["cells_per_radius"], round(r["max_step_s"] * 1e3, 6)) for r in rows}
    plan = GRADED_PLAN if graded else BACKWARD_PLAN if backward else PLAN
    if adaptive:
        plan, graded = ADAPTIVE_PLAN, True
    for cells_per_radius, step_ms in plan:
        if (cells_per_radius, step_ms) in done or (only and (cells_per_radius, step_ms) != only):
            continue
        extra: dict[str, object] = {"ddt_scheme": "backward"} if backward else {}
        if graded:
            extra = {
                "radial_cells": GRADED_MESHES[cells_per_radius],
                "wall_grading": GRADED_WALL,
            }
        try:
            row = bench(
                work / f"n{cells_per_radius}-dt{step_ms:g}ms{'-graded' if graded else ''}"
                f"{'-backward' if backward else ''}{'-adaptive' if adaptive else ''}",
                cells_per_radius,
                1,
                end_time_s,
                step_ms * 1e-3,
                0.5,
                0.5,
                adjust_time_step=adaptive,
                **extra,  # type: ignore[arg-type]
            )
        except CfdError as error:  # a run that blows up is a result too
            row = {
                "cells_per_radius": cells_per_radius,
                "max_step_s": step_ms * 1e-3,
                **extra,
                "failed": str(error).splitlines()[0],
            }
        rows = json.loads(out.read_text()) if out.is_file() else []  # other processes' rows
        rows.append(row)
        print(json.dumps(row), flush=True)
        out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


def record_stall(out: Path, work: Path, cells_per_radius: int) -> None:
    """Record an adaptive graded run that was stopped because its step collapsed: the last
    simulated time, step and Courant number from its log."""
    case = work / f"n{cells_per_radius}-dt2ms-graded-adaptive"
    text = (case / "log.interFoam").read_text()
    times = re.findall(r"^Time = ([0-9.eE+-]+)", text, re.M)
    steps = re.findall(r"^deltaT = ([0-9.eE+-]+)", text, re.M)
    courant = re.findall(r"^Courant Number mean: \S+ max: (\S+)", text, re.M)
    rows = json.loads(out.read_text()) if out.is_file() else []
    rows.append(
        {
            "cells_per_radius": cells_per_radius,
            "max_step_s": 2e-3,
            "radial_cells": GRADED_MESHES[cells_per_radius],
            "wall_grading": GRADED_WALL,
            "adjust_time_step": True,
            "failed": f"adaptive step collapsed to {float(steps[-1]):.3g} s at t = "
            f"{float(times[-1]):.4g} s (largest Courant number {float(courant[-1]):.2f}); "
            "stopped",
        }
    )
    out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


def backfill(out: Path, work: Path, graded: bool = False, backward: bool = False) -> None:
    """Add ``max_courant_late`` to rows run before it was recorded (from their case logs)."""
    from bench_cfd_speed import late_courant

    if not out.is_file():
        return
    rows = json.loads(out.read_text())
    for row in rows:
        if "max_courant_late" not in row:
            step_ms = round(row["max_step_s"] * 1e3, 6)
            case = work / (
                f"n{row['cells_per_radius']}-dt{step_ms:g}ms{'-graded' if graded else ''}"
                f"{'-backward' if backward else ''}"
            )
            row["max_courant_late"] = late_courant(case)
    out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--analyse-only", action="store_true")
    parser.add_argument("--end-time", type=float, default=2.0)
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-damping"))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-damping-study.json")
    parser.add_argument("--graded-out", type=Path, default=DATA / "cfd-damping-graded.json")
    parser.add_argument("--graded", action="store_true", help="run the wall-graded meshes")
    parser.add_argument("--backward", action="store_true", help="backward scheme for U")
    parser.add_argument("--backward-out", type=Path, default=DATA / "cfd-damping-backward.json")
    parser.add_argument("--backfill", action="store_true", help="add late Courant numbers")
    parser.add_argument("--adaptive", action="store_true", help="graded meshes, adaptive step")
    parser.add_argument("--record-stall", type=int, default=None, help="CELLS of a stalled run")
    parser.add_argument("--adaptive-out", type=Path, default=DATA / "cfd-damping-adaptive.json")
    parser.add_argument("--only", nargs=2, type=float, default=None, help="CELLS STEP_MS")
    args = parser.parse_args()
    if args.record_stall is not None:
        record_stall(args.adaptive_out, args.work, args.record_stall)
        return
    if args.backfill:
        backfill(args.out, args.work)
        backfill(args.graded_out, args.work, graded=True)
        backfill(args.backward_out, args.work, backward=True)
        return
    if not args.analyse_only:
        if args.adaptive:
            only = None if args.only is None else (int(args.only[0]), args.only[1])
            run_plan(args.adaptive_out, args.work, args.end_time, adaptive=True, only=only)
        elif args.graded:
            only = None if args.only is None else (int(args.only[0]), args.only[1])
            run_plan(args.graded_out, args.work, args.end_time, graded=True, only=only)
        elif args.backward:
            run_plan(args.backward_out, args.work, args.end_time, backward=True)
        else:
            run_plan(args.out, args.work, args.end_time)


if __name__ == "__main__":
    main()
