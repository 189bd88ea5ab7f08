"""Scenario files, `sloshkit run` and `sloshkit reproduce`: examples run, errors are clear,
outputs are atomic."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import run_entry_point
from typer.testing import CliRunner

from sloshkit.cli import app
from sloshkit.errors import InputError
from sloshkit.io.scenario import PAPER_SCENARIO, parse_scenario, read_scenario
from sloshkit.report.build import build_report

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("name", ["vial-2ml.toml", "bottle-100ml.toml"])
def test_example_scenarios_run(tmp_path, name):
    result = CliRunner().invoke(
        app, ["run", str(EXAMPLES / name), "--out", str(tmp_path / "r"), "--json"]
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    report = Path(payload["report"])
    assert report.is_file() and report.stat().st_size > 50_000
    plan = json.loads((tmp_path / "r" / "tables" / "plan.json").read_text())
    assert any(row["verified"] == "yes" for row in plan)
    compare = json.loads((tmp_path / "r" / "tables" / "compare.json").read_text())
    assert compare[0]["law"] == "trapezoidal"
    assert compare[0]["peak jerk [m/s³]"] is None  # unbounded: null, not Infinity
    text = report.read_text()
    assert '<section id="summary">' in text and '<nav id="contents"' in text
    if name == "vial-2ml.toml":  # a 2 mL vial sloshes beyond linear theory in the fast laws
        assert 'class="warning"' in text and "beyond small-amplitude theory" in text
        assert any("beyond small-amplitude theory" in text for text in payload["warnings"])


def test_paper_example_matches_the_built_in_scenario():
    from_file = read_scenario(EXAMPLES / "paper-vial.toml")
    built_in = parse_scenario(PAPER_SCENARIO)
    assert from_file.model.modes[0].omega_rad_s == built_in.model.modes[0].omega_rad_s
    assert from_file.plan_limits == built_in.plan_limits
    assert from_file.paper_comparison


@pytest.mark.parametrize(
    ("mutate", "needle"),
    [
        (lambda d: d.update(colour="blue"), "colour"),
        (lambda d: d["container"].update(radious="2cm"), "radious"),
        (lambda d: d.update(pump={}), "pump"),
        (lambda d: d["fill"].update(volume="2mL"), "exactly one"),
        (lambda d: d["limits"].pop("vmax"), "vmax"),
        (lambda d: d.update(analyses=["model", "dance"]), "dance"),
        (lambda d: d["container"].update(radius="-1mm"), "radius"),
    ],
)
def test_scenario_errors_name_the_problem(mutate, needle):
    document = json.loads(json.dumps(PAPER_SCENARIO))
    mutate(document)
    with pytest.raises(InputError, match=needle):
        parse_scenario(document)


def test_run_cli_bad_file_exits_2(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[container]\nradius = 'abc'\n")
    proc = run_entry_point("run", str(path))
    assert proc.returncode == 2
    assert "radius" in proc.stderr and "Traceback" not in proc.stderr


def test_failed_report_leaves_nothing_half_written(tmp_path, monkeypatch):
    import sloshkit.report.motion_sections as sections

    def explode(*args, **kwargs):
        raise RuntimeError("simulated failure in the middle of the report")

    monkeypatch.setattr(sections, "_plan_section", explode)  # the last section
    scenario = parse_scenario(PAPER_SCENARIO)
    with pytest.raises(RuntimeError):
        build_report(scenario, tmp_path / "out")
    assert not (tmp_path / "out").exists()
    assert list(tmp_path.iterdir()) == []


def test_every_command_help_shows_examples():
    runner = CliRunner()
    for command in (
        "model",
        "simulate",
        "compare",
        "sweep",
        "calibrate",
        "plan",
        "reproduce",
        "run",
    ):
        result = runner.invoke(app, [command, "--help"])
        assert result.exit_code == 0
        assert "Example" in result.stdout, command
