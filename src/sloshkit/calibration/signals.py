"""Signal preparation shared by the calibration estimators: checks, uniform resampling,
low-pass filtering, the spectral peak, a robust noise level and the usable peaks of a decay."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import signal as sps

from sloshkit.errors import InputError, require_increasing

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class PreparedSignal:
    """A uniformly sampled signal in the analysis window, with how it was prepared.

    ``raw_time_s``/``raw_values`` hold the whole (resampled, filtered) record, ``time_s``/``values``
    the detrended window and ``trend`` what detrending removed from it.

    Attributes
    ----------
    time_s, values : numpy.ndarray
        The detrended window [s] (signal units).
    raw_time_s, raw_values : numpy.ndarray
        The whole resampled, filtered record.
    window_s : tuple of float
        Start and end of the window [s].
    notes : tuple of str
        How the record was prepared.
    trend : numpy.ndarray or None
        What detrending removed from the window.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 1.0, 0.25)
    >>> signal = PreparedSignal(t, np.ones(4), t, np.ones(4), (0.0, 0.75), trend=np.ones(4))
    >>> signal.sample_period_s, signal.undetrended.tolist()
    (0.25, [2.0, 2.0, 2.0, 2.0])
    """

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

    @property
    def sample_period_s(self) -> float:
        """Uniform sample period of the prepared signal [s]."""
        return float(self.time_s[1] - self.time_s[0])


def uniform_signal(
    time_s: FloatArray, values: FloatArray, lowpass_hz: float | None = None
) -> tuple[FloatArray, FloatArray, list[str]]:
    """Check a record and return it on a uniform grid, optionally low-passed.

    Raises `InputError` for NaN values, duplicate or decreasing time stamps or fewer than 8
    samples. Uneven time steps are resampled (linear interpolation) onto a uniform grid at the
    median step. ``lowpass_hz`` applies a zero-phase 4th-order Butterworth filter
    (`scipy.signal.sosfiltfilt`).

    Parameters
    ----------
    time_s : sample times [s], strictly increasing
    values : the signal (any unit)
    lowpass_hz : optional cut-off [Hz]

    Returns
    -------
    (time [s], values, notes): the uniform record and what was done to it.

    Examples
    --------
    >>> import numpy as np
    >>> t, y, notes = uniform_signal(np.array([0, 0.1, 0.21, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8]),
    ...                              np.arange(9.0))
    >>> round(float(t[1] - t[0]), 3), notes[0].startswith("resampled")
    (0.1, True)
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
    if t.size < 8:
        raise InputError("signal", f"{t.size} samples", "needs at least 8 samples")
    steps = np.diff(t)
    notes: list[str] = []
    step = float(np.median(steps))
    if steps.max() > 1.01 * steps.min():
        uniform = np.arange(t[0], t[-1] + 0.5 * step, step)
        uniform = uniform[uniform <= t[-1] + 1e-12]
        y = np.interp(uniform, t, y)
        t = uniform
        notes.append(f"resampled uneven steps onto a uniform {1e3 * step:.4g} ms grid")
    if lowpass_hz is not None:
        nyquist = 0.5 / step
        if not 0.0 < lowpass_hz < nyquist:
            raise InputError(
                "lowpass", f"{lowpass_hz:g} Hz", f"must be between 0 and the Nyquist {nyquist:g} Hz"
            )
        sos = sps.butter(4, lowpass_hz / nyquist, output="sos")
        if y.size > 30:
            y = sps.sosfiltfilt(sos, y)
            notes.append(f"zero-phase 4th-order Butterworth low-pass at {lowpass_hz:g} Hz")
    return t, np.asarray(y, dtype=float), notes


