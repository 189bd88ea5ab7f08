"""Figure of a CFD validation: CFD wall elevation against the pendulum model (seed Fig. 9)."""

from __future__ import annotations

import importlib
from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot


def _entry(result: Any, key: str, default: Any = None) -> Any:
    """A field of a `sloshkit.cfd.validation.CfdValidation` (or of its v1 dict form)."""
    if isinstance(result, dict):
        return result.get(key, default)
    if key == "quantity_label":
        return result.quantity_label
    return getattr(result, key, default)


def plot_cfd_validation(result: Any, path: str | Path | None = None, *, ax: Any = None) -> Any:
    """CFD wall elevation against the pendulum model for the same motion (seed Fig. 9).

    Parameters
    ----------
    result : CfdValidation or dict
        A CFD validation (`sloshkit.cfd.pipeline.validate`; ``result.plot()`` calls this
        function), or a dict with its fields: ``time_s``, ``cfd_elevation_m``,
        ``model_elevation_m``, ``correlation`` and optionally ``excitation_end_s`` and
        ``quantity_label``.
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
    >>> t = np.linspace(0, 1, 101)
    >>> figure = plot_cfd_validation({"time_s": t, "cfd_elevation_m": 1e-3 * np.sin(30 * t),
    ...                               "model_elevation_m": 1e-3 * np.sin(29 * t),
    ...                               "correlation": 0.97})
    >>> figure.axes[0].get_title()
    'CFD vs equivalent model (correlation 0.970)'
    """
    figure, axis = panels(ax, 1, figsize=(8, 4.2), layout="constrained")
    t = _entry(result, "time_s")
    axis.plot(
        t,
        1e3 * np.asarray(_entry(result, "cfd_elevation_m")),
        label="CFD (interFoam)",
        linewidth=1.4,
    )
    axis.plot(
        t,
        1e3 * np.asarray(_entry(result, "model_elevation_m")),
        "--",
        label="pendulum model",
        linewidth=1.2,
    )
    end = _entry(result, "excitation_end_s")
    if end:
        axis.axvline(end, color="grey", linestyle=":", linewidth=1)
    axis.set_xlabel("time [s]")
    axis.set_ylabel(_entry(result, "quantity_label") or "wall elevation at 0.98 R [mm]")
    correlation = _entry(result, "correlation")
    axis.set_title(
        "CFD vs equivalent model"
        + ("" if correlation is None else f" (correlation {correlation:.3f})")
    )
    axis.grid(alpha=0.3)
    axis.legend()
    return save_figure(figure, path)


# The result class lives in sloshkit.cfd, a sibling layer that plotting must not import
# statically (import-linter): it is looked up by name, as `sloshkit.results.PLOTS` does.
register_plot(importlib.import_module("sloshkit.cfd.validation").CfdValidation)(plot_cfd_validation)
