"""Amplitude dependence of a free decay: the backbone.

Real slosh is not linear: the first mode softens at large amplitude (its frequency drops, like
a pendulum's, omega(A) ~ omega_0 (1 - A^2/16) for an angle A; Ibrahim, *Liquid Sloshing
Dynamics* (2005) §8) and its damping grows with amplitude (contact-line and boundary-layer
losses). A single fit over the whole decay averages these.

`backbone` fits the damped sinusoid in sliding windows of a few periods along the decay
(sliding-window identification, Feldman, *Hilbert Transform Applications in Mechanical
Vibration* (2011) §5, which avoids the end effects of the Hilbert transform) and gives, per
window, the amplitude at its centre, omega_n and zeta. The small-amplitude limit comes from
weighted regressions omega_n = omega_0 + k_2 A^2 (a softening or hardening backbone is even in
A) and zeta = zeta_0 + k_1 A (amplitude-proportional damping, e.g. quadratic drag); omega_0 and
zeta_0 are the linear model's calibration.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import curve_fit

from sloshkit.calibration.signals import PreparedSignal, noise_level
from sloshkit.errors import InputError
from sloshkit.results import ResultMixin

FloatArray = NDArray[np.float64]

#: A trend is reported when it exceeds this many standard errors ...
SIGNIFICANCE = 3.0
#: ... and changes omega_n by this fraction, or zeta by that one, over the amplitude range.
OMEGA_CHANGE = 0.002
ZETA_CHANGE = 0.05


@dataclass(frozen=True, eq=False)
class Backbone(ResultMixin):
    """Frequency and damping against amplitude along a free decay (arrays per window).

    Attributes
    ----------
    time_s, amplitude, omega_n_rad_s, damping_ratio : numpy.ndarray
        Per window: centre time [s], amplitude (signal units), omega_n [rad/s] and zeta.
    small_amplitude_omega_n_rad_s, small_amplitude_damping_ratio : float
        The weighted lines' values at zero amplitude.
    omega_n_se_rad_s, damping_ratio_se : float
        Their standard errors.
    omega_slope_rad_s_per_amplitude2, zeta_slope_per_amplitude : float
        Slopes of omega_n against amplitude^2 and of zeta against amplitude.
    omega_dependent, zeta_dependent : bool
        Whether the trend is significant (`SIGNIFICANCE`) and large (`OMEGA_CHANGE`,
        `ZETA_CHANGE`).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration import prepare_signal
    >>> t = np.arange(0, 6, 0.002)
    >>> prepared, _ = prepare_signal(t, np.exp(-0.6 * t) * np.cos(29.99 * t), start_s=0.0)
    >>> found = backbone(prepared, 30.0, 0.02)
    >>> found.omega_dependent, round(float(np.median(found.damping_ratio)), 3)
    (False, 0.02)
    """

    time_s: FloatArray
    amplitude: FloatArray
    omega_n_rad_s: FloatArray
    damping_ratio: FloatArray
    small_amplitude_omega_n_rad_s: float
    small_amplitude_damping_ratio: float
    omega_n_se_rad_s: float
    damping_ratio_se: float
    omega_slope_rad_s_per_amplitude2: float
    zeta_slope_per_amplitude: float
    omega_dependent: bool
    zeta_dependent: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary and the per-window arrays."""
        return {
            "small_amplitude_omega_n_rad_s": self.small_amplitude_omega_n_rad_s,
            "small_amplitude_frequency_hz": self.small_amplitude_omega_n_rad_s / (2 * math.pi),
            "small_amplitude_damping_ratio": self.small_amplitude_damping_ratio,
            "small_amplitude_omega_n_se_rad_s": self.omega_n_se_rad_s,
            "small_amplitude_damping_ratio_se": self.damping_ratio_se,
            "omega_slope_rad_s_per_amplitude2": self.omega_slope_rad_s_per_amplitude2,
            "zeta_slope_per_amplitude": self.zeta_slope_per_amplitude,
            "omega_amplitude_dependent": self.omega_dependent,
            "zeta_amplitude_dependent": self.zeta_dependent,
            "time_s": self.time_s.tolist(),
            "amplitude": self.amplitude.tolist(),
            "omega_n_rad_s": self.omega_n_rad_s.tolist(),
            "damping_ratio": self.damping_ratio.tolist(),
        }

    def columns(self) -> dict[str, FloatArray]:
        """One row per window: centre time, amplitude (signal units), omega_n, zeta."""
        return {
            "time_s": self.time_s,
            "amplitude": self.amplitude,
            "omega_n_rad_s": self.omega_n_rad_s,
            "damping_ratio": self.damping_ratio,
        }


def _local_model(
    t: FloatArray, a: float, b: float, zeta: float, omega: float, c: float
) -> FloatArray:
    damped = omega * np.sqrt(max(1e-12, 1.0 - zeta**2))
    return np.asarray(
        np.exp(-zeta * omega * t) * (a * np.cos(damped * t) + b * np.sin(damped * t)) + c,
        dtype=float,
    )


