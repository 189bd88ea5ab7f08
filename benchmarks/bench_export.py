"""Benchmark: export of the README's planned move to every format, with the round trip.

The paper's vial (R 20.5 mm, h 39 mm, water, damping ratio 0.03) moving 0.5 m (shaped plan,
peak slosh <= 5 deg, residual <= 0.25 deg, v <= 1.5 m/s, a <= 20 m/s^2, j <= 500 m/s^3, 4 ms
controller period), on a UR5e with the path starting at (-0.7, -0.25, 0.3) m in its base
frame. Prints, per format, the samples written, the export time (IK included), the IK time per
sample, and the round trip: largest relative difference of the slosh metrics and the largest
distance of the rebuilt container from the planned path.

Run: .venv/bin/python benchmarks/bench_export.py
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.export import FORMATS, Mounting, export_plan, load_arm
from sloshkit.export.exporter import SUFFIXES
from sloshkit.plan.line.planner import plan
from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits


def main() -> None:
    model = equivalent_model(
        UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, damping_ratio=0.03
    )
    limits = SloshLimits(math.radians(5.0), math.radians(0.25))
    problem = PlanProblem(
        distance_m=0.5,
        machine=MachineLimits(1.5, 20.0, 500.0),
        slosh=limits,
        model=model,
        sample_period_s=0.004,
    )
    result = plan(problem, "shaped")
    folder = Path(tempfile.mkdtemp())
    source = Path(result.to_csv(folder / "plan.csv"))
    arm = load_arm("ur5e")
    mounting = Mounting(base_xyz_m=(-0.7, -0.25, 0.3))
    summary = result.to_dict()
    print(f"plan: {summary['method']}, {summary['duration_s']:.4f} s")
    print(
        f"{'format':<10} {'samples':>8} {'export [s]':>11} {'per sample [ms]':>16} "
        f"{'max rel. diff':>14} {'path error [m]':>15} {'passed':>7}"
    )
    for fmt in FORMATS:
        start = time.perf_counter()
        exported = export_plan(
            source,
            fmt,
            folder / f"plan{SUFFIXES[fmt]}",
            arm=arm,
            mounting=mounting,
            model=model,
            limits=limits,
        )
        elapsed = time.perf_counter() - start
        trip = exported.round_trip
        assert trip is not None
        print(
            f"{fmt:<10} {exported.samples:>8d} {elapsed:>11.2f} "
            f"{1e3 * elapsed / exported.samples:>16.2f} "
            f"{max(trip.relative_differences.values()):>14.2e} "
            f"{trip.max_position_error_m:>15.2e} {trip.passed!s:>7}"
        )


if __name__ == "__main__":
    main()
