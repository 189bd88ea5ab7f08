"""Figures of result objects (matplotlib, imported only when a figure is drawn).

One module per result family; each registers its figure functions with
`sloshkit.results.register_plot`, and `sloshkit.results.PLOTS` names them so that
``result.plot()`` imports only the module it needs. The names below are imported on first use
(``from sloshkit.plotting import plot_sweep_map`` imports `sloshkit.plotting.sweep` alone);
`load_all` imports every module. Plotting draws only what a result object holds: it never
simulates, plans or selects a pyplot backend.

- `sloshkit.plotting.response`: `SloshResponse`, laws and responses side by side.
- `sloshkit.plotting.sweep`: slosh maps of a `SweepResult`.
- `sloshkit.plotting.calibration`: a `CalibrationResult`.
- `sloshkit.plotting.plan`: a `PlanResult`.
- `sloshkit.plotting.cfd`: a CFD validation.
- `sloshkit.plotting.response3d`: a 3-D `SpatialResponse`; measured against predicted series.
- `sloshkit.plotting.plan3d`: a 3-D `PathPlanResult`.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the real signatures for type checkers; imported lazily at run time
    from sloshkit.plotting.calibration import (
        plot_backbone,
        plot_calibration,
        plot_forced_identification,
        plot_free_response,
    )
    from sloshkit.plotting.cfd import plot_cfd_validation
    from sloshkit.plotting.plan import plot_plan
    from sloshkit.plotting.plan3d import plot_path_plan
    from sloshkit.plotting.response import (
        plot_law_comparison,
        plot_response,
        plot_slosh_comparison,
    )
    from sloshkit.plotting.response3d import plot_measured_comparison, plot_spatial_response
    from sloshkit.plotting.sweep import plot_sweep_map

#: Public figure function -> the module that defines it.
FUNCTIONS: dict[str, str] = {
    "plot_backbone": "sloshkit.plotting.calibration",
    "plot_calibration": "sloshkit.plotting.calibration",
    "plot_cfd_validation": "sloshkit.plotting.cfd",
    "plot_forced_identification": "sloshkit.plotting.calibration",
    "plot_free_response": "sloshkit.plotting.calibration",
    "plot_law_comparison": "sloshkit.plotting.response",
    "plot_measured_comparison": "sloshkit.plotting.response3d",
    "plot_path_plan": "sloshkit.plotting.plan3d",
    "plot_plan": "sloshkit.plotting.plan",
    "plot_response": "sloshkit.plotting.response",
    "plot_slosh_comparison": "sloshkit.plotting.response",
    "plot_spatial_response": "sloshkit.plotting.response3d",
    "plot_sweep_map": "sloshkit.plotting.sweep",
}


def load_all() -> list[str]:
    """Import every plotting module, registering all its figure functions.

    Returns
    -------
    list of str
        The modules imported, sorted.

    Examples
    --------
    >>> "sloshkit.plotting.sweep" in load_all()
    True
    """
    modules = sorted(set(FUNCTIONS.values()))
    for module in modules:
        importlib.import_module(module)
    return modules


def __getattr__(name: str) -> Any:
    if name in FUNCTIONS:
        value = getattr(importlib.import_module(FUNCTIONS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "FUNCTIONS",
    "load_all",
    "plot_backbone",
    "plot_calibration",
    "plot_cfd_validation",
    "plot_forced_identification",
    "plot_free_response",
    "plot_law_comparison",
    "plot_measured_comparison",
    "plot_path_plan",
    "plot_plan",
    "plot_response",
    "plot_slosh_comparison",
    "plot_spatial_response",
    "plot_sweep_map",
]
