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
    columns = count if count <= 3 else (2 if count == 4 else 3)
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
    limit = result.max_angle_deg if quantity == "peak_angle_deg" else result.max_residual_deg
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
            if limit is not None:
                _hatch_violations(axis, x, heights_mm, values[index] <= limit)
        else:
            axis.plot(x, values[index].T, marker=".")
        axis.set_title(law)
        axis.set_xlabel("duration [s]" if result.axis == "duration" else "peak acceleration [m/s²]")
        if index % columns == 0:
            axis.set_ylabel("fill height [mm]")
    for index in range(count, rows * columns):
        figure.delaxes(axes[index // columns][index % columns])
    label = (
        "peak slosh angle θ₁ [°]" if quantity == "peak_angle_deg" else "residual slosh angle θ₁ [°]"
    )
    if image is not None:
        bar = figure.colorbar(image, ax=axes.ravel()[:count].tolist(), label=label, shrink=0.9)
        _plain_log_ticks(bar, float(norm.vmin or low), float(norm.vmax or high))
    what = "peak" if quantity == "peak_angle_deg" else "residual"
    figure.suptitle(
        f"{label}, {1e3 * result.distance_m:.0f} mm move; "
        + (f"hatched: {what} above {limit:g}°" if limit is not None else f"no {what} limit given")
    )
    return save_figure(figure, path)


def _hatch_violations(axis: Any, x: Any, heights_mm: Any, ok: Any) -> None:
    """Hatch the cells where ``ok`` is False and outline the boundary."""
    import numpy as np

    if ok.all():
        return
    if not ok.any():
        axis.fill_between(
            [x.min(), x.max()],
            heights_mm.min(),
            heights_mm.max(),
            facecolor="none",
            hatch="//",
            edgecolor="black",
            linewidth=0,
        )
        return
    level = np.asarray(ok, dtype=float)
    axis.contour(x, heights_mm, level, levels=[0.5], colors="white", linewidths=1.5)
    axis.contourf(x, heights_mm, level, levels=[-0.5, 0.5], colors="none", hatches=["//"])


def _plain_log_ticks(bar: Any, low: float, high: float) -> None:
    """Colour-bar ticks at 1, 2, 5 x 10^k written as plain numbers (not 4x10^1)."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

    ticks = [
        m * 10.0**k
        for k in range(math.floor(math.log10(low)) - 1, math.ceil(math.log10(high)) + 1)
        for m in (1, 2, 5)
        if low <= m * 10.0**k <= high
    ]
    bar.ax.yaxis.set_major_locator(FixedLocator(ticks))
    bar.ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    bar.ax.yaxis.set_minor_formatter(NullFormatter())
