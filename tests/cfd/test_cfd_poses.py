"""3-D container motions in the CFD: the acceleration table against closed forms (pure), the
tilted initial fill, and a real tiny pose-driven run compared with the 3-D pendulum model."""

from __future__ import annotations

import json
import math
import shutil

import numpy as np
import pytest
from conftest import run_entry_point
from scipy.spatial.transform import Rotation

from sloshkit.cfd.case import CaseSpec, acceleration_table, case_files
from sloshkit.cfd.excitation import GRAVITY_WORLD, PoseExcitation
from sloshkit.cfd.fields import rest_surface_normal
from sloshkit.model.liquids import get_liquid
from sloshkit.motion.poses import PoseTrajectory

WATER = get_liquid("water-25C")


def constant_poses(rotation: Rotation, duration_s: float = 1.0) -> PoseTrajectory:
    t = np.linspace(0.0, duration_s, 101)
    return PoseTrajectory(t, np.zeros((t.size, 3)), np.tile(rotation.as_quat(), (t.size, 1)))


def test_static_tilt_gives_the_apparent_gravity_of_the_tilted_frame():
    """g0 - a must equal R^T g: gravity seen from a container tilted by 20 deg about y."""
    rotation = Rotation.from_euler("y", 20.0, degrees=True)
    excitation = PoseExcitation(constant_poses(rotation), cutoff_hz=None)
    linear, omega, alpha = excitation.frame_motion(np.linspace(0.1, 0.9, 9))
    apparent = GRAVITY_WORLD - linear
    expected = rotation.inv().apply(GRAVITY_WORLD)
    assert np.allclose(apparent, expected, atol=1e-9)
    assert abs(apparent[0, 0]) == pytest.approx(9.81 * math.sin(math.radians(20)), rel=1e-9)
    assert np.allclose(omega, 0.0) and np.allclose(alpha, 0.0)
    # The initial surface is normal to gravity in the first pose.
    spec = CaseSpec(0.0205, 0.039, WATER, excitation=excitation, cells_per_radius=4)
    assert np.allclose(rest_surface_normal(spec), rotation.inv().apply([0, 0, 1]))


def test_translation_and_spin_give_body_frame_acceleration_and_rates():
    """x = A sin(w t) along world x while spinning at rate s about the (vertical) axis: the
    table holds R^T a and Omega = (0, 0, s)."""
    amplitude, w, spin = 0.01, 2 * math.pi, 1.5
    t = np.arange(0.0, 2.0 + 1e-9, 1e-3)
    position = np.zeros((t.size, 3))
    position[:, 0] = amplitude * np.sin(w * t)
    quaternion = Rotation.from_euler("z", (spin * t)[:, None]).as_quat()
    excitation = PoseExcitation(PoseTrajectory(t, position, quaternion), cutoff_hz=None)
    times = np.array([0.4, 0.8, 1.3])
    linear, omega, alpha = excitation.frame_motion(times)
    a_world = np.zeros((times.size, 3))
    a_world[:, 0] = -amplitude * w**2 * np.sin(w * times)
    expected = Rotation.from_euler("z", (spin * times)[:, None]).inv().apply(a_world)
    assert np.allclose(linear, expected, atol=2e-3 * amplitude * w**2)
    assert np.allclose(omega, [0.0, 0.0, spin], atol=1e-3)
    assert np.allclose(alpha, 0.0, atol=1e-2)
    table = acceleration_table(
        CaseSpec(0.0205, 0.039, WATER, excitation=excitation, end_time_s=0.5)
    )
    assert table.splitlines()[0] == "601"  # 0 .. end + 0.1 s every millisecond
    files = case_files(CaseSpec(0.0205, 0.039, WATER, excitation=excitation, probe_angles=12))
    assert files["sloshkit-poses.csv"].startswith("t [s],x [m],y [m],z [m],qx,qy,qz,qw")
    assert files["system/controlDict"].count("(20.09 0 ") > 10  # the column at +x


@pytest.mark.skipif(shutil.which("interFoam") is None, reason="OpenFOAM is not installed")
def test_pose_driven_run_against_the_3d_model(tmp_path):
    """A tiny mesh driven by a lateral move with a small tilt: CFD slosh height and the
    3-D pendulum model correlate and agree on the peak within 35 % (coarse mesh)."""
    t = np.arange(0.0, 0.4 + 1e-9, 1e-3)
    s = t / 0.4
    shape = 35 * s**4 - 84 * s**5 + 70 * s**6 - 20 * s**7  # septic rest-to-rest
    pose_file = tmp_path / "move.csv"
    rows = ["t [s],x [mm],y [mm],z [mm],roll [deg],pitch [deg],yaw [deg]"]
    rows += [f"{ti},{30 * si},{10 * si},0,0,{2 * si},0" for ti, si in zip(t, shape, strict=True)]
    pose_file.write_text("\n".join(rows) + "\n")
    case = tmp_path / "c"
    result = run_entry_point(
        "cfd",
        "validate",
        "--case",
        str(case),
        "--excitation",
        "poses",
        "--pose-file",
        str(pose_file),
        "--end-time",
        "0.8s",
        "--cells-per-radius",
        "5",
        "--probe-angles",
        "8",
        "--plot",
        str(tmp_path / "poses.png"),
        "--json",
    )
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    assert payload["kind"] == "poses"
    assert len(payload["probe_angles_deg"]) == 8
    assert payload["correlation"] > 0.8
    assert payload["wall_correlation"] > 0.8
    peak = payload["comparison"]["peak_slosh_height_m"]
    assert peak["relative_difference"] == pytest.approx(0.0, abs=0.35)
    # a small lateral move drives the order m = 1 (the model's only one) far above the others
    orders = payload["azimuthal_orders"]
    assert [row["order"] for row in orders] == [0, 1, 2, 3]
    first = orders[1]["peak_cfd_m"]
    assert first == pytest.approx(orders[1]["peak_model_m"], rel=0.35)
    assert all(row["peak_cfd_m"] < 0.3 * first for row in orders if row["order"] != 1)
    assert all(row["peak_model_m"] < 1e-9 for row in orders if row["order"] != 1)
    assert (tmp_path / "poses.png").stat().st_size > 10_000
