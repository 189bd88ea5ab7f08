"""Forced-response identification on real robot records (tests/data/measured-3d, MIT licence):
the first-mode frequency from a production move's measured slosh heights (camera, about 60
frames/s, clocks not synchronised) against the same container's force-sensor free decay,
omega_d = 19.04 rad/s (data README), through the API and the CLI. The whole table of six series
is printed by validation/calibrate_measured_3d.py (all within 1.05 %, median 0.47 %)."""

from __future__ import annotations

import csv
import json
import warnings
from pathlib import Path

import numpy as np
import pytest
from conftest import run_entry_point

from sloshkit.calibration import identify_simulated
from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.spatial import simulate_spatial

DATA = Path(__file__).parents[1] / "data" / "measured-3d"
FREE_DECAY_OMEGA_D = 19.04  # rad/s, force-sensor free decay of the same container


@pytest.mark.parametrize("name", ["Tilt_TRD_3D_0.3m_3s_30deg"])
def test_frequency_from_a_measured_production_move(name):
    rows = {row["name"]: row for row in csv.DictReader((DATA / "manifest.csv").open())}
    pose_table = np.loadtxt(DATA / "poses" / f"{name}.csv", delimiter=",", skiprows=1)
    poses = PoseTrajectory(pose_table[:, 0], pose_table[:, 1:4], pose_table[:, 4:8], name=name)
    measured = np.loadtxt(DATA / "measured" / f"{name}.csv", delimiter=",", skiprows=1)
    delay = float(rows[name]["tau_s"])
    settle = max(0.0, float(measured[-1, 0]) - delay - poses.end_s + 0.5)
    base = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.080, 3, damping_ratio=0.0066
    )

    def simulate_height(omega, zeta):
        model = base.with_mode(1, omega_rad_s=omega)
        for mode in model.modes:
            model = model.with_mode(mode.n, damping_ratio=zeta)
        response = simulate_spatial(model, poses, settle_time_s=settle, sample_period_s=0.008)
        return response.time_s, response.slosh_height_m

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
    assert found.omega_n_rad_s == pytest.approx(FREE_DECAY_OMEGA_D, rel=0.015)
    assert found.r2 > 0.9
    assert found.delay_s == pytest.approx(delay, abs=0.1)


def test_cli_identifies_a_measured_series_with_its_clock_offset():
    name = "Tilt_TRD_3D_0.3m_3s_30deg"
    proc = run_entry_point(
        "calibrate", str(DATA / "measured" / f"{name}.csv"), "--time-column", "t_s",
        "--signal-column", "slosh_height_m", "--motion-file", str(DATA / "poses" / f"{name}.csv"),
        "--clock-offset", "9.3s", "--fit-clock-offset", "--radius", "49mm",
        "--fill-height", "80mm", "--liquid", "water-20C", "--damping-ratio", "0.0066", "--json",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    payload = json.loads(proc.stdout)
    assert payload["method"] == "forced"
    assert payload["omega_n_rad_s"] == pytest.approx(FREE_DECAY_OMEGA_D, rel=0.015)
    assert payload["delay_s"] == pytest.approx(9.356, abs=0.02)
    assert payload["r2"] > 0.9
