"""Figure of a CFD validation: CFD wall elevation against the pendulum model (seed Fig. 9)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plotting.base import panels, save_figure


def plot_cfd_validation(
    result: dict[str, Any], path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """CFD wall elevation against the pendulum model for the same motion (seed Fig. 9).

    Parameters
    ----------
    result : dict
        A CFD validation (`sloshkit.cfd.pipeline.validate`): ``time_s``,
        ``cfd_elevation_m``, ``model_elevation_m``, ``correlation`` and optionally
        ``excitation_end_s`` and ``quantity_label``.
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
    t = result["time_s"]
    axis.plot(
        t, 1e3 * np.asarray(result["cfd_elevation_m"]), label="CFD (interFoam)", linewidth=1.4
    )
    axis.plot(
        t,
        1e3 * np.asarray(result["model_elevation_m"]),
        "--",
        label="pendulum model",
        linewidth=1.2,
    )
    if result.get("excitation_end_s"):
        axis.axvline(result["excitation_end_s"], color="grey", linestyle=":", linewidth=1)
    axis.set_xlabel("time [s]")
    axis.set_ylabel(result.get("quantity_label", "wall elevation at 0.98 R [mm]"))
    axis.set_title(f"CFD vs equivalent model (correlation {result['correlation']:.3f})")
    axis.grid(alpha=0.3)
    axis.legend()
    return save_figure(figure, path)
