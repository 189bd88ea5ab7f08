"""Velocities and accelerations of a sampled rigid-body pose trajectory, without amplifying noise.

Method
------
Poses are first put on a uniform grid (cubic spline / `scipy.spatial.transform.RotationSpline`
when the grid differs from the samples), padded at both ends with the held first and last
pose (the container rests before and after), and then differentiated with a Savitzky-Golay
filter (local least-squares polynomial of degree 4, ``scipy.signal.savgol_filter``): positions
give velocity and acceleration, the sign-continuous quaternion components give q' and q''.
The filter is exact for polynomials up to degree 4 over its window and is a low-pass with a
3-dB cut-off of about f_c = (N + 1) / (3.2 M - 4.6) * f_Nyquist for degree N and half-width
M (Schafer 2011, eq. 11); the half-width is chosen from the requested ``cutoff_hz``
(default 25 Hz: above the slosh modes and robot motion content of a few hertz, well below a
500 Hz controller's Nyquist frequency). With ``cutoff_hz=None`` the derivatives of an
interpolating quintic spline are used instead (exact data, no smoothing).

Angular velocity and acceleration in the body (container) frame follow from the quaternion
kinematics omega_b = 2 vec(q* q') and omega_b' = 2 vec(q* q'') (for |q| = 1; Diebel 2006
eq. 109), world components by omega_w = R omega_b, omega_w' = R omega_b'. A body-fixed point
r_b has a = a_O + alpha x r + omega x (omega x r) with r = R r_b.

References
----------
- A. Savitzky, M. J. E. Golay, Anal. Chem. 36 (1964) 1627. doi:10.1021/ac60214a047
- R. W. Schafer, "What is a Savitzky-Golay filter?", IEEE Signal Process. Mag. 28 (2011) 111.
  doi:10.1109/MSP.2011.941097
- J. Diebel, "Representing attitude: Euler angles, unit quaternions, and rotation vectors",
  Stanford University (2006).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import make_interp_spline
from scipy.signal import savgol_filter
from scipy.spatial.transform import Rotation

from sloshkit.errors import InputError, require_positive
from sloshkit.motion.quaternions import quaternion_matrix, quaternion_rates, sign_continuous

FloatArray = NDArray[np.float64]


class _Poses(Protocol):
    """What the kinematics read of sampled poses (`sloshkit.motion.poses.PoseTrajectory` is
    one). Written as a protocol so that this module, which `PoseTrajectory.kinematics` uses,
    does not import the trajectory's module back."""

    @property
    def time_s(self) -> FloatArray: ...

    @property
    def position_m(self) -> FloatArray: ...

    @property
    def quaternion_xyzw(self) -> FloatArray: ...

    @property
    def sample_period_s(self) -> float: ...

    @property
    def is_uniform(self) -> bool: ...

    def resample(self, sample_period_s: float) -> _Poses: ...


#: Default 3-dB cut-off of the differentiating filter [Hz].
DEFAULT_CUTOFF_HZ = 25.0
#: Degree of the Savitzky-Golay polynomial.
SAVGOL_DEGREE = 4


