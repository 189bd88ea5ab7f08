"""Issue 24: plans that survive the export, and the export to the arm made safe.

The README's plan -> export pipeline as a user runs it (the entry point in a subprocess), the
plan file's header (model and limits), the limits at every supported controller period, moves
not at rest, failed round trips, the URScript settle and hold, the rosbag2 read back with the
real message types, and the documented IK configuration.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import run_entry_point

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.export.headers import plan_header, read_plan_header, write_plan_csv
from sloshkit.export.plans import LinePlan, PoseStream, read_metadata, read_plan
from sloshkit.export.roundtrip import line_metrics
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
from sloshkit.plan.path.problem import SpatialSloshLimits

README_PLAN = (
    "plan",
    "--distance",
    "0.5m",
    "--max-angle",
    "5deg",
    "--max-residual",
    "0.25deg",
    "--vmax",
    "1.5m/s",
    "--amax",
    "20m/s^2",
    "--jmax",
    "500m/s^3",
    "--damping-ratio",
    "0.03",
    "--sample-period",
    "4ms",
)
README_EXPORT = (
    "--format",
    "urscript",
    "--robot",
    "ur5e",
    "--base-pose=-0.7m,-0.25m,0.3m",
    "--damping-ratio",
    "0.03",
    "--max-angle",
    "5deg",
    "--max-residual",
    "0.25deg",
)


@pytest.fixture(scope="module")
def readme_plan(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The README's `sloshkit plan ... --out traj.csv`, run once."""
    folder = tmp_path_factory.mktemp("readme")
    out = folder / "traj.csv"
    proc = run_entry_point(*README_PLAN, "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    assert "chosen: optimal" in proc.stdout
    return out


def _model() -> object:
    return equivalent_model(
        UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, damping_ratio=0.03
    )


def test_readme_pipeline_plan_then_export_passes_its_round_trip(
    readme_plan: Path, tmp_path: Path
) -> None:
    """It exited 1 ("export 5.01921 > limit 5"): the plan was verified at 4 ms only."""
    out = tmp_path / "traj.script"
    proc = run_entry_point("export", str(readme_plan), *README_EXPORT, "--out", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    payload = json.loads(proc.stdout)
    trip = payload["round_trip"]
    assert payload["passed"] and payload["written"] and trip["violations"] == []
    assert trip["export"]["peak_angle_deg"] <= 5.0
    assert trip["export"]["residual_angle_deg"] <= 0.25
    assert payload["model_source"].startswith("plan file")
    assert payload["warnings"] == []  # the command line repeats the plan's model and limits
    assert out.is_file()


def test_readme_plan_with_export_urscript_passes(tmp_path: Path) -> None:
    """`plan ... --export urscript` exited 1 (3.007 deg > 3 deg) for the same reason."""
    out = tmp_path / "traj.csv"
    proc = run_entry_point(
        *README_PLAN[:4], "3deg", *README_PLAN[5:], "--out", str(out),
        "--export", "urscript", "--base-pose=-0.7m,-0.25m,0.3m",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr + proc.stdout  # exit 1 when the round trip fails
    assert "round trip: passed" in proc.stdout
    assert (tmp_path / "traj.script").is_file() and out.is_file()


@pytest.mark.parametrize("period_s", [0.002, 0.004, 0.008])
def test_plan_limits_hold_at_every_supported_controller_period(
    readme_plan: Path, period_s: float
) -> None:
    """The 4 ms plan resampled at 2, 4 and 8 ms and re-simulated (the round trip's
    simulation) stays within its limits (to the round trip's 0.1 % resolution)."""
    plan = read_plan(readme_plan)
    assert isinstance(plan, LinePlan)
    resampled = plan.resample(period_s)
    metrics = line_metrics(_model(), resampled.time_s, resampled.position_m)  # type: ignore[arg-type]
    assert metrics["peak_angle_deg"] <= 5.0 * (1 + 1e-3)
    assert metrics["residual_angle_deg"] <= 0.25 * (1 + 1e-3)


def test_plan_on_the_check_grid_is_exact_at_2ms() -> None:
    """The optimal plan at 4 ms, simulated independently on the 2 ms grid (exact first-order
    hold of the exact motion's velocity samples), meets its limits to solver precision; on
    the old 4 ms-only check the same problem's optimum left 5.019 deg at 2 ms."""
    from sloshkit.motion.sampling import export_samples
    from sloshkit.plan.line.optimal import plan_optimal
    from sloshkit.sim.discretisation import linear_response
    from sloshkit.sim.metrics import free_amplitude

    model = _model()
    problem = PlanProblem(
        0.3,
        MachineLimits(1.5, 20.0, 500.0),
        SloshLimits(math.radians(5), math.radians(0.25)),
        model,  # type: ignore[arg-type]
        4e-3,
    )
    best = plan_optimal(problem)
    assert best.feasible
    samples = export_samples(best.motion, 2e-3)
    theta, rate = linear_response(model, samples["velocity_m_s"], 2e-3)  # type: ignore[arg-type]
    first = model.modes[0]  # type: ignore[attr-defined]
    residual = free_amplitude(theta[0, -1], rate[0, -1], first.omega_rad_s, first.damping_ratio)
    assert np.max(np.abs(theta[0])) <= math.radians(5) * (1 + 1e-7)
    assert residual <= math.radians(0.25) * (1 + 1e-7)
    # The limit is reached (an optimum rides it), so the check is not vacuous.
    assert np.max(np.abs(theta[0])) > math.radians(5) * (1 - 1e-3)


def test_plan_file_header_carries_model_limits_and_units(readme_plan: Path) -> None:
    header = read_plan_header(read_metadata(readme_plan))
    assert header is not None
    assert header["kind"] == "line" and header["sample_period_s"] == 0.004
    assert header["slosh_check_period_s"] == 0.002
    assert header["model"]["modes"][0]["damping_ratio"] == 0.03
    assert header["model_options"]["damping_ratio"] == 0.03
    assert header["limits"]["max_angle_rad"] == pytest.approx(math.radians(5))
    assert "t_s [s]" in read_metadata(readme_plan)["units"]


def test_export_takes_the_model_from_the_header_and_warns_on_overrides(
    readme_plan: Path, tmp_path: Path
) -> None:
    """Without model options the plan's own model (not the default vial); an option given
    replaces only itself, with a warning that reaches JSON."""
    plain = run_entry_point(
        "export", str(readme_plan), "--out", str(tmp_path / "a.poses.csv"), "--json"
    )
    assert plain.returncode == 0, plain.stderr
    payload = json.loads(plain.stdout)
    assert payload["model_source"] == "plan file" and payload["warnings"] == []
    assert payload["limits"]["max_angle_rad"] == pytest.approx(math.radians(5))
    changed = run_entry_point(
        "export", str(readme_plan), "--out", str(tmp_path / "b.poses.csv"),
        "--damping-ratio", "0.01", "--json",
    )  # fmt: skip
    payload = json.loads(changed.stdout)
    assert payload["model_source"] == "plan file, with --damping-ratio from the command line"
    assert any("damping ratio 0.01" in warning for warning in payload["warnings"])
    # The plan's fill and radius were kept: only the damping differs.
    assert not any("radius" in warning for warning in payload["warnings"])


def test_export_refuses_a_plan_without_header_and_without_model_options(tmp_path: Path) -> None:
    t = np.arange(101) * 0.004
    s = t / t[-1]
    plan = tmp_path / "bare.csv"
    rows = np.column_stack((t, 0.1 * s**3 * (10 - 15 * s + 6 * s**2)))
    np.savetxt(plan, rows, delimiter=",", header="t_s,position_m", comments="")
    proc = run_entry_point("export", str(plan), "--json")
    assert proc.returncode == 2
    assert "names no model" in proc.stderr and "--radius" in proc.stderr
    assert proc.stdout == "" and not (tmp_path / "bare.poses.csv").exists()
    given = run_entry_point("export", str(plan), "--radius", "20.5mm", "--json")
    assert given.returncode == 0, given.stderr
    assert json.loads(given.stdout)["model_source"] == "command line"
    unchecked = run_entry_point(
        "export", str(plan), "--no-check", "--out", str(tmp_path / "x.csv"), "--json"
    )
    assert unchecked.returncode == 0, unchecked.stderr


def test_export_checks_a_3d_plan_against_its_slosh_height_limits(tmp_path: Path) -> None:
    """A pose plan whose header says 0.1 mm of slosh height: the export's round trip
    re-simulates it with the 3-D model and fails on that limit (exit 1, no file left)."""
    t = np.arange(151) * 0.004
    s = t / t[-1]
    x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    upright = np.tile([0, 0, 0, 1.0], (151, 1))
    stream = PoseStream(PoseTrajectory(t, np.column_stack((x, 0 * x, 0 * x)), upright))
    header = plan_header(_model(), SpatialSloshLimits(1e-4, 1e-4), 0.004)  # type: ignore[arg-type]
    plan = write_plan_csv(
        tmp_path / "poses.csv",
        {
            "t": stream.time_s,
            "x": stream.position_m[:, 0],
            "y": stream.position_m[:, 1],
            "z": stream.position_m[:, 2],
            "qx": stream.quaternion_xyzw[:, 0],
            "qy": stream.quaternion_xyzw[:, 1],
            "qz": stream.quaternion_xyzw[:, 2],
            "qw": stream.quaternion_xyzw[:, 3],
        },
        header,
    )
    out = tmp_path / "poses.joints.csv"
    proc = run_entry_point(
        "export", str(plan), "--format", "joint-csv", "--base-pose=-0.49m,-0.13m,390mm",
        "--out", str(out), "--json",
    )  # fmt: skip
    assert proc.returncode == 1, proc.stderr
    payload = json.loads(proc.stdout)
    assert payload["round_trip"]["method"].startswith("3-D")
    assert any(v.startswith("peak_slosh_height_m") for v in payload["round_trip"]["violations"])
    assert payload["written"] is False and not out.exists()


def test_export_refuses_a_move_that_does_not_end_at_rest(tmp_path: Path) -> None:
    t = np.arange(101) * 0.004
    plan = tmp_path / "cut.csv"
    rows = np.column_stack((t, 0.5 * t, 0.5 + 0 * t, 0 * t))
    np.savetxt(
        plan, rows, delimiter=",", header="t_s,position_m,velocity_m_s,acceleration_m_s2",
        comments="",
    )  # fmt: skip
    proc = run_entry_point("export", str(plan), "--radius", "20.5mm", "--format", "joint-csv")
    assert proc.returncode == 2
    assert "end speed 0.5 m/s" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "cut.joints.csv").exists()


@pytest.mark.parametrize("fmt", ["urscript", "ros2-bag"])
def test_failed_round_trip_leaves_no_file(readme_plan: Path, tmp_path: Path, fmt: str) -> None:
    """A limit the plan does not meet (4 deg for a 5 deg plan): exit 1, nothing at --out."""
    out = tmp_path / ("move.script" if fmt == "urscript" else "move.bag")
    proc = run_entry_point(
        "export", str(readme_plan), "--format", fmt, "--base-pose=-0.7m,-0.25m,0.3m",
        "--max-angle", "4deg", "--max-residual", "0.25deg", "--out", str(out), "--json",
    )  # fmt: skip
    assert proc.returncode == 1
    assert json.loads(proc.stdout)["written"] is False
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []  # no staging folder either


def test_urscript_waits_for_the_approach_and_holds_the_last_target(
    readme_plan: Path, tmp_path: Path
) -> None:
    from sloshkit.export.formats.urscript import hold_time, read_urscript

    out = tmp_path / "move.script"
    proc = run_entry_point("export", str(readme_plan), *README_EXPORT, "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    lines = out.read_text().splitlines()
    movej = next(i for i, line in enumerate(lines) if line.strip().startswith("movej("))
    assert lines[movej + 2].strip().startswith("sleep(")
    wait = float(lines[movej + 2].strip()[len("sleep(") : -1])
    # The bound's decay to the residual limit at zeta = 0.03, f1 = 4.72 Hz: seconds.
    assert 1.0 < wait < 30.0
    assert lines[-3].endswith("# hold the last target") and lines[-2].strip() == "stopj(2.0)"
    assert f", {hold_time(0.05):g}, " in lines[-3]
    times, joints = read_urscript(out)  # the hold is not a sample of the move
    assert np.allclose(np.diff(times), 0.002)
    assert np.array_equal(joints[-1], joints[-2]) is False or joints.shape[0] > 2


def test_ros2_bag_reads_back_with_the_real_message_type(readme_plan: Path, tmp_path: Path) -> None:
    """A 1.57 s trajectory (past the 0.6 s that `ros2 topic pub "$(...)"` carries): the bag's
    one message, deserialised by rosbags' typestore as trajectory_msgs/msg/JointTrajectory,
    holds the same joint samples as the joint CSV."""
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_typestore

    from sloshkit.export.formats.joint_csv import read_joint_csv

    bag = tmp_path / "move.bag"
    common = ("--base-pose=-0.7m,-0.25m,0.3m", "--json")
    proc = run_entry_point(
        "export", str(readme_plan), "--format", "ros2-bag", "--out", str(bag), *common
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["round_trip"]["passed"]
    csv = tmp_path / "move.joints.csv"
    proc = run_entry_point(
        "export", str(readme_plan), "--format", "joint-csv", "--out", str(csv), *common
    )
    assert proc.returncode == 0, proc.stderr
    store = get_typestore(Stores.ROS2_JAZZY)
    with Reader(bag) as reader:
        (connection,) = reader.connections
        assert connection.topic == "/joint_trajectory_controller/joint_trajectory"
        assert connection.msgtype == "trajectory_msgs/msg/JointTrajectory"
        messages = list(reader.messages())
    assert len(messages) == 1
    message = store.deserialize_cdr(messages[0][2], connection.msgtype)
    joints = read_joint_csv(csv)
    assert list(message.joint_names) == list(joints.joint_names)
    assert message.header.frame_id == "base"
    positions = np.array([point.positions for point in message.points])
    times = np.array(
        [p.time_from_start.sec + 1e-9 * p.time_from_start.nanosec for p in message.points]
    )
    assert times[-1] > 1.5
    assert np.allclose(positions, joints.position_rad, atol=1e-12)
    assert np.allclose(times, joints.time_s, atol=1e-9)


def test_default_ik_configuration_is_the_documented_one_on_the_far_side() -> None:
    """A pose behind the base (x > 0) from the default seed: the base turns towards it and the
    arm keeps the documented configuration (shoulder as the seed, elbow up), instead of
    reaching over its shoulder (shoulder lift -195 deg before)."""
    from sloshkit.export.ik import solve_joint_path
    from sloshkit.export.kinematics import load_arm

    arm = load_arm("ur5e")
    target = arm.forward(arm.home_rad[None])[0]
    target[:3, 3] = [0.5, 0.13, 0.3]
    frames = np.stack([target] * 3)
    frames[1:, 0, 3] += [0.001, 0.002]
    first = solve_joint_path(arm, frames, np.arange(3) * 0.004).position_rad[0]
    shoulder, elbow = math.degrees(first[1]), math.degrees(first[2])
    assert -180.0 < shoulder < 0.0  # not flipped over the top
    assert elbow > 0.0  # elbow up, as the seed (0, -90, 90, -90, -90, 0 deg)
