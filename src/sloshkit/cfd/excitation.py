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

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class FreeDecay:
    """Initial free surface tilted by ``tilt_rad`` about the y axis (rising towards +x)."""

    tilt_rad: float = math.radians(3.0)

    def acceleration(self, t: FloatArray) -> FloatArray:
        """No container motion [m/s^2]."""
        return np.zeros_like(t)


@dataclass(frozen=True)
class Harmonic:
    """The seed paper's excitation: x(t) = A sin(2 pi f t) for ``duration_s``, then at rest
    (acceleration -A (2 pi f)^2 sin(2 pi f t), zero at both ends for whole cycles)."""

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
    ``duration_s``, e.g. a sloshkit motion law)."""

    name: str
    acceleration_function: Callable[[FloatArray], FloatArray]
    duration_s: float = 0.0

    def acceleration(self, t: FloatArray) -> FloatArray:
        """Container acceleration [m/s^2]."""
        return np.asarray(self.acceleration_function(t), dtype=float)


Excitation = FreeDecay | Harmonic | MotionExcitation


def frame_motion(
    excitation: Excitation, t: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Linear acceleration [m/s^2], angular velocity [rad/s] and angular acceleration
    [rad/s^2] of the container frame at ``t``, each (n, 3)."""
    frames = getattr(excitation, "frame_motion", None)
    if frames is not None:
        linear, omega, alpha = frames(t)
        return (np.asarray(linear), np.asarray(omega), np.asarray(alpha))
    linear = np.zeros((t.size, 3))
    linear[:, 0] = excitation.acceleration(t)
    return linear, np.zeros((t.size, 3)), np.zeros((t.size, 3))
