"""Figure of a 3-D path plan: top view of the path and the slosh height of every candidate.

Draws a `sloshkit.plan.path.result.PathPlanResult` (registered for ``plot()``): the slosh
heights are those its verification simulated (nothing is simulated here).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plan.path.result import PathPlanResult
from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot


@register_plot(PathPlanResult)
def plot_path_plan(result: PathPlanResult, ax: Any = None, path: str | Path | None = None) -> Any:
    """Top view of the path with the chosen export, and slosh height against time.

    Parameters
    ----------
    result : PathPlanResult
        The plan.
    ax : matplotlib Axes, optional
        Area for the two panels; a new figure otherwise.
    path : str or Path, optional
        Save the figure there.

    Returns
    -------
    matplotlib.figure.Figure

    References
    ----------
    The verification of `sloshkit.plan.path.result.verify`.

    Examples
    --------
    >>> callable(plot_path_plan)
    True
    """
    figure, (top, heights) = panels(ax, 1, 2, figsize=(11.0, 4.2), layout="constrained")
    geometry = result.problem.path
    s = np.linspace(0.0, geometry.length_m, 800)
    line = geometry.position(s)
    top.plot(line[:, 0], line[:, 1], color="0.6", lw=3, label="path")
    chosen = result.chosen
    if chosen is not None and chosen.poses is not None:
        points = chosen.poses.position_m
        top.plot(points[:, 0], points[:, 1], ".", ms=2, label=f"{chosen.method} export")
    top.set_aspect("equal", adjustable="datalim")
    top.set_xlabel("x [m]")
    top.set_ylabel("y [m]")
    top.legend(loc="best", fontsize=8)
    for candidate in result.candidates:
        check = candidate.verification
        if check is None or check.time_s.size == 0:
            continue
        heights.plot(
            check.time_s,
            1e3 * check.height_m,
            lw=1.0,
            label=f"{candidate.method} ({candidate.duration_s:.2f} s)",
        )
    limit = result.problem.slosh.max_height_m
    heights.axhline(1e3 * limit, color="k", ls="--", lw=0.8, label="limit")
    heights.set_xlabel("time [s]")
    heights.set_ylabel("slosh height [mm]")
    heights.legend(loc="best", fontsize=8)
    if path is not None:
        save_figure(figure, path)
    return figure
