"""The tilted family of the 3-D path planner: tilt compensation of the timing family.

The largest acceleration cap of the timing family (`sloshkit.plan.path.retime`) whose tilted
export (`sloshkit.plan.path.tilt_compensation.tilt_compensated`, the container tilted to the
smoothed apparent gravity of its first mode) passes the linear screen and the tilt and angular
limits, verified (`tilted_family`). It is the ``tilt`` method's plan where that method's
programs, which make the tilt angles variables (`sloshkit.plan.path.optimal`), verify no
tilted plan.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.limits import machine_violations
from sloshkit.plan.path.problem import PathProblem, sample_path
from sloshkit.plan.path.result import PathCandidate, Verifier, verified_candidate, verify
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import (
    fastest_capped,
    lowest_cap_failure,
    stretcher,
    timing_shapers,
)
from sloshkit.plan.path.tilt_compensation import tilt_compensated


def tilt_transform(
    problem: PathProblem,
) -> tuple[Callable[[PoseTrajectory], PoseTrajectory], float]:
    """The tilt compensation of the ``tilt`` method
    (`sloshkit.plan.path.tilt_compensation.tilt_compensated` with the first mode's bob height,
    ``max_tilt_rad`` and ``tilt_centre_height_m``) and its
    smoothing: a fifth of the first mode's period (the tilt's angular acceleration excites the
    liquid; 0.01-0.06 s were compared on a straight move, longer is calmer).

    Parameters
    ----------
    problem : PathProblem
        Limits and model.

    Returns
    -------
    tuple
        (PoseTrajectory -> tilted PoseTrajectory, the smoothing [s]).

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> tilted, smoothing = tilt_transform(_example_problem())
    >>> round(smoothing, 3)
    0.066
    """
    bob = problem.model.modes[0].bob_height_m
    smoothing = 2.0 * math.pi / problem.model.modes[0].omega_rad_s / 5.0

    def tilted(poses: PoseTrajectory) -> PoseTrajectory:
        return tilt_compensated(
            poses, bob, problem.max_tilt_rad, problem.tilt_centre_height_m, smoothing
        )

    return tilted, smoothing


def tilted_family(problem: PathProblem, verifier: Verifier = verify) -> PathCandidate:
    """Tilt compensation of the family: the largest cap whose tilted export passes the screen
    and the tilt and angular limits, verified.

    Parameters
    ----------
    problem : PathProblem
        Path, limits (``max_tilt_rad``, ``tilt_centre_height_m``), model.
    verifier : callable
        Verification of an export.

    Returns
    -------
    PathCandidate
        Method ``tilt``, ``detail["source"]`` ``family``.

    References
    ----------
    Feddema et al. (1997), doi:10.1109/37.569711.

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.result import linear_verifier
    >>> problem = _example_problem()
    >>> found = tilted_family(problem, linear_verifier)
    >>> found.feasible, found.verification.peak_tilt_rad > 0.0
    (True, True)
    """
    started = time.perf_counter()
    models = problem.models()
    tilted, smoothing = tilt_transform(problem)

    def passes(poses: PoseTrajectory) -> bool:
        candidate = tilted(poses)
        return screen_ok(problem, linear_screen(models, candidate)) and not machine_violations(
            problem, candidate, True
        )

    best: tuple[float, float, Callable[[float], PoseTrajectory], str] | None = None
    # The curve shaper is not tried: tilting removes the turning forcing it is for (on the
    # series' paths it never gave a faster tilted plan and cost a third more compute).
    for name, shaper in timing_shapers(problem)[:2]:
        found = fastest_capped(problem, passes, shaper)
        if found is None:
            continue
        cap, member = found
        plain = stretcher(problem, member)
        duration = tilted(plain(1.0)).duration_s
        if best is None or duration < best[0]:
            best = (duration, cap, plain, name)
    if best is None:
        failure = lowest_cap_failure(
            problem,
            lambda member: tilted(sample_path(problem.path, member, problem.sample_period_s)),
            True,
        )
        message = f"no tilted timing meets the limits: at the lowest cap, {failure}"
        return PathCandidate("tilt", None, None, time.perf_counter() - started, message)
    _, cap, plain, shaper_name = best
    detail = {
        "source": "family",
        "acceleration_cap_m_s2": cap,
        "tilt_smoothing_s": smoothing,
        "shaper": shaper_name,
        "rotation_centre_height_m": problem.tilt_centre_height_m,
    }
    return verified_candidate(
        "tilt",
        problem,
        lambda f: tilted(plain(f)),
        1.0,
        started,
        verifier,
        True,
        detail,
    )


__all__ = ["tilt_transform", "tilted_family"]
