"""The 3-D path planner: methods side by side, each verified, the fastest feasible chosen.

All methods use the timing family of `sloshkit.plan.retime` (acceleration-capped time-optimal
speed profile, box filter for the jerk limit, optional ZV/ZVD shaping of the timing):

- ``retime``: the largest acceleration cap whose member passes the linear slosh screen
  (bisection), with and without shaping, the faster one;
- ``shaped``: per-axis input shaping of the members (each Cartesian axis convolved with the
  ZV/ZVD shaper of the first mode, which cancels its residual for every lateral direction), the
  largest cap whose export passes the screen and keeps within ``max_path_deviation_m`` of the
  path (shaping the axes cuts corners; the deviation is measured on the export);
- ``tilt``: tilt compensation (`sloshkit.plan.tilt`) of the members, the largest cap whose
  tilted export passes the screen and the tilt and angular limits;
- ``auto``: all three, the fastest verified.

Every candidate is verified with the nonlinear 3-D model (`sloshkit.plan.spatial.verify`); when
the verified export still exceeds a slosh limit, it is stretched in time by the excess and
verified again (a few times). An optional reference timing (the pose file's own) is slowed
uniformly until the screen passes and reported as the ``uniform`` candidate, the naive fix the
methods are compared with (never chosen).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.plan.retime import (
    Timing,
    axis_shaped_samples,
    fastest_capped,
    first_mode_shaper,
    slowed_until,
    stretcher,
)
from sloshkit.plan.spatial import (
    PathProblem,
    PoseSamples,
    Verification,
    linear_screen,
    machine_violations,
    path_deviation,
    sample_path,
    screen_ok,
    verify,
)
from sloshkit.plan.tilt import tilt_compensated
from sloshkit.results import ResultMixin

FloatArray = NDArray[np.float64]
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
class PathPlanResult(ResultMixin):
    """The chosen export and every candidate tried (``columns``: the chosen pose export)."""

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

    def columns(self) -> dict[str, FloatArray]:
        """The chosen export as pose-file columns (``t,x,y,z,qx,qy,qz,qw``, SI)."""
        if self.chosen is None or self.chosen.poses is None:
            raise InputError("plan", "infeasible", "no trajectory to export")
        return self.chosen.poses.columns()


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


def plan_shaped(problem: PathProblem, verifier: Verifier = verify) -> PathCandidate:
    """Per-axis input shaping (ZV, ZVD with a band) of the family's members, the largest
    acceleration cap whose shaped export passes the screen, the machine limits and the path
    deviation bound (module docstring)."""
    started = time.perf_counter()
    shaper = first_mode_shaper(problem)
    models = problem.models()

    def sampler(member: Timing) -> PoseSamples:
        return axis_shaped_samples(problem.path, member, shaper, problem.sample_period_s)

    def passes(poses: PoseSamples) -> bool:
        return (
            screen_ok(problem, linear_screen(models, poses))
            and not machine_violations(problem, poses, False)
            and path_deviation(problem.path, poses) <= problem.max_path_deviation_m
        )

    found = fastest_capped(problem, passes, None, sampler=sampler)
    if found is None:
        return PathCandidate(
            "shaped",
            None,
            None,
            time.perf_counter() - started,
            "no per-axis shaped timing meets the limits",
        )
    cap, member = found

    def poses_for(factor: float) -> PoseSamples:
        return sampler(member.stretched(factor))

    return _verified(
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
    transcription: bool = True,
    warm_starts: Sequence[Timing] = (),
) -> PathCandidate:
    """The fastest acceleration cap of the family under the slosh screen, then (with
    ``transcription``) the minimum-time transcription warm-started from it (module doc)."""
    started = time.perf_counter()
    models = problem.models()
    best: tuple[float, float, Timing, str] | None = None
    for shaper in (first_mode_shaper(problem), None):
        found = fastest_capped(
            problem, lambda poses: screen_ok(problem, linear_screen(models, poses)), shaper
        )
        if found is None:
            continue
        cap, member = found
        duration = sample_path(problem.path, member, problem.sample_period_s).duration_s
        if best is None or duration < best[0]:
            best = (duration, cap, member, "none" if shaper is None else shaper.name)
    if best is None:
        return PathCandidate(
            "retime",
            None,
            None,
            time.perf_counter() - started,
            "no acceleration cap down to 0.1 % of amax meets the slosh limits",
        )
    duration, cap, member, shaper_name = best
    poses_for = stretcher(problem, member)
    detail: dict[str, Any] = {"acceleration_cap_m_s2": cap, "shaper": shaper_name}
    if transcription:
        warm = min([member, *warm_starts], key=lambda timing: timing.duration_s)
        refined = _transcribed(problem, warm)
        if refined is not None and refined[0].duration_s < duration:
            timing, status = refined
            poses_for = stretcher(problem, timing)
            detail = {**detail, "ipopt_status": status}
    return _verified("retime", problem, poses_for, 1.0, started, verifier, False, detail)


#: Fractions of the peak and residual limits the transcription is solved for: its limits hold
#: at the nodes of an RK4 model, and on the measured TRD path the sampled export exceeded them
#: by 4 % (peak) and 20 % (residual); stretching the solution uniformly does not help (the
#: residual it cancels comes back), and re-solving with tightened limits did not converge.
TRANSCRIPTION_TIGHTENING = (0.95, 0.8)


def _transcribed(problem: PathProblem, warm: Timing) -> tuple[Timing, str] | None:
    """The transcription warm-started from ``warm`` (limits tightened by
    `TRANSCRIPTION_TIGHTENING`); (timing, IPOPT status) when its export passes the linear
    screen and the Cartesian limits, else None."""
    from sloshkit.plan.transcription import optimal_timing

    path = problem.path
    peak, residual = TRANSCRIPTION_TIGHTENING
    solved = optimal_timing(problem, warm, tightening=peak, residual_tightening=residual)
    if solved is None:
        return None
    motion, status = solved
    grid = np.linspace(0.0, motion.duration_s, max(8, math.ceil(motion.duration_s / 5e-4)) + 1)
    timing = Timing.from_samples("retime", grid, np.clip(motion.position(grid), 0, path.length_m))
    poses = sample_path(path, timing, problem.sample_period_s)
    if not screen_ok(problem, linear_screen(problem.models(), poses)) or machine_violations(
        problem, poses, False
    ):
        return None
    return timing, status


def plan_tilt(problem: PathProblem, verifier: Verifier = verify) -> PathCandidate:
    """Tilt compensation of the family, the largest cap that passes every screen."""
    started = time.perf_counter()
    bob = problem.model.modes[0].bob_height_m
    models = problem.models()

    # Smoothing: a fifth of the first mode's period (the tilt's angular acceleration excites
    # the liquid; 0.01-0.06 s were compared on a straight move, longer is calmer).
    smoothing = 2.0 * math.pi / problem.model.modes[0].omega_rad_s / 5.0

    def tilted(poses: PoseSamples) -> PoseSamples:
        return tilt_compensated(
            poses, bob, problem.max_tilt_rad, problem.tilt_centre_height_m, smoothing
        )

    def passes(poses: PoseSamples) -> bool:
        candidate = tilted(poses)
        return screen_ok(problem, linear_screen(models, candidate)) and not machine_violations(
            problem, candidate, True
        )

    best: tuple[float, float, Callable[[float], PoseSamples], str] | None = None
    for shaper in (first_mode_shaper(problem), None):
        found = fastest_capped(problem, passes, shaper)
        if found is None:
            continue
        cap, member = found
        plain = stretcher(problem, member)
        duration = tilted(plain(1.0)).duration_s
        if best is None or duration < best[0]:
            best = (duration, cap, plain, "none" if shaper is None else shaper.name)
    if best is None:
        return PathCandidate(
            "tilt", None, None, time.perf_counter() - started, "no tilted timing meets the limits"
        )
    _, cap, plain, shaper_name = best

    def poses_for(factor: float) -> PoseSamples:
        return tilted(plain(factor))

    detail = {
        "acceleration_cap_m_s2": cap,
        "tilt_smoothing_s": smoothing,
        "shaper": shaper_name,
        "rotation_centre_height_m": problem.tilt_centre_height_m,
    }
    return _verified("tilt", problem, poses_for, 1.0, started, verifier, True, detail)


def plan_uniform(
    problem: PathProblem, reference: Timing, verifier: Verifier = verify
) -> PathCandidate:
    """The reference timing slowed uniformly until the screen passes (the naive fix)."""
    started = time.perf_counter()

    poses_for = stretcher(problem, reference)
    found = slowed_until(problem, poses_for)
    if found is None:
        return PathCandidate(
            "uniform",
            None,
            None,
            time.perf_counter() - started,
            "no uniform stretch up to 64x meets the slosh limits",
        )
    return _verified("uniform", problem, poses_for, found[0], started, verifier, False, {})


def plan_path(
    problem: PathProblem,
    method: str = "auto",
    reference: Timing | None = None,
    progress: Callable[[str], None] | None = None,
    verifier: Verifier = verify,
    transcription: bool = False,
    tilt: bool = True,
) -> PathPlanResult:
    """Plan a slosh-safe timing (and tilt) of ``problem.path``.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    method : str
        ``auto`` (all), ``retime``, ``shaped`` or ``tilt``.
    reference : Timing, optional
        The path's existing timing (e.g. of the pose file it came from): slowed uniformly and
        reported as the ``uniform`` candidate, never chosen.
    progress : callable, optional
        Receives one line per step.
    verifier : callable
        Verification of an export (default: the nonlinear 3-D model, `verify`).
    transcription : bool
        Also try the casadi/IPOPT transcription (`sloshkit.plan.transcription`) warm-started
        from the family (and the reference) for ``retime``; off by default: on the measured
        paths it takes minutes on a loaded 2-core machine and its export rarely passes.
    tilt : bool
        Whether ``auto`` may tilt the container (``method="tilt"`` always does).

    Returns
    -------
    PathPlanResult
        The fastest feasible candidate (or, when none is feasible, the fastest at all).

    References
    ----------
    Bobrow et al. (1985); Singer & Seering (1990); Feddema et al. (1997).

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path import path_from_waypoints
    >>> from sloshkit.plan.spatial import CartesianLimits, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       model, sample_period_s=0.01)
    >>> result = plan_path(problem, "shaped", verifier=linear_verifier)
    >>> result.feasible, result.chosen.method
    (True, 'shaped')
    """
    if method not in PATH_METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(PATH_METHODS))
    say = progress or (lambda _: None)
    candidates: list[PathCandidate] = []
    uniform = None if reference is None else plan_uniform(problem, reference, verifier)
    warm_starts = (
        []
        if uniform is None or uniform.poses is None
        else [
            reference.stretched(float(uniform.detail["stretch"]))  # type: ignore[union-attr]
        ]
    )
    if method in ("auto", "retime"):
        say("retime: fastest acceleration cap under the slosh limits")
        candidates.append(plan_retime(problem, verifier, transcription, warm_starts))
    if method in ("auto", "shaped"):
        say("shaped: per-axis input shaping")
        candidates.append(plan_shaped(problem, verifier))
    if method == "tilt" or (method == "auto" and tilt):
        say("tilt: tilt compensation with re-timing")
        candidates.append(plan_tilt(problem, verifier))
    feasible = [c for c in candidates if c.feasible]
    pool = feasible or [c for c in candidates if c.poses is not None]
    chosen = min(pool, key=lambda c: c.duration_s) if pool else None
    if uniform is not None:
        candidates.append(uniform)
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
    "plan_uniform",
]
