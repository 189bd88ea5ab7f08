"""Time-step study of the CFD free decay: how the largest step (maxDeltaT), the Courant limits
and the number of pressure correctors change the frequency, the damping and the cost.

Every row is `bench_cfd_speed.bench` (2 s of free decay of the seed paper's vial, 3 deg tilt).
Results go to data/cfd-timestep-study.json; README.md discusses them.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_timestep_study.py [--np 1]
[--cells-per-radius 11]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

# bench_cfd_speed (the benchmark every row is) lives in benchmarks/.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from bench_cfd_speed import bench

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"

#: (largest step [ms], Courant limit, pressure correctors)
PLAN = [
    (1.0, 0.5, 2),
    (2.0, 0.5, 2),
    (4.0, 0.5, 2),
    (2.0, 0.5, 3),
    (1.0, 0.5, 3),
    (4.0, 0.1, 2),
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--cells-per-radius", type=int, default=11)
    parser.add_argument("--end-time", type=float, default=2.0)
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-timestep"))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-timestep-study.json")
    args = parser.parse_args()
    rows = json.loads(args.out.read_text()) if args.out.is_file() else []
    done = {(r["max_step_s"], r["max_courant"], r["pressure_correctors"]) for r in rows}
    for step_ms, courant, correctors in PLAN:
        if (step_ms * 1e-3, courant, correctors) in done:
            continue
        row = bench(
            args.work / f"dt{step_ms:g}-co{courant:g}-nc{correctors}",
            args.cells_per_radius,
            args.np,
            args.end_time,
            step_ms * 1e-3,
            courant,
            courant,
            correctors,
        )
        rows.append(row)
        print(json.dumps(row), flush=True)
        args.out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
