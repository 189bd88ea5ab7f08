"""`sloshkit simulate --pose-file`: pose-file reading, JSON/CSV/plot contract, 1-D equivalence."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import run_entry_point
from typer.testing import CliRunner

from sloshkit.cli import app
from sloshkit.errors import InputError
from sloshkit.io.poses import read_pose_file, split_column_name
from sloshkit.motion.laws import quintic
from sloshkit.motion.sampling import sample_times

runner = CliRunner()
DATA = Path(__file__).parents[1] / "data" / "measured-3d"
MODEL = ["--radius", "49mm", "--fill-height", "80mm", "--liquid", "water-20C"]
KEYS = {
    "duration_s",
    "peak_slosh_height_m",
    "residual_slosh_height_m",
    "peak_angle_deg",
    "residual_angle_deg",
    "warnings",
}


def _quintic_file(path: Path, separator: str = ",", millimetres: bool = False) -> Path:
    law = quintic(0.2, 1.0)
    t = sample_times(1.0, 0.002)
    x = law.position(t) * (1e3 if millimetres else 1.0)
    header = ["t", "x [mm]" if millimetres else "x", "y", "z", "qx", "qy", "qz", "qw"]
    lines = [separator.join(header)]
    lines += [
        separator.join(f"{v:.12g}" for v in (ti, xi, 0, 0, 0, 0, 0, 1))
        for ti, xi in zip(t, x, strict=True)
    ]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_column_names_with_units() -> None:
    assert split_column_name("x [mm]") == ("x", "mm")
    assert split_column_name("t(ms)") == ("t", "ms")
    assert split_column_name("yaw_deg") == ("yaw", "deg")
    assert split_column_name("qx") == ("qx", None)


def test_reader_honours_units_separators_and_tool_offset(tmp_path: Path) -> None:
    plain = read_pose_file(_quintic_file(tmp_path / "a.csv"))
    semicolon = read_pose_file(_quintic_file(tmp_path / "b.csv", ";", millimetres=True))
    spaces = read_pose_file(_quintic_file(tmp_path / "c.txt", " "))
    for other in (semicolon, spaces):
        assert np.allclose(other.position_m, plain.position_m, atol=1e-12)
    shifted = read_pose_file(tmp_path / "a.csv", tool_offset_m=(0.0, 0.0, -0.1))
    assert np.allclose(shifted.position_m[:, 2], -0.1)


def test_reader_errors(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("t,x,y,z\n0,0,0,0\n1,0,0,0\n")
    with pytest.raises(InputError, match="orientation"):
        read_pose_file(bad)
    bad.write_text("t,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,2\n1,0,0,0,0,0,0,1\n")
    with pytest.raises(InputError, match="unit quaternion"):
        read_pose_file(bad)


def test_pose_file_json_and_files(tmp_path: Path) -> None:
    poses = DATA / "poses" / "TRD_2D_0.3m_2.4s_270deg.csv"
    result = runner.invoke(
        app,
        [
            "simulate",
            "--pose-file",
            str(poses),
            *MODEL,
            "--damping-ratio",
            "0.0066",
            "--csv",
            str(tmp_path / "out.csv"),
            "--plot",
            str(tmp_path / "out.png"),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert KEYS <= set(payload)
    assert payload["duration_s"] == pytest.approx(3.4)
    assert any("slosh angle" in message for message in payload["warnings"])
    header = (tmp_path / "out.csv").read_text().splitlines()[0].split(",")
    assert {"t_s", "slosh_height_m", "surface_tilt_x_rad", "surface_tilt_y_rad"} <= set(header)
    assert (tmp_path / "out.png").stat().st_size > 1000


def test_a_1d_law_and_the_same_move_as_poses_give_the_same_numbers(tmp_path: Path) -> None:
    path = _quintic_file(tmp_path / "move.csv")
    one_d = json.loads(
        runner.invoke(
            app,
            ["simulate", "--law", "quintic", "--distance", "0.2m", "--duration", "1s", "--json"],
        ).stdout
    )
    three_d = json.loads(
        runner.invoke(app, ["simulate", "--pose-file", str(path), "--json"]).stdout
    )
    assert three_d["peak_angle_deg"] == pytest.approx(one_d["peak_angle_deg"], rel=2e-3)
    assert three_d["residual_angle_deg"] == pytest.approx(one_d["residual_angle_deg"], rel=5e-3)
    assert math.isfinite(three_d["peak_slosh_height_m"])


def test_bad_pose_input_exits_2(tmp_path: Path) -> None:
    path = _quintic_file(tmp_path / "move.csv")
    proc = run_entry_point("simulate", "--pose-file", str(path), "--tool-offset", "1,2")
    assert proc.returncode == 2
    assert "--tool-offset" in proc.stderr and "Traceback" not in proc.stderr
    result = runner.invoke(app, ["simulate", "--pose-file", str(tmp_path / "missing.csv")])
    assert isinstance(result.exception, InputError)
