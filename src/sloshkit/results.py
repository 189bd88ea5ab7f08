"""One protocol for every result object: ``to_dict``, ``to_pandas``, ``to_csv``, ``plot``.

A result class inherits `ResultMixin` and implements one hook, `ResultMixin.columns` (named,
equal-length 1-D arrays, SI units in the names); it may override `ResultMixin.to_dict` for a
richer JSON document. ``plot`` delegates to a function of `sloshkit.plotting` registered for the
result's class with `register_plot`, so the core never imports matplotlib. `PLOTS` names that
function as a ``"module:function"`` string per result class: the first ``plot`` call imports only
that plotting module (by name, through `importlib`), not every figure of the package. See
``docs/conventions.md``.

Examples
--------
>>> import numpy as np
>>> from dataclasses import dataclass
>>> @dataclass
... class Decay(ResultMixin):
...     t: np.ndarray
...     def columns(self):
...         return {"t_s": self.t, "angle_rad": np.exp(-self.t)}
>>> Decay(np.array([0.0, 1.0])).to_dict()["angle_rad"]
[1.0, 0.36787944117144233]
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from sloshkit.files import write_columns_csv

#: The package of the plotting functions; its ``load_all()`` imports (registers) every one.
PLOTTING_PACKAGE = "sloshkit.plotting"

#: Result class (``module.qualname``) -> ``"module:function"`` that draws it, resolved on the
#: first ``plot()``: drawing a sweep imports neither the calibration figures nor scipy.signal.
PLOTS: dict[str, str] = {
    "sloshkit.sim.response.SloshResponse": "sloshkit.plotting.response:plot_response",
    "sloshkit.sim.spatial_response.SpatialResponse": (
        "sloshkit.plotting.response3d:plot_spatial_response"
    ),
    "sloshkit.sweep.result.SweepResult": "sloshkit.plotting.sweep:plot_sweep_map",
    "sloshkit.calibration.result.CalibrationResult": (
        "sloshkit.plotting.calibration:plot_calibration"
    ),
    "sloshkit.calibration.backbone.Backbone": "sloshkit.plotting.calibration:plot_backbone",
    "sloshkit.calibration.forced.ForcedIdentification": (
        "sloshkit.plotting.calibration:plot_forced_identification"
    ),
    "sloshkit.plan.line.planner.PlanResult": "sloshkit.plotting.plan:plot_plan",
    "sloshkit.plan.path.result.PathPlanResult": "sloshkit.plotting.plan3d:plot_path_plan",
    "sloshkit.cfd.validation.CfdValidation": "sloshkit.plotting.cfd:plot_cfd_validation",
}

PlotFunction = Callable[..., Any]
_PLOTTERS: dict[type, PlotFunction] = {}


@runtime_checkable
class Result(Protocol):
    """What every sloshkit result offers (structural type of `ResultMixin`).

    Examples
    --------
    A simulation result satisfies the protocol:

    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> response = sk.simulate(model, sk.quintic(0.1, 0.5), sample_period_s=2e-3)
    >>> all(hasattr(response, name) for name in ("to_dict", "to_pandas", "to_csv", "plot"))
    True
    >>> sorted(response.columns())[:2]
    ['acceleration_m_s2', 'angle_1_rad']
    """

    def columns(self) -> Mapping[str, ArrayLike]:
        """Named, equal-length 1-D arrays (SI units in the names)."""
        ...  # pragma: no cover

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict (SI units in the keys)."""
        ...  # pragma: no cover

    def to_pandas(self) -> Any:
        """`columns` as a pandas DataFrame."""
        ...  # pragma: no cover

    def to_csv(self, path: str | Path) -> Path:
        """`columns` written as CSV."""
        ...  # pragma: no cover

    def plot(self, ax: Any = None, *, path: str | Path | None = None, **options: Any) -> Any:
        """The result's figure."""
        ...  # pragma: no cover


def register_plot(result_type: type) -> Callable[[PlotFunction], PlotFunction]:
    """Decorator: register ``function(result, ax=None, path=None) -> Figure`` for a result type.

    Parameters
    ----------
    result_type : type
        The result class whose ``plot`` method calls the decorated function.

    Returns
    -------
    Callable
        The decorator (returns the function unchanged).

    Examples
    --------
    >>> class Dummy(ResultMixin):
    ...     def columns(self):
    ...         return {"t_s": [0.0]}
    >>> @register_plot(Dummy)
    ... def plot_dummy(result, ax=None, path=None):
    ...     return "figure"
    >>> Dummy().plot()
    'figure'
    """

    def decorate(function: PlotFunction) -> PlotFunction:
        _PLOTTERS[result_type] = function
        return function

    return decorate


