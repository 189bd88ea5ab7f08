"""The logarithmic-decrement estimators of a free decay, over the peaks above the noise.

- ``logdec``: weighted robust regression of ln(swing) on the peak times over every peak above
  the noise, slope -zeta omega_n (Inman, *Engineering Vibration*, 4th ed. (2014) §1.6, written
  as a regression like Ewins, *Modal Testing*, 2nd ed. (2000) §4.3), with a 95 % interval. Each
  swing's weight is its inverse variance in the logarithm (swing / noise)^2, and a soft-L1 loss
  (`scipy.optimize.least_squares`) limits the pull of a single noise spike.
- ``logdec-2peak``: the seed paper's form over the first and last usable peak,
  delta = ln(Y_0 / Y_k) / k (seed paper eqs. 11-12), kept for comparison.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy import stats
from scipy.optimize import least_squares

from sloshkit.calibration.estimators import Estimate, zeta_from_log_decrement
from sloshkit.calibration.signals import PreparedSignal, noise_level, usable_peaks
from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


def _checked_peaks(
    prepared: PreparedSignal, period_guess_s: float
) -> tuple[FloatArray, FloatArray, float]:
    t, y = prepared.time_s, prepared.values
    noise = noise_level(y, period_guess_s / (t[1] - t[0]))
    times, heights = usable_peaks(t, y, period_guess_s, noise)
    if times.size < 3:
        raise InputError(
            "signal",
            f"{times.size} peak(s) above the noise",
            "needs at least 3 positive peaks in the window for a logarithmic decrement "
            "(longer record, lower noise or less filtering)",
        )
    spacing = np.diff(times)
    if np.std(spacing) > 0.2 * np.mean(spacing):
        raise InputError(
            "signal",
            "irregular peaks",
            f"peak spacing varies by {100 * np.std(spacing) / np.mean(spacing):.0f} %: not a "
            "single free oscillation (noise, beating or forcing); low-pass or move --start",
        )
    return times, heights, noise


def _from_decrement(
    method: str, delta: float, damped: float, times: FloatArray, heights: FloatArray
) -> Estimate:
    if delta <= 0.0:
        raise InputError(
            "signal",
            f"log decrement {delta:.3g}",
            "the amplitude grows over the window: not a free decay",
        )
    zeta = zeta_from_log_decrement(delta)
    return Estimate(
        method=method,
        omega_n_rad_s=damped / math.sqrt(1.0 - zeta**2),
        damping_ratio=zeta,
        damped_omega_rad_s=damped,
        log_decrement=delta,
        n_peaks=int(times.size),
        amplitude=float(heights[0]),
    )


def estimate_logdec_2peak(prepared: PreparedSignal, period_guess_s: float) -> Estimate:
    """The seed paper's form: delta = ln(Y_0 / Y_k) / k over the first and last usable peak;
    the damped period is the mean peak spacing.

    Parameters
    ----------
    prepared : PreparedSignal
        The window of the free decay.
    period_guess_s : float
        Expected damped period [s] (spaces the peak search).

    Returns
    -------
    Estimate
        Method ``logdec-2peak``.

    References
    ----------
    De Simone, M. C. et al., the seed paper, eqs. 11-12.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration.window import prepare_signal
    >>> t = np.arange(0.0, 4.0, 0.002)
    >>> omega, zeta = 30.0, 0.02
    >>> y = np.exp(-zeta * omega * t) * np.cos(omega * np.sqrt(1 - zeta**2) * t)
    >>> prepared, _ = prepare_signal(t, y, start_s=0.0)
    >>> found = estimate_logdec_2peak(prepared, 2 * np.pi / 30.0)
    >>> round(found.damping_ratio, 3), found.n_peaks > 10
    (0.02, True)
    """
    times, heights, _ = _checked_peaks(prepared, period_guess_s)
    cycles = np.round((times[-1] - times[0]) / float(np.median(np.diff(times))))
    delta = math.log(heights[0] / heights[-1]) / max(1.0, float(cycles))
    damped = 2.0 * math.pi * cycles / float(times[-1] - times[0])
    return _from_decrement("logdec-2peak", delta, damped, times, heights)


def estimate_logdec(prepared: PreparedSignal, period_guess_s: float) -> Estimate:
    """Regression of ln(swing) over all usable peaks (module docstring), with 95 % intervals
    on zeta (from the decay rate) and omega_n (from the regression of peak time on cycle).

    Parameters
    ----------
    prepared : PreparedSignal
        The window of the free decay.
    period_guess_s : float
        Expected damped period [s] (spaces the peak search).

    Returns
    -------
    Estimate
        Method ``logdec``, with 95 % intervals.

    References
    ----------
    Inman, D. J., *Engineering Vibration*, 4th ed. (2014) §1.6.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration.window import prepare_signal
    >>> t = np.arange(0.0, 4.0, 0.002)
    >>> omega, zeta = 30.0, 0.02
    >>> y = np.exp(-zeta * omega * t) * np.cos(omega * np.sqrt(1 - zeta**2) * t)
    >>> prepared, _ = prepare_signal(t, y, start_s=0.0)
    >>> found = estimate_logdec(prepared, 2 * np.pi / 30.0)
    >>> round(found.omega_n_rad_s, 1), round(found.damping_ratio, 3)
    (30.0, 0.02)
    >>> low, high = found.damping_ratio_interval
    >>> bool(low <= 0.02 <= high)
    True
    """
    times, heights, noise = _checked_peaks(prepared, period_guess_s)
    cycles = np.round((times - times[0]) / float(np.median(np.diff(times))))
    design = np.column_stack((np.ones_like(cycles), cycles))
    (_, period), period_residual, *_ = np.linalg.lstsq(design, times, rcond=None)
    n = times.size
    dof = max(1, n - 2)
    factor = float(stats.t.ppf(0.975, dof))
    cycle_spread = float(np.sum((cycles - cycles.mean()) ** 2))
    period_rss = float(period_residual[0]) if period_residual.size else 0.0
    period_se = math.sqrt(period_rss / dof / cycle_spread) if cycle_spread > 0 else 0.0
    # Standard deviation of ln(swing) for each peak: noise of a swing over the swing.
    step = prepared.time_s[1] - prepared.time_s[0]
    points = max(3, 2 * int(0.1 * period / step) + 1)
    sigma_log = np.maximum(noise * math.sqrt(1.0 / points), 1e-12 * heights.max()) / heights
    tau = times - times[0]

    def residuals(p: FloatArray) -> FloatArray:
        return np.asarray((np.log(heights) - (p[0] - p[1] * tau)) / sigma_log, dtype=float)

    slope0 = -np.polyfit(tau, np.log(heights), 1, w=1.0 / sigma_log)[0]
    solution = least_squares(residuals, [math.log(heights[0]), slope0], loss="soft_l1", f_scale=2.0)
    rate = float(solution.x[1])
    jac = solution.jac
    rss = float(np.sum(solution.fun**2))
    try:
        covariance = np.linalg.inv(jac.T @ jac) * rss / dof
        rate_se = math.sqrt(max(0.0, float(covariance[1, 1])))
    except np.linalg.LinAlgError:
        rate_se = math.inf
    delta = rate * float(period)
    estimate = _from_decrement("logdec", delta, 2.0 * math.pi / float(period), times, heights)
    zeta = float(estimate.damping_ratio or 0.0)
    omega = float(estimate.omega_n_rad_s or 0.0)
    low_rate, high_rate = rate - factor * rate_se, rate + factor * rate_se
    zeta_interval = (
        zeta_from_log_decrement(max(0.0, low_rate * float(period))),
        zeta_from_log_decrement(high_rate * float(period)),
    )
    relative = factor * period_se / float(period)
    return Estimate(
        method="logdec",
        omega_n_rad_s=omega,
        damping_ratio=zeta,
        damped_omega_rad_s=estimate.damped_omega_rad_s,
        log_decrement=delta,
        n_peaks=n,
        omega_n_interval=(omega * (1.0 - relative), omega * (1.0 + relative)),
        damping_ratio_interval=zeta_interval,
        amplitude=float(heights[0]),
        residual_rms=float(np.sqrt(np.mean((solution.fun * sigma_log) ** 2))),
    )
