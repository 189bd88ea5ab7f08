"""Figure plumbing shared by the plotting modules: new figures without pyplot, panels inside a
caller's Axes, atomic saving.

Figures are `matplotlib.figure.Figure` objects created directly, never through pyplot: no
backend is selected (a notebook keeps its own) and nothing is kept in pyplot's figure registry.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from sloshkit.files import atomic_open


def panels(
    ax: Any,
    rows: int,
    columns: int = 1,
    *,
    figsize: tuple[float, float],
    sharex: bool = False,
    sharey: bool = False,
    squeeze: bool = True,
    layout: Any = None,
) -> tuple[Any, Any]:
    """(figure, axes) for a figure of ``rows`` x ``columns`` panels.

    Parameters
    ----------
    ax : matplotlib.axes.Axes or None
        None: a new `matplotlib.figure.Figure`; otherwise the panels share the area of ``ax``
        (which is removed when more than one panel is needed) in its figure.
    rows, columns : int
        Panel grid.
    figsize : tuple of float
        Size of a new figure [in].
    sharex, sharey, squeeze : bool
        As in `matplotlib.figure.Figure.subplots`.
    layout : str, optional
        Layout engine of a new figure (e.g. ``"constrained"``).

    Returns
    -------
    tuple
        (figure, axes) as `matplotlib.figure.Figure.subplots` returns them.

    Examples
    --------
    Two panels sharing the area of one axes of an existing figure:

    >>> from matplotlib.figure import Figure
    >>> host = Figure().subplots(1, 2)[1]
    >>> figure, axes = panels(host, 2, figsize=(6, 4), sharex=True)
    >>> len(axes), len(figure.axes)
    (2, 3)
    """
    from matplotlib.figure import Figure

    if ax is None:
        figure = Figure(figsize=figsize, layout=layout)
        axes = figure.subplots(rows, columns, sharex=sharex, sharey=sharey, squeeze=squeeze)
        return figure, axes
    figure = ax.get_figure()
    if rows * columns == 1:
        if squeeze:
            return figure, ax
        import numpy as np

        return figure, np.array([[ax]])
    spec = ax.get_subplotspec().subgridspec(rows, columns)
    ax.remove()
    axes = spec.subplots(sharex=sharex, sharey=sharey, squeeze=squeeze)
    return figure, axes


def save_figure(figure: Any, path: str | Path | None) -> Any:
    """Save ``figure`` atomically (format from the suffix) when ``path`` is given; return it.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure.
    path : str or Path, optional
        Target file; nothing is written when None.

    Returns
    -------
    matplotlib.figure.Figure
        ``figure``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from matplotlib.figure import Figure
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "empty.svg"
    >>> figure = save_figure(Figure(), target)
    >>> target.read_text()[:5]
    '<?xml'
    """
    if path is not None:
        target = Path(path)
        with atomic_open(target, "wb") as stream:
            figure.savefig(
                stream, format=target.suffix.lstrip(".") or "png", dpi=130, bbox_inches="tight"
            )
    return figure
