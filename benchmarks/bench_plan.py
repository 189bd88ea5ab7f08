"""Benchmark: every planning method on the issue's case.

The paper's vial (R 20.5 mm, h 39 mm, water, damping ratio 0.03 as in its Table 3) moving
0.5 m with peak slosh <= 5 deg, residual <= 0.25 deg, v <= 1.5 m/s, a <= 20 m/s^2,
j <= 500 m/s^3, 4 ms controller period. Prints each method's duration, its speed-up over the
best of the paper's laws, its ratio to the optimal-control duration and its compute time (the
fast method timed as the best of 5 runs after a warm-up).

Run: .venv/bin/python benchmarks/bench_plan.py [--robust 0.1]
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.errors import ValidityWarning
from sloshkit.plan.optimal import plan_optimal
from sloshkit.plan.planner import plan
from sloshkit.plan.problem import PAPER_LAWS, MachineLimits, PlanProblem, SloshLimits
from sloshkit.plan.searches import plan_paper_law, plan_shaped


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robust", type=float, default=0.0)
    args = parser.parse_args()
    warnings.simplefilter("ignore", ValidityWarning)
    model = equivalent_model(
        UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, damping_ratio=0.03
    )
    problem = PlanProblem(
        0.5,
        MachineLimits(1.5, 20.0, 500.0),
        SloshLimits(math.radians(5.0), math.radians(0.25), robustness=args.robust),
        model,
        4e-3,
    )
    rows = []
    for law in PAPER_LAWS:
        rows.append(plan_paper_law(law, problem))
    plan_shaped(problem, ("zv",))  # warm-up: numba kernels
    fast_times = []
    for _ in range(5):
        started = time.perf_counter()
        fast = plan_shaped(problem, ("zv",))
        fast_times.append(time.perf_counter() - started)
    rows.append(fast)
    shaped = plan_shaped(problem)
    rows.append(shaped)
    optimal = plan_optimal(problem, shaped.motion)
    rows.append(optimal)
    started = time.perf_counter()
    auto = plan(problem).chosen
    auto_time = time.perf_counter() - started

    best_paper = min(r.duration_s for r in rows[: len(PAPER_LAWS)] if r.feasible)
    print(f"0.5 m move, |theta| <= 5 deg, residual <= 0.25 deg, band +-{100 * args.robust:g} %")
    print(
        f"{'method':<14}{'duration [s]':>13}{'feasible':>10}{'vs best paper':>15}"
        f"{'vs optimal':>12}{'compute [s]':>13}"
    )
    labels = [*PAPER_LAWS, "fast (zv)", "shaped", "optimal"]
    times = [r.compute_time_s for r in rows]
    times[len(PAPER_LAWS)] = min(fast_times)
    for label, row, seconds in zip(labels, rows, times, strict=True):
        print(
            f"{label:<14}{row.duration_s:>13.4f}{'yes' if row.feasible else 'no':>10}"
            f"{best_paper / row.duration_s:>14.2f}x{row.duration_s / optimal.duration_s:>12.3f}"
            f"{seconds:>13.3f}"
        )
    assert auto is not None
    feasible = "yes" if auto.feasible else "no"
    print(
        f"{'auto -> ' + auto.method:<14}{auto.duration_s:>13.4f}{feasible:>10}"
        f"{best_paper / auto.duration_s:>14.2f}x{auto.duration_s / optimal.duration_s:>12.3f}"
        f"{auto_time:>13.3f}"
    )


if __name__ == "__main__":
    main()
