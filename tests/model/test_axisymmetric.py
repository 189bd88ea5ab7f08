"""Sloshing modes of axisymmetric containers by finite elements, each against a published or
exact value: the upright cylinder's closed form (Abramson 1966, <= 0.1 %), the 45-degree cone
standing on its vertex (exact: omega^2 h / g = 1), the half-full sphere (McIver 1989:
omega^2 R / g = 1.5601, <= 1 %), and the convergence with the mesh."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sloshkit.errors import InputError, ValidityWarning
from sloshkit.model.axisymmetric import axisymmetric_modes
from sloshkit.model.document import model_from_document, model_to_document
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model, model_family
from sloshkit.model.profile import (
    ProfileContainer,
    ProfileSegment,
    cone_profile,
    cylinder_profile,
    profile_from_segments,
    sphere_profile,
)
from sloshkit.model.theory import (
    bessel_roots,
    bob_offset_from_cg,
    natural_frequency,
    slosh_mass_ratio,
    wall_elevation_factor,
)

WATER = get_liquid("water-25C")


def closed_form(radius: float, height: float, count: int = 3) -> dict[str, np.ndarray]:
    """The cylinder's per-unit-density modal quantities (Abramson 1966 §6.2, Dodge 2000 §3)."""
    xi = bessel_roots(count)
    return {
        "eigenvalue": natural_frequency(radius, height, xi, 1.0) ** 2,
        "mass": slosh_mass_ratio(radius, height, xi) * math.pi * radius**2 * height,
        "bob": height / 2 + bob_offset_from_cg(radius, height, xi),
        "wall": wall_elevation_factor(radius, xi),
    }


def relative_errors(radius: float, height: float, radial_cells: int | None = None) -> np.ndarray:
    modes = axisymmetric_modes(
        cylinder_profile(radius, 5 * height), height, 3, radial_cells=radial_cells
    )
    exact = closed_form(radius, height)
    found = (
        modes.eigenvalues_1_m,
        modes.mass_per_density_m3,
        modes.bob_height_m,
        modes.wall_elevation_factor_m,
    )
    return np.array(
        [np.abs(np.array(f) / exact[k] - 1.0) for f, k in zip(found, exact, strict=True)]
    )


@pytest.mark.parametrize("depth_ratio", [0.3, 1.0, 1.9024, 4.0])
def test_abramson1966_cylinder_closed_form_within_0_1_percent(depth_ratio):
    """Frequencies, slosh masses, bob heights and wall factors of the first three modes."""
    radius = 0.0205
    errors = relative_errors(radius, depth_ratio * radius)
    assert errors.max() <= 1e-3, errors
    # The first mode, which carries 98 % of the slosh moment, is far better than that.
    assert errors[:, 0].max() <= 2e-5, errors[:, 0]


def test_cylinder_model_from_the_profile_matches_the_closed_form_model(seed_model):
    profile_model = equivalent_model(cylinder_profile(0.0205, 0.08), WATER, 0.039)
    assert profile_model.liquid_mass_kg == pytest.approx(seed_model.liquid_mass_kg, rel=1e-12)
    assert profile_model.cg_height_m == pytest.approx(seed_model.cg_height_m, rel=1e-12)
    assert profile_model.radius_m == pytest.approx(seed_model.radius_m, rel=1e-12)
    for mode, exact in zip(profile_model.modes, seed_model.modes, strict=True):
        for name in ("omega_rad_s", "slosh_mass_kg", "length_m", "pivot_height_m"):
            assert getattr(mode, name) == pytest.approx(getattr(exact, name), rel=1e-3), name
        assert mode.damping_ratio == pytest.approx(exact.damping_ratio, rel=1e-4)
    assert profile_model.rigid_mass_kg > 0


def test_cone_45_degrees_vertex_down_is_exact():
    """phi = x z solves the cone problem with omega^2 h / g = 1 (harmonic; d phi/dn ~ z - r = 0
    on the wall z = r; d phi/dz = x = phi / h on the surface): quadratic elements hold it to
    round-off, on any mesh."""
    for cells in (4, 12):
        modes = axisymmetric_modes(cone_profile(0.03, 0.03), 0.012, 2, radial_cells=cells)
        assert modes.eigenvalues_1_m[0] * 0.012 == pytest.approx(1.0, abs=1e-9)
    # The same exact mode gives the pendulum in closed form (C = pi h^5/4, N = pi h^6/4,
    # D = 3 pi h^5/20): m_1 = 3/4 of the liquid, bob at 3h/5, L_1 = h.
    height = 0.012
    volume = math.pi * height**3 / 3
    modes = axisymmetric_modes(cone_profile(0.03, 0.03), height, 1)
    assert modes.mass_per_density_m3[0] == pytest.approx(0.75 * volume, rel=1e-9)
    assert modes.bob_height_m[0] == pytest.approx(0.6 * height, rel=1e-9)


