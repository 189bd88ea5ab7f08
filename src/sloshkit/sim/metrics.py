"""Slosh metrics shared by every simulation path: the time grid, the residual amplitude of the
free oscillation left after a move, settling defaults."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from sloshkit.model.modal import SloshModel

FloatArray = NDArray[np.float64]


#: Default tolerance for the settling time: 0.1 degree of the first mode [rad].
DEFAULT_SETTLE_TOLERANCE_RAD = math.radians(0.1)


def free_amplitude(
    angle_rad: FloatArray | float,
    rate_rad_s: FloatArray | float,
    omega_rad_s: float,
    damping_ratio: float,
) -> FloatArray:
    """Envelope amplitude of the free damped oscillation through the state (theta, theta').

    theta(t) = e^{-zeta w t} (A cos w_d t + B sin w_d t), A = theta, B = (theta' + zeta w theta)
    / w_d; the amplitude is sqrt(A^2 + B^2) [rad].
    """
    damped = omega_rad_s * math.sqrt(max(1e-300, 1.0 - damping_ratio**2))
    angle = np.asarray(angle_rad, dtype=float)
    quadrature = (
        np.asarray(rate_rad_s, dtype=float) + damping_ratio * omega_rad_s * angle
    ) / damped
    return np.asarray(np.hypot(angle, quadrature), dtype=float)


def default_settle_time(model: SloshModel) -> float:
    """Time simulated after the move for plots: 5 first-mode periods, at least 1 s [s]."""
    return max(1.0, 5.0 * 2.0 * math.pi / model.modes[0].omega_rad_s)


def simulation_grid(
    move_duration_s: float, sample_period_s: float, settle_time_s: float
) -> FloatArray:
    """Uniform times k dt from 0 to at least T + settle time [s] (shared by all paths)."""
    count = math.ceil((move_duration_s + settle_time_s) / sample_period_s - 1e-9) + 1
    return np.arange(count, dtype=float) * sample_period_s


def residual_from_state(
    time_s: FloatArray,
    angle_rad: FloatArray,
    rate_rad_s: FloatArray,
    move_duration_s: float,
    model: SloshModel,
) -> FloatArray:
    """Per-mode free-oscillation amplitude at T, from the state at the first sample t_k >= T
    scaled back by exp(zeta omega (t_k - T)) (exact for the linear model)."""
    index = int(np.searchsorted(time_s, move_duration_s - 1e-12))
    index = min(index, time_s.size - 1)
    lag = time_s[index] - move_duration_s
    amplitudes = []
    for row, mode in enumerate(model.modes):
        amplitude = free_amplitude(
            angle_rad[row, index], rate_rad_s[row, index], mode.omega_rad_s, mode.damping_ratio
        )
        amplitudes.append(float(amplitude) * math.exp(mode.damping_ratio * mode.omega_rad_s * lag))
    return np.asarray(amplitudes)
