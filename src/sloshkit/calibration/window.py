"""Finding the free decay in a record that starts with the forced motion.

A record from a machine holds the move (the container accelerated by a slide or a robot) and
then the free slosh. During the move the signal carries the forcing: a force sensor sees the
rigid-body inertia m a, often 20 times the slosh force; a height or angle signal sees the
quasi-static tilt a/g. Both lie outside the slosh band. After the move only the free
oscillation at the damped slosh frequency remains, and its envelope only decreases.

`find_free_decay` therefore

1. takes the damped frequency f_d from the spectrum of the record's second half (re-estimated
   once from the detected decay),
2. splits the signal with a zero-phase band-pass around f_d (0.6-1.6 f_d) into the slosh band
   and the rest, and measures both over one-period sliding windows,
3. calls "forcing" every time the out-of-band part exceeds both 4 times its level at the end of
   the record (noise) and 30 % of the slosh-band amplitude there, or the slosh band's local
   frequency (phase rate of its analytic signal, over two periods) differs from f_d by more
   than 6 % where the slosh is well above the noise (a harmonic forcing inside the band),
4. starts the decay at the largest slosh-band envelope after the forcing, plus a settling margin
   (one damped period by default) when forcing was found.

With a motion file the end of the forcing is known exactly; only step 4 remains. The window is
reported with its reason (`DecayWindow`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from scipy import signal as sps
from scipy.ndimage import uniform_filter1d

from sloshkit.calibration.signals import PreparedSignal, spectral_peak, uniform_signal
from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]
Detrend = Literal["mean", "linear", "none"]

#: Settling margin after the end of the forcing, in damped periods.
SETTLE_PERIODS = 1.0
#: A local frequency this far (relative) from the decay's is forcing (a softening mode drifts
#: less: 4 % at a 0.8 rad pendulum amplitude).
FREQUENCY_CHANGE = 0.06


@dataclass(frozen=True)
class DecayWindow:
    """The analysis window and why it was chosen.

    ``source`` is ``"user"`` (``--start``), ``"motion"`` (end of a motion file + margin),
    ``"signal"`` (forcing end detected in the signal + margin) or ``"decay"`` (no forcing
    found: from the largest slosh envelope).

    Attributes
    ----------
    start_s, end_s : float
        The window [s].
    source : str
        user, motion, signal or decay.
    reason : str
        Why, in words.
    forcing_end_s : float or None
        Where the forcing ends [s], when known.
    settle_s : float
        Settling margin after the forcing [s].
    frequency_hz : float or None
        Slosh frequency used to find the window [Hz].

    Examples
    --------
    >>> DecayWindow(1.0, 4.0, "user", "--start").to_dict()["start_s"]
    1.0
    """

    start_s: float
    end_s: float
    source: str
    reason: str
    forcing_end_s: float | None = None
    settle_s: float = 0.0
    frequency_hz: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description with unit-suffixed keys."""
        return {
            "start_s": self.start_s,
            "end_s": self.end_s,
            "source": self.source,
            "reason": self.reason,
            "forcing_end_s": self.forcing_end_s,
            "settle_s": self.settle_s,
        }


def slosh_band(t: FloatArray, y: FloatArray, frequency_hz: float) -> tuple[FloatArray, FloatArray]:
    """(slosh-band part, everything else) of a uniform record: zero-phase 2nd-order
    Butterworth band-pass 0.6-1.6 f (`scipy.signal.sosfiltfilt`).

    Parameters
    ----------
    t, y : numpy.ndarray
        Uniform times [s] and the record.
    frequency_hz : float
        Slosh frequency [Hz].

    Returns
    -------
    tuple of numpy.ndarray
        (slosh band, the rest).

    Examples
    --------
    A slow drift and the slosh separate:

    >>> import numpy as np
    >>> t = np.arange(0.0, 10.0, 0.01)
    >>> slosh, rest = slosh_band(t, np.sin(2 * np.pi * 5 * t) + 0.5 * t, 5.0)
    >>> round(float(np.std(slosh[200:-200])), 2)
    0.71
    """
    nyquist = 0.5 / (t[1] - t[0])
    low, high = 0.6 * frequency_hz / nyquist, min(0.95, 1.6 * frequency_hz / nyquist)
    if not 0.0 < low < high:
        raise InputError(
            "signal", f"{frequency_hz:.4g} Hz", "is too close to the Nyquist frequency"
        )
    sos = sps.butter(2, [low, high], btype="bandpass", output="sos")
    band = sps.sosfiltfilt(sos, y - np.median(y))
    return np.asarray(band, dtype=float), np.asarray(y - np.median(y) - band, dtype=float)