@pytest.mark.parametrize(
    ("container", "height"),
    [
        (sphere_profile(0.01), 0.01),
        (sphere_profile(0.01), 0.004),
        (cone_profile(0.02, 0.01), 0.008),
        (cylinder_profile(0.007, 0.03, 0.0005), 0.0065),
        (
            profile_from_segments(
                [
                    ProfileSegment("cylinder", 0.007, 0.02, heel_radius_m=0.0005),
                    ProfileSegment("neck", 0.0035, 0.008, shoulder_height_m=0.005),
                ]
            ),
            0.023,
        ),
    ],
)
def test_quasi_static_sum_rule_holds_for_any_profile(container, height):
    """A steady lateral acceleration a tilts the free surface by a/g and shifts the liquid's
    centre of mass by (a/g) I_S / V, I_S = pi R_s^4 / 4 (the waterplane's second moment); the
    pendulums, all hanging along the apparent gravity, shift it by sum m_n L_n (a/g) / m_F. So
    sum_n m_n L_n = rho pi R_s^4 / 4 for any container (the waterplane's second moment of ship
    hydrostatics; for the cylinder Abramson 1966's m_F R^2 / (4h)); ten modes close it to 1e-3."""
    modes = axisymmetric_modes(container, height, 10, radial_cells=32)
    moment = sum(
        m / lam for m, lam in zip(modes.mass_per_density_m3, modes.eigenvalues_1_m, strict=True)
    )
    assert moment == pytest.approx(math.pi * modes.surface_radius_m**4 / 4, rel=1e-3)
    # The same tilt raises the wall by R_s tan(psi): the wall factors sum to R_s over all modes
    # (the 3-D model's planar mapping adds the rest); ten modes carry 93-100 % of it.
    wall = sum(modes.wall_elevation_factor_m) / modes.surface_radius_m
    assert 0.9 < wall < 1.0 + 1e-3
    assert np.all(np.diff(modes.eigenvalues_1_m) > 0)
    assert np.all(np.array(modes.mass_per_density_m3) > 0)


def test_mciver1989_half_full_sphere_first_mode():
    """McIver (1989) and Budiansky (1960): omega_1^2 R / g = 1.5601 for the half-full sphere."""
    radius = 0.01
    modes = axisymmetric_modes(sphere_profile(radius), radius, 1)
    value = modes.eigenvalues_1_m[0] * radius
    assert value == pytest.approx(1.5601, rel=1e-2)  # the contract
    assert value == pytest.approx(1.5601, rel=1e-4)  # what the solver achieves


def test_convergence_with_the_mesh_is_of_fourth_order_for_the_eigenvalues():
    """P2 elements: eigenvalue errors fall as h^4 (halving the cells: about 16 times)."""
    errors = [relative_errors(0.0205, 0.039, cells)[0, 1] for cells in (8, 16, 32)]
    assert errors[0] > errors[1] > errors[2]
    assert errors[0] / errors[1] > 8 and errors[1] / errors[2] > 8, errors


def test_heel_raises_the_fill_height_and_vanishes_with_its_radius():
    volume = 1e-6
    plain = cylinder_profile(0.007, 0.03)
    heeled = cylinder_profile(0.007, 0.03, 0.001)
    assert heeled.fill_height_for_volume(volume) > plain.fill_height_for_volume(volume)
    corner = (1 - math.pi / 4) * 0.001**2  # the heel's missing area in the meridian section
    # Pappus: the ring's volume is that area times 2 pi times its centroid's radius (~R).
    missing = plain.volume_for_fill_height(0.005) - heeled.volume_for_fill_height(0.005)
    assert missing == pytest.approx(corner * 2 * math.pi * 0.0068, rel=0.02)
    tiny = cylinder_profile(0.007, 0.03, 1e-6)
    f_tiny = axisymmetric_modes(tiny, 0.006, 1).eigenvalues_1_m[0]
    f_plain = axisymmetric_modes(plain, 0.006, 1).eigenvalues_1_m[0]
    assert f_tiny == pytest.approx(f_plain, rel=1e-6)


