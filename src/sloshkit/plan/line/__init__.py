"""The 1-D planner: the fastest rest-to-rest move along a line that keeps the slosh within limits.

- `sloshkit.plan.line.problem`: limits, `PlanProblem`, candidates.
- `sloshkit.plan.line.verification`: every candidate re-simulated from its sampled export.
- `sloshkit.plan.line.searches`: the paper's laws and shaped S-curves.
- `sloshkit.plan.line.optimal`: minimum-time control on the export grid (linear programs,
  HiGHS), and its smooth variant.
- `sloshkit.plan.line.export_grid`: those linear programs on the controller's export grid,
  solved by HiGHS (the longest move of a duration, the smooth move).
- `sloshkit.plan.line.grid_program`: their assembly: variables, rows, bounds, and what
  changes with the last step.
- `sloshkit.plan.line.triplets`: sparse matrices as (row, column, value) triplets.
- `sloshkit.plan.line.grid_moves`: moves on the export grid, measured again.
- `sloshkit.plan.line.optimal_nonlinear`: the large-angle pendulums by multiple shooting
  (casadi/IPOPT).
- `sloshkit.plan.line.work_estimate`: the planner's work, estimated before it starts.
- `sloshkit.plan.line.planner`: `plan` and `PlanResult` (``sloshkit.plan(...)`` calls `plan`).

It never imports the path planner (`sloshkit.plan.path`; an import-linter contract).
"""
