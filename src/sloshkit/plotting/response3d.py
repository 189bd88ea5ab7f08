"""Figures of 3-D slosh responses: path (top view) and slosh height, measured against predicted.

Draws `sloshkit.sim.spatial_response.SpatialResponse` objects (registered for ``plot()``) and
the measured-data comparison of ``validation/validate_measured_3d.py``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot
from sloshkit.sim.spatial_response import SpatialResponse


@register_plot(SpatialResponse)
def plot_spatial_response(
    response: SpatialResponse,
    path: str | Path | None = None,
    *,
    ax: Any = None,
    limit_m: float | None = None,
) -> Any:
    """Top view of the path and slosh height against time; returns the Figure.

    Parameters
    ----------
    response : the 3-D slosh response
    path : save the figure there when given
    ax : an Axes whose area holds the two panels; a new figure otherwise
    limit_m : slosh-height limit drawn as a horizontal line [m] (default: the free board
        wall height - fill height when the wall height is known)

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> poses = sk.poses_from_law(sk.quintic(0.05, 0.8), (1, 1, 0), sample_period_s=0.005)
    >>> figure = plot_spatial_response(sk.simulate_spatial(model, poses), limit_m=0.01)
    >>> len(figure.axes)
    2
    """
    figure, axes = panels(ax, 1, 2, figsize=(11, 4.2))
    xyz = response.path_m
    time = response.time_s
    moving = time <= response.motion_end_s + 1e-12
    axes[0].plot(1e3 * xyz[moving, 0], 1e3 * xyz[moving, 1], color="tab:blue")
    axes[0].plot(1e3 * xyz[0, 0], 1e3 * xyz[0, 1], "o", color="tab:green", label="start")
    axes[0].plot(1e3 * xyz[-1, 0], 1e3 * xyz[-1, 1], "s", color="tab:red", label="end")
    axes[0].set_xlabel("x [mm]")
    axes[0].set_ylabel("y [mm]")
    axes[0].set_aspect("equal", adjustable="datalim")
    axes[0].set_title("path (top view)")
    axes[0].legend(loc="best", fontsize=8)
    axes[1].plot(time, 1e3 * response.slosh_height_m, label=f"slosh height ({response.kind})")
    wall = response.model.container.wall_height_m
    limit = limit_m
    if limit is None and wall is not None:
        limit = wall - response.model.fill_height_m
    if limit is not None:
        axes[1].axhline(1e3 * limit, color="tab:red", linestyle="--", label="limit")
    axes[1].axvline(response.motion_end_s, color="grey", linestyle=":", linewidth=1)
    axes[1].set_xlabel("time [s]")
    axes[1].set_ylabel("slosh height [mm]")
    axes[1].set_title(response.motion_name or "3-D slosh")
    axes[1].grid(alpha=0.3)
    axes[1].legend(loc="upper right", fontsize=8)
    if ax is None:
        figure.tight_layout()
    return save_figure(figure, path)


def plot_measured_comparison(
    series: list[dict[str, Any]], path: str | Path | None = None, columns: int = 2
) -> Any:
    """Measured against predicted slosh-height series, one panel per series.

    Each item has ``name``, ``measured_t_s``, ``measured_m`` and ``predicted`` (a list of
    (label, time [s], height [m])).

    Parameters
    ----------
    series : list of dict
        The series.
    path : str or Path, optional
        Where to save the figure.
    columns : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 1, 11)
    >>> series = [{"name": "run 1", "measured_t_s": t, "measured_m": 0.01 * t,
    ...            "predicted": [("model", t, 0.011 * t)]}]
    >>> plot_measured_comparison(series, columns=1).axes[0].get_title()
    'run 1'

    """
    rows = int(np.ceil(len(series) / columns))
    figure, axes = panels(None, rows, columns, figsize=(6 * columns, 2.8 * rows), squeeze=False)
    for axis, item in zip(axes.flat, series, strict=False):
        axis.plot(
            item["measured_t_s"],
            1e3 * np.asarray(item["measured_m"]),
            color="black",
            linewidth=1.0,
            label="measured",
        )
        for label, t, height in item["predicted"]:
            axis.plot(t, 1e3 * np.asarray(height), linewidth=1.0, label=label, alpha=0.85)
        axis.set_title(item["name"], fontsize=9)
        axis.set_xlabel("time, pose clock [s]")
        axis.set_ylabel("slosh height [mm]")
        axis.grid(alpha=0.3)
    for axis in list(axes.flat)[len(series) :]:
        axis.axis("off")
    axes.flat[0].legend(loc="upper left", fontsize=7)
    figure.tight_layout()
    return save_figure(figure, path)
