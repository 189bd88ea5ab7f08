"""Free-decay calibration: window, every estimator independently, warnings, backbone."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Literal

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from sloshkit.calibration.backbone import Backbone, backbone
from sloshkit.calibration.decrement import estimate_logdec, estimate_logdec_2peak
from sloshkit.calibration.estimators import (
    Estimate,
    estimate_fft,
    estimate_fit,
    log_decrement_from_zeta,
)
from sloshkit.calibration.result import CalibrationResult, disagreements
from sloshkit.calibration.signals import noise_level, spectral_peak, usable_peaks
from sloshkit.calibration.window import prepare_signal
from sloshkit.errors import InputError, ValidityWarning

FloatArray = NDArray[np.float64]
Method = Literal["fit", "logdec", "fft", "logdec-2peak", "backbone"]
METHODS: tuple[str, ...] = ("fit", "logdec", "fft", "logdec-2peak", "backbone")
#: Estimators that give a damping ratio and may stand in for a failed one, in this order.
FALLBACKS: tuple[str, ...] = ("fit", "logdec")


def _backbone_estimate(curve: Backbone) -> Estimate:
    omega, zeta = curve.small_amplitude_omega_n_rad_s, curve.small_amplitude_damping_ratio
    factor = float(stats.t.ppf(0.975, max(1, curve.time_s.size - 2)))
    return Estimate(
        method="backbone",
        omega_n_rad_s=omega,
        damping_ratio=zeta,
        damped_omega_rad_s=omega * math.sqrt(max(0.0, 1.0 - zeta**2)),
        log_decrement=log_decrement_from_zeta(zeta) if zeta < 1.0 else None,
        omega_n_interval=(omega - factor * curve.omega_n_se_rad_s,
                          omega + factor * curve.omega_n_se_rad_s),
        damping_ratio_interval=(max(0.0, zeta - factor * curve.damping_ratio_se),
                                zeta + factor * curve.damping_ratio_se),
        note="small-amplitude limit of the sliding-window backbone",
    )  # fmt: skip


def calibrate(
    time_s: FloatArray,
    values: FloatArray,
    method: Method = "fit",
    start_s: float | None = None,
    end_s: float | None = None,
    detrend: Literal["mean", "linear", "none"] = "linear",
    lowpass_hz: float | None = None,
    source: str = "",
    *,
    forcing_end_s: float | None = None,
    settle_s: float | None = None,
) -> CalibrationResult:
    """Frequency and damping of the free decay in (time, values), by every estimator.

    Each estimator runs on its own (`sloshkit.calibration.estimators`); one failing does not
    stop the others. ``method`` chooses the one reported and written to a model file; if it
    fails, fit or else logdec is reported is reported instead, with a
    `ValidityWarning`. A clear disagreement between fit and logdec and an amplitude-dependent
    backbone also warn; every warning is kept in the result (and its JSON).

    Parameters
    ----------
    time_s, values : the record (times strictly increasing; uneven steps are resampled)
    method : fit, logdec, fft, logdec-2peak or backbone
    start_s, end_s : window [s]; by default found by `find_free_decay`
    detrend : mean, linear or none (the fit models offset and drift itself)
    lowpass_hz : optional zero-phase low-pass cut-off [Hz]
    source : where the data came from (for provenance)
    forcing_end_s : end of the applied motion when known [s] (the window starts after it)
    settle_s : settling margin after the forcing [s] (default one damped period)

    Returns
    -------
    CalibrationResult

    Raises
    ------
    InputError when the record is not usable or no estimator of damping answers.

    References
    ----------
    Seed paper eqs. 11-12; Inman, *Engineering Vibration*, 4th ed. (2014) §1.6.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 6, 0.002)
    >>> result = calibrate(t, np.exp(-0.58 * t) * np.cos(29 * t), start_s=0.0)
    >>> round(result.omega_n_rad_s, 2), round(result.damping_ratio, 4)
    (29.01, 0.02)
    """
    if method not in METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(METHODS))
    prepared, window = prepare_signal(
        time_s,
        values,
        start_s,
        end_s,
        detrend,
        lowpass_hz,
        forcing_end_s=forcing_end_s,
        settle_s=settle_s,
    )
    frequency, _, _ = spectral_peak(prepared.time_s, prepared.values)
    if not frequency > 0.0:
        raise InputError("signal", "no spectral peak", "has no oscillation in the window")
    period = 1.0 / frequency
    estimates: dict[str, Estimate] = {}
    errors: dict[str, InputError] = {}
    runs: tuple[tuple[str, Callable[[], Estimate]], ...] = (
        ("fit", lambda: estimate_fit(prepared)),
        ("logdec", lambda: estimate_logdec(prepared, period)),
        ("fft", lambda: estimate_fft(prepared)),
        ("logdec-2peak", lambda: estimate_logdec_2peak(prepared, period)),
    )
    for name, run in runs:
        try:
            estimates[name] = run()
        except InputError as error:
            errors[name] = error
            estimates[name] = Estimate.failed(name, error)
    curve: Backbone | None = None
    fit = estimates["fit"]
    start_omega = fit.omega_n_rad_s or estimates["logdec"].omega_n_rad_s or 2 * math.pi * frequency
    start_zeta = fit.damping_ratio or estimates["logdec"].damping_ratio or 0.01
    try:
        curve = backbone(prepared, float(start_omega), float(start_zeta))
        estimates["backbone"] = _backbone_estimate(curve)
    except InputError as error:
        errors["backbone"] = error
        estimates["backbone"] = Estimate.failed("backbone", error)
    messages: list[str] = []
    chosen_name: str = method
    if estimates[method].failure:
        answered = [name for name in FALLBACKS if not estimates[name].failure]
        if not answered:
            raise errors[method] if method in FALLBACKS else errors["fit"]
        chosen_name = answered[0]
        messages.append(
            f"{method} failed ({estimates[method].failure}); reporting {chosen_name} instead"
        )
    elif not any(not estimates[name].failure for name in ("fit", "logdec")) and method != "fft":
        raise errors["fit"]
    chosen = estimates[chosen_name]
    if chosen.note and chosen_name != "backbone":
        messages.append(chosen.note)
    messages.extend(disagreements(estimates))
    if curve is not None and (curve.omega_dependent or curve.zeta_dependent):
        messages.append(
            "frequency and/or damping depend on the amplitude (backbone: omega_n "
            f"{curve.omega_n_rad_s.min():.4g}-{curve.omega_n_rad_s.max():.4g} rad/s, zeta "
            f"{curve.damping_ratio.min():.3g}-{curve.damping_ratio.max():.3g}); the linear "
            "model's calibration is the small-amplitude limit (--method backbone: omega_n "
            f"{curve.small_amplitude_omega_n_rad_s:.4g} rad/s, zeta "
            f"{curve.small_amplitude_damping_ratio:.3g})"
        )
    for message in messages:
        warnings.warn(message, ValidityWarning, stacklevel=2)
    noise = noise_level(prepared.values, period / prepared.sample_period_s)
    times, heights = usable_peaks(prepared.time_s, prepared.values, period, noise)
    return CalibrationResult(
        method=chosen_name,
        chosen=chosen,
        estimates=estimates,
        signal=prepared,
        source=source,
        peak_times_s=times,
        peak_values=heights,
        window=window,
        warnings=tuple(messages),
        noise_rms=noise,
        backbone=curve,
        requested_method=method,
    )
