"""Unit-quaternion helpers (scalar-last x, y, z, w; container -> world), vectorised in numpy.

References
----------
J. Diebel, "Representing attitude: Euler angles, unit quaternions, and rotation vectors",
Stanford University (2006), eqs. 109 and 125.
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
