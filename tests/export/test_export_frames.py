"""Frames for export: the default mounting, rigid-transform algebra, quaternion signs."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from sloshkit.export.frames import (
    Mounting,
    invert,
    matrices_to_poses,
    poses_to_matrices,
    rotation_angle_rad,
    transform,
)
from sloshkit.export.kinematics import load_arm
from sloshkit.motion.quaternions import sign_continuous

angles = st.floats(-math.pi, math.pi, allow_nan=False)
lengths = st.floats(-2.0, 2.0, allow_nan=False)


def test_default_mounting_hangs_the_container_below_a_downward_flange():
    """UR5e home: flange z points down; the container's bottom is 100 mm below the flange and
    its axis points up (opposite to the flange's z axis)."""
    arm = load_arm("ur5e")
    flange = arm.forward(arm.home_rad[None])[0]
    np.testing.assert_allclose(flange[:3, 2], [0.0, 0.0, -1.0], atol=1e-12)
    container = flange @ Mounting().flange_to_container
    np.testing.assert_allclose(container[:3, 2], [0.0, 0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(container[:3, 3] - flange[:3, 3], [0.0, 0.0, -0.1], atol=1e-12)


@settings(max_examples=50, deadline=None)
@given(lengths, lengths, lengths, angles, angles, angles)
def test_invert_undoes_a_transform(x, y, z, roll, pitch, yaw):
    matrix = transform((x, y, z), (roll, pitch, yaw))
    np.testing.assert_allclose(invert(matrix) @ matrix, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(matrix @ invert(matrix), np.eye(4), atol=1e-12)


@settings(max_examples=50, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_poses_round_trip_and_quaternions_stay_sign_continuous(seed):
    rng = np.random.default_rng(seed)
    rotations = Rotation.from_rotvec(np.cumsum(rng.normal(0.0, 0.3, (20, 3)), axis=0))
    quaternion = rotations.as_quat() * rng.choice([-1.0, 1.0], size=(20, 1))
    position = rng.normal(0.0, 1.0, (20, 3))
    matrices = poses_to_matrices(position, quaternion)
    back_position, back_quaternion = matrices_to_poses(matrices)
    np.testing.assert_allclose(back_position, position, atol=1e-12)
    assert np.all(np.sum(back_quaternion[1:] * back_quaternion[:-1], axis=1) >= 0.0)
    assert back_quaternion[0, 3] >= 0.0
    assert rotation_angle_rad(poses_to_matrices(position, back_quaternion), matrices).max() < 1e-7
    flipped = sign_continuous(quaternion)
    np.testing.assert_allclose(np.abs(np.sum(flipped * quaternion, axis=1)), 1.0, atol=1e-12)


def test_rotation_angle_is_accurate_near_zero():
    small = transform((0.0, 0.0, 0.0), (1e-9, 0.0, 0.0))
    assert abs(float(rotation_angle_rad(small, np.eye(4))) - 1e-9) < 1e-15
    half = transform((0.0, 0.0, 0.0), (0.0, 0.0, 2.0))
    assert abs(float(rotation_angle_rad(half, np.eye(4))) - 2.0) < 1e-12
