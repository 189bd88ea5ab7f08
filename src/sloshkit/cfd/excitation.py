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
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from sloshkit.cfd.foam import format_number
from sloshkit.cfd.spec import SCALE

if TYPE_CHECKING:
    from sloshkit.cfd.spec import CaseSpec

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


def frame_motion(spec: CaseSpec, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Linear acceleration [m/s^2], angular velocity [rad/s] and angular acceleration
    [rad/s^2] of the container frame at ``t``, each (n, 3)."""
    excitation = spec.excitation
    frames = getattr(excitation, "frame_motion", None)
    if frames is not None:
        linear, omega, alpha = frames(t)
        return (np.asarray(linear), np.asarray(omega), np.asarray(alpha))
    linear = np.zeros((t.size, 3))
    linear[:, 0] = excitation.acceleration(t)
    return linear, np.zeros((t.size, 3)), np.zeros((t.size, 3))


def acceleration_table(spec: CaseSpec, step_s: float = 1e-3) -> str:
    """``constant/acceleration.dat``: (t ((ax ay az) (wx wy wz) (dwx dwy dwz))), lengths in mm,
    covering [0, endTime + 0.1 s] (a time outside the table is fatal)."""
    end = spec.end_time_s + 0.1
    t = np.arange(0.0, end + step_s, step_s)
    linear, omega, alpha = frame_motion(spec, t)
    linear = linear * SCALE

    def vector(v: FloatArray) -> str:
        return "(" + " ".join(format_number(float(x)) for x in v) + ")"

    rows = "\n".join(
        f"({format_number(round(float(time), 9))} ({vector(a)} {vector(w)} {vector(dw)}))"
        for time, a, w, dw in zip(t, linear, omega, alpha, strict=True)
    )
    return f"{t.size}\n(\n{rows}\n)\n"
