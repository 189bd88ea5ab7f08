"""Planning of the fastest rest-to-rest move that keeps the slosh within limits.

- `sloshkit.plan.problem`: limits, `PlanProblem`, candidates.
- `sloshkit.plan.verification`: every candidate re-simulated from its sampled export.
- `sloshkit.plan.searches`: the paper's laws and shaped S-curves.
- `sloshkit.plan.optimal`: minimum-time control (casadi/IPOPT).
- `sloshkit.plan.planner`: `plan` and `PlanResult`.
"""
