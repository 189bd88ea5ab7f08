"""The path program's pendulums (`sloshkit.plan.path.pendulums`,
`sloshkit.plan.path.small_angle`): the small-angle track the tilted search starts with,
against the 3-D simulation's linear kernel, and its linearisation against a perturbed track."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sloshkit.plan.path.pendulums import at_rest, pendulum_track, step_jacobians
from sloshkit.plan.path.small_angle import linear_period, linear_track

G = 9.81
PERIOD_S = 0.004
ARGS = (
    np.array([0.02, 0.005]),
    np.array([np.sqrt(G / 0.02), np.sqrt(G / 0.005)]),
    np.array([0.0066, 0.02]),
)


def _drive(samples: int, turning: float) -> np.ndarray:
    """Two modes' drive: a lateral force, a varying vertical one and the frame's turning rates
    (p, q) and their derivatives scaled by ``turning``."""
    t = np.arange(samples) * PERIOD_S
    drive = np.zeros((2, samples, 7))
    drive[:, :, 0] = -3.0 * np.sin(6.0 * t)
    drive[:, :, 1] = 2.0 * np.cos(4.0 * t)
    drive[:, :, 2] = -G + 0.5 * np.cos(3.0 * t)
    drive[:, :, 3] = turning * np.sin(2.0 * t)
    drive[:, :, 4] = 0.6 * turning * np.cos(2.0 * t)
    drive[:, :, 5] = 2.0 * turning * np.cos(2.0 * t)
    drive[:, :, 6] = -1.2 * turning * np.sin(2.0 * t)
    return drive


@pytest.mark.parametrize("turning", [0.0, 0.5])
def test_the_small_angle_period_steps_the_simulations_linear_kernel(turning: float) -> None:
    """`linear_period`, the numpy period the programs differentiate, advances every sample of
    the 3-D simulation's compiled linear kernel (`linear_track`) to the next one, with and
    without the frame turning; the wall reads the angle (u_z = -1)."""
    drive = _drive(300, turning)
    rest = np.array([[0.0, 0.0, -G]] * 2)
    unit, rate = linear_track(drive, rest, *ARGS, PERIOD_S)
    c = 2.0 * ARGS[2] * ARGS[1]
    floor = 1e-3 * ARGS[1] ** 2
    following = linear_period(
        unit[:, :-1],
        rate[:, :-1],
        drive[:, :-1],
        drive[:, 1:],
        ARGS[0][:, None],
        c[:, None],
        floor[:, None],
        PERIOD_S,
    )
    scale = np.abs(unit[..., :2]).max()
    assert np.allclose(following[0], unit[:, 1:], rtol=0.0, atol=1e-12 * scale)
    assert np.allclose(following[1], rate[:, 1:], rtol=0.0, atol=1e-10 * np.abs(rate).max())
    assert np.all(unit[..., 2] == -1.0) and np.all(rate[..., 2] == 0.0)


@settings(max_examples=10, deadline=None)
@given(sample=st.integers(1, 200), component=st.integers(0, 6), later=st.integers(1, 90))
def test_the_small_angle_jacobians_predict_a_perturbed_track(
    sample: int, component: int, later: int
) -> None:
    """A small change of the drive at one sample moves the small-angle track ``later``
    samples on as the step Jacobians chained along it predict (the track is linear in the
    force and nearly so in the turning rates)."""
    drive = _drive(300, 0.5)
    rest = np.array([[0.0, 0.0, -G]] * 2)
    unit, rate = linear_track(drive, rest, *ARGS, PERIOD_S)
    a, b, e = step_jacobians(unit, rate, drive, *ARGS, PERIOD_S, linear=True)
    change = np.zeros(7)
    change[component] = 1e-3 if component < 3 else 1e-4
    moved = drive.copy()
    moved[:, sample] += change
    unit2, rate2 = linear_track(moved, rest, *ARGS, PERIOD_S)
    end = sample + later
    for mode in range(2):
        dx = a[mode, sample] @ (e[mode, sample - 1] @ change) + b[mode, sample] @ change
        for k in range(sample + 1, end):
            dx = a[mode, k] @ dx
        exact = np.concatenate(
            (unit2[mode, end] - unit[mode, end], rate2[mode, end] - rate[mode, end])
        )
        assert np.allclose(dx, exact, rtol=0.0, atol=1e-3 * np.abs(exact).max() + 1e-15)


def test_at_rest_is_each_models_equilibrium() -> None:
    """Under a constant force both tracks settle where `at_rest` says."""
    force = np.tile([-0.2 * G, 0.1 * G, -G], (1, 4000, 1))
    rest = np.array([[0.0, 0.0, -G]])
    args = (np.array([0.01]), np.array([np.sqrt(G / 0.01)]), np.array([0.3]), 1e-3)
    for linear in (False, True):
        unit, _ = pendulum_track(force, rest, *args, linear=linear)
        assert np.allclose(unit[0, -1, :2], at_rest(force[0, -1], linear), atol=1e-6)
