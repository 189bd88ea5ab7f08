"""Speed of the 3-D slosh simulation (issue 12, item 6).

A 10 s pose trajectory at 500 Hz (a circle with vertical motion, spin about the vertical and a
rocking tilt), 3 modes, on one core: `simulate_spatial` linear (target < 20 ms) and nonlinear
(target < 200 ms), timed end to end (kinematics, drive, integration, metrics), best of 5 after
a warm-up (numba compilation is cached on disk). Baseline in the same run: the same equations
integrated by `scipy.integrate.solve_ivp` (RK45, rtol 1e-8, drive interpolated linearly), with
the agreement of the slosh heights. Also: the batch path for 20 trajectories, and the linear
model with an amplitude-dependent first mode (`sloshkit.sim.spatial_amplitude`, slopes of the
measured free decay's backbone) against the plain linear model (target: within 2x).

Run: PYTHONPATH=src python benchmarks/bench_spatial.py
"""

from __future__ import annotations

import contextlib
import os
import time
import warnings

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import interp1d
from scipy.spatial.transform import Rotation

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.spatial import simulate_spatial
from sloshkit.sim.spatial_amplitude import AmplitudeDependence
from sloshkit.sim.spatial_batch import spatial_batch_metrics
from sloshkit.sim.spatial_drive import spatial_drive

warnings.simplefilter("ignore", ValidityWarning)


def trajectory(
    duration_s: float = 10.0, sample_period_s: float = 0.002, scale: float = 1.0
) -> PoseTrajectory:
    t = np.arange(round(duration_s / sample_period_s) + 1) * sample_period_s
    s = 0.5 * (1.0 - np.cos(np.pi * t / duration_s))  # smooth 0 -> 1
    turn = 2 * np.pi * 3 * s
    position = scale * np.column_stack(
        (0.3 * np.sin(turn), 0.3 * np.cos(turn) - 0.3, 0.05 * np.sin(2 * turn))
    )
    angles = np.column_stack((2 * turn, 0.2 * np.sin(turn)))
    return PoseTrajectory(t, position, Rotation.from_euler("zx", angles).as_quat(), "bench")


def best_of(function, repeat: int = 5) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """(best wall-clock time, best CPU time of this process) over ``repeat`` runs [s]; the CPU
    time is the fairer figure on a shared machine."""
    wall, cpu = [], []
    for _ in range(repeat):
        started, started_cpu = time.perf_counter(), time.process_time()
        function()
        wall.append(time.perf_counter() - started)
        cpu.append(time.process_time() - started_cpu)
    return min(wall), min(cpu)


def scipy_linear(model, poses):  # type: ignore[no-untyped-def]
    """Baseline: the linear equations of `sloshkit.sim.spatial` with solve_ivp."""
    kin = poses.extended(0.0).kinematics()
    drive = spatial_drive(model, kin)
    t = drive.time_s
    modes = model.modes
    heights = np.zeros(t.size)
    vector = np.zeros((t.size, 2))
    for row, mode in enumerate(modes):
        table = np.column_stack(
            (drive.specific_force_m_s2[row], drive.tilt_rate_rad_s, drive.tilt_acceleration_rad_s2)
        )
        drive_at = interp1d(t, table, axis=0, assume_sorted=True)

        def rhs(time_s, y, drive_at=drive_at, mode=mode):  # type: ignore[no-untyped-def]
            fx, fy, fz, p, q, dp, dq = drive_at(time_s)
            theta, rate = y[:2], y[2:]
            coupling = np.array([p, q]) * (p * theta[0] + q * theta[1])
            u = np.array([fx, fy]) / mode.length_m + np.array([dq, -dp])
            stiffness = -fz / mode.length_m
            damping = 2 * mode.damping_ratio * mode.omega_rad_s
            return np.concatenate((rate, u - stiffness * theta - coupling - damping * rate))

        rest = drive.rest_force_m_s2[row]
        start = np.array([rest[0] / -rest[2], rest[1] / -rest[2], 0.0, 0.0])
        solution = solve_ivp(rhs, (t[0], t[-1]), start, t_eval=t, rtol=1e-8, atol=1e-10)
        vector += mode.wall_elevation_factor_m * solution.y[:2].T
    heights = np.hypot(vector[:, 0], vector[:, 1])
    return heights


def main() -> None:
    with contextlib.suppress(AttributeError, OSError):  # one core (Linux only)
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    model = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 3, damping_ratio=0.0066
    )
    poses = trajectory()
    options = {"settle_time_s": 0.0}
    linear = simulate_spatial(model, poses, **options)
    nonlinear = simulate_spatial(model, poses, nonlinear=True, **options)
    t_linear, c_linear = best_of(lambda: simulate_spatial(model, poses, **options))
    t_nonlinear, c_nonlinear = best_of(
        lambda: simulate_spatial(model, poses, nonlinear=True, **options)
    )
    started, started_cpu = time.perf_counter(), time.process_time()
    baseline = scipy_linear(model, poses)
    t_scipy, c_scipy = time.perf_counter() - started, time.process_time() - started_cpu
    agreement = np.max(np.abs(baseline - linear.slosh_height_m)) / linear.peak_slosh_height_m
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"10 s pose trajectory at 500 Hz ({poses.time_s.size} samples), 3 modes, one core")
    print(f"(load average {load:.1f}; wall-clock / process CPU time, best of 5)")
    print(
        f"  linear    simulate_spatial: {1e3 * t_linear:7.1f} / {1e3 * c_linear:6.1f} ms (< 20 ms)"
    )
    print(
        f"  nonlinear simulate_spatial: {1e3 * t_nonlinear:7.1f} / {1e3 * c_nonlinear:6.1f} ms "
        "(< 200 ms)"
    )
    print(
        f"  scipy solve_ivp baseline (linear, RK45): {1e3 * t_scipy:7.0f} / {1e3 * c_scipy:6.0f} ms"
    )
    print(
        f"  CPU-time ratio baseline / linear: {c_scipy / c_linear:.0f}x, "
        f"baseline / nonlinear: {c_scipy / c_nonlinear:.0f}x"
    )
    print(f"  max |height difference| linear vs baseline: {100 * agreement:.4f} % of the peak")
    print(
        f"  peak slosh height linear {1e3 * linear.peak_slosh_height_m:.2f} mm, "
        f"nonlinear {1e3 * nonlinear.peak_slosh_height_m:.2f} mm"
    )
    # slopes of the measured free decay (docs/validation-3d.md); their values do not matter here
    dependence = AmplitudeDependence((-5.83,), (0.0,), (0.22,), "free decay")
    simulate_spatial(model, poses, amplitude_dependence=dependence, **options)
    t_amplitude, c_amplitude = best_of(
        lambda: simulate_spatial(model, poses, amplitude_dependence=dependence, **options)
    )
    print(
        f"  linear + free-decay backbone: {1e3 * t_amplitude:7.1f} / {1e3 * c_amplitude:6.1f} ms"
        f" (CPU-time ratio to linear {c_amplitude / c_linear:.2f}x, target <= 2x)"
    )
    batch = [trajectory(scale=s) for s in np.linspace(0.5, 1.0, 20)]
    spatial_batch_metrics(model, batch[:2], settle_time_s=0.0)
    t_batch, c_batch = best_of(
        lambda: spatial_batch_metrics(model, batch, settle_time_s=0.0), repeat=3
    )
    print(
        f"  batch path, 20 trajectories: {1e3 * t_batch:7.1f} / {1e3 * c_batch:6.1f} ms "
        f"({1e3 * c_batch / 20:.1f} ms CPU each)"
    )


if __name__ == "__main__":
    main()