def _moving_std(values: FloatArray, width: int) -> FloatArray:
    mean = uniform_filter1d(values, width, mode="nearest")
    square = uniform_filter1d(values**2, width, mode="nearest")
    return np.asarray(np.sqrt(np.clip(square - mean**2, 0.0, None)), dtype=float)


def _detect(
    t: FloatArray, y: FloatArray, frequency_hz: float, forcing_end_s: float | None
) -> tuple[float | None, float]:
    """(end of forcing found in the signal or None, time of the largest envelope after it)."""
    band, rest = slosh_band(t, y, frequency_hz)
    width = max(3, round(1.0 / (frequency_hz * (t[1] - t[0]))))
    outside = _moving_std(rest, width)
    envelope = math.sqrt(2.0) * np.sqrt(uniform_filter1d(band**2, width, mode="nearest"))
    signal = sps.hilbert(band)
    analytic = np.abs(signal)
    detected = forcing_end_s
    if detected is None:
        tail = t >= t[0] + 0.7 * (t[-1] - t[0])
        reference = float(np.median(outside[tail]))
        forcing = (outside > 4.0 * reference) & (outside > 0.3 * envelope)
        # A harmonic forcing inside the slosh band shows as a local frequency (phase rate of
        # the analytic signal over two periods) away from the decay's, where the slosh is
        # well above the noise.
        rate = np.gradient(np.unwrap(np.angle(signal)), t) / (2.0 * math.pi)
        local = uniform_filter1d(rate, 2 * width, mode="nearest")
        strong = (envelope > 10.0 * reference) & (envelope > 1e-3 * float(envelope.max()))
        forcing |= strong & (np.abs(local / frequency_hz - 1.0) > FREQUENCY_CHANGE)
        # The edges of the filters and of the sliding windows are not forcing.
        forcing[: 2 * width] = False
        forcing[-2 * width :] = False
        hits = np.nonzero(forcing)[0]
        detected = float(t[hits[-1]]) if hits.size else None
    after = t >= (t[0] if detected is None else detected)
    # The analytic envelope rings at the record's end: never start there.
    after[-2 * width :] = False
    candidates = np.nonzero(after)[0]
    if candidates.size == 0:
        return detected, float(t[-1])
    top = candidates[int(np.argmax(analytic[candidates]))]
    return detected, float(t[top])


def find_free_decay(
    time_s: FloatArray,
    values: FloatArray,
    *,
    forcing_end_s: float | None = None,
    settle_s: float | None = None,
    end_s: float | None = None,
) -> DecayWindow:
    """The window of the free decay in a uniformly sampled record (see the module docstring).

    Parameters
    ----------
    time_s, values : uniform record (`uniform_signal`)
    forcing_end_s : end of the forcing when known (motion file) [s]; detected when None
    settle_s : margin after the end of the forcing [s]; default one damped period
    end_s : window end [s]; default the last sample

    Returns
    -------
    DecayWindow with the start, the end, the forcing end and the reason.

    References
    ----------
    Butterworth band-split and sliding RMS: Oppenheim & Schafer, *Discrete-Time Signal
    Processing*, 3rd ed. (2010) §7.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 8, 0.002)
    >>> move = np.where(t < 2, 20 * np.sin(np.pi * t / 2) ** 2, 0.0)
    >>> decay = np.where(t >= 2, np.exp(-0.6 * (t - 2)) * np.sin(29 * (t - 2)), 0.0)
    >>> window = find_free_decay(t, move + decay)
    >>> window.source, 2.0 <= window.start_s < 2.6
    ('signal', True)
    """
    t = np.asarray(time_s, dtype=float)
    y = np.asarray(values, dtype=float)
    end = float(t[-1]) if end_s is None else float(end_s)
    span = float(t[-1] - t[0])
    margin_periods = SETTLE_PERIODS

    def peak_after(moment: float) -> float:
        part = t >= moment
        if np.count_nonzero(part) < 16:
            return 0.0
        return spectral_peak(t[part], sps.detrend(y[part]))[0]

    if forcing_end_s is not None:
        frequency = peak_after(float(forcing_end_s))
        if not frequency > 0.0:
            raise InputError(
                "motion", f"ends at {forcing_end_s:.4g} s", "leaves no record after it"
            )
        detected, top = _detect(t, y, frequency, forcing_end_s)
    else:
        # The decay's frequency from a tail of the record, checked against the window it
        # leads to (a short decay after a long move needs a short tail).
        found: tuple[float, float | None, float] | None = None
        for fraction in (0.5, 0.7, 0.85):
            guess = peak_after(float(t[0]) + fraction * span)
            if not guess > 0.0:
                continue
            detected, top = _detect(t, y, guess, None)
            frequency = peak_after(top)
            if not frequency > 0.0:
                continue
            detected, top = _detect(t, y, frequency, None)
            start = top if detected is None else max(top, detected + margin_periods / frequency)
            if (t[-1] - start) * frequency >= 3.0:
                found = (frequency, detected, top)
                break
        if found is None:
            raise InputError(
                "signal",
                "no free decay",
                "found no free oscillation of at least 3 periods after the forcing; give the "
                "window (--start) or the motion (--motion-file)",
            )
        frequency, detected, top = found
    period = 1.0 / frequency
    margin = margin_periods * period if settle_s is None else float(settle_s)
    if forcing_end_s is not None:
        start = max(float(forcing_end_s) + margin, float(t[0]))
        return DecayWindow(
            start_s=start,
            end_s=end,
            source="motion",
            reason=f"motion ends at {forcing_end_s:.4g} s (motion file); settling margin "
            f"{margin:.3g} s",
            forcing_end_s=float(forcing_end_s),
            settle_s=margin,
            frequency_hz=frequency,
        )
    if detected is not None:
        start = max(detected + margin, top)
        return DecayWindow(
            start_s=start,
            end_s=end,
            source="signal",
            reason=f"forcing found in the signal until {detected:.4g} s (out-of-band content "
            f"above 4x its end-of-record level); settling margin {margin:.3g} s; largest "
            f"slosh envelope after it at {top:.4g} s",
            forcing_end_s=detected,
            settle_s=margin,
            frequency_hz=frequency,
        )
    return DecayWindow(
        start_s=top,
        end_s=end,
        source="decay",
        reason=f"no forcing found in the signal; from the largest slosh envelope at {top:.4g} s",
        frequency_hz=frequency,
    )


