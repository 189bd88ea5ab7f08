"""Benchmark: the linear fast path (`sloshkit.sim.batch_kernel`, `sloshkit.sweep`) against a
hand-vectorised `scipy.signal.lfilter` path and a plain scipy `solve_ivp` loop over the same cases.

Cases: the seed paper's vial (3 modes, zeta = 0.03), 0.5 m moves of about 2 s (1.9-2.1 s),
trapezoidal / cubic / quintic / septic laws, sampled at 1 kHz. The baseline integrates the
acceleration-driven equations (paper eq. 7, 3 modes) with RK45 at rtol 1e-8, atol 1e-10,
evaluated on the same 1 kHz grid, piece by piece between the laws' breakpoints, and computes
the same metrics. The lfilter baseline samples the laws with sloshkit's compiled sampler into a
(cases x samples) array and runs `scipy.signal.lfilter` along time for each mode, all cases at
once, in chunks of 1,000. The fused kernel samples the law inside a numba kernel and keeps only the
metrics (memory O(cases)); its peak memory is measured as the growth of the process's peak RSS
over a 100,000-case run. Everything runs in this process, on one core, side by side; rates are
cases per second of CPU time of this process (the machine is shared; wall clock is shown too).
The fused kernel, the array path and the lfilter baseline run alternately ``--repeat`` times;
each row gives its best, so the ratios compare bests measured in the same run.

Run: .venv/bin/python benchmarks/bench_batch.py [--markdown] [--cases 100000] [--repeat 3]
"""

from __future__ import annotations

import argparse
import itertools
import math
import resource
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.signal import lfilter

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.model.modal import model_family
from sloshkit.motion import make_law
from sloshkit.motion.sampling import steps_for, steps_to_reach
from sloshkit.motion.scaling import scaled_velocity_samples, unit_duration_shape
from sloshkit.sim.batch import batch_metrics
from sloshkit.sim.batch_kernel import law_metrics
from sloshkit.sim.discretisation import velocity_driven_discretisation
from sloshkit.sweep import run_sweep

LAWS = ("trapezoidal", "cubic", "quintic", "septic")
DT = 1e-3
DISTANCE = 0.5


