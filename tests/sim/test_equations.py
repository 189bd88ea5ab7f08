"""One source per equation: the pendulum right-hand side, the residual amplitude and the wall
elevation give the same numbers in numpy, in plain floats and as casadi expressions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sloshkit.motion.laws import quintic
from sloshkit.motion.sampling import export_samples, sample_times, steps_for, steps_to_reach
from sloshkit.sim.equations import pendulum_angular_acceleration
from sloshkit.sim.metrics import (
    free_amplitude,
    free_oscillation_components,
    simulation_grid,
    wall_elevation,
    wall_elevation_factors,
)
from sloshkit.sim.simulate import simulate

casadi = pytest.importorskip("casadi")

STATES = [(0.2, -1.3, 2.5), (-0.7, 0.4, -9.0), (1.2, 3.0, 0.0)]


@pytest.mark.parametrize("nonlinear", [False, True])
@pytest.mark.parametrize(("angle", "rate", "acceleration"), STATES)
def test_rhs_is_the_same_in_numpy_floats_and_casadi(angle, rate, acceleration, nonlinear):
    omega, zeta, length = 29.7, 0.03, 0.011
    in_numpy = pendulum_angular_acceleration(
        np.array([angle]),
        np.array([rate]),
        np.array([acceleration]),
        omega,
        zeta,
        length,
        nonlinear=nonlinear,
    )[0]
    in_floats = pendulum_angular_acceleration(
        angle,
        rate,
        acceleration,
        omega,
        zeta,
        length,
        nonlinear=nonlinear,
        sin=math.sin,
        cos=math.cos,
    )
    x = casadi.SX.sym("x", 3)
    expression = pendulum_angular_acceleration(
        x[0], x[1], x[2], omega, zeta, length, nonlinear=nonlinear, sin=casadi.sin, cos=casadi.cos
    )
    in_casadi = float(casadi.Function("f", [x], [expression])([angle, rate, acceleration]))
    assert in_floats == pytest.approx(in_numpy, rel=1e-14)
    assert in_casadi == pytest.approx(in_numpy, rel=1e-12)
    # The closed form of the linear pendulum (seed paper eq. 7) as an independent check.
    if not nonlinear:
        assert in_floats == pytest.approx(
            -2 * zeta * omega * rate - omega**2 * angle - acceleration / length, rel=1e-14
        )


def test_free_amplitude_components_in_casadi_and_against_the_free_response():
    omega, zeta = 12.0, 0.05
    angle, rate = 0.03, -0.4
    a, b = free_oscillation_components(angle, rate, omega, zeta)
    damped = omega * math.sqrt(1 - zeta**2)
    # theta(t) = e^{-zeta w t} (A cos w_d t + B sin w_d t) passes through (angle, rate) at t = 0.
    assert a == angle
    assert -zeta * omega * a + damped * b == pytest.approx(rate, rel=1e-14)
    x = casadi.SX.sym("x", 2)
    ca, cb = free_oscillation_components(x[0], x[1], omega, zeta)
    squared = float(casadi.Function("f", [x], [ca**2 + cb**2])([angle, rate]))
    assert math.sqrt(squared) == pytest.approx(float(free_amplitude(angle, rate, omega, zeta)))


def test_wall_elevation_numpy_and_casadi(seed_model_table3):
    factors = wall_elevation_factors(seed_model_table3)
    angles = np.array([[0.1, -0.2], [0.02, 0.01], [-0.005, 0.0]])[: factors.size]
    expected = factors @ angles
    np.testing.assert_allclose(wall_elevation(factors, angles), expected, rtol=1e-14)
    x = casadi.SX.sym("x", factors.size)
    expression = wall_elevation(factors, [x[i] for i in range(factors.size)])
    value = float(casadi.Function("f", [x], [expression])(angles[:, 0]))
    assert value == pytest.approx(expected[0], rel=1e-14)


def test_one_grid_rule_everywhere():
    for duration, step in [(1.0, 1e-3), (0.3, 0.1), (1.05, 0.1), (2.0, 4e-3)]:
        count = steps_to_reach(duration, step)
        assert (count - 1) * step < duration - 1e-12 <= count * step
        assert sample_times(duration, step).size == count + 1
        assert steps_for(duration, step) == count + 2
        assert simulation_grid(duration, step, 0.0).size == count + 1
        law = quintic(0.1, duration)
        assert export_samples(law, step)["t_s"].size == count + 1


def test_simulate_refuses_the_v1_argument_order(seed_model_table3):
    with pytest.raises(TypeError, match="model comes first"):
        simulate(quintic(0.1, 1.0), seed_model_table3)
