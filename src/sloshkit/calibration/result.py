"""The free-decay calibration result: every estimator, the window, warnings, the backbone."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.calibration.estimators import Estimate
from sloshkit.calibration.signals import PreparedSignal
from sloshkit.calibration.window import DecayWindow
from sloshkit.model.modal import SloshModel
from sloshkit.results import ResultMixin

if TYPE_CHECKING:
    from sloshkit.calibration.backbone import Backbone

FloatArray = NDArray[np.float64]

#: Estimators disagree when omega_n differs by more than this fraction ...
OMEGA_DISAGREEMENT = 0.01
#: ... or zeta by more than this fraction, and one estimate lies outside the other's 95 %
#: interval (the two cannot both describe the record: a wide interval of one does not make the
#: other's precise answer agree with it).
ZETA_DISAGREEMENT = 0.15


def _estimate_dict(estimate: Estimate) -> dict[str, Any]:
    omega = estimate.omega_n_rad_s
    return {
        "omega_n_rad_s": omega,
        "frequency_hz": None if omega is None else omega / (2 * math.pi),
        "damping_ratio": estimate.damping_ratio,
        "log_decrement": estimate.log_decrement,
        "omega_n_interval_rad_s": None
        if estimate.omega_n_interval is None
        else list(estimate.omega_n_interval),
        "damping_ratio_interval": None
        if estimate.damping_ratio_interval is None
        else list(estimate.damping_ratio_interval),
        "n_peaks": estimate.n_peaks,
        "failure": estimate.failure or None,
    }


@dataclass(frozen=True, eq=False)
class CalibrationResult(ResultMixin):
    """Calibrated frequency and damping, with every estimator's answer for comparison.

    Built by `sloshkit.calibration.calibrate`; follows the result protocol (``to_dict``,
    ``to_pandas``, ``to_csv`` of the analysed window, ``plot``).

    Parameters
    ----------
    method : str
        The estimator reported and written to a model file.
    chosen : Estimate
        Its answer.
    estimates : dict of str to Estimate
        Every estimator's answer (fit, logdec, fft, logdec-2peak, backbone), failures included.
    signal : PreparedSignal
        The record as analysed: resampled, filtered, windowed and detrended.
    source : str
        Where the record came from (provenance).
    peak_times_s, peak_values : numpy.ndarray
        The usable peaks [s] and their swings (signal units).
    window : DecayWindow, optional
        The window and why it was chosen.
    warnings : tuple of str
        The `ValidityWarning` messages (fallback, disagreement, amplitude dependence).
    noise_rms : float, optional
        Noise standard deviation of the decay (signal units).
    backbone : Backbone, optional
        Frequency and damping against amplitude.
    requested_method : str
        The estimator asked for (differs from ``method`` when it failed).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration import calibrate
    >>> t = np.arange(0, 6, 0.002)
    >>> result = calibrate(t, np.exp(-0.58 * t) * np.cos(29 * t), start_s=0.0)
    >>> result.method, sorted(result.to_dict()["window"])[:2]
    ('fit', ['end_s', 'forcing_end_s'])
    """

    method: str
    chosen: Estimate
    estimates: dict[str, Estimate]
    signal: PreparedSignal
    source: str = ""
    peak_times_s: FloatArray = field(default_factory=lambda: np.zeros(0))
    peak_values: FloatArray = field(default_factory=lambda: np.zeros(0))
    window: DecayWindow | None = None
    warnings: tuple[str, ...] = ()
    noise_rms: float | None = None
    backbone: Backbone | None = None
    requested_method: str = ""

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
            "requested_method": self.requested_method or self.method,
            "window_s": list(self.signal.window_s),
            "window": None if self.window is None else self.window.to_dict(),
            "n_peaks": int(self.peak_times_s.size),
            "noise_rms": self.noise_rms,
            "residual_rms": chosen.residual_rms,
            "omega_n_interval_rad_s": None
            if chosen.omega_n_interval is None
            else list(chosen.omega_n_interval),
            "damping_ratio_interval": None
            if chosen.damping_ratio_interval is None
            else list(chosen.damping_ratio_interval),
            "source": self.source,
            "notes": list(self.signal.notes) + [e.note for e in self.estimates.values() if e.note],
            "warnings": list(self.warnings),
            "estimates": {name: _estimate_dict(e) for name, e in self.estimates.items()},
            "backbone": None if self.backbone is None else self.backbone.to_dict(),
        }
        payload["disagreement"] = relative_spread(self.estimates)
        return payload

    def columns(self) -> dict[str, FloatArray]:
        """The analysed window: time, detrended signal, the signal as recorded, and the fit's
        curve over the recorded signal (NaN when the fit failed); signal units are the
        record's."""
        signal = self.signal
        fit = self.estimates.get("fit")
        curve = np.full_like(signal.time_s, np.nan)
        if fit is not None and not fit.failure and fit.fitted is not None:
            curve = fit.fitted
        return {
            "time_s": signal.time_s,
            "signal": signal.values,
            "signal_recorded": signal.undetrended,
            "fit": curve,
        }

    def estimate_table(self) -> Any:
        """One row per estimator as a pandas DataFrame (pandas imported lazily)."""
        from sloshkit.results import require_pandas

        rows = [{"estimator": name, **_estimate_dict(e)} for name, e in self.estimates.items()]
        return require_pandas().DataFrame(rows).set_index("estimator")

    def provenance(self) -> str:
        """Which estimator and window produced the calibration (for model files)."""
        window = self.signal.window_s
        why = "" if self.window is None else f", window from {self.window.source}"
        return (
            f"calibration: {self.method} of {self.source or 'signal'} "
            f"[{window[0]:.4g}, {window[1]:.4g}] s{why}"
        )

    def calibrated_model(self, model: SloshModel) -> SloshModel:
        """``model`` with mode 1's frequency and every mode's damping ratio replaced.

        The damping applies to all modes, as the correlations do; higher-mode frequencies stay
        theoretical. Provenance records the estimator, the data file and the window.
        """
        source = self.provenance()
        calibrated = model.with_mode(1, omega_rad_s=self.omega_n_rad_s, source=source)
        if self.damping_ratio is not None:
            for mode in calibrated.modes:
                calibrated = calibrated.with_mode(
                    mode.n, damping_ratio=self.damping_ratio, source=source
                )
        return calibrated


