"""Container motions that drive a CFD case, and the acceleration table OpenFOAM reads.

The flow is solved in the container's frame on a static mesh; OpenFOAM's fvOption
``tabulatedAccelerationSource`` reads a table of the frame's linear acceleration, angular
velocity and angular acceleration and adds the fictitious forces (g_eff = g - a, plus the
rotating-frame terms).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.motion.pose_kinematics import PoseKinematics
from sloshkit.motion.poses import PoseTrajectory

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class FreeDecay:
    """Initial free surface tilted by ``tilt_rad`` about the y axis (rising towards +x).

    Parameters
    ----------
    tilt_rad : float
        Initial tilt of the free surface [rad].

    Returns
    -------
    FreeDecay

    Examples
    --------
    >>> import numpy as np
    >>> FreeDecay(0.05).acceleration(np.array([0.0, 1.0]))
    array([0., 0.])
    """

    tilt_rad: float = math.radians(3.0)

    def acceleration(self, t: FloatArray) -> FloatArray:
        """No container motion [m/s^2]."""
        return np.zeros_like(t)


@dataclass(frozen=True)
class Harmonic:
    """The seed paper's excitation: x(t) = A sin(2 pi f t) for ``duration_s``, then at rest
    (acceleration -A (2 pi f)^2 sin(2 pi f t), zero at both ends for whole cycles).

    Parameters
    ----------
    amplitude_m : float
        Displacement amplitude A [m].
    frequency_hz : float
        Frequency f [Hz].
    duration_s : float
        How long the container oscillates [s].

    Returns
    -------
    Harmonic

    References
    ----------
    De Simone et al. (2024), the seed paper, Fig. 9 (10 mm at 1 Hz for 2 s).

    Examples
    --------
    >>> import numpy as np
    >>> round(float(Harmonic(0.01, 1.0, 2.0).acceleration(np.array([0.25]))[0]), 4)
    -0.3948
    """

    amplitude_m: float = 0.01
    frequency_hz: float = 1.0
    duration_s: float = 2.0

    def acceleration(self, t: FloatArray) -> FloatArray:
        """Container acceleration [m/s^2]."""
        omega = 2 * math.pi * self.frequency_hz
        values = -self.amplitude_m * omega**2 * np.sin(omega * t)
        return np.where((t >= 0) & (t <= self.duration_s), values, 0.0)


@dataclass(frozen=True)
class MotionExcitation:
    """Any container motion given by its acceleration function of time [m/s^2] (zero after
    ``duration_s``, e.g. a sloshkit motion law).

    Parameters
    ----------
    name : str
        Label of the motion.
    acceleration_function : callable
        t [s] -> container acceleration along x [m/s^2].
    duration_s : float
        When the motion ends [s].

    Returns
    -------
    MotionExcitation

    Examples
    --------
    >>> import numpy as np
    >>> move = MotionExcitation("step", lambda t: np.where(t < 0.1, 2.0, 0.0), 0.1)
    >>> move.acceleration(np.array([0.0, 0.2]))
    array([2., 0.])
    """

    name: str
    acceleration_function: Callable[[FloatArray], FloatArray]
    duration_s: float = 0.0

    def acceleration(self, t: FloatArray) -> FloatArray:
        """Container acceleration [m/s^2]."""
        return np.asarray(self.acceleration_function(t), dtype=float)


#: Gravity in the world frame [m/s^2] (z up), as in constant/g of the case.
GRAVITY_WORLD = np.array([0.0, 0.0, -GRAVITY_M_S2])


@dataclass(frozen=True, eq=False)
class PoseExcitation:
    """A 3-D pose trajectory of the container's bottom centre (translation, tilt, rotation).

    Parameters
    ----------
    poses : PoseTrajectory
        The container's poses (container -> world).
    cutoff_hz : float, optional
        Cut-off of the smoothed differentiation (default that of `PoseTrajectory.kinematics`).
    sample_period_s : float
        Step of the kinematics grid [s].

    Returns
    -------
    PoseExcitation

    The case is solved in the container frame C with its origin at the bottom centre (the
    mesh origin). ``tabulatedAccelerationSource`` (OpenFOAM v1912) sets g = g0 - a with g0
    the constant ``constant/g`` in mesh (container) coordinates, and adds
    -rho (2 Omega x U + Omega x (Omega x r) + dOmega/dt x r) with r measured from the mesh
    origin. So the table holds, in container coordinates,

        a = g0 - R^T (g - a_O),   Omega = omega_C,   dOmega/dt = alpha_C

    with R (container -> world) and a_O the acceleration of the bottom centre in the world
    frame: then g0 - a = R^T (g - a_O), the apparent gravity in the container frame, which
    also turns with the container's tilt. Kinematics come from
    `sloshkit.motion.poses.PoseTrajectory.kinematics` (smoothed with ``cutoff_hz``); before
    the first and after the last pose the container rests in that pose.

    References
    ----------
    OpenFOAM v1912, ``src/fvOptions/sources/derived/tabulatedAccelerationSource``
    (``tabulatedAccelerationSourceTemplates.C``: the source terms above); L. D. Landau and
    E. M. Lifshitz, *Mechanics*, 3rd ed., §39 (motion in a non-inertial frame).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> t = np.linspace(0.0, 1.0, 11)
    >>> still = PoseTrajectory(t, np.zeros((11, 3)), np.tile([0.0, 0.0, 0.0, 1.0], (11, 1)))
    >>> linear, omega, alpha = PoseExcitation(still).frame_motion(np.array([0.5]))
    >>> np.round(linear + 0.0, 6), float(np.abs(omega).max())
    (array([[0., 0., 0.]]), 0.0)
    """

    poses: PoseTrajectory
    cutoff_hz: float | None = None
    sample_period_s: float = 1e-3

    @property
    def name(self) -> str:
        """The trajectory's label."""
        return self.poses.name or "poses"

    @property
    def duration_s(self) -> float:
        """Time from the first to the last pose [s] (CFD time 0 is the first pose)."""
        return self.poses.duration_s

    @cached_property
    def _kinematics(self) -> PoseKinematics:
        if self.cutoff_hz is None:
            return self.poses.kinematics(self.sample_period_s)
        return self.poses.kinematics(self.sample_period_s, cutoff_hz=self.cutoff_hz)

    @property
    def initial_up_body(self) -> FloatArray:
        """World up (0, 0, 1) in container coordinates at the first pose."""
        rotation = Rotation.from_quat(self.poses.quaternion_xyzw[0])
        return np.asarray(rotation.inv().apply([0.0, 0.0, 1.0]), dtype=float)

    def acceleration(self, t: FloatArray) -> FloatArray:
        """x component of the table's linear acceleration [m/s^2] (see `frame_motion`)."""
        return self.frame_motion(t)[0][:, 0]

    def frame_motion(self, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Table rows at CFD times ``t``: (a, Omega, dOmega/dt) in container coordinates."""
        kinematics = self._kinematics
        grid = kinematics.time_s - self.poses.start_s
        times = np.asarray(t, dtype=float)
        inside = (times >= grid[0]) & (times <= grid[-1])

        def interpolate(values: FloatArray, hold: bool) -> FloatArray:
            columns = [np.interp(times, grid, values[:, k]) for k in range(values.shape[1])]
            result = np.column_stack(columns)
            return result if hold else np.where(inside[:, None], result, 0.0)

        quaternion = interpolate(kinematics.quaternion_xyzw, hold=True)
        quaternion /= np.linalg.norm(quaternion, axis=1)[:, None]
        to_body = Rotation.from_quat(quaternion).inv()
        accel_world = interpolate(kinematics.acceleration_m_s2, hold=False)
        apparent = to_body.apply(GRAVITY_WORLD[None, :] - accel_world)
        linear = GRAVITY_WORLD[None, :] - apparent
        omega = interpolate(kinematics.angular_velocity_body_rad_s, hold=False)
        alpha = interpolate(kinematics.angular_acceleration_body_rad_s2, hold=False)
        return np.asarray(linear), omega, alpha


Excitation = FreeDecay | Harmonic | MotionExcitation | PoseExcitation


def frame_motion(
    excitation: Excitation, t: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Linear acceleration [m/s^2], angular velocity [rad/s] and angular acceleration
    [rad/s^2] of the container frame at ``t``, each (n, 3).

    Parameters
    ----------
    excitation : Excitation
        The motion.
    t : ndarray
        Times [s].

    Returns
    -------
    tuple of ndarray
        (linear acceleration, angular velocity, angular acceleration), each (n, 3).

    Examples
    --------
    >>> import numpy as np
    >>> linear, omega, alpha = frame_motion(Harmonic(0.01, 1.0, 2.0), np.array([0.25, 3.0]))
    >>> np.round(linear[:, 0], 4), omega.shape
    (array([-0.3948,  0.    ]), (2, 3))
    """
    frames = getattr(excitation, "frame_motion", None)
    if frames is not None:
        linear, omega, alpha = frames(t)
        return (np.asarray(linear), np.asarray(omega), np.asarray(alpha))
    linear = np.zeros((t.size, 3))
    linear[:, 0] = excitation.acceleration(t)
    return linear, np.zeros((t.size, 3)), np.zeros((t.size, 3))