def lfilter_coefficients(
    omega: float, zeta: float, length: float, step: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(b_theta, a, b_y) of the first-order-hold discretisation as an IIR filter (ss2tf)."""
    from scipy.signal import ss2tf

    phi, gamma, g1 = velocity_driven_discretisation(omega, zeta, length, step)
    b_theta, a = ss2tf(phi, gamma[:, None], np.array([[1.0, 0.0]]), np.array([[g1[0]]]))
    b_y, _ = ss2tf(phi, gamma[:, None], np.array([[0.0, 1.0]]), np.array([[g1[1]]]))
    return b_theta[0], a, b_y[0]


def baseline_case(model, motion, rtol=1e-8, atol=1e-10):
    """solve_ivp RK45 (rtol 1e-8, atol 1e-10) of all modes; same metrics as the fast path."""
    modes = model.modes
    omega = np.array([m.omega_rad_s for m in modes])
    zeta = np.array([m.damping_ratio for m in modes])
    length = np.array([m.length_m for m in modes])
    factor = np.array([m.wall_elevation_factor_m for m in modes])
    acceleration = motion.derivative_pp(2)
    end = motion.duration_s
    grid = np.arange(steps_to_reach(end, DT) + 1) * DT
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


def lfilter_metrics(model, unit_velocity, durations, chunk=1000):
    """Hand-vectorised baseline: the law sampled on the (cases x samples) grid (sloshkit's
    compiled sampler), one `scipy.signal.lfilter` per mode over all cases, masked metrics (the
    same definitions)."""
    steps = steps_for(float(durations.max()), DT)
    out = {key: [] for key in ("peak", "residual", "wall")}
    for start in range(0, durations.size, chunk):
        block = durations[start : start + chunk]
        # the compiled sampler, so that the baseline is the filter, not the sampling
        velocity = np.ascontiguousarray(scaled_velocity_samples(unit_velocity, block, DT, steps).T)
        last = np.floor((block + 1e-12) / DT).astype(int)
        after = np.where(last * DT >= block - 1e-12, last, last + 1)
        during = np.arange(steps)[None, :] <= last[:, None]
        rows = np.arange(block.size)
        wall = np.zeros_like(velocity)
        for index, mode in enumerate(model.modes):
            b_theta, a, b_y = lfilter_coefficients(
                mode.omega_rad_s, mode.damping_ratio, mode.length_m, DT
            )
            theta = lfilter(b_theta, a, velocity, axis=-1)
            wall += mode.wall_elevation_factor_m * theta
            if index == 0:
                out["peak"].append(np.max(np.where(during, np.abs(theta), 0.0), axis=1))
                rate = lfilter(b_y, a, velocity, axis=-1) - velocity / mode.length_m
                angle_end, rate_end = theta[rows, after], rate[rows, after]
                damped = mode.omega_rad_s * math.sqrt(1 - mode.damping_ratio**2)
                quadrature = (rate_end + mode.damping_ratio * mode.omega_rad_s * angle_end) / damped
                lag = after * DT - block
                out["residual"].append(
                    np.hypot(angle_end, quadrature)
                    * np.exp(mode.damping_ratio * mode.omega_rad_s * lag)
                )
        out["wall"].append(np.max(np.where(during, np.abs(wall), 0.0), axis=1))
    return {key: np.concatenate(value) for key, value in out.items()}


def timed(function, *args, **kwargs):
    """(result, wall seconds, CPU seconds of this process)."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - wall, time.process_time() - cpu


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=100_000)
    parser.add_argument("--lfilter-cases", type=int, default=3000)
    parser.add_argument("--baseline-cases", type=int, default=12)
    parser.add_argument("--fill-heights", type=int, default=50)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument(
        "--markdown", action="store_true", help="print the docs/performance.md table"
    )
    args = parser.parse_args()

    container, water = UprightCylinder(0.0205), get_liquid("water-25C")
    model = equivalent_model(container, water, 0.039, damping_ratio=0.03)
    law = "septic"
    unit = unit_duration_shape(make_law(law, DISTANCE, duration_s=1.0)).derivative_pp(1)
    durations = np.random.default_rng(0).uniform(1.9, 2.1, args.cases)

    # Warm up: numba compiles or loads its cache once per process.
    law_metrics(model, unit, durations[:100], DT)
    batch_metrics(model, scaled_velocity_samples(unit, durations[:2], DT, 2200), durations[:2], DT)

    # 1. The fused kernel on every case; peak memory as the growth of the peak RSS (first run).
    subset = durations[: min(args.cases, 20_000)]
    few = durations[: args.lfilter_cases]

    def array_path():
        """2. Sampling into an array, then the array kernel (chunks of 4,096 cases)."""
        parts = []
        for start in range(0, subset.size, 4096):
            block = subset[start : start + 4096]
            velocity = scaled_velocity_samples(unit, block, DT, steps_for(block.max(), DT))
            parts.append(batch_metrics(model, velocity, block, DT).peak_angle_rad)
        return np.concatenate(parts)

    best = {}

    def keep(name, wall, cpu):
        old = best.get(name, (np.inf, np.inf))
        best[name] = (min(old[0], wall), min(old[1], cpu))

    before = peak_rss_mb()
    for repeat in range(args.repeat):
        fused, wall, cpu = timed(law_metrics, model, unit, durations, DT)
        if repeat == 0:
            fused_memory = peak_rss_mb() - before
            process_memory = peak_rss_mb()
        keep("fused", wall, cpu)
        array_peak, wall, cpu = timed(array_path)
        keep("array", wall, cpu)
        # 3. The hand-vectorised lfilter baseline.
        reference, wall, cpu = timed(lfilter_metrics, model, unit, few)
        keep("lfilter", wall, cpu)
    (fused_wall, fused_cpu), (array_wall, array_cpu) = best["fused"], best["array"]
    lfilter_wall, lfilter_cpu = best["lfilter"]
    agreement = max(
        float(np.max(np.abs(fused.peak_angle_rad[: few.size] - reference["peak"]))),
        float(np.max(np.abs(fused.residual_angle_rad[: few.size] - reference["residual"]))),
    ) / float(np.max(reference["peak"]))
    assert np.allclose(array_peak, fused.peak_angle_rad[: subset.size], rtol=1e-9)

    # 4. A sweep: fill heights x laws x durations.
    heights = np.linspace(0.010, 0.060, args.fill_heights)
    grid = np.linspace(1.9, 2.1, 200)
    family = model_family(container, water, damping_ratio=0.03)
    sweep, sweep_wall, sweep_cpu = timed(
        run_sweep, family, LAWS, DISTANCE, grid, fill_heights_m=heights
    )

    # 5. solve_ivp on a few of the same cases: accuracy and the slow reference.
    picks = durations[: args.baseline_cases]
    exact, ivp_wall, ivp_cpu = timed(
        lambda: [baseline_case(model, make_law(law, DISTANCE, duration_s=d)) for d in picks]
    )
    exact = np.array(exact)
    ours = np.column_stack(
        (
            fused.peak_angle_rad[: picks.size],
            fused.residual_angle_rad[: picks.size],
            fused.peak_wall_elevation_m[: picks.size],
            fused.residual_wall_elevation_m[: picks.size],
        )
    )
    errors = np.max(np.abs(ours - exact) / np.abs(exact), axis=0)

    lfilter_rate = few.size / lfilter_cpu
    rows = [
        ("`solve_ivp` RK45 loop, rtol 1e-8", picks.size, ivp_wall, ivp_cpu),
        ("hand-vectorised `lfilter` (same samples)", few.size, lfilter_wall, lfilter_cpu),
        ("sampling array + array kernel (before)", subset.size, array_wall, array_cpu),
        ("fused kernel (law sampled inside)", durations.size, fused_wall, fused_cpu),
        (f"sweep, {args.fill_heights} fill heights x 4 laws", sweep.cases, sweep_wall, sweep_cpu),
    ]
    if args.markdown:
        print("| path | cases | cases/s (CPU) | wall [s] | vs `lfilter` |")
        print("|---|---|---|---|---|")
    else:
        print(f"Linear slosh metrics, 3 modes, {law} moves of 1.9-2.1 s at 1 kHz, one core")
        print(f"{'path':<48}{'cases':>8}{'cases/s':>12}{'wall [s]':>10}{'vs lfilter':>12}")
    for label, cases, wall, cpu in rows:
        rate = cases / cpu
        if args.markdown:
            print(
                f"| {label} | {cases:,} | {rate:,.0f} | {wall:.2f} | {rate / lfilter_rate:.1f}× |"
            )
        else:
            print(f"{label:<48}{cases:>8}{rate:>12,.0f}{wall:>10.2f}{rate / lfilter_rate:>11.1f}x")
    names = ("peak angle", "residual angle", "peak wall elevation", "residual wall elevation")
    print()
    print(
        f"best of {args.repeat}; fused kernel: peak RSS growth {fused_memory:.0f} MB for "
        f"{durations.size:,} cases (process peak {process_memory:.0f} MB); "
        f"max relative difference to solve_ivp (rtol 1e-8): "
        + ", ".join(f"{n} {e:.1e}" for n, e in zip(names, errors, strict=True))
        + f"; to the lfilter path {agreement:.1e}"
    )


if __name__ == "__main__":
    main()