def relative_spread(estimates: dict[str, Estimate]) -> dict[str, float | None]:
    """(max - min) / mean of omega_n and of zeta over the estimators that answered.

    Parameters
    ----------
    estimates : dict
        Estimator name -> `Estimate`.

    Returns
    -------
    dict
        ``omega_n_relative_spread`` and ``damping_ratio_relative_spread`` (None with fewer
        than two answers).

    Examples
    --------
    >>> from sloshkit.calibration.estimators import Estimate
    >>> spread = relative_spread({"fit": Estimate("fit", 30.0, 0.02, 29.99),
    ...                           "fft": Estimate("fft", 30.3, None, 30.3)})
    >>> round(spread["omega_n_relative_spread"], 4), spread["damping_ratio_relative_spread"]
    (0.01, None)
    """
    omegas = [e.omega_n_rad_s for e in estimates.values() if e.omega_n_rad_s is not None]
    zetas = [e.damping_ratio for e in estimates.values() if e.damping_ratio is not None]

    def spread(values: list[float]) -> float | None:
        return (max(values) - min(values)) / float(np.mean(values)) if len(values) > 1 else None

    return {
        "omega_n_relative_spread": spread(omegas),
        "damping_ratio_relative_spread": spread(zetas),
    }


def disagreements(estimates: dict[str, Estimate]) -> list[str]:
    """Messages for a clear disagreement between ``fit`` and ``logdec``: relative differences
    beyond `OMEGA_DISAGREEMENT` / `ZETA_DISAGREEMENT` with one estimate outside the other's
    95 % interval.

    On sloshkit's shipped CFD free decay the fit gives zeta 0.0069 (interval 0.0064-0.0074)
    and logdec 0.0024 (interval 0-0.022): logdec lies outside the fit's interval, so the two
    disagree although logdec's wide interval contains the fit. The check that both intervals
    miss each other let that pass silently.

    Parameters
    ----------
    estimates : dict
        Estimator name -> `Estimate`.

    Returns
    -------
    list of str
        One message per quantity on which the two disagree.

    Examples
    --------
    >>> from sloshkit.calibration.estimators import Estimate
    >>> fit = Estimate("fit", 30.0, 0.020, 30.0, damping_ratio_interval=(0.019, 0.021))
    >>> logdec = Estimate("logdec", 30.0, 0.030, 30.0, damping_ratio_interval=(0.028, 0.032))
    >>> [m[:32] for m in disagreements({"fit": fit, "logdec": logdec})]
    ['estimators disagree on zeta: fit']
    >>> disagreements({"fit": fit, "logdec": fit})
    []
    >>> vague = Estimate("logdec", 30.0, 0.0024, 30.0, damping_ratio_interval=(0.0, 0.022))
    >>> precise = Estimate("fit", 30.0, 0.0069, 30.0, damping_ratio_interval=(0.0064, 0.0074))
    >>> [m[:54] for m in disagreements({"fit": precise, "logdec": vague})]
    ['estimators disagree on zeta: fit 0.0069, logdec 0.0024']
    """
    fit, logdec = estimates.get("fit"), estimates.get("logdec")
    if fit is None or logdec is None or fit.failure or logdec.failure:
        return []
    messages = []
    pairs = (
        ("omega_n", fit.omega_n_rad_s, logdec.omega_n_rad_s, OMEGA_DISAGREEMENT,
         fit.omega_n_interval, logdec.omega_n_interval),
        ("zeta", fit.damping_ratio, logdec.damping_ratio, ZETA_DISAGREEMENT,
         fit.damping_ratio_interval, logdec.damping_ratio_interval),
    )  # fmt: skip
    for name, a, b, limit, interval_a, interval_b in pairs:
        if a is None or b is None or a == 0.0:
            continue
        difference = abs(b - a) / abs(a)
        outside = []
        for value_name, value, other_name, interval in (
            ("logdec", b, "fit", interval_a),
            ("fit", a, "logdec", interval_b),
        ):
            if interval is None:
                outside.append(f"{other_name} has no interval")
            elif not interval[0] <= value <= interval[1]:
                outside.append(
                    f"{value_name} {value:.4g} lies outside {other_name}'s 95 % interval "
                    f"{interval[0]:.4g}-{interval[1]:.4g}"
                )
        if difference > limit and outside:
            messages.append(
                f"estimators disagree on {name}: fit {a:.4g}, logdec {b:.4g} "
                f"({100 * difference:.1f} %; {'; '.join(outside)}): the record is not one "
                "clean linear decay; check the window, the noise or an amplitude-dependent "
                "(nonlinear) decay (see the backbone)"
            )
    return messages
