"""Figure of a CFD validation: CFD wall elevation against the pendulum model (seed Fig. 9)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plotting.base import panels, save_figure


def _entry(result: Any, key: str, default: Any = None) -> Any:
    """A field of a `sloshkit.cfd.validation.CfdValidation` (or of its v1 dict form)."""
    if isinstance(result, dict):
        return result.get(key, default)
    if key == "quantity_label":
        return result.quantity_label
    return getattr(result, key, default)


def plot_cfd_validation(result: Any, path: str | Path | None = None, *, ax: Any = None) -> Any:
    """CFD wall elevation against the pendulum model for the same motion (seed Fig. 9).

    ``result`` is a `sloshkit.cfd.validation.CfdValidation` (``result.plot()`` calls this
    function) or a dict with the same fields.
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
