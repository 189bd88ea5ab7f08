"""The result of comparing a CFD case with the pendulum model for the same motion.

`CfdValidation` follows the shared result protocol (`sloshkit.results.ResultMixin`):
``to_dict`` is the JSON document of ``sloshkit cfd validate --json``, ``columns`` /
``to_pandas`` / ``to_csv`` hold the two compared series, and ``plot`` draws the seed paper's
Fig. 9 with `sloshkit.plotting.cfd.plot_cfd_validation` (registered here through
`sloshkit.results.register_plot` and imported by name when a figure is drawn, so this module
never imports matplotlib).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.results import ResultMixin, register_plot

#: Kinds of comparison: the 1-D wall elevation, or the 3-D slosh height of a pose trajectory.
KINDS = ("wall-elevation", "poses")


def comparison_row(cfd: float | None, model: float | None) -> dict[str, float | None]:
    """One row of a comparison: both values and the relative difference to the model.

    Parameters
    ----------
    cfd : float or None
        The CFD value (None when it could not be measured).
    model : float or None
        The model value.

    Returns
    -------
    dict
        ``cfd``, ``model`` and ``relative_difference`` ((cfd - model) / model, or None).

    Examples
    --------
    >>> comparison_row(1.1, 1.0)["relative_difference"]  # doctest: +ELLIPSIS
    0.100000...
    >>> comparison_row(None, 1.0)["relative_difference"] is None
    True
    """
    difference = None
    if cfd is not None and model is not None and model != 0.0:
        difference = (cfd - model) / model
    return {"cfd": cfd, "model": model, "relative_difference": difference}


def require_model_first(model: object, case: object) -> None:
    """Refuse the v1 argument order ``(case, model)`` with a `TypeError` saying so.

    Parameters
    ----------
    model : object
        What was passed as the model.
    case : object
        What was passed as the case folder.

    Returns
    -------
    None

    Raises
    ------
    TypeError
        ``model`` is a path (or ``case`` is not one).

    Examples
    --------
    >>> require_model_first(Path("case"), None)
    Traceback (most recent call last):
    ...
    TypeError: validate takes (model, case); got a path first (the v1 order was (case, model))
    """
    if isinstance(model, str | Path) or not isinstance(case, str | Path):
        raise TypeError(
            "validate takes (model, case); got a path first (the v1 order was (case, model))"
        )


@dataclass(frozen=True, eq=False)
class CfdValidation(ResultMixin):
    """A finished CFD case against the equivalent pendulum model for the same motion.

    Parameters
    ----------
    case : str
        The case folder.
    comparison : dict
        Quantity name (with its unit) -> `comparison_row`.
    correlation : float or None
        Correlation of the two compared series over the whole record.
    time_s : ndarray
        Sample times of the CFD record [s].
    cfd_elevation_m, model_elevation_m : ndarray
        The compared series [m]: the wall elevation at 0.98 R (1-D), or the slosh height, the
        largest wall elevation over the probe columns (poses).
    excitation_end_s : float
        When the container stops moving [s] (0 for a free decay).
    kind : str
        ``wall-elevation`` or ``poses`` (see `KINDS`).
    extra : dict
        Further JSON keys of a pose comparison (``wall_correlation``, ``probe_angles_deg``,
        ``quantity_label``).

    Returns
    -------
    CfdValidation

    References
    ----------
    De Simone et al. (2024), the seed paper, Table 4 and Fig. 9.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> result = CfdValidation("c", {"damping_ratio": comparison_row(0.005, 0.006)}, 0.99,
    ...                        t, 1e-3 * t, 1e-3 * t, 0.5)
    >>> sorted(result.to_dict())
    ['case', 'comparison', 'correlation', 'excitation_end_s']
    >>> list(result.columns())
    ['time_s', 'cfd_elevation_m', 'model_elevation_m']
    """

    case: str
    comparison: dict[str, dict[str, float | None]]
    correlation: float | None
    time_s: NDArray[np.float64]
    cfd_elevation_m: NDArray[np.float64]
    model_elevation_m: NDArray[np.float64]
    excitation_end_s: float
    kind: str = "wall-elevation"
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def quantity_label(self) -> str:
        """Axis label of the compared series."""
        return str(self.extra.get("quantity_label", "wall elevation at 0.98 R [mm]"))

    def columns(self) -> dict[str, NDArray[np.float64]]:
        """The compared series: ``time_s``, ``cfd_elevation_m``, ``model_elevation_m``."""
        return {
            "time_s": self.time_s,
            "cfd_elevation_m": self.cfd_elevation_m,
            "model_elevation_m": self.model_elevation_m,
        }

    def to_dict(self) -> dict[str, Any]:
        """The JSON document of ``sloshkit cfd validate --json`` (no series)."""
        payload: dict[str, Any] = {"case": self.case}
        if self.kind == "poses":
            payload["kind"] = self.kind
        payload.update(comparison=self.comparison, correlation=self.correlation)
        payload.update(self.extra)
        payload["excitation_end_s"] = self.excitation_end_s
        return payload


@register_plot(CfdValidation)
def _plot_validation(
    result: CfdValidation, ax: Any = None, path: str | Path | None = None, **options: Any
) -> Any:
    """Draw with `sloshkit.plotting.cfd` (imported by name: matplotlib stays in plotting/)."""
    plotting = importlib.import_module("sloshkit.plotting.cfd")
    return plotting.plot_cfd_validation(result, path, ax=ax, **options)
