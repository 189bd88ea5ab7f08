"""Natural frequency and damping ratio from a free-decay signal.

Signals: a free-surface elevation (camera, CFD probe), a slosh angle, or a lateral force, after
the container has stopped. Three estimators, reported side by side:

- ``logdec``: peaks (parabolic interpolation), each measured as half the swing to the
  following trough, and the logarithmic decrement averaged over k cycles,
  delta = ln(Y_0 / Y_k) / k, with the exact conversion zeta = delta / sqrt(4 pi^2 + delta^2)
  (seed paper eqs. 11-12; Inman, *Engineering Vibration*, 4th ed. (2014) §1.6). The damped
  period is the mean peak spacing.
- ``fit`` (default): nonlinear least squares of
  y = exp(-zeta omega_n t) (a cos(omega_d t) + b sin(omega_d t)) + c, started from the other
  estimates, with 95 % confidence intervals from the covariance (Student t).
- ``fft``: spectral peak of the zero-padded, Hann-windowed signal with Gaussian (log-parabolic)
  interpolation (Gasior & Gonzalez, CERN-AB-2004-023). The half-power bandwidth gives zeta only
  when it spans several frequency bins and the record holds several decay times; otherwise zeta
  is not reported, with a warning: a 10 s record resolves 0.1 Hz, far wider than the 0.09 Hz
  bandwidth of zeta = 0.01 at 4.7 Hz.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from scipy import signal as sps
from scipy import stats
from scipy.optimize import curve_fit

from sloshkit.errors import InputError, ValidityWarning, require_increasing
from sloshkit.model.modal import SloshModel
from sloshkit.results import plotter_for

FloatArray = NDArray[np.float64]
Method = Literal["fit", "logdec", "fft"]
METHODS: tuple[str, ...] = ("fit", "logdec", "fft")


def zeta_from_log_decrement(delta: float) -> float:
    """Exact damping ratio from the logarithmic decrement: delta / sqrt(4 pi^2 + delta^2)."""
    return delta / math.sqrt(4.0 * math.pi**2 + delta**2)


def log_decrement_from_zeta(zeta: float) -> float:
    """Logarithmic decrement of a damping ratio: 2 pi zeta / sqrt(1 - zeta^2)."""
    return 2.0 * math.pi * zeta / math.sqrt(1.0 - zeta**2)


@dataclass(frozen=True)
class PreparedSignal:
    """A uniformly sampled signal in the analysis window, with how it was prepared."""

    time_s: FloatArray
    values: FloatArray
    raw_time_s: FloatArray
    raw_values: FloatArray
    window_s: tuple[float, float]
    notes: tuple[str, ...] = ()
    trend: FloatArray | None = None

    @property
    def undetrended(self) -> FloatArray:
        """The windowed values before the trend was removed."""
        return self.values if self.trend is None else self.values + self.trend


def prepare_signal(
    time_s: FloatArray,
    values: FloatArray,
    start_s: float | None = None,
    end_s: float | None = None,
    detrend: Literal["mean", "linear", "none"] = "linear",
    lowpass_hz: float | None = None,
) -> PreparedSignal:
    """Check, window, resample, detrend and optionally low-pass a signal.

    Raises `InputError` for NaN values, duplicate or decreasing time stamps, a constant signal
    or an empty window. Uneven time steps are resampled (linear interpolation) onto a uniform
    grid at the median step. The window starts at ``start_s``, or automatically at the largest
    peak of |y|, after which a free decay only decreases. ``lowpass_hz`` applies a zero-phase
    4th-order Butterworth filter (`scipy.signal.filtfilt`).
    """
    t = np.asarray(time_s, dtype=float)
    y = np.asarray(values, dtype=float)
    if t.size == 0:
        raise InputError("signal", "empty", "the file has no samples")
    bad = ~np.isfinite(t) | ~np.isfinite(y)
    if bad.any():
        rows = np.nonzero(bad)[0]
        listed = ", ".join(str(r + 1) for r in rows[:5]) + (" ..." if rows.size > 5 else "")
        raise InputError(
            "signal",
            f"{rows.size} NaN/inf value(s) at data row(s) {listed}",
            "remove or fill them first",
        )
    require_increasing("time", t)
    steps = np.diff(t)
    notes: list[str] = []
    if t.size < 8:
        raise InputError("signal", f"{t.size} samples", "needs at least 8 samples")
    step = float(np.median(steps))
    if steps.max() > 1.01 * steps.min():
        uniform = np.arange(t[0], t[-1] + 0.5 * step, step)
        y = np.interp(uniform, t, y)
        t = uniform
        notes.append(f"resampled uneven steps onto a uniform {1e3 * step:.4g} ms grid")
    raw_t, raw_y = t.copy(), y.copy()
    if lowpass_hz is not None:
        nyquist = 0.5 / step
        if not 0.0 < lowpass_hz < nyquist:
            raise InputError(
                "lowpass", f"{lowpass_hz:g} Hz", f"must be between 0 and the Nyquist {nyquist:g} Hz"
            )
        b, a = sps.butter(4, lowpass_hz / nyquist)
        if y.size > 3 * max(len(a), len(b)):
            y = sps.filtfilt(b, a, y)
            notes.append(f"zero-phase 4th-order Butterworth low-pass at {lowpass_hz:g} Hz")
    if start_s is None:
        start_s = _free_decay_start(t, y)
        notes.append(f"free decay detected from {start_s:.4g} s (largest peak)")
    end = float(t[-1]) if end_s is None else float(end_s)
    inside = (t >= start_s) & (t <= end)
    if np.count_nonzero(inside) < 8:
        raise InputError(
            "window",
            f"[{start_s:.6g}, {end:.6g}] s",
            f"holds fewer than 8 samples; the data span [{t[0]:.6g}, {t[-1]:.6g}] s",
        )
    t_window, y_window = t[inside], y[inside]
    if np.ptp(y_window) <= 1e-12 * max(1.0, float(np.max(np.abs(y_window)))):
        raise InputError("signal", "constant", "has no oscillation in the window")
    if detrend == "mean":
        trend = np.full_like(y_window, y_window.mean())
    elif detrend == "linear":
        trend = y_window - sps.detrend(y_window, type="linear")
    elif detrend == "none":
        trend = np.zeros_like(y_window)
    else:
        raise InputError("detrend", detrend, "must be mean, linear or none")
    y_window = y_window - trend
    return PreparedSignal(
        time_s=t_window,
        values=np.asarray(y_window, dtype=float),
        raw_time_s=raw_t,
        raw_values=raw_y,
        window_s=(float(t_window[0]), float(t_window[-1])),
        notes=tuple(notes),
        trend=np.asarray(trend, dtype=float),
    )


def _free_decay_start(t: FloatArray, y: FloatArray) -> float:
    centred = y - np.median(y)
    peaks, _ = sps.find_peaks(np.abs(centred))
    if peaks.size == 0:
        return float(t[0])
    return float(t[peaks[np.argmax(np.abs(centred[peaks]))]])


@dataclass(frozen=True)
class Estimate:
    """One estimator's result (SI); ``None`` where the estimator cannot say."""

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


