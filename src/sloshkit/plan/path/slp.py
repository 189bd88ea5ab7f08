"""Sequential linear programming (SLP) on the speed-scaling warp of a timing, for ``retime``.

The variables are the B-spline coefficients c_k of the warp of a feasible seed timing s(u)
(`sloshkit.plan.path.timing.warped_timing`: time runs c(u) times slower at the seed's time u, so
the speed along the path becomes s'(u) / c(u), the path-speed profile b(s) = s'^2 of TOPP
scaled by 1 / c^2, and c stays C2 so the jerk stays finite). The duration is exactly linear in
them, T = sum_k w_k c_k with w_k = integral of the k-th B-spline over [0, T_seed]. The slosh
outputs of the linear screen (`sloshkit.plan.path.screen.screen_outputs`) are linearised
around the current warp by forward differences: per model of the band, the residual bound
sum_n e_n |(A_n, B_n)| (the mode amplitudes after the move) and the peak wall height in each of
``2 K`` windows of the seed's time. Each step solves the linear program

    min_dc  w . dc   s.t.  g + J dc <= (1 - margin) limit,  |dc_k| <= rho c_k,  c + dc >= floor

with HiGHS (`scipy.optimize.linprog`), and is accepted when the screen of the new warp (and the
Cartesian and angular limits) passes; the trust region rho grows after an accepted step and
halves after a rejected one (Fletcher, *Practical Methods of Optimization*, Wiley (1987)
ch. 14; the SLP/trust-region scheme of Byrd, Gould, Nocedal & Waltz, Math. Program. 100
(2004) 27-48, doi:10.1007/s10107-003-0485-4). Every accepted step is screened and shorter, so
the result is never slower than the seed. Unlike the coordinate pattern search
(`sloshkit.plan.path.search.warp_search`), which can only lower one coefficient at a time, a
step may slow one part of the move to speed up another: on turning paths the residual
constraint binds and the fastest timings trade speed along the path.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.sampling import steps_to_reach
from sloshkit.plan.path.problem import SEARCH_MARGIN, PathProblem
from sloshkit.plan.path.screen import linear_screen, screen_outputs
from sloshkit.plan.path.timing import WARP_FLOOR, Timing, warp_clock, warped_timing

FloatArray = NDArray[np.float64]
#: Warp coefficients of the SLP.
SLP_KNOTS = 16
#: Largest number of linear screens one `slp_search` spends.
SLP_SCREENS = 250
#: Initial and largest trust-region radius (relative change of a coefficient per step).
SLP_RADIUS = (0.15, 0.4)
#: Smallest trust radius before the search stops.
SLP_MIN_RADIUS = 0.004
#: Relative forward-difference step of the coefficients.
SLP_DIFFERENCE = 0.02
#: The LP aims this much below the screen's limits (the linearisation's error).
SLP_BACKOFF = 0.98
#: Screens one call of the reference model counts for in the budget (the nonlinear model of
#: two differentiations costs about eight linear screens).
REFERENCE_COST = 8
#: The share of each limit the reference model's heights must keep to accept a step.
REFERENCE_KEEP = 0.99


def slp_search(
    problem: PathProblem,
    seed: Timing,
    passes: Callable[[PoseTrajectory], bool],
    knots: int = SLP_KNOTS,
    max_screens: int = SLP_SCREENS,
    margin: float = SEARCH_MARGIN,
    reference: Callable[[PoseTrajectory], tuple[float, float]] | None = None,
    transform: Callable[[PoseTrajectory], PoseTrajectory] | None = None,
) -> tuple[Timing, int]:
    """Shorten a feasible timing by trust-region SLP on its warp coefficients (module
    docstring): the linearised duration is minimised under the linearised residual and
    windowed peak heights of the linear screen, each step accepted only when ``passes``.

    Parameters
    ----------
    problem : PathProblem
        Path, sample period, models and the slosh limits the LP aims at (with ``margin``).
    seed : Timing
        A timing whose export passes.
    passes : callable
        PoseTrajectory -> bool, the acceptance test (the screen against the same limits and the
        Cartesian and angular limits).
    knots : int
        Number of warp coefficients (at least 4).
    max_screens : int
        Budget of linear screens (differences and trials; a call of ``reference`` counts
        `REFERENCE_COST`).
    margin : float
        Relative margin the LP keeps from each slosh limit.
    reference : callable, optional
        PoseTrajectory -> (peak, residual) slosh heights of a more exact model (the nonlinear 3-D
        model, `sloshkit.plan.path.result.verify`). Then a step is accepted only when these
        are within the limits (1 % kept) and ``passes`` holds, and the LP's limits are
        corrected by the gap between this model and the screen at the current timing (defect
        correction: the screen gives the sensitivities, the reference the levels).
    transform : callable, optional
        PoseTrajectory -> PoseTrajectory applied to each sampled timing before it is screened,
        linearised, passed to ``passes`` and ``reference`` (e.g. ``tilt``'s tilt
        compensation); it may add equally many rest samples at both ends.

    Returns
    -------
    tuple
        (the improved timing (the seed itself when no step was accepted), screens spent).

    References
    ----------
    Fletcher (1987) ch. 14; Byrd et al. (2004), doi:10.1007/s10107-003-0485-4; the speed
    profile b(s) = s'^2 as the variable of time-optimal path timing: Verscheure et al., IEEE
    Trans. Autom. Control 54(10) (2009) 2318-2327, doi:10.1109/TAC.2009.2028959.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.limits import kinematics
    >>> problem = _example_problem()
    >>> seed = Timing.from_samples("slow", np.linspace(0, 3, 31),
    ...                            0.3 * np.sin(np.linspace(0, np.pi / 2, 31)) ** 2)
    >>> fast, screens = slp_search(problem, seed, lambda p: kinematics(p)["velocity"] < 0.3,
    ...                            knots=6, max_screens=30)
    >>> fast.duration_s < 0.8 * seed.duration_s
    True
    """
    period = problem.sample_period_s
    models = problem.models()
    length = problem.path.length_m
    grid = np.linspace(0.0, seed.duration_s, max(64, math.ceil(4 * seed.duration_s / period)))
    windows = 2 * knots
    weights = np.array([warp_clock(grid, np.eye(knots)[k])[-1] for k in range(knots)])
    keep = (1.0 - margin) * SLP_BACKOFF
    slosh = problem.slosh

    def corrected(poses: PoseTrajectory) -> tuple[float, float] | None:
        # The LP's (residual, height) limits; None when the reference rejects ``poses``.
        if reference is None:
            return keep * slosh.max_residual_height_m, keep * slosh.max_height_m
        peak, residual = reference(poses)
        if peak > REFERENCE_KEEP * slosh.max_height_m:
            return None
        if residual > REFERENCE_KEEP * slosh.max_residual_height_m:
            return None
        screen = linear_screen(models, poses)
        return (
            keep * slosh.max_residual_height_m - (residual - screen.residual_height_m),
            keep * slosh.max_height_m - (peak - screen.peak_height_m),
        )

    modes = [len(model.modes) for model in models]

    def sample(factors: FloatArray, exact: bool = True) -> tuple[PoseTrajectory, FloatArray]:
        # exact: on the controller grid (the export's); otherwise on a grid whose period is
        # adjusted so that it ends at T exactly (smooth in the factors, for the differences).
        clock = warp_clock(grid, factors)
        count = steps_to_reach(clock[-1], period)
        t = np.arange(count + 1, dtype=float) * period
        if not exact:
            t = np.linspace(0.0, clock[-1], count + 1)
        u = np.interp(t, clock, grid)
        s = np.clip(seed.position(u), 0.0, length)
        s[-1] = length
        quaternions = problem.path.orientation(s).as_quat()
        poses = PoseTrajectory(t, problem.path.position(s), quaternions)
        return (poses if transform is None else transform(poses)), u

    def outputs(factors: FloatArray) -> FloatArray:
        # Per model: the modes' scaled amplitude rows e_n (A_n, B_n), then the window peaks.
        poses, u = sample(factors, False)
        index = np.minimum((u / seed.duration_s * windows).astype(int), windows - 1)
        values = []
        pad = (poses.time_s.size - u.size) // 2  # rest samples a transform added at each end
        index = np.concatenate((np.zeros(pad, int), index, np.full(pad, windows - 1)))
        for wall, _, _, amplitudes in screen_outputs(models, poses):
            peaks = np.zeros(windows)
            np.maximum.at(peaks, index, wall)
            values.append(np.concatenate((amplitudes.ravel(), peaks)))
        return np.concatenate(values)

    factors = np.ones(knots)
    current = outputs(factors)
    limits = corrected(sample(factors)[0])
    screens = 2 + (0 if reference is None else REFERENCE_COST)
    if limits is None:
        return seed, screens
    radius = SLP_RADIUS[0]
    jacobian: FloatArray | None = None
    while screens < max_screens and radius > SLP_MIN_RADIUS:
        if jacobian is None:
            if screens + knots >= max_screens:
                break
            jacobian = np.empty((current.size, knots))
            for k in range(knots):
                trial = factors.copy()
                trial[k] *= 1.0 - SLP_DIFFERENCE
                jacobian[:, k] = (outputs(trial) - current) / (trial[k] - factors[k])
            screens += knots
        step = _lp_step(weights, jacobian, current, factors, radius, modes, windows, limits)
        if step is None or weights @ step > -1e-4 * (weights @ factors):
            radius *= 0.5
            continue
        trial = factors + step
        poses = sample(trial)[0]
        screens += 1
        found = None
        if passes(poses):
            found = corrected(poses)
            screens += 0 if reference is None else REFERENCE_COST
        if found is not None:
            factors, current, jacobian, limits = trial, outputs(trial), None, found
            screens += 1
            radius = min(1.5 * radius, SLP_RADIUS[1])
        else:
            radius *= 0.5
    if np.all(factors == 1.0):
        return seed, screens
    return warped_timing(seed, factors), screens


def _directions(amplitude: FloatArray) -> FloatArray:
    """Rows d with |x| <= max_d d . x for every x in R^4, exact along ``amplitude``: with u its
    direction and q_1..q_3 an orthonormal basis of the rest, |x| <= |u . x| + sum_j |q_j . x|
    (the triangle inequality, then |y|_2 <= |y|_1), written as the 16 sign combinations. A
    local upper bound of the norm, so the LP's residual is never optimistic near the current
    amplitude (an outer polytope of the ball would be, by up to its covering ratio)."""
    norm = float(np.linalg.norm(amplitude))
    start = amplitude / norm if norm > 0.0 else np.eye(4)[0]
    basis = np.linalg.qr(np.column_stack((start, np.eye(4))))[0][:, :4].T
    basis[0] = start
    signs = np.array(list(itertools.product((-1.0, 1.0), repeat=4)))
    return np.asarray(signs @ basis, dtype=float)


def _lp_step(
    weights: FloatArray,
    jacobian: FloatArray,
    current: FloatArray,
    factors: FloatArray,
    radius: float,
    modes: list[int],
    windows: int,
    limits: tuple[float, float],
) -> FloatArray | None:
    """The LP step dc of `slp_search` (None when the LP has no solution). Variables: dc and one
    bound r_n >= |a_n + J_n dc| per mode and model (the amplitude row a_n in R^4, the norm
    replaced by the upper bound of `_directions`); per model
    sum_n r_n <= the residual limit (or the current residual when above it); the window peaks
    p + J_p dc <= the height limit (or their current value)."""
    from scipy.optimize import linprog

    knots = factors.size
    bounds_count = sum(modes)
    rows: list[FloatArray] = []
    right: list[float] = []
    offset = 0
    variable = knots
    for count in modes:
        residual = 0.0
        for _ in range(count):
            amplitude = current[offset : offset + 4]
            gradient = jacobian[offset : offset + 4]
            norm = float(np.linalg.norm(amplitude))
            residual += norm
            for direction in _directions(amplitude):
                row = np.zeros(knots + bounds_count)
                row[:knots] = direction @ gradient
                row[variable] = -1.0
                rows.append(row)
                right.append(-float(direction @ amplitude))
            offset += 4
            variable += 1
        row = np.zeros(knots + bounds_count)
        row[variable - count : variable] = 1.0
        rows.append(row)
        right.append(max(limits[0], residual))
        for window in range(windows):
            row = np.zeros(knots + bounds_count)
            row[:knots] = jacobian[offset + window]
            rows.append(row)
            right.append(max(limits[1] - float(current[offset + window]), 0.0))
        offset += windows
    lower = np.maximum(-radius * factors, WARP_FLOOR - factors)
    bounds = [*zip(lower, radius * factors, strict=True), *[(0.0, None)] * bounds_count]
    found = linprog(
        np.concatenate((weights, np.zeros(bounds_count))),
        A_ub=np.array(rows),
        b_ub=np.array(right),
        bounds=bounds,
        method="highs",
    )
    if found.status != 0:
        return None
    return np.asarray(found.x[:knots], dtype=float)


__all__ = ["SLP_KNOTS", "SLP_SCREENS", "slp_search"]
