"""Verification and results of the 3-D path planner: `verify`, candidates, the stretch loop.

Every candidate export is verified (`verify`, the nonlinear 3-D model, or
a verifier wrapping it, e.g. with a robot's joint-speed check); when the verification fails
only on limits that a slower copy of the same export meets (slosh heights, Cartesian and
angular peaks, joint speeds), the export is stretched uniformly in time by the excess and
verified again, at most `ATTEMPTS` times (`verified_candidate`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.limits import (
    kinematics,
    machine_stretch,
    machine_violations,
    path_deviation,
)
from sloshkit.plan.path.problem import PathProblem
from sloshkit.plan.path.screen import linear_screen
from sloshkit.results import ResultMixin

FloatArray = NDArray[np.float64]
#: Verifications of one candidate: the first and up to three stretched re-tries.
ATTEMPTS = 4
#: Violations (by their leading words) that a uniform stretch in time reduces.
STRETCHABLE = (
    "peak slosh",
    "residual slosh",
    "surface",
    "velocity",
    "acceleration",
    "jerk",
    "angular velocity",
    "angular acceleration",
    "joint speed",
)


@dataclass(frozen=True)
class Verification:
    """Nonlinear 3-D simulation of an export (worst over the band) and the limit checks.

    Parameters
    ----------
    peak_height_m : float
        Peak slosh height [m].
    residual_height_m : float
        Residual slosh height [m].
    peak_tilt_rad : float
        Largest tilt of the container axis from vertical [rad].
    max_path_deviation_m : float
        Largest distance of the export from the path [m].
    violations : tuple of str
        The limits broken (empty: feasible).
    time_s : ndarray
        Times of the nominal model's slosh height (for figures) [s].
    height_m : ndarray
        The nominal model's slosh height over time [m].
    required_stretch : float
        A uniform slow-down the verifier estimates for limits outside the slosh and Cartesian
        ones (a robot's joint speeds); 1 when none.
    peak_slosh_angle_rad : float
        The first mode's largest pendulum angle (the free surface's slope at the wall) [rad]:
        above `sloshkit.sim.simulate.LARGE_ANGLE_DEG` the model is outside small-amplitude
        theory.

    Examples
    --------
    >>> Verification(0.01, 0.001, 0.0, 0.0, ()).feasible
    True
    """

    peak_height_m: float
    residual_height_m: float
    peak_tilt_rad: float
    max_path_deviation_m: float
    violations: tuple[str, ...]
    time_s: FloatArray = field(default_factory=lambda: np.empty(0))
    height_m: FloatArray = field(default_factory=lambda: np.empty(0))
    required_stretch: float = 1.0
    peak_slosh_angle_rad: float = 0.0

    @property
    def feasible(self) -> bool:
        """True when no limit is broken."""
        return not self.violations


def verify(problem: PathProblem, poses: PoseTrajectory, tilted: bool = False) -> Verification:
    """Simulate the export with the nonlinear 3-D model (all modes, every band frequency) and
    check the slosh, Cartesian, angular and tilt limits.

    The slosh height is `sloshkit.sim.spatial.simulate_spatial`'s peak slosh height (the
    largest free-surface elevation at the wall, over the circumference) and its residual
    slosh height after the move; the surface angle its first-mode deflection. The export is
    simulated twice, with exact differentiation of the poses and with the default smoothing
    filter that ``simulate --pose-file`` uses, and the worse of the two counts.

    Parameters
    ----------
    problem : PathProblem
        Limits and model.
    poses : PoseTrajectory
        The export.
    tilted : bool
        Whether the tilt limit applies.

    Returns
    -------
    Verification

    References
    ----------
    `sloshkit.sim.spatial` (the 3-D spherical-pendulum model and its sources).

    Examples
    --------
    >>> from sloshkit.plan.path.planner import _example_problem
    >>> from sloshkit.plan.path.retime import family_member
    >>> from sloshkit.plan.path.problem import sample_path
    >>> problem = _example_problem()
    >>> poses = sample_path(problem.path, family_member(problem, 10.0, None), 0.01)
    >>> verify(problem, poses).violations[0][:17]
    'peak slosh height'
    """
    import warnings

    from sloshkit.errors import ValidityWarning
    from sloshkit.motion.pose_kinematics import DEFAULT_CUTOFF_HZ
    from sloshkit.sim.spatial import simulate_spatial

    peak = residual = angle = 0.0
    series: tuple[FloatArray, FloatArray] = (np.empty(0), np.empty(0))
    models = problem.models()
    for index, model in enumerate(models):
        for cutoff in (None, DEFAULT_CUTOFF_HZ):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                response = simulate_spatial(model, poses, nonlinear=True, cutoff_hz=cutoff)
            peak = max(peak, float(response.peak_slosh_height_m))
            residual = max(residual, float(response.residual_slosh_height_m))
            angle = max(angle, float(response.peak_angle_rad))
            if cutoff is None and index == len(models) // 2:
                series = (response.time_s, response.slosh_height_m)
    slosh = problem.slosh
    violations = machine_violations(problem, poses, tilted)
    if peak > slosh.max_height_m:
        violations.append(f"peak slosh height {peak * 1e3:.4g} > {slosh.max_height_m * 1e3:.4g} mm")
    if residual > slosh.max_residual_height_m:
        violations.append(
            f"residual slosh height {residual * 1e3:.4g} > "
            f"{slosh.max_residual_height_m * 1e3:.4g} mm"
        )
    if slosh.max_surface_angle_rad is not None and angle > slosh.max_surface_angle_rad:
        violations.append(
            f"surface angle {math.degrees(angle):.4g} > "
            f"{math.degrees(slosh.max_surface_angle_rad):.4g} deg"
        )
    end = problem.path.position(problem.path.length_m)
    if float(np.linalg.norm(poses.position_m[-1] - end)) > 1e-6:
        violations.append("does not end on the path's last pose")
    return Verification(
        peak,
        residual,
        kinematics(poses)["tilt"],
        path_deviation(problem.path, poses),
        tuple(violations),
        *series,
        peak_slosh_angle_rad=angle,
    )


Verifier = Callable[[PathProblem, PoseTrajectory, bool], Verification]


@runtime_checkable
class JointSpeedCheck(Protocol):
    """A verifier that also checks an arm's joint speeds, and lends the path program the
    joints along the path (`sloshkit.export.path_robot.RobotVerifier`): the program then
    limits the joint speeds itself instead of leaving them to a uniform stretch.

    Examples
    --------
    >>> isinstance(verify, JointSpeedCheck)
    False
    """

    def joint_positions(self, poses: PoseTrajectory) -> FloatArray:
        """The arm's joints (n, dof) [rad] at the poses, as the export solves them; raises
        `sloshkit.errors.InputError` when the IK fails."""
        ...

    @property
    def joint_speed_limits_rad_s(self) -> FloatArray:
        """Each joint's speed limit [rad/s]."""
        ...


