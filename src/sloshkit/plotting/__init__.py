"""Figures of result objects (matplotlib, imported only when a figure is drawn).

One module per result family; importing this package registers each figure function with
`sloshkit.results.register_plot`, which is how ``result.plot()`` finds it. Plotting draws only
what a result object holds: it never simulates, plans or selects a pyplot backend.

- `sloshkit.plotting.response`: `SloshResponse`, laws and responses side by side.
- `sloshkit.plotting.sweep`: slosh maps of a `SweepResult`.
- `sloshkit.plotting.calibration`: a `CalibrationResult`.
- `sloshkit.plotting.plan`: a `PlanResult`.
- `sloshkit.plotting.cfd`: a CFD validation.
- `sloshkit.plotting.spatial`: a 3-D `SpatialResponse`; measured against predicted series.
- `sloshkit.plotting.plan3d`: a 3-D `PathPlanResult`.
"""

from sloshkit.plotting.calibration import plot_calibration, plot_free_response
from sloshkit.plotting.cfd import plot_cfd_validation
from sloshkit.plotting.plan import plot_plan
from sloshkit.plotting.plan3d import plot_path_plan
from sloshkit.plotting.response import plot_law_comparison, plot_response, plot_slosh_comparison
from sloshkit.plotting.spatial import plot_measured_comparison, plot_spatial_response
from sloshkit.plotting.sweep import plot_sweep_map

__all__ = [
    "plot_calibration",
    "plot_cfd_validation",
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
