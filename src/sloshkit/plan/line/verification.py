"""Verification of a candidate motion from its sampled export.

Verification never trusts a planner's internal model: the motion is sampled at the controller's
period, and the exported velocity samples (linear between samples) are simulated again with the
exact discretisation of every mode, for every frequency of the robustness band. The slosh is
simulated on the *slosh check grid*: the controller period divided into `slosh_substeps`
equal sub-steps, no longer than `FINEST_CONTROLLER_PERIOD_S` (the 2 ms of URScript ``servoj``),
so that a plan's limits hold when it is resampled for any supported controller (2 ms URScript,
4 ms the default, 8 ms and longer for ROS 2 and the others), not only on its own grid.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import ValidityWarning
from sloshkit.motion.profile import Motion
from sloshkit.motion.recorded import from_samples
from sloshkit.motion.sampling import export_samples
from sloshkit.plan.line.problem import Candidate, PlanProblem, PlanStatus, Verification
from sloshkit.sim.discretisation import linear_response
from sloshkit.sim.metrics import free_amplitude, wall_elevation, wall_elevation_factors
from sloshkit.sim.simulate import simulate

FloatArray = NDArray[np.float64]

#: The finest controller period a plan is exported to [s]: URScript ``servoj`` on the UR
#: e-Series (500 Hz). A plan's slosh limits are checked on a grid at least this fine.
FINEST_CONTROLLER_PERIOD_S = 0.002


def slosh_substeps(sample_period_s: float) -> int:
    """Sub-steps of a controller period on the slosh check grid: the fewest equal parts no
    longer than `FINEST_CONTROLLER_PERIOD_S` (the grid rule, `steps_to_reach`).

    Parameters
    ----------
    sample_period_s : float
        The plan's controller period [s].

    Returns
    -------
    int
        m >= 1; the slosh is checked every ``sample_period_s / m``.

    Examples
    --------
    >>> slosh_substeps(0.004), slosh_substeps(0.002), slosh_substeps(0.001), slosh_substeps(0.008)
    (2, 1, 1, 4)
    """
    from sloshkit.motion.sampling import steps_to_reach

    return max(1, steps_to_reach(sample_period_s, FINEST_CONTROLLER_PERIOD_S))


def verify(motion: Motion, problem: PlanProblem) -> Verification:
    """Re-simulate the sampled export of ``motion`` and check every limit.

    The velocity sampled on the slosh check grid (`slosh_substeps` per controller period) is
    taken as linear between samples (what the exact first-order-hold discretisation assumes)
    and simulated for each model of the band. The residual amplitude is taken from the state
    at the last sample, when the move is over. Machine limits and the end position are checked
    on the controller's samples. With
    ``problem.nonlinear`` the exported accelerations drive the large-angle pendulums instead.

    Parameters
    ----------
    motion : Motion
        The candidate move.
    problem : PlanProblem
        Its limits, model, band and sample period.

    Returns
    -------
    Verification
        Peaks, residual, end error and the violated limits.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(0.1, sk.MachineLimits(1.0, 5.0, 200.0),
    ...                          sk.SloshLimits(0.1, 0.01), model)
    >>> verify(sk.quintic(0.1, 1.5), problem).feasible
    True
    """
    samples = export_samples(motion, problem.sample_period_s)
    velocity = samples["velocity_m_s"]
    ts = problem.sample_period_s
    peak_angle = residual = peak_wall = 0.0
    if problem.nonlinear:
        peak_angle, residual, peak_wall = _verify_nonlinear(samples, problem)
    check_period = ts / slosh_substeps(ts)
    check = velocity if check_period == ts else export_samples(motion, check_period)["velocity_m_s"]
    for model in [] if problem.nonlinear else problem.models():
        theta, rate = linear_response(model, check, check_period)
        first = model.modes[0]
        wall = wall_elevation(wall_elevation_factors(model), theta)
        peak_angle = max(peak_angle, float(np.max(np.abs(theta[0]))))
        residual = max(
            residual,
            float(
                free_amplitude(theta[0, -1], rate[0, -1], first.omega_rad_s, first.damping_ratio)
            ),
        )
        peak_wall = max(peak_wall, float(np.max(np.abs(wall))))
    machine, slosh = problem.machine, problem.slosh
    peaks = {
        "velocity": float(np.max(np.abs(velocity))),
        "acceleration": float(np.max(np.abs(samples["acceleration_m_s2"]))),
        "jerk": motion.peak_jerk_m_s3,
    }
    end_error = abs(float(samples["position_m"][-1]) - problem.distance_m)
    violations = []
    checks = [
        ("peak angle", peak_angle, slosh.max_angle_rad, math.degrees, "deg"),
        ("residual angle", residual, slosh.max_residual_rad, math.degrees, "deg"),
        ("velocity", peaks["velocity"], machine.max_velocity_m_s, float, "m/s"),
        ("acceleration", peaks["acceleration"], machine.max_acceleration_m_s2, float, "m/s^2"),
        ("jerk", peaks["jerk"], machine.max_jerk_m_s3, float, "m/s^3"),
    ]
    if slosh.max_wall_elevation_m is not None:
        checks.append(("wall elevation", peak_wall, slosh.max_wall_elevation_m, float, "m"))
    if problem.max_duration_s is not None:
        checks.append(("duration", motion.duration_s, problem.max_duration_s, float, "s"))
    for name, value, limit, unit_of, unit in checks:
        # 1e-7: the optimiser meets its bounds to solver precision.
        if value > limit * (1.0 + 1e-7):
            violations.append(f"{name} {unit_of(value):.4g} > {unit_of(limit):.4g} {unit}")
    if end_error > 1e-6 * problem.distance_m:
        violations.append(f"ends {end_error:.3g} m from the target")
    return Verification(
        duration_s=motion.duration_s,
        peak_angle_rad=peak_angle,
        residual_angle_rad=residual,
        peak_wall_elevation_m=peak_wall,
        peak_velocity_m_s=peaks["velocity"],
        peak_acceleration_m_s2=peaks["acceleration"],
        peak_jerk_m_s3=peaks["jerk"],
        end_error_m=end_error,
        violations=tuple(violations),
    )


def _verify_nonlinear(
    samples: dict[str, FloatArray], problem: PlanProblem
) -> tuple[float, float, float]:
    """Peak angle, residual and peak wall elevation of the exported acceleration samples
    (cubic spline) with the large-angle pendulums, worst over the band."""
    import warnings

    motion = from_samples(samples["t_s"], acceleration_m_s2=samples["acceleration_m_s2"])
    peak = residual = wall = 0.0
    for model in problem.models():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            response = simulate(
                model,
                motion,
                kind="nonlinear",
                sample_period_s=problem.sample_period_s,
                settle_time_s=0.0,
            )
        peak = max(peak, float(np.max(np.abs(response.angle_rad[0]))))
        residual = max(residual, response.residual_angle_rad)
        wall = max(wall, float(np.max(np.abs(response.wall_elevation_m))))
    return peak, residual, wall


def checked_candidate(
    method: str, motion: Motion, problem: PlanProblem, started: float, **detail: Any
) -> Candidate:
    """A planner's motion as a `Candidate`, verified (`verify`): feasible only when its export
    meets every limit, else its violations in the message.

    Parameters
    ----------
    method : str
        The planner's name.
    motion : Motion
        The planned motion.
    problem : PlanProblem
        Limits, model and sample period.
    started : float
        ``time.perf_counter()`` when the planner started (the compute time ends now).
    **detail
        The planner's own figures, kept in ``Candidate.detail``.

    Returns
    -------
    Candidate

    Examples
    --------
    >>> import time
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             0.04)
    >>> problem = sk.PlanProblem(0.1, sk.MachineLimits(1.0, 5.0, 200.0),
    ...                          sk.SloshLimits(0.3, 0.05), model)
    >>> found = checked_candidate("quintic", sk.quintic(0.1, 1.5), problem, time.perf_counter())
    >>> found.method, found.status.name, found.message
    ('quintic', 'FEASIBLE', 'verified')
    """
    check = verify(motion, problem)
    status = PlanStatus.FEASIBLE if check.feasible else PlanStatus.INFEASIBLE
    message = "verified" if check.feasible else "violates " + "; ".join(check.violations)
    return Candidate(method, status, motion, check, time.perf_counter() - started, message, detail)


def only_slosh_violations(candidate: Candidate) -> bool:
    """Whether a verified candidate breaks slosh limits only (peak or residual angle, wall
    elevation), not a machine limit: then slowing it down can mend it.

    Parameters
    ----------
    candidate : Candidate
        A verified candidate (`checked_candidate`).

    Returns
    -------
    bool
        False when it was not verified or a machine limit is broken.

    Examples
    --------
    >>> import time
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             0.04)
    >>> problem = sk.PlanProblem(0.1, sk.MachineLimits(1.0, 5.0, 200.0),
    ...                          sk.SloshLimits(0.01, 0.005), model)
    >>> fast = checked_candidate("quintic", sk.quintic(0.1, 0.5), problem, time.perf_counter())
    >>> fast.status.name, only_slosh_violations(fast)
    ('INFEASIBLE', True)
    >>> faster = checked_candidate("quintic", sk.quintic(0.1, 0.3), problem, time.perf_counter())
    >>> only_slosh_violations(faster)  # 6.4 m/s^2 > 5 m/s^2 too
    False
    """
    check = candidate.verification
    return check is not None and all(
        v.startswith(("peak angle", "residual angle", "wall elevation")) for v in check.violations
    )
