"""The 3-D path planner: methods side by side, each verified, the fastest feasible chosen.

- ``retime``: the minimum-time timing of the path, upright, by sequential second-order-cone
  programs of a spline transcription on the export grid (`sloshkit.plan.path.optimal`).
  The timing family of `sloshkit.plan.path.retime` (time-optimal speed profile under an
  acceleration cap, box filter for the jerk limit, optional ZV/ZVD or curve shaping of the
  timing) stands in for them: its fastest cap that passes the linear screen
  (`sloshkit.plan.path.search.upright_family`) is the plan when the programs verify
  nothing, and when even the slowest member fails the screen the family runs first and
  names the limit that binds (`_plan_exists`);
- ``tilt``: the same programs with the two tilt angles of every sample as variables, never
  longer than their upright plan; the tilt-compensated family member
  (`sloshkit.plan.path.tilt.tilted_family`) stands in for them the same way;
- ``shaped``: per-axis input shaping of the members (each Cartesian axis convolved with the
  ZV/ZVD shaper of the first mode, which cancels its residual for every lateral direction), the
  largest cap whose export passes the screen and keeps within ``max_path_deviation_m`` of the
  path (shaping the axes cuts corners; the deviation is measured on the export);
- ``auto``: ``shaped``, and the programs of ``retime`` (and ``tilt``) on moves up to about
  5 s (`AUTO_OPTIMAL_MAX_SAMPLES`; with an arm 1.2 s, `AUTO_ARM_OPTIMAL_MAX_SAMPLES`), the
  families on longer ones (the tilted programs take a minute or more there);
- ``optimal``: ``tilt`` with the tilt free, else ``retime`` (the name of the 1-D planner's
  minimum-time method).

Every candidate is verified with the nonlinear 3-D model (`sloshkit.plan.path.result.verify`); when
the verified export still exceeds a limit that a slower copy meets (slosh, Cartesian, angular,
a robot's joint speeds), it is stretched in time by the excess and verified again
(`sloshkit.plan.path.result.verified_candidate`). An optional reference timing (the pose
file's own) is slowed uniformly until the limits and the screen pass and reported as the
``uniform`` candidate, the naive fix the methods are compared with (never chosen, but part of
``retime``'s floor).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.limits import machine_violations, path_deviation
from sloshkit.plan.path.problem import PathProblem
from sloshkit.plan.path.result import (
    JointSpeedCheck,
    PathCandidate,
    PathPlanResult,
    Verifier,
    linear_verifier,
    verified_candidate,
    verify,
)
from sloshkit.plan.path.retime import axis_shaped_samples, first_mode_shaper
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import (
    fastest_capped,
    lowest_cap_failure,
    plan_uniform,
    slowest_member,
    upright_family,
)
from sloshkit.plan.path.tilt import tilted_family
from sloshkit.plan.path.timing import Timing

FloatArray = NDArray[np.float64]
PATH_METHODS: tuple[str, ...] = ("auto", "retime", "shaped", "tilt", "optimal")


def _failed(method: str, started: float, message: str) -> PathCandidate:
    return PathCandidate(method, None, None, time.perf_counter() - started, message)


def plan_shaped(problem: PathProblem, verifier: Verifier = verify) -> PathCandidate:
    """Per-axis input shaping (ZV, ZVD with a band) of the family's members: the largest
    acceleration cap whose shaped export passes the screen, the machine limits and the path
    deviation bound (module docstring), then verified.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    verifier : callable
        Verification of an export (default `sloshkit.plan.path.result.verify`).

    Returns
    -------
    PathCandidate

    References
    ----------
    Singer & Seering (1990), doi:10.1115/1.2894142.

    Examples
    --------
    >>> problem = _example_problem()
    >>> plan_shaped(problem, linear_verifier).feasible
    True
    """
    started = time.perf_counter()
    shaper = first_mode_shaper(problem)
    models = problem.models()

    def sampler(member: Timing) -> PoseTrajectory:
        return axis_shaped_samples(problem.path, member, shaper, problem.sample_period_s)

    def passes(poses: PoseTrajectory) -> bool:
        return (
            screen_ok(problem, linear_screen(models, poses))
            and not machine_violations(problem, poses, False)
            and path_deviation(problem.path, poses) <= problem.max_path_deviation_m
        )

    found = fastest_capped(problem, passes, None, sampler=sampler)
    if found is None:
        failure = lowest_cap_failure(problem, sampler, deviation=True)
        message = f"no per-axis shaped timing meets the limits: at the lowest cap, {failure}"
        return _failed("shaped", started, message)
    cap, member = found

    def poses_for(factor: float) -> PoseTrajectory:
        return sampler(member.stretched(factor))

    return verified_candidate(
        "shaped",
        problem,
        poses_for,
        1.0,
        started,
        verifier,
        False,
        {"shaper": shaper.name, "acceleration_cap_m_s2": cap},
    )


def _fastest(method: str, started: float, pool: Sequence[PathCandidate | None]) -> PathCandidate:
    """The fastest feasible candidate of ``pool`` as ``method``'s, its origin in
    ``detail["source"]`` (``program``, ``family`` or ``uniform``) and ``compute_time_s`` the
    method's since ``started``; when none is feasible, the first failure's message (the
    family's, which names the limit that binds at its lowest cap), the program's in
    ``detail["program"]``."""
    present = [c for c in pool if c is not None]
    feasible = [c for c in present if c.feasible]
    elapsed = time.perf_counter() - started
    if feasible:
        chosen = min(feasible, key=lambda c: c.duration_s)
        detail = {"source": chosen.method, **chosen.detail}
        return replace(chosen, method=method, detail=detail, compute_time_s=elapsed)
    failures = sorted(present, key=lambda c: c.detail.get("source") == "program")
    if not failures:
        return _failed(method, started, "no candidate ran")
    program = [c.message for c in present if c.detail.get("source") == "program"]
    detail = {"program": program[0]} if program else {}
    return replace(failures[0], method=method, compute_time_s=elapsed, detail=detail)


def _floor_found(floor: Sequence[PathCandidate]) -> bool:
    """Whether the programs run: a floor plan exists, verified or not (a family member whose
    export passed the linear screen; the nonlinear verification may still find it a percent
    over a limit, which the programs, imposing the verification's own model, can meet). With
    none, no family member down to `sloshkit.plan.path.search.LOWEST_CAP_FRACTION` of amax
    (so slow that its slosh is quasi-static) passes the screen, the request fails with the
    limit binding there, and the programs, which would try ever longer durations, do not run."""
    return any(candidate.poses is not None for candidate in floor)


def _plan_exists(problem: PathProblem) -> bool:
    """Whether the slowest family member (`sloshkit.plan.path.search.slowest_member`) passes
    the linear screen: then a plan exists, and ``retime``'s and ``tilt``'s programs run, their
    families only when the programs verify nothing (`_verified`). Else the families run
    first, and the programs only when one found a plan (`_floor_found`)."""
    return screen_ok(problem, linear_screen(problem.models(), slowest_member(problem)))


def _verified(candidate: PathCandidate | None, tilted: bool = False) -> bool:
    """Whether the programs' candidate is a verified plan (with ``tilted``, a tilted one: the
    tilted programs return their upright plan when their tilted search verified nothing);
    when it is, the families do not run after them: they never gave a shorter plan on the
    benchmark and cost 0.8 s on TRD_2D (docs/planning-3d.md, "The families")."""
    if candidate is None or not candidate.feasible:
        return False
    return not tilted or bool(candidate.detail.get("tilted"))


def _program_candidates(
    problem: PathProblem,
    verifier: Verifier,
    say: Callable[[str], None],
    tilt: bool,
    retime: bool = True,
) -> tuple[PathCandidate | None, PathCandidate | None]:
    """`sloshkit.plan.path.optimal.plan_programs`, each candidate's source marked."""
    from sloshkit.plan.path.optimal import plan_programs

    say("programs: the minimum-time timing by sequential cone programs")
    return tuple(  # type: ignore[return-value]
        None if c is None else replace(c, detail={**c.detail, "source": "program"})
        for c in plan_programs(problem, verifier, say, tilt=tilt, retime=retime)
    )


def plan_retime(
    problem: PathProblem,
    verifier: Verifier = verify,
    floor: Sequence[PathCandidate] = (),
    progress: Callable[[str], None] | None = None,
) -> PathCandidate:
    """The minimum-time upright timing of the path (`sloshkit.plan.path.optimal.plan_programs`),
    or a ``floor`` candidate when one is faster; the family's verified member
    (`sloshkit.plan.path.search.upright_family`) when the programs verify nothing (or do not
    run, `_plan_exists`); the container stays on the path.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    verifier : callable
        Verification of an export.
    floor : sequence of PathCandidate
        Other verified plans of the same path that ``retime`` must not be slower than (e.g.
        ``uniform``).
    progress : callable, optional
        Receives one line per step.

    Returns
    -------
    PathCandidate
        Method ``retime``; ``detail["source"]`` says which plan it is.

    References
    ----------
    Bobrow, Dubowsky & Gibson (1985), doi:10.1177/027836498500400301.

    Examples
    --------
    >>> problem = _example_problem()
    >>> found = plan_retime(problem, verify)
    >>> found.feasible, found.detail["source"]
    (True, 'program')
    """
    started = time.perf_counter()
    family = None if _plan_exists(problem) else upright_family(problem, verifier)
    if family is not None and not _floor_found([family, *floor]):
        return _fastest("retime", started, [family, *floor])
    program, _ = _program_candidates(problem, verifier, progress or (lambda _: None), False)
    if family is None and not _verified(program):
        family = upright_family(problem, verifier)
    return _fastest("retime", started, [program, family, *floor])


def plan_tilt(
    problem: PathProblem,
    verifier: Verifier = verify,
    floor: Sequence[PathCandidate] = (),
    progress: Callable[[str], None] | None = None,
) -> PathCandidate:
    """The minimum-time timing and tilt of the path (`sloshkit.plan.path.optimal.plan_programs`
    with ``tilt``; never longer than their upright plan), or ``floor`` when one is faster;
    the fastest of the families' verified members (upright and tilt-compensated) when the
    programs verify nothing (or do not run, `_plan_exists`).

    Parameters
    ----------
    problem : PathProblem
        Path, limits (``max_tilt_rad``, ``tilt_centre_height_m``), model.
    verifier : callable
        Verification of an export.
    floor : sequence of PathCandidate
        Other verified plans of the same path (e.g. ``uniform``).
    progress : callable, optional
        Receives one line per step.

    Returns
    -------
    PathCandidate
        Method ``tilt``; ``detail["source"]`` says which plan it is, ``detail["tilted"]``
        whether the program's plan tilts.

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711 (tilt compensation).

    Examples
    --------
    >>> problem = _example_problem()
    >>> found = plan_tilt(problem, verify)
    >>> found.feasible, found.duration_s <= plan_retime(problem, verify).duration_s
    (True, True)
    """
    started = time.perf_counter()
    # the families in the pool's order: the tilted member first
    families: list[PathCandidate] = []
    if not _plan_exists(problem):
        families = [tilted_family(problem, verifier), upright_family(problem, verifier)]
        if not _floor_found([*families, *floor]):
            return _fastest("tilt", started, [*families, *floor])
    _, program = _program_candidates(problem, verifier, progress or (lambda _: None), True, False)
    if not families and not _verified(program, tilted=True):
        families = [tilted_family(problem, verifier)]
        if not _verified(program):
            families.append(upright_family(problem, verifier))
    return _fastest("tilt", started, [program, *families, *floor])


#: ``auto`` runs the programs of ``retime`` and ``tilt`` when their first start
#: (`sloshkit.plan.path.starts.capped_start`, within 3-21 % of their plans on the benchmark's
#: paths) has at most this many export samples (5 s at 4 ms) and no arm is checked. Their
#: compute grows with the samples: upright 0.2 s and 1.1 s on the 0.78 s pick-and-place and
#: the 2.07 s TRD_2D move, tilted 0.7 s and 4.5-5 s (0.656 s and 1.456 s, where the families
#: give 1.21 s and 1.94 s in about a second), on the 4-7 s moves 2-12 s upright and 17-60 s
#: tilted. A move is planned once and run many times, so a minute for a cycle 1.3-1.9 times
#: shorter than the families' is worth it; on longer moves ``auto`` returns the families'
#: and ``shaped``'s plans, and ``retime`` or ``tilt`` asked for by name run the programs.
AUTO_OPTIMAL_MAX_SAMPLES = 1250
#: The same bound with an arm's joint speeds checked (1.2 s at 4 ms): the joint rows and the
#: IK of the verified exports make the programs dearer (1.9 s upright and 2.7 s tilted for
#: the pick-and-place with the UR5e, 6 s and 30 s for TRD_2D).
AUTO_ARM_OPTIMAL_MAX_SAMPLES = 300


def _programs_affordable(
    problem: PathProblem, found: Sequence[PathCandidate] | None, arm: bool
) -> bool:
    """Whether ``auto`` runs the programs: a plan exists (``found`` None: `_plan_exists`
    said so; else `_floor_found`) and their first start
    (`sloshkit.plan.path.starts.capped_start`, about the length of their plan) has at most
    `AUTO_OPTIMAL_MAX_SAMPLES` samples (`AUTO_ARM_OPTIMAL_MAX_SAMPLES` with an arm). The
    families' plans are no estimate: under the default angular limits the TRD_2D families
    need 3.0-3.3 s where the programs find 1.94 s."""
    if found is not None and not _floor_found(found):
        return False
    from sloshkit.plan.path.starts import capped_start

    bound = AUTO_ARM_OPTIMAL_MAX_SAMPLES if arm else AUTO_OPTIMAL_MAX_SAMPLES
    return capped_start(problem).steps <= bound


def plan_path(
    problem: PathProblem,
    method: str = "auto",
    reference: Timing | None = None,
    progress: Callable[[str], None] | None = None,
    verifier: Verifier = verify,
    tilt: bool = True,
) -> PathPlanResult:
    """Plan a slosh-safe timing (and tilt) of a 3-D path, every candidate verified.

    The methods (`plan_retime`, `plan_shaped`, `plan_tilt`) are compared side by side; each
    export is simulated again with ``verifier`` (the nonlinear 3-D model of every mode and
    band frequency by default) before it may be called feasible, and the fastest feasible one
    is chosen. The export (`PathPlanResult.columns`, ``to_csv``) is a pose file
    ``t,x,y,z,qx,qy,qz,qw`` that ``sloshkit simulate --pose-file`` reads.

    Parameters
    ----------
    problem : PathProblem
        Path, Cartesian/angular limits, slosh limits, model, sample period.
    method : str
        ``auto`` (``shaped``, ``retime`` and with ``tilt`` ``tilt``, their programs only on
        moves whose time-optimal profile under the quasi-static cap has at most
        `AUTO_OPTIMAL_MAX_SAMPLES` samples, with an arm `AUTO_ARM_OPTIMAL_MAX_SAMPLES`; the
        fastest verified), ``retime``, ``shaped``,
        ``tilt``, or ``optimal`` (``tilt`` with ``tilt``, else ``retime``).
    reference : Timing, optional
        The path's existing timing (e.g. of the pose file it came from): slowed uniformly and
        reported as the ``uniform`` candidate, never chosen; ``retime`` and ``tilt`` are never
        slower than it.
    progress : callable, optional
        Receives one line per step.
    verifier : callable
        (problem, poses, tilted) -> Verification (default `verify`: the nonlinear 3-D model;
        `sloshkit.export.path_robot.robot_verifier` adds a robot's joint-speed check).
    tilt : bool
        Whether ``auto`` and ``optimal`` may tilt the container (``method="tilt"`` always
        tilts, ``retime`` never).

    Returns
    -------
    PathPlanResult
        The fastest feasible candidate (or, when none is feasible, the fastest at all) and
        every candidate with its verification and compute time.

    References
    ----------
    Bobrow, Dubowsky & Gibson (1985), doi:10.1177/027836498500400301 (time-optimal path
    timing); Singer & Seering (1990), doi:10.1115/1.2894142 (input shaping); Feddema et al.
    (1997), doi:10.1109/37.569711 (tilt compensation).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> problem = sk.PathProblem(
    ...     sk.path_from_waypoints([[0, 0, 0], [0.3, 0, 0], [0.3, 0.2, 0]], blend_radius_m=0.05),
    ...     sk.CartesianLimits(2.0, 10.0, 100.0), sk.SpatialSloshLimits(0.01, 0.002), model,
    ...     sample_period_s=0.02)
    >>> result = sk.plan_path(problem, "shaped", verifier=linear_verifier)
    >>> result.feasible, result.chosen.method, float(result.columns()["y"][-1])
    (True, 'shaped', 0.2)
    """
    if method not in PATH_METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(PATH_METHODS))
    if method == "optimal":
        method = "tilt" if tilt and problem.max_tilt_rad > 0.0 else "retime"
    say = progress or (lambda _: None)
    candidates: list[PathCandidate] = []
    uniform = None if reference is None else plan_uniform(problem, reference, verifier)
    floor = [] if uniform is None else [uniform]
    if method == "retime":
        say("retime: the minimum-time timing, upright")
        candidates.append(plan_retime(problem, verifier, floor, say))
    elif method == "tilt":
        say("tilt: the minimum-time timing and tilt")
        candidates.append(plan_tilt(problem, verifier, floor, say))
    else:
        if method in ("auto", "shaped"):
            say("shaped: per-axis input shaping")
            candidates.append(plan_shaped(problem, verifier))
        if method == "auto":
            candidates += _auto(problem, verifier, floor, candidates, say, tilt)
    feasible = [c for c in candidates if c.feasible]
    pool = feasible or [c for c in candidates if c.poses is not None]
    chosen = min(pool, key=lambda c: c.duration_s) if pool else None
    if uniform is not None:
        candidates.append(uniform)
    return PathPlanResult(problem, chosen, tuple(candidates))


