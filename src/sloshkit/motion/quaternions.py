"""Unit-quaternion helpers (scalar-last x, y, z, w; container -> world), vectorised in numpy.

Every function takes arrays of quaternions with the components on the last axis (``(..., 4)``)
and broadcasts over the leading axes. The product is Hamilton's: ``hamilton_product(a, b)`` is
the rotation b followed by a (R(a b) = R(a) R(b)), as in scipy's ``Rotation``.

References
----------
J. Diebel, "Representing attitude: Euler angles, unit quaternions, and rotation vectors",
Stanford University (2006), eqs. 109 and 125.
J. Solà, "Quaternion kinematics for the error-state Kalman filter", arXiv:1711.02508 (2017),
§1.2 (product, conjugate), §1.3 (exponential and logarithm maps), §2.4 (rotating vectors).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]


def sign_continuous(quaternion_xyzw: ArrayLike) -> FloatArray:
    """Flip quaternion signs so that consecutive quaternions have a non-negative dot product.

    The first quaternion is made to have w >= 0. q and -q are the same rotation; continuity is
    needed before any interpolation or differentiation of the components.

    Parameters
    ----------
    quaternion_xyzw : array (N, 4)
        Quaternions, scalar last.

    Returns
    -------
    numpy.ndarray
        A copy with signs flipped where needed.

    Examples
    --------
    >>> sign_continuous([[0, 0, 0, -1.0], [0, 0, 0, 1.0]]).tolist()
    [[-0.0, -0.0, -0.0, 1.0], [0.0, 0.0, 0.0, 1.0]]
    >>> sign_continuous(np.empty((0, 4))).shape
    (0, 4)
    """
    q = np.array(quaternion_xyzw, dtype=float, copy=True)
    if q.shape[0] and q[0, 3] < 0.0:
        q[0] = -q[0]
    dots = np.einsum("ij,ij->i", q[1:], q[:-1])
    flips = np.cumsum(dots < 0.0) % 2 == 1
    q[1:][flips] = -q[1:][flips]
    return q


def quaternion_matrix(quaternion_xyzw: ArrayLike) -> FloatArray:
    """Rotation matrices (M, 3, 3) of unit quaternions (x, y, z, w).

    Same result as `scipy.spatial.transform.Rotation.as_matrix` (Diebel 2006 eq. 125), in plain
    vectorised numpy (faster for long trajectories).

    Parameters
    ----------
    quaternion_xyzw : array (..., 4)
        Unit quaternions, scalar last.

    Returns
    -------
    numpy.ndarray
        Matrices (..., 3, 3) rotating container coordinates into world coordinates.

    Examples
    --------
    >>> quaternion_matrix([0.0, 0.0, 0.0, 1.0]).tolist()
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    q = np.asarray(quaternion_xyzw, dtype=float)
    x, y, z, w = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    out = np.empty((*q.shape[:-1], 3, 3))
    out[..., 0, 0] = 1 - 2 * (y * y + z * z)
    out[..., 0, 1] = 2 * (x * y - z * w)
    out[..., 0, 2] = 2 * (x * z + y * w)
    out[..., 1, 0] = 2 * (x * y + z * w)
    out[..., 1, 1] = 1 - 2 * (x * x + z * z)
    out[..., 1, 2] = 2 * (y * z - x * w)
    out[..., 2, 0] = 2 * (x * z - y * w)
    out[..., 2, 1] = 2 * (y * z + x * w)
    out[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return out


def quaternion_rates(
    q: FloatArray, q_dot: FloatArray, q_ddot: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Body angular velocity 2 vec(q* q') and acceleration 2 vec(q* q''), scaled by 1/|q|^2.

    Quaternion kinematics q' = q (0, omega_b) / 2 (Diebel 2006 eq. 109); differentiating once
    more, vec(q* q'') = omega_b' / 2 for a unit quaternion.

    Parameters
    ----------
    q, q_dot, q_ddot : arrays (N, 4)
        Quaternion components and their first and second time derivatives.

    Returns
    -------
    tuple of numpy.ndarray
        (omega_b [rad/s], omega_b' [rad/s^2]), each (N, 3), in the body frame.

    Examples
    --------
    >>> import numpy as np
    >>> q = np.array([[0.0, 0.0, 0.0, 1.0]])
    >>> rates = quaternion_rates(q, np.array([[0.0, 0.0, 0.5, 0.0]]), np.zeros((1, 4)))
    >>> rates[0].tolist()
    [[0.0, 0.0, 1.0]]
    """

    def vec_conj_product(a: FloatArray, b: FloatArray) -> FloatArray:
        """vec(conj(a) b) = a_w b_v - b_w a_v - a_v x b_v, component by component."""
        ax, ay, az, aw = a[:, 0], a[:, 1], a[:, 2], a[:, 3]
        bx, by, bz, bw = b[:, 0], b[:, 1], b[:, 2], b[:, 3]
        return np.column_stack(
            (
                aw * bx - bw * ax - (ay * bz - az * by),
                aw * by - bw * ay - (az * bx - ax * bz),
                aw * bz - bw * az - (ax * by - ay * bx),
            )
        )

    scale = 2.0 / np.einsum("ij,ij->i", q, q)[:, None]
    return scale * vec_conj_product(q, q_dot), scale * vec_conj_product(q, q_ddot)


def hamilton_product(a: ArrayLike, b: ArrayLike) -> FloatArray:
    """Hamilton products a b of quaternions (scalar last): the rotation b, then a.

    (a_v, a_w)(b_v, b_w) = (a_w b_v + b_w a_v + a_v x b_v, a_w b_w - a_v . b_v) (Solà 2017 §1.2).

    Parameters
    ----------
    a, b : array (..., 4)
        Quaternions, scalar last (broadcast against each other).

    Returns
    -------
    numpy.ndarray
        The products (..., 4).

    Examples
    --------
    >>> half = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]  # 90 deg about z
    >>> np.round(hamilton_product(half, half), 12).tolist()  # 180 deg about z
    [0.0, 0.0, 1.0, 0.0]
    """
    ax, ay, az, aw = np.moveaxis(np.asarray(a, dtype=float), -1, 0)
    bx, by, bz, bw = np.moveaxis(np.asarray(b, dtype=float), -1, 0)
    return np.stack(
        (
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ),
        axis=-1,
    )


def conjugate(quaternion_xyzw: ArrayLike) -> FloatArray:
    """Conjugates (-x, -y, -z, w): the inverse rotations of unit quaternions (Solà 2017 §1.2).

    Parameters
    ----------
    quaternion_xyzw : array (..., 4)
        Quaternions, scalar last.

    Returns
    -------
    numpy.ndarray
        The conjugates (..., 4).

    Examples
    --------
    >>> conjugate([0.1, 0.2, 0.3, 0.9]).tolist()
    [-0.1, -0.2, -0.3, 0.9]
    """
    return np.asarray(np.asarray(quaternion_xyzw, dtype=float) * np.array([-1.0, -1.0, -1.0, 1.0]))


def rotation_vector(quaternion_xyzw: ArrayLike) -> FloatArray:
    """Rotation vectors (axis times angle, angle in [0, pi]) of unit quaternions: the
    logarithm map 2 atan2(|q_v|, q_w) q_v/|q_v| (Solà 2017 §1.3), with q and -q alike.

    Parameters
    ----------
    quaternion_xyzw : array (..., 4)
        Unit quaternions, scalar last.

    Returns
    -------
    numpy.ndarray
        Rotation vectors (..., 3) [rad].

    Examples
    --------
    >>> q = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]  # 90 deg about z
    >>> np.round(rotation_vector(q) / (np.pi / 2), 12).tolist()
    [0.0, 0.0, 1.0]
    >>> float(np.linalg.norm(rotation_vector([0.0, 0.0, 0.0, -1.0])))  # -q is q
    0.0
    """
    q = np.asarray(quaternion_xyzw, dtype=float)
    q = np.where(q[..., 3:4] < 0.0, -q, q)
    sine = np.linalg.norm(q[..., :3], axis=-1)
    angle = 2.0 * np.arctan2(sine, q[..., 3])
    # angle / sin(angle / 2) -> 2 for small angles (series 2 + angle^2 / 12)
    scale = np.where(sine > 1e-6, angle / np.maximum(sine, 1e-300), 2.0 + angle**2 / 12.0)
    return np.asarray(q[..., :3] * scale[..., None])


def rotate(quaternion_xyzw: ArrayLike, vectors: ArrayLike) -> FloatArray:
    """R(q) v: vectors in container coordinates turned into world coordinates.

    v' = v + 2 w (q_v x v) + 2 q_v x (q_v x v), the expansion of q (v, 0) q* for a unit
    quaternion (Solà 2017 §2.4).

    Parameters
    ----------
    quaternion_xyzw : array (..., 4)
        Unit quaternions, scalar last.
    vectors : array (..., 3)
        Vectors (broadcast against the quaternions).

    Returns
    -------
    numpy.ndarray
        The rotated vectors (..., 3).

    Examples
    --------
    >>> q = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]  # 90 deg about z
    >>> np.round(rotate(q, [1.0, 0.0, 0.0]), 12).tolist()
    [0.0, 1.0, 0.0]
    """
    q = np.asarray(quaternion_xyzw, dtype=float)
    v = np.asarray(vectors, dtype=float)
    u, w = q[..., :3], q[..., 3:4]
    t = 2.0 * np.cross(u, v)
    return np.asarray(v + w * t + np.cross(u, t))


def rotate_inverse(quaternion_xyzw: ArrayLike, vectors: ArrayLike) -> FloatArray:
    """R(q)^T v: world vectors in container coordinates (`rotate` by the conjugate).

    Parameters
    ----------
    quaternion_xyzw : array (..., 4)
        Unit quaternions, scalar last.
    vectors : array (..., 3)
        Vectors (broadcast against the quaternions).

    Returns
    -------
    numpy.ndarray
        The vectors in the rotated frame (..., 3).

    Examples
    --------
    >>> q = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]  # 90 deg about z
    >>> np.round(rotate_inverse(q, [0.0, 1.0, 0.0]), 12).tolist()
    [1.0, 0.0, 0.0]
    """
    return rotate(conjugate(quaternion_xyzw), vectors)


def rotated_z_axis(quaternion_xyzw: ArrayLike) -> FloatArray:
    """R(q) e_z: the container's axis in world coordinates (the third column of
    `quaternion_matrix`).

    Parameters
    ----------
    quaternion_xyzw : array (..., 4)
        Unit quaternions, scalar last.

    Returns
    -------
    numpy.ndarray
        Unit vectors (..., 3).

    Examples
    --------
    >>> q = [np.sin(np.pi / 4), 0.0, 0.0, np.cos(np.pi / 4)]  # 90 deg about x
    >>> np.round(rotated_z_axis(q), 12).tolist()
    [0.0, -1.0, 0.0]
    """
    x, y, z, w = np.moveaxis(np.asarray(quaternion_xyzw, dtype=float), -1, 0)
    return np.stack((2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)), axis=-1)
