"""Independent estimators of frequency and damping from a free decay.

- ``fit``: nonlinear least squares of y = exp(-zeta omega_n t) (a cos omega_d t + b sin omega_d t)
  + c + d t, started from the spectrum alone (spectral peak for omega_d, a grid over zeta with
  the amplitudes solved linearly), never from another estimator; 95 % intervals from the
  covariance (Student t).
- ``logdec``: weighted robust regression of ln(swing) on the peak times over every peak above
  the noise, slope -zeta omega_n (Inman, *Engineering Vibration*, 4th ed. (2014) §1.6, written
  as a regression like Ewins, *Modal Testing*, 2nd ed. (2000) §4.3), with a 95 % interval. Each
  swing's weight is its inverse variance in the logarithm (swing / noise)^2, and a soft-L1 loss
  (`scipy.optimize.least_squares`) limits the pull of a single noise spike.
- ``logdec-2peak``: the seed paper's form over the first and last usable peak,
  delta = ln(Y_0 / Y_k) / k (seed paper eqs. 11-12), kept for comparison.
- ``fft``: spectral peak with Gaussian interpolation; half-power bandwidth damping only when it
  is resolved (several bins, several decay times).

zeta = delta / sqrt(4 pi^2 + delta^2) is the exact conversion of the logarithmic decrement.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy import signal as sps
from scipy import stats
from scipy.optimize import curve_fit

from sloshkit.calibration.signals import PreparedSignal, spectral_peak
from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


def zeta_from_log_decrement(delta: float) -> float:
    """Exact damping ratio from the logarithmic decrement: delta / sqrt(4 pi^2 + delta^2).

    Parameters
    ----------
    delta : float
        Logarithmic decrement ln(Y_k / Y_{k+1}) of successive peaks.

    Returns
    -------
    float
        The damping ratio zeta.

    References
    ----------
    Inman, D. J., *Engineering Vibration*, 4th ed. (2014) §1.6.

    Examples
    --------
    >>> round(zeta_from_log_decrement(0.163), 4)
    0.0259
    """
    return delta / math.sqrt(4.0 * math.pi**2 + delta**2)


def log_decrement_from_zeta(zeta: float) -> float:
    """Logarithmic decrement of a damping ratio: 2 pi zeta / sqrt(1 - zeta^2).

    Parameters
    ----------
    zeta : float
        Damping ratio (below 1).

    Returns
    -------
    float
        The logarithmic decrement delta.

    References
    ----------
    Inman, D. J., *Engineering Vibration*, 4th ed. (2014) §1.6.

    Examples
    --------
    >>> round(log_decrement_from_zeta(0.02594), 3)
    0.163
    """
    return 2.0 * math.pi * zeta / math.sqrt(1.0 - zeta**2)


@dataclass(frozen=True)
class Estimate:
    """One estimator's result (SI); ``None`` where the estimator cannot say.

    ``failure`` holds the reason when the estimator could not produce a result; ``fitted`` the
    fit's curve over the window (with its offset and drift), for the fit only.

    Attributes
    ----------
    method : str
        fit, logdec, logdec-2peak or fft.
    omega_n_rad_s, damping_ratio, damped_omega_rad_s : float or None
        Natural frequency [rad/s], damping ratio and damped frequency [rad/s].
    log_decrement : float or None
        The logarithmic decrement delta.
    n_peaks : int
        Peaks used (decrement estimators).
    residual_rms : float or None
        RMS of the fit's residual (signal units).
    omega_n_interval, damping_ratio_interval : tuple of float or None
        95 % confidence intervals.
    amplitude, offset : float or None
        Amplitude of the first peak and the fitted offset (signal units).
    note, failure : str
        A remark on the estimate; why there is none.
    fitted : numpy.ndarray or None
        The fitted curve over the window (fit only).

    Examples
    --------
    >>> Estimate("fft", 30.0, 0.02, 29.994).damping_ratio
    0.02
    >>> Estimate.failed("logdec", InputError("signal", "flat", "must oscillate")).failure
    "signal = 'flat' is invalid: must oscillate"
    """

    method: str
    omega_n_rad_s: float | None
    damping_ratio: float | None
    damped_omega_rad_s: float | None
    log_decrement: float | None = None
    n_peaks: int = 0
    residual_rms: float | None = None
    omega_n_interval: tuple[float, float] | None = None
    damping_ratio_interval: tuple[float, float] | None = None
    amplitude: float | None = None
    offset: float | None = None
    note: str = ""
    failure: str = ""
    fitted: FloatArray | None = field(default=None, compare=False, repr=False)

    @classmethod
    def failed(cls, method: str, error: InputError) -> Estimate:
        """An estimator that could not answer, with the reason."""
        return cls(method, None, None, None, failure=str(error))


def _decay_model(
    t: FloatArray, a: float, b: float, zeta: float, omega: float, c: float, d: float
) -> FloatArray:
    damped = omega * np.sqrt(max(1e-12, 1.0 - zeta**2))
    oscillation = np.exp(-zeta * omega * t) * (a * np.cos(damped * t) + b * np.sin(damped * t))
    return np.asarray(oscillation + c + d * t, dtype=float)


def spectral_guess(t: FloatArray, y: FloatArray) -> tuple[float, float]:
    """(omega_n, zeta) first guess from the spectrum alone: the spectral peak gives omega_d;
    zeta is the best of a logarithmic grid 3e-4...0.45 with the amplitude, offset and drift
    solved by linear least squares for each value.

    Parameters
    ----------
    t, y : numpy.ndarray
        Uniform times [s] and the decaying signal.

    Returns
    -------
    tuple of float
        (omega_n [rad/s], zeta).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration.window import prepare_signal
    >>> t = np.arange(0.0, 4.0, 0.002)
    >>> omega, zeta = 30.0, 0.02
    >>> y = np.exp(-zeta * omega * t) * np.cos(omega * np.sqrt(1 - zeta**2) * t)
    >>> prepared, _ = prepare_signal(t, y, start_s=0.0)
    >>> omega_n, zeta_n = spectral_guess(prepared.time_s, prepared.values)
    >>> round(omega_n, 1), round(zeta_n, 2)
    (30.0, 0.02)
    """
    frequency, _, _ = spectral_peak(t, sps.detrend(y))
    if not frequency > 0.0:
        raise InputError("signal", "no spectral peak", "has no oscillation in the window")
    damped = 2.0 * math.pi * frequency
    tau = t - t[0]
    best = (math.inf, 0.01)
    for zeta in np.geomspace(3e-4, 0.45, 36):
        omega = damped / math.sqrt(1.0 - zeta**2)
        envelope = np.exp(-zeta * omega * tau)
        design = np.column_stack(
            (envelope * np.cos(damped * tau), envelope * np.sin(damped * tau), np.ones_like(t), tau)
        )
        _, residual, *_ = np.linalg.lstsq(design, y, rcond=None)
        cost = float(residual[0]) if residual.size else math.inf
        if cost < best[0]:
            best = (cost, float(zeta))
    zeta = best[1]
    return damped / math.sqrt(1.0 - zeta**2), zeta


def estimate_fit(prepared: PreparedSignal) -> Estimate:
    """Least-squares damped sinusoid plus offset and drift (fitted together, not detrended
    first: removing a line fitted to a decaying oscillation biases zeta), started from
    `spectral_guess`, with 95 % confidence intervals.

    Parameters
    ----------
    prepared : PreparedSignal
        The window of the free decay (`sloshkit.calibration.window.prepare_signal`).

    Returns
    -------
    Estimate
        Method ``fit``, with intervals and the fitted curve.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration.window import prepare_signal
    >>> t = np.arange(0.0, 4.0, 0.002)
    >>> omega, zeta = 30.0, 0.02
    >>> y = np.exp(-zeta * omega * t) * np.cos(omega * np.sqrt(1 - zeta**2) * t)
    >>> prepared, _ = prepare_signal(t, y, start_s=0.0)
    >>> found = estimate_fit(prepared)
    >>> round(found.omega_n_rad_s, 3), round(found.damping_ratio, 4)
    (30.0, 0.02)"""
    t = prepared.time_s - prepared.time_s[0]
    y = prepared.undetrended
    omega_guess, zeta_guess = spectral_guess(t, y)
    damped = omega_guess * math.sqrt(1.0 - zeta_guess**2)
    envelope = np.exp(-zeta_guess * omega_guess * t)
    design = np.column_stack(
        (envelope * np.cos(damped * t), envelope * np.sin(damped * t), np.ones_like(t), t)
    )
    (a0, b0, c0, d0), *_ = np.linalg.lstsq(design, y, rcond=None)
    scale = float(np.max(np.abs(prepared.values))) or 1.0
    span = float(t[-1]) or 1.0
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            parameters, covariance = curve_fit(
                _decay_model,
                t,
                y,
                p0=[a0, b0, zeta_guess, omega_guess, c0, d0],
                bounds=(
                    [-np.inf, -np.inf, 0.0, 0.5 * omega_guess, -np.inf, -np.inf],
                    [np.inf, np.inf, 0.9, 2.0 * omega_guess, np.inf, np.inf],
                ),
                x_scale=[scale, scale, 0.01, omega_guess, scale, scale / span],
                max_nfev=20000,
            )
    except RuntimeError as error:
        raise InputError(
            "signal", "fit", f"the damped-sinusoid fit did not converge ({error})"
        ) from None
    residual = y - _decay_model(t, *parameters)
    rms = float(np.sqrt(np.mean(residual**2)))
    explained = 1.0 - float(np.var(residual) / np.var(prepared.values))
    if explained < 0.5:
        raise InputError(
            "signal",
            f"fit explains {100 * explained:.0f} % of the variance",
            "no damped oscillation found (pure noise or forced motion?)",
        )
    a, b, zeta, omega, c, _ = (float(p) for p in parameters)
    if zeta <= 1e-6:
        raise InputError(
            "signal",
            "damping ratio 0",
            "the amplitude grows or stays constant over the window: not a free decay",
        )
    if zeta >= 0.5:
        raise InputError(
            "signal",
            f"damping ratio {zeta:.2f}",
            "too heavily damped to measure: fewer than 2 peaks above the noise",
        )
    dof = max(1, t.size - parameters.size)
    factor = float(stats.t.ppf(0.975, dof))
    errors = np.sqrt(np.clip(np.diag(covariance), 0.0, np.inf))
    return Estimate(
        method="fit",
        omega_n_rad_s=omega,
        damping_ratio=zeta,
        damped_omega_rad_s=omega * math.sqrt(1.0 - zeta**2),
        log_decrement=log_decrement_from_zeta(zeta),
        residual_rms=rms,
        omega_n_interval=(omega - factor * errors[3], omega + factor * errors[3]),
        damping_ratio_interval=(max(0.0, zeta - factor * errors[2]), zeta + factor * errors[2]),
        amplitude=math.hypot(a, b),
        offset=c,
        fitted=y - residual,
    )


def estimate_fft(prepared: PreparedSignal) -> Estimate:
    """Spectral peak frequency; bandwidth damping only when it is resolved.

    Parameters
    ----------
    prepared : PreparedSignal
        The window of the free decay.

    Returns
    -------
    Estimate
        Method ``fft``; ``damping_ratio`` is None (with a note) when the half-power bandwidth
        is not resolved.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration.window import prepare_signal
    >>> t = np.arange(0.0, 4.0, 0.002)
    >>> omega, zeta = 30.0, 0.02
    >>> y = np.exp(-zeta * omega * t) * np.cos(omega * np.sqrt(1 - zeta**2) * t)
    >>> prepared, _ = prepare_signal(t, y, start_s=0.0)
    >>> found = estimate_fft(prepared)
    >>> round(found.damped_omega_rad_s, 1)
    30.0
    """
    t, y = prepared.time_s, prepared.values
    frequency, resolution, _ = spectral_peak(t, y)
    if not frequency > 0.0:
        raise InputError("signal", "no spectral peak", "has no oscillation in the window")
    duration = t[-1] - t[0]
    n = y.size
    padded = 8 * int(2 ** math.ceil(math.log2(n)))
    spectrum = np.abs(np.fft.rfft(y, padded)) ** 2  # rectangular window: Lorentzian line
    frequencies = np.fft.rfftfreq(padded, t[1] - t[0])
    k = int(np.argmin(np.abs(frequencies - frequency)))
    half = spectrum[k] / 2.0
    low = k
    while low > 0 and spectrum[low] > half:
        low -= 1
    high = k
    while high < spectrum.size - 1 and spectrum[high] > half:
        high += 1
    bandwidth = float(frequencies[high] - frequencies[low])
    zeta: float | None = bandwidth / (2.0 * frequency)
    note = ""
    decay_times = duration * 2 * math.pi * frequency * (zeta or 0.0)
    if zeta is None or zeta >= 0.5 or bandwidth < 4.0 * resolution or decay_times < 3.0:
        note = (
            f"half-power bandwidth {bandwidth:.3g} Hz is not resolved by a {duration:.3g} s "
            f"record (resolution {resolution:.3g} Hz, {decay_times:.2g} decay times): no "
            "damping from the spectrum; use fit or logdec"
        )
        zeta = None
    damped = 2.0 * math.pi * frequency
    omega = damped / math.sqrt(1.0 - zeta**2) if zeta is not None else damped
    return Estimate(
        method="fft",
        omega_n_rad_s=omega,
        damping_ratio=zeta,
        damped_omega_rad_s=damped,
        log_decrement=None if zeta is None else log_decrement_from_zeta(zeta),
        note=note,
    )
