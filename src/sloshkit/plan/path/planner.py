"""The 3-D path planner: methods side by side, each verified, the fastest feasible chosen.

All methods use the timing family of `sloshkit.plan.path.retime` (acceleration-capped time-optimal
speed profile, box filter for the jerk limit, optional ZV/ZVD shaping of the timing):

- ``retime``: the largest cap whose member passes the linear screen (with and without shaping),
  and the verified ``uniform`` timing, each improved locally by speed-scaling warps
  (`sloshkit.plan.path.improve.warped_candidates`: pattern search and sequential linear
  programming);
- ``shaped``: per-axis input shaping of the members (each Cartesian axis convolved with the
  ZV/ZVD shaper of the first mode, which cancels its residual for every lateral direction), the
  largest cap whose export passes the screen and keeps within ``max_path_deviation_m`` of the
  path (shaping the axes cuts corners; the deviation is measured on the export);
- ``tilt``: tilt compensation (`sloshkit.plan.path.tilt_compensation`) of the members, the
  largest cap whose tilted export passes the screen and the tilt and angular limits, then
  improved by the same local searches on the tilted export, seeded also from ``retime``'s
  timing in ``auto`` (`sloshkit.plan.path.tilt`);
- ``auto``: all three (and ``optimal`` on short moves), the fastest verified;
- ``optimal``: the minimum-time timing (and, with ``tilt``, the tilt) of the path by
  sequential second-order-cone programs of a spline transcription on the export grid
  (`sloshkit.plan.path.optimal`): the fastest verified moves, at a minute or more of compute
  on long paths, so ``auto`` runs it only on short moves (`AUTO_OPTIMAL_MAX_SAMPLES`,
  `AUTO_ARM_OPTIMAL_MAX_SAMPLES`); with
  ``tilt`` the tilt angles are variables of its programs.

Every candidate is verified with the nonlinear 3-D model (`sloshkit.plan.path.result.verify`); when
the verified export still exceeds a limit that a slower copy meets (slosh, Cartesian, angular,
a robot's joint speeds), it is stretched in time by the excess and verified again
(`sloshkit.plan.path.result.verified_candidate`). An optional reference timing (the pose
file's own) is slowed uniformly until the limits and the screen pass and reported as the
``uniform`` candidate, the naive fix the methods are compared with (never chosen).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.improve import fastest_improved, ladder_affordable
from sloshkit.plan.path.ladder import TARGET_LADDER, ladder_seeds, method_timing, plan_uniform
from sloshkit.plan.path.limits import machine_violations, path_deviation
from sloshkit.plan.path.problem import PathProblem, sample_path
from sloshkit.plan.path.result import (
    JointSpeedCheck,
    PathCandidate,
    PathPlanResult,
    Verifier,
    linear_verifier,
    verified_candidate,
    verify,
)
from sloshkit.plan.path.retime import (
    axis_shaped_samples,
    first_mode_shaper,
)
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import (
    LOWEST_CAP_FRACTION,
    fastest_capped,
    lowest_cap_failure,
    stretcher,
)
from sloshkit.plan.path.tilt import improved_tilt, plan_tilt, timing_shapers
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


def plan_retime(
    problem: PathProblem,
    verifier: Verifier = verify,
    seeds: Sequence[tuple[PathCandidate, Timing]] = (),
    timings: Sequence[tuple[str, Timing]] = (),
) -> PathCandidate:
    """The fastest acceleration cap of the family under the slosh screen (with the first-mode
    timing shaper, without, and on curved paths with `sloshkit.plan.path.retime.curve_shaper`),
    verified. The verified family timing and every verified ``seeds`` timing are candidates
    too, each improved by `sloshkit.plan.path.improve.warped_candidates` (pattern search and
    SLP on a speed-scaling warp) and verified again; the
    fastest verified one wins, so ``retime`` is never slower than a feasible seed. The
    container stays on the path.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    verifier : callable
        Verification of an export.
    seeds : sequence of (PathCandidate, Timing)
        Verified candidates of the same path and their timings (e.g. ``uniform``).
    timings : sequence of (str, Timing)
        Other timings of the path (e.g. the ``shaped`` and ``tilt`` members), seeds once
        slowed until they pass (`sloshkit.plan.path.improve.ladder_seeds`, which also seeds
        the family and ``seeds`` under the stricter targets of `TARGET_LADDER`).

    Returns
    -------
    PathCandidate

    References
    ----------
    Bobrow et al. (1985), doi:10.1177/027836498500400301.

    Examples
    --------
    >>> problem = _example_problem()
    >>> plan_retime(problem, linear_verifier).detail["shaper"]
    'zv'
    """
    return _retime(problem, verifier, seeds, timings)[0]


def _retime(
    problem: PathProblem,
    verifier: Verifier,
    seeds: Sequence[tuple[PathCandidate, Timing]],
    timings: Sequence[tuple[str, Timing]],
) -> tuple[PathCandidate, Timing | None]:
    """`plan_retime` and the timing of its export (None when it failed)."""
    started = time.perf_counter()
    models = problem.models()
    best: tuple[float, float, Timing, str] | None = None
    shapers = dict(timing_shapers(problem))
    for name, shaper in shapers.items():
        found = fastest_capped(
            problem, lambda poses: screen_ok(problem, linear_screen(models, poses)), shaper
        )
        if found is None:
            continue
        cap, member = found
        duration = sample_path(problem.path, member, problem.sample_period_s).duration_s
        if best is None or duration < best[0]:
            best = (duration, cap, member, name)
    pool = [(replace(c, detail={**c.detail, "seed": c.method}), t) for c, t in seeds if c.feasible]
    if best is None and not pool:
        message = (
            f"no acceleration cap down to {100 * LOWEST_CAP_FRACTION:g} % of amax meets the slosh "
            f"limits: at that cap, {lowest_cap_failure(problem)}"
        )
        return _failed("retime", started, message), None
    if best is not None:
        duration, cap, timing, shaper_name = best
        detail: dict[str, Any] = {"acceleration_cap_m_s2": cap, "shaper": shaper_name}
        family = verified_candidate(
            "retime", problem, stretcher(problem, timing), 1.0, started, verifier, False, detail
        )
        stretched = timing.stretched(float(family.detail["stretch"]))
        pool.append((replace(family, detail={**family.detail, "seed": "family"}), stretched))
    # The continuation over stricter targets and the other methods' timings (seeds).
    others = [(c.method, t, ladder) for c, t in seeds if c.feasible for ladder in TARGET_LADDER[1:]]
    others += [(name, timing, TARGET_LADDER[0]) for name, timing in timings]
    shaper = None if best is None else shapers[best[3]]
    ladder = TARGET_LADDER[1:] if best is not None else ()
    extra: list[tuple[PathCandidate, Timing]] = []
    if ladder_affordable(problem, min(t.duration_s for _, t in pool)):
        extra = ladder_seeds(problem, verifier, started, shaper, others, ladder)
    chosen, timing = fastest_improved(problem, pool, verifier, started, ladder=extra)
    return replace(chosen, method="retime", compute_time_s=time.perf_counter() - started), timing


#: ``auto`` also runs ``optimal`` when the fastest verified plan of the other methods has at
#: most this many export samples (2.4 s at 4 ms) and no arm is checked. Its compute grows with
#: the samples: upright about 1.5 s for the benchmark's 0.78 s pick-and-place (196 samples)
#: and 6 s for the 2.09 s TRD_2D move (522 samples), where `retime` took 20 s for 2.54 s;
#: tilted 3 s and 60 s (0.664 s and 1.464 s, where `tilt` gives 1.08 s and 1.88 s), and 70 s
#: tilted on TRD_2D under the default angular limits (1.940 s, where `retime` gives 2.264 s
#: in 11 s). A move is planned once and run many times, so a minute for a 20 % shorter cycle
#: is worth it.
AUTO_OPTIMAL_MAX_SAMPLES = 600
#: The same bound with an arm's joint speeds checked (1.2 s at 4 ms): the joint rows and the
#: IK of the verified exports make ``optimal`` dearer (6 s upright and 12 s tilted for the
#: pick-and-place with the UR5e, 173 s and 226 s for TRD_2D).
AUTO_ARM_OPTIMAL_MAX_SAMPLES = 300


def _optimal_affordable(problem: PathProblem, feasible: Sequence[PathCandidate], arm: bool) -> bool:
    """Whether ``auto`` runs ``optimal`` too: a verified plan exists and the fastest one has at
    most `AUTO_OPTIMAL_MAX_SAMPLES` samples (`AUTO_ARM_OPTIMAL_MAX_SAMPLES` with an arm;
    ``optimal``'s programs grow with the samples, and the joints' rows and IK make them
    dearer)."""
    if not feasible:
        return False
    fastest = min(c.duration_s for c in feasible)
    bound = AUTO_ARM_OPTIMAL_MAX_SAMPLES if arm else AUTO_OPTIMAL_MAX_SAMPLES
    return fastest / problem.sample_period_s <= bound


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
        ``auto`` (``retime``, ``shaped``, ``tilt`` with ``tilt``, and ``optimal`` when the
        fastest of them has at most `AUTO_OPTIMAL_MAX_SAMPLES` samples, with an arm
        `AUTO_ARM_OPTIMAL_MAX_SAMPLES`; the fastest verified),
        ``retime``, ``shaped``, ``tilt`` or ``optimal`` (`sloshkit.plan.path.optimal`).
    reference : Timing, optional
        The path's existing timing (e.g. of the pose file it came from): slowed uniformly and
        reported as the ``uniform`` candidate, never chosen.
    progress : callable, optional
        Receives one line per step.
    verifier : callable
        (problem, poses, tilted) -> Verification (default `verify`: the nonlinear 3-D model;
        `sloshkit.export.path_robot.robot_verifier` adds a robot's joint-speed check).
    tilt : bool
        Whether ``auto`` may tilt the container and whether ``optimal`` makes the tilt
        variables of its programs (``method="tilt"`` always tilts).

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
    say = progress or (lambda _: None)
    candidates: list[PathCandidate] = []
    uniform = None if reference is None else plan_uniform(problem, reference, verifier)
    seeds = (
        []
        if uniform is None or not uniform.feasible
        else [(uniform, reference.stretched(float(uniform.detail["stretch"])))]  # type: ignore[union-attr]
    )
    if method == "optimal":
        from sloshkit.plan.path.optimal import plan_optimal

        say("optimal: the minimum-time timing by sequential cone programs")
        candidates.append(plan_optimal(problem, verifier, say, tilt=tilt))
    if method in ("auto", "shaped"):
        say("shaped: per-axis input shaping")
        candidates.append(plan_shaped(problem, verifier))
    tilting = method == "tilt" or (method == "auto" and tilt)
    if tilting:
        say("tilt: tilt compensation with re-timing")
        candidates.append(plan_tilt(problem, verifier, improve=method == "tilt"))
    if method in ("auto", "retime"):
        say("retime: fastest acceleration cap under the slosh limits, then local searches")
        shapers = dict(timing_shapers(problem))
        timings = [method_timing(problem, c, shapers) for c in candidates if c.poses is not None]
        found, timing = _retime(problem, verifier, seeds, timings)
        candidates.insert(0, found)
        if tilting:
            # The tilt family's timing improved on the tilted export, seeded also from
            # retime's timing (tilting a good timing is a natural seed).
            say("tilt: local searches on the tilted export")
            retimed = [] if timing is None or not found.feasible else [timing]
            candidates[-1] = improved_tilt(problem, candidates[-1], retimed, verifier)
    feasible = [c for c in candidates if c.feasible]
    arm = isinstance(verifier, JointSpeedCheck)
    if method == "auto" and _optimal_affordable(problem, feasible, arm):
        from sloshkit.plan.path.optimal import plan_optimal

        say("optimal: the minimum-time timing by sequential cone programs (a short move)")
        # without seeds: on short moves the capped timing's searches end shorter than those
        # from the other plans (pick-and-place, tilted: 0.644 s against 0.82 s and 0.79 s
        # from tilt's and retime's plans on the coarse grid), which would cost 8 s more
        candidates.append(plan_optimal(problem, verifier, say, tilt=tilt))
        feasible = [c for c in candidates if c.feasible]
    pool = feasible or [c for c in candidates if c.poses is not None]
    chosen = min(pool, key=lambda c: c.duration_s) if pool else None
    if uniform is not None:
        candidates.append(uniform)
    return PathPlanResult(problem, chosen, tuple(candidates))


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
