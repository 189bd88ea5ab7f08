"""Benchmark: the linear fast path (`sloshkit.sim.batch`, `sloshkit.sweep`) against a plain
scipy `solve_ivp` loop over the same cases.

Cases: the seed paper's vial (3 modes, zeta = 0.03), 0.5 m moves of about 2 s (1.9-2.1 s),
trapezoidal / cubic / quintic / septic laws, sampled at 1 kHz. The baseline integrates the
acceleration-driven equations (paper eq. 7, 3 modes) with RK45 at rtol 1e-8, atol 1e-10,
evaluated on the same 1 kHz grid, piece by piece between the laws' breakpoints, and computes
the same metrics. Both run in this process, on one core (numba and scipy here are
single-threaded).

Run: .venv/bin/python benchmarks/bench_batch.py [--baseline-cases 40]
"""

from __future__ import annotations

import argparse
import itertools
import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.model.modal import model_family
from sloshkit.motion import make_law
from sloshkit.motion.sampling import steps_for
from sloshkit.motion.scaling import scaled_velocity_samples, unit_duration_shape
from sloshkit.sim.batch import batch_metrics
from sloshkit.sweep import run_sweep

LAWS = ("trapezoidal", "cubic", "quintic", "septic")
DT = 1e-3
DISTANCE = 0.5


