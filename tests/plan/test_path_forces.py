"""The path program's specific forces (`sloshkit.plan.path.forces.specific_forces`)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.forces import specific_forces
from sloshkit.plan.path.geometry import path_from_poses, path_from_waypoints

MODEL = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
GRAVITY = np.array([0.0, 0.0, -MODEL.gravity_m_s2])


def _quintic(length: float, steps: int) -> np.ndarray:
    tau = np.linspace(0.0, 1.0, steps + 1)
    return length * tau**3 * (10 - 15 * tau + 6 * tau**2)


def test_an_upright_straight_move_feels_gravity_minus_its_acceleration():
    path = path_from_waypoints([[0, 0, 0], [0.2, 0, 0]])
    s = _quintic(0.2, 60)[None]
    force, kinematic = specific_forces(
        path, MODEL.modes, GRAVITY, s, np.zeros((1, 61, 2)), 0.01, 0.0
    )
    acceleration = kinematic["acceleration"][0, 1:-1]  # at the samples
    for mode in range(len(MODEL.modes)):
        np.testing.assert_allclose(force[0, mode], GRAVITY - acceleration, atol=1e-9)
    np.testing.assert_allclose(force[0, -1], np.broadcast_to(GRAVITY, (61, 3)), atol=1e-12)
    np.testing.assert_allclose(kinematic["tilt_rates"], 0.0, atol=1e-12)


def test_a_turn_about_the_vertical_does_not_turn_the_non_spinning_frame():
    # a move along x with a pure yaw about the container's own axis: N, the container frame
    # with its spin removed, stays the world's, so the force in N is the world's g - a
    yaw = Rotation.from_rotvec(np.outer(np.linspace(0.0, np.pi / 2, 5), [0.0, 0.0, 1.0]))
    path = path_from_poses(np.linspace(0, 0.1, 5)[:, None] * [1.0, 0.0, 0.0], yaw.as_quat())
    s = _quintic(path.length_m, 50)[None]
    force, kinematic = specific_forces(
        path, MODEL.modes, GRAVITY, s, np.zeros((1, 51, 2)), 0.01, 0.0
    )
    acceleration = kinematic["acceleration"][0, 1:-1]
    assert np.max(np.abs(acceleration[:, 0])) > 0.5
    np.testing.assert_allclose(force[0, 0], GRAVITY - acceleration, atol=1e-6)
    np.testing.assert_allclose(kinematic["tilt_rates"], 0.0, atol=1e-9)
    assert np.max(np.abs(kinematic["omega"][0, :, 2])) > 1.0  # the yaw rate itself is there


@settings(max_examples=20, deadline=None)
@given(
    tilt=st.floats(-0.5, 0.5),
    centre=st.floats(0.0, 0.1),
    fraction=st.floats(0.3, 1.0),
)
def test_a_batch_is_its_sets_evaluated_one_by_one(tilt, centre, fraction):
    path = path_from_waypoints([[0, 0, 0], [0.2, 0, 0], [0.2, 0.2, 0.1]])
    steps = 40
    sets = [_quintic(path.length_m, steps), _quintic(fraction * path.length_m, steps)]
    bump = np.sin(np.linspace(0.0, np.pi, steps + 1)) ** 2
    tilts = [np.zeros((steps + 1, 2)), np.column_stack((tilt * bump, -0.5 * tilt * bump))]
    together = specific_forces(
        path, MODEL.modes, GRAVITY, np.stack(sets), np.stack(tilts), 0.01, centre
    )
    for index in range(2):
        alone = specific_forces(
            path, MODEL.modes, GRAVITY, sets[index][None], tilts[index][None], 0.01, centre
        )
        np.testing.assert_allclose(together[0][index], alone[0][0], rtol=1e-12, atol=1e-9)
        for key, value in alone[1].items():
            np.testing.assert_allclose(together[1][key][index], value[0], rtol=1e-12, atol=1e-9)


def test_the_tilt_rates_are_the_tilt_derivatives_for_a_pure_tilt():
    # the container held still and tilted about x: N's lateral rate is the tilt rate
    path = path_from_waypoints([[0, 0, 0], [1e-9, 0, 0]])
    steps, period = 100, 0.005
    t = np.arange(steps + 1) * period
    angle = 0.3 * np.sin(np.pi * t / t[-1]) ** 2
    tilt = np.column_stack((angle, np.zeros_like(angle)))[None]
    _, kinematic = specific_forces(
        path, MODEL.modes, GRAVITY, np.zeros((1, steps + 1)), tilt, period, 0.0
    )
    rate = np.gradient(angle, period)
    np.testing.assert_allclose(kinematic["tilt_rates"][0, 1:-1, 0], rate[1:-1], atol=0.02)