def _interpolated_peaks(
    t: FloatArray, y: FloatArray, distance: int, half_width: int = 1
) -> tuple[FloatArray, FloatArray]:
    """Positive peaks refined by a least-squares parabola over +-``half_width`` samples
    (3-point interpolation for 1); a wider parabola averages out noise on the peak."""
    indices, _ = sps.find_peaks(y, distance=max(1, distance))
    half = max(1, half_width)
    indices = indices[(indices >= half) & (indices < y.size - half)]
    indices = indices[y[indices] > 0]
    times, heights = [], []
    for i in indices:
        window_t = t[i - half : i + half + 1] - t[i]
        curvature, slope, value = np.polyfit(window_t, y[i - half : i + half + 1], 2)
        if curvature < 0:
            vertex = -slope / (2 * curvature)
            if abs(vertex) <= window_t[-1]:
                times.append(t[i] + vertex)
                heights.append(value - slope**2 / (4 * curvature))
                continue
        times.append(t[i])
        heights.append(y[i])
    return np.asarray(times), np.asarray(heights)


def spectral_peak(t: FloatArray, y: FloatArray) -> tuple[float, float, float]:
    """(damped frequency [Hz], resolution 1/T [Hz], Hann-windowed spectrum peak estimate)."""
    n = y.size
    step = t[1] - t[0]
    padded = 8 * int(2 ** math.ceil(math.log2(n)))
    spectrum = np.abs(np.fft.rfft(y * np.hanning(n), padded))
    frequencies = np.fft.rfftfreq(padded, step)
    spectrum[0] = 0.0
    k = int(np.argmax(spectrum))
    if 0 < k < spectrum.size - 1 and np.all(spectrum[k - 1 : k + 2] > 0):
        a, b, c = np.log(spectrum[k - 1 : k + 2])
        denominator = a - 2 * b + c
        shift = 0.0 if denominator == 0 else 0.5 * (a - c) / denominator
    else:
        shift = 0.0
    df = frequencies[1] - frequencies[0]
    return float(frequencies[k] + shift * df), 1.0 / (n * step), float(spectrum[k])


