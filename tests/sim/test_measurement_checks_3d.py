"""The measurement checks of validation/measurement_checks_3d.py against analytic references.

docs/validation-3d.md ("What the camera reads") rests on these functions: the static wall
height of the plane normal to the apparent gravity, the reading of a series at the tops of its
quasi-static humps, the free-slosh band ratio and the two-camera triangulation.
"""

from __future__ import annotations

import importlib
import math
import warnings
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion.poses import PoseTrajectory, poses_from_rpy
from sloshkit.sim.spatial import simulate_spatial

VALIDATION = Path(__file__).parents[2] / "validation"
RADIUS_M = 0.049


@pytest.fixture
def checks(monkeypatch: pytest.MonkeyPatch) -> ModuleType:
    # the script imports its neighbour validate_measured_3d, as when run from validation/
    monkeypatch.syspath_prepend(str(VALIDATION))
    return importlib.import_module("measurement_checks_3d")


def _model() -> SloshModel:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return equivalent_model(
            UprightCylinder(RADIUS_M), get_liquid("water-20C"), 0.080, 3, damping_ratio=0.0066
        )


def _slow_tilt(peak_deg: float, duration_s: float = 6.0) -> PoseTrajectory:
    """A tilt about x from 0 to peak_deg and back, raised-cosine, slow against 1/f_1 = 0.33 s."""
    t = np.arange(0.0, duration_s, 0.002)
    roll = math.radians(peak_deg) * 0.5 * (1.0 - np.cos(2.0 * np.pi * t / duration_s))
    zeros = np.zeros_like(t)
    return poses_from_rpy(t, np.zeros((t.size, 3)), roll, zeros, zeros, "slow tilt")


def test_static_wall_height_of_a_held_tilt_is_r_tan_psi(checks: ModuleType) -> None:
    t = np.arange(0.0, 1.0, 0.002)
    psi = math.radians(20.0)
    zeros = np.zeros_like(t)
    poses = poses_from_rpy(t, np.zeros((t.size, 3)), zeros + psi, zeros, zeros, "held tilt")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(_model(), poses, settle_time_s=0.5)
    static = checks.static_wall_height_m(response)
    assert static == pytest.approx(RADIUS_M * math.tan(psi), rel=1e-9)


def test_a_hump_is_read_at_its_top_after_the_clock_is_recovered(checks: ModuleType) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(_model(), _slow_tilt(25.0), settle_time_s=2.0)
    static = checks.static_wall_height_m(response)
    offset_s = 3.0  # the camera clock runs 3 s ahead of the pose clock
    t_camera = np.arange(0.0, response.time_s[-1], 1.0 / 60.0) + offset_s
    measured = 0.8 * np.interp(t_camera - offset_s, response.time_s, static)
    item = {
        "name": "slow tilt",
        "class": "Tilt",
        "measured_t_s": t_camera,
        "measured_m": measured,
        "end_s": 6.0,
    }
    humps = checks.quasi_static_humps(item, response)
    assert len(humps) == 1
    hump = humps[0]
    assert hump["clock_offset_s"] == pytest.approx(offset_s, abs=0.011)
    # R tan 25 deg, plus 0.5 % from the tilt's angular acceleration at the free-surface centre
    assert hump["static_m"] == pytest.approx(RADIUS_M * math.tan(math.radians(25.0)), rel=0.01)
    assert hump["measured_max_m"] / hump["static_m"] == pytest.approx(0.8, rel=2e-3)
    assert hump["time_s"] == pytest.approx(3.0, abs=0.01)


def test_band_ratio_tells_a_fixed_point_from_the_highest_point(checks: ModuleType) -> None:
    t = np.arange(0.0, 8.0, 1.0 / 60.0)
    wave = 0.003 * np.cos(19.15 * t)
    fixed_point = checks.omega_band_ratio(t, wave, 1.0, 7.0)
    highest_point = checks.omega_band_ratio(t, np.abs(wave), 1.0, 7.0)
    assert fixed_point > 100.0
    assert highest_point < 0.01


def _level_camera(azimuth_rad: float, distance_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """A camera on the horizontal plane y = 0 looking at the origin (x_camera = R x + t)."""
    centre = distance_mm * np.array([math.cos(azimuth_rad), 0.0, math.sin(azimuth_rad)])
    forward = -centre / distance_mm
    down = np.array([0.0, -1.0, 0.0])
    right = np.cross(down, forward)
    rotation = np.vstack([right, down, forward])
    return rotation, -rotation @ centre


@pytest.mark.parametrize("direction_deg", [0.0, 45.0, 130.0, 250.0])
def test_distant_level_cameras_triangulate_the_true_wall_height(
    checks: ModuleType, direction_deg: float
) -> None:
    # far away and level with the surface the cameras see the highest point of the wall at the
    # same image row as its true height, so both rays meet at it
    poses = [_level_camera(0.0, 1e5), _level_camera(math.pi / 2, 1e5)]
    height = checks.triangulated_height_mm(poses, 20.0, math.radians(direction_deg), 0.0)
    assert height == pytest.approx(20.0, rel=0.01)


def test_close_cameras_above_the_surface_read_low(checks: ModuleType) -> None:
    # 140 mm from the axis and 20 mm above the rest level, as far as the rig allows: perspective
    # makes the far rim the highest image point of a flat surface and pulls the reading down
    poses = [_level_camera(0.0, 140.0), _level_camera(math.pi / 2, 140.0)]
    factors = [
        checks.triangulated_height_mm(poses, 20.0, math.radians(a), -20.0) / 20.0
        for a in range(0, 360, 30)
    ]
    assert max(factors) < 0.9


def test_model_humps_of_a_slow_tilt_are_quasi_static_and_read_back(checks: ModuleType) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(_model(), _slow_tilt(25.0), settle_time_s=2.0)
    offset_s = 2.0
    t_camera = np.arange(0.0, response.time_s[-1], 1.0 / 60.0) + offset_s
    item = {
        "class": "Tilt_RD",
        "measured_t_s": t_camera,
        "measured_m": np.interp(t_camera - offset_s, response.time_s, response.slosh_height_m),
        "end_s": 6.0,
    }
    humps = checks.model_humps(item, response)
    assert len(humps) == 1
    # slow against the first mode: the model stands at its own static value (three modes:
    # 0.94 of the plane), and a camera that reads the model reads it back at the hump's top
    assert abs(humps[0]["overshoot"]) < 0.02
    assert humps[0]["measured_max_m"] == pytest.approx(humps[0]["model_m"], rel=2e-3)
    table = checks.overshoot_table(humps * 3)
    assert "+0.0 (+0.0 to +0.0)" in table
