"""Rigid transforms for export: poses as 4x4 homogeneous matrices, quaternions scalar last.

Conventions (the pose-file conventions of sloshkit): positions in metres; a pose ``T_a_b`` maps
coordinates in frame b to frame a (``p_a = R p_b + t``); quaternions (x, y, z, w) with the scalar
last, rotating the container frame into the world frame (scipy's convention); roll-pitch-yaw
angles are fixed-axis x-y-z rotations, R = Rz(yaw) Ry(pitch) Rx(roll), as in URDF ``rpy``
(ROS REP 103). Quaternions and rotation algebra come from `scipy.spatial.transform.Rotation`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.quaternions import sign_continuous

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Mounting:
    """Where the path sits on the robot: the container in the flange, the path in the base.

    Attributes
    ----------
    tool_offset_m : container bottom centre in the flange frame (x, y, z) [m]
    tool_rpy_rad : container frame's orientation in the flange frame (roll, pitch, yaw) [rad]
    base_xyz_m : path frame origin in the robot base frame [m]
    base_rpy_rad : path frame orientation in the robot base frame (roll, pitch, yaw) [rad]

    The default hangs the container 100 mm below the flange with its axis opposite to the
    flange's z axis (a rotation of pi about the flange x axis), and takes the path's own
    coordinates as base coordinates.

    Examples
    --------
    >>> Mounting().flange_to_container[:3, 3].round(6).tolist()
    [0.0, 0.0, 0.1]
    """

    tool_offset_m: tuple[float, float, float] = (0.0, 0.0, 0.1)
    tool_rpy_rad: tuple[float, float, float] = (np.pi, 0.0, 0.0)
    base_xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    base_rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def flange_to_container(self) -> FloatArray:
        """T_flange_container (4x4)."""
        return transform(self.tool_offset_m, self.tool_rpy_rad)

    @property
    def base_to_path(self) -> FloatArray:
        """T_base_path (4x4)."""
        return transform(self.base_xyz_m, self.base_rpy_rad)

    def to_dict(self) -> dict[str, list[float]]:
        """The mounting with unit-suffixed keys (metres, radians)."""
        return {
            "tool_offset_m": list(self.tool_offset_m),
            "tool_rotation_rpy_rad": list(self.tool_rpy_rad),
            "base_position_m": list(self.base_xyz_m),
            "base_rotation_rpy_rad": list(self.base_rpy_rad),
        }


def transform(xyz: Sequence[float], rpy: Sequence[float]) -> FloatArray:
    """4x4 homogeneous transform from a translation [m] and roll-pitch-yaw angles [rad].

    Parameters
    ----------
    xyz : translation (x, y, z) [m]
    rpy : fixed-axis x-y-z angles (roll, pitch, yaw) [rad], R = Rz(yaw) Ry(pitch) Rx(roll)

    Returns
    -------
    numpy.ndarray
        The 4x4 matrix.

    References
    ----------
    ROS REP 103, "Standard Units of Measure and Coordinate Conventions" (rpy convention).

    Examples
    --------
    >>> transform((0.0, 0.0, 0.1), (np.pi, 0.0, 0.0)).round(6)[:3, 2]
    array([ 0., -0., -1.])
    """
    from scipy.spatial.transform import Rotation  # here: a plan that exports nothing needs none

    matrix = np.eye(4)
    matrix[:3, :3] = Rotation.from_euler("xyz", np.asarray(rpy, dtype=float)).as_matrix()
    matrix[:3, 3] = np.asarray(xyz, dtype=float)
    return matrix


def poses_to_matrices(position_m: FloatArray, quaternion_xyzw: FloatArray) -> FloatArray:
    """(N, 4, 4) transforms from positions (N, 3) [m] and quaternions (N, 4), scalar last.

    Parameters
    ----------
    position_m : numpy.ndarray
        Positions (N, 3) [m].
    quaternion_xyzw : numpy.ndarray
        Unit quaternions (N, 4), scalar last.

    Returns
    -------
    numpy.ndarray
        (N, 4, 4).

    Examples
    --------
    A quarter turn about z, then back to poses:

    >>> import numpy as np
    >>> q = np.array([[0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)]])
    >>> matrix = poses_to_matrices(np.array([[1.0, 2.0, 3.0]]), q)
    >>> matrix[0, :3, 0].round(6).tolist(), matrix[0, :3, 3].tolist()
    ([0.0, 1.0, 0.0], [1.0, 2.0, 3.0])
    >>> bool(np.allclose(matrices_to_poses(matrix)[1], q))
    True
    """
    from scipy.spatial.transform import Rotation

    count = position_m.shape[0]
    matrices = np.zeros((count, 4, 4))
    matrices[:, :3, :3] = Rotation.from_quat(quaternion_xyzw).as_matrix()
    matrices[:, :3, 3] = position_m
    matrices[:, 3, 3] = 1.0
    return matrices


def matrices_to_poses(matrices: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Positions (N, 3) [m] and unit quaternions (N, 4, scalar last, w >= 0 at the first
    sample and sign-continuous after it) from (N, 4, 4) transforms.

    Parameters
    ----------
    matrices : numpy.ndarray
        Rigid transforms (N, 4, 4).

    Returns
    -------
    tuple of numpy.ndarray
        Positions (N, 3) [m] and quaternions (N, 4).

    Examples
    --------
    >>> import numpy as np
    >>> position, quaternion = matrices_to_poses(np.eye(4)[None])
    >>> position.tolist(), quaternion.tolist()
    ([[0.0, 0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]])
    """
    from scipy.spatial.transform import Rotation

    quaternion = Rotation.from_matrix(matrices[:, :3, :3]).as_quat()
    return np.array(matrices[:, :3, 3]), sign_continuous(quaternion)