@dataclass(frozen=True, eq=False)
class PoseKinematics:
    """Smoothed pose, velocities and accelerations on a uniform time grid (SI).

    The time derivatives of a `sloshkit.motion.poses.PoseTrajectory` (`pose_kinematics`, or
    `PoseTrajectory.kinematics`), what the 3-D drive (`sloshkit.sim.spatial_drive`) and the
    CFD excitation read; the poses themselves stay in the trajectory.

    Attributes
    ----------
    time_s : uniform times (M,) [s]
    position_m, velocity_m_s, acceleration_m_s2 : bottom centre, world frame (M, 3)
    quaternion_xyzw : smoothed unit quaternions, container -> world (M, 4)
    angular_velocity_body_rad_s, angular_acceleration_body_rad_s2 : container frame (M, 3)
    cutoff_hz : the filter's approximate 3-dB cut-off [Hz] (``inf`` without smoothing)
    window : Savitzky-Golay window length in samples (0 without smoothing)

    Examples
    --------
    >>> from sloshkit.motion.laws import quintic
    >>> from sloshkit.motion.pose_builders import poses_from_law
    >>> poses = poses_from_law(quintic(0.1, 0.5), sample_period_s=0.002)
    >>> kinematics = pose_kinematics(poses, cutoff_hz=None)
    >>> round(float(kinematics.velocity_m_s[:, 0].max()), 4)  # 15/8 d/T for a quintic
    0.375
    """

    time_s: FloatArray
    position_m: FloatArray
    velocity_m_s: FloatArray
    acceleration_m_s2: FloatArray
    quaternion_xyzw: FloatArray
    angular_velocity_body_rad_s: FloatArray
    angular_acceleration_body_rad_s2: FloatArray
    cutoff_hz: float
    window: int

    @property
    def rotation(self) -> Rotation:
        """Orientations (container -> world)."""
        return Rotation.from_quat(self.quaternion_xyzw)

    @cached_property
    def rotation_matrix(self) -> FloatArray:
        """Rotation matrices (M, 3, 3), columns = container axes in world coordinates."""
        return quaternion_matrix(self.quaternion_xyzw)

    def to_world(self, body_vectors: ArrayLike) -> FloatArray:
        """Body-frame vectors (M, 3) or one (3,) vector in world coordinates (M, 3)."""
        vectors = np.broadcast_to(np.asarray(body_vectors, dtype=float), self.position_m.shape)
        return np.asarray(np.einsum("kij,kj->ki", self.rotation_matrix, vectors), dtype=float)

    @cached_property
    def angular_velocity_world_rad_s(self) -> FloatArray:
        """Angular velocity in world coordinates (M, 3) [rad/s]."""
        return self.to_world(self.angular_velocity_body_rad_s)

    @cached_property
    def angular_acceleration_world_rad_s2(self) -> FloatArray:
        """Angular acceleration in world coordinates (M, 3) [rad/s^2]."""
        return self.to_world(self.angular_acceleration_body_rad_s2)

    def point_velocity(self, offset_body_m: ArrayLike) -> FloatArray:
        """World velocity of the body-fixed point ``offset_body_m`` (container frame) [m/s]."""
        arm = self.to_world(np.asarray(offset_body_m, dtype=float).reshape(3))
        return np.asarray(
            self.velocity_m_s + np.cross(self.angular_velocity_world_rad_s, arm), dtype=float
        )

    def point_acceleration(self, offset_body_m: ArrayLike) -> FloatArray:
        """World acceleration of a body-fixed point: a_O + alpha x r + omega x (omega x r)."""
        arm = self.to_world(np.asarray(offset_body_m, dtype=float).reshape(3))
        omega = self.angular_velocity_world_rad_s
        alpha = self.angular_acceleration_world_rad_s2
        return np.asarray(
            self.acceleration_m_s2 + np.cross(alpha, arm) + np.cross(omega, np.cross(omega, arm)),
            dtype=float,
        )


