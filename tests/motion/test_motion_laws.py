"""Motion laws: end points, limits, published peak values, user motions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sloshkit.errors import InputError
from sloshkit.motion import (
    LAW_NAMES,
    cubic,
    from_samples,
    make_law,
    quintic,
    s_curve,
    septic,
    trapezoidal,
)

POLYNOMIALS = {"cubic": cubic, "quintic": quintic, "septic": septic}


def test_trapveltraj_defaults_reproduce_the_seed_paper_move():
    """D = 0.5 m at 0.5 m/s: T = 1.5 s and a = 1 m/s^2 (physics-notes.md, MATLAB trapveltraj)."""
    law = trapezoidal(0.5, peak_velocity_m_s=0.5)
    assert law.duration_s == pytest.approx(1.5)
    assert law.peak_acceleration_m_s2 == pytest.approx(1.0)
    assert law.peak_velocity_m_s == pytest.approx(0.5)
    assert law.acceleration(0.25) == pytest.approx(1.0)
    assert law.acceleration(1.25) == pytest.approx(-1.0)
    assert math.isinf(law.peak_jerk_m_s3)


def test_trapezoid_with_both_velocity_and_duration():
    law = trapezoidal(0.5, peak_velocity_m_s=0.4, duration_s=2.0)
    assert law.duration_s == pytest.approx(2.0)
    assert law.peak_velocity_m_s == pytest.approx(0.4)
    assert law.peak_acceleration_m_s2 == pytest.approx(0.4 / (2.0 - 0.5 / 0.4))
    with pytest.raises(InputError, match="peak_velocity"):
        trapezoidal(0.5, peak_velocity_m_s=0.2, duration_s=2.0)  # too slow to get there


@pytest.mark.parametrize(
    ("name", "peak_velocity", "peak_acceleration", "peak_jerk"),
    [
        # Biagiotti & Melchiorri (2008) Table 2.1 (dimensionless peaks, D = T = 1).
        ("cubic", 1.5, 6.0, math.inf),
        ("quintic", 1.875, 5.7735, 60.0),
        ("septic", 2.1875, 7.5132, 52.5),
    ],
)
def test_polynomial_peaks_match_published_coefficients(
    name, peak_velocity, peak_acceleration, peak_jerk
):
    law = POLYNOMIALS[name](1.0, 1.0)
    assert law.peak_velocity_m_s == pytest.approx(peak_velocity, rel=1e-4)
    assert law.peak_acceleration_m_s2 == pytest.approx(peak_acceleration, rel=1e-4)
    assert law.peak_jerk_m_s3 == pytest.approx(peak_jerk, rel=1e-4)


def test_minimum_jerk_is_the_quintic():
    t = np.linspace(0, 2, 101)
    np.testing.assert_allclose(
        make_law("minimum-jerk", 0.3, duration_s=2).position(t), quintic(0.3, 2).position(t)
    )


def test_s_curve_matches_ruckig_and_its_limits():
    from ruckig import InputParameter, Ruckig, Trajectory

    law = s_curve(0.5, 1.0, 5.0, 50.0)
    parameters = InputParameter(1)
    parameters.current_position, parameters.target_position = [0.0], [0.5]
    parameters.max_velocity, parameters.max_acceleration, parameters.max_jerk = [1.0], [5.0], [50.0]
    trajectory = Trajectory(1)
    Ruckig(1).calculate(parameters, trajectory)
    assert law.duration_s == pytest.approx(trajectory.duration, rel=1e-12)
    for t in np.linspace(0, trajectory.duration, 37):
        position, velocity, acceleration = trajectory.at_time(t)
        assert law.position(t) == pytest.approx(position[0], abs=1e-12)
        assert law.velocity(t) == pytest.approx(velocity[0], abs=1e-12)
        assert law.acceleration(t) == pytest.approx(acceleration[0], abs=1e-9)
    assert law.peak_velocity_m_s <= 1.0 + 1e-12
    assert law.peak_acceleration_m_s2 <= 5.0 + 1e-12
    assert law.peak_jerk_m_s3 <= 50.0 + 1e-12


@settings(max_examples=150, deadline=None)
@given(
    name=st.sampled_from(LAW_NAMES),
    distance=st.floats(1e-3, 2.0),
    duration=st.floats(0.05, 10.0),
    vmax=st.floats(0.05, 3.0),
    amax=st.floats(0.2, 50.0),
    jmax=st.floats(1.0, 2000.0),
)
def test_every_law_is_rest_to_rest_and_within_its_limits(
    name, distance, duration, vmax, amax, jmax
):
    law = make_law(
        name,
        distance,
        duration_s=duration,
        max_velocity_m_s=vmax,
        max_acceleration_m_s2=amax,
        max_jerk_m_s3=jmax,
    )
    end = law.duration_s
    assert law.position(0.0) == 0.0
    assert law.position(end) == pytest.approx(distance, rel=1e-11)
    assert law.position(end + 1.0) == pytest.approx(distance, rel=1e-11)
    # Rounding scales with the law's own peaks (a long S-curve has tiny D/T^2).
    scale_v, scale_a = law.peak_velocity_m_s, law.peak_acceleration_m_s2
    assert abs(law.velocity(0.0)) <= 1e-9 * scale_v and abs(law.velocity(end)) <= 1e-9 * scale_v
    if name not in ("trapezoidal", "cubic"):
        assert abs(law.acceleration(0.0)) <= 1e-9 * scale_a
        assert abs(law.acceleration(end)) <= 1e-9 * scale_a
    if name == "septic":
        jerk = law.derivative_pp(3)
        assert (
            abs(jerk(0.0)) <= 1e-8 * distance / end**3
            and abs(jerk(end)) <= 1e-8 * distance / end**3
        )
    if name == "s-curve":
        assert law.peak_velocity_m_s <= vmax * (1 + 1e-9)
        assert law.peak_acceleration_m_s2 <= amax * (1 + 1e-9)
        assert law.peak_jerk_m_s3 <= jmax * (1 + 1e-9)
    else:
        assert end == pytest.approx(duration)
    samples = law.sample(1e-3)
    assert np.all(np.isfinite(np.column_stack(list(samples.values()))))
    # Peaks found from the pieces are never exceeded by dense samples.
    t = np.linspace(0, end, 4001)
    assert np.max(np.abs(law.velocity(t))) <= law.peak_velocity_m_s * (1 + 1e-9)
    assert np.max(np.abs(law.acceleration(t))) <= law.peak_acceleration_m_s2 * (1 + 1e-9)


def test_position_samples_are_differentiated_consistently():
    t = np.linspace(0, 1.2, 241)
    exact = septic(0.4, 1.2)
    user = from_samples(t, position_m=exact.position(t))
    grid = np.linspace(0, 1.2, 999)
    np.testing.assert_allclose(user.position(grid), exact.position(grid), atol=1e-9)
    np.testing.assert_allclose(user.velocity(grid), exact.velocity(grid), atol=1e-6)
    np.testing.assert_allclose(user.acceleration(grid), exact.acceleration(grid), atol=1e-3)


def test_acceleration_samples_are_integrated_from_rest():
    t = np.linspace(0, 1.5, 301) + 10.0  # shifted clock
    exact = quintic(0.5, 1.5)
    user = from_samples(t, acceleration_m_s2=exact.acceleration(t - 10.0))
    assert user.duration_s == pytest.approx(1.5)
    assert user.distance_m == pytest.approx(0.5, rel=1e-6)
    np.testing.assert_allclose(
        user.velocity(np.linspace(0, 1.5, 50)), exact.velocity(np.linspace(0, 1.5, 50)), atol=1e-6
    )


@pytest.mark.parametrize(
    ("time", "parameter"),
    [
        ([0, 0.1, 0.1, 0.3, 0.4, 0.5, 0.6], "time"),
        ([0, 0.2, 0.1, 0.3, 0.4, 0.5, 0.6], "time"),
        ([0, 0.1, float("nan"), 0.3, 0.4, 0.5, 0.6], "motion samples"),
    ],
)
def test_bad_user_motion_is_rejected(time, parameter):
    with pytest.raises(InputError) as info:
        from_samples(time, position_m=np.linspace(0, 1, 7))
    assert info.value.parameter == parameter


@pytest.mark.parametrize(
    ("kwargs", "parameter"),
    [
        ({"distance_m": 0.0, "duration_s": 1.0}, "distance"),
        ({"distance_m": 0.5, "duration_s": -1.0}, "duration"),
    ],
)
def test_non_positive_distance_or_duration(kwargs, parameter):
    with pytest.raises(InputError) as info:
        quintic(**kwargs)
    assert info.value.parameter == parameter


def test_unknown_law_and_missing_limits():
    with pytest.raises(InputError, match="must be one of"):
        make_law("bang-bang", 0.5, duration_s=1.0)
    with pytest.raises(InputError, match="vmax"):
        make_law("s-curve", 0.5)
