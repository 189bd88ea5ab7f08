"""Minimum-time control of the large-angle pendulums by direct multiple shooting (casadi/IPOPT).

Used for ``--nonlinear-optimal``; the linear problem is solved on the export grid by
`sloshkit.plan.line.optimal`. Jerk as the control, piecewise constant; states position, velocity,
acceleration and every mode's angle and rate, for each frequency of the robustness band, with
the slosh limits as path constraints and the residual amplitude as a terminal constraint,
warm-started from the best fast method (Betts, *Practical Methods for Optimal Control*, 2nd ed.,
SIAM (2010) ch. 4, doi:10.1137/1.9780898718577). Path constraints hold at the shooting nodes
only: when the verified export violates a slosh limit, the limits are tightened by the
violation and the problem solved again.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.laws import s_curve
from sloshkit.motion.profile import Motion, piecewise_constant_jerk
from sloshkit.plan.line.problem import Candidate, PlanProblem, PlanStatus
from sloshkit.plan.line.searches import plan_shaped
from sloshkit.plan.line.verification import checked_candidate, only_slosh_violations
from sloshkit.sim.discretisation import linear_mode_response
from sloshkit.sim.equations import pendulum_angular_acceleration
from sloshkit.sim.metrics import (
    free_oscillation_components,
    wall_elevation,
    wall_elevation_factors,
)

FloatArray = NDArray[np.float64]


def plan_optimal_nonlinear(
    problem: PlanProblem,
    warm_start: Motion | None = None,
    nonlinear: bool = True,
    intervals: int | None = None,
    attempts: int = 4,
) -> Candidate:
    """Minimum-time move by direct multiple shooting (RK4, 2 sub-steps, piecewise-constant
    jerk), solved by IPOPT. Path constraints hold at the nodes; if the verified export still
    violates a slosh limit, the limits are tightened by the violation and the problem solved
    again (up to ``attempts`` times).

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model and sample period.
    warm_start : Motion, optional
        A feasible move to start from (default: the ZV-shaped S-curve).
    nonlinear : bool
        Large-angle pendulums (else the linear ones, on the shooting grid).
    intervals : int, optional
        Shooting intervals (default: one per sample period, 60 to 240).
    attempts : int
        Solves with tightened limits at most.

    Returns
    -------
    Candidate
        ``optimal``; ``detail`` has ``intervals``, ``ipopt_status``, ``model`` and
        ``tightening``.

    References
    ----------
    Betts, *Practical Methods for Optimal Control*, 2nd ed., SIAM (2010) ch. 4,
    doi:10.1137/1.9780898718577.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(0.01, sk.MachineLimits(1.0, 5.0, 200.0),
    ...                          sk.SloshLimits(0.1, 0.01), model, 0.02)
    >>> plan_optimal_nonlinear(problem, sk.quintic(0.01, 0.5), intervals=8).method
    'optimal'
    """
    started = time.perf_counter()
    try:
        import casadi as ca
    except ImportError:  # pragma: no cover - casadi is in the optional extra
        return Candidate(
            "optimal", PlanStatus.FAILED, message="casadi is not installed: pip install casadi"
        )
    if warm_start is None:
        warm_start = plan_shaped(problem, ("zv",)).motion or s_curve(
            problem.distance_m,
            problem.machine.max_velocity_m_s,
            problem.machine.max_acceleration_m_s2,
            problem.machine.max_jerk_m_s3,
        )
    count = intervals or int(
        np.clip(round(warm_start.duration_s / problem.sample_period_s), 60, 240)
    )
    tightening = 1.0
    last: Candidate | None = None
    for attempt in range(attempts):
        solution = _solve_ocp(ca, problem, warm_start, count, nonlinear, tightening)
        if solution is None:
            break
        durations, jerks, stats = solution
        motion = piecewise_constant_jerk("optimal", [durations] * count, list(jerks))
        motion = Motion("optimal", motion.position_pp)
        candidate = checked_candidate(
            "optimal",
            motion,
            problem,
            started,
            intervals=count,
            ipopt_status=stats,
            model="nonlinear" if nonlinear else "linear",
            tightening=tightening,
        )
        last = candidate
        if candidate.feasible or not only_slosh_violations(candidate):
            return candidate
        check = candidate.verification
        assert check is not None
        ratios = [
            check.peak_angle_rad / problem.slosh.max_angle_rad,
            check.residual_angle_rad / problem.slosh.max_residual_rad,
        ]
        if problem.slosh.max_wall_elevation_m is not None:
            ratios.append(check.peak_wall_elevation_m / problem.slosh.max_wall_elevation_m)
        tightening *= 1.0 / max(ratios) * (0.999 - 0.002 * attempt)
        warm_start = motion
    if last is not None:
        return replace(last, compute_time_s=time.perf_counter() - started)
    return Candidate(
        "optimal",
        PlanStatus.FAILED,
        None,
        None,
        time.perf_counter() - started,
        "IPOPT found no solution",
    )


def _solve_ocp(
    ca: Any, problem: PlanProblem, guess: Motion, count: int, nonlinear: bool, tightening: float
) -> tuple[float, FloatArray, str] | None:
    """Build the multiple-shooting NLP with casadi SX expressions and solve it with IPOPT.

    Returns (interval length [s], jerk per interval [m/s^3], IPOPT status) or None.
    """
    models = problem.models()
    modes = [mode for model in models for mode in model.modes]
    first_rows = [sum(len(m.modes) for m in models[:i]) for i in range(len(models))]
    size = len(modes)
    width = 3 + 2 * size
    machine, slosh = problem.machine, problem.slosh
    omega = ca.DM([m.omega_rad_s for m in modes])
    zeta = ca.DM([m.damping_ratio for m in modes])
    length = ca.DM([m.length_m for m in modes])

    state_symbol = ca.SX.sym("x", width)
    jerk_symbol = ca.SX.sym("u")
    step_symbol = ca.SX.sym("h")
    acceleration = state_symbol[2]
    theta = state_symbol[3 : 3 + size]
    rate = state_symbol[3 + size :]
    second = pendulum_angular_acceleration(
        theta, rate, acceleration, omega, zeta, length, nonlinear=nonlinear, sin=ca.sin, cos=ca.cos
    )
    derivative = ca.Function(
        "f",
        [state_symbol, jerk_symbol],
        [ca.vertcat(state_symbol[1], acceleration, jerk_symbol, rate, second)],
    )
    state = state_symbol
    sub = step_symbol / 2
    for _ in range(2):  # RK4, two sub-steps per interval
        k1 = derivative(state, jerk_symbol)
        k2 = derivative(state + sub / 2 * k1, jerk_symbol)
        k3 = derivative(state + sub / 2 * k2, jerk_symbol)
        k4 = derivative(state + sub * k3, jerk_symbol)
        state = state + sub / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    advance = ca.Function("F", [state_symbol, jerk_symbol, step_symbol], [state])

    duration = ca.SX.sym("T")
    states = ca.SX.sym("X", width, count + 1)
    controls = ca.SX.sym("U", count)
    step = duration / count
    shooting = advance.map(count)(states[:, :-1], controls.T, ca.repmat(step, 1, count))
    constraints = [ca.vec(states[:, 1:] - shooting)]
    low = [np.zeros(width * count)]
    high = [np.zeros(width * count)]

    def add(expression: Any, lower: float | FloatArray, upper: float | FloatArray) -> None:
        constraints.append(ca.vec(expression))
        n = int(ca.vec(expression).shape[0])
        low.append(np.broadcast_to(np.asarray(lower, dtype=float), (n,)).copy())
        high.append(np.broadcast_to(np.asarray(upper, dtype=float), (n,)).copy())

    for row in first_rows:
        mode = modes[row]
        theta_end, quadrature = free_oscillation_components(
            states[3 + row, count],
            states[3 + size + row, count],
            mode.omega_rad_s,
            mode.damping_ratio,
        )
        add(theta_end**2 + quadrature**2, -np.inf, (slosh.max_residual_rad * tightening) ** 2)
    if slosh.max_wall_elevation_m is not None:
        limit = slosh.max_wall_elevation_m * tightening
        for index, model in enumerate(models):
            angles = [states[3 + first_rows[index] + i, :] for i in range(len(model.modes))]
            add(wall_elevation(wall_elevation_factors(model), angles), -limit, limit)

    # Bounds on the decision variables: start at rest, end at rest on the target, limits.
    state_low = np.full((width, count + 1), -np.inf)
    state_high = np.full((width, count + 1), np.inf)
    state_low[1, :], state_high[1, :] = -machine.max_velocity_m_s, machine.max_velocity_m_s
    state_low[2, :], state_high[2, :] = (
        -machine.max_acceleration_m_s2,
        machine.max_acceleration_m_s2,
    )
    angle_limit = slosh.max_angle_rad * tightening
    for row in first_rows:
        state_low[3 + row, :], state_high[3 + row, :] = -angle_limit, angle_limit
    state_low[:, 0] = state_high[:, 0] = 0.0
    state_low[0, count] = state_high[0, count] = problem.distance_m
    state_low[1:3, count] = state_high[1:3, count] = 0.0

    variables = ca.vertcat(duration, ca.vec(states), controls)
    variable_low = np.concatenate(
        ([1e-3], state_low.ravel(order="F"), np.full(count, -machine.max_jerk_m_s3))
    )
    variable_high = np.concatenate(
        ([np.inf], state_high.ravel(order="F"), np.full(count, machine.max_jerk_m_s3))
    )
    regularisation = 1e-6 * duration * ca.sumsqr(controls / machine.max_jerk_m_s3) / count
    solver = ca.nlpsol(
        "plan",
        "ipopt",
        {"x": variables, "f": duration + regularisation, "g": ca.vertcat(*constraints)},
        {
            "print_time": False,
            "ipopt": {
                "print_level": 0,
                "sb": "yes",
                "max_iter": 3000,
                "tol": 1e-9,
                "acceptable_tol": 1e-7,
                "bound_relax_factor": 0.0,
            },
        },
    )

    # Warm start from the guess, stretched onto the grid, with its simulated slosh.
    t_guess = np.linspace(0.0, guess.duration_s, count + 1)
    initial_states = np.zeros((width, count + 1))
    initial_states[0] = guess.position(t_guess)
    initial_states[1] = guess.velocity(t_guess)
    initial_states[2] = guess.acceleration(t_guess)
    velocity_guess = initial_states[1]
    for row, mode in enumerate(modes):
        theta_guess, rate_guess = linear_mode_response(
            velocity_guess,
            guess.duration_s / count,
            mode.omega_rad_s,
            mode.damping_ratio,
            mode.length_m,
        )
        initial_states[3 + row] = theta_guess
        initial_states[3 + size + row] = rate_guess
    initial = np.concatenate(
        (
            [guess.duration_s],
            initial_states.ravel(order="F"),
            guess.jerk(0.5 * (t_guess[:-1] + t_guess[1:])),
        )
    )
    result = solver(
        x0=initial,
        lbx=variable_low,
        ubx=variable_high,
        lbg=np.concatenate(low),
        ubg=np.concatenate(high),
    )
    status = str(solver.stats().get("return_status", ""))
    if not solver.stats().get("success", False) and status not in ("Solved_To_Acceptable_Level",):
        return None
    solution = np.asarray(result["x"], dtype=float).ravel()
    return float(solution[0]) / count, solution[-count:], status
