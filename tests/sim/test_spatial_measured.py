"""The 3-D model against six measured robot series (tests/data/measured-3d, MIT licence).

Each series is predicted from its commanded poses with the container's own parameters
(R 49 mm, h 80 mm, water at 20 C, damping ratio 0.0066 from the free decay); nothing is
fitted to the series. Target (issue 12): median |peak error| <= 10 %, 90th percentile <= 25 %.
The full table with both model variants is printed by validation/validate_measured_3d.py.
"""

from __future__ import annotations

import csv
import warnings
from pathlib import Path

import numpy as np
import pytest

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.spatial import simulate_spatial

DATA = Path(__file__).parents[1] / "data" / "measured-3d"


def _series() -> list[dict[str, str]]:
    with (DATA / "manifest.csv").open() as stream:
        return list(csv.DictReader(stream))


def _peak_errors(nonlinear: bool) -> list[float]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        model = equivalent_model(
            UprightCylinder(0.049), get_liquid("water-20C"), 0.080, 3, damping_ratio=0.0066
        )
        errors = []
        for row in _series():
            pose = np.loadtxt(DATA / "poses" / f"{row['name']}.csv", delimiter=",", skiprows=1)
            poses = PoseTrajectory(pose[:, 0], pose[:, 1:4], pose[:, 4:8], row["name"])
            response = simulate_spatial(model, poses, nonlinear=nonlinear, settle_time_s=3.0)
            errors.append(response.peak_slosh_height_m / float(row["meas_peak_m"]) - 1.0)
    return errors


def test_the_data_is_complete() -> None:
    rows = _series()
    assert len(rows) == 6
    assert (DATA / "LICENSE").read_text().startswith("MIT License")
    for row in rows:
        measured = np.loadtxt(DATA / "measured" / f"{row['name']}.csv", delimiter=",", skiprows=1)
        peak = float(np.max(measured[:, 1]) - float(row["baseline_m"]))
        assert peak == pytest.approx(float(row["meas_peak_m"]), rel=1e-3)


@pytest.mark.parametrize("nonlinear", [False, True])
def test_measured_peaks_within_the_target(nonlinear: bool) -> None:
    errors = np.abs(_peak_errors(nonlinear))
    assert np.median(errors) <= 0.10
    assert np.percentile(errors, 90) <= 0.25