def noise_level(y: FloatArray, samples_per_period: float) -> float:
    """Standard deviation of what a Savitzky-Golay smoother (window a quarter period) leaves."""
    window = int(samples_per_period / 4) | 1
    if window < 5 or y.size <= window:
        return 0.0
    smooth = sps.savgol_filter(y, window, 3)
    return float(np.std(y - smooth))


def usable_peaks(t: FloatArray, y: FloatArray, period_s: float) -> tuple[FloatArray, FloatArray]:
    """Peaks and their swing (peak minus the following trough, halved), until the decay
    reaches the noise.

    The swing cancels any offset left by detrending, and is proportional to the amplitude at the
    peak, so ratios Y_0 / Y_k are those of the amplitudes. Peaks are kept while the swing is
    above max(10 % of the first, 10 noise standard deviations): peaks picked from noise are
    biased upwards and would bias the decrement low.
    """
    step = t[1] - t[0]
    distance = int(0.6 * period_s / step)
    # A parabola over +-1/10 period fits a cosine peak to 1e-3 and averages the noise.
    half_width = max(1, int(0.1 * period_s / step))
    times, heights = _interpolated_peaks(t, y, distance, half_width)
    trough_times, trough_depths = _interpolated_peaks(t, -y, distance, half_width)
    swings_t, swings = [], []
    for time_value, height in zip(times, heights, strict=True):
        following = np.nonzero(trough_times > time_value)[0]
        if following.size == 0 or trough_times[following[0]] - time_value > 0.8 * period_s:
            continue
        swings_t.append(time_value)
        swings.append(0.5 * (height + trough_depths[following[0]]))
    times, heights = np.asarray(swings_t), np.asarray(swings)
    if heights.size == 0:
        return times, heights
    floor = max(0.1 * heights[0], 10.0 * noise_level(y, period_s / step))
    below = np.nonzero(heights < floor)[0]
    stop = int(below[0]) if below.size else heights.size
    return times[:stop], heights[:stop]


def estimate_logdec(prepared: PreparedSignal, period_guess_s: float) -> Estimate:
    """The seed paper's method: peaks, logarithmic decrement over k cycles."""
    t, y = prepared.time_s, prepared.values
    t[1] - t[0]
    times, heights = usable_peaks(t, y, period_guess_s)
    if times.size < 3:
        raise InputError(
            "signal",
            f"{times.size} peak(s)",
            "needs at least 3 positive peaks in the window for a logarithmic decrement "
            "(longer record, earlier --start, or less filtering)",
        )
    spacing = np.diff(times)
    if np.std(spacing) > 0.2 * np.mean(spacing):
        raise InputError(
            "signal",
            "irregular peaks",
            f"peak spacing varies by {100 * np.std(spacing) / np.mean(spacing):.0f} %: not a "
            "single free oscillation (noise, beating or forcing); low-pass or move --start",
        )
    cycles = times.size - 1
    delta = math.log(heights[0] / heights[-1]) / cycles
    if delta <= 0.0:
        raise InputError(
            "signal",
            f"log decrement {delta:.3g}",
            "the amplitude grows over the window: not a free decay",
        )
    zeta = zeta_from_log_decrement(delta)
    damped = 2.0 * math.pi / float(np.mean(spacing))
    return Estimate(
        method="logdec",
        omega_n_rad_s=damped / math.sqrt(1.0 - zeta**2),
        damping_ratio=zeta,
        damped_omega_rad_s=damped,
        log_decrement=delta,
        n_peaks=int(times.size),
        amplitude=float(heights[0]),
    )


def estimate_fft(prepared: PreparedSignal) -> Estimate:
    """Spectral peak frequency; bandwidth damping only when it is resolved."""
    t, y = prepared.time_s, prepared.values
    frequency, resolution, _ = spectral_peak(t, y)
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
    zeta = bandwidth / (2.0 * frequency) if frequency > 0 else None
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


