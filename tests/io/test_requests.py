"""The request layer (sloshkit.io.requests): the CLI and scenario files read the same way."""

from __future__ import annotations

import copy

import pytest

from sloshkit.errors import InputError
from sloshkit.io.requests import (
    container_request,
    fill_height_request,
    fraction_request,
    liquid_request,
    model_request,
)
from sloshkit.io.scenario import PAPER_SCENARIO, parse_scenario
from sloshkit.model.liquids import get_liquid


def test_scenario_and_cli_build_the_same_model():
    scenario = parse_scenario(PAPER_SCENARIO)
    container = container_request("20.5mm")
    direct = model_request(
        container,
        liquid_request("water-25C"),
        fill_height_request(container, "39mm", None),
        damping_law=scenario.raw.get("model", {}).get("damping_law", "seed"),
        damping_ratio=scenario.raw.get("model", {}).get("damping_ratio"),
    )
    assert [m.omega_rad_s for m in direct.modes] == [m.omega_rad_s for m in scenario.model.modes]
    assert direct.modes[0].damping_ratio == scenario.model.modes[0].damping_ratio


@pytest.mark.parametrize("robust", ["ten%", "abc", "%"])
def test_scenario_robustness_that_is_not_a_number_is_an_input_error(robust):
    document = copy.deepcopy(PAPER_SCENARIO)
    document.setdefault("limits", {})["robust"] = robust
    with pytest.raises(InputError, match="robust"):
        parse_scenario(document)


def test_fractions_and_percentages():
    assert fraction_request("10%", "robust") == pytest.approx(0.1)
    assert fraction_request(" 0.25 ", "robust") == 0.25
    assert fraction_request(0.05, "robust") == 0.05


def test_liquid_overrides_keep_the_preset_and_say_so():
    base = get_liquid("water-25C")
    liquid = liquid_request("water-25C", viscosity="2 mPa*s", note="overridden in the scenario")
    assert liquid.density_kg_m3 == base.density_kg_m3
    assert liquid.viscosity_pa_s == pytest.approx(2e-3)
    assert liquid.source.endswith("(overridden in the scenario)")
    assert liquid_request("water-25C") is base


def test_fill_height_from_volume_and_the_conflicts():
    container = container_request("20mm", wall_height="60mm")
    assert fill_height_request(container, None, "2 mL") == pytest.approx(2e-6 / (3.14159265 * 4e-4))
    with pytest.raises(InputError, match="exactly one"):
        fill_height_request(container, "10mm", "2 mL")
    with pytest.raises(InputError, match="exactly one"):
        fill_height_request(container, None, None, default=None)
    assert fill_height_request(container, None, None) == pytest.approx(0.039)
