"""One damping value per report, stated where it comes from; a scenario's model options reach
every section; the fit/logdec disagreement warns on the shipped CFD decay (issue 24)."""

from __future__ import annotations

import html
import json
import re
import tomllib
import warnings
from pathlib import Path

import pytest

from sloshkit.calibration import calibrate
from sloshkit.errors import ValidityWarning
from sloshkit.io.scenario import parse_scenario
from sloshkit.model.modal import equivalent_model
from sloshkit.report import motion_sections
from sloshkit.report.build import build_report
from sloshkit.report.cfd_reference import shipped_cfd_free_decay
from sloshkit.report.paper import paper_scenario

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _shipped_calibration():
    time_s, elevation_m, _ = shipped_cfd_free_decay()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return calibrate(time_s, elevation_m, source="sloshkit CFD free decay (shipped)")


def test_fit_logdec_disagreement_warns_on_the_shipped_cfd_decay():
    time_s, elevation_m, _ = shipped_cfd_free_decay()
    with pytest.warns(ValidityWarning, match="estimators disagree on zeta"):
        result = calibrate(time_s, elevation_m)
    fit, logdec = result.estimates["fit"], result.estimates["logdec"]
    assert fit.damping_ratio == pytest.approx(0.0069, abs=5e-5)
    assert logdec.damping_ratio == pytest.approx(0.0024, abs=5e-5)
    assert any("disagree on zeta" in text for text in result.to_dict()["warnings"])


def test_cfd_report_states_one_damping_and_its_source(tmp_path):
    """`reproduce --cfd`: the CFD calibration's zeta in the model table, the summary, the plan;
    the paper's 0.03 only where the paper's own inputs are shown (Table 3, Table 4)."""
    scenario = paper_scenario()
    calibration = _shipped_calibration()
    zeta = calibration.damping_ratio
    assert zeta is not None and abs(zeta - 0.03) > 0.02
    report = build_report(scenario, tmp_path / "report", cfd_calibration=calibration)
    tables = report.parent / "tables"
    model_rows = json.loads((tables / "model.json").read_text())
    assert [row["zeta"] for row in model_rows] == pytest.approx([zeta] * len(model_rows))
    text = html.unescape(report.read_text())
    summary = text[text.index('<section id="summary">') : text.index("</section>")]
    assert f"ζ = {zeta:.3g} from calibration: fit of" in re.sub(r"\s+", " ", summary)
    assert "ζ = 0.03" not in summary
    calibration_rows = json.loads((tables / "table4_calibration.json").read_text())
    theory = next(r for r in calibration_rows if r["estimator"] == "equivalent model (theory)")
    assert theory["zeta"] is None  # the scenario's 0.03 is not shown as a second model value
    # Later sections use the same model: the plan's verification is on the calibrated model.
    warnings_file = json.loads((report.parent / "warnings.json").read_text())
    assert any("disagree on zeta" in item["message"] for item in warnings_file)


def test_demo_report_carries_the_disagreement_in_its_calibration(tmp_path):
    report = build_report(paper_scenario(), tmp_path / "report")
    noted = json.loads((report.parent / "warnings.json").read_text())
    assert any(
        item["section"] == "Calibration" and "disagree on zeta" in item["message"] for item in noted
    )
    summary = html.unescape(report.read_text())
    assert "ζ = 0.03 from the paper's Table 3" in re.sub(r"\s+", " ", summary)


@pytest.mark.parametrize("correction", [True, False])
def test_scenario_capillary_correction_reaches_the_maps(monkeypatch, tmp_path, correction):
    """`run examples/vial-2ml.toml`: its surface_tension_correction (true there; false: turned
    off) holds at every fill height of the sweep, not only at the scenario's own."""
    document = tomllib.loads((EXAMPLES / "vial-2ml.toml").read_text(encoding="utf-8"))
    document["model"]["surface_tension_correction"] = correction
    document["analyses"] = ["model", "sweep"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        scenario = parse_scenario(document)
    assert scenario.model.surface_tension_correction is correction
    seen = {}
    original = motion_sections.run_sweep

    def spy(model_at, *args, **kwargs):
        seen["model_at"] = model_at
        return original(model_at, *args, **kwargs)

    monkeypatch.setattr(motion_sections, "run_sweep", spy)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        build_report(scenario, tmp_path / "report")
        other = seen["model_at"](0.015)
        expected = equivalent_model(
            scenario.model.container,
            scenario.model.liquid,
            0.015,
            damping_ratio=scenario.model.modes[0].damping_ratio,
            surface_tension=correction,
        )
    assert other.surface_tension_correction is correction
    assert other.modes[0].omega_rad_s == pytest.approx(expected.modes[0].omega_rad_s)
