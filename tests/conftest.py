"""Shared fixtures: the seed paper's vial, the measured robot series' cylinder."""

from __future__ import annotations

import dataclasses
import os
import subprocess
import sys

import pytest
from hypothesis import settings

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model

# CI replays the same examples every run (a red build is then reproducible); locally hypothesis
# explores new ones.
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The tests marked ``slow`` (each half a minute or more) first: pytest-xdist's workers
    take tests in collection order, and a long one collected last keeps one worker running
    alone at the end."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


SEED_RADIUS_M = 0.0205  # De Simone et al. (2024) Table 3
SEED_FILL_HEIGHT_M = 0.039


def seed_vial() -> SloshModel:
    """The paper's vial with water at 25 °C (Table 1 density 997 kg/m^3), 3 modes."""
    return equivalent_model(
        UprightCylinder(SEED_RADIUS_M), get_liquid("water-25C"), SEED_FILL_HEIGHT_M
    )


def seed_vial_table3() -> SloshModel:
    """The paper's vial as in its Table 3: rho = 1000 kg/m^3, damping ratio 0.03."""
    water = dataclasses.replace(get_liquid("water-25C"), density_kg_m3=1000.0)
    return equivalent_model(
        UprightCylinder(SEED_RADIUS_M), water, SEED_FILL_HEIGHT_M, damping_ratio=0.03
    )


@pytest.fixture
def seed_model() -> SloshModel:
    return seed_vial()


@pytest.fixture
def seed_model_table3() -> SloshModel:
    return seed_vial_table3()


@pytest.fixture(scope="module")
def robot_vial() -> SloshModel:
    """The measured robot series' cylinder (tests/data/measured-3d): R = 49 mm, h = 80 mm,
    water, zeta = 0.0066."""
    return equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )


def run_entry_point(*args: str) -> subprocess.CompletedProcess[str]:
    """Run the real `sloshkit` entry point (as the installed command does) and capture it."""
    return subprocess.run(
        [sys.executable, "-c", "from sloshkit.cli import main; main()", *args],
        capture_output=True,
        text=True,
        check=False,
    )
