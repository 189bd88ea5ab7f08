"""The numbers the README quotes are recomputed here: a change in the code that moves them makes
this test fail until the README is updated (issue 17)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from sloshkit.cli import app

README = Path(__file__).resolve().parents[1] / "README.md"
runner = CliRunner()


def _json(*args: str) -> dict:
    result = runner.invoke(app, [*args, "--json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def _close(printed: str, value: float) -> bool:
    """``value`` rounds to the printed number (to its last printed digit)."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return abs(float(printed) - value) <= 0.5 * 10.0**-decimals + 1e-12


def test_readme_compare_table_matches_the_code():
    text = README.read_text(encoding="utf-8")
    rows = re.findall(
        r"^\| (trapezoidal|cubic|quintic|septic)[^|]* \| ([\d.]+)° \| ([\d.]+)° \| ([\d.]+) mm \|$",
        text,
        flags=re.MULTILINE,
    )
    assert len(rows) == 4, "the README's compare table changed shape"
    payload = _json(
        "compare", "--distance", "0.5m", "--peak-velocity", "0.5m/s", "--damping-ratio", "0.03"
    )
    computed = {row["law"]: row for row in payload["laws"]}
    drift = []
    for law, peak, residual, wall in rows:
        row = computed[law]
        for printed, value, what in (
            (peak, row["peak_angle_deg"], "peak θ₁ [°]"),
            (residual, row["residual_angle_deg"], "residual θ₁ [°]"),
            (wall, 1e3 * row["peak_wall_elevation_m"], "peak wall η [mm]"),
        ):
            if not _close(printed, value):
                drift.append(f"{law} {what}: README {printed}, code {value:.4g}")
    ratio = re.search(r"The trapezoid leaves ([\d.]+) times the residual", text)
    assert ratio is not None
    value = computed["trapezoidal"]["residual_angle_deg"] / computed["septic"]["residual_angle_deg"]
    if not _close(ratio.group(1), value):
        drift.append(f"trapezoid/septic residual ratio: README {ratio.group(1)}, code {value:.3g}")
    assert drift == []


def test_readme_model_figures_match_the_code():
    text = README.read_text(encoding="utf-8")
    quoted = re.search(
        r"ω₁ = ([\d.]+) rad/s \(paper 29.7\), f₁ = ([\d.]+) Hz,\s+L₁ = ([\d.]+) mm"
        r".*?m₁ = ([\d.]+) g with ρ = 1000 kg/m³",
        text,
        flags=re.DOTALL,
    )
    assert quoted is not None, "the README's model sentence changed shape"
    payload = _json("model", "--density", "1000kg/m^3")
    first = payload["modes"][0]
    omega, frequency, length, mass = quoted.groups()
    assert _close(omega, first["omega_rad_s"])
    assert _close(frequency, first["frequency_hz"])
    assert _close(length, 1e3 * first["length_m"])
    assert _close(mass, 1e3 * first["slosh_mass_kg"])


def test_readme_says_how_to_activate_the_venv():
    text = README.read_text(encoding="utf-8")
    assert "source .venv/bin/activate" in text


@pytest.mark.parametrize("command", ["sloshkit --version"])
def test_readme_commands_exist(command):
    assert command in README.read_text(encoding="utf-8")


def test_docs_validation_table_matches_the_code():
    """The sloshkit column of docs/validation.md's model table."""
    import dataclasses

    from sloshkit.model.geometry import UprightCylinder
    from sloshkit.model.liquids import get_liquid
    from sloshkit.model.modal import equivalent_model

    text = (README.parent / "docs" / "validation.md").read_text(encoding="utf-8")

    def cell(quantity: str) -> str:
        row = re.search(rf"^\| {re.escape(quantity)} \|[^|]*\| ([^|]+) \|", text, re.MULTILINE)
        assert row is not None, f"docs/validation.md lost its {quantity} row"
        return row.group(1).strip()

    water = get_liquid("water-25C")
    vial = UprightCylinder(0.0205)
    paper = equivalent_model(
        vial, dataclasses.replace(water, density_kg_m3=1000.0), 0.039, damping_ratio=0.03
    )
    first = paper.modes[0]
    checks = [
        (cell("ω₁").split()[0], first.omega_rad_s),
        (cell("f₁").split()[0], first.frequency_hz),
        (cell("L₁").split()[0], first.length_m),
        (cell("m₁ (ρ = 1000)").split()[0], first.slosh_mass_kg),
        (cell("k₁").split()[0], first.stiffness_n_m),
        (cell("c₁ (ζ = 0.03)").split()[0], first.damping_coefficient_n_s_m),
        (
            cell('"hinge location"').split()[1].replace("−", "-"),
            first.bob_height_m - paper.cg_height_m,
        ),
        (cell("ζ").split()[0], equivalent_model(vial, water, 0.039).modes[0].damping_ratio),
    ]
    drift = [f"{printed} vs {value:.5g}" for printed, value in checks if not _close(printed, value)]
    assert drift == []
