"""The minimum-time timing of a 3-D path on the export grid, by sequential second-order-cone
programming (`sloshkit.plan.path.program`, the model; `sloshkit.plan.path.cone`, one program).

The minimum time comes from programs whose sample period is a variable too (`_dilated_search`):
first on a grid four times coarser than the export's (programs a quarter the size; a bracketed
search over N finds its start, `_minimum_time`), then on the export's period from that timing
spread by a cubic B-spline, then on the export grid itself (`free_time`).

The programs model what the verification simulates without its smoothing filter; the
verification, which also simulates the export through that filter, can still exceed a slosh
limit by a percent or two. The program's limit is then moved by regula falsi (`_next_limit`)
and the search restarts from the last samples on the export's period (`plan_optimal`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.plan.path.cone import PENALTY, PROGRAM_MARGIN, cone_step
from sloshkit.plan.path.joints import joint_map
from sloshkit.plan.path.program import PathProgram, ProgramIterate, ProgramLimits
from sloshkit.plan.path.samples import PathSamples, export_poses, rescaled, smoothed

#: Relative width of the bracket on N at which the search stops (the smallest feasible N is kept).
SEARCH_TOLERANCE = 2e-3
#: Durations solved per search, at most.
MAX_SEARCH = 14
#: Searches of `plan_optimal`, each with the program's slosh limits moved towards the values
#: at which the verification meets its limits (`_next_limit`), at most.
TIGHTENINGS = 5
#: A verified plan whose peak or residual is within this fraction of its limit ends them.
LIMIT_TOLERANCE = 0.02
#: The tilt's rate and acceleration limits where the angular ones are lifted [rad/s, rad/s^2]
#: (as `benchmarks/ocp_reference.py`'s tilted problem).
TILT_RATE_RAD_S = math.pi
TILT_ACCELERATION_RAD_S2 = math.radians(1000.0)
#: Where the program's slosh limits aim, as a fraction of the limits: the first round starts
#: there and `_next_limit` moves them towards the verification meeting it.
LIMIT_AIM = 1.0 - 0.5 * LIMIT_TOLERANCE


def _margin_at(
    program: PathProgram,
    start: PathSamples,
    trust: float = 0.1,
    iterations: int = 8,
    tolerance: float = 2e-3,
    enough: float = 0.0,
) -> tuple[ProgramIterate, float]:
    """The samples of N steps (N from ``start``) whose largest ratio to a limit is least:
    cone programs (`cone_step`) from ``start``, a step kept when its exact evaluation is
    better (the trust region then grows by half, else it halves). The residual's own trust
    region halves when its prediction missed the exact residual by more than a quarter of the
    predicted change (and 0.02), else grows by half. Stops when a step gains less than a
    quarter of ``tolerance`` and its prediction was right to ``tolerance``, or as soon as the
    largest ratio is at most ``enough``.
    Returns the best iterate and its largest ratio."""
    current = program.iterate(start)
    residual_trust = 1.0
    for _ in range(iterations):
        if current.excess <= enough:
            break
        step = cone_step(program, current.samples, current.evaluation, trust, residual_trust)
        if step is None:
            trust *= 0.5
            continue
        trial = program.iterate(step.samples)
        before, after = current.ratios["residual slosh"], trial.ratios["residual slosh"]
        if abs(after - step.residual) > max(0.25 * abs(step.residual - before), 0.02):
            residual_trust *= 0.5
        else:
            residual_trust = min(1.5 * residual_trust, 2.0)
        if trial.excess < current.excess:
            gain = current.excess - trial.excess
            current = trial
            trust = min(trust * 1.5, 1.0)
            if (
                gain < 0.25 * tolerance
                and abs(trial.excess - (1.0 - PROGRAM_MARGIN + step.sigma)) < tolerance
            ):
                break
        else:
            trust *= 0.5
            if trust < 1e-3:
                break
    return current, current.excess


def _dilated_search(
    program: PathProgram,
    start: PathSamples,
    iterations: int = 12,
    trust: float = 0.1,
    dilation_trust: float = 0.05,
    tolerance: float = 1e-3,
) -> ProgramIterate:
    """The shortest samples of N steps (N from ``start``) whose period is free: cone programs
    (`cone_step` with ``dilation_trust``) from ``start``, a step kept when its exact merit
    ln h + `PENALTY` max(0, ratio - 1 + `PROGRAM_MARGIN`) falls (the trust regions of the
    speed and of epsilon then grow by half, else they halve). Stops when a kept step shortens
    the period by less than ``tolerance`` with every limit met."""
    keep = 1.0 - PROGRAM_MARGIN

    def merit(iterate: ProgramIterate) -> float:
        return math.log(iterate.samples.period_s) + PENALTY * max(0.0, iterate.excess - keep)

    current = program.iterate(start)
    for _ in range(iterations):
        # the residual's own trust region stays open: the penalty must be able to remove an
        # excess residual, and the merit test rejects a step that mispredicted it
        step = cone_step(program, current.samples, current.evaluation, trust, 1.0, dilation_trust)
        if step is None:
            trust, dilation_trust = 0.5 * trust, 0.5 * dilation_trust
            continue
        trial = program.iterate(step.samples)
        gain = merit(current) - merit(trial)
        if gain > 0.0:
            shortened = current.samples.period_s - trial.samples.period_s
            current = trial
            trust, dilation_trust = min(1.5 * trust, 1.0), min(1.5 * dilation_trust, 0.2)
            if current.feasible and shortened < tolerance * current.samples.period_s:
                break
        else:
            trust, dilation_trust = 0.5 * trust, 0.5 * dilation_trust
            if trust < 1e-3:
                break
    return current


#: Sample period of the first, coarse free-time search [s] (about 20 samples per period of
#: the fundamental mode of a vial; the export grid then refines it).
COARSE_PERIOD_S = 0.016
#: Programs of the coarse grid's free-period search, at most (it ends earlier when a kept step
#: shortens the period by less than 0.1 %: on TRD_2D after 25-40).
COARSE_ITERATIONS = 60
#: Export-grid durations tried after the free-time searches, at most.
EXPORT_TRIES = 4


def free_time(
    program: PathProgram, start: PathSamples, log: Any = None, coarse: bool = True
) -> tuple[ProgramIterate, list[tuple[int, float]]]:
    """The fewest export samples whose timing meets every limit.

    1. On a grid of `COARSE_PERIOD_S` (when ``coarse``; its programs are a quarter the size):
       the bracketed search over N (`_minimum_time`), then the same N with the period free
       (`_dilated_search`): the coarse minimum time.
    2. On the export's period Ts: that timing spread (`smoothed`) over the steps of its
       duration, the period free again (the finer grid sees the higher modes' residual the
       coarse one smooths away).
    3. On the export grid: N, the steps of that duration
       (`sloshkit.motion.sampling.steps_to_reach`); its best margin (`_margin_at`, ended when
       every limit is met with half `PROGRAM_MARGIN` to spare), N increased while a limit is
       still exceeded (at most `EXPORT_TRIES`), each N from the last one's samples.

    Parameters
    ----------
    program : PathProgram
        The problem's model.
    start : PathSamples
        The first timing, on the export grid.
    log : callable, optional
        Receives one line per search.
    coarse : bool
        Whether to start on the coarse grid (False: ``start`` is already near the optimum).

    Returns
    -------
    tuple
        The feasible iterate (`ProgramIterate`) and the (N, r) pairs tried on the export grid.

    Raises
    ------
    RuntimeError
        When no export-grid duration met the limits.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> program = PathProgram(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model], limits, 0.01)
    >>> t = np.arange(61) / 60  # a quintic rest-to-rest timing of 0.6 s
    >>> start = PathSamples(0.1 * t**3 * (10 - 15 * t + 6 * t**2), np.zeros((61, 2)), 0.01)
    >>> best, tried = free_time(program, start)
    >>> best.feasible, best.samples.steps < 60
    (True, True)
    """
    from sloshkit.motion.sampling import steps_to_reach

    ts = start.period_s
    duration = start.steps * ts
    factor = max(1, int(COARSE_PERIOD_S / ts + 1e-9)) if coarse else 1

    def free(samples: PathSamples, steps: int, iterations: int, trust: float) -> ProgramIterate:
        length = samples.steps * samples.period_s
        spread = smoothed if steps > samples.steps else rescaled
        found = _dilated_search(
            program, spread(samples, steps, length / steps), iterations, trust, 0.5 * trust
        )
        if log:
            log(
                f"free period at N = {steps}: {found.samples.steps * found.samples.period_s:.4f}"
                f" s, largest ratio {found.excess:.4f} ({program.programs} programs)"
            )
        return found

    current = start
    if factor > 1:
        coarse_steps = steps_to_reach(duration, factor * ts)
        found, _ = _minimum_time(program, rescaled(start, coarse_steps, factor * ts), log)
        # the coarse grid's own minimum, its period free
        current = free(found.samples, found.samples.steps, COARSE_ITERATIONS, 0.1).samples
    # on the export's period; it starts near its optimum: a quarter of the trust regions
    duration = current.steps * current.period_s
    found = free(current, steps_to_reach(duration, ts), 8, 0.025)
    current, duration = found.samples, found.samples.steps * found.samples.period_s
    steps = steps_to_reach(duration, ts)
    history: list[tuple[int, float, ProgramIterate]] = []
    for _ in range(EXPORT_TRIES):
        # enough margin that the verification's finer checks pass as well
        iterate, ratio = _margin_at(
            program, rescaled(current, steps, ts), iterations=4, enough=1.0 - 0.5 * PROGRAM_MARGIN
        )
        history.append((steps, ratio, iterate))
        if log:
            log(f"N = {steps}: largest ratio to a limit {ratio:.4f} ({program.programs} programs)")
        if ratio <= 1.0:
            return iterate, [(h[0], h[1]) for h in history]
        current = iterate.samples
        # half the step of r ~ (N0 / N)^2: near r = 1 the margin program, not the duration,
        # is what fell short
        steps += max(1, math.ceil(0.5 * steps * (math.sqrt(ratio) - 1.0)))
    worst = min(history, key=lambda h: h[1])[2]
    binding = max(worst.ratios, key=lambda key: worst.ratios[key])
    raise RuntimeError(f"no timing up to {steps * ts:.3g} s meets the limits (binding: {binding})")


def _minimum_time(
    program: PathProgram, start: PathSamples, log: Any = None
) -> tuple[ProgramIterate, list[tuple[int, float]]]:
    """The fewest steps N whose best samples (`_margin_at`) meet every limit.

    r(N), the largest ratio to a limit, falls about as (N0 / N)^2 when the slosh or the
    acceleration binds: the next N solves r = 1 on the secant of log r against log N through the
    last two, kept inside the bracket of solved N (the largest infeasible, the smallest
    feasible) and within 20 % of the last; the search stops when the bracket is
    `SEARCH_TOLERANCE` wide. Each r(N) starts from the nearest feasible samples rescaled
    (from the start while none is).

    Returns the best feasible iterate and the (N, r) pairs tried; raises `RuntimeError` when
    no N up to four times the start's meets the limits."""
    history: list[tuple[int, float, ProgramIterate]] = []
    steps = start.steps
    guess = start
    for _ in range(MAX_SEARCH):
        steps_now = rescaled(guess, steps)
        iterate, ratio = _margin_at(program, steps_now)
        history.append((steps, ratio, iterate))
        if log:
            log(
                f"N = {steps} of {steps_now.period_s * 1e3:.4g} ms: largest ratio to a limit "
                f"{ratio:.4f} ({program.programs} programs)"
            )
        feasible = [h for h in history if h[1] <= 1.0]
        infeasible = [h for h in history if h[1] > 1.0]
        low = max((h[0] for h in infeasible), default=0)
        high = min((h[0] for h in feasible), default=None)
        if high is not None and high - low <= max(1, int(SEARCH_TOLERANCE * high)):
            break
        if len(history) == 1 or abs(math.log(history[-1][1] / history[-2][1])) < 1e-9:
            target = steps * math.sqrt(ratio)
        else:
            (n1, r1, _), (n2, r2, _) = history[-2], history[-1]
            slope = math.log(r2 / r1) / math.log(n2 / n1)
            target = n2 * (r2 ** (-1.0 / slope) if slope < -0.1 else math.sqrt(r2))
        target = min(max(target, 0.8 * steps), 1.25 * steps)
        new = math.ceil(target)
        upper = high - 1 if high is not None else 4 * start.steps
        new = min(max(new, low + 1), upper)
        if any(h[0] == new for h in history):
            new = (low + upper + 1) // 2
        if any(h[0] == new for h in history) or new > 4 * start.steps:
            break
        # from the nearest feasible samples: stretching an infeasible iterate carries its
        # broken residual along (from none yet, the start stretched)
        solved = [h for h in history if h[1] <= 1.0]
        guess = min(solved, key=lambda h: abs(h[0] - new))[2].samples if solved else start
        steps = new
    feasible = [h for h in history if h[1] <= 1.0]
    if not feasible:
        worst = min(history, key=lambda h: h[1])
        binding = max(worst[2].ratios, key=lambda key: worst[2].ratios[key])
        raise RuntimeError(
            f"no timing up to {max(h[0] for h in history) * program.ts:.3g} s meets the limits "
            f"(binding: {binding})"
        )
    best = min(feasible, key=lambda h: h[0])
    return best[2], [(h[0], h[1]) for h in history]


