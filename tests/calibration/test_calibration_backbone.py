"""Backbone: a softening pendulum decay with amplitude-proportional (quadratic) damping.

theta'' + 2 zeta_0 omega_0 theta' + c_q theta'|theta'| + omega_0^2 sin(theta) = 0. First-order
averaging (Krylov-Bogoliubov; Nayfeh & Mook, *Nonlinear Oscillations* (1979) §2.3, §4.1) gives
omega(A) = omega_0 (1 - A^2/16) and, from the energy lost per cycle, the equivalent damping
zeta(A) = zeta_0 + 4 c_q A / (3 pi). The exact pendulum frequency is
omega_0 pi / (2 K(sin^2(A/2))) (complete elliptic integral, parameter m)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

from sloshkit.calibration import backbone, calibrate, prepare_signal
from sloshkit.errors import ValidityWarning

OMEGA_0 = 21.0
ZETA_0 = 0.004
QUADRATIC = 0.035


def _nonlinear_decay(amplitude=0.8, duration=24.0, noise=0.002, seed=0):
    def rhs(_t, state):
        angle, rate = state
        return [
            rate,
            -2 * ZETA_0 * OMEGA_0 * rate
            - QUADRATIC * rate * abs(rate)
            - OMEGA_0**2 * math.sin(angle),
        ]

    t = np.arange(0, duration, 0.002)
    solution = solve_ivp(rhs, (0, duration), [amplitude, 0.0], t_eval=t, rtol=1e-10, atol=1e-12)
    rng = np.random.default_rng(seed)
    return t, solution.y[0] + rng.normal(0, noise, t.size)


@pytest.fixture(scope="module")
def curve():
    t, y = _nonlinear_decay()
    prepared, _ = prepare_signal(t, y, start_s=0.0, detrend="none")
    return backbone(prepared, OMEGA_0, 0.01)


def test_nayfeh_mook_small_amplitude_limit(curve):
    assert curve.small_amplitude_omega_n_rad_s == pytest.approx(OMEGA_0, rel=3e-3)
    assert curve.small_amplitude_damping_ratio == pytest.approx(ZETA_0, abs=1e-3)


def test_nayfeh_mook_softening_and_damping_slopes(curve):
    assert curve.omega_dependent and curve.zeta_dependent
    assert curve.omega_slope_rad_s_per_amplitude2 == pytest.approx(-OMEGA_0 / 16, rel=0.15)
    assert curve.zeta_slope_per_amplitude == pytest.approx(4 * QUADRATIC / (3 * math.pi), rel=0.15)


def test_backbone_follows_the_exact_pendulum_frequency(curve):
    """Each window's frequency against the exact period of a pendulum of its amplitude."""
    big = curve.amplitude > 0.15
    exact = OMEGA_0 * math.pi / (2 * ellipk(np.sin(curve.amplitude[big] / 2) ** 2))
    assert np.allclose(curve.omega_n_rad_s[big], exact, rtol=4e-3)


def test_calibrate_warns_and_reports_the_small_amplitude_limit():
    t, y = _nonlinear_decay(duration=16.0)
    with pytest.warns(ValidityWarning, match="depend on the amplitude"):
        result = calibrate(t, y, method="backbone", start_s=0.0)
    assert result.method == "backbone"
    assert result.omega_n_rad_s == pytest.approx(OMEGA_0, rel=3e-3)
    payload = result.to_dict()
    assert payload["backbone"]["omega_amplitude_dependent"] is True
    assert any("small-amplitude" in message for message in payload["warnings"])


def test_linear_decay_has_a_flat_backbone():
    t = np.arange(0, 10, 0.002)
    zeta = 0.012
    y = np.exp(-zeta * OMEGA_0 * t) * np.cos(OMEGA_0 * math.sqrt(1 - zeta**2) * t)
    y += np.random.default_rng(2).normal(0, 0.003, t.size)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)
        result = calibrate(t, y, start_s=0.0)
    assert result.backbone is not None
    assert not result.backbone.omega_dependent
    assert not result.backbone.zeta_dependent
    assert result.backbone.small_amplitude_damping_ratio == pytest.approx(zeta, rel=0.1)


def test_backbone_table_and_figure(curve, tmp_path):
    frame = curve.to_pandas()
    assert list(frame.columns) == ["time_s", "amplitude", "omega_n_rad_s", "damping_ratio"]
    assert curve.to_csv(tmp_path / "b.csv").stat().st_size > 100
    curve.plot(tmp_path / "b.png")
    assert (tmp_path / "b.png").stat().st_size > 10_000
