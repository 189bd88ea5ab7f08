"""Planning of the fastest rest-to-rest move that keeps the slosh within limits.

- `sloshkit.plan.problem`: limits, `PlanProblem`, candidates.
- `sloshkit.plan.verification`: every candidate re-simulated from its sampled export.
- `sloshkit.plan.searches`: the paper's laws and shaped S-curves.
- `sloshkit.plan.optimal`: minimum-time control on the export grid (linear programs, HiGHS;
  large-angle pendulums by casadi/IPOPT).
- `sloshkit.plan.planner`: `plan` and `PlanResult`.

The package itself is callable: ``sloshkit.plan(problem, ...)`` is
`sloshkit.plan.planner.plan` (a package attribute of ``sloshkit`` cannot also be a function,
so the package forwards the call).
"""

import sys
import types
from typing import Any

from sloshkit.plan.planner import PlanResult
from sloshkit.plan.planner import plan as _plan


class _CallablePackage(types.ModuleType):
    """Module type of `sloshkit.plan`: calling it runs `sloshkit.plan.planner.plan`."""

    def __call__(self, *args: Any, **kwargs: Any) -> PlanResult:
        return _plan(*args, **kwargs)


__wrapped__ = _plan  # inspect.signature and the API reference follow it
sys.modules[__name__].__class__ = _CallablePackage
