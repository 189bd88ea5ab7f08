"""The amplitude-dependent first mode of the 3-D model (`sloshkit.sim.spatial_amplitude`).

References: a free oscillation of the model must follow the analytic backbone it is built from,
omega(A) = omega_n + k_2 A^2 and zeta(A) = zeta_n + k_1 A (equivalent linearisation, Nayfeh &
Mook 1979 §4.1-4.2), measured here from zero crossings and the energy envelope, independently
of sloshkit's own identification; small amplitudes must reproduce the linear model; the
container's measured free decay must soften, as the multimodal theory predicts for fill depths
h/R > 1.05 (Faltinsen, Lukovsky & Timokha, J. Fluid Mech. 804 (2016)).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from sloshkit.calibration.amplitude import decay_amplitude_dependence
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion.laws import septic
from sloshkit.motion.pose_builders import poses_from_law
from sloshkit.sim.spatial import simulate_spatial
from sloshkit.sim.spatial_amplitude import AmplitudeDependence, force_per_radian

DECAY = Path(__file__).resolve().parents[1] / "data" / "measured-3d" / "free_decay_force.csv"


def _model(modes: int = 1, zeta: float = 0.01) -> SloshModel:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return equivalent_model(
            UprightCylinder(0.049), get_liquid("water-20C"), 0.08, modes, damping_ratio=zeta
        )


def _free_oscillation(model: SloshModel, dependence: AmplitudeDependence | None):  # type: ignore[no-untyped-def]
    """A short, hard push (0.05 m in 0.25 s) and 10 s of free oscillation."""
    poses = poses_from_law(septic(0.05, 0.25))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(
            model, poses, settle_time_s=10.0, cutoff_hz=None, amplitude_dependence=dependence
        )
    return response, poses.end_s + 0.2


def _zero_crossing_backbone(response, start_s: float):  # type: ignore[no-untyped-def]
    """(amplitude, omega) per full cycle of the free oscillation, from upward zero crossings
    (interpolated) and the energy amplitude sqrt(x^2 + (x'/omega)^2) averaged over the cycle,
    omega that cycle's frequency."""
    t = response.time_s
    x = response.angle_rad[0][:, 0]
    rate = response.rate_rad_s[0][:, 0]
    keep = t > start_s
    t, x, rate = t[keep], x[keep], rate[keep]
    up = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    crossings = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    rows = []
    for first, second, index in zip(crossings[:-1], crossings[1:], up[:-1], strict=True):
        cycle = (t >= first) & (t < second)
        omega = 2.0 * math.pi / (second - first)
        rows.append((float(np.mean(np.hypot(x[cycle], rate[cycle] / omega))), omega, index))
    return np.asarray(rows)


def test_free_oscillation_follows_the_analytic_frequency_backbone() -> None:
    model = _model()
    dependence = AmplitudeDependence((-20.0,), (0.0,), (0.6,), "test")
    response, start = _free_oscillation(model, dependence)
    rows = _zero_crossing_backbone(response, start)
    amplitude, omega = rows[:, 0], rows[:, 1]
    assert amplitude.max() > 0.3  # a large oscillation: the shift reaches 9 % of omega_n
    expected = model.modes[0].omega_rad_s - 20.0 * amplitude**2
    shift = model.modes[0].omega_rad_s - expected
    big = amplitude > 0.1
    np.testing.assert_allclose(omega[big], expected[big], atol=0.03 * float(shift.max()) + 0.01)


def test_free_oscillation_follows_the_analytic_damping_backbone() -> None:
    model = _model(zeta=0.01)
    dependence = AmplitudeDependence((0.0,), (0.02,), (0.6,), "test")
    response, start = _free_oscillation(model, dependence)
    rows = _zero_crossing_backbone(response, start)
    amplitude = rows[:, 0]
    omega_n = model.modes[0].omega_rad_s
    period = 2.0 * math.pi / omega_n
    # decay rate over three cycles: d ln A / dt = -zeta(A) omega_n
    zeta = np.log(amplitude[:-3] / amplitude[3:]) / (3.0 * period * omega_n)
    middle = 0.5 * (amplitude[:-3] + amplitude[3:])
    assert middle.max() > 0.6  # beyond the cap: zeta is held at its value there
    np.testing.assert_allclose(zeta, 0.01 + 0.02 * np.minimum(middle, 0.6), rtol=0.03)


def test_zero_slopes_are_the_linear_model() -> None:
    model = _model(modes=3, zeta=0.0066)
    linear, _ = _free_oscillation(model, None)
    flat, _ = _free_oscillation(model, AmplitudeDependence((0.0,), (0.0,), (1.0,), "flat"))
    np.testing.assert_allclose(flat.slosh_height_m, linear.slosh_height_m, rtol=0, atol=1e-12)


def test_small_amplitudes_reproduce_the_linear_model() -> None:
    model = _model(modes=3, zeta=0.0066)
    poses = poses_from_law(septic(0.02, 2.0))  # gentle: the wave stays below 0.01 rad
    dependence = AmplitudeDependence((-5.8,), (0.0,), (0.22,), "measured-like")
    linear = simulate_spatial(model, poses)
    softened = simulate_spatial(model, poses, amplitude_dependence=dependence)
    assert linear.peak_angle_rad < 0.02
    assert softened.peak_slosh_height_m == pytest.approx(linear.peak_slosh_height_m, rel=1e-4)
    assert softened.metrics()["amplitude_model"] == "measured-like"
    assert linear.metrics()["amplitude_model"] == "none"


def test_a_static_tilt_of_the_apparent_gravity_is_not_a_wave() -> None:
    """A = 0 at the quasi-static equilibrium: a steady lateral acceleration gives the linear
    (planar-statics) slope however strong the softening."""
    model = _model(zeta=0.3)
    poses = poses_from_law(septic(0.5, 6.0))
    linear = simulate_spatial(model, poses, cutoff_hz=None)
    softened = simulate_spatial(
        model,
        poses,
        cutoff_hz=None,
        amplitude_dependence=AmplitudeDependence((-50.0,), (0.0,), (1.0,)),
    )
    np.testing.assert_allclose(softened.angle_rad, linear.angle_rad, rtol=0, atol=2e-5)


def test_the_measured_free_decay_softens_and_its_damping_does_not_grow() -> None:
    """The container of tests/data/measured-3d (h/R = 1.63 > 1.05): soft spring, as theory
    says; the damping trend is not significant, so it is left out."""
    model = _model(zeta=0.0066)
    record = np.loadtxt(DECAY, delimiter=",", skiprows=1)
    found = decay_amplitude_dependence(model, record[:, 0], record[:, 2], 2.6)
    slope = found.curve.omega_slope_rad_s_per_amplitude2
    assert found.curve.omega_dependent and slope < -3.0 * found.omega_slope_se_rad_s_per_n2
    assert not found.curve.zeta_dependent
    assert found.dependence.zeta_slope_per_rad == (0.0,)
    assert found.dependence.omega_slope_rad_s_per_rad2[0] == pytest.approx(
        slope * force_per_radian(model) ** 2
    )
    # the record covers wave amplitudes up to about 0.2 rad (9 mm at the wall)
    assert 0.15 < found.dependence.amplitude_cap_rad[0] < 0.3
    assert found.curve.small_amplitude_omega_n_rad_s == pytest.approx(
        model.modes[0].omega_rad_s, rel=0.01
    )


def test_the_nonlinear_pendulum_refuses_a_backbone() -> None:
    model = _model()
    with pytest.raises(InputError, match="amplitude_dependence"):
        simulate_spatial(
            model,
            poses_from_law(septic(0.05, 1.0)),
            nonlinear=True,
            amplitude_dependence=AmplitudeDependence((-1.0,), (0.0,), (0.2,)),
        )


def test_bad_backbones_are_refused() -> None:
    with pytest.raises(InputError):
        AmplitudeDependence((-1.0, 0.0), (0.0,), (0.2,))
    with pytest.raises(InputError):
        AmplitudeDependence((math.nan,), (0.0,), (0.2,))
    with pytest.raises(InputError):
        AmplitudeDependence((-1.0,), (0.0,), (-0.2,))