def _decay_model(
    t: FloatArray, a: float, b: float, zeta: float, omega: float, c: float, d: float
) -> FloatArray:
    damped = omega * np.sqrt(max(1e-12, 1.0 - zeta**2))
    oscillation = np.exp(-zeta * omega * t) * (a * np.cos(damped * t) + b * np.sin(damped * t))
    return np.asarray(oscillation + c + d * t, dtype=float)


def estimate_fit(prepared: PreparedSignal, omega_guess: float, zeta_guess: float) -> Estimate:
    """Least-squares damped sinusoid plus offset and drift (fitted together, not detrended
    first: removing a line fitted to a decaying oscillation biases zeta), with 95 % confidence
    intervals."""
    t = prepared.time_s - prepared.time_s[0]
    y = prepared.undetrended
    damped = omega_guess * math.sqrt(max(1e-12, 1.0 - zeta_guess**2))
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
                p0=[a0, b0, max(zeta_guess, 1e-4), omega_guess, c0, d0],
                bounds=(
                    [-np.inf, -np.inf, 0.0, 0.2 * omega_guess, -np.inf, -np.inf],
                    [np.inf, np.inf, 0.9, 5.0 * omega_guess, np.inf, np.inf],
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
    dof = max(1, t.size - parameters.size)
    factor = float(stats.t.ppf(0.975, dof))
    errors = np.sqrt(np.clip(np.diag(covariance), 0.0, np.inf))
    a, b, zeta, omega, c, _ = (float(p) for p in parameters)
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
    )


@dataclass(frozen=True, eq=False)
class CalibrationResult:
    """Calibrated frequency and damping, with every estimator's answer for comparison.

    Parameters
    ----------
    method : str
        The estimator reported.
    chosen : Estimate
        Its estimate.
    estimates : dict of str to Estimate
        Every estimator's estimate.
    signal : PreparedSignal
        The windowed, detrended signal.
    source : str
        Where the signal comes from.
    peak_times_s, peak_values : numpy.ndarray
        Detected peaks [s] and their values.

    Examples
    --------
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> t = np.linspace(0.0, 4.0, 2001)
    >>> result = sk.calibrate(t, np.exp(-0.9 * t) * np.cos(30.0 * t))
    >>> sorted(result.estimates)
    ['fft', 'fit', 'logdec']
    """

    method: str
    chosen: Estimate
    estimates: dict[str, Estimate]
    signal: PreparedSignal
    source: str = ""
    peak_times_s: FloatArray = field(default_factory=lambda: np.zeros(0))
    peak_values: FloatArray = field(default_factory=lambda: np.zeros(0))

    @property
    def omega_n_rad_s(self) -> float:
        """Calibrated natural circular frequency [rad/s]."""
        return float(self.chosen.omega_n_rad_s or math.nan)

    @property
    def damping_ratio(self) -> float | None:
        """Calibrated damping ratio [-] (None when the chosen method cannot tell)."""
        return self.chosen.damping_ratio

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready result with the calibrate command's keys."""
        chosen = self.chosen
        damped = chosen.damped_omega_rad_s
        payload: dict[str, Any] = {
            "omega_n_rad_s": chosen.omega_n_rad_s,
            "frequency_hz": None
            if chosen.omega_n_rad_s is None
            else chosen.omega_n_rad_s / (2 * math.pi),
            "damped_frequency_hz": None if damped is None else damped / (2 * math.pi),
            "damping_ratio": chosen.damping_ratio,
            "log_decrement": chosen.log_decrement,
            "method": self.method,
            "window_s": list(self.signal.window_s),
            "n_peaks": int(self.peak_times_s.size),
            "residual_rms": chosen.residual_rms,
            "omega_n_interval_rad_s": None
            if chosen.omega_n_interval is None
            else list(chosen.omega_n_interval),
            "damping_ratio_interval": None
            if chosen.damping_ratio_interval is None
            else list(chosen.damping_ratio_interval),
            "source": self.source,
            "notes": list(self.signal.notes) + [e.note for e in self.estimates.values() if e.note],
            "estimates": {
                name: {
                    "omega_n_rad_s": e.omega_n_rad_s,
                    "frequency_hz": None
                    if e.omega_n_rad_s is None
                    else e.omega_n_rad_s / (2 * math.pi),
                    "damping_ratio": e.damping_ratio,
                    "log_decrement": e.log_decrement,
                }
                for name, e in self.estimates.items()
            },
        }
        payload["disagreement"] = _disagreement(self.estimates)
        return payload

    def calibrated_model(self, model: SloshModel) -> SloshModel:
        """``model`` with mode 1's frequency and every mode's damping ratio replaced.

        The damping applies to all modes, as the correlations do; higher-mode frequencies stay
        theoretical. Provenance records the method, the data file and the window.
        """
        source = (
            f"calibration: {self.method} of {self.source or 'signal'} "
            f"[{self.signal.window_s[0]:.4g}, {self.signal.window_s[1]:.4g}] s"
        )
        calibrated = model.with_mode(1, omega_rad_s=self.omega_n_rad_s, source=source)
        if self.damping_ratio is not None:
            for mode in calibrated.modes:
                calibrated = calibrated.with_mode(
                    mode.n, damping_ratio=self.damping_ratio, source=source
                )
        return calibrated

    def plot(self, path: str | Path | None = None) -> Any:
        """Signal, detected peaks and fitted envelope (the seed paper's Fig. 5b)."""
        return plotter_for(type(self))(self, path=path)