def baseline_case(model, motion, rtol=1e-8, atol=1e-10):
    """solve_ivp RK45 (rtol 1e-8, atol 1e-10) of all modes; same metrics as the fast path."""
    modes = model.modes
    omega = np.array([m.omega_rad_s for m in modes])
    zeta = np.array([m.damping_ratio for m in modes])
    length = np.array([m.length_m for m in modes])
    factor = np.array([m.wall_elevation_factor_m for m in modes])
    acceleration = motion.derivative_pp(2)
    end = motion.duration_s
    grid = np.arange(math.ceil(end / DT - 1e-9) + 1) * DT
    grid = grid[grid <= end + 1e-12]
    edges = sorted({0.0, *motion.breakpoints_s.tolist(), end})
    state = np.zeros(2 * len(modes))
    angles = []
    for start, stop in itertools.pairwise(edges):
        last = np.nextafter(stop, start)

        def rhs(t, y, start=start, last=last):
            a = float(acceleration(min(max(t, start), last)))
            theta, rate = y[: len(modes)], y[len(modes) :]
            return np.concatenate((rate, -2 * zeta * omega * rate - omega**2 * theta - a / length))

        inside = grid[(grid >= start) & (grid <= stop)]
        t_eval = np.union1d(inside, [stop])
        sol = solve_ivp(
            rhs, (start, stop), state, method="RK45", rtol=rtol, atol=atol, t_eval=t_eval
        )
        angles.append(sol.y[: len(modes), np.isin(t_eval, inside)])
        state = sol.y[:, -1]
    theta = np.concatenate(angles, axis=1)
    damped = omega * np.sqrt(1 - zeta**2)
    amplitude = np.hypot(
        state[: len(modes)], (state[len(modes) :] + zeta * omega * state[: len(modes)]) / damped
    )
    return (
        np.max(np.abs(theta[0])),
        amplitude[0],
        np.max(np.abs(factor @ theta)),
        factor @ amplitude,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline-cases", type=int, default=40)
    parser.add_argument("--durations", type=int, default=200)
    parser.add_argument("--fill-heights", type=int, default=50)
    args = parser.parse_args()

    container, water = UprightCylinder(0.0205), get_liquid("water-25C")
    model = equivalent_model(container, water, 0.039, damping_ratio=0.03)
    durations = np.linspace(1.9, 2.1, args.durations)

    # Warm up (numba compiles or loads its cache once per process).
    shape = unit_duration_shape(make_law("quintic", DISTANCE, duration_s=1.0)).derivative_pp(1)
    batch_metrics(
        model,
        scaled_velocity_samples(shape, durations[:2], DT, steps_for(2.1, DT)),
        durations[:2],
        DT,
    )

    # 1. One model, end to end (velocity sampling + kernel), all laws x durations.
    started = time.perf_counter()
    fast = {}
    for law in LAWS:
        shape = unit_duration_shape(make_law(law, DISTANCE, duration_s=1.0)).derivative_pp(1)
        velocity = scaled_velocity_samples(shape, durations, DT, steps_for(durations.max(), DT))
        fast[law] = batch_metrics(model, velocity, durations, DT)
    one_model = time.perf_counter() - started
    one_model_cases = len(LAWS) * durations.size

    # 2. A sweep: fill heights x laws x durations (velocity histories shared across heights).
    heights = np.linspace(0.010, 0.060, args.fill_heights)
    family = model_family(container, water, damping_ratio=0.03)
    result = run_sweep(family, LAWS, DISTANCE, durations, fill_heights_m=heights)

    # 3. Baseline: solve_ivp loop on a subset of the same cases.
    rng = np.random.default_rng(1)
    picks = [
        (LAWS[rng.integers(len(LAWS))], int(rng.integers(durations.size)))
        for _ in range(args.baseline_cases)
    ]
    started = time.perf_counter()
    reference = [
        baseline_case(model, make_law(law, DISTANCE, duration_s=durations[k])) for law, k in picks
    ]
    baseline = (time.perf_counter() - started) / len(picks)
    started = time.perf_counter()
    loose = [
        baseline_case(model, make_law(law, DISTANCE, duration_s=durations[k]), 1e-5, 1e-8)
        for law, k in picks
    ]
    baseline_loose = (time.perf_counter() - started) / len(picks)
    loose_errors = np.max(
        np.abs(np.array(loose) - np.array(reference)) / np.abs(np.array(reference)), axis=0
    )

    errors = np.zeros(4)
    for (law, k), ref in zip(picks, reference, strict=True):
        metrics = fast[law]
        ours = (
            metrics.peak_angle_rad[k],
            metrics.residual_angle_rad[k],
            metrics.peak_wall_elevation_m[k],
            metrics.residual_wall_elevation_m[k],
        )
        errors = np.maximum(errors, np.abs(np.array(ours) - np.array(ref)) / np.abs(np.array(ref)))

    per_case_one = one_model / one_model_cases
    per_case_sweep = result.elapsed_s / result.cases

    def row(label: str, cases: int, seconds: float) -> None:
        per_case = seconds / cases
        print(
            f"{label:<46}{cases:>8}{seconds:>10.3f}{1 / per_case:>12,.0f}"
            f"{baseline / per_case:>12,.1f}x"
        )

    print("Linear slosh metrics, 3 modes, 2 s moves at 1 kHz, one core")
    print(f"{'path':<46}{'cases':>8}{'time [s]':>10}{'cases/s':>12}{'speed-up':>13}")
    row("solve_ivp RK45 loop, rtol 1e-8, atol 1e-10", len(picks), baseline * len(picks))
    row("solve_ivp RK45 loop, rtol 1e-5, atol 1e-8", len(picks), baseline_loose * len(picks))
    row("fast path, one model (sampling + kernel)", one_model_cases, one_model)
    row("fast path, sweep over 50 fill heights", result.cases, result.elapsed_s)
    names = ("peak angle", "residual angle", "peak wall elevation", "residual wall elevation")
    print("max relative difference to solve_ivp at rtol 1e-8:")
    for label, values in (("fast path", errors), ("solve_ivp rtol 1e-5", loose_errors)):
        print(
            f"  {label:<20}" + ", ".join(f"{n} {e:.1e}" for n, e in zip(names, values, strict=True))
        )
    print(
        f"speed-up over solve_ivp at comparable accuracy (rtol 1e-5): one model "
        f"{baseline_loose / per_case_one:,.0f}x, sweep {baseline_loose / per_case_sweep:,.0f}x"
    )


if __name__ == "__main__":
    main()
