"""Slosh maps of a sweep: one heat map per law."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot
from sloshkit.sweep import SweepResult


@register_plot(SweepResult)
def plot_sweep_map(
    result: SweepResult,
    quantity: str = "peak_angle_deg",
    path: str | Path | None = None,
    *,
    ax: Any = None,
) -> Any:
    """Heat map of ``quantity`` (``peak_angle_deg`` or ``residual_angle_deg``) over fill height
    and duration (or peak acceleration), one panel per law; the safe region is outlined."""
    from matplotlib.colors import LogNorm

    values = getattr(result, quantity)
    count = len(result.laws)
    columns = min(count, 3)
    rows = math.ceil(count / columns)
    figure, axes = panels(
        ax,
        rows,
        columns,
        figsize=(4.6 * columns, 3.8 * rows),
        squeeze=False,
        sharey=True,
        layout="constrained",
    )
    positive = values[values > 0]
    low = float(positive.min()) if positive.size else 1e-6
    high = float(values.max()) if values.size else 1.0
    norm = LogNorm(vmin=max(low, high * 1e-4), vmax=max(high, low * 10))
    safe = result.safe()
    heights_mm = 1e3 * result.fill_heights_m
    image = None
    for index, law in enumerate(result.laws):
        axis = axes[index // columns][index % columns]
        x = (
            result.durations_s[index]
            if result.axis == "duration"
            else result.peak_acceleration_m_s2[index]
        )
        if x.size > 1 and heights_mm.size > 1:
            image = axis.pcolormesh(
                x, heights_mm, values[index], norm=norm, shading="nearest", cmap="viridis"
            )
            if not safe[index].any():
                axis.fill_between(
                    [x.min(), x.max()],
                    heights_mm.min(),
                    heights_mm.max(),
                    facecolor="none",
                    hatch="//",
                    edgecolor="black",
                    linewidth=0,
                )
            elif not safe[index].all():
                axis.contour(
                    x,
                    heights_mm,
                    safe[index].astype(float),
                    levels=[0.5],
                    colors="white",
                    linewidths=1.5,
                )
                axis.contourf(
                    x,
                    heights_mm,
                    safe[index].astype(float),
                    levels=[-0.5, 0.5],
                    colors="none",
                    hatches=["//"],
                )
        else:
            axis.plot(x, values[index].T, marker=".")
        axis.set_title(law)
        axis.set_xlabel("duration [s]" if result.axis == "duration" else "peak acceleration [m/s²]")
        if index % columns == 0:
            axis.set_ylabel("fill height [mm]")
    for index in range(count, rows * columns):
        axes[index // columns][index % columns].set_visible(False)
    label = "peak slosh angle θ₁ [deg]" if quantity == "peak_angle_deg" else "residual θ₁ [deg]"
    if image is not None:
        figure.colorbar(image, ax=axes.ravel().tolist(), label=label, shrink=0.9)
    limits = []
    if result.max_angle_deg is not None:
        limits.append(f"peak ≤ {result.max_angle_deg:g}°")
    if result.max_residual_deg is not None:
        limits.append(f"residual ≤ {result.max_residual_deg:g}°")
    figure.suptitle(
        f"{label}, {1e3 * result.distance_m:.0f} mm move"
        + (f"; hatched: violates {', '.join(limits)}" if limits else "")
    )
    return save_figure(figure, path)
