"""Seeds of ``retime``: timings of the same path the local searches of
`sloshkit.plan.path.improve` start from, each verified against the true limits.

- ``uniform``: the reference timing (e.g. the pose file's own) slowed uniformly until it meets
  the limits (`plan_uniform`; also the naive fix the planner is compared with);
- the **continuation** (`ladder_seeds`): the residual is an oscillating function of the
  timing and its feasible timings form separate basins; a local search stays in its seed's
  basin, so a looser problem could return a longer plan than a stricter one on the same path,
  though every plan feasible under the stricter limits is feasible under the looser ones.
  The family's fastest member and the ``uniform`` timing found under a ladder of stricter
  internal targets (`TARGET_LADDER`) lie in other basins; so do the other methods' timings of
  the path (`method_timing`: the ``shaped`` and ``tilt`` members before their axes are
  shaped or the container tilted). The polishing against the true limits then relaxes them
  into the slack (continuation in the limits: Allgower & Georg, *Introduction to Numerical
  Continuation Methods*, SIAM (2003), doi:10.1137/1.9780898719154).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import replace

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.shaping import Shaper
from sloshkit.plan.path.limits import machine_stretch
from sloshkit.plan.path.problem import PathProblem
from sloshkit.plan.path.result import PathCandidate, Verifier, verified_candidate, verify
from sloshkit.plan.path.retime import ShaperFactory, family_member
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import fastest_capped, slowed_until, stretcher
from sloshkit.plan.path.timing import Timing

#: The ladder of internal targets (fractions of the peak and of the residual limit) under
#: which `ladder_seeds` finds seeds, every one verified against the true limits: the residual
#: oscillates with the timing, so a search stays in its seed's basin of feasible timings, and
#: stricter targets start it in other basins (continuation; module docstring).
TARGET_LADDER: tuple[tuple[float, float], ...] = ((1.0, 1.0), (1.0, 0.5), (0.9, 0.25))

Seeded = tuple[PathCandidate, Timing]


def plan_uniform(
    problem: PathProblem, reference: Timing, verifier: Verifier = verify
) -> PathCandidate:
    """The reference timing slowed uniformly until it meets the Cartesian and angular limits
    and then the slosh screen (the naive fix), then verified.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    reference : Timing
        The timing to slow down (e.g. the pose file's own).
    verifier : callable
        Verification of an export.

    Returns
    -------
    PathCandidate

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> from sloshkit.plan.path.retime import capped_timing
    >>> problem = _example_problem()
    >>> found = plan_uniform(problem, capped_timing(problem, 10.0), linear_verifier)
    >>> found.feasible, found.detail["stretch"] > 1.0
    (True, True)
    """
    started = time.perf_counter()

    poses_for = stretcher(problem, reference)
    found = slowed_until(problem, poses_for, machine_stretch(problem, poses_for(1.0)))
    if found is None:
        message = "no uniform stretch up to 64x meets the slosh limits"
        return PathCandidate("uniform", None, None, time.perf_counter() - started, message)
    return verified_candidate("uniform", problem, poses_for, found[0], started, verifier, False, {})


def targeted(problem: PathProblem, target: tuple[float, float]) -> PathProblem:
    """``problem`` with its peak and residual limits scaled by ``target``.

    Parameters
    ----------
    problem : PathProblem
        The problem.
    target : tuple of float
        Fractions of the peak and of the residual limit.

    Returns
    -------
    PathProblem

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> targeted(_example_problem(), (0.9, 0.25)).slosh.max_residual_height_m
    0.0005
    """
    slosh = problem.slosh
    return replace(
        problem,
        slosh=replace(
            slosh,
            max_height_m=target[0] * slosh.max_height_m,
            max_residual_height_m=target[1] * slosh.max_residual_height_m,
        ),
    )


def ladder_seeds(
    problem: PathProblem,
    verifier: Verifier,
    started: float,
    shaper: Shaper | ShaperFactory | None,
    timings: Sequence[tuple[str, Timing, tuple[float, float]]],
    ladder: Sequence[tuple[float, float]] = TARGET_LADDER[1:],
) -> list[Seeded]:
    """Verified seeds of a continuation over stricter internal targets: for every ``target``
    of ``ladder`` (fractions of the peak and residual limits) the family's fastest member with
    ``shaper`` under the screen at that target, and every timing of ``timings`` (a name, a
    timing of the path, its target) slowed uniformly until it meets the Cartesian and
    angular limits and the screen at its target. Each is verified against the TRUE limits and
    carries ``seed`` and ``target`` in its detail
    (`sloshkit.plan.path.improve.warped_candidates` polishes it against the true limits).

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model.
    verifier : callable
        Verification of an export.
    started : float
        ``time.perf_counter()`` when the method started.
    shaper : Shaper, callable or None
        The timing shaper of the family's members.
    timings : sequence of (str, Timing, (float, float))
        Other timings of the same path (e.g. ``uniform``, ``shaped``, ``tilt``'s members).
    ladder : sequence of (float, float)
        The family's targets (default `TARGET_LADDER` without the true limits).

    Returns
    -------
    list of (PathCandidate, Timing)
        The verified seeds (feasible or not) and the timings of their exports.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> problem = _example_problem()
    >>> seeds = ladder_seeds(problem, linear_verifier, time.perf_counter(), None, [])
    >>> [seed.detail["target"] for seed, _ in seeds]
    [[1.0, 0.5], [0.9, 0.25]]
    >>> all(seed.feasible for seed, _ in seeds)
    True
    """
    models = problem.models()
    seeds: list[Seeded] = []

    def add(name: str, timing: Timing, factor: float, target: tuple[float, float]) -> None:
        detail = {"seed": name, "target": list(target)}
        poses_for = stretcher(problem, timing)
        found = verified_candidate(
            "retime", problem, poses_for, factor, started, verifier, False, detail
        )
        seeds.append((found, timing.stretched(float(found.detail["stretch"]))))

    for target in ladder:
        tight = targeted(problem, target)

        def passes(poses: PoseTrajectory, tight: PathProblem = tight) -> bool:
            return screen_ok(tight, linear_screen(models, poses))

        found = fastest_capped(tight, passes, shaper)
        if found is not None:
            add("family", found[1], 1.0, target)
    for name, timing, target in timings:
        tight = targeted(problem, target)
        poses_for = stretcher(problem, timing)
        slowed = slowed_until(tight, poses_for, machine_stretch(problem, poses_for(1.0)))
        if slowed is not None:
            add(name, timing, slowed[0], target)
    return seeds


def method_timing(
    problem: PathProblem,
    candidate: PathCandidate,
    shapers: dict[str, Shaper | ShaperFactory | None],
) -> tuple[str, Timing]:
    """The timing of the path under a ``shaped`` or ``tilt`` candidate (its family member,
    stretched as verified), before the axes are shaped or the container tilted.

    Parameters
    ----------
    problem : PathProblem
        Path and limits.
    candidate : PathCandidate
        A ``shaped`` or ``tilt`` candidate (its detail holds ``acceleration_cap_m_s2``,
        ``stretch`` and, for ``tilt``, the timing shaper's name).
    shapers : dict
        The timing shapers by name (``tilt``'s).

    Returns
    -------
    tuple
        (the method's name, the timing).

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem, plan_shaped
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> problem = _example_problem()
    >>> shaped = plan_shaped(problem, linear_verifier)
    >>> name, timing = method_timing(problem, shaped, {})
    >>> name, timing.duration_s < shaped.duration_s
    ('shaped', True)
    """
    detail = candidate.detail
    shaper = None if candidate.method == "shaped" else shapers[detail["shaper"]]
    member = family_member(problem, float(detail["acceleration_cap_m_s2"]), shaper)
    return candidate.method, member.stretched(float(detail["stretch"]))


__all__ = ["TARGET_LADDER", "ladder_seeds", "method_timing", "plan_uniform", "targeted"]
