"""Figures of a calibration: the signal, its peaks and the fitted decay (seed Fig. 5b); the
backbone (frequency and damping against amplitude); a forced-response identification."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.calibration import Backbone, CalibrationResult, ForcedIdentification
from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot

FloatArray = NDArray[np.float64]


@register_plot(CalibrationResult)
def plot_calibration(
    result: CalibrationResult,
    path: str | Path | None = None,
    *,
    ax: Any = None,
    signal_label: str = "signal (detrended) [unit of the record]",
) -> Any:
    """Signal in the window, every peak and trough, the peaks the estimators use and the fitted
    decay envelope (seed Fig. 5b); ``signal_label`` names the signal and its unit.

    Parameters
    ----------
    result : CalibrationResult
        The calibration.
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.
    signal_label : str
        The y label: the signal and its unit.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration import calibrate
    >>> t = np.arange(0, 4, 0.002)
    >>> result = calibrate(t, np.exp(-0.6 * t) * np.cos(30 * t), start_s=0.0)
    >>> figure = plot_calibration(result, signal_label="height [m]")
    >>> figure.axes[0].get_ylabel()
    'height [m]'
    """
    from scipy.signal import find_peaks

    figure, axis = panels(ax, 1, figsize=(8, 4.2), layout="constrained")
    signal = result.signal
    axis.plot(signal.time_s, signal.values, color="tab:blue", linewidth=1, label="signal (window)")
    omega = result.chosen.omega_n_rad_s
    if omega and signal.time_s.size > 2:
        step = float(np.median(np.diff(signal.time_s)))
        distance = max(1, int(0.6 * 2 * math.pi / omega / step))
        extremes = np.sort(
            np.concatenate(
                [
                    find_peaks(signal.values, distance=distance)[0],
                    find_peaks(-signal.values, distance=distance)[0],
                ]
            )
        )
        axis.plot(
            signal.time_s[extremes],
            signal.values[extremes],
            "o",
            markerfacecolor="none",
            color="tab:gray",
            markersize=6,
            label=f"peaks and troughs ({extremes.size})",
        )
    axis.plot(
        result.peak_times_s,
        result.peak_values,
        "o",
        color="tab:red",
        markersize=4,
        label=f"peaks above the noise, used by logdec ({result.peak_times_s.size})",
    )
    fit = result.estimates.get("fit")
    if fit is not None and fit.amplitude is not None and fit.omega_n_rad_s and fit.damping_ratio:
        t0 = signal.time_s[0]
        envelope = fit.amplitude * np.exp(
            -fit.damping_ratio * fit.omega_n_rad_s * (signal.time_s - t0)
        )
        # The plotted signal is detrended; the envelope is centred on zero like it.
        axis.plot(
            signal.time_s,
            envelope,
            "--",
            color="black",
            linewidth=1,
            label=f"fit envelope, ζ = {fit.damping_ratio:.4f}",
        )
        axis.plot(signal.time_s, -envelope, "--", color="black", linewidth=1)
    chosen = result.chosen
    frequency = (chosen.omega_n_rad_s or math.nan) / (2 * math.pi)
    zeta = "n/a" if chosen.damping_ratio is None else f"{chosen.damping_ratio:.4f}"
    window = result.window
    why = "" if window is None else f" (window: {window.source})"
    axis.set_title(f"{result.method}: f_n = {frequency:.4g} Hz, ζ = {zeta}{why}")
    axis.set_xlabel("time [s]")
    axis.set_ylabel(signal_label)
    axis.grid(alpha=0.3)
    axis.legend(loc="upper right", fontsize="small")
    return save_figure(figure, path)


def plot_free_response(
    time_s: FloatArray,
    measured_m: FloatArray,
    model_m: FloatArray,
    model_label: str,
    path: str | Path | None = None,
    *,
    ax: Any = None,
) -> Any:
    """A measured (or CFD) wall elevation and the pendulum's free response over it (seed Fig. 9).

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s].
    measured_m : numpy.ndarray
        Measured wall elevation [m].
    model_m : numpy.ndarray
        The model's free response at the same times [m].
    model_label : str
        Legend of the model's curve.
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2, 201)
    >>> decay = 1e-3 * np.exp(-0.6 * t) * np.cos(30 * t)
    >>> figure = plot_free_response(t, decay, 0.98 * decay, "pendulum")
    >>> [line.get_label() for line in figure.axes[0].get_lines()][:2]
    ['CFD (interFoam), wall elevation', 'pendulum']
    """
    figure, axis = panels(ax, 1, figsize=(8, 4), layout="constrained")
    axis.plot(time_s, 1e3 * measured_m, label="CFD (interFoam), wall elevation")
    axis.plot(time_s, 1e3 * model_m, "--", label=model_label)
    axis.set_xlabel("time [s]")
    axis.set_ylabel("wall elevation [mm]")
    axis.grid(alpha=0.3)
    axis.legend()
    return save_figure(figure, path)


@register_plot(Backbone)
def plot_backbone(backbone: Backbone, path: str | Path | None = None, *, ax: Any = None) -> Any:
    """Frequency and damping against amplitude (sliding-window fits) with the regressions
    whose intercepts are the small-amplitude (linear) calibration.

    Parameters
    ----------
    backbone : Backbone
        The sliding-window fits (`sloshkit.calibration.backbone`).
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration import prepare_signal
    >>> from sloshkit.calibration.backbone import backbone
    >>> t = np.arange(0, 6, 0.002)
    >>> prepared, _ = prepare_signal(t, np.exp(-0.6 * t) * np.cos(29.99 * t), start_s=0.0)
    >>> len(plot_backbone(backbone(prepared, 30.0, 0.02)).axes)
    2
    """
    figure, axes = panels(ax, 1, 2, figsize=(9, 3.8), layout="constrained")
    amplitude = backbone.amplitude
    line = np.linspace(0.0, float(amplitude.max()), 50)
    omega_0 = backbone.small_amplitude_omega_n_rad_s
    axes[0].plot(amplitude, backbone.omega_n_rad_s / (2 * math.pi), "o", markersize=4)
    axes[0].plot(
        line,
        (omega_0 + backbone.omega_slope_rad_s_per_amplitude2 * line**2) / (2 * math.pi),
        "--",
        color="black",
        label=f"f₀ = {omega_0 / (2 * math.pi):.4g} Hz",
    )
    axes[0].set_ylabel("natural frequency f_n [Hz]")
    axes[1].plot(amplitude, backbone.damping_ratio, "o", markersize=4, color="tab:red")
    axes[1].plot(
        line,
        backbone.small_amplitude_damping_ratio + backbone.zeta_slope_per_amplitude * line,
        "--",
        color="black",
        label=f"ζ₀ = {backbone.small_amplitude_damping_ratio:.4g}",
    )
    axes[1].set_ylabel("damping ratio ζ [-]")
    for axis in axes:
        axis.set_xlabel("amplitude (signal units)")
        axis.grid(alpha=0.3)
        axis.legend(loc="best")
    axes[0].set_title("backbone: frequency vs amplitude")
    axes[1].set_title("damping vs amplitude")
    return save_figure(figure, path)


@register_plot(ForcedIdentification)
def plot_forced_identification(
    result: ForcedIdentification, path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """Measured record and the identified model's simulation, with the motion's span.

    Parameters
    ----------
    result : ForcedIdentification
        The identification.
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.calibration.forced import ForcedIdentification, FitStatistics
    >>> t = np.linspace(0.0, 1.0, 50)
    >>> fit = FitStatistics(np.array([1.0]), np.sin(9 * t), np.zeros(3), 1.0, 0.0, 1.0)
    >>> result = ForcedIdentification.from_fit(
    ...     fit, t, np.sin(9 * t), signal_kind="height", omega_n_rad_s=9.0, damping_ratio=0.02,
    ...     constrained={}, linear=fit.linear_parameters(["gain"], first=2),
    ...     motion_span_s=(0.0, 0.3))
    >>> len(plot_forced_identification(result).axes) >= 1
    True
    """
    figure, axes = panels(ax, 2, figsize=(8, 5.5), sharex=True, layout="constrained")
    axes[0].plot(result.time_s, result.measured, color="tab:blue", linewidth=1, label="measured")
    axes[0].plot(
        result.time_s, result.predicted, "--", color="black", linewidth=1, label="identified model"
    )
    axes[1].plot(result.time_s, result.measured - result.predicted, color="tab:red", linewidth=1)
    axes[1].set_ylabel("residual")
    axes[1].set_xlabel("time [s]")
    for axis in axes:
        for edge in result.motion_span_s:
            axis.axvline(edge, color="grey", linestyle=":", linewidth=1)
        axis.grid(alpha=0.3)
    axes[0].legend(loc="upper right")
    axes[0].set_title(
        f"forced response ({result.signal_kind}): f_n = {result.omega_n_rad_s / (2 * math.pi):.4g}"
        f" Hz, ζ = {result.damping_ratio:.4f}, R² = {result.r2:.4f}"
    )
    return save_figure(figure, path)
