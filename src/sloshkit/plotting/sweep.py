"""Slosh maps of a sweep: one heat map per law."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from sloshkit.files import atomic_open
from sloshkit.plotting.base import panels
from sloshkit.results import register_plot
from sloshkit.sweep import SweepResult

#: Margins of a new map figure [in]: left, right (colour bar and its label), bottom, top
#: (suptitle), gaps between panels (x, y). Fixed: no layout engine, no tight bounding box, so
#: the figure is drawn once, when it is saved.
_MARGINS_IN = {"left": 0.75, "right": 1.25, "bottom": 0.55, "top": 0.65, "wide": 0.4, "high": 0.8}
_PANEL_IN = (3.9, 2.75)
_BAR_IN = (0.18, 0.3)  # colour-bar width and its gap to the panels


@register_plot(SweepResult)
def plot_sweep_map(
    result: SweepResult,
    quantity: str = "peak_angle_deg",
    path: str | Path | None = None,
    *,
    ax: Any = None,
) -> Any:
    """Heat map of ``quantity`` over fill height and duration (or peak acceleration), one panel
    per law; the cells that break the quantity's limit are hatched and outlined.

    Parameters
    ----------
    result : SweepResult
        The sweep.
    quantity : str
        ``"peak_angle_deg"`` or ``"residual_angle_deg"``.
    path : str or Path, optional
        Save the figure there (format from the suffix).
    ax : matplotlib.axes.Axes, optional
        Draw into this axes' area of its figure instead of a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        The figure: one panel per law and a colour bar (the last axes).

    Examples
    --------
    >>> import sloshkit as sk
    >>> from sloshkit.model.modal import model_family
    >>> family = model_family(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"))
    >>> sweep = sk.run_sweep(family, ["quintic", "septic"], 0.1, [0.8, 1.2, 1.6],
    ...                      fill_heights_m=[0.03, 0.04])
    >>> len(plot_sweep_map(sweep, "residual_angle_deg").axes)  # two panels and the colour bar
    3
    """
    from matplotlib.colors import LogNorm

    values = getattr(result, quantity)
    count = len(result.laws)
    columns = count if count <= 3 else (2 if count == 4 else 3)
    rows = math.ceil(count / columns)
    if ax is None:
        figure, axes, bar_axis = _fixed_grid(rows, columns, count)
    else:
        figure, grid = panels(ax, rows, columns, figsize=(0, 0), squeeze=False, sharey=True)
        for index in range(count, rows * columns):
            figure.delaxes(grid[index // columns][index % columns])
        axes = [grid[index // columns][index % columns] for index in range(count)]
        bar_axis = None
    positive = values[values > 0]
    low = float(positive.min()) if positive.size else 1e-6
    high = float(values.max()) if values.size else 1.0
    norm = LogNorm(vmin=max(low, high * 1e-4), vmax=max(high, low * 10))
    limit = result.max_angle_deg if quantity == "peak_angle_deg" else result.max_residual_deg
    heights_mm = 1e3 * result.fill_heights_m
    label = (
        "peak slosh angle θ₁ [°]" if quantity == "peak_angle_deg" else "residual slosh angle θ₁ [°]"
    )
    image = None
    for index, (law, axis) in enumerate(zip(result.laws, axes, strict=True)):
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
        else:  # one fill height or one duration: the values as curves, one per fill height
            axis.plot(x, values[index].T, marker=".")
        axis.set_title(law)
        axis.set_xlabel("duration [s]" if result.axis == "duration" else "peak acceleration [m/s²]")
        if index % columns == 0:
            axis.set_ylabel("fill height [mm]" if image is not None else label)
    if image is not None:
        if bar_axis is None:
            bar = figure.colorbar(image, ax=axes, label=label, shrink=0.9)
        else:
            bar = figure.colorbar(image, cax=bar_axis, label=label)
        _plain_log_ticks(bar, float(norm.vmin or low), float(norm.vmax or high))
    elif bar_axis is not None:
        figure.delaxes(bar_axis)
    what = "peak" if quantity == "peak_angle_deg" else "residual"
    figure.suptitle(
        f"{label}, {1e3 * result.distance_m:.0f} mm move; "
        + (f"hatched: {what} above {limit:g}°" if limit is not None else f"no {what} limit given")
    )
    return _save(figure, path)


def _fixed_grid(rows: int, columns: int, count: int) -> tuple[Any, list[Any], Any]:
    """A new figure with ``count`` panels (shared y axis) and a colour-bar axes at fixed
    positions (`_MARGINS_IN`)."""
    from matplotlib.figure import Figure

    margin = _MARGINS_IN
    panel_w, panel_h = _PANEL_IN
    bar_w, bar_gap = _BAR_IN
    width = margin["left"] + columns * panel_w + (columns - 1) * margin["wide"] + margin["right"]
    height = margin["bottom"] + rows * panel_h + (rows - 1) * margin["high"] + margin["top"]
    figure = Figure(figsize=(width, height))
    axes: list[Any] = []
    for index in range(count):
        row, column = divmod(index, columns)
        left = margin["left"] + column * (panel_w + margin["wide"])
        bottom = height - margin["top"] - (row + 1) * panel_h - row * margin["high"]
        axis = figure.add_axes(
            (left / width, bottom / height, panel_w / width, panel_h / height),
            sharey=axes[0] if axes else None,
        )
        if column > 0:
            axis.tick_params(labelleft=False)
        axes.append(axis)
    right = margin["left"] + columns * panel_w + (columns - 1) * margin["wide"] + bar_gap
    span = rows * panel_h + (rows - 1) * margin["high"]
    bar_axis = figure.add_axes(
        (
            right / width,
            (margin["bottom"] + 0.05 * span) / height,
            bar_w / width,
            0.9 * span / height,
        )
    )
    figure.suptitle("", y=1.0 - 0.2 / height)
    return figure, axes, bar_axis


def _save(figure: Any, path: str | Path | None) -> Any:
    """Save ``figure`` atomically, drawn once (no tight bounding box: the layout is fixed)."""
    if path is not None:
        target = Path(path)
        with atomic_open(target, "wb") as stream:
            figure.savefig(stream, format=target.suffix.lstrip(".") or "png", dpi=130)
    return figure


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
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter, NullLocator

    ticks = [
        m * 10.0**k
        for k in range(math.floor(math.log10(low)) - 1, math.ceil(math.log10(high)) + 1)
        for m in (1, 2, 5)
        if low <= m * 10.0**k <= high
    ]
    bar.ax.yaxis.set_major_locator(FixedLocator(ticks))
    bar.ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    bar.ax.yaxis.set_minor_formatter(NullFormatter())
    bar.ax.yaxis.set_minor_locator(NullLocator())
