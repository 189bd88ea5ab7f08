"""The quaternion helpers of `sloshkit.motion.quaternions` against scipy's ``Rotation`` (an
independent implementation), on random rotations, and their vectorised shapes."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sloshkit.motion.quaternions import (
    conjugate,
    hamilton_product,
    quaternion_matrix,
    rotate,
    rotate_inverse,
    rotated_z_axis,
    rotation_vector,
    sign_continuous,
)

RNG = np.random.default_rng(26)
FIRST = Rotation.random(200, random_state=RNG)
SECOND = Rotation.random(200, random_state=RNG)
VECTORS = RNG.normal(size=(200, 3))


def test_hamilton_product_composes_as_scipy_does():
    product = hamilton_product(FIRST.as_quat(), SECOND.as_quat())
    expected = (FIRST * SECOND).as_quat()
    # q and -q are one rotation: compare the rotations, and the components up to sign
    assert np.allclose(quaternion_matrix(product), (FIRST * SECOND).as_matrix(), atol=1e-12)
    assert np.allclose(np.abs(np.einsum("ij,ij->i", product, expected)), 1.0, atol=1e-12)


def test_the_conjugate_is_the_inverse_rotation():
    q = FIRST.as_quat()
    identity = hamilton_product(q, conjugate(q))
    assert np.allclose(identity, [0.0, 0.0, 0.0, 1.0], atol=1e-12)
    assert np.allclose(quaternion_matrix(conjugate(q)), FIRST.inv().as_matrix(), atol=1e-12)


def test_rotation_vector_matches_scipy_for_q_and_minus_q():
    q = FIRST.as_quat()
    expected = FIRST.as_rotvec()
    assert np.allclose(rotation_vector(q), expected, atol=1e-10)
    assert np.allclose(rotation_vector(-q), expected, atol=1e-10)


@pytest.mark.parametrize("angle", [0.0, 1e-9, 1e-7, 1e-5, 1e-3])
def test_rotation_vector_is_accurate_near_the_identity(angle):
    axis = np.array([0.6, -0.8, 0.0])
    q = Rotation.from_rotvec(angle * axis).as_quat()
    assert np.allclose(rotation_vector(q), angle * axis, rtol=1e-9, atol=1e-18)


def test_rotate_and_its_inverse_match_the_matrices():
    q = FIRST.as_quat()
    turned = rotate(q, VECTORS)
    assert np.allclose(turned, FIRST.apply(VECTORS), atol=1e-12)
    assert np.allclose(rotate_inverse(q, turned), VECTORS, atol=1e-12)
    assert np.allclose(rotate_inverse(q, VECTORS), FIRST.apply(VECTORS, inverse=True), atol=1e-12)
    assert np.allclose(rotated_z_axis(q), FIRST.as_matrix()[:, :, 2], atol=1e-12)


def test_helpers_broadcast_over_leading_axes():
    q = FIRST.as_quat().reshape(10, 20, 4)
    assert hamilton_product(q, q[:1]).shape == (10, 20, 4)
    assert rotate(q, np.array([0.0, 0.0, 1.0])).shape == (10, 20, 3)
    assert rotation_vector(q).shape == (10, 20, 3)
    assert np.allclose(rotate(q, [0.0, 0.0, 1.0]), rotated_z_axis(q), atol=1e-12)


def test_sign_continuity_keeps_the_rotations_and_removes_the_flips():
    q = FIRST.as_quat()
    flipped = q * np.where(RNG.random(200) < 0.5, -1.0, 1.0)[:, None]
    smooth = sign_continuous(flipped)
    assert np.allclose(quaternion_matrix(smooth), FIRST.as_matrix(), atol=1e-12)
    path = Rotation.from_rotvec(np.linspace(0.0, 6.0, 300)[:, None] * [0.0, 0.0, 1.0]).as_quat()
    noisy = path * np.where(RNG.random(300) < 0.3, -1.0, 1.0)[:, None]
    repaired = sign_continuous(noisy)
    assert repaired[0, 3] >= 0.0
    assert np.all(np.einsum("ij,ij->i", repaired[1:], repaired[:-1]) > 0.0)