def plan_optimal(problem: Any, verifier: Any, log: Any = None, tilt: bool = False) -> Any:
    """The minimum-time timing (and, with ``tilt``, the tilt) of the path, verified.

    Rounds of the free-time search (`free_time`): the first from the time-optimal speed
    profile under the quasi-static acceleration that tilts a level surface to the height
    limit (h = R a / g; `sloshkit.plan.path.retime.capped_timing`), each next one from the last
    one's samples on the export's period with the program's slosh limits moved towards the
    values at which the verification meets its limits (`_next_limit`; at most `TIGHTENINGS`).
    The rounds end when the verified plan's binding slosh is within `LIMIT_TOLERANCE` of its
    limit, when a round one sample shorter failed the verification, or when a round no
    longer shortens the plan; the shortest verified timing is kept. A limit outside the
    program is met by a uniform stretch (`sloshkit.plan.path.result.verified_candidate`); a
    verifier that checks an arm's joint speeds (`sloshkit.plan.path.result.JointSpeedCheck`)
    lends the programs the joints along the path (`sloshkit.plan.path.joints.joint_map`),
    and they limit the joint speeds themselves. With ``tilt`` the rounds run twice, tilted
    and then upright, each from the capped timing, and the shorter verified plan is kept
    (the SCP is local: either search can end in a local optimum the other avoids).

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    verifier : callable
        (problem, poses, tilted) -> Verification.
    log : callable, optional
        Receives one line per solved duration.
    tilt : bool
        Whether the two tilt angles of every sample are variables of the programs (zero at
        both ends; limited to ``problem.max_tilt_rad``, the angular velocity and acceleration
        limits, else pi rad/s and 1000 deg/s^2, about ``problem.tilt_centre_height_m``).
        With an arm's joint check (`sloshkit.plan.path.result.JointSpeedCheck`) the plan is
        upright (``detail["upright"]`` says why): the joints along the path are solved
        upright.

    Returns
    -------
    PathCandidate
        Method ``optimal``; ``detail`` has the first search's duration, the programs solved,
        each round's limits, verified slosh and whether it tilted, and the search.

    Examples
    --------
    >>> import sloshkit as sk
    >>> from sloshkit.plan.path.result import verify
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> problem = sk.PathProblem(sk.path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     sk.CartesianLimits(2.0, 10.0, 100.0), sk.SpatialSloshLimits(0.008, 0.001), model,
    ...     sample_period_s=0.01)
    >>> found = plan_optimal(problem, verify)
    >>> rounds = found.detail["rounds"]
    >>> found.feasible, found.duration_s == min(r["duration_s"] for r in rounds
    ...     if r["verified_peak_m"] <= 0.008 and r["verified_residual_m"] <= 0.001)
    (True, True)
    """
    import time
    from dataclasses import replace

    from sloshkit.plan.path.problem import sample_path
    from sloshkit.plan.path.result import JointSpeedCheck, PathCandidate, verified_candidate
    from sloshkit.plan.path.retime import capped_timing
    from sloshkit.plan.path.timing import Timing

    started = time.perf_counter()
    machine, slosh = problem.machine, problem.slosh
    # the program's slosh limits start where `_next_limit` aims: the verification's filtered
    # simulation exceeds the program's model by a percent or so
    aim = LIMIT_AIM
    limits = ProgramLimits(
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
        machine.max_angular_velocity_rad_s,
        machine.max_angular_acceleration_rad_s2,
        aim * slosh.max_height_m,
        aim * slosh.max_residual_height_m,
        max_tilt_rad=problem.max_tilt_rad,
        max_tilt_rate_rad_s=machine.max_angular_velocity_rad_s or TILT_RATE_RAD_S,
        max_tilt_acceleration_rad_s2=(
            machine.max_angular_acceleration_rad_s2 or TILT_ACCELERATION_RAD_S2
        ),
    )
    tilt = tilt and problem.max_tilt_rad > 0.0
    ts = problem.sample_period_s
    radius = float(problem.model.radius_m)
    cap = min(machine.max_acceleration_m_s2, GRAVITY_M_S2 * slosh.max_height_m / radius)
    first = capped_timing(problem, cap)
    grid = sample_path(problem.path, first, ts)
    s = np.clip(
        first.position(np.minimum(grid.time_s, first.duration_s)), 0.0, problem.path.length_m
    )
    s[-1] = problem.path.length_m
    warm = PathSamples(np.maximum.accumulate(s), np.zeros((s.size, 2)), ts)
    joints = joint_map(problem, verifier) if isinstance(verifier, JointSpeedCheck) else None
    if isinstance(joints, str):
        return PathCandidate("optimal", None, None, time.perf_counter() - started, joints)
    # the joints along the path are solved upright: a tilt would move them, and the tilted
    # programs with an arm diverged on the export grid (TRD_2D with the UR5e)
    upright_for_arm = tilt and joints is not None
    tilt = tilt and not upright_for_arm
    rounds: list[dict[str, float]] = []
    verified: list[tuple[int, ProgramIterate, bool]] = []
    searches: list[tuple[int, float]] = []
    programs = 0
    failure = ""
    first_limits, start = limits, warm
    # with tilt, a tilted search and an upright one, each from the capped timing, and the
    # shorter plan: each can end in a local optimum the other avoids (RD_2D: 5.544 s tilted,
    # 4.428 s upright; the tilted search from the upright plan reached 0.724 s on
    # pick-and-place, 0.644 s from the capped timing)
    for tilted in (True, False) if tilt else (False,):
        limits, warm = first_limits, start
        for _ in range(TIGHTENINGS):
            program = PathProgram(
                problem.path,
                problem.models(),
                limits,
                ts,
                tilt=tilted,
                centre_height_m=problem.tilt_centre_height_m,
                joints=joints,
            )
            try:
                # a later round starts from the last one's samples, already near its optimum
                coarse = not any(r["tilted"] == float(tilted) for r in rounds)
                best, search = free_time(program, warm, log, coarse=coarse)
            except RuntimeError as error:
                failure = str(error)
                break
            warm = best.samples
            searches += search
            programs += program.programs
            check = verifier(problem, export_poses(problem, best.samples), tilted)
            rounds.append(
                {
                    "duration_s": best.samples.steps * ts,
                    "height_limit_m": limits.max_height_m,
                    "residual_limit_m": limits.max_residual_height_m,
                    "verified_peak_m": check.peak_height_m,
                    "verified_residual_m": check.residual_height_m,
                    "tilted": float(tilted),
                }
            )
            if log:
                log(
                    f"verified: peak {check.peak_height_m * 1e3:.3g} mm, residual "
                    f"{check.residual_height_m * 1e3:.3g} mm"
                )
            feasible = (
                check.peak_height_m <= slosh.max_height_m
                and check.residual_height_m <= slosh.max_residual_height_m
            )
            if feasible:
                verified.append((best.samples.steps, best, tilted))
                mine = [v for v in verified if v[2] == tilted]
                closest = max(
                    check.peak_height_m / slosh.max_height_m,
                    check.residual_height_m / slosh.max_residual_height_m,
                )
                # done when the binding slosh limit is met within the tolerance, when a round one
                # sample shorter failed the verification, or when moving the program's limits
                # towards the limit no longer shortens the plan
                shorter_failed = any(
                    r["duration_s"] < rounds[-1]["duration_s"] - 0.5 * ts
                    and r["duration_s"] >= rounds[-1]["duration_s"] - 1.5 * ts
                    for r in rounds[:-1]
                    if r["tilted"] == float(tilted)
                )
                if (
                    closest >= 1.0 - LIMIT_TOLERANCE
                    or shorter_failed
                    or (len(mine) >= 2 and mine[-1][0] >= mine[-2][0])
                ):
                    break
            limits = replace(
                limits,
                max_height_m=_next_limit(
                    [r for r in rounds if r["tilted"] == float(tilted)],
                    "height_limit_m",
                    "verified_peak_m",
                    slosh.max_height_m,
                ),
                max_residual_height_m=_next_limit(
                    [r for r in rounds if r["tilted"] == float(tilted)],
                    "residual_limit_m",
                    "verified_residual_m",
                    slosh.max_residual_height_m,
                ),
            )
    if not verified:
        message = failure or "the verification's slosh exceeds the limits after every tightening"
        return PathCandidate("optimal", None, None, time.perf_counter() - started, message)
    _, corrected, tilt = min(verified, key=lambda entry: (entry[0], not entry[2]))
    samples = corrected.samples
    timing = Timing.from_samples("optimal", np.arange(samples.s_m.size) * ts, samples.s_m)

    def poses_for(factor: float) -> Any:
        if factor == 1.0:
            return export_poses(problem, samples)
        if tilt:  # the timing and the tilt together, over the stretched duration
            return export_poses(problem, rescaled(samples, math.ceil(samples.steps * factor)))
        return sample_path(problem.path, timing.stretched(factor), ts)

    detail: dict[str, Any] = {
        "first_search_s": rounds[0]["duration_s"],
        "programs": programs,
        "rounds": rounds,
        "search": searches,
    }
    if upright_for_arm:
        detail["upright"] = "the arm's joints along the path are solved upright"
    return verified_candidate("optimal", problem, poses_for, 1.0, started, verifier, tilt, detail)


