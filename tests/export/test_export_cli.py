"""`sloshkit export` and `sloshkit plan --export`: JSON contract, exit codes, one-line errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from conftest import run_entry_point
from typer.testing import CliRunner

from sloshkit.cli import app

runner = CliRunner()
BASE_POSE = "--base-pose=-0.49m,-0.13m,390mm"


def write_quintic_plan(path: Path, distance_m: float = 0.1, duration_s: float = 0.4) -> Path:
    """A quintic move as `sloshkit plan --out` writes it (t_s, position_m, ...)."""
    t = np.arange(round(duration_s / 0.004) + 1) * 0.004
    s = t / duration_s
    columns = {
        "t_s": t,
        "position_m": distance_m * s**3 * (10 - 15 * s + 6 * s**2),
        "velocity_m_s": distance_m / duration_s * 30 * s**2 * (1 - s) ** 2,
        "acceleration_m_s2": distance_m / duration_s**2 * 60 * s * (1 - s) * (1 - 2 * s),
        "jerk_m_s3": distance_m / duration_s**3 * 60 * (1 - 6 * s + 6 * s**2),
    }
    table = np.column_stack(list(columns.values()))
    np.savetxt(path, table, delimiter=",", header=",".join(columns), comments="", fmt="%.10g")
    return path


def test_export_joint_csv_json_contract(tmp_path: Path) -> None:
    plan = write_quintic_plan(tmp_path / "plan.csv")
    result = runner.invoke(
        app,
        ["export", str(plan), "--format", "joint-csv", BASE_POSE, "--damping-ratio=0.03", "--json"],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.output)
    assert set(payload) == {
        "format",
        "path",
        "samples",
        "sample_period_s",
        "joints",
        "round_trip",
        "passed",
        "written",  # False when a failed round trip removed the file (issue 24)
        "notes",
        "model_source",  # the plan file's header, the command line or both (issue 24)
        "limits",
        "warnings",  # every --json object carries the command's validity warnings (issue 17)
    }
    assert payload["path"] == str(tmp_path / "plan.joints.csv")
    assert (tmp_path / "plan.joints.csv").is_file()
    assert payload["samples"] == 101 and payload["sample_period_s"] == 0.004
    trip = payload["round_trip"]
    assert trip["passed"] and payload["passed"]
    assert set(trip) == {
        "passed",
        "method",
        "relative_tolerance",
        "plan",
        "export",
        "relative_difference",
        "max_position_error_m",
        "max_orientation_error_deg",
        "violations",
    }
    assert trip["max_position_error_m"] < 1e-6
    assert payload["joints"]["joint_names"][0] == "shoulder_pan_joint"


def test_export_exits_1_when_a_limit_is_broken(tmp_path: Path) -> None:
    plan = write_quintic_plan(tmp_path / "plan.csv")
    result = runner.invoke(
        app,
        [
            *("export", str(plan), "--format", "cam-table", "--out", str(tmp_path / "cam.csv")),
            *("--max-angle", "0.5deg", "--max-residual", "0.25deg", "--radius", "20.5mm"),
            "--json",
        ],
    )
    assert result.exit_code == 1, result.output
    payload = json.loads(result.output)
    assert not payload["passed"]
    assert any("limit" in violation for violation in payload["round_trip"]["violations"])


def test_unreachable_path_is_one_line_exit_2(tmp_path: Path) -> None:
    plan = write_quintic_plan(tmp_path / "plan.csv", duration_s=0.1)
    completed = run_entry_point(
        "export", str(plan), "--format", "ros2", "--robot", "ur5e", "--base-pose=2m,0,0.3m",
        "--radius", "20.5mm",
    )  # fmt: skip
    assert completed.returncode == 2
    lines = completed.stderr.strip().splitlines()
    assert len(lines) == 1 and "sample 0" in lines[0] and "cannot reach" in lines[0]
    assert "Traceback" not in completed.stderr


def test_plan_export_writes_the_chosen_move(tmp_path: Path) -> None:
    out = tmp_path / "move.csv"
    result = runner.invoke(
        app,
        [
            *("plan", "--distance", "0.1m", "--max-angle", "5deg", "--max-residual", "0.25deg"),
            *("--vmax", "1m/s", "--amax", "10m/s^2", "--jmax", "200m/s^3", "--method", "paper"),
            *("--damping-ratio", "0.03", "--out", str(out), "--export", "cam-table", "--json"),
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.output)
    assert payload["export"]["path"] == str(tmp_path / "move.cam.csv")
    assert payload["export"]["round_trip"]["passed"]
    header = (tmp_path / "move.cam.csv").read_text().splitlines()
    assert any(line.startswith("# limits: ") for line in header)
    assert any(line.startswith("# model: ") for line in header)


def test_export_of_a_pose_stream_uses_the_3d_model(tmp_path: Path) -> None:
    """A pose-csv written by export is itself a plan: its joint export is checked in 3-D."""
    from sloshkit.export import Mounting, export_plan, read_plan

    plan = write_quintic_plan(tmp_path / "plan.csv", duration_s=0.2)
    poses = tmp_path / "poses.csv"
    export_plan(
        read_plan(plan),
        "pose-csv",
        poses,
        mounting=Mounting(base_xyz_m=(-0.49, -0.13, 0.39)),
        check=False,
    )
    result = runner.invoke(
        app, ["export", str(poses), "--format", "joint-csv", "--radius", "20.5mm", "--json"]
    )
    assert result.exit_code == 0, result.output
    trip = json.loads(result.output)["round_trip"]
    assert trip["passed"] and "3-D" in trip["method"]
    assert "peak_slosh_height_m" in trip["plan"]


def test_mounting_and_seed_options_are_parsed_with_units(tmp_path: Path) -> None:
    plan = write_quintic_plan(tmp_path / "plan.csv", distance_m=0.05, duration_s=0.2)
    result = runner.invoke(
        app,
        [
            *("export", str(plan), "--format", "joint-csv", "--axis", "y", "--json"),
            *("--seed-joints", "0,-90deg,90deg,-90deg,-90deg,0", "--radius", "20.5mm"),
            *("--tool-offset", "0,0,0.1m", "--tool-rotation", "3.141592653589793,0,0"),
            "--base-pose=-490mm,-0.13m,0.39m,0deg,0deg,90deg",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.output)
    assert payload["round_trip"]["passed"]
    header = (tmp_path / "plan.joints.csv").read_text()
    assert '"base_rotation_rpy_rad": [0.0, 0.0, 1.570796326795]' in header
    bad = runner.invoke(app, ["export", str(plan), "--base-pose", "1,2"])
    assert bad.exit_code != 0
    assert "base_pose" in str(bad.exception) or "base_pose" in bad.output
