"""Figure of a CFD validation: CFD wall elevation against the pendulum model (seed Fig. 9)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plotting.base import panels, save_figure


def plot_cfd_validation(
    result: dict[str, Any], path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """CFD wall elevation against the pendulum model for the same motion (seed Fig. 9)."""
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