def _next_limit(
    rounds: list[dict[str, float]], program_key: str, verified_key: str, limit: float
) -> float:
    """The program's next limit: the verification's value is an increasing function v(p) of
    the program's limit p (v = p for a linear verification); regula falsi for v(p) = limit
    (slightly below) on the rounds that bracket it, else p limit / v (at most the limit)."""
    aim = LIMIT_AIM * limit
    points = sorted((r[program_key], r[verified_key]) for r in rounds)
    below = [p for p in points if p[1] <= aim]
    above = [p for p in points if p[1] > aim]
    if below and above:
        (p1, v1), (p2, v2) = below[-1], above[0]
        if v2 > v1 and p2 > p1:  # rounds at one program limit bracket nothing
            return p1 + (aim - v1) * (p2 - p1) / (v2 - v1)
    p, v = rounds[-1][program_key], rounds[-1][verified_key]
    return min(limit, p * aim / max(v, 1e-12))


__all__ = [
    "COARSE_ITERATIONS",
    "COARSE_PERIOD_S",
    "EXPORT_TRIES",
    "LIMIT_AIM",
    "LIMIT_TOLERANCE",
    "MAX_SEARCH",
    "SEARCH_TOLERANCE",
    "TIGHTENINGS",
    "TILT_ACCELERATION_RAD_S2",
    "TILT_RATE_RAD_S",
    "free_time",
    "plan_optimal",
]