def prepare_signal(
    time_s: FloatArray,
    values: FloatArray,
    start_s: float | None = None,
    end_s: float | None = None,
    detrend: Detrend = "linear",
    lowpass_hz: float | None = None,
    *,
    forcing_end_s: float | None = None,
    settle_s: float | None = None,
) -> tuple[PreparedSignal, DecayWindow]:
    """Check, resample, low-pass, window and detrend a record.

    The window starts at ``start_s`` when given, else where `find_free_decay` puts it (after
    ``forcing_end_s`` when known). Raises `InputError` for bad records or an empty window.

    Parameters
    ----------
    time_s, values : numpy.ndarray
        The record [s] (signal units).
    start_s, end_s : float, optional
        The window [s] (default: found in the record; to its end).
    detrend : str
        mean, linear or none.
    lowpass_hz : float, optional
        Zero-phase low-pass cut-off [Hz].
    forcing_end_s : float, optional
        Where the forcing ends [s], when known.
    settle_s : float, optional
        Settling margin after the forcing [s] (default: `SETTLE_PERIODS` periods).

    Returns
    -------
    tuple
        (`PreparedSignal`, `DecayWindow`).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 4, 0.005)
    >>> prepared, window = prepare_signal(t, np.exp(-t) * np.cos(30 * t), start_s=1.0)
    >>> prepared.window_s[0], window.source
    (1.0, 'user')
    """
    t, y, notes = uniform_signal(time_s, values, lowpass_hz)
    if np.ptp(y) <= 1e-12 * max(1.0, float(np.max(np.abs(y)))):
        raise InputError("signal", "constant", "has no oscillation")
    if start_s is None:
        window = find_free_decay(t, y, forcing_end_s=forcing_end_s, settle_s=settle_s, end_s=end_s)
    else:
        end = float(t[-1]) if end_s is None else float(end_s)
        window = DecayWindow(float(start_s), end, "user", "window start given by the user")
    inside = (t >= window.start_s - 1e-12) & (t <= window.end_s + 1e-12)
    if np.count_nonzero(inside) < 8:
        raise InputError(
            "window",
            f"[{window.start_s:.6g}, {window.end_s:.6g}] s",
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
    if window.source != "user":
        notes.append(f"free decay from {window.start_s:.4g} s: {window.reason}")
    prepared = PreparedSignal(
        time_s=t_window,
        values=np.asarray(y_window - trend, dtype=float),
        raw_time_s=t,
        raw_values=y,
        window_s=(float(t_window[0]), float(t_window[-1])),
        notes=tuple(notes),
        trend=np.asarray(trend, dtype=float),
    )
    return prepared, window
