"""Containers by name and by profile file, as users give them: the catalogue, the profile files
(CSV, TOML points and primitives), the request layer, scenario files and the command line (the
real entry point, stdout parsed as JSON)."""

from __future__ import annotations

import json
import math

import pytest
from conftest import run_entry_point

from sloshkit.errors import InputError
from sloshkit.io.profiles import read_profile_file
from sloshkit.io.requests import fill_height_request, profile_request
from sloshkit.io.scenario import parse_scenario
from sloshkit.model.catalogue import ISO8362_VIALS, catalogue_container, iso8362_profile
from sloshkit.model.profile import ProfileContainer


@pytest.mark.parametrize("size", list(ISO8362_VIALS))
def test_iso8362_brimful_volume_round_trip_against_the_catalogue(size):
    """The profile built from the table's dimensions holds the table's brimful volume within
    the table's tolerance, and volume -> height -> volume is exact."""
    vial = ISO8362_VIALS[size]
    profile = iso8362_profile(size)
    brimful = profile.brimful_volume_m3 * 1e6
    assert abs(brimful - vial.brimful_ml) <= vial.brimful_tolerance_ml
    height = profile.fill_height_for_volume(vial.brimful_ml * 1e-6 * 0.5)
    assert profile.volume_for_fill_height(height) == pytest.approx(vial.brimful_ml * 0.5e-6)
    assert profile.radius_m == pytest.approx((vial.d1_mm / 2 - vial.s1_mm) * 1e-3)


def test_catalogue_names_and_errors():
    assert catalogue_container("iso8362-2r").name == "iso8362-2R"
    with pytest.raises(InputError, match="iso8362-2R, iso8362-4R"):
        catalogue_container("iso9187-1mL")
    with pytest.raises(InputError, match="not both"):
        profile_request("iso8362-2R", "x.csv")


def test_profile_csv_in_millimetres(tmp_path):
    path = tmp_path / "bottle.csv"
    path.write_text("z [mm],r [mm]\n0,5\n1,6\n40,6\n48,3\n", encoding="utf-8")
    profile = read_profile_file(path)
    assert profile.name == "bottle"
    assert profile.z_m == pytest.approx((0.0, 0.001, 0.04, 0.048))
    assert profile.radius_at(0.02) == pytest.approx(0.006)
    height = fill_height_request(profile, None, "2 mL")
    assert profile.volume_for_fill_height(height) == pytest.approx(2e-6)


def test_profile_toml_points_and_primitives_agree(tmp_path):
    points = tmp_path / "points.toml"
    points.write_text('name = "tube"\nz_mm = [0, 30]\nr_mm = [7, 7]\n', encoding="utf-8")
    segments = tmp_path / "segments.toml"
    segments.write_text(
        '[[segment]]\nkind = "cylinder"\nradius = "7mm"\nheight = "30mm"\n', encoding="utf-8"
    )
    a, b = read_profile_file(points), read_profile_file(segments)
    assert a.name == "tube" and b.name == "segments"
    assert a.volume_for_fill_height(0.01) == pytest.approx(b.volume_for_fill_height(0.01))
    assert a.volume_for_fill_height(0.01) == pytest.approx(math.pi * 0.007**2 * 0.01)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("z [mm],r [mm]\n0,5\n0,6\n", "increase strictly"),
        ("z [mm],r [mm]\n0,5\n10,abc\n", "not numeric"),
        ("a,b,c\n0,1,2\n", "z \\[mm\\] and r \\[mm\\]"),
    ],
)
def test_profile_csv_errors_name_the_option(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError, match=message) as caught:
        read_profile_file(path)
    assert caught.value.parameter == "profile"


def test_profile_toml_errors(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[[segment]]\nkind = "pyramid"\nradius = "7mm"\nheight = "1mm"\n')
    with pytest.raises(InputError, match="cylinder, cone, sphere, neck"):
        read_profile_file(path)
    path.write_text('z_mm = [0, 1]\nr_mm = [1, 1]\ncolour = "red"\n')
    with pytest.raises(InputError, match="not a profile key"):
        read_profile_file(path)


def test_scenario_container_by_name():
    scenario = parse_scenario(
        {"analyses": ["model"], "container": {"name": "iso8362-6R"}, "fill": {"volume": "3mL"}}
    )
    assert isinstance(scenario.model.container, ProfileContainer)
    assert scenario.model.liquid_mass_kg == pytest.approx(
        3e-6 * scenario.model.liquid.density_kg_m3
    )
    with pytest.raises(InputError, match="exactly one of radius, name"):
        parse_scenario({"container": {"radius": "7mm", "name": "iso8362-2R"}})


def test_cli_model_of_the_real_2r_vial_with_its_heel():
    """The issue's command: the modes of the real vial (heel, profile) as one JSON object."""
    result = run_entry_point("model", "--container", "iso8362-2R", "--fill-volume", "1mL", "--json")
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    assert payload["container"] == "iso8362-2R"
    assert payload["liquid_volume_m3"] == pytest.approx(1e-6)
    assert payload["radius_m"] == pytest.approx(0.007)
    # The heel takes volume from the bottom corner: the fill is higher than in the plain tube.
    assert payload["fill_height_m"] > 1e-6 / (math.pi * 0.007**2)
    first = payload["modes"][0]
    # Bo = 6.7: the capillary correction (+22.8 %) is on by default, so omega^2 > g / L.
    assert payload["surface_tension_correction"] is True
    assert first["omega_rad_s"] ** 2 > 9.81 / first["length_m"]
    assert 9.0 < first["frequency_hz"] < 10.0
    assert any("Bond number" in text for text in payload["warnings"])
    plain = run_entry_point(
        "model",
        "--container",
        "iso8362-2R",
        "--fill-volume",
        "1mL",
        "--json",
        "--no-surface-tension-correction",
    )
    first = json.loads(plain.stdout)["modes"][0]
    assert first["length_m"] == pytest.approx(9.81 / first["omega_rad_s"] ** 2, rel=1e-9)
    assert 7.0 < first["frequency_hz"] < 8.5


def test_cli_profile_file_and_conflicts(tmp_path):
    path = tmp_path / "tube.csv"
    path.write_text("z [mm],r [mm]\n0,7\n30,7\n", encoding="utf-8")
    profile = run_entry_point("model", "--profile", str(path), "--fill-height", "10mm", "--json")
    cylinder = run_entry_point("model", "--radius", "7mm", "--fill-height", "10mm", "--json")
    assert profile.returncode == cylinder.returncode == 0, profile.stderr
    ours = json.loads(profile.stdout)["modes"][0]["omega_rad_s"]
    exact = json.loads(cylinder.stdout)["modes"][0]["omega_rad_s"]
    assert ours == pytest.approx(exact, rel=1e-4)
    both = run_entry_point("model", "--container", "iso8362-2R", "--radius", "8mm")
    assert both.returncode == 2 and both.stdout == ""
    assert both.stderr.strip().count("\n") == 0 and "--container" in both.stderr


def test_cli_cfd_refuses_a_profile_in_one_line(tmp_path):
    case = tmp_path / "case"
    result = run_entry_point("cfd", "run", "--container", "iso8362-2R", "--case", str(case))
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "upright cylinders only" in lines[0]
    assert not case.exists()
