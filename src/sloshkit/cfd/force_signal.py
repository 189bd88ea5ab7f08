"""The wall force of a CFD case as the signal of its free decay: is it usable, and how much
spurious high-frequency content (parasitic currents) does it carry.

In free decay the lateral wall force of the first mode oscillates at the same frequency and
decays at the same rate as the wall elevation: in linear modal theory both are proportional
to the modal amplitude (Abramson, NASA SP-106, 1966, ch. 2 and 6). The force integrates the
pressure over the whole wall instead of the volume fraction along a thin column of probes, so
on coarse meshes (where the slosh amplitude is about one cell) it gives the same frequency and
damping with far less estimator scatter (the damping study in docs/cfd.md: fit and
logarithmic decrement agree within 20 % on the wall force in every uniform run, and differ by
up to 6.4x on the probe elevation).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

#: Noise ratio above which a wall force is taken to carry parasitic currents. The damping
#: study (studies/cfd-damping/README.md; its cfd_damping_estimators.py) measured at most 0.23
#: in every clean run and at least 0.88 in every run with parasitic currents (graded meshes at
#: small steps); 0.5 lies between the two groups.
NOISE_RATIO_LIMIT = 0.5

#: Step alternation (`step_alternation`) above which a wall force carries interFoam's
#: step-to-step pressure oscillation. The damping study (studies/cfd-damping/README.md; its
#: cfd_damping_estimators.py) measured 0.0002-0.0019 on uniform meshes and at most 0.0044 on
#: the wall-graded runs whose damping agrees across steps, and 0.013-0.96 on the runs where
#: the oscillation is visible in the force (where the damping moved by up to a third,
#: up or down, between neighbouring steps); 0.01 lies between the two groups.
STEP_ALTERNATION_LIMIT = 0.01

#: The cutoff of `noise_ratio` as a multiple of the first-mode frequency (15 Hz in the study,
#: whose first mode is near 5 Hz).
NOISE_CUTOFF_FACTOR = 3.0


def usable_force(force_n: ArrayLike) -> bool:
    """Whether a wall-force record can carry a calibration: every sample finite and not all
    equal (a case without force output, or a synthetic one, writes zeros).

    Parameters
    ----------
    force_n : array_like
        Wall force samples [N].

    Returns
    -------
    bool

    Examples
    --------
    >>> usable_force([0.0, 0.0, 0.0]), usable_force([0.0, 1e-4, -1e-4])
    (False, True)
    >>> usable_force([0.0, float("nan"), 1.0])
    False
    """
    values = np.asarray(force_n, dtype=float)
    if values.size < 2 or not np.all(np.isfinite(values)):
        return False
    return bool(np.ptp(values) > 1e-12 * max(float(np.max(np.abs(values))), 1e-300))


def noise_ratio(
    time_s: ArrayLike,
    values: ArrayLike,
    *,
    cutoff_hz: float,
    start_s: float = 0.0,
    stop_s: float = math.inf,
) -> float:
    """RMS of the part of a uniformly sampled signal above ``cutoff_hz`` over the RMS of the
    part below it, between ``start_s`` and ``stop_s``: the spurious high-frequency content
    that parasitic currents put into the wall force. The whole record is filtered; the
    window only selects the samples compared.

    The low-pass part is a zero-phase 4th-order Butterworth filter (``scipy.signal.butter``
    and ``sosfiltfilt``); the high-pass part is the signal minus it.

    Parameters
    ----------
    time_s : array_like
        Uniform sample times [s].
    values : array_like
        The signal.
    cutoff_hz : float
        Cutoff [Hz] (the study: three times the first-mode frequency, `NOISE_CUTOFF_FACTOR`).
    start_s, stop_s : float
        Only samples after ``start_s`` and up to ``stop_s`` count [s].

    Returns
    -------
    float
        The ratio; nan when it cannot be measured (the cutoff at or above the Nyquist
        frequency, too few samples, or no low-frequency content).

    References
    ----------
    Butterworth, "On the theory of filter amplifiers", Wireless Engineer 7 (1930) 536-541;
    the threshold `NOISE_RATIO_LIMIT` is the damping study's (docs/cfd.md).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 2.0, 1e-3)
    >>> clean = np.sin(2 * np.pi * 5.0 * t)
    >>> round(noise_ratio(t, clean, cutoff_hz=15.0, start_s=0.5), 2)  # filter edge effects
    0.04
    >>> noisy = clean + 0.5 * np.sin(2 * np.pi * 80.0 * t)
    >>> round(noise_ratio(t, noisy, cutoff_hz=15.0, start_s=0.5), 2)
    0.5
    >>> burst = clean + np.where(t > 1.5, 0.5 * np.sin(2 * np.pi * 80.0 * t), 0.0)
    >>> round(noise_ratio(t, burst, cutoff_hz=15.0, start_s=0.5, stop_s=1.4), 2)
    0.0
    """
    from scipy.signal import butter, sosfiltfilt

    t = np.asarray(time_s, dtype=float)
    y = np.asarray(values, dtype=float)
    if t.size < 32 or not math.isfinite(cutoff_hz) or cutoff_hz <= 0:
        return math.nan
    sample_rate = 1.0 / float(t[1] - t[0])
    if cutoff_hz >= 0.5 * sample_rate:
        return math.nan
    sos = butter(4, cutoff_hz, fs=sample_rate, output="sos")
    smooth = sosfiltfilt(sos, y)
    inside = (t > start_s) & (t <= stop_s)
    if np.count_nonzero(inside) < 2:
        return math.nan
    low = float(np.std(smooth[inside]))
    if low == 0.0:
        return math.nan
    return float(np.std((y - smooth)[inside]) / low)


def step_alternation(values: ArrayLike) -> float:
    """RMS of the step-to-step alternating part of a signal sampled at every time step, over
    the RMS of the signal: how much of a sign change at every step it carries.

    The alternating part is a quarter of the second difference,
    a[n] = (y[n+1] - 2 y[n] + y[n-1]) / 4. For y = A (-1)^n it is exactly A; for a smooth
    oscillation y = A sin(w n dt) it is A sin^2(w dt / 2), about (w dt / 2)^2 A (2.5e-4 A for
    the 5 Hz first mode at a 1 ms step). So the ratio measures a step-to-step oscillation
    directly, with a background set by the step, unlike a low-pass split (`noise_ratio`),
    which also counts higher slosh modes.

    Parameters
    ----------
    values : array_like
        The signal, one sample per time step (at least 3).

    Returns
    -------
    float
        The ratio; nan with fewer than 3 samples or a zero signal.

    References
    ----------
    The second difference's response to a sampled sinusoid, -4 sin^2(w dt / 2), e.g.
    R. W. Hamming, *Digital Filters*, 3rd ed., Dover (1998), §3.6; the threshold
    `STEP_ALTERNATION_LIMIT` is the damping study's (docs/cfd.md).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 2.0, 1e-3)
    >>> clean = np.sin(2 * np.pi * 5.0 * t)
    >>> round(step_alternation(clean), 6)  # sin^2(pi * 5 Hz * 1 ms)
    0.000247
    >>> flip = 0.1 * (-1.0) ** np.arange(t.size)
    >>> round(step_alternation(clean + flip), 3)  # 0.1 / sqrt(0.5 + 0.01)
    0.14
    """
    y = np.asarray(values, dtype=float)
    if y.size < 3:
        return math.nan
    scale = float(np.sqrt(np.mean(y**2)))
    if scale == 0.0 or not math.isfinite(scale):
        return math.nan
    alternating = (y[2:] - 2.0 * y[1:-1] + y[:-2]) / 4.0
    return float(np.sqrt(np.mean(alternating**2)) / scale)
