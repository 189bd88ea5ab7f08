"""Forced-response identification on the six measured robot series (tests/data/measured-3d).

For each series, omega_n and zeta of the first mode (and the camera/robot clock offset) are
fitted by simulating the 3-D slosh model (`sloshkit.sim.spatial.simulate_spatial`) along the
commanded poses against the measured slosh heights, and compared with the same container's
force-sensor free decay (omega_d = 19.04 rad/s, zeta = 0.0066; data README).

Run: PYTHONPATH=src python validation/calibrate_measured_3d.py
"""

from __future__ import annotations

import csv
import time
import warnings
from pathlib import Path

import numpy as np

from sloshkit.calibration import identify_simulated
from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.spatial import simulate_spatial

DATA = Path(__file__).parents[1] / "tests" / "data" / "measured-3d"
FREE_DECAY_OMEGA_D = 19.04


def main() -> None:
    """Print one line per series and the median frequency error."""
    base = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.080, 3, damping_ratio=0.0066
    )
    errors = []
    with (DATA / "manifest.csv").open() as stream:
        rows = list(csv.DictReader(stream))
    for row in rows:
        name = row["name"]
        table = np.loadtxt(DATA / "poses" / f"{name}.csv", delimiter=",", skiprows=1)
        poses = PoseTrajectory(table[:, 0], table[:, 1:4], table[:, 4:8], name=name)
        measured = np.loadtxt(DATA / "measured" / f"{name}.csv", delimiter=",", skiprows=1)
        delay = float(row["tau_s"])
        settle = max(0.0, float(measured[-1, 0]) - delay - poses.end_s + 0.5)
        calls = [0]

        def simulate_height(
            omega: float,
            zeta: float,
            poses: PoseTrajectory = poses,
            settle: float = settle,
            calls: list[int] = calls,
        ) -> tuple[np.ndarray, np.ndarray]:
            calls[0] += 1
            model = base.with_mode(1, omega_rad_s=omega)
            for mode in model.modes:
                model = model.with_mode(mode.n, damping_ratio=zeta)
            response = simulate_spatial(model, poses, settle_time_s=settle, sample_period_s=0.008)
            return response.time_s, response.slosh_height_m

        started = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            found = identify_simulated(
                simulate_height,
                measured[:, 0],
                measured[:, 1],
                omega_guess_rad_s=base.modes[0].omega_rad_s,
                delay_s=delay,
                fit_delay=True,
                omega_range=(0.85, 1.2),
                require_constrained=False,
            )
        damped = found.omega_n_rad_s * np.sqrt(1 - found.damping_ratio**2)
        error = damped / FREE_DECAY_OMEGA_D - 1
        errors.append(abs(error))
        low, high = found.damping_ratio_interval
        print(
            f"{name:28s} omega_d {damped:7.3f} rad/s ({100 * error:+5.2f} %)  zeta "
            f"{found.damping_ratio:.4f} [{low:.4f}, {high:.4f}]  offset {found.delay_s:6.3f} s "
            f"(manifest {delay:6.3f})  R2 {found.r2:.3f}  {calls[0]} sims "
            f"{time.perf_counter() - started:5.1f} s"
        )
    print(f"median |omega_d error| {100 * float(np.median(errors)):.2f} %")


if __name__ == "__main__":
    main()
