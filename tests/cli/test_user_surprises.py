"""What a user sees (issue 17): units in file headers, warnings in --json, tables at 80
columns, --version, conflicting or implausible options, sweeps without limits."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from typer.testing import CliRunner

from sloshkit.cli import app
from sloshkit.errors import ValidityWarning
from sloshkit.io.motions import read_motion_file
from sloshkit.io.tables import base_name, unit_from_name

runner = CliRunner()


def _quintic_rows(scale_t: float, scale_x: float) -> str:
    t = np.linspace(0.0, 0.4, 81)
    tau = t / 0.4
    x = 0.02 * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
    return "\n".join(f"{a * scale_t:.9g},{b * scale_x:.9g}" for a, b in zip(t, x, strict=True))


@pytest.mark.parametrize(
    ("header", "scale_t", "scale_x"),
    [("t,x", 1.0, 1.0), ("t [ms],x [mm]", 1e3, 1e3), ("t_ms,position_mm", 1e3, 1e3)],
)
def test_motion_file_honours_units_in_its_header(tmp_path, header, scale_t, scale_x):
    path = tmp_path / "move.csv"
    path.write_text(header + "\n" + _quintic_rows(scale_t, scale_x) + "\n")
    motion = read_motion_file(path)
    assert motion.duration_s == pytest.approx(0.4)
    assert motion.distance_m == pytest.approx(0.02)


def test_unit_free_millisecond_file_warns_and_the_warning_reaches_json(tmp_path):
    path = tmp_path / "move.csv"
    path.write_text("t,x\n" + _quintic_rows(1e3, 1e3) + "\n")
    with pytest.warns(ValidityWarning, match=r"lasts 400 s.*t \[ms\]"):
        read_motion_file(path)
    result = runner.invoke(
        app,
        ["simulate", "--law", f"file:{path}", "--sample-period", "20ms", "--json"],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert any("implausible for a container" in text for text in payload["warnings"])


def test_unit_names():
    assert unit_from_name("a [m/s^2]") == "m/s^2"
    assert unit_from_name("time_s") == "s"
    assert base_name("Time [s]") == "time" and base_name("x_mm") == "x"


def test_version():
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0
    assert re.fullmatch(r"sloshkit \d+\.\d+\.\d+\S*\n", result.stdout)


def test_json_carries_a_warnings_list():
    payload = json.loads(runner.invoke(app, ["model", "--json"]).stdout)
    assert payload["warnings"] == []
    payload = json.loads(runner.invoke(app, ["model", "--radius", "20.5", "--json"]).stdout)
    assert any("no unit" in text and "20.5 m" in text for text in payload["warnings"])


def test_model_file_with_model_options_is_refused(tmp_path):
    model_file = tmp_path / "model.toml"
    assert runner.invoke(app, ["model", "--json"]).exit_code == 0
    from sloshkit.io.models import write_model_file
    from sloshkit.model.geometry import UprightCylinder
    from sloshkit.model.liquids import get_liquid
    from sloshkit.model.modal import equivalent_model

    write_model_file(
        model_file, equivalent_model(UprightCylinder(0.01), get_liquid("water-25C"), 0.02)
    )
    result = runner.invoke(app, ["model", "--model-file", str(model_file), "--radius", "3mm"])
    assert result.exit_code != 0
    assert "--radius" in str(result.exception) or "--radius" in result.output
    ok = runner.invoke(app, ["model", "--model-file", str(model_file), "--json"])
    assert json.loads(ok.stdout)["radius_m"] == pytest.approx(0.01)


@pytest.mark.parametrize(
    "args",
    [
        ["model"],
        ["simulate", "--duration", "1s", "--sample-period", "5ms"],
        ["compare", "--sample-period", "5ms"],
    ],
)
def test_tables_fit_80_columns_with_units(args, monkeypatch):
    import sys

    monkeypatch.setattr(sys.modules["sloshkit.cli.app"].stdout, "width", 80)
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert max(len(line) for line in lines) <= 80
    assert "…" not in result.stdout
    assert "_s " not in result.stdout and "_deg" not in result.stdout  # no raw JSON keys
    assert "[s]" in result.stdout or "[rad/s]" in result.stdout


def test_sweep_without_limits_says_so():
    result = runner.invoke(
        app,
        ["sweep", "--fill-height", "39mm", "--duration", "1s:2s:3", "--laws", "quintic", "--json"],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert any("no limits given" in text for text in payload["warnings"])


def test_run_without_out_writes_to_the_working_folder(tmp_path, monkeypatch):
    import sys
    from pathlib import Path

    module = sys.modules["sloshkit.cli.report"]
    seen = []
    monkeypatch.setattr(module, "_run_report", lambda scenario, out, *rest: seen.append(out))
    monkeypatch.chdir(tmp_path)
    example = Path(__file__).resolve().parents[2] / "examples" / "vial-2ml.toml"
    result = runner.invoke(app, ["run", str(example)])
    assert result.exit_code == 0, result.output
    assert seen and seen[0].resolve().parent == tmp_path.resolve()
    assert seen[0].name == "vial-2ml-report"


def test_calibration_record_in_unlabelled_milliseconds_warns(tmp_path):
    t = np.arange(0.0, 4.0, 0.002)
    eta = 1e-3 * np.exp(-0.03 * 29.66 * t) * np.cos(29.66 * t)
    path = tmp_path / "decay.csv"
    path.write_text(
        "t,eta\n" + "\n".join(f"{1e3 * a:.6g},{b:.6e}" for a, b in zip(t, eta, strict=True))
    )
    result = runner.invoke(
        app, ["calibrate", str(path), "--time-column", "t", "--signal-column", "eta", "--json"]
    )
    payload = json.loads(result.stdout)
    assert any("--time-unit ms" in text for text in payload["warnings"])
    path.write_text(
        "t [ms],eta\n" + "\n".join(f"{1e3 * a:.6g},{b:.6e}" for a, b in zip(t, eta, strict=True))
    )
    result = runner.invoke(
        app, ["calibrate", str(path), "--time-column", "t [ms]", "--signal-column", "eta", "--json"]
    )
    payload = json.loads(result.stdout)
    assert payload["frequency_hz"] == pytest.approx(29.66 / (2 * np.pi), rel=0.01)
    assert not any("--time-unit ms" in text for text in payload["warnings"])
