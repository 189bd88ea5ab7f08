"""The 3-D path planner: slosh-safe timing (and tilt) of a container along a given 3-D path.

- `sloshkit.plan.path.geometry`: the path (`Path`, `path_from_waypoints`, `path_from_poses`).
- `sloshkit.plan.path.problem`: `PathProblem`, its limits, the sampled pose export.
- `sloshkit.plan.path.planner`: `plan_path`, the methods side by side, each verified.
- `sloshkit.plan.path.result`: the verification (`verify`), candidates, `PathPlanResult`.
- `sloshkit.plan.path.limits`: kinematic limits of a sampled export.
- `sloshkit.plan.path.screen`: the linear slosh screen of a sampled export.
- `sloshkit.plan.path.timing`: `Timing` and the filters of the timing family.
- `sloshkit.plan.path.retime`: the jerk-limited, slosh-aware timing family.
- `sloshkit.plan.path.search`, `sloshkit.plan.path.slp`, `sloshkit.plan.path.improve`,
  `sloshkit.plan.path.ladder`: the ``retime`` method's searches, SLP, improvement and seeds.
- `sloshkit.plan.path.tilt_compensation`: the container's axis along the apparent gravity.
- `sloshkit.plan.path.tilt`: the ``tilt`` method (tilt compensation and re-timing).
- `sloshkit.plan.path.optimal`, `sloshkit.plan.path.minimum_time`,
  `sloshkit.plan.path.splines`, `sloshkit.plan.path.transcription`,
  `sloshkit.plan.path.program`, `sloshkit.plan.path.samples`, `sloshkit.plan.path.joints`,
  `sloshkit.plan.path.pendulums`: the ``optimal`` method (sequential second-order-cone
  programs on a spline transcription): its verified plan, its search over the duration, the
  splines, one program, its model, its samples, the arm's joints and the pendulums along the
  path.

It never imports the 1-D planner (`sloshkit.plan.line`; an import-linter contract).
"""