def _disagreement(estimates: dict[str, Estimate]) -> dict[str, float | None]:
    omegas = [e.omega_n_rad_s for e in estimates.values() if e.omega_n_rad_s is not None]
    zetas = [e.damping_ratio for e in estimates.values() if e.damping_ratio is not None]

    def spread(values: list[float]) -> float | None:
        return (max(values) - min(values)) / float(np.mean(values)) if len(values) > 1 else None

    return {
        "omega_n_relative_spread": spread(omegas),
        "damping_ratio_relative_spread": spread(zetas),
    }


def calibrate(
    time_s: FloatArray,
    values: FloatArray,
    method: Method = "fit",
    start_s: float | None = None,
    end_s: float | None = None,
    detrend: Literal["mean", "linear", "none"] = "linear",
    lowpass_hz: float | None = None,
    source: str = "",
) -> CalibrationResult:
    """Frequency and damping of the free decay in (time, values), by every estimator.

    ``method`` chooses which result is reported (and written to a model file); all are computed.
    Raises `InputError` for signals that are not a free decay.

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s], strictly increasing.
    values : numpy.ndarray
        The decaying signal (any unit: wall elevation, angle, ...).
    method : str
        Reported estimator: ``fit``, ``logdec`` or ``fft``.
    start_s, end_s : float, optional
        Window of the free decay [s].
    detrend : {"mean", "linear", "none"}
        Trend removed before estimating.
    lowpass_hz : float, optional
        Low-pass cut-off [Hz].
    source : str
        Where the signal comes from (kept in the provenance).

    Returns
    -------
    CalibrationResult
        The chosen estimate and every estimator's answer.

    References
    ----------
    M. C. De Simone et al., Appl. Sci. 14 (2024) 4522, §3 (logarithmic decrement),
    doi:10.3390/app14114522.

    Examples
    --------
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> t = np.linspace(0.0, 4.0, 2001)
    >>> signal = np.exp(-0.03 * 30.0 * t) * np.cos(30.0 * np.sqrt(1 - 0.03**2) * t)
    >>> result = sk.calibrate(t, signal)
    >>> round(result.omega_n_rad_s, 1), round(result.damping_ratio, 3)
    (30.0, 0.03)
    """
    if method not in METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(METHODS))
    prepared = prepare_signal(time_s, values, start_s, end_s, detrend, lowpass_hz)
    frequency, _, _ = spectral_peak(prepared.time_s, prepared.values)
    if frequency <= 0.0:
        raise InputError("signal", "no spectral peak", "has no oscillation in the window")
    estimates: dict[str, Estimate] = {"fft": estimate_fft(prepared)}
    logdec = estimate_logdec(prepared, 1.0 / frequency)
    estimates["logdec"] = logdec
    estimates["fit"] = estimate_fit(
        prepared,
        float(logdec.omega_n_rad_s or 2 * math.pi * frequency),
        float(logdec.damping_ratio or 0.01),
    )
    if estimates.get(method) is not None and estimates[method].note:
        warnings.warn(estimates[method].note, ValidityWarning, stacklevel=2)
    times, heights = usable_peaks(prepared.time_s, prepared.values, 1.0 / frequency)
    return CalibrationResult(
        method=method,
        chosen=estimates[method],
        estimates={name: estimates[name] for name in METHODS},
        signal=prepared,
        source=source,
        peak_times_s=times,
        peak_values=heights,
    )
