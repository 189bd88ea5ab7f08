"""Tilt compensation: incline the container so that its axis follows the apparent gravity.

In the container's accelerating frame the liquid feels the specific force f = g - a. If the
container axis is kept anti-parallel to f, the equilibrium free surface stays normal to the
axis and the liquid has nothing to slosh towards; a constant horizontal acceleration a needs
the tilt atan(a / g) (Feddema, Dohrmann, Parker, Robinett, Romero & Schmitt, "Control for
slosh-free motion of an open container", IEEE Control Systems 17(1) (1997) 29-36,
doi:10.1109/37.569711; Soprani et al., slosh-free trajectories with position and orientation,
AntiSloshing project, University of Bologna).

Here the acceleration is that of the first mode's bob rest point (where the liquid's sloshing
mass sits), from the sampled export, smoothed by a zero-phase Gaussian filter so that the tilt
rate stays continuous; the tilt is clipped to ``max_tilt``. The rotation is the smallest one
that carries the path's own container axis onto the compensating axis, about a centre on the
axis at ``tilt_centre_height_m`` above the container bottom (the bottom by default), which keeps
that point on the path. The smoothing blurs the acceleration beyond the ends of the move, so the
export gets 3 standard deviations of rest before and after the move, during which the container
tilts in and back out: it starts and ends upright at rest. (Feeding the tilted bob point's
acceleration back into the tilt was tried and is unstable: the tilt would then depend on its own
second derivative.)
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.ndimage import gaussian_filter1d
from scipy.spatial.transform import Rotation

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.problem import GRAVITY, second_difference

FloatArray = NDArray[np.float64]
#: Standard deviation of the Gaussian smoothing of the acceleration [s].
SMOOTHING_S = 0.03


def compensating_axis(acceleration_m_s2: FloatArray, max_tilt_rad: float) -> FloatArray:
    """Unit container axes anti-parallel to f = g - a, tilted at most ``max_tilt_rad`` from
    vertical (horizontal part scaled down when the limit binds).

    Parameters
    ----------
    acceleration_m_s2 : ndarray, shape (n, 3)
        Acceleration of the point whose apparent gravity is followed [m/s^2].
    max_tilt_rad : float
        Largest tilt from vertical [rad].

    Returns
    -------
    ndarray, shape (n, 3)
        Unit axes.

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711.

    Examples
    --------
    >>> axis = compensating_axis(np.array([[3.0, 0.0, 0.0]]), np.radians(30))
    >>> round(float(np.degrees(np.arctan2(axis[0, 0], axis[0, 2]))), 3)  # atan(a / g)
    17.004
    """
    wanted = np.asarray(acceleration_m_s2, dtype=float) - GRAVITY
    horizontal = np.linalg.norm(wanted[:, :2], axis=1)
    tilt = np.minimum(np.arctan2(horizontal, wanted[:, 2]), max_tilt_rad)
    direction = np.where(
        horizontal[:, None] > 1e-12, wanted[:, :2] / np.maximum(horizontal, 1e-12)[:, None], 0.0
    )
    return np.column_stack((np.sin(tilt)[:, None] * direction, np.cos(tilt)))


def tilt_compensated(
    poses: PoseTrajectory,
    bob_height_m: float,
    max_tilt_rad: float,
    centre_height_m: float = 0.0,
    smoothing_s: float = SMOOTHING_S,
) -> PoseTrajectory:
    """``poses`` re-oriented so the container axis follows the apparent gravity (module doc).

    Parameters
    ----------
    poses : PoseTrajectory
        The untilted export (uniform sample period, at rest at both ends).
    bob_height_m : float
        Height of the first mode's bob above the container bottom [m].
    max_tilt_rad : float
        Largest tilt of the axis from vertical [rad].
    centre_height_m : float
        Rotation centre on the axis above the bottom [m]; it stays on the path.
    smoothing_s : float
        Standard deviation of the zero-phase Gaussian filter on the acceleration [s].

    Returns
    -------
    PoseTrajectory
        Rest samples added before and after (3 ``smoothing_s`` each); positions change only
        when the centre is not the bottom.

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711.

    Examples
    --------
    >>> t = np.arange(0, 401) * 0.005
    >>> x = 0.5 * 2.0 * t**2  # constant 2 m/s^2 along x
    >>> poses = PoseTrajectory(t, np.c_[x, 0 * t, 0 * t], np.tile([0, 0, 0, 1.0], (t.size, 1)))
    >>> tilted = tilt_compensated(poses, 0.03, np.radians(30), smoothing_s=0.0)
    >>> axis = tilted.rotation.apply([0, 0, 1])[200]
    >>> round(float(np.degrees(np.arctan2(axis[0], axis[2]))), 2)  # atan(2 / g)
    11.52
    """
    ts = float(poses.time_s[1] - poses.time_s[0])
    pad = math.ceil(3.0 * smoothing_s / ts)
    count = poses.time_s.size + 2 * pad
    index = np.clip(np.arange(count) - pad, 0, poses.time_s.size - 1)
    position = poses.position_m[index]
    base = Rotation.from_quat(poses.quaternion_xyzw[index])
    base_axis = base.apply([0.0, 0.0, 1.0])
    acceleration = second_difference(position + bob_height_m * base_axis, ts)
    if smoothing_s > 0:
        acceleration = gaussian_filter1d(acceleration, smoothing_s / ts, axis=0, mode="nearest")
    target = compensating_axis(acceleration, max_tilt_rad)
    cross = np.cross(base_axis, target)
    sine = np.linalg.norm(cross, axis=1)
    angle = np.arctan2(sine, np.sum(base_axis * target, axis=1))
    unit = np.where(sine[:, None] > 1e-15, cross / np.maximum(sine, 1e-15)[:, None], 0.0)
    rotation = Rotation.from_rotvec(unit * angle[:, None]) * base
    centre = np.array([0.0, 0.0, centre_height_m])
    position = position + base.apply(centre) - rotation.apply(centre)
    time_s = np.arange(count, dtype=float) * ts
    return PoseTrajectory(time_s, position, rotation.as_quat())


def peak_tilt_rad(poses: PoseTrajectory) -> float:
    """Largest angle between the container axis and the vertical [rad].

    Parameters
    ----------
    poses : PoseTrajectory
        The export.

    Returns
    -------
    float

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> q = Rotation.from_euler("x", [[0.0], [0.2]]).as_quat()
    >>> round(peak_tilt_rad(PoseTrajectory(np.arange(2) * 0.1, np.zeros((2, 3)), q)), 6)
    0.2
    """
    axis = poses.rotation.apply([0.0, 0.0, 1.0])
    return float(np.max(np.arccos(np.clip(axis[:, 2], -1.0, 1.0))))