def _auto(
    problem: PathProblem,
    verifier: Verifier,
    floor: list[PathCandidate],
    others: Sequence[PathCandidate],
    say: Callable[[str], None],
    tilt: bool,
) -> list[PathCandidate]:
    """``auto``'s ``retime`` and (with ``tilt``) ``tilt``: the programs once for both on a
    short move (`_programs_affordable`) when a plan exists (`_plan_exists`, else the families
    first and a plan among theirs or ``others``' such as ``shaped``); the families where the
    programs did not run or verified nothing. ``retime``'s compute is its family's and its
    upright rounds', ``tilt``'s all of it (its tilted rounds start from the upright ones)."""
    started = time.perf_counter()
    tilting = tilt and problem.max_tilt_rad > 0.0
    first: list[PathCandidate] = []
    if not _plan_exists(problem):
        first = [upright_family(problem, verifier)]
        first += [tilted_family(problem, verifier)] if tilting else []
    program: tuple[PathCandidate | None, PathCandidate | None] = (None, None)
    known = [*first, *floor, *others] if first else None
    if _programs_affordable(problem, known, isinstance(verifier, JointSpeedCheck)):
        program = _program_candidates(problem, verifier, say, tilting)
    upright, tilted = (first[0], first[1] if tilting else None) if first else (None, None)
    if not first:
        if not _verified(program[0]):
            say("retime: the family's fastest acceleration cap under the slosh screen")
            upright = upright_family(problem, verifier)
        if tilting and not _verified(program[1], tilted=True):
            say("tilt: tilt compensation of the family")
            tilted = tilted_family(problem, verifier)
    retime = _fastest("retime", started, [program[0], upright, *floor])
    own = sum(c.compute_time_s for c in (upright, program[0]) if c is not None)
    retime = replace(retime, compute_time_s=own)
    if not tilting:
        return [retime]
    tilt_candidate = _fastest("tilt", started, [program[1], tilted, retime, *floor])
    return [retime, replace(tilt_candidate, compute_time_s=time.perf_counter() - started)]


__all__ = [
    "AUTO_ARM_OPTIMAL_MAX_SAMPLES",
    "AUTO_OPTIMAL_MAX_SAMPLES",
    "PATH_METHODS",
    "PathCandidate",
    "PathPlanResult",
    "linear_verifier",
    "plan_path",
    "plan_retime",
    "plan_shaped",
    "plan_tilt",
    "plan_uniform",
]


def _example_problem() -> PathProblem:
    """A 0.3 m straight path with the measured series' vial (for the examples)."""
    from sloshkit.model.geometry import UprightCylinder
    from sloshkit.model.liquids import get_liquid
    from sloshkit.model.modal import equivalent_model
    from sloshkit.plan.path.geometry import path_from_waypoints
    from sloshkit.plan.path.problem import CartesianLimits, SpatialSloshLimits

    model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    return PathProblem(
        path_from_waypoints(np.array([[0.0, 0.0, 0.0], [0.3, 0.0, 0.0]])),
        CartesianLimits(2.0, 10.0, 100.0),
        SpatialSloshLimits(0.01, 0.002),
        model,
        sample_period_s=0.01,
    )
