"""The 3-D path planner: slosh-safe timing (and tilt) of a container along a given 3-D path.

- `sloshkit.plan.path.geometry`: the path (`Path`, `path_from_waypoints`, `path_from_poses`).
- `sloshkit.plan.path.problem`: `PathProblem`, its limits, the sampled pose export.
- `sloshkit.plan.path.planner`: `plan_path`, the methods side by side, each verified:
  ``retime`` and ``tilt`` (the programs; the families where they verify nothing), ``shaped``.
- `sloshkit.plan.path.result`: the verification (`verify`), candidates, `PathPlanResult`.
- `sloshkit.plan.path.limits`: kinematic limits of a sampled export.
- `sloshkit.plan.path.screen`: the linear slosh screen of a sampled export.
- `sloshkit.plan.path.timing`: `Timing` and the filters of the timing family.
- `sloshkit.plan.path.retime`: the jerk-limited, slosh-aware timing family.
- `sloshkit.plan.path.search`: the family's cap search, its verified members
  (`upright_family`) and the uniform stretch (`plan_uniform`).
- `sloshkit.plan.path.tilt_compensation`: the container's axis along the apparent gravity.
- `sloshkit.plan.path.tilt`: the tilt-compensated family member (`tilted_family`).
- `sloshkit.plan.path.optimal`, `sloshkit.plan.path.starts`,
  `sloshkit.plan.path.minimum_time`, `sloshkit.plan.path.splines`,
  `sloshkit.plan.path.transcription`, `sloshkit.plan.path.program`,
  `sloshkit.plan.path.samples`, `sloshkit.plan.path.joints`, `sloshkit.plan.path.pendulums`,
  `sloshkit.plan.path.small_angle`: the programs of ``retime`` and ``tilt`` (sequential
  second-order-cone programs on a spline transcription): their verified plans, where the
  search starts, its search over the duration, the splines, one program, its model, its
  samples, the arm's joints and the pendulums along the path.

It never imports the 1-D planner (`sloshkit.plan.line`; an import-linter contract).
"""