@dataclass(frozen=True, eq=False)
class PathCandidate:
    """One method's best export, its verification and its compute time.

    Parameters
    ----------
    method : str
        ``retime``, ``shaped``, ``tilt`` or ``uniform``.
    poses : PoseTrajectory or None
        The sampled export (None when the method found nothing).
    verification : Verification or None
        Its verification.
    compute_time_s : float
        Wall time the method took [s].
    message : str
        ``verified`` or the reason it is not feasible.
    detail : dict
        Method-specific figures (acceleration cap, shaper, stretch, ...).

    Examples
    --------
    >>> PathCandidate("retime", None, None, 0.1, "nothing found").feasible
    False
    """

    method: str
    poses: PoseTrajectory | None
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
            "peak_slosh_angle_deg": (
                None if check is None else math.degrees(check.peak_slosh_angle_rad)
            ),
            "max_path_deviation_m": None if check is None else check.max_path_deviation_m,
            "feasible": self.feasible,
            "violations": [] if check is None else list(check.violations),
            "compute_time_s": self.compute_time_s,
            "message": self.message,
            **self.detail,
        }


@dataclass(frozen=True, eq=False)
class PathPlanResult(ResultMixin):
    """The chosen export and every candidate tried (``columns``: the chosen pose export).

    Parameters
    ----------
    problem : PathProblem
        The problem solved.
    chosen : PathCandidate or None
        The fastest feasible candidate (the fastest at all when none is feasible).
    candidates : tuple of PathCandidate
        Every method tried (and ``uniform`` with a reference timing).

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, SpatialSloshLimits
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(1.0, 5.0, 50.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> PathPlanResult(problem, None, ()).to_dict()["feasible"]
    False
    """

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
            "peak_slosh_angle_deg": chosen.get("peak_slosh_angle_deg"),
            "max_path_deviation_m": chosen.get("max_path_deviation_m"),
            "feasible": self.feasible,
            "candidates": [c.to_dict() for c in self.candidates],
        }

    def columns(self) -> dict[str, FloatArray]:
        """The chosen export as pose-file columns (``t,x,y,z,qx,qy,qz,qw``, SI)."""
        if self.chosen is None or self.chosen.poses is None:
            raise InputError("plan", "infeasible", "no trajectory to export")
        return self.chosen.poses.columns()


