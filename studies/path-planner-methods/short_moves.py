"""`retime` against `optimal` on random short moves (the family of the property test in
tests/test_properties.py: a straight line or a blended corner, with a rise and an optional
90 deg yaw; the measured series' vial; random height limit and acceleration), upright, each
plan verified with the nonlinear 3-D model.

Run: ``PYTHONPATH=src python studies/path-planner-methods/short_moves.py SEED CASES``.
"""

import math
import sys
import time
import warnings

import numpy as np

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.geometry import path_from_waypoints
from sloshkit.plan.path.planner import plan_path
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits


def main(seed: int, cases: int) -> None:
    """Plan ``cases`` random moves from ``seed`` with both methods; print one line each."""
    warnings.simplefilter("ignore")
    vial = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )
    rng = np.random.default_rng(seed)
    for case in range(cases):
        first = rng.uniform(0.08, 0.25)
        second = 0.0 if rng.random() < 0.3 else rng.uniform(0.08, 0.15)
        rise = rng.uniform(-0.05, 0.05)
        yaw = rng.choice([0.0, math.pi / 2])
        height = rng.choice([0.006, 0.01, 0.015])
        acc = rng.choice([5.0, 8.0, 10.0])
        points = [[0.0, 0.0, 0.0], [first, 0.0, 0.0]] + ([[first, second, rise]] if second else [])
        yaws = np.linspace(0, yaw, len(points))
        problem = PathProblem(
            path_from_waypoints(points, yaw_rad=yaws, blend_radius_m=0.03),
            CartesianLimits(1.5, acc, 10 * acc),
            SpatialSloshLimits(height, 0.002),
            vial,
        )
        out = []
        for m in ("retime", "optimal"):
            t = time.perf_counter()
            r = plan_path(problem, m, tilt=False)
            c = next(c for c in r.candidates if c.method == m)
            out.append(f"{m} {c.duration_s:.3f} s ({c.feasible}, {time.perf_counter() - t:.1f} s)")
        print(
            f"case {case}: {first:.3f} {second:.3f} {rise:+.3f} yaw {math.degrees(yaw):.0f} "
            f"h {height * 1e3:.0f} mm a {acc:g}: " + " | ".join(out),
            flush=True,
        )


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
