"""Slosh simulation: cross-checks between independent methods and physical properties."""

from __future__ import annotations

import dataclasses
import itertools
import math
import warnings

import numpy as np
import pytest
from conftest import seed_vial_table3
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from sloshkit.errors import ValidityWarning
from sloshkit.motion import make_law, quintic, septic, trapezoidal
from sloshkit.sim.metrics import free_amplitude
from sloshkit.sim.simulate import simulate, simulate_cart_pendulum


def _solve_ivp_reference(motion, mode, time):
    """Acceleration-driven eq. 7 integrated by RK45 at tight tolerances, piece by piece."""
    w, z, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
    acceleration = motion.derivative_pp(2)
    edges = sorted({0.0, *motion.breakpoints_s.tolist(), float(time[-1])})
    state = np.zeros(2)
    angle = np.zeros_like(time)
    rate = np.zeros_like(time)
    for start, stop in itertools.pairwise(edges):
        last = np.nextafter(stop, start)

        def rhs(t, y, start=start, last=last):
            moment = min(max(t, start), last)
            a = float(acceleration(moment)) if moment < motion.duration_s else 0.0
            return [y[1], -2 * z * w * y[1] - w * w * y[0] - a / length]

        inside = (time >= start) & (time <= stop)
        t_eval = np.union1d(time[inside], [stop])
        sol = solve_ivp(rhs, (start, stop), state, rtol=1e-11, atol=1e-13, t_eval=t_eval)
        keep = np.isin(t_eval, time[inside])
        angle[inside], rate[inside] = sol.y[0, keep], sol.y[1, keep]
        state = sol.y[:, -1]
    return angle, rate


@pytest.mark.parametrize("name", ["trapezoidal", "cubic", "quintic", "septic", "s-curve"])
def test_linear_fast_path_matches_solve_ivp(seed_model_table3, name):
    motion = make_law(
        name,
        0.5,
        peak_velocity_m_s=0.5,
        max_velocity_m_s=0.5,
        max_acceleration_m_s2=1.0,
        max_jerk_m_s3=10.0,
    )
    response = simulate(seed_model_table3, motion, sample_period_s=1e-3, settle_time_s=1.0)
    for row, mode in enumerate(seed_model_table3.modes):
        angle, rate = _solve_ivp_reference(motion, mode, response.time_s)
        scale = np.max(np.abs(angle))
        # First-order hold on the velocity: exact for the trapezoid, O((omega dt)^2) otherwise.
        assert np.max(np.abs(response.angle_rad[row] - angle)) < 1e-4 * scale
        assert np.max(np.abs(response.rate_rad_s[row] - rate)) < 5e-4 * np.max(np.abs(rate))


def test_nonlinear_equals_linear_at_small_amplitude(seed_model_table3):
    motion = quintic(0.005, 1.0)  # 5 mm move: angles of a few hundredths of a degree
    linear = simulate(seed_model_table3, motion)
    nonlinear = simulate(seed_model_table3, motion, kind="nonlinear")
    scale = np.max(np.abs(linear.angle_rad))
    assert np.max(np.abs(linear.angle_rad - nonlinear.angle_rad)) < 1e-4 * scale
    assert nonlinear.residual_angle_rad == pytest.approx(linear.residual_angle_rad, rel=1e-3)


