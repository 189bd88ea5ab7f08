"""Minimum-time timing of a path with the slosh dynamics, by direct multiple shooting.

Casadi/IPOPT (Betts, *Practical Methods for Optimal Control*, 2nd ed., SIAM (2010) ch. 4):
states s, s', s'' and, for every mode and every frequency of the robustness band, the 2-D
deflection of the spherical pendulum and its rate (the linear model of
`sloshkit.plan.path.screen`); control: the path jerk s''', piecewise constant; path-dependent speed,
acceleration (tangential and centripetal), jerk and angular-speed limits and the slosh-height
limit at the nodes, the residual amplitude at the end. The path enters through tables of its
derivatives on a grid of s (linear interpolants, evaluated at the nodes; the RK4 stages use the
path quantities interpolated linearly in time between nodes).

The planner warm-starts it from the fastest member of the parametric family of
`sloshkit.plan.path.retime` that passes the slosh screen. Measured on the TRD path of the measured
series: about 100-190 IPOPT iterations and 5-15 s on this (shared) machine with 60 intervals;
100-160 intervals did not converge in 200 s (the curvature peak of 29/m of that path makes the
node constraints nearly non-smooth), so 60 is the default.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sloshkit.motion.profile import Motion, piecewise_constant_jerk
from sloshkit.plan.path.geometry import Path
from sloshkit.plan.path.limits import machine_violations
from sloshkit.plan.path.problem import GRAVITY, SEARCH_MARGIN, PathProblem, sample_path
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.timing import FINE_STEP_S, Timing

FloatArray = NDArray[np.float64]
#: Fraction of the Cartesian limits the transcription uses (they hold at its nodes only).
MARGIN = 0.98


def path_tables(path: Path, count: int) -> tuple[FloatArray, FloatArray]:
    """Grid of s and the table of path quantities the transcription interpolates.

    Rows 0-1 R_N^T g, 2-3 R_N^T p', 4-5 R_N^T (R e_z)', 6-7 R_N^T p'', 8-9 R_N^T (R e_z)''
    (lateral components in the spin-free container frame R_N), 10-12 p', 13-15 p'', 16-18
    p''', 19-21 omega_s (world).

    Parameters
    ----------
    path : Path
        The geometry.
    count : int
        Grid points.

    Returns
    -------
    tuple of ndarray
        (s grid [m], table of shape (22, count)).

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> grid, table = path_tables(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]), 5)
    >>> table.shape, table[10:13, 2].round(6).tolist()  # p' along x
    ((22, 5), [1.0, 0.0, 0.0])
    """
    grid = np.linspace(0.0, path.length_m, count)
    rotation = path.orientation(grid)
    axis = rotation.apply([0.0, 0.0, 1.0])
    omega = path.angular_rate(grid, 1)
    omega_rate = path.angular_rate(grid, 2)
    axis_first = np.cross(omega, axis)
    axis_second = np.cross(omega_rate, axis) + np.cross(omega, axis_first)
    body_spin = rotation.inv().apply(omega)[:, 2]
    spin = np.concatenate(
        ([0.0], np.cumsum(0.5 * (body_spin[1:] + body_spin[:-1]) * np.diff(grid)))
    )
    frame = rotation * Rotation.from_rotvec(-spin[:, None] * np.array([0.0, 0.0, 1.0]))

    def lateral(vectors: FloatArray) -> FloatArray:
        return np.asarray(frame.inv().apply(vectors)[:, :2].T)

    first, second, third = (path.position(grid, k) for k in (1, 2, 3))
    table = np.vstack(
        (
            lateral(np.tile(GRAVITY, (grid.size, 1))),
            lateral(first),
            lateral(axis_first),
            lateral(second),
            lateral(axis_second),
            first.T,
            second.T,
            third.T,
            omega.T,
        )
    )
    return grid, table


def optimal_timing(
    problem: PathProblem,
    warm: Any,
    intervals: int = 60,
    tightening: float = 1.0,
    residual_tightening: float | None = None,
    slosh_dynamics: bool = True,
) -> tuple[Motion, str] | None:
    """Solve the minimum-time transcription from the warm start.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model (every mode of every model of the band is a state).
    warm : Timing or Motion
        Warm start with ``duration_s``, ``position``, ``velocity``, ``acceleration``, ``jerk``.
    intervals : int
        Shooting intervals (piecewise-constant path jerk).
    tightening : float
        Factor (<= 1) on the slosh limits the solver sees.
    residual_tightening : float, optional
        Separate factor on the residual limit (default: ``tightening``).
    slosh_dynamics : bool
        Without it only the Cartesian and angular limits remain (the jerk-limited time-optimal
        timing of the path).

    Returns
    -------
    tuple or None
        (timing as a `Motion` of s, IPOPT status), None when IPOPT fails.

    References
    ----------
    Betts (2010) ch. 4.

    Examples
    --------
    >>> MARGIN < 1.0
    True
    """
    import casadi as ca

    path, machine, slosh = problem.path, problem.machine, problem.slosh
    count = intervals
    grid, table = path_tables(path, int(np.clip(path.length_m / 2e-3, 300, 2000)))
    geometry = ca.interpolant(
        "geometry", "linear", [grid], table.ravel(order="F"), {"lookup_mode": ["exact"]}
    )
    models = problem.models() if slosh_dynamics else []
    modes = [(number, mode) for number, model in enumerate(models) for mode in model.modes]
    size = len(modes)
    width = 3 + 4 * size
    x = ca.SX.sym("x", width)
    jerk = ca.SX.sym("u")
    geo = ca.SX.sym("g", 10)  # forcing rows of the table at the current s
    s_rate, s_acc = x[1], x[2]
    rows = [x[1], x[2], jerk]
    for index, (_, mode) in enumerate(modes):
        phi = x[3 + 4 * index : 5 + 4 * index]
        rate = x[5 + 4 * index : 7 + 4 * index]
        force = (
            geo[0:2]
            - (geo[2:4] + mode.bob_height_m * geo[4:6]) * s_acc
            - (geo[6:8] + mode.bob_height_m * geo[8:10]) * s_rate**2
        )
        accel = (
            force / mode.length_m
            - 2 * mode.damping_ratio * mode.omega_rad_s * rate
            - mode.omega_rad_s**2 * phi
        )
        rows.extend([rate[0], rate[1], accel[0], accel[1]])
    derivative = ca.Function("f", [x, jerk, geo], [ca.vertcat(*rows)])
    # RK4, two sub-steps per interval; the path quantities vary linearly in time between
    # their values at the interval's two nodes (only the nodes call the interpolant).
    step = ca.SX.sym("h")
    geo_start, geo_end = ca.SX.sym("ga", 10), ca.SX.sym("gb", 10)

    def geo_at(fraction: float) -> Any:
        return geo_start + fraction * (geo_end - geo_start)

    state = x
    sub = step / 2
    for half in range(2):
        k1 = derivative(state, jerk, geo_at(0.5 * half))
        k2 = derivative(state + sub / 2 * k1, jerk, geo_at(0.5 * half + 0.25))
        k3 = derivative(state + sub / 2 * k2, jerk, geo_at(0.5 * half + 0.25))
        k4 = derivative(state + sub * k3, jerk, geo_at(0.5 * half + 0.5))
        state = state + sub / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    advance = ca.Function("F", [x, jerk, step, geo_start, geo_end], [state])

    duration = ca.MX.sym("T")
    states = ca.MX.sym("X", width, count + 1)
    controls = ca.MX.sym("U", count)
    node_geo = geometry.map(count + 1)(states[0, :])
    shooting = advance.map(count)(
        states[:, :-1],
        controls.T,
        ca.repmat(duration / count, 1, count),
        node_geo[0:10, :-1],
        node_geo[0:10, 1:],
    )
    constraints: list[Any] = [ca.vec(states[:, 1:] - shooting)]
    low: list[FloatArray] = [np.zeros(width * count)]
    high: list[FloatArray] = [np.zeros(width * count)]

    def add(expression: Any, upper: float) -> None:
        flat = ca.vec(expression)
        constraints.append(flat)
        low.append(np.full(flat.shape[0], -np.inf))
        high.append(np.full(flat.shape[0], upper))

    rate_n, acc_n = states[1, :], states[2, :]
    first, second, third, omega = (node_geo[r : r + 3, :] for r in (10, 13, 16, 19))

    def rows3(row: Any) -> Any:
        return ca.repmat(row, 3, 1)

    add(ca.sum1(first**2) * rate_n**2, (MARGIN * machine.max_velocity_m_s) ** 2)
    add(
        ca.sum1((first * rows3(acc_n) + second * rows3(rate_n**2)) ** 2),
        (MARGIN * machine.max_acceleration_m_s2) ** 2,
    )
    for offset in (0, 1):  # the piecewise-constant jerk at both ends of its interval
        nodes = slice(offset, count + offset)
        cartesian_jerk = (
            first[:, nodes] * rows3(controls.T)
            + 3 * second[:, nodes] * rows3(rate_n[nodes] * acc_n[nodes])
            + third[:, nodes] * rows3(rate_n[nodes] ** 3)
        )
        add(ca.sum1(cartesian_jerk**2), (MARGIN * machine.max_jerk_m_s3) ** 2)
    if machine.max_angular_velocity_rad_s is not None:
        add(ca.sum1(omega**2) * rate_n**2, (MARGIN * machine.max_angular_velocity_rad_s) ** 2)
    limit = slosh.max_height_m * tightening
    start_geo = np.asarray(table[:, 0])
    end_geo = np.asarray(table[:, -1])
    residual_terms: dict[int, Any] = {}
    for index, (model_index, mode) in enumerate(modes):
        deflection = states[3 + 4 * index : 5 + 4 * index, :]
        residual_terms.setdefault(model_index, 0)
        rest_end = end_geo[0:2] / (mode.length_m * mode.omega_rad_s**2)
        cosine = deflection[:, count] - ca.DM(rest_end)
        damped = mode.omega_rad_s * math.sqrt(1 - mode.damping_ratio**2)
        sine = (
            states[5 + 4 * index : 7 + 4 * index, count]
            + mode.damping_ratio * mode.omega_rad_s * cosine
        ) / damped
        residual_terms[model_index] += mode.wall_elevation_factor_m * ca.sqrt(
            ca.sumsqr(cosine) + ca.sumsqr(sine) + 1e-14
        )
        if mode.n == 1 and slosh.max_surface_angle_rad is not None:
            add(ca.sum1(deflection**2), (slosh.max_surface_angle_rad * tightening) ** 2)
    for model_index, _model in enumerate(models):
        wall = 0
        for index, (owner, mode) in enumerate(modes):
            if owner == model_index:
                wall = (
                    wall + mode.wall_elevation_factor_m * states[3 + 4 * index : 5 + 4 * index, :]
                )
        add(ca.sum1(wall**2), limit**2)
        add(
            residual_terms[model_index],
            slosh.max_residual_height_m
            * (tightening if residual_tightening is None else residual_tightening),
        )

    state_low = np.full((width, count + 1), -np.inf)
    state_high = np.full((width, count + 1), np.inf)
    state_low[0], state_high[0] = 0.0, path.length_m
    state_low[1] = 0.0
    acceleration_cap = machine.max_acceleration_m_s2 / max(
        1e-9, float(np.min(np.linalg.norm(table[10:13], axis=0)))
    )
    state_low[2], state_high[2] = -acceleration_cap, acceleration_cap
    initial = np.zeros(width)
    for index, (_, mode) in enumerate(modes):
        initial[3 + 4 * index : 5 + 4 * index] = start_geo[0:2] / (
            mode.length_m * mode.omega_rad_s**2
        )
    state_low[:, 0] = state_high[:, 0] = initial
    state_low[0:3, count] = state_high[0:3, count] = (path.length_m, 0.0, 0.0)
    jerk_cap = machine.max_jerk_m_s3 * 1e3
    variables = ca.vertcat(duration, ca.vec(states), controls)
    bounds_low = np.concatenate(([1e-2], state_low.ravel(order="F"), np.full(count, -jerk_cap)))
    bounds_high = np.concatenate(([np.inf], state_high.ravel(order="F"), np.full(count, jerk_cap)))
    scale = machine.max_jerk_m_s3
    regularisation = 1e-6 * duration * ca.sumsqr(controls / scale) / count
    solver = ca.nlpsol(
        "retime",
        "ipopt",
        {"x": variables, "f": duration + regularisation, "g": ca.vertcat(*constraints)},
        {
            "print_time": False,
            "expand": True,
            "ipopt": {
                "print_level": 0,
                "sb": "yes",
                "max_iter": 1500,
                "tol": 1e-8,
                "acceptable_tol": 1e-6,
                "max_cpu_time": 45.0,
                "mu_strategy": "adaptive",
            },
        },
    )
    # Warm start: the guess on the grid, its slosh states integrated with the same map.
    t_guess = np.linspace(0.0, warm.duration_s, count + 1)
    mid = 0.5 * (t_guess[1:] + t_guess[:-1])
    guess_jerk = warm.jerk(mid)
    guess = np.zeros((width, count + 1))
    guess[:, 0] = initial
    h = warm.duration_s / count
    guess[0] = np.clip(warm.position(t_guess), 0.0, path.length_m)
    guess[1] = np.maximum(warm.velocity(t_guess), 0.0)
    guess[2] = warm.acceleration(t_guess)
    guess_geo = np.asarray(geometry.map(count + 1)(guess[0]))[0:10]
    for k in range(count):
        guess[3:, k + 1] = np.asarray(
            advance(guess[:, k], guess_jerk[k], h, guess_geo[:, k], guess_geo[:, k + 1])
        ).ravel()[3:]
    result = solver(
        x0=np.concatenate(([warm.duration_s], guess.ravel(order="F"), guess_jerk)),
        lbx=bounds_low,
        ubx=bounds_high,
        lbg=np.concatenate(low),
        ubg=np.concatenate(high),
    )
    stats = solver.stats()
    status = str(stats.get("return_status", ""))
    if not stats.get("success", False) and status != "Solved_To_Acceptable_Level":
        return None
    solution = np.asarray(result["x"], dtype=float).ravel()
    interval = float(solution[0]) / count
    timing = piecewise_constant_jerk("retime", [interval] * count, list(solution[-count:]))
    return Motion("retime", timing.position_pp), status


#: Re-solves after the first when the sampled export breaks a slosh limit in the screen.
TIGHTENING_STEPS = 2


def transcribed_timing(problem: PathProblem, warm: Any) -> tuple[Timing, str] | None:
    """`optimal_timing` checked on the export grid, with a bounded verify-and-tighten loop.

    The transcription's slosh limits hold at its shooting nodes of an RK4 model with the path
    quantities interpolated between nodes; the sampled export can break them between and at
    the nodes (by 4 % peak and 20 % residual on the measured TRD path). So the export of each
    solution is screened (`sloshkit.plan.path.screen.linear_screen` on the controller grid, with
    the search margin): when a slosh limit is broken, that limit is tightened by the ratio of
    the screened value to the allowed one and the problem is solved again, warm-started from
    the previous solution, at most `TIGHTENING_STEPS` times.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    warm : Timing or Motion
        First warm start.

    Returns
    -------
    tuple or None
        (timing, IPOPT status) of the first solution whose export passes the screen and the
        Cartesian limits, None when IPOPT fails or the loop ends without one.

    References
    ----------
    Betts (2010) ch. 4 (direct transcription); the export check is this library's.

    Examples
    --------
    >>> TIGHTENING_STEPS
    2
    """
    path, slosh = problem.path, problem.slosh
    models = problem.models()
    keep = 1.0 - SEARCH_MARGIN
    peak_factor = residual_factor = keep
    for _ in range(1 + TIGHTENING_STEPS):
        solved = optimal_timing(
            problem, warm, tightening=peak_factor, residual_tightening=residual_factor
        )
        if solved is None:
            return None
        motion, status = solved
        grid = np.linspace(
            0.0, motion.duration_s, max(8, math.ceil(motion.duration_s / FINE_STEP_S)) + 1
        )
        timing = Timing.from_samples(
            "retime", grid, np.clip(motion.position(grid), 0.0, path.length_m)
        )
        poses = sample_path(path, timing, problem.sample_period_s)
        if machine_violations(problem, poses, False):
            return None
        screen = linear_screen(models, poses)
        if screen_ok(problem, screen):
            return timing, status
        peak_factor *= min(1.0, keep * slosh.max_height_m / screen.peak_height_m)
        residual_factor *= min(1.0, keep * slosh.max_residual_height_m / screen.residual_height_m)
        warm = timing
    return None
