"""`sloshkit simulate` and `sloshkit compare`: JSON contract, files, errors."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import run_entry_point
from typer.testing import CliRunner

from sloshkit.cli import app

runner = CliRunner()

SIMULATE_KEYS = {
    "duration_s",
    "peak_angle_deg",
    "residual_angle_deg",
    "peak_wall_elevation_m",
    "residual_wall_elevation_m",
    "settling_time_s",
    "peak_acceleration_m_s2",
    "peak_jerk_m_s3",
}


def test_simulate_json_keys_and_files(tmp_path):
    result = runner.invoke(
        app,
        [
            "simulate",
            "--law",
            "quintic",
            "--distance",
            "0.5m",
            "--duration",
            "1.5s",
            "--damping-ratio",
            "0.03",
            "--csv",
            str(tmp_path / "r.csv"),
            "--plot",
            str(tmp_path / "r.png"),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert SIMULATE_KEYS <= set(payload)
    assert payload["duration_s"] == pytest.approx(1.5)
    assert payload["peak_jerk_m_s3"] == pytest.approx(60 * 0.5 / 1.5**3)
    assert (tmp_path / "r.png").stat().st_size > 10_000
    header = (tmp_path / "r.csv").read_text().splitlines()[0]
    assert header.startswith("t_s,position_m,velocity_m_s,acceleration_m_s2,angle_1_rad")


@pytest.mark.filterwarnings("ignore::sloshkit.errors.ValidityWarning")
def test_simulate_s_curve_from_machine_limits():
    payload = json.loads(
        runner.invoke(
            app,
            [
                "simulate",
                "--law",
                "s-curve",
                "--distance",
                "0.5m",
                "--vmax",
                "1m/s",
                "--amax",
                "5m/s^2",
                "--jmax",
                "50m/s^3",
                "--json",
            ],
        ).stdout
    )
    assert payload["duration_s"] == pytest.approx(0.8)
    assert payload["peak_acceleration_m_s2"] == pytest.approx(5.0)


def test_simulate_trapezoid_jerk_is_null_in_json():
    payload = json.loads(
        runner.invoke(
            app, ["simulate", "--law", "trapezoidal", "--peak-velocity", "0.5m/s", "--json"]
        ).stdout
    )
    assert payload["peak_jerk_m_s3"] is None
    assert payload["duration_s"] == pytest.approx(1.5)


def test_simulate_user_motion_file(tmp_path):
    t = np.linspace(0, 1.5, 301)
    tau = t / 1.5
    x = 0.5 * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
    path = tmp_path / "move.csv"
    path.write_text("t,x\n" + "\n".join(f"{a},{b}" for a, b in zip(t, x, strict=True)))
    from_file = json.loads(
        runner.invoke(app, ["simulate", "--law", f"file:{path}", "--json"]).stdout
    )
    exact = json.loads(
        runner.invoke(app, ["simulate", "--law", "quintic", "--duration", "1.5s", "--json"]).stdout
    )
    assert from_file["residual_angle_deg"] == pytest.approx(exact["residual_angle_deg"], rel=1e-3)


def test_compare_writes_table_and_figures(tmp_path):
    result = runner.invoke(
        app,
        [
            "compare",
            "--distance",
            "0.5m",
            "--peak-velocity",
            "0.5m/s",
            "--damping-ratio",
            "0.03",
            "--out",
            str(tmp_path),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert payload["model"] == "linear" and payload["distance_m"] == pytest.approx(0.5)
    assert isinstance(payload["warnings"], list)
    rows = payload["laws"]
    assert json.loads((tmp_path / "compare.json").read_text())["laws"] == rows
    assert [row["law"] for row in rows] == ["trapezoidal", "cubic", "quintic", "septic", "s-curve"]
    for row in rows:
        assert SIMULATE_KEYS <= set(row)
    residual = {row["law"]: row["residual_angle_deg"] for row in rows}
    assert residual["trapezoidal"] > 5 * residual["septic"]
    for name in ("compare.csv", "compare.json", "fig7_laws.png", "fig8_slosh.png"):
        assert (tmp_path / name).stat().st_size > 100


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["simulate", "--law", "warp"], "law"),
        (["simulate", "--distance", "-1m", "--duration", "1s"], "distance"),
        (["simulate", "--duration", "0s"], "duration"),
        (["simulate", "--law", "s-curve", "--vmax", "1m/s"], "amax"),
        (["simulate", "--law", "file:/nonexistent.csv"], "file"),
        (["simulate", "--duration", "1s", "--model", "quantum"], "model"),
        (["compare", "--peak-velocity", "-1m/s"], "--peak-velocity"),
    ],
)
def test_bad_input_exits_2_with_one_line(args, needle):
    proc = run_entry_point(*args)
    assert proc.returncode == 2, proc.stderr
    assert needle in proc.stderr
    assert "Traceback" not in proc.stderr


def test_non_monotonic_motion_file(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("t,x\n0,0\n0.1,0.1\n0.1,0.2\n0.3,0.3\n0.4,0.4\n0.5,0.5\n0.6,0.6\n")
    proc = run_entry_point("simulate", "--law", f"file:{path}")
    assert proc.returncode == 2
    assert "time" in proc.stderr and "increase" in proc.stderr
