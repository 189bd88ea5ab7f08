"""A CFD campaign on a local Dask cluster from the CLI (tiny meshes): one table and a
calibration-versus-fill model; interrupted, it resumes without redoing finished cases; the
cluster listens on loopback only."""

from __future__ import annotations

import json
import shutil
import signal
import subprocess
import time

import pytest
from conftest import run_entry_point
from test_cfd_hardening import ENTRY, _exposed_sockets, _process_tree

from sloshkit.cfd.campaign import fill_model

pytestmark = pytest.mark.skipif(
    shutil.which("interFoam") is None, reason="OpenFOAM is not installed (make test installs it)"
)
ARGS = [
    "cfd",
    "sweep",
    "--fills",
    "30mm,39mm,50mm",
    "--meshes",
    "4",
    "--end-time",
    "1s",
    "--delta-t",
    "2ms",
    "--tilt",
    "4deg",
    "--workers",
    "2",
]


def test_campaign_resumes_after_an_interruption_and_gathers_a_fill_model(tmp_path):
    out = tmp_path / "campaign"
    process = subprocess.Popen(
        [*ENTRY, *ARGS, "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    exposed: list[str] = []
    try:
        while process.poll() is None and len(list(out.glob("*/sloshkit-result.json"))) < 1:
            for pid in _process_tree(process.pid):
                exposed += _exposed_sockets(pid)
            time.sleep(0.2)
        process.send_signal(signal.SIGTERM)
    finally:
        process.communicate(timeout=120)
    assert exposed == []
    finished = {p.parent.name for p in out.glob("*/sloshkit-result.json")}
    assert 1 <= len(finished) <= 3
    stamps = {name: (out / name / "sloshkit-result.json").stat().st_mtime for name in finished}
    result = run_entry_point(*ARGS, "--out", str(out), "--json")
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    assert payload["skipped"] == len(finished)
    for name in finished:  # finished cases were not run again
        assert (out / name / "sloshkit-result.json").stat().st_mtime == stamps[name]
    rows = payload["rows"]
    assert [row["status"] for row in rows] == ["completed"] * 3
    # Linear theory: the frequency rises with the fill towards its deep-liquid limit.
    theory = [row["theory_frequency_hz"] for row in rows]
    assert theory == sorted(theory)
    for row in rows:
        assert row["frequency_ratio"] == pytest.approx(1.0, abs=0.1)
    group = payload["model"]["groups"][0]
    assert group["cases"] == 3 and "slope_per_fill_over_radius" in group["frequency_ratio"]
    assert (out / "results.csv").read_text().startswith("case,status,liquid,fill_height_m")


def test_fill_model_is_the_least_squares_line():
    rows = [
        {
            "status": "completed",
            "liquid": "water",
            "cells_per_radius": 4,
            "fill_height_m": h,
            "radius_m": 0.02,
            "frequency_ratio": 1.0 + 0.01 * h / 0.02,
            "damping_ratio": None,
        }
        for h in (0.01, 0.02, 0.04)
    ]
    group = fill_model(rows)["groups"][0]
    assert group["frequency_ratio"]["slope_per_fill_over_radius"] == pytest.approx(0.01)
    assert group["frequency_ratio"]["intercept"] == pytest.approx(1.0)
    assert "damping_ratio" not in group
