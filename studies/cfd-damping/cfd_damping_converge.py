"""Session-3 runs of the CFD damping study: the time step towards its asymptotic range, a
second-order (Crank-Nicolson) family, and wall-graded meshes that might form a family.

Each entry of `PLAN` is one serial free decay of the seed vial (3 deg tilt, fixed step, the
same 2 s window as data/cfd-damping-study.json unless stated); one row per run, keyed by the
entry's name, goes to data/cfd-damping-converge.json (resumable: finished keys are kept, a run
that blows up or is refused is a row with ``failed``). `studies/cfd-damping/cfd_damping_analysis.py`
reads the rows.

Run: PYTHONPATH=src nice -n 5 python studies/cfd-damping/cfd_damping_converge.py [--only KEY ...]
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path
from typing import Any

# bench_cfd_speed (the benchmark every run of the study is) lives in benchmarks/.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from bench_cfd_speed import bench

from sloshkit.cfd.state import CfdError
from sloshkit.errors import InputError

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
CN = "CrankNicolson 0.9"


def entry(
    cells: int,
    step_ms: float,
    ddt: str = "Euler",
    grading: float = 1.0,
    radial: int | None = None,
    end_s: float = 2.0,
    predictor: bool = False,
    surface: int = 2,
    tilt: float = 3.0,
) -> dict[str, Any]:
    """One planned run, named by its settings."""
    name = f"n{cells}-dt{step_ms:g}ms"
    if ddt != "Euler":
        name += "-cn" if ddt == CN else f"-{ddt}"
    if grading < 1.0:
        name += f"-g{grading:g}r{radial}"
    if end_s != 2.0:
        name += f"-t{end_s:g}s"
    if predictor:
        name += "-mp"
    if surface != 2:
        name += f"-s{surface}"
    if tilt != 3.0:
        name += f"-tilt{tilt:g}"
    return {
        "key": name,
        "cells_per_radius": cells,
        "step_ms": step_ms,
        "ddt_scheme": ddt,
        "wall_grading": grading,
        "radial_cells": radial,
        "end_time_s": end_s,
        "momentum_predictor": predictor,
        "surface_refinement": surface,
        "tilt_deg": tilt,
    }


#: The plan; the rows of data/cfd-damping-converge.json are in the order actually run (the
#: graded 16/radius mesh damped less at 2 ms than its neighbours, so its 1 ms run went before
#: the cheaper checks).
PLAN = [
    entry(8, 0.25),
    entry(8, 2.0, CN),
    entry(8, 1.0, CN),
    entry(8, 0.5, CN),
    entry(8, 0.125),
    entry(11, 0.25),
    entry(8, 0.25, CN),
    entry(8, 0.0625),
    entry(8, 0.125, CN),
    # the wall-graded family at a fixed grading of 0.25 (data/cfd-damping-graded-meshes.json):
    # cells per radius and annulus cells refined together by about 4/3
    entry(9, 2.0, grading=0.25, radial=7),
    entry(12, 2.0, grading=0.25, radial=10),
    entry(9, 1.0, grading=0.25, radial=7),
    entry(12, 1.0, grading=0.25, radial=10),
    entry(16, 2.0, grading=0.25, radial=13),
    entry(9, 0.5, grading=0.25, radial=7),
    entry(16, 1.0, grading=0.25, radial=13),
    # not run: 12/radius at 0.5 ms and 9/radius at 0.25 ms (the 9/radius run at 0.5 ms was
    # already swamped by parasitic currents)
    # session 4: the momentum predictor against the 2-step oscillation of the wall force at
    # small steps (README.md, *Damping*): it did not remove it on 9/radius at 0.5 ms, and the
    # 16/radius mesh blew up at its start at 1 ms; the rest of its series was not run
    entry(9, 0.5, grading=0.25, radial=7, predictor=True),
    entry(16, 1.0, grading=0.25, radial=13, predictor=True),
    # session 4: the finest graded mesh, clean at 1 and 2 ms, at a smaller step, and the next
    # mesh of the family (20/radius, 16 annulus cells, 179,200 cells)
    entry(16, 0.5, grading=0.25, radial=13),  # stopped at 0.7 s: force noise 0.6-1.1 (below)
    entry(20, 2.0, grading=0.25, radial=16),
    entry(20, 1.0, grading=0.25, radial=16),
    # session 4: is it the free surface? The slosh amplitude at the wall (1.07 mm) is about one
    # vertical cell of the default band (R/2N: 0.85 mm at 12/radius); s4 halves those cells
    entry(12, 2.0, grading=0.25, radial=10, surface=4),
    # session 4: a 4 ms step on every graded mesh, so that each has three steps of its own
    # (the steps below 1 ms carry the noise)
    entry(16, 4.0, grading=0.25, radial=13),
    entry(12, 4.0, grading=0.25, radial=10),
    entry(9, 4.0, grading=0.25, radial=7),
    # session 4: the next mesh after 20/radius at the step where 20/radius did not move
    entry(24, 2.0, grading=0.25, radial=19),
    {**entry(24, 1.0, grading=0.25, radial=19), "processes": 2},  # 2 ranks: 304,128 cells
    {**entry(28, 2.0, grading=0.25, radial=22), "processes": 2},
    # (not run: 20/radius at 4 ms; 16/radius at 4 ms already had a late Courant number of 1.4)
    # session 4: a second time scheme on the finest clean graded mesh at the smallest clean step
    # (the step error of Euler at 1 ms against Crank-Nicolson's); it blew up at 0.05 s
    entry(16, 1.0, CN, grading=0.25, radial=13),
    # session 4: twice the tilt (slosh amplitude 2.1 mm at the wall, about 2.5 default cells at
    # 12/radius): does the damping depend on the amplitude measured in cells?
    entry(12, 2.0, grading=0.25, radial=10, tilt=6.0),
    entry(16, 2.0, grading=0.25, radial=13, surface=4),
    entry(9, 1.0, grading=0.25, radial=7, tilt=6.0),
    entry(9, 0.5, grading=0.25, radial=7, tilt=6.0),
    # session 5: a third step for the finest meshes between the clean 1 ms and the noisy 0.5 ms
    # (step ratio 1.43), so that each has three steps of its own below 4 ms
    entry(16, 0.7, grading=0.25, radial=13),
    entry(20, 0.7, grading=0.25, radial=16),
    {**entry(24, 0.7, grading=0.25, radial=19), "processes": 2},
    entry(12, 0.7, grading=0.25, radial=10),
    entry(9, 0.7, grading=0.25, radial=7),
    # session 5: the finest mesh at 1 ms, so that three meshes have a clean 1 ms run (16/radius
    # at 1 ms carries a trace of the step-to-step oscillation), and a test of the step
    # extrapolation from 2/1/0.7 ms on 24/radius
    {**entry(28, 1.0, grading=0.25, radial=22), "processes": 2},
    {**entry(24, 0.5, grading=0.25, radial=19), "processes": 2},
]


def run_entry(item: dict[str, Any], work: Path) -> dict[str, Any]:
    """Run one entry; a blow-up or a refused mesh is a row with ``failed``."""
    try:
        row = bench(
            work / item["key"],
            item["cells_per_radius"],
            item.get("processes", 1),
            item["end_time_s"],
            item["step_ms"] * 1e-3,
            0.5,
            0.5,
            adjust_time_step=False,
            wall_grading=item["wall_grading"],
            radial_cells=item["radial_cells"],
            ddt_scheme=item["ddt_scheme"],
            momentum_predictor=item.get("momentum_predictor", False),
            surface_refinement=item.get("surface_refinement", 2),
            tilt_deg=item.get("tilt_deg", 3.0),
        )
    except (CfdError, InputError) as error:
        row = {"failed": str(error).splitlines()[0]}
    return {**item, **row}


#: Graded O-grids checked at rest (blockMesh + checkMesh) before any run: (cells per radius,
#: wall grading, annulus cells). The stable mesh of session 2 is (12, 0.1, 8).
MESH_CHECKS = [
    (12, 0.1, 8),
    (16, 0.1, 11),
    (9, 0.25, 7),
    (10, 0.25, 8),
    (12, 0.25, 10),
    (12, 0.2, 10),
    (12, 0.3, 12),
    (16, 0.25, 13),
    (16, 0.2, 12),
    (16, 0.3, 12),
    (20, 0.25, 16),
]


def check_meshes(work: Path, out: Path) -> None:
    """Mesh quality of the `MESH_CHECKS` O-grids (sloshkit's own checkMesh parsing)."""
    import math

    from cfd_wall_grading import PATTERNS, tool

    from sloshkit.cfd.case import CaseSpec, FreeDecay
    from sloshkit.cfd.mesh import wall_cell_size_m
    from sloshkit.cfd.prepare import write_case
    from sloshkit.model.liquids import get_liquid

    rows = []
    for cells, grading, radial in MESH_CHECKS:
        spec = CaseSpec(
            0.0205,
            0.039,
            get_liquid("water-25C"),
            FreeDecay(math.radians(3.0)),
            cells_per_radius=cells,
            radial_cells=radial,
            wall_grading=grading,
        )
        case = write_case(spec, work / f"mesh-n{cells}-g{grading:g}r{radial}", overwrite=True)
        tool(case, "blockMesh")
        log = tool(case, "checkMesh", "-allGeometry")
        row: dict[str, Any] = {
            "cells_per_radius": cells,
            "wall_grading": grading,
            "radial_cells": radial,
            "wall_cell_mm": 1e3 * wall_cell_size_m(spec),
        }
        for key, pattern in PATTERNS.items():
            match = re.search(pattern, log)
            row[key] = float(match.group(1)) if match else None
        match = re.search(r"^\s*cells:\s+(\d+)", log, re.M)
        row["cells"] = int(match.group(1)) if match else None
        rows.append(row)
        print(json.dumps(row), flush=True)
    out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-damping3"))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-damping-converge.json")
    parser.add_argument("--only", nargs="*", default=None, help="run these keys only")
    parser.add_argument("--list", action="store_true", help="list the plan's keys")
    parser.add_argument("--check-meshes", action="store_true", help="checkMesh the graded grids")
    args = parser.parse_args()
    if args.check_meshes:
        check_meshes(args.work, DATA / "cfd-damping-graded-meshes.json")
        return
    if args.list:
        print("\n".join(item["key"] for item in PLAN))
        return
    for item in PLAN:
        rows = json.loads(args.out.read_text()) if args.out.is_file() else []
        if any(r["key"] == item["key"] for r in rows):
            continue
        if args.only is not None and item["key"] not in args.only:
            continue
        row = run_entry(item, args.work)
        rows = json.loads(args.out.read_text()) if args.out.is_file() else []
        rows.append(row)
        print(json.dumps(row), flush=True)
        args.out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
