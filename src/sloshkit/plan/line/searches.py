"""Searches over motion families: the seed paper's laws at their shortest feasible duration
(scan on the fast path, then bisection) and shaped S-curves (ruckig S-curve convolved with an
input shaper, with its acceleration and jerk limits searched)."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError, warn_validity
from sloshkit.model.modal import SloshModel
from sloshkit.motion.laws import make_law, s_curve
from sloshkit.motion.profile import Motion
from sloshkit.motion.sampling import steps_for, steps_to_reach
from sloshkit.motion.scaling import scaled_velocity_samples, unit_duration_shape
from sloshkit.motion.shaping import Shaper, make_shaper, shape_motion, zv
from sloshkit.plan.line.problem import (
    SEARCH_MARGIN,
    SHAPERS,
    Candidate,
    MachineLimits,
    PlanProblem,
    PlanStatus,
)
from sloshkit.plan.line.verification import checked_candidate, only_slosh_violations
from sloshkit.plan.line.work_estimate import slosh_floor_s, work_limit
from sloshkit.sim.batch import batch_metrics

FloatArray = NDArray[np.float64]


def _screen(
    velocities: FloatArray, durations: FloatArray, problem: PlanProblem, dt: float
) -> NDArray[np.bool_]:
    """Slosh feasibility of many (samples x cases) velocity histories, with the search margin.

    The angle and residual limits concern the first mode only: without a wall-elevation limit
    the other modes are not simulated. The recursion runs in numpy (`batch_metrics` with
    ``use_numba=False``): for the few hundred cases of a search, loading the compiled kernel
    costs more than it saves.
    """
    keep = np.ones(durations.size, dtype=bool)
    slosh = problem.slosh
    wall = slosh.max_wall_elevation_m
    for model in problem.models():
        screened = model if wall is not None else replace(model, modes=model.modes[:1])
        metrics = batch_metrics(screened, velocities, durations, dt, use_numba=False)
        keep &= metrics.peak_angle_rad <= slosh.max_angle_rad * (1 - SEARCH_MARGIN)
        keep &= metrics.residual_angle_rad <= slosh.max_residual_rad * (1 - SEARCH_MARGIN)
        if wall is not None:
            keep &= metrics.peak_wall_elevation_m <= wall * (1 - SEARCH_MARGIN)
    return keep


def _velocity_matrix(
    motions: Sequence[Motion], dt: float, shaper: Shaper | None = None
) -> tuple[FloatArray, FloatArray]:
    """Velocity samples (samples x cases) of each motion, optionally shaped, and durations."""
    extra = 0.0 if shaper is None else shaper.duration_s
    durations = np.array([m.duration_s + extra for m in motions])
    steps = steps_to_reach(float(durations.max()), dt) + 2
    t = np.arange(steps, dtype=float) * dt
    matrix = np.zeros((steps, len(motions)))
    delays = np.zeros(1) if shaper is None else shaper.times_s
    amplitudes = np.ones(1) if shaper is None else shaper.amplitudes
    for column, motion in enumerate(motions):
        local = t[:, None] - delays[None, :]
        inside = (local >= 0.0) & (local <= motion.duration_s)
        values = np.zeros_like(local)
        values[inside] = motion.derivative_pp(1)(local[inside])
        matrix[:, column] = values @ amplitudes
    return matrix, durations


def _screen_motions(
    motions: Sequence[Motion], problem: PlanProblem, shaper: Shaper
) -> tuple[NDArray[np.bool_], FloatArray]:
    """`_screen` of shaped motions and their durations, in blocks of similar duration (each
    block simulated only as long as its longest move: the same numbers as one block)."""
    dt = problem.sample_period_s
    own = np.array([motion.duration_s for motion in motions])
    order = np.argsort(own, kind="stable")
    feasible = np.zeros(own.size, dtype=bool)
    durations = np.zeros(own.size)
    for start in range(0, own.size, _SCREEN_BLOCK):
        block = order[start : start + _SCREEN_BLOCK]
        velocity, durations[block] = _velocity_matrix([motions[i] for i in block], dt, shaper)
        feasible[block] = _screen(velocity, durations[block], problem, dt)
    return feasible, durations


#: Cases screened together (a block is simulated as long as its longest move).
_SCREEN_BLOCK = 50


def _machine_floor(shape: Motion, limits: MachineLimits) -> float:
    """Shortest duration at which a time-scaled law meets the velocity, acceleration and jerk
    limits (its shape given for T = 1 s)."""
    floors = [
        shape.peak_velocity_m_s / limits.max_velocity_m_s,
        math.sqrt(shape.peak_acceleration_m_s2 / limits.max_acceleration_m_s2),
    ]
    if math.isfinite(shape.peak_jerk_m_s3):
        floors.append((shape.peak_jerk_m_s3 / limits.max_jerk_m_s3) ** (1.0 / 3.0))
    return max(floors)


def plan_paper_law(law: str, problem: PlanProblem, grid: int = 400) -> Candidate:
    """The shortest duration at which a paper law meets the limits (scan, then bisection).

    Laws with acceleration jumps have unbounded jerk: they are reported with the duration that
    meets the other limits, and flagged infeasible under a jerk limit.

    Parameters
    ----------
    law : str
        ``trapezoidal``, ``cubic``, ``quintic`` or ``septic``.
    problem : PlanProblem
        Distance, limits, model and sample period.
    grid : int
        Durations screened per scan.

    Returns
    -------
    Candidate
        The law at its shortest verified duration (or why none was found).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(0.1, sk.MachineLimits(1.0, 5.0, 200.0),
    ...                          sk.SloshLimits(0.1, 0.01), model)
    >>> plan_paper_law("quintic", problem, grid=50).feasible
    True
    """

    started = time.perf_counter()
    shape = unit_duration_shape(make_law(law, problem.distance_m, duration_s=1.0))
    # No move is shorter than the slosh bound (`sloshkit.plan.line.work_estimate.slosh_floor_s`;
    # 1 % below it, as the angle is checked at the samples only): under tight slosh limits the scan
    # starts there instead of widening from the machine's floor.
    floor = max(_machine_floor(shape, problem.machine), 0.99 * slosh_floor_s(problem))
    dt = problem.sample_period_s  # screen on the grid the verification uses
    velocity_pp = shape.derivative_pp(1)
    upper = floor
    budget = work_limit() / (len(problem.models()) * len(problem.model.modes) * grid)
    stopped = False
    for _ in range(6):  # widen the scan until something is feasible (within the work limit)
        if upper * 4.0 / dt > budget and upper > floor:
            stopped = True
            break
        upper *= 4.0
        scan = _Scan(velocity_pp, np.linspace(floor, upper, grid), problem)
        first = scan.first_feasible(0)
        if first is not None:
            break
    if stopped or first is None:
        return Candidate(
            law,
            PlanStatus.INFEASIBLE,
            None,
            None,
            time.perf_counter() - started,
            f"no duration up to {upper:.3g} s meets the slosh limits"
            + (" (longer scans exceed the planner work limit)" if stopped else ""),
        )
    durations = scan.durations
    if first == 0:
        best = float(durations[0])
    else:
        low, high = float(durations[first - 1]), float(durations[first])
        for _ in range(30):
            middle = 0.5 * (low + high)
            single = scaled_velocity_samples(
                velocity_pp, np.array([middle]), dt, steps_for(middle, dt)
            )
            if _screen(single, np.array([middle]), problem, dt)[0]:
                high = middle
            else:
                low = middle
        best = high
    attempt: int | None = first
    while attempt is not None:
        duration = best if attempt == first else float(durations[attempt])
        candidate = checked_candidate(
            law, make_law(law, problem.distance_m, duration_s=duration), problem, started
        )
        if candidate.feasible or not only_slosh_violations(candidate):
            return candidate
        attempt = scan.first_feasible(attempt + 1)
    return candidate


class _Scan:
    """The slosh screen of a time-scaled law over a grid of increasing durations, evaluated a
    block of durations at a time and only as far as asked: the search needs the first feasible
    duration (and, rarely, the next ones), and each block is simulated only as long as its own
    longest move (the same numbers as screening the whole grid at once)."""

    def __init__(self, velocity_pp: object, durations: FloatArray, problem: PlanProblem):
        self.velocity_pp, self.durations, self.problem = velocity_pp, durations, problem
        self.feasible = np.zeros(durations.size, dtype=bool)
        self.screened = 0  # durations[:screened] are screened

    def first_feasible(self, start: int) -> int | None:
        """The first feasible index from ``start`` on (None: none on the grid)."""
        dt = self.problem.sample_period_s
        while True:
            found = np.flatnonzero(self.feasible[start : self.screened])
            if found.size:
                return start + int(found[0])
            if self.screened >= self.durations.size:
                return None
            block = self.durations[self.screened : self.screened + _SCREEN_BLOCK]
            velocity = scaled_velocity_samples(
                self.velocity_pp, block, dt, steps_for(float(block[-1]), dt)
            )
            self.feasible[self.screened : self.screened + block.size] = _screen(
                velocity, block, self.problem, dt
            )
            self.screened += block.size


def shaper_for(name: str, model: SloshModel) -> Shaper:
    """A shaper on the first mode (``zv``, ``zvd``, ``ei``) or ``zv2``: ZV on modes 1 and 2.

    Parameters
    ----------
    name : str
        ``zv``, ``zvd``, ``ei`` or ``zv2``.
    model : SloshModel
        The model whose modes it cancels.

    Returns
    -------
    Shaper

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> shaper_for("zv2", model).amplitudes.size
    4
    """
    first = model.modes[0]
    if name == "zv2":
        if len(model.modes) < 2:
            return zv(first.omega_rad_s, first.damping_ratio)
        second = model.modes[1]
        shaper = zv(first.omega_rad_s, first.damping_ratio).convolve(
            zv(second.omega_rad_s, second.damping_ratio)
        )
        return Shaper("zv2", shaper.amplitudes, shaper.times_s)
    return make_shaper(name, first.omega_rad_s, first.damping_ratio)


def plan_shaped(problem: PlanProblem, shapers: Sequence[str] = SHAPERS) -> Candidate:
    """Shaped S-curves: for each shaper, a grid over the S-curve's acceleration and jerk limits
    screened at once on the fast path, then a bisection on the acceleration; the fastest
    verified result.

    Parameters
    ----------
    problem : PlanProblem
        Distance, limits, model and sample period.
    shapers : sequence of str
        Shapers to try (`sloshkit.plan.line.problem.SHAPERS`).

    Returns
    -------
    Candidate
        The fastest verified shaped move (``detail`` lists every shaper tried).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(0.1, sk.MachineLimits(1.0, 5.0, 200.0),
    ...                          sk.SloshLimits(0.1, 0.01), model)
    >>> plan_shaped(problem, ("zv",)).feasible
    True
    """
    started = time.perf_counter()
    machine = problem.machine
    dt = problem.sample_period_s  # screen on the grid the verification uses
    best: Candidate | None = None
    tried: list[str] = []
    for name in shapers:
        try:
            shaper = shaper_for(name, problem.model)
        except InputError as error:  # e.g. no EI shaper exists at a large damping ratio
            tried.append(f"{name}: skipped ({error.valid})")
            warn_validity(
                f"no {name.upper()} shaper exists for damping ratio "
                f"{problem.model.modes[0].damping_ratio:.3g}; planned with the other shapers"
            )
            continue
        accelerations = machine.max_acceleration_m_s2 * np.geomspace(1e-3, 1.0, 40)
        jerks = machine.max_jerk_m_s3 * np.array([1.0, 0.2, 0.04])
        bases: list[Motion] = []
        settings: list[tuple[float, float]] = []
        for jerk in jerks:
            for acceleration in accelerations:
                bases.append(
                    s_curve(problem.distance_m, machine.max_velocity_m_s, acceleration, jerk)
                )
                settings.append((acceleration, jerk))
        feasible, durations = _screen_motions(bases, problem, shaper)
        if not feasible.any():
            tried.append(f"{name}: nothing feasible")
            continue
        index = int(np.argmin(np.where(feasible, durations, np.inf)))
        acceleration, jerk = settings[index]
        # Bisection on the acceleration between the best feasible and the next grid value.
        ratio = float(accelerations[1] / accelerations[0])
        low, high = acceleration, min(machine.max_acceleration_m_s2, acceleration * ratio)
        for _ in range(14):
            if high - low <= 1e-4 * low:
                break
            middle = 0.5 * (low + high)
            base = s_curve(problem.distance_m, machine.max_velocity_m_s, middle, jerk)
            single, duration = _velocity_matrix([base], dt, shaper)
            if _screen(single, duration, problem, dt)[0] and duration[0] <= durations[index] + 1e-9:
                low = middle
            else:
                high = middle
        base = s_curve(problem.distance_m, machine.max_velocity_m_s, low, jerk)
        candidate = checked_candidate(
            f"shaped-{name}",
            shape_motion(base, shaper),
            problem,
            started,
            shaper=name,
            base_acceleration_m_s2=low,
            base_jerk_m_s3=jerk,
        )
        tried.append(f"{name}: {candidate.duration_s:.4f} s")
        if best is None or (candidate.feasible, -candidate.duration_s) > (
            best.feasible,
            -best.duration_s,
        ):
            best = candidate
    if best is None:
        return Candidate(
            "shaped",
            PlanStatus.INFEASIBLE,
            None,
            None,
            time.perf_counter() - started,
            "no shaped S-curve meets the limits (" + "; ".join(tried) + ")",
        )
    return replace(
        best,
        compute_time_s=time.perf_counter() - started,
        detail={**best.detail, "shapers_tried": tried},
    )
