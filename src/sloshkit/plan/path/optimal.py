"""The minimum-time timing of a 3-D path, verified: rounds of the free-time search of the
path program (`sloshkit.plan.path.minimum_time.free_time`; `sloshkit.plan.path.program`, the
model; `sloshkit.plan.path.cone`, one program), each exported and re-simulated.

The programs model what the verification simulates without its smoothing filter; the
verification, which also simulates the export through that filter, can still exceed a slosh
limit by a percent or two. The program's limit is then moved by regula falsi (`_next_limit`)
and the search restarts from the last samples on the export's period (`plan_optimal`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.joints import joint_map
from sloshkit.plan.path.minimum_time import free_time
from sloshkit.plan.path.program import PathProgram, ProgramIterate, ProgramLimits
from sloshkit.plan.path.samples import PathSamples, export_poses, rescaled, samples_from_poses

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
#: The second search (upright, after the tilted one) ends after its coarse grid when that
#: minimum is longer than the first search's verified plan by more than this fraction: the
#: finer grids moved the coarse minimum by -0.8 % to +2.8 % on the benchmark's cases.
PRUNE = 0.03


def plan_optimal(
    problem: Any,
    verifier: Any,
    log: Any = None,
    tilt: bool = False,
    seeds: Sequence[PoseTrajectory] = (),
) -> Any:
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
    The verified plans of other methods in ``seeds`` start the first round's coarse search
    too (`free_time`'s ``seeds``; read back as samples by
    `sloshkit.plan.path.samples.samples_from_poses`): a tilted one the tilted search, an
    upright one the upright search.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    verifier : callable
        (problem, poses, tilted) -> Verification.
    log : callable, optional
        Receives one line per solved duration.
    seeds : sequence of PoseTrajectory
        Verified exports of the path (``tilt``'s and ``retime``'s plans in
        `sloshkit.plan.path.planner.plan_path`); one that is not on the path is skipped.
    tilt : bool
        Whether the two tilt angles of every sample are variables of the programs (zero at
        both ends; limited to ``problem.max_tilt_rad``, the angular velocity and acceleration
        limits, else pi rad/s and 1000 deg/s^2, about ``problem.tilt_centre_height_m``).
        With an arm's joint check (`sloshkit.plan.path.result.JointSpeedCheck`) the joints
        enter the tilted programs by their quadratic model in the tilt
        (`sloshkit.plan.path.joints.JointModel`); when the arm cannot reach the tilted probes
        of that model, the plan is upright (``detail["upright"]`` says why).

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
    arm = isinstance(verifier, JointSpeedCheck)
    joints = joint_map(problem, verifier, tilt=tilt) if arm else None
    if isinstance(joints, str):
        return PathCandidate("optimal", None, None, time.perf_counter() - started, joints)
    # the joints' model in the tilt needs the IK of the tilted probes: where the arm cannot
    # reach them, plan upright
    upright_for_arm = tilt and joints is not None and joints.tilt_gradient is None
    tilt = tilt and not upright_for_arm
    starts: dict[bool, list[PathSamples]] = {True: [], False: []}
    for seed in seeds:
        try:
            read = samples_from_poses(problem, seed)
        except ValueError as error:
            if log:
                log(f"seed skipped: {error}")
            continue
        starts[bool(np.any(np.abs(read.tilt_rad) > 1e-9))].append(read)
    rounds: list[dict[str, float]] = []
    pruned: list[float] = []
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
                more = starts[tilted] if coarse else []
                # the second search goes on only while it can still beat the first's plan
                longest = (1.0 + PRUNE) * min((v[0] * ts for v in verified), default=math.inf)
                found = free_time(program, warm, log, coarse, more, longest if coarse else math.inf)
            except RuntimeError as error:
                failure = str(error)
                break
            if found is None:
                pruned.append(float(tilted))
                break
            best, search = found
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
        "seeds_s": [seed.duration_s for seed in seeds],
        "pruned": pruned,
    }
    if upright_for_arm:
        detail["upright"] = "the arm cannot reach the path tilted by the joint model's probes"
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
    "LIMIT_AIM",
    "LIMIT_TOLERANCE",
    "PRUNE",
    "TIGHTENINGS",
    "TILT_ACCELERATION_RAD_S2",
    "TILT_RATE_RAD_S",
    "plan_optimal",
]
