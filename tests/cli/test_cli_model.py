"""`sloshkit model`: the issue's JSON contract, units, and clean errors."""

from __future__ import annotations

import json

import pytest
from conftest import run_entry_point
from typer.testing import CliRunner

from sloshkit.cli import app

runner = CliRunner()


def run(*args: str):
    return runner.invoke(app, list(args))


def test_model_json_reproduces_the_paper_vial():
    result = run(
        "model", "--radius", "20.5mm", "--fill-height", "39mm", "--liquid", "water-25C", "--json"
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    first = payload["modes"][0]
    assert round(first["omega_rad_s"], 1) == 29.7
    assert round(first["length_m"], 3) == 0.011
    assert len(payload["modes"]) == 3
    for key in ("liquid_mass_kg", "rigid_mass_kg"):
        assert payload[key] > 0
    for key in (
        "n",
        "omega_rad_s",
        "frequency_hz",
        "slosh_mass_kg",
        "length_m",
        "pivot_height_m",
        "bob_height_m",
        "stiffness_n_m",
        "damping_ratio",
        "damping_coefficient_n_s_m",
    ):
        assert key in first


def test_model_options():
    result = run(
        "model",
        "--radius",
        "8 mm",
        "--fill-volume",
        "2 mL",
        "--modes",
        "5",
        "--damping-law",
        "stephens",
        "--surface-tension-correction",
        "--json",
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert payload["fill_height_m"] == pytest.approx(2e-6 / (3.141592653589793 * 0.008**2))
    assert len(payload["modes"]) == 5
    assert payload["damping_law"] == "stephens"
    assert payload["surface_tension_correction"] is True


def test_damping_ratio_option():
    payload = json.loads(run("model", "--damping-ratio", "0.03", "--json").stdout)
    assert payload["modes"][0]["damping_ratio"] == 0.03


def test_table_output_has_units():
    result = run("model")
    assert result.exit_code == 0
    assert "[rad/s]" in result.stdout and "29.66" in result.stdout


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--radius", "-3mm"], "radius"),
        (["--radius", "0"], "radius"),
        (["--radius", "nan"], "radius"),
        (["--radius", "3 furlongs/s"], "radius"),
        (["--radius", "abc"], "radius"),
        (["--fill-height", "50mm", "--wall-height", "40mm"], "--fill-height"),
        (["--liquid", "mercury"], "liquid"),
        (["--damping-law", "magic"], "--damping-law"),
    ],
)
def test_bad_input_is_one_line_and_exit_code_2(args, needle):
    """Run the real entry point: one line on stderr, exit code 2, no traceback."""
    proc = run_entry_point("model", *args)
    assert proc.returncode == 2
    assert needle in proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().startswith("error:")


def test_validity_warning_is_printed_not_raised():
    proc = run_entry_point("model", "--radius", "20mm", "--fill-height", "2mm")
    assert proc.returncode == 0
    assert "warning:" in proc.stderr and "shallow" in proc.stderr