def test_nonlinear_softens_at_large_amplitude(seed_model_table3):
    motion = make_law(
        "s-curve", 0.5, max_velocity_m_s=1.0, max_acceleration_m_s2=5.0, max_jerk_m_s3=50.0
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        linear = simulate(seed_model_table3, motion)
        nonlinear = simulate(seed_model_table3, motion, kind="nonlinear")
    assert not np.allclose(linear.angle_rad[0], nonlinear.angle_rad[0], atol=1e-3)


def test_free_decay_recovers_damped_frequency_and_damping(seed_model_table3):
    """After the move the first mode rings at omega_d and decays at zeta omega."""
    model = seed_model_table3
    response = simulate(model, trapezoidal(0.01, duration_s=0.3), settle_time_s=4.0)
    mode = model.modes[0]
    after = response.time_s > 0.3
    t = response.time_s[after]
    theta = response.angle_rad[0, after]
    # Upward zero crossings give the damped period.
    crossings = t[1:][(theta[:-1] < 0) & (theta[1:] >= 0)]
    period = np.mean(np.diff(crossings))
    assert 2 * math.pi / period == pytest.approx(mode.damped_omega_rad_s, rel=2e-3)
    envelope = free_amplitude(
        theta, response.rate_rad_s[0, after], mode.omega_rad_s, mode.damping_ratio
    )
    slope = np.polyfit(t, np.log(envelope), 1)[0]
    # The three modes superpose; the first dominates the envelope fit.
    assert -slope / mode.omega_rad_s == pytest.approx(mode.damping_ratio, rel=0.05)


def test_residual_from_state_equals_sampled_peaks_after_the_move(seed_model_table3):
    model = dataclasses.replace(seed_model_table3, modes=seed_model_table3.modes[:1])
    motion = trapezoidal(0.5, peak_velocity_m_s=0.5)
    response = simulate(model, motion, sample_period_s=2e-4, settle_time_s=0.5)
    mode = model.modes[0]
    after = response.time_s >= motion.duration_s
    decay = np.exp(
        mode.damping_ratio * mode.omega_rad_s * (response.time_s[after] - motion.duration_s)
    )
    assert np.max(np.abs(response.angle_rad[0, after]) * decay) == pytest.approx(
        response.residual_angle_rad, rel=1e-3
    )


def test_zero_motion_gives_zero_slosh(seed_model):
    motion = trapezoidal(1e-12, duration_s=1.0)
    response = simulate(seed_model, motion)
    assert np.max(np.abs(response.angle_rad)) < 1e-9


@settings(max_examples=30, deadline=None)
@given(
    scale=st.floats(0.01, 10.0), name=st.sampled_from(["trapezoidal", "cubic", "quintic", "septic"])
)
def test_linear_response_scales_with_distance(scale, name):
    seed_model_table3 = seed_vial_table3()
    base = simulate(seed_model_table3, make_law(name, 0.1, duration_s=1.2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        scaled = simulate(seed_model_table3, make_law(name, 0.1 * scale, duration_s=1.2))
    peak = np.max(np.abs(scaled.angle_rad))
    np.testing.assert_allclose(scaled.angle_rad, scale * base.angle_rad, rtol=0, atol=1e-10 * peak)
    assert scaled.residual_angle_rad == pytest.approx(scale * base.residual_angle_rad, rel=1e-9)


@settings(max_examples=20, deadline=None)
@given(
    zeta=st.floats(0.0, 0.2),
    distance=st.floats(0.001, 0.3),
    kind=st.sampled_from(["linear", "nonlinear"]),
)
def test_free_motion_never_gains_energy(zeta, distance, kind):
    model = seed_vial_table3()
    for n in range(1, 4):
        model = model.with_mode(n, damping_ratio=zeta)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate(model, quintic(distance, 0.4), kind=kind, settle_time_s=1.0)
    after = response.time_s >= 0.4
    for row, mode in enumerate(model.modes):
        theta, rate = response.angle_rad[row, after], response.rate_rad_s[row, after]
        potential = (1 - np.cos(theta)) if kind == "nonlinear" else theta**2 / 2
        energy = rate**2 / 2 + mode.omega_rad_s**2 * potential
        # Integrator tolerance (rtol 1e-10) allows tiny wiggles when zeta = 0.
        assert np.all(np.diff(energy) <= 1e-8 * max(energy[0], 1e-30))


def test_desimone2024_finding_jerk_continuous_laws_slosh_less(seed_model_table3):
    """Paper §4 and Fig. 9: trapezoidal and cubic laws leave far more residual slosh than the
    quintic and jerk-optimised laws at the same duration (1.5 s for 0.5 m at 0.5 m/s)."""
    residual = {}
    for name in ("trapezoidal", "cubic", "quintic", "septic"):
        motion = make_law(name, 0.5, peak_velocity_m_s=0.5)
        residual[name] = simulate(seed_model_table3, motion).residual_angle_rad
    assert residual["trapezoidal"] > 5 * residual["septic"]
    assert residual["cubic"] > 5 * residual["septic"]
    assert residual["trapezoidal"] > 3 * residual["quintic"]
    assert residual["septic"] < residual["quintic"]


def test_cart_pendulum_reduces_to_acceleration_driven_model(seed_model_table3):
    """Paper eqs. 4-5 driven by a force: feeding the cart's own acceleration back into the
    linear eq. 7 gives the same angles at small amplitude."""
    model = seed_model_table3
    cart_mass = 0.5

    def force(t):
        return 0.2 * math.sin(2 * math.pi * 1.0 * t) if t < 1.0 else 0.0

    cart = simulate_cart_pendulum(
        model, force, cart_mass_kg=cart_mass, duration_s=2.0, sample_period_s=1e-3
    )
    velocity = cart.velocity_m_s
    from sloshkit.sim.discretisation import linear_mode_response

    for row, mode in enumerate(model.modes):
        theta, _ = linear_mode_response(
            velocity, 1e-3, mode.omega_rad_s, mode.damping_ratio, mode.length_m
        )
        scale = np.max(np.abs(cart.angle_rad[row]))
        assert np.max(np.abs(theta - cart.angle_rad[row])) < 2e-3 * scale
    # Momentum: the impulse of F equals the system's momentum once the force stops.
    total = cart_mass + model.liquid_mass_kg
    assert total * cart.velocity_m_s[-1] + sum(
        mode.slosh_mass_kg
        * mode.length_m
        * cart.rate_rad_s[i, -1]
        * math.cos(cart.angle_rad[i, -1])
        for i, mode in enumerate(model.modes)
    ) == pytest.approx(0.0, abs=1e-9)


def test_metrics_and_exports(seed_model_table3, tmp_path):
    response = simulate(seed_model_table3, septic(0.5, 1.5))
    metrics = response.metrics()
    assert set(metrics) == {
        "duration_s",
        "peak_angle_deg",
        "residual_angle_deg",
        "peak_wall_elevation_m",
        "residual_wall_elevation_m",
        "settling_time_s",
        "peak_acceleration_m_s2",
        "peak_jerk_m_s3",
    }
    assert metrics["settling_time_s"] > metrics["duration_s"]
    path = response.to_csv(tmp_path / "out.csv")
    header = path.read_text().splitlines()[0].split(",")
    assert header[:4] == ["t_s", "position_m", "velocity_m_s", "acceleration_m_s2"]
    assert "wall_elevation_m" in header and "slosh_force_n" in header
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    assert data.shape == (response.time_s.size, len(header))
    frame = response.to_pandas()
    assert list(frame.columns) == header
    response.plot(tmp_path / "fig.png")
    assert (tmp_path / "fig.png").stat().st_size > 10_000


def test_spill_warning_when_wall_is_low(seed_model_table3):
    from sloshkit.model.geometry import UprightCylinder

    model = dataclasses.replace(seed_model_table3, container=UprightCylinder(0.0205, 0.040))
    with pytest.warns(ValidityWarning, match="spill"):
        simulate(model, trapezoidal(0.5, peak_velocity_m_s=0.5))