@settings(max_examples=40, deadline=None)
@given(
    fraction=st.floats(0.01, 1.0),
    heel=st.floats(0.0, 0.9),
    neck=st.floats(0.2, 0.9),
)
def test_fill_volume_height_round_trip(fraction, heel, neck):
    profile = profile_from_segments(
        [
            ProfileSegment("cylinder", 0.01, 0.03, heel_radius_m=heel * 0.01),
            ProfileSegment("neck", neck * 0.01, 0.01, shoulder_height_m=0.005),
        ]
    )
    volume = fraction * profile.brimful_volume_m3
    height = profile.fill_height_for_volume(volume)
    assert profile.volume_for_fill_height(height) == pytest.approx(volume, rel=1e-9)


def test_centroid_of_a_cone_is_three_quarters_up():
    assert cone_profile(0.01, 0.02).centroid_height_m(0.02) == pytest.approx(0.015, rel=1e-12)


def test_profile_checks_name_the_problem():
    with pytest.raises(InputError, match="increase strictly"):
        ProfileContainer((0.0, 0.01, 0.01), (0.005, 0.005, 0.006))
    with pytest.raises(InputError, match="start at z = 0"):
        ProfileContainer((0.001, 0.01), (0.005, 0.005))
    with pytest.raises(InputError, match="brimful"):
        cylinder_profile(0.01, 0.01).fill_height_for_volume(1.0)
    with pytest.raises(InputError, match="inner height"):
        equivalent_model(cylinder_profile(0.01, 0.01), WATER, 0.02)
    with pytest.raises(InputError, match="modes"):
        axisymmetric_modes(cylinder_profile(0.01, 0.05), 0.01, 11)


def test_damping_correlation_applies_to_a_near_cylinder_and_warns_elsewhere():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)
        model = equivalent_model(cylinder_profile(0.0205, 0.08, 0.001), WATER, 0.039)
    assert "equivalent depth" in model.provenance["damping_ratio"]
    with pytest.warns(ValidityWarning, match="no damping correlation"):
        equivalent_model(sphere_profile(0.05), WATER, 0.05)
    user = equivalent_model(sphere_profile(0.05), WATER, 0.05, damping_ratio=0.02)
    assert user.modes[0].damping_ratio == 0.02


def test_model_document_round_trip_keeps_the_profile():
    model = equivalent_model(cone_profile(0.04, 0.04), WATER, 0.02, damping_ratio=0.01)
    again = model_from_document(model_to_document(model))
    assert again == model
    assert isinstance(again.container, ProfileContainer)


def test_model_family_of_a_profile_caches_each_fill():
    family = model_family(cylinder_profile(0.007, 0.03, 0.0005), WATER, damping_ratio=0.01)
    first = family(0.006)
    assert family(0.006) == first
    assert family(0.008).modes[0].omega_rad_s > first.modes[0].omega_rad_s


def test_profile_model_summary_names_the_container():
    model = equivalent_model(cylinder_profile(0.007, 0.03), WATER, 0.006, damping_ratio=0.01)
    summary = model.to_dict()
    assert summary["container"] == "cylinder"
    assert summary["liquid_volume_m3"] == pytest.approx(math.pi * 0.007**2 * 0.006)
    cylinder = equivalent_model(UprightCylinder(0.007), WATER, 0.006, damping_ratio=0.01)
    assert "container" not in cylinder.to_dict()


def test_deep_fill_meets_the_closed_form_with_the_mesh_cut_below_the_modes():
    """h = 400 R: the mesh stops 8 radii below the surface; omega^2 = g xi / R (deep limit)."""
    radius, height = 0.005, 2.0
    errors = relative_errors(radius, height)
    assert errors.max() <= 1e-3
    modes = axisymmetric_modes(cylinder_profile(radius, 3.0), height, 1)
    assert modes.bob_height_m[0] == pytest.approx(height - 2 * radius / 1.8411837813406595)


@settings(max_examples=10, deadline=None)
@given(scale=st.floats(1e-3, 1e3))
def test_geometric_similarity(scale):
    """Scaling the container by k scales lambda by 1/k, masses by k^3, heights by k (the solver
    works in units of the surface radius, so this holds to round-off)."""
    base = axisymmetric_modes(cone_profile(0.02, 0.03), 0.017, 2)
    scaled = axisymmetric_modes(cone_profile(0.02 * scale, 0.03 * scale), 0.017 * scale, 2)
    np.testing.assert_allclose(
        np.array(scaled.eigenvalues_1_m) * scale, base.eigenvalues_1_m, rtol=1e-9
    )
    np.testing.assert_allclose(
        np.array(scaled.mass_per_density_m3) / scale**3, base.mass_per_density_m3, rtol=1e-9
    )
    np.testing.assert_allclose(np.array(scaled.bob_height_m) / scale, base.bob_height_m, rtol=1e-9)
