"""Export formats: golden files (reviewed by eye once), parse-back, and format rules.

The golden plan is a 20 mm quintic move in 0.1 s sampled every 10 ms, on a UR5e, its path
starting 0.39 m above the base near the arm's home pose. Goldens are compared line by line:
text exactly, numbers to 1e-7 absolute (IK converges to about 1e-9, differently on different
machines). Regenerate them with ``SLOSHKIT_UPDATE_GOLDEN=1`` and review the diff.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
import yaml

from sloshkit.errors import InputError
from sloshkit.export.exporter import STREAM_FORMATS, SUFFIXES, export_plan
from sloshkit.export.formats.cam_table import read_cam_table
from sloshkit.export.formats.joint_csv import read_joint_csv
from sloshkit.export.formats.pose_csv import read_pose_csv
from sloshkit.export.formats.ros2 import read_ros2_yaml
from sloshkit.export.formats.urscript import read_urscript, write_urscript
from sloshkit.export.frames import Mounting
from sloshkit.export.kinematics import load_arm
from sloshkit.export.plans import LinePlan, PoseStream
from sloshkit.export.readback import rebuild_container_poses
from sloshkit.motion.poses import PoseTrajectory

GOLDEN = Path(__file__).parents[1] / "data" / "export"
MOUNTING = Mounting(base_xyz_m=(-0.49, -0.13, 0.39))
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def quintic_plan(distance_m: float = 0.02, duration_s: float = 0.1, period_s: float = 0.01):
    t = np.arange(round(duration_s / period_s) + 1) * period_s
    s = t / duration_s
    position = distance_m * s**3 * (10 - 15 * s + 6 * s**2)
    velocity = distance_m / duration_s * 30 * s**2 * (1 - s) ** 2
    acceleration = distance_m / duration_s**2 * 60 * s * (1 - s) * (1 - 2 * s)
    return LinePlan(t, position, velocity, acceleration, "quintic.csv")


@pytest.fixture(scope="module")
def ur5e():
    return load_arm("ur5e")


def assert_matches_golden(path: Path, name: str) -> None:
    golden = GOLDEN / name
    if os.environ.get("SLOSHKIT_UPDATE_GOLDEN"):
        golden.write_text(path.read_text())
    expected = golden.read_text().splitlines()
    actual = path.read_text().splitlines()
    assert len(actual) == len(expected), name
    for number, (line, reference) in enumerate(zip(actual, expected, strict=True), start=1):
        if line.lstrip().startswith("# sloshkit_version:"):
            continue
        assert NUMBER.sub("#", line) == NUMBER.sub("#", reference), f"{name}:{number}"
        values = [float(v) for v in NUMBER.findall(line)]
        references = [float(v) for v in NUMBER.findall(reference)]
        np.testing.assert_allclose(values, references, atol=1e-7, err_msg=f"{name}:{number}")


@pytest.mark.parametrize("fmt", STREAM_FORMATS)  # programs: test_vendor_*.py
def test_golden_file_and_parse_back(fmt: str, tmp_path: Path, ur5e) -> None:
    out = tmp_path / f"quintic{SUFFIXES[fmt]}"
    result = export_plan(quintic_plan(), fmt, out, arm=ur5e, mounting=MOUNTING, check=False)
    assert result.path == out
    if fmt == "ros2-bag":  # a binary folder: its message is compared with the ros2 YAML's
        from sloshkit.export.formats.ros2 import read_ros2_yaml
        from sloshkit.export.formats.ros2_bag import read_ros2_bag

        bag, frame = read_ros2_bag(out)
        yaml, yaml_frame = read_ros2_yaml(GOLDEN / "quintic.ros2.yaml")
        assert frame == yaml_frame and bag.joint_names == yaml.joint_names
        np.testing.assert_allclose(bag.position_rad, yaml.position_rad, atol=1e-11)
        np.testing.assert_allclose(bag.time_s, yaml.time_s, atol=1e-12)
    else:
        assert_matches_golden(out, out.name)
    # Parse back: the rebuilt container follows the plan along x from the path start.
    time, poses = rebuild_container_poses(fmt, out, ur5e, MOUNTING)
    plan = quintic_plan()
    expected_time = np.arange(51) * 0.002 if fmt == "urscript" else plan.time_s
    np.testing.assert_allclose(time, expected_time, atol=1e-12)
    start = np.array([0.0, 0.0, 0.0]) if fmt == "cam-table" else np.array(MOUNTING.base_xyz_m)
    if fmt == "cam-table":
        poses = np.linalg.inv(MOUNTING.base_to_path)[None] @ poses
    along = poses[:, :3, 3] - start
    np.testing.assert_allclose(along[:, 0], plan.evaluate(time)[0], atol=1e-6)
    np.testing.assert_allclose(along[:, 1:], 0.0, atol=1e-6)


def test_pose_csv_header_and_values(tmp_path: Path) -> None:
    out = export_plan(
        quintic_plan(), "pose-csv", tmp_path / "p.csv", mounting=MOUNTING, check=False
    )
    text = out.path.read_text()
    for key in ("format", "sloshkit_version", "units", "frame", "sample_period_s", "mounting"):
        assert f"# {key}: " in text
    stream = read_pose_csv(out.path)
    assert stream.metadata["sample_period_s"] == "0.01"
    np.testing.assert_allclose(stream.quaternion_xyzw, np.tile([0, 0, 0, 1.0], (11, 1)))
    np.testing.assert_allclose(stream.position_m[-1], [-0.47, -0.13, 0.39], atol=1e-12)


def test_pose_csv_resamples_at_a_chosen_rate(tmp_path: Path) -> None:
    out = tmp_path / "p.csv"
    export_plan(quintic_plan(), "pose-csv", out, sample_period_s=0.004, check=False)
    stream = read_pose_csv(out)
    assert stream.time_s.size == 26
    # The quintic plan is reproduced exactly by its quintic Hermite interpolant.
    s = stream.time_s / 0.1
    np.testing.assert_allclose(
        stream.position_m[:, 0], 0.02 * s**3 * (10 - 15 * s + 6 * s**2), atol=1e-12
    )


def test_joint_csv_parses_back_to_the_same_joints(tmp_path: Path, ur5e) -> None:
    out = tmp_path / "j.csv"
    result = export_plan(quintic_plan(), "joint-csv", out, arm=ur5e, mounting=MOUNTING, check=False)
    parsed = read_joint_csv(out)
    assert result.joints is not None
    assert parsed.joint_names == ur5e.joint_names
    for name in ("position_rad", "velocity_rad_s", "acceleration_rad_s2"):
        np.testing.assert_allclose(
            getattr(parsed, name), getattr(result.joints, name), rtol=1e-11, atol=1e-12
        )


def test_ros2_yaml_is_a_joint_trajectory_message(tmp_path: Path, ur5e) -> None:
    out = tmp_path / "t.yaml"
    result = export_plan(quintic_plan(), "ros2", out, arm=ur5e, mounting=MOUNTING, check=False)
    message = yaml.safe_load(out.read_text())
    assert set(message) == {"header", "joint_names", "points"}
    assert message["header"] == {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "base"}
    assert message["joint_names"] == list(ur5e.joint_names)
    assert len(message["points"]) == 11
    for index, point in enumerate(message["points"]):
        assert set(point) == {
            "positions",
            "velocities",
            "accelerations",
            "effort",
            "time_from_start",
        }
        assert point["time_from_start"] == {"sec": 0, "nanosec": 10_000_000 * index}
        assert len(point["positions"]) == 6 and point["effort"] == []
    joints, frame = read_ros2_yaml(out)
    assert frame == "base" and result.joints is not None
    np.testing.assert_allclose(joints.position_rad, result.joints.position_rad, atol=1e-11)


def test_urscript_has_one_servoj_per_2ms_sample(tmp_path: Path, ur5e) -> None:
    out = tmp_path / "m.script"
    result = export_plan(quintic_plan(), "urscript", out, arm=ur5e, mounting=MOUNTING, check=False)
    lines = out.read_text().splitlines()
    servoj = [line for line in lines if line.strip().startswith("servoj(")]
    assert result.sample_period_s == 0.002
    assert len(servoj) == result.samples + 1 == round(0.1 / 0.002) + 2  # and the hold
    assert all(line.endswith(", 0, 0, 0.002, 0.05, 500)") for line in servoj[:-1])
    assert servoj[-1].endswith(", 0, 0, 0.2, 0.05, 500)  # hold the last target")
    assert lines[0] == "def sloshkit_move():" and lines[-2:] == ["  stopj(2.0)", "end"]
    assert all(line.startswith("  ") for line in lines[1:-1])  # one def ... end block
    assert sum(line.strip().startswith("movej(") for line in lines) == 1
    time, joints = read_urscript(out)
    assert joints.shape == (51, 6)
    np.testing.assert_allclose(np.diff(time), 0.002, atol=1e-15)


def test_urscript_rejects_out_of_range_parameters(tmp_path: Path, ur5e) -> None:
    with pytest.raises(InputError, match="gain"):
        export_plan(
            quintic_plan(),
            "urscript",
            tmp_path / "m.script",
            arm=ur5e,
            mounting=MOUNTING,
            gain=50.0,
            check=False,
        )
    with pytest.raises(InputError, match=r"0\.002"):
        export_plan(
            quintic_plan(),
            "urscript",
            tmp_path / "m.script",
            arm=ur5e,
            mounting=MOUNTING,
            sample_period_s=0.004,
            check=False,
        )
    result = export_plan(
        quintic_plan(), "joint-csv", tmp_path / "j.csv", arm=ur5e, mounting=MOUNTING, check=False
    )
    assert result.joints is not None
    with pytest.raises(InputError, match=r"0\.002"):
        write_urscript(tmp_path / "x.script", result.joints, {})


def test_cam_table_round_trips_and_refuses_3d_plans(tmp_path: Path) -> None:
    out = tmp_path / "c.csv"
    export_plan(quintic_plan(), "cam-table", out, check=False)
    line = read_cam_table(out)
    plan = quintic_plan()
    for name in ("time_s", "position_m", "velocity_m_s", "acceleration_m_s2"):
        np.testing.assert_allclose(getattr(line, name), getattr(plan, name), atol=1e-12)
    upright = np.tile([0, 0, 0, 1.0], (11, 1))
    stream = PoseStream(PoseTrajectory(plan.time_s, np.zeros((11, 3)), upright))
    with pytest.raises(InputError, match="1-D plan"):
        export_plan(stream, "cam-table", out, check=False)


def test_unknown_format_and_missing_arm(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="must be one of"):
        export_plan(quintic_plan(), "kuka-rsi", tmp_path / "x", check=False)
    with pytest.raises(InputError, match="needs an arm"):
        export_plan(quintic_plan(), "joint-csv", tmp_path / "x", check=False)
    with pytest.raises(InputError, match="slosh model"):
        export_plan(quintic_plan(), "pose-csv", tmp_path / "x")
