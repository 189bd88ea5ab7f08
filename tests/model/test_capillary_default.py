"""The capillary (Bond-number) correction is applied by default where it changes omega_1 by
more than `CAPILLARY_THRESHOLD`, says so, and can be turned off (issue 24)."""

from __future__ import annotations

import json
import math
import warnings

import pytest
from conftest import run_entry_point

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import CAPILLARY_THRESHOLD, equivalent_model
from sloshkit.model.theory import bessel_roots, bond_number, surface_tension_factor
from sloshkit.plan.line.planner import plan
from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
from sloshkit.plan.line.verification import verify

SMALL = UprightCylinder(0.008)
WATER = get_liquid("water-25C")  # the how-do-i plan uses the default liquid
SMALL_FILL = SMALL.fill_height_for_volume(2e-6)
SMALL_MODEL = ("--radius", "8mm", "--fill-volume", "2mL")


def _model(container, liquid, fill, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = equivalent_model(container, liquid, fill, **options)
    return model, [str(w.message) for w in caught if issubclass(w.category, ValidityWarning)]


def test_small_vial_is_corrected_by_default_and_says_so():
    default, said = _model(SMALL, WATER, SMALL_FILL)
    plain, said_off = _model(SMALL, WATER, SMALL_FILL, surface_tension=False)
    forced, _ = _model(SMALL, WATER, SMALL_FILL, surface_tension=True)
    assert default.surface_tension_correction and not plain.surface_tension_correction
    ratio = default.modes[0].omega_rad_s / plain.modes[0].omega_rad_s
    assert ratio == pytest.approx(1.179, abs=1e-3)  # +17.9 %
    assert default.modes[0].omega_rad_s == forced.modes[0].omega_rad_s
    assert any("17.9 %" in text and "is applied" in text for text in said)
    assert any("17.9 %" in text and "correction is off" in text for text in said_off)
    assert "by default" in default.provenance["omega"]


def test_paper_vial_keeps_its_numbers():
    """Water in the 20.5 mm vial: the correction (+2.9 %) is below the threshold."""
    liquid = get_liquid("water-25C")
    bond = bond_number(liquid.density_kg_m3, 0.0205, liquid.surface_tension_n_m)
    factor = float(surface_tension_factor(bessel_roots(1), bond)[0])
    assert factor - 1 == pytest.approx(0.029, abs=5e-4) and factor - 1 < CAPILLARY_THRESHOLD
    model, said = _model(UprightCylinder(0.0205), liquid, 0.039)
    assert not model.surface_tension_correction and said == []
    assert model.modes[0].omega_rad_s == pytest.approx(29.66, abs=5e-3)


@pytest.mark.parametrize("radius_mm", [8.0, 12.0, 15.0, 16.0, 20.5, 49.0])
def test_applied_exactly_where_the_correction_exceeds_the_threshold(radius_mm):
    container = UprightCylinder(radius_mm * 1e-3)
    model, _ = _model(container, WATER, 2 * container.radius_m)
    bond = bond_number(WATER.density_kg_m3, container.radius_m, WATER.surface_tension_n_m)
    factor = float(surface_tension_factor(bessel_roots(1), bond)[0])
    assert model.surface_tension_correction == (factor - 1 > CAPILLARY_THRESHOLD)


def test_cli_default_correction_reaches_json_warnings_and_flags_override():
    payloads = {}
    for flag in ("", "--surface-tension-correction", "--no-surface-tension-correction"):
        proc = run_entry_point("model", *SMALL_MODEL, *((flag,) if flag else ()), "--json")
        assert proc.returncode == 0, proc.stderr
        payloads[flag] = json.loads(proc.stdout)
    omega = {flag: payload["modes"][0]["omega_rad_s"] for flag, payload in payloads.items()}
    assert omega[""] == pytest.approx(omega["--surface-tension-correction"])
    assert omega[""] / omega["--no-surface-tension-correction"] == pytest.approx(1.179, abs=1e-3)
    assert any("is applied" in text for text in payloads[""]["warnings"])
    assert any(
        "correction is off" in text
        for text in payloads["--no-surface-tension-correction"]["warnings"]
    )


def test_how_do_i_plan_is_safe_by_default():
    """docs/how-do-i.md's plan for the 2 mL vial: planned with the correction (the default) it
    meets its limits on the corrected model; planned without it, the corrected model is left
    swinging at about 10x the residual limit."""
    corrected, _ = _model(SMALL, WATER, SMALL_FILL)
    plain, _ = _model(SMALL, WATER, SMALL_FILL, surface_tension=False)
    limits = SloshLimits(math.radians(5.0), math.radians(0.25))

    def problem(model):
        return PlanProblem(0.15, MachineLimits(1.5, 20.0, 500.0), limits, model, 4e-3)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        safe = plan(problem(corrected), "optimal")
        unsafe = plan(problem(plain), "optimal", smooth=False)
    assert safe.chosen is not None and unsafe.chosen is not None
    assert verify(safe.chosen.motion, problem(corrected)).feasible
    left = verify(unsafe.chosen.motion, problem(corrected)).residual_angle_rad
    assert left > 5 * limits.max_residual_rad