def _weighted_line(
    x: FloatArray, y: FloatArray, weight: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Weighted least-squares line y = p0 + p1 x: (parameters, standard errors)."""
    design = np.column_stack((np.ones_like(x), x)) * np.sqrt(weight)[:, None]
    target = y * np.sqrt(weight)
    parameters, *_ = np.linalg.lstsq(design, target, rcond=None)
    residual = target - design @ parameters
    dof = max(1, x.size - 2)
    covariance = np.linalg.pinv(design.T @ design) * float(residual @ residual) / dof
    errors = np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    return np.asarray(parameters, dtype=float), np.asarray(errors, dtype=float)


def backbone(
    prepared: PreparedSignal,
    omega_guess_rad_s: float,
    zeta_guess: float,
    *,
    periods: float = 3.0,
) -> Backbone:
    """Sliding-window fits along a free decay (see the module docstring).

    Parameters
    ----------
    prepared : the windowed decay (`prepare_signal`)
    omega_guess_rad_s, zeta_guess : starting values (the global fit) [rad/s], [-]
    periods : window length in damped periods; windows advance by one period

    Returns
    -------
    Backbone with per-window amplitude, omega_n and zeta and the small-amplitude limit.

    References
    ----------
    Feldman, *Hilbert Transform Applications in Mechanical Vibration*, Wiley (2011) §5;
    Ibrahim, *Liquid Sloshing Dynamics*, Cambridge (2005) §8, doi:10.1017/CBO9780511536656.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration import prepare_signal
    >>> t = np.arange(0, 6, 0.002)
    >>> prepared, _ = prepare_signal(t, np.exp(-0.6 * t) * np.cos(29.99 * t), start_s=0.0)
    >>> round(backbone(prepared, 30.0, 0.02).small_amplitude_omega_n_rad_s, 2)
    30.0
    """
    t, y = prepared.time_s, prepared.values
    step = t[1] - t[0]
    period = 2.0 * math.pi / omega_guess_rad_s
    noise = noise_level(y, period / step)
    length = max(8, round(periods * period / step))
    advance = max(1, round(period / step))
    rows: list[tuple[float, float, float, float]] = []
    omega, zeta = omega_guess_rad_s, max(zeta_guess, 1e-4)
    for first in range(0, t.size - length + 1, advance):
        local_t = t[first : first + length] - t[first]
        local_y = y[first : first + length]
        scale = float(np.max(np.abs(local_y)))
        if scale < 10.0 * noise or scale == 0.0:
            break
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                parameters, _ = curve_fit(
                    _local_model,
                    local_t,
                    local_y,
                    p0=[local_y[0], 0.0, zeta, omega, 0.0],
                    bounds=(
                        [-np.inf, -np.inf, 0.0, 0.7 * omega_guess_rad_s, -np.inf],
                        [np.inf, np.inf, 0.9, 1.4 * omega_guess_rad_s, np.inf],
                    ),
                    x_scale=[scale, scale, 0.01, omega_guess_rad_s, scale],
                    max_nfev=5000,
                )
        except RuntimeError:
            continue
        a, b, zeta_local, omega_local, _ = (float(p) for p in parameters)
        centre = 0.5 * float(local_t[-1])
        amplitude = math.hypot(a, b) * math.exp(-zeta_local * omega_local * centre)
        rows.append((float(t[first]) + centre, amplitude, omega_local, zeta_local))
        omega, zeta = omega_local, max(zeta_local, 1e-4)
    if len(rows) < 3:
        raise InputError(
            "signal",
            f"{len(rows)} backbone window(s)",
            f"needs at least 3 windows of {periods:g} periods above the noise for the backbone",
        )
    table = np.asarray(rows)
    times, amplitudes, omegas, zetas = table.T
    if float(np.median(zetas)) <= 1e-6:
        raise InputError(
            "signal", "damping ratio 0", "the amplitude does not decay: not a free decay"
        )
    weight = amplitudes**2  # local fits on larger amplitudes are relatively less noisy
    omega_fit, omega_se = _weighted_line(amplitudes**2, omegas, weight)
    zeta_fit, zeta_se = _weighted_line(amplitudes, zetas, weight)
    top = float(np.max(amplitudes))
    return Backbone(
        time_s=times,
        amplitude=amplitudes,
        omega_n_rad_s=omegas,
        damping_ratio=zetas,
        small_amplitude_omega_n_rad_s=float(omega_fit[0]),
        small_amplitude_damping_ratio=float(max(0.0, zeta_fit[0])),
        omega_n_se_rad_s=float(omega_se[0]),
        damping_ratio_se=float(zeta_se[0]),
        omega_slope_rad_s_per_amplitude2=float(omega_fit[1]),
        zeta_slope_per_amplitude=float(zeta_fit[1]),
        omega_dependent=bool(
            abs(omega_fit[1]) > SIGNIFICANCE * omega_se[1]
            and abs(omega_fit[1]) * top**2 > OMEGA_CHANGE * abs(omega_fit[0])
        ),
        zeta_dependent=bool(
            abs(zeta_fit[1]) > SIGNIFICANCE * zeta_se[1]
            and abs(zeta_fit[1]) * top > ZETA_CHANGE * abs(zeta_fit[0])
        ),
    )
