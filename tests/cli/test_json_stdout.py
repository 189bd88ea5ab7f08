"""stdout carries the result only: every ``--json`` command, run as users run it (the installed
``sloshkit`` entry point in a subprocess), prints exactly one JSON object on stdout, even when a
C library writes to file descriptor 1 during the work (today's HiGHS prints its banner there)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
POSES = ROOT / "tests" / "data" / "measured-3d" / "poses" / "TRD_2D_0.3m_2.4s_270deg.csv"
DECAY = ROOT / "src" / "sloshkit" / "report" / "data" / "cfd-free-decay.csv"


def entry_point() -> list[str]:
    """The installed console script beside this interpreter (or on PATH)."""
    beside = Path(sys.executable).with_name("sloshkit")
    if beside.exists():
        return [str(beside)]
    found = shutil.which("sloshkit")
    if found is None:  # pragma: no cover - an environment without the console script
        pytest.skip("the sloshkit console script is not installed")
    return [found]


def run_json(args: list[str], cwd: Path) -> dict[str, object]:
    result = subprocess.run(
        [*entry_point(), *args, "--json"],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "COLUMNS": "100"},
    )
    assert result.returncode in (0, 1), result.stderr[-2000:]
    payload = json.loads(result.stdout)  # the whole of stdout is one JSON document
    assert isinstance(payload, dict)
    assert isinstance(payload.get("warnings"), list)
    return payload


PLAN_1D = [
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
]

CASES = {
    "model": ["model", "--radius", "8mm", "--fill-volume", "2mL"],
    "simulate": ["simulate", "--law", "quintic", "--distance", "0.5m", "--duration", "1.5s"],
    "simulate-poses": [
        "simulate",
        "--pose-file",
        str(POSES),
        "--radius",
        "49mm",
        "--fill-height",
        "80mm",
        "--liquid",
        "water-20C",
        "--damping-ratio",
        "0.0066",
    ],
    "compare": ["compare", "--distance", "0.5m", "--peak-velocity", "0.5m/s"],
    "sweep": [
        "sweep",
        "--distance",
        "0.5m",
        "--fill-height",
        "20mm:40mm:3",
        "--duration",
        "1s:2s:3",
        "--laws",
        "quintic,septic",
        "--max-angle",
        "10deg",
    ],
    "calibrate": ["calibrate", str(DECAY), "--time-column", "0", "--signal-column", "1"],
    "plan-auto": PLAN_1D,
    "plan-optimal": [*PLAN_1D, "--method", "optimal"],
    "plan-optimal-smooth": [*PLAN_1D, "--method", "optimal", "--smooth"],
    "plan-fast": [*PLAN_1D, "--method", "fast"],
    "plan-shaped": [*PLAN_1D, "--method", "shaped"],
    "plan-septic": [*PLAN_1D, "--method", "septic"],
}


@pytest.mark.parametrize("name", list(CASES))
def test_every_json_command_prints_only_json_on_stdout(name, tmp_path):
    payload = run_json(CASES[name], tmp_path)
    if name.startswith("plan"):
        assert payload["duration_s"] > 0


def test_plan_then_export_prints_only_json(tmp_path):
    run_json([*PLAN_1D, "--out", "traj.csv"], tmp_path)
    payload = run_json(
        ["export", "traj.csv", "--format", "pose-csv", "--out", "traj.poses.csv"], tmp_path
    )
    assert (tmp_path / "traj.poses.csv").exists()
    assert payload


def test_a_c_level_write_during_the_work_does_not_reach_stdout(tmp_path):
    """A write to file descriptor 1 from C (buffered by C's stdio and flushed at exit) and one
    straight to the descriptor, both made while the command works, land on stderr."""
    code = (
        "import ctypes, os, sys\n"
        "import sloshkit.cli.options as options\n"
        "result = options.print_json\n"
        "def noisy(payload):\n"
        "    ctypes.CDLL(None).printf(b'C-LEVEL BANNER\\n')\n"
        "    os.write(1, b'FD-LEVEL BANNER\\n')\n"
        "    result(payload)\n"
        "options.print_json = noisy\n"
        "from sloshkit.cli import main\n"
        "sys.argv = ['sloshkit', 'model', '--json']\n"
        "main()\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300
    )
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    assert payload["modes"]
    assert "FD-LEVEL BANNER" in result.stderr
    assert "C-LEVEL BANNER" in result.stderr


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (["model", "--radius", "abc"], "error: --radius = 'abc' is invalid"),
        (["simulate", "--pose-file", "missing.csv"], "error: --pose-file = 'missing.csv'"),
        (["model", "--fill-height", "1m", "--wall-height", "10mm"], "error: --fill-height ="),
        (["export", "missing.csv", "--format", "urscript"], "error: PLAN_FILE = 'missing.csv'"),
    ],
)
def test_errors_name_the_option_as_written(args, named, tmp_path):
    result = subprocess.run(
        [*entry_point(), *args], cwd=tmp_path, capture_output=True, text=True, timeout=300
    )
    assert result.returncode == 2
    assert result.stderr.startswith(named), result.stderr
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr


def test_help_keeps_units_in_brackets(tmp_path):
    result = subprocess.run(
        [*entry_point(), "simulate", "--help"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "COLUMNS": "200"},
    )
    assert result.returncode == 0
    assert "(t [ms], x [mm])" in result.stdout