def verified_candidate(
    method: str,
    problem: PathProblem,
    poses_for: Callable[[float], PoseTrajectory],
    factor: float,
    started: float,
    verifier: Verifier,
    tilted: bool,
    detail: dict[str, Any],
) -> PathCandidate:
    """Verify ``poses_for(factor)``; while it fails only on stretchable limits (`STRETCHABLE`)
    stretch it by the largest excess and verify again (`ATTEMPTS` in all).

    Parameters
    ----------
    method : str
        The candidate's name.
    problem : PathProblem
        Limits.
    poses_for : callable
        The export stretched uniformly in time by a factor.
    factor : float
        First stretch tried.
    started : float
        ``time.perf_counter()`` when the method started (for its compute time).
    verifier : callable
        (problem, poses, tilted) -> Verification.
    tilted : bool
        Whether the tilt limit applies.
    detail : dict
        Figures to report (the final ``stretch`` is added).

    Returns
    -------
    PathCandidate

    Examples
    --------
    >>> import time
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.search import stretcher
    >>> from sloshkit.plan.path.retime import family_member
    >>> from sloshkit.plan.path.problem import CartesianLimits, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(2.0, 10.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), model, sample_period_s=0.01)
    >>> poses_for = stretcher(problem, family_member(problem, 10.0, None))
    >>> found = verified_candidate("x", problem, poses_for, 1.0, time.perf_counter(),
    ...                            linear_verifier, False, {})
    >>> found.feasible, found.detail["stretch"] > 1.0
    (True, True)
    """
    check: Verification | None = None
    poses = poses_for(factor)
    for attempt in range(ATTEMPTS):
        check = verifier(problem, poses, tilted)
        if check.feasible or not _stretchable(check) or attempt == ATTEMPTS - 1:
            break
        # the candidate keeps the last verified export and its stretch
        factor *= _required_stretch(problem, poses, check) * 1.005
        poses = poses_for(factor)
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


def _stretchable(check: Verification) -> bool:
    return all(v.startswith(STRETCHABLE) for v in check.violations)


def _required_stretch(problem: PathProblem, poses: PoseTrajectory, check: Verification) -> float:
    """Uniform stretch c >= 1 that brings every stretchable peak within its limit: slosh
    heights taken as quadratic in the accelerations (c^-2), speeds c^-1, accelerations c^-2,
    jerks c^-3, joint speeds as the verifier estimates (``required_stretch``)."""
    slosh = problem.slosh
    excess = max(
        check.peak_height_m / slosh.max_height_m,
        check.residual_height_m / slosh.max_residual_height_m,
        1.0,
    )
    return max(math.sqrt(excess), machine_stretch(problem, poses), check.required_stretch)


def linear_verifier(problem: PathProblem, poses: PoseTrajectory, tilted: bool) -> Verification:
    """A verification with the linear screen instead of the nonlinear model (for tests and
    examples of the search logic only; the CLI never calls a plan feasible with it).

    Parameters
    ----------
    problem : PathProblem
        Limits and model.
    poses : PoseTrajectory
        The export.
    tilted : bool
        Whether the tilt limit applies.

    Returns
    -------
    Verification

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.motion.laws import s_curve
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, SpatialSloshLimits, sample_path
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(2.0, 10.0, 100.0),
    ...                       SpatialSloshLimits(0.001, 0.001), model, sample_period_s=0.01)
    >>> poses = sample_path(path, s_curve(0.3, 1.0, 3.0, 30.0), 0.01)
    >>> linear_verifier(problem, poses, False).violations
    ('peak slosh height', 'residual slosh height')
    """
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
    "ATTEMPTS",
    "JointSpeedCheck",
    "PathCandidate",
    "PathPlanResult",
    "Verification",
    "Verifier",
    "linear_verifier",
    "verified_candidate",
    "verify",
]
