"""Motion planning within slosh limits, in two halves.

- `sloshkit.plan.line`: the 1-D planner, the fastest rest-to-rest move along a line
  (`sloshkit.plan.line.planner.plan`, `PlanProblem`, `PlanResult`).
- `sloshkit.plan.path`: the 3-D path planner, the slosh-safe timing (and tilt) of a given path
  (`sloshkit.plan.path.planner.plan_path`, `PathProblem`, `PathPlanResult`).

The two halves do not import each other; each sub-package's docstring lists its modules.

The package itself is callable: ``sloshkit.plan(problem, ...)`` is
`sloshkit.plan.line.planner.plan` (a package attribute of ``sloshkit`` cannot also be a
function, so the package forwards the call).
"""

import sys
import types
from typing import Any

from sloshkit.plan.line.planner import PlanResult
from sloshkit.plan.line.planner import plan as _plan


class _CallablePackage(types.ModuleType):
    """Module type of `sloshkit.plan`: calling it runs `sloshkit.plan.line.planner.plan`."""

    def __call__(self, *args: Any, **kwargs: Any) -> PlanResult:
        return _plan(*args, **kwargs)


__wrapped__ = _plan  # inspect.signature and the API reference follow it
sys.modules[__name__].__class__ = _CallablePackage