def spectral_peak(t: FloatArray, y: FloatArray) -> tuple[float, float, float]:
    """(damped frequency [Hz], resolution 1/T [Hz], Hann-windowed spectrum peak estimate).

    Zero-padded, Hann-windowed spectrum with Gaussian (log-parabolic) interpolation of the peak
    (Gasior & Gonzalez, CERN-AB-2004-023).

    Parameters
    ----------
    t, y : numpy.ndarray
        Uniform times [s] and the signal.

    Returns
    -------
    tuple of float
        (peak frequency [Hz], resolution [Hz], the peak's spectral height).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 4, 0.01)
    >>> round(spectral_peak(t, np.sin(2 * np.pi * 3.3 * t))[0], 2)
    3.3
    """
    n = y.size
    step = t[1] - t[0]
    padded = 8 * int(2 ** math.ceil(math.log2(n)))
    spectrum = np.abs(np.fft.rfft((y - np.mean(y)) * np.hanning(n), padded))
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
    """Robust standard deviation of the measurement noise of an oscillation.

    What a cubic Savitzky-Golay smoother over a quarter period leaves is noise (a sinusoid is
    reproduced to < 1e-3); its median absolute deviation / 0.6745 estimates the noise standard
    deviation without being pulled by spikes, and dividing by sqrt(1 - h_0) (h_0 the smoother's
    centre weight) undoes the part of the noise the smoother keeps. Quantisation counts as
    noise (step / sqrt(12)).

    Parameters
    ----------
    y : numpy.ndarray
        Uniformly sampled oscillation.
    samples_per_period : float
        Samples in one period of the oscillation.

    Returns
    -------
    float
        The noise standard deviation (signal units).

    References
    ----------
    Rousseeuw & Croux, JASA 88 (1993) 1273, doi:10.1080/01621459.1993.10476408;
    Savitzky & Golay, Anal. Chem. 36 (1964) 1627, doi:10.1021/ac60214a047.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 10, 0.002)
    >>> y = np.sin(2 * np.pi * 4 * t) + np.random.default_rng(1).normal(0, 0.01, t.size)
    >>> round(noise_level(y, 125.0), 3)
    0.01
    """
    window = int(samples_per_period / 4) | 1
    if window < 7 or y.size <= window:
        window = 7
        if y.size <= window:
            return 0.0
    smooth = sps.savgol_filter(y, window, 3)
    centre = float(sps.savgol_coeffs(window, 3)[window // 2])
    residual = y - smooth
    mad = float(np.median(np.abs(residual - np.median(residual))))
    return mad / 0.6745 / math.sqrt(max(1e-6, 1.0 - centre))


def interpolated_peaks(
    t: FloatArray, y: FloatArray, distance: int, half_width: int = 1, guard: int = 0
) -> tuple[FloatArray, FloatArray]:
    """Positive peaks refined by a least-squares parabola over +-``half_width`` samples
    (3-point interpolation for 1); a wider parabola averages out noise on the peak.

    A peak must be the largest sample within +-``guard`` samples, all inside the record: at
    the record's edges a decaying signal has a local maximum made by noise, not a peak.

    Parameters
    ----------
    t, y : numpy.ndarray
        Uniform times [s] and the signal.
    distance : int
        Smallest distance between peaks [samples].
    half_width : int
        Half-width of the parabola [samples].
    guard : int
        Half-width of the neighbourhood a peak must dominate [samples].

    Returns
    -------
    tuple of numpy.ndarray
        Peak times [s] and heights.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 1.0, 0.01)
    >>> times, heights = interpolated_peaks(t, np.cos(2 * np.pi * 3 * (t - 0.105)), 20)
    >>> np.round(times, 3).tolist(), np.round(heights, 3).tolist()
    ([0.105, 0.438, 0.772], [1.0, 1.0, 1.0])
    """
    indices, _ = sps.find_peaks(y, distance=max(1, distance))
    half = max(1, half_width, guard)
    indices = indices[(indices >= half) & (indices < y.size - half)]
    indices = indices[y[indices] > 0]
    if guard > 0:
        indices = np.asarray(
            [i for i in indices if y[i] >= np.max(y[i - guard : i + guard + 1])], dtype=int
        )
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
    return np.asarray(times, dtype=float), np.asarray(heights, dtype=float)


#: A swing is usable while it exceeds this many noise standard deviations.
PEAK_FLOOR_NOISE = 8.0


def usable_peaks(
    t: FloatArray, y: FloatArray, period_s: float, noise: float | None = None
) -> tuple[FloatArray, FloatArray]:
    """Peaks and their swing (peak minus the following trough, halved), until the decay
    reaches the noise.

    The swing cancels any offset left by detrending and is proportional to the amplitude at the
    peak, so ratios Y_0 / Y_k are those of the amplitudes. Peaks are kept while the swing stays
    above `PEAK_FLOOR_NOISE` noise standard deviations of the decay itself (`noise_level`):
    peaks picked from noise are biased upwards and would bias the decrement low. The floor does
    not depend on the largest swing, so a large forced motion before the window cannot hide
    the decay.

    Parameters
    ----------
    t, y : numpy.ndarray
        Uniform times [s] and the decay.
    period_s : float
        Damped period [s].
    noise : float, optional
        Noise standard deviation (default: `noise_level`).

    Returns
    -------
    tuple of numpy.ndarray
        Peak times [s] and swings.

    Examples
    --------
    The swings of a decay with zeta = 0.02 fall by exp(2 pi zeta) per cycle:

    >>> import numpy as np
    >>> t = np.arange(0.0, 2.0, 0.001)
    >>> times, swings = usable_peaks(t, np.exp(-0.02 * 30 * t) * np.cos(30 * t), 2 * np.pi / 30)
    >>> round(float(np.log(swings[0] / swings[1])), 3), round(2 * np.pi * 0.02, 3)
    (0.126, 0.126)
    """
    step = t[1] - t[0]
    distance = int(0.6 * period_s / step)
    # A parabola over +-1/10 period fits a cosine peak to 1e-3 and averages the noise.
    half_width = max(1, int(0.1 * period_s / step))
    guard = int(0.25 * period_s / step)
    times, heights = interpolated_peaks(t, y, distance, half_width, guard)
    trough_times, trough_depths = interpolated_peaks(t, -y, distance, half_width, guard)
    swings_t, swings = [], []
    for time_value, height in zip(times, heights, strict=True):
        following = np.nonzero(trough_times > time_value)[0]
        if following.size == 0 or trough_times[following[0]] - time_value > 0.8 * period_s:
            continue
        swings_t.append(time_value)
        swings.append(0.5 * (height + trough_depths[following[0]]))
    peak_t, swing = np.asarray(swings_t, dtype=float), np.asarray(swings, dtype=float)
    if swing.size == 0:
        return peak_t, swing
    sigma = noise_level(y, period_s / step) if noise is None else noise
    floor = PEAK_FLOOR_NOISE * sigma
    below = np.nonzero(swing <= floor)[0]
    stop = int(below[0]) if below.size else swing.size
    return peak_t[:stop], swing[:stop]
