"""The drive of the spatial slosh pendulums: the specific force at each mode's hinge and the
tilt rates, in the container's non-spinning frame N (the model: `sloshkit.sim.spatial`).

f = kappa_n g_vec - a_hinge, a_hinge = a_O + alpha x r_n + omega x (omega x r_n), with
r_n = H_n times the container axis and kappa_n = omega_n^2 L_n / g (Abramson, NASA SP-106
(1966) ch. 6; Dodge, SwRI (2000) §3); N tilts with the container axis and does not spin about
it (an ideal liquid is not dragged by rotation about the axis of an axisymmetric container).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sloshkit.model.modal import SloshModel
from sloshkit.motion.pose_kinematics import PoseKinematics

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class SpatialDrive:
    """The drive of the slosh pendulums in the container's non-spinning frame N.

    Attributes
    ----------
    time_s : (M,) [s]
    specific_force_m_s2 : (modes + 1, M, 3) kappa_n g_vec - a_hinge in N for each mode; the
        last row is g_vec - a at the free-surface centre (quasi-static correction)
    tilt_rate_rad_s : (M, 2) lateral angular velocity (p, q) of N in N
    tilt_acceleration_rad_s2 : (M, 2) its derivative
    spin_angle_rad : (M,) phi, the container's rotation about its own axis relative to N
    kinematics : the pose kinematics used
    rest_force_m_s2 : (modes + 1, 3) kappa_n g_vec in the container frame of the first pose:
        the drive of the container resting before the motion (initial equilibrium)

    Examples
    --------
    A container at rest feels gravity only:

    >>> import numpy as np
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.motion.pose_kinematics import pose_kinematics
    >>> from sloshkit.motion.poses import poses_from_rpy
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, 1)
    >>> rest = poses_from_rpy(np.linspace(0, 0.1, 11), np.zeros((11, 3)), *np.zeros((3, 11)))
    >>> drive = spatial_drive(model, pose_kinematics(rest, cutoff_hz=None))
    >>> drive.specific_force_m_s2.shape, drive.specific_force_m_s2[-1, 0].round(2).tolist()
    ((2, 11, 3), [0.0, 0.0, -9.81])
    """

    time_s: FloatArray
    specific_force_m_s2: FloatArray
    tilt_rate_rad_s: FloatArray
    tilt_acceleration_rad_s2: FloatArray
    spin_angle_rad: FloatArray
    kinematics: PoseKinematics
    rest_force_m_s2: FloatArray


def _cross(a: FloatArray, b: FloatArray) -> FloatArray:
    """Row-wise cross product of (M, 3) arrays (faster than numpy.cross for 3-vectors)."""
    return np.column_stack(
        (
            a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1],
            a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
            a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0],
        )
    )


def spatial_drive(model: SloshModel, kinematics: PoseKinematics) -> SpatialDrive:
    """Specific force at each mode's hinge and the tilt rates, in the non-spinning frame.

    Parameters
    ----------
    model : equivalent model (pivot heights, L_n, omega_n)
    kinematics : `PoseKinematics` of the container's bottom centre

    Returns
    -------
    SpatialDrive

    References
    ----------
    Goldstein, *Classical Mechanics*, 3rd ed. (2002) §4.9-4.10 (rigid-body point
    accelerations, rotating frames).

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.motion.laws import quintic
    >>> from sloshkit.motion.pose_builders import poses_from_law
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1)
    >>> drive = spatial_drive(model, poses_from_law(quintic(0.1, 1.0)).kinematics())
    >>> round(float(drive.specific_force_m_s2[0, 0, 2]), 2)
    -9.81
    """
    g = model.gravity_m_s2
    time = kinematics.time_s
    matrix = kinematics.rotation_matrix  # (M, 3, 3) container -> world
    axis = matrix[:, :, 2]
    omega_w = kinematics.angular_velocity_world_rad_s
    alpha_w = kinematics.angular_acceleration_world_rad_s2
    omega_b = kinematics.angular_velocity_body_rad_s
    alpha_b = kinematics.angular_acceleration_body_rad_s2
    # lever per unit height: alpha x e + omega x (omega x e)
    lever = _cross(alpha_w, axis) + _cross(omega_w, _cross(omega_w, axis))
    spin = np.concatenate(
        ([0.0], np.cumsum(0.5 * (omega_b[1:, 2] + omega_b[:-1, 2]) * np.diff(time)))
    )
    cos_s, sin_s = np.cos(spin), np.sin(spin)

    def to_n(vectors_world: FloatArray) -> FloatArray:
        body = np.einsum("kji,kj->ki", matrix, vectors_world)
        return np.stack(
            (
                cos_s * body[:, 0] - sin_s * body[:, 1],
                sin_s * body[:, 0] + cos_s * body[:, 1],
                body[:, 2],
            ),
            axis=-1,
        )

    heights = [mode.pivot_height_m for mode in model.modes] + [model.fill_height_m]
    kappas = [mode.omega_rad_s**2 * mode.length_m / g for mode in model.modes] + [1.0]
    forces = np.empty((len(heights), time.size, 3))
    for row, (height, kappa) in enumerate(zip(heights, kappas, strict=True)):
        hinge = kinematics.acceleration_m_s2 + height * lever
        specific = -hinge
        specific[:, 2] -= kappa * g
        forces[row] = to_n(specific)
    rate_n = np.stack(
        (
            cos_s * omega_b[:, 0] - sin_s * omega_b[:, 1],
            sin_s * omega_b[:, 0] + cos_s * omega_b[:, 1],
        ),
        -1,
    )
    accel_rot = np.stack(
        (
            cos_s * alpha_b[:, 0] - sin_s * alpha_b[:, 1],
            sin_s * alpha_b[:, 0] + cos_s * alpha_b[:, 1],
        ),
        -1,
    )
    spin_rate = omega_b[:, 2:3]
    tilt_accel = accel_rot + spin_rate * np.stack((-rate_n[:, 1], rate_n[:, 0]), -1)
    gravity_body = matrix[0].T @ np.array([0.0, 0.0, -g])
    rest = np.outer(kappas, gravity_body)
    return SpatialDrive(time, forces, rate_n, tilt_accel, spin, kinematics, rest)