def invert(matrix: FloatArray) -> FloatArray:
    """Inverse of a rigid transform (4x4, or stacked (N, 4, 4)).

    Parameters
    ----------
    matrix : numpy.ndarray
        Rigid transform(s) [R p; 0 1].

    Returns
    -------
    numpy.ndarray
        [R^T -R^T p; 0 1].

    Examples
    --------
    >>> import numpy as np
    >>> shift = np.eye(4)
    >>> shift[:3, 3] = [1.0, 2.0, 3.0]
    >>> invert(shift)[:3, 3].tolist()
    [-1.0, -2.0, -3.0]
    """
    rotation = np.swapaxes(matrix[..., :3, :3], -1, -2)
    inverse = np.zeros_like(matrix)
    inverse[..., :3, :3] = rotation
    inverse[..., :3, 3] = -np.einsum("...ij,...j->...i", rotation, matrix[..., :3, 3])
    inverse[..., 3, 3] = 1.0
    return inverse


def rotation_angle_rad(matrices_a: FloatArray, matrices_b: FloatArray) -> FloatArray:
    """Angle of the rotation between two stacks of transforms or rotations [rad].

    Parameters
    ----------
    matrices_a, matrices_b : numpy.ndarray
        (N, 4, 4) transforms or (N, 3, 3) rotations.

    Returns
    -------
    numpy.ndarray
        (N,) angles in [0, pi].

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> turned = Rotation.from_euler("z", [0.3]).as_matrix()
    >>> rotation_angle_rad(np.eye(3)[None], turned).round(9).tolist()
    [0.3]
    """
    relative = np.einsum("...ji,...jk->...ik", matrices_a[..., :3, :3], matrices_b[..., :3, :3])
    trace = np.clip((np.trace(relative, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    # arccos loses precision near 0: use the skew part as well (atan2 of sin and cos).
    skew = np.stack(
        [
            relative[..., 2, 1] - relative[..., 1, 2],
            relative[..., 0, 2] - relative[..., 2, 0],
            relative[..., 1, 0] - relative[..., 0, 1],
        ],
        axis=-1,
    )
    return np.asarray(np.arctan2(np.linalg.norm(skew, axis=-1) / 2.0, trace), dtype=float)
