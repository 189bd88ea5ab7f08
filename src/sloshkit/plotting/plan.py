"""Figure of a plan: the verified candidates' moves and slosh against the limits."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.plan.line.planner import PlanResult
from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot


@register_plot(PlanResult)
def plot_plan(result: PlanResult, path: str | Path | None = None, *, ax: Any = None) -> Any:
    """Velocity, acceleration and first-mode slosh angle of each verified candidate
    (its exported samples, `PlanResult.histories`), with the limits.

    Parameters
    ----------
    result : PlanResult
        The plan.
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
    >>> import math
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> problem = sk.PlanProblem(0.2, sk.MachineLimits(1.0, 10.0, 200.0),
    ...                          sk.SloshLimits(math.radians(5), math.radians(0.5)), model, 0.004)
    >>> result = sk.plan(problem, "shaped")
    >>> len(plot_plan(result).axes)
    3
    """

    figure, axes = panels(ax, 3, figsize=(8.5, 8.5), sharex=True, layout="constrained")
    problem = result.problem
    for history in result.histories():
        is_chosen = history["chosen"]
        style = {"linewidth": 2.2 if is_chosen else 1.0, "alpha": 1.0 if is_chosen else 0.7}
        label = f"{history['method']} ({history['duration_s']:.3f} s)" + (" ◀" if is_chosen else "")
        t = history["t_s"]
        axes[0].plot(t, history["velocity_m_s"], label=label, **style)
        axes[1].plot(t, history["acceleration_m_s2"], **style)
        axes[2].plot(t, np.degrees(history["angle_1_rad"]), **style)
    limit = math.degrees(problem.slosh.max_angle_rad)
    for sign in (1, -1):
        axes[2].axhline(sign * limit, color="red", linestyle="--", linewidth=1)
    axes[0].set_ylabel("velocity [m/s]")
    axes[1].set_ylabel("acceleration [m/s²]")
    axes[2].set_ylabel("slosh angle θ₁ [deg]")
    axes[2].set_xlabel("time [s]")
    for axis in axes:
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[0].set_title(
        f"Fastest moves of {1e3 * problem.distance_m:.0f} mm with |θ₁| ≤ {limit:g}°, residual ≤ "
        f"{math.degrees(problem.slosh.max_residual_rad):g}° (verified at "
        f"{1e3 * problem.sample_period_s:g} ms)"
    )
    return save_figure(figure, path)
