"""The 3-D path planner: methods side by side, each verified, the fastest feasible chosen.

- ``retime``: `sloshkit.plan.retime.optimal_timing` (casadi/IPOPT) warm-started from the
  jerk-limited time-optimal timing without slosh, slowed uniformly until the slosh screen
  passes; when the verified export still exceeds a slosh limit, the limits the solver sees are
  reduced by the excess and the problem solved again (a few times);
- ``shaped``: the time-optimal timing without slosh, convolved with a ZV shaper on the first
  mode (ZVD with a robustness band; Singer & Seering, ASME J. Dyn. Syst. Meas. Control 112
  (1990) 76-82, doi:10.1115/1.2894142) and slowed uniformly until the screen passes: the path
  timing is shaped, so the container stays on the path (``max_path_deviation_m`` is measured);
- ``tilt``: tilt compensation (`sloshkit.plan.tilt`) on the slosh-free and the ``retime``
  timings, each slowed uniformly until the screen and the angular and tilt limits pass;
- ``auto``: all three, the fastest verified.

Every candidate is verified with the nonlinear 3-D model (`sloshkit.plan.spatial.verify`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path as FilePath
from typing import Any

from sloshkit.errors import InputError
from sloshkit.motion.laws import Motion
from sloshkit.plan.retime import (
    cartesian_timing,
    optimal_timing,
    scale_timing,
    slowed_until,
    stretch_until,
)
from sloshkit.plan.spatial import (
    PathProblem,
    PoseSamples,
    Verification,
    linear_screen,
    machine_violations,
    sample_path,
    screen_ok,
    verify,
)
from sloshkit.plan.tilt import tilt_compensated

PATH_METHODS: tuple[str, ...] = ("auto", "retime", "shaped", "tilt")
Verifier = Callable[[PathProblem, PoseSamples, bool], Verification]
#: Re-tries after a verification that fails on slosh only.
ATTEMPTS = 4


@dataclass(frozen=True, eq=False)
class PathCandidate:
    """One method's best export, its verification and its compute time [s]."""

    method: str
    poses: PoseSamples | None
    verification: Verification | None
    compute_time_s: float
    message: str
    detail: dict[str, Any] = field(default_factory=dict)

    @property
    def feasible(self) -> bool:
        """Verified to meet every limit."""
        return self.verification is not None and self.verification.feasible

    @property
    def duration_s(self) -> float:
        """Duration of the export [s] (inf without one)."""
        return math.inf if self.poses is None else self.poses.duration_s

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI, unit-suffixed keys)."""
        check = self.verification
        return {
            "method": self.method,
            "duration_s": None if self.poses is None else self.duration_s,
            "peak_slosh_height_m": None if check is None else check.peak_height_m,
            "residual_slosh_height_m": None if check is None else check.residual_height_m,
            "peak_tilt_deg": None if check is None else math.degrees(check.peak_tilt_rad),
            "max_path_deviation_m": None if check is None else check.max_path_deviation_m,
            "feasible": self.feasible,
            "violations": [] if check is None else list(check.violations),
            "compute_time_s": self.compute_time_s,
            "message": self.message,
            **self.detail,
        }


@dataclass(frozen=True, eq=False)
class PathPlanResult:
    """The chosen export and every candidate tried."""

    problem: PathProblem
    chosen: PathCandidate | None
    candidates: tuple[PathCandidate, ...]

    @property
    def feasible(self) -> bool:
        """True when some method met every limit."""
        return self.chosen is not None and self.chosen.feasible

    def reason(self) -> str:
        """Why no method met the limits (one line per method)."""
        return "; ".join(f"{c.method}: {c.message}" for c in self.candidates)

    def to_dict(self) -> dict[str, Any]:
        """The ``plan --path`` JSON keys."""
        chosen = self.chosen.to_dict() if self.chosen is not None else {}
        return {
            "method": chosen.get("method"),
            "duration_s": chosen.get("duration_s"),
            "peak_slosh_height_m": chosen.get("peak_slosh_height_m"),
            "residual_slosh_height_m": chosen.get("residual_slosh_height_m"),
            "peak_tilt_deg": chosen.get("peak_tilt_deg"),
            "max_path_deviation_m": chosen.get("max_path_deviation_m"),
            "feasible": self.feasible,
            "candidates": [c.to_dict() for c in self.candidates],
        }

    def to_csv(self, path: str | FilePath) -> FilePath:
        """Write the chosen export as a pose file (``t,x,y,z,qx,qy,qz,qw``, SI)."""
        from sloshkit.io import write_columns_csv

        if self.chosen is None or self.chosen.poses is None:
            raise InputError("plan", "infeasible", "no trajectory to export")
        return write_columns_csv(path, self.chosen.poses.columns())


def _verified(
    method: str,
    problem: PathProblem,
    poses_for: Callable[[float], PoseSamples],
    factor: float,
    started: float,
    verifier: Verifier,
    tilted: bool,
    detail: dict[str, Any],
) -> PathCandidate:
    """Verify poses_for(factor); on a slosh-only violation stretch by the excess and retry."""
    check: Verification | None = None
    poses = poses_for(factor)
    for _ in range(ATTEMPTS):
        poses = poses_for(factor)
        check = verifier(problem, poses, tilted)
        if check.feasible or not _slosh_only(check):
            break
        factor *= math.sqrt(_excess(problem, check)) * 1.005
    assert check is not None
    message = "verified" if check.feasible else "violates " + "; ".join(check.violations)
    return PathCandidate(
        method,
        poses,
        check,
        time.perf_counter() - started,
        message,
        {**detail, "stretch": factor},
    )


def _slosh_only(check: Verification) -> bool:
    return all(v.startswith(("peak slosh", "residual slosh", "surface")) for v in check.violations)


def _excess(problem: PathProblem, check: Verification) -> float:
    """Largest ratio of a verified slosh value to its limit (>= 1 when violated)."""
    slosh = problem.slosh
    return max(
        check.peak_height_m / slosh.max_height_m,
        check.residual_height_m / slosh.max_residual_height_m,
        1.0,
    )


def plan_shaped(
    problem: PathProblem, bases: Sequence[Motion], verifier: Verifier = verify
) -> PathCandidate:
    """Shaped path timing (module docstring): the fastest base after shaping and slowing."""
    from sloshkit.motion.shaping import shape_motion, zv, zvd

    started = time.perf_counter()
    first = problem.model.modes[0]
    make = zvd if problem.slosh.robustness > 0 else zv
    shaper = make(first.omega_rad_s, first.damping_ratio)
    best: tuple[float, float, Motion] | None = None
    for base in bases:

        def poses_for(c: float, base: Motion = base) -> PoseSamples:
            return sample_path(
                problem.path, shape_motion(scale_timing(base, c), shaper), problem.sample_period_s
            )

        found = slowed_until(problem, poses_for)
        if found is not None and (best is None or found[1].duration_s < best[0]):
            best = (found[1].duration_s, found[0], base)
    if best is None:
        return PathCandidate("shaped", None, None, time.perf_counter() - started,
                             "no shaped timing up to 64x slower meets the slosh screen")
    _, factor, base = best

    def chosen(c: float) -> PoseSamples:
        return sample_path(
            problem.path, shape_motion(scale_timing(base, c), shaper), problem.sample_period_s
        )

    return _verified("shaped", problem, chosen, factor, started, verifier, False,
                     {"shaper": shaper.name})


def plan_retime(
    problem: PathProblem, bases: Sequence[Motion], verifier: Verifier = verify
) -> tuple[PathCandidate, Motion | None]:
    """Minimum-time timing under the slosh limits (module docstring) and the timing itself."""
    started = time.perf_counter()
    warm: Motion | None = None
    for base in bases:
        found = stretch_until(
            lambda c, base=base: screen_ok(
                problem,
                linear_screen(
                    problem.models(),
                    sample_path(problem.path, scale_timing(base, c), problem.sample_period_s),
                ),
            )
        )
        if found is not None:
            candidate = scale_timing(base, found)
            if warm is None or candidate.duration_s < warm.duration_s:
                warm = candidate
    if warm is None:
        return PathCandidate("retime", None, None, time.perf_counter() - started,
                             "no warm start meets the slosh screen"), None
    tightening = 1.0
    last: PathCandidate | None = None
    timing: Motion | None = None
    for attempt in range(ATTEMPTS):
        solved = optimal_timing(problem, warm, tightening=tightening)
        if solved is None:
            break
        timing, status = solved
        poses = sample_path(problem.path, timing, problem.sample_period_s)
        screen = linear_screen(problem.models(), poses)
        ratio = max(
            screen.peak_height_m / problem.slosh.max_height_m,
            screen.residual_height_m / problem.slosh.max_residual_height_m,
        )
        detail = {"ipopt_status": status, "tightening": tightening, "attempts": attempt + 1}
        if ratio <= 1.0 and not machine_violations(problem, poses, False):
            check = verifier(problem, poses, False)
            last = PathCandidate(
                "retime", poses, check, time.perf_counter() - started,
                "verified" if check.feasible else "violates " + "; ".join(check.violations),
                detail,
            )
            if check.feasible or not _slosh_only(check):
                return last, timing
            ratio = _excess(problem, check)
        tightening *= 0.995 / max(ratio, 1.0 + 1e-3)
        warm = timing
    if last is not None:
        return last, timing
    return PathCandidate("retime", None, None, time.perf_counter() - started,
                         "IPOPT found no timing that passes the screen"), None


def plan_tilt(
    problem: PathProblem, bases: Sequence[Motion], verifier: Verifier = verify
) -> PathCandidate:
    """Tilt compensation on each base timing, slowed until every limit passes the screen."""
    started = time.perf_counter()
    bob = problem.model.modes[0].bob_height_m
    models = problem.models()

    def make(base: Motion) -> Callable[[float], PoseSamples]:
        def poses_for(c: float) -> PoseSamples:
            plain = sample_path(problem.path, scale_timing(base, c), problem.sample_period_s)
            return tilt_compensated(
                plain, bob, problem.max_tilt_rad, problem.tilt_centre_height_m
            )

        return poses_for

    best: tuple[float, float, Callable[[float], PoseSamples]] | None = None
    for base in bases:
        poses_for = make(base)
        found = stretch_until(
            lambda c, poses_for=poses_for: screen_ok(problem, linear_screen(models, poses_for(c)))
            and not machine_violations(problem, poses_for(c), True)
        )
        if found is not None:
            duration = poses_for(found).duration_s
            if best is None or duration < best[0]:
                best = (duration, found, poses_for)
    if best is None:
        return PathCandidate("tilt", None, None, time.perf_counter() - started,
                             "no tilted timing up to 64x slower meets the limits")
    _, factor, poses_for = best
    detail = {"rotation_centre_height_m": problem.tilt_centre_height_m}
    return _verified("tilt", problem, poses_for, factor, started, verifier, True, detail)


def plan_path(
    problem: PathProblem,
    method: str = "auto",
    reference: Motion | None = None,
    progress: Callable[[str], None] | None = None,
    verifier: Verifier = verify,
) -> PathPlanResult:
    """Plan a slosh-safe timing (and tilt) of ``problem.path``.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    method : str
        ``auto`` (all), ``retime``, ``shaped`` or ``tilt``.
    reference : Motion, optional
        An existing timing s(t) of the path (e.g. of the pose file it came from), tried as an
        extra starting point.
    progress : callable, optional
        Receives one line per step.
    verifier : callable
        Verification of an export (default: the nonlinear 3-D model, `verify`).

    Returns
    -------
    PathPlanResult
        The fastest feasible candidate (or the fastest at all when none is feasible).

    References
    ----------
    Betts (2010) ch. 4; Singer & Seering (1990); Feddema et al. (1997).

    Examples
    --------
    >>> METHODS = PATH_METHODS; "tilt" in METHODS
    True
    """
    if method not in PATH_METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(PATH_METHODS))
    say = progress or (lambda _: None)
    say("time-optimal jerk-limited timing without slosh")
    base = cartesian_timing(problem)
    free = optimal_timing(problem, base, slosh_dynamics=False)
    bases = [free[0] if free is not None else base]
    if reference is not None:
        bases.append(reference)
    candidates: list[PathCandidate] = []
    retimed: Motion | None = None
    if method in ("auto", "retime", "tilt"):
        say("retime: minimum-time transcription with the slosh dynamics (IPOPT)")
        retime_candidate, retimed = plan_retime(problem, bases, verifier)
        if method != "tilt":
            candidates.append(retime_candidate)
    if method in ("auto", "shaped"):
        say("shaped: input-shaped path timing")
        candidates.append(plan_shaped(problem, bases, verifier))
    if method in ("auto", "tilt"):
        say("tilt: tilt compensation with re-timing")
        tilt_bases = [*bases, *([retimed] if retimed is not None else [])]
        candidates.append(plan_tilt(problem, tilt_bases, verifier))
    feasible = [c for c in candidates if c.feasible]
    pool = feasible or [c for c in candidates if c.poses is not None]
    chosen = min(pool, key=lambda c: c.duration_s) if pool else None
    return PathPlanResult(problem, chosen, tuple(candidates))


def linear_verifier(problem: PathProblem, poses: PoseSamples, tilted: bool) -> Verification:
    """A verification with the linear screen instead of the nonlinear model (for tests of the
    search logic only; never used to call a plan feasible by the CLI)."""
    from sloshkit.plan.spatial import kinematics, path_deviation

    screen = linear_screen(problem.models(), poses)
    violations = machine_violations(problem, poses, tilted)
    if screen.peak_height_m > problem.slosh.max_height_m:
        violations.append("peak slosh height")
    if screen.residual_height_m > problem.slosh.max_residual_height_m:
        violations.append("residual slosh height")
    return Verification(
        screen.peak_height_m,
        screen.residual_height_m,
        kinematics(poses)["tilt"],
        path_deviation(problem.path, poses),
        tuple(violations),
    )


__all__ = [
    "PATH_METHODS",
    "PathCandidate",
    "PathPlanResult",
    "linear_verifier",
    "plan_path",
    "plan_retime",
    "plan_shaped",
    "plan_tilt",
]
