"""Wall-graded O-grids for the oscillating boundary layer: mesh quality, and whether interFoam
stays stable on them.

For each (radial cells, wall grading) the script writes the paper's vial case, runs blockMesh
and ``checkMesh -allGeometry`` and records the wall cell size, the maximum non-orthogonality
and skewness, the minimum cell determinant and the maximum aspect ratio; with ``--run T`` it
also runs T seconds of free decay (serial) and records whether the solver survived and its
largest Courant number. Results: data/cfd-wall-grading.json.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_wall_grading.py [--run 0.2]
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
from pathlib import Path

from sloshkit.cfd.case import CaseSpec, FreeDecay
from sloshkit.cfd.mesh import wall_cell_size_m
from sloshkit.cfd.run import openfoam_environment, write_case
from sloshkit.model.liquids import get_liquid

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
PLAN = [(5, 1.0), (10, 0.2), (12, 0.1), (16, 0.05), (20, 0.02)]
PATTERNS = {
    "max_non_orthogonality_deg": r"Mesh non-orthogonality Max: ([0-9.eE+-]+)",
    "max_skewness": r"Max skewness = ([0-9.eE+-]+)",
    "min_determinant": r"Cell determinant \(wellposedness\) : minimum: ([0-9.eE+-]+)",
    "max_aspect_ratio": r"Max aspect ratio = ([0-9.eE+-]+)",
    "min_face_weight": r"Face interpolation weight : minimum: ([0-9.eE+-]+)",
}


def tool(case: Path, *command: str) -> str:
    completed = subprocess.run(
        command, cwd=case, env=openfoam_environment(), capture_output=True, text=True
    )
    return completed.stdout + completed.stderr


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only-strong", action="store_true", help="the two finest gradings")
    parser.add_argument("--run", type=float, default=0.0, help="seconds of free decay to run")
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-grading"))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-wall-grading.json")
    args = parser.parse_args()
    rows = []
    for radial, grading in PLAN[3:] if args.only_strong else PLAN:
        spec = CaseSpec(
            0.0205,
            0.039,
            get_liquid("water-25C"),
            FreeDecay(math.radians(3.0)),
            cells_per_radius=10,
            radial_cells=radial,
            wall_grading=grading,
            end_time_s=max(args.run, 0.01),
            write_interval_s=max(args.run, 0.01),
            delta_t_s=1e-3,
        )
        case = write_case(spec, args.work / f"m{radial}-g{grading:g}", overwrite=True)
        tool(case, "blockMesh")
        log = tool(case, "checkMesh", "-allGeometry")
        row: dict[str, object] = {
            "radial_cells": radial,
            "wall_grading": grading,
            "wall_cell_mm": 1e3 * wall_cell_size_m(spec),
            "cells": int(re.search(r"^\s*cells:\s+(\d+)", log, re.M).group(1)),  # type: ignore[union-attr]
            "failed_checks": "Failed" in log and "mesh checks" in log,
        }
        for key, pattern in PATTERNS.items():
            match = re.search(pattern, log)
            row[key] = float(match.group(1)) if match else None
        if args.run > 0:
            tool(case, "setFields")
            solver = tool(case, "interFoam")
            times = re.findall(r"^Time = ([0-9.eE+-]+)$", solver, re.M)
            courants = [
                float(c) for c in re.findall(r"^Courant Number mean: \S+ max: (\S+)", solver, re.M)
            ]
            row["reached_s"] = float(times[-1]) if times else 0.0
            row["stable"] = bool(times) and float(times[-1]) >= args.run - 1e-9
            row["max_courant"] = max(courants) if courants else None
            row["steps"] = len(times)
        rows.append(row)
        print(json.dumps(row), flush=True)
    args.out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