def savgol_half_width(cutoff_hz: float, sample_period_s: float, degree: int = SAVGOL_DEGREE) -> int:
    """Half-width M of the Savitzky-Golay window for a 3-dB cut-off ``cutoff_hz``.

    Inverts f_c / f_Nyquist = (N + 1) / (3.2 M - 4.6) (Schafer 2011, eq. 11); at least
    degree/2 + 1 so that the window is longer than the polynomial.

    Parameters
    ----------
    cutoff_hz : float
        Wanted 3-dB cut-off [Hz].
    sample_period_s : float
        Sample period [s].
    degree : int
        Polynomial degree N.

    Returns
    -------
    int
        M (the window has 2 M + 1 samples).

    References
    ----------
    Schafer, R. W., What is a Savitzky-Golay filter?, IEEE Signal Process. Mag. 28 (2011) 111,
    doi:10.1109/MSP.2011.941097.

    Examples
    --------
    >>> savgol_half_width(25.0, 0.002)
    17
    """
    nyquist = 0.5 / sample_period_s
    ratio = require_positive("cutoff", cutoff_hz, "Hz") / nyquist
    half = round(((degree + 1) / min(ratio, 1.0) + 4.6) / 3.2)
    return int(max(half, degree // 2 + 1))


def pose_kinematics(
    poses: _Poses,
    sample_period_s: float | None = None,
    *,
    cutoff_hz: float | None = DEFAULT_CUTOFF_HZ,
) -> PoseKinematics:
    """Kinematics of ``poses`` on the uniform grid t_0 + k dt up to the last pose.

    Parameters
    ----------
    poses : the sampled poses (container at rest before the first and after the last)
    sample_period_s : grid step dt [s] (default: the poses' median step)
    cutoff_hz : approximate 3-dB cut-off of the Savitzky-Golay differentiator [Hz], or None
        for the derivatives of an interpolating quintic spline (exact data only)

    Returns
    -------
    PoseKinematics

    References
    ----------
    Savitzky & Golay (1964); Schafer (2011); Diebel (2006) — see the module docstring.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.motion.laws import septic
    >>> from sloshkit.motion.pose_builders import poses_from_law
    >>> kin = pose_kinematics(poses_from_law(septic(0.5, 1.0), sample_period_s=0.002))
    >>> bool(abs(kin.acceleration_m_s2[:, 0].max() - septic(0.5, 1.0).peak(2)) < 0.01)
    True
    """
    dt = poses.sample_period_s if sample_period_s is None else float(sample_period_s)
    dt = require_positive("sample_period", dt, "s")
    grid = poses
    if not (poses.is_uniform and abs(poses.sample_period_s - dt) <= 1e-9 * dt):
        grid = poses.resample(dt)
    time = grid.time_s
    count = time.size
    if cutoff_hz is None:
        return _spline_kinematics(grid, dt)
    half = savgol_half_width(cutoff_hz, dt)
    window = 2 * half + 1
    data = np.hstack((grid.position_m, grid.quaternion_xyzw))
    if count < 2:
        raise InputError("poses", count, "need at least 2 samples")
    # mode="nearest" extends the data with the held first and last pose (rest before/after)
    smooth = savgol_filter(data, window, SAVGOL_DEGREE, deriv=0, axis=0, mode="nearest")
    first = savgol_filter(data, window, SAVGOL_DEGREE, deriv=1, delta=dt, axis=0, mode="nearest")
    second = savgol_filter(data, window, SAVGOL_DEGREE, deriv=2, delta=dt, axis=0, mode="nearest")
    omega, alpha = quaternion_rates(smooth[:, 3:], first[:, 3:], second[:, 3:])
    quaternion_out = smooth[:, 3:] / np.linalg.norm(smooth[:, 3:], axis=1)[:, None]
    nyquist = 0.5 / dt
    actual = (
        min(nyquist, (SAVGOL_DEGREE + 1) / (3.2 * half - 4.6) * nyquist) if half > 2 else nyquist
    )
    return PoseKinematics(
        time_s=time,
        position_m=np.asarray(smooth[:, :3], dtype=float),
        velocity_m_s=np.asarray(first[:, :3], dtype=float),
        acceleration_m_s2=np.asarray(second[:, :3], dtype=float),
        quaternion_xyzw=sign_continuous(quaternion_out),
        angular_velocity_body_rad_s=omega,
        angular_acceleration_body_rad_s2=alpha,
        cutoff_hz=float(actual),
        window=window,
    )


def _spline_kinematics(grid: _Poses, dt: float) -> PoseKinematics:
    """Derivatives of interpolating quintic splines (positions and quaternion components)."""
    time = grid.time_s
    degree = min(5, time.size - 1)
    if degree % 2 == 0:
        degree -= 1
    data = np.hstack((grid.position_m, grid.quaternion_xyzw))
    spline = make_interp_spline(time, data, k=degree, axis=0)
    smooth = np.asarray(spline(time), dtype=float)
    first = np.asarray(spline(time, 1), dtype=float)
    second = np.asarray(spline(time, 2), dtype=float) if degree >= 2 else np.zeros_like(first)
    omega, alpha = quaternion_rates(smooth[:, 3:], first[:, 3:], second[:, 3:])
    return PoseKinematics(
        time_s=time,
        position_m=smooth[:, :3],
        velocity_m_s=first[:, :3],
        acceleration_m_s2=second[:, :3],
        quaternion_xyzw=sign_continuous(
            smooth[:, 3:] / np.linalg.norm(smooth[:, 3:], axis=1)[:, None]
        ),
        angular_velocity_body_rad_s=omega,
        angular_acceleration_body_rad_s2=alpha,
        cutoff_hz=math.inf,
        window=0,
    )
