"""Figure of a calibration: the signal, its peaks and the fitted decay (seed Fig. 5b)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.calibration import CalibrationResult
from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot

FloatArray = NDArray[np.float64]


@register_plot(CalibrationResult)
def plot_calibration(
    result: CalibrationResult, path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """Signal in the window, detected peaks and the fitted decay envelope (seed Fig. 5b)."""
    figure, axis = panels(ax, 1, figsize=(8, 4.2), layout="constrained")
    signal = result.signal
    axis.plot(signal.time_s, signal.values, color="tab:blue", linewidth=1, label="signal (window)")
    axis.plot(
        result.peak_times_s,
        result.peak_values,
        "o",
        color="tab:red",
        markersize=4,
        label=f"peaks ({result.peak_times_s.size})",
    )
    fit = result.estimates.get("fit")
    if fit is not None and fit.amplitude is not None and fit.omega_n_rad_s and fit.damping_ratio:
        t0 = signal.time_s[0]
        envelope = fit.amplitude * np.exp(
            -fit.damping_ratio * fit.omega_n_rad_s * (signal.time_s - t0)
        )
        # The plotted signal is detrended; the envelope is centred on zero like it.
        offset = 0.0
        axis.plot(
            signal.time_s,
            offset + envelope,
            "--",
            color="black",
            linewidth=1,
            label=f"fit envelope, ζ = {fit.damping_ratio:.4f}",
        )
        axis.plot(signal.time_s, offset - envelope, "--", color="black", linewidth=1)
    chosen = result.chosen
    frequency = (chosen.omega_n_rad_s or math.nan) / (2 * math.pi)
    zeta = "n/a" if chosen.damping_ratio is None else f"{chosen.damping_ratio:.4f}"
    axis.set_title(f"{result.method}: f_n = {frequency:.4g} Hz, ζ = {zeta}")
    axis.set_xlabel("time [s]")
    axis.set_ylabel("signal (detrended)")
    axis.grid(alpha=0.3)
    axis.legend(loc="upper right")
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
    """
    figure, axis = panels(ax, 1, figsize=(8, 4), layout="constrained")
    axis.plot(time_s, 1e3 * measured_m, label="CFD (interFoam), wall elevation")
    axis.plot(time_s, 1e3 * model_m, "--", label=model_label)
    axis.set_xlabel("time [s]")
    axis.set_ylabel("wall elevation [mm]")
    axis.grid(alpha=0.3)
    axis.legend()
    return save_figure(figure, path)