def plotter_for(result_type: type) -> PlotFunction:
    """The plotting function registered for ``result_type`` (or one of its bases).

    Looks in the registry, then in `PLOTS` (importing only the module named there), then imports
    every plotting module (``sloshkit.plotting.load_all``) for a function registered elsewhere.

    Parameters
    ----------
    result_type : type
        A result class.

    Returns
    -------
    callable
        The registered function.

    Raises
    ------
    TypeError
        When no function is registered for the type.

    Examples
    --------
    >>> from sloshkit.sim.response import SloshResponse
    >>> plotter_for(SloshResponse).__name__
    'plot_response'
    """
    for klass in result_type.__mro__:
        if klass in _PLOTTERS:
            return _PLOTTERS[klass]
        target = PLOTS.get(f"{klass.__module__}.{klass.__qualname__}")
        if target is not None:
            module, _, name = target.partition(":")
            function: PlotFunction = getattr(importlib.import_module(module), name)
            _PLOTTERS.setdefault(klass, function)
            return _PLOTTERS[klass]
    importlib.import_module(PLOTTING_PACKAGE).load_all()
    for klass in result_type.__mro__:
        if klass in _PLOTTERS:
            return _PLOTTERS[klass]
    raise TypeError(f"no plotting function registered for {result_type.__name__}")


def registered_plotters() -> dict[type, PlotFunction]:
    """The plotting functions registered so far, by result type (a copy).

    Returns
    -------
    dict
        Result type -> plotting function.

    Examples
    --------
    >>> from sloshkit.sim.response import SloshResponse
    >>> _ = plotter_for(SloshResponse)
    >>> registered_plotters()[SloshResponse].__name__
    'plot_response'
    """
    return dict(_PLOTTERS)


def require_pandas() -> Any:
    """Import pandas or raise an `ImportError` that says how to install it.

    Returns
    -------
    module
        The ``pandas`` module.

    Examples
    --------
    >>> require_pandas().__name__
    'pandas'
    """
    try:
        import pandas
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "to_pandas() needs pandas, which is optional: pip install pandas"
        ) from exc
    return pandas


class ResultMixin:
    """Default implementation of the result protocol from the `columns` hook.

    Examples
    --------
    >>> import numpy as np
    >>> class Trace(ResultMixin):
    ...     def columns(self):
    ...         return {"t_s": np.array([0.0, 1.0])}
    >>> Trace().to_dict()
    {'t_s': [0.0, 1.0]}
    """

    def columns(self) -> Mapping[str, ArrayLike]:
        """Named, equal-length 1-D arrays (SI units in the names); implemented by each result."""
        raise NotImplementedError(f"{type(self).__name__} does not define columns()")

    def to_dict(self) -> dict[str, Any]:
        """`columns` as lists of floats (override for a richer document)."""
        return {
            name: np.asarray(values, dtype=float).tolist()
            for name, values in self.columns().items()
        }

    def to_pandas(self) -> Any:
        """`columns` as a pandas DataFrame (pandas is imported here, and is optional)."""
        return require_pandas().DataFrame(dict(self.columns()))

    def to_csv(self, path: str | Path) -> Path:
        """Write `columns` as CSV with a header row, atomically; returns the path."""
        columns = {name: np.asarray(v, dtype=float) for name, v in self.columns().items()}
        return write_columns_csv(path, columns)

    def plot(self, ax: Any = None, *, path: str | Path | None = None, **options: Any) -> Any:
        """The result's matplotlib Figure, drawn by the function registered for its type.

        ``ax``: an Axes to draw into (its figure is returned) or None for a new Figure; the
        figure is saved to ``path`` when given; ``options`` go to the plotting function. No
        pyplot backend is selected. A path given in place of ``ax`` (the v1 signature
        ``plot(path)``) is taken as ``path``.
        """
        if isinstance(ax, str | os.PathLike):
            ax, path = None, ax
        return plotter_for(type(self))(self, ax=ax, path=path, **options)
