"""What to plan: machine and slosh limits, the problem, and the outcome of one method."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field, replace
from typing import Any

from sloshkit.errors import require_in_range, require_positive
from sloshkit.model.modal import SloshModel
from sloshkit.motion.profile import Motion

PAPER_LAWS: tuple[str, ...] = ("trapezoidal", "cubic", "quintic", "septic")


SHAPERS: tuple[str, ...] = ("zv", "zvd", "ei", "zv2")


#: Relative margin the searches keep from each slosh limit, so that the sampled export (which
#: the verification simulates) still meets it.
SEARCH_MARGIN = 0.01


@dataclass(frozen=True)
class MachineLimits:
    """Machine limits (SI).

    Parameters
    ----------
    max_velocity_m_s : float
        Velocity limit [m/s].
    max_acceleration_m_s2 : float
        Acceleration limit [m/s^2].
    max_jerk_m_s3 : float
        Jerk limit [m/s^3].

    Examples
    --------
    >>> from sloshkit import MachineLimits
    >>> MachineLimits(1.0, 5.0, 200.0).max_jerk_m_s3
    200.0
    """

    max_velocity_m_s: float
    max_acceleration_m_s2: float
    max_jerk_m_s3: float

    def __post_init__(self) -> None:
        require_positive("vmax", self.max_velocity_m_s, "m/s")
        require_positive("amax", self.max_acceleration_m_s2, "m/s^2")
        require_positive("jmax", self.max_jerk_m_s3, "m/s^3")


@dataclass(frozen=True)
class SloshLimits:
    """Slosh limits of a plan.

    Parameters
    ----------
    max_angle_rad : float
        Limit on the first-mode angle during the move [rad].
    max_residual_rad : float
        Limit on its residual amplitude after the move [rad].
    max_wall_elevation_m : float, optional
        Limit on the wall elevation during the move [m].
    robustness : float
        Relative frequency band (e.g. 0.1 for +-10 %) over which the limits must hold.

    Examples
    --------
    >>> import math
    >>> from sloshkit import SloshLimits
    >>> SloshLimits(math.radians(5), math.radians(0.5), robustness=0.1).robustness
    0.1
    """

    max_angle_rad: float
    max_residual_rad: float
    max_wall_elevation_m: float | None = None
    robustness: float = 0.0

    def __post_init__(self) -> None:
        require_positive("max_angle", self.max_angle_rad, "rad")
        require_positive("max_residual", self.max_residual_rad, "rad")
        if self.max_wall_elevation_m is not None:
            require_positive("max_wall_elevation", self.max_wall_elevation_m, "m")
        require_in_range("robustness", self.robustness, 0.0, 0.5)


@dataclass(frozen=True)
class PlanProblem:
    """What to plan.

    Parameters
    ----------
    distance_m : float
        Travel distance [m].
    machine : MachineLimits
        Machine limits.
    slosh : SloshLimits
        Slosh limits.
    model : SloshModel
        The equivalent model.
    sample_period_s : float
        The controller's sample period [s] (the export and its verification).
    max_duration_s : float, optional
        Longest acceptable duration [s].
    nonlinear : bool
        Verify with the large-angle pendulums.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> problem = sk.PlanProblem(
    ...     0.1,
    ...     sk.MachineLimits(1.0, 5.0, 200.0),
    ...     sk.SloshLimits(max_angle_rad=0.1, max_residual_rad=0.01),
    ...     model,
    ... )
    >>> [round(m.modes[0].frequency_hz, 3) for m in problem.models()]
    [4.72]
    """

    distance_m: float
    machine: MachineLimits
    slosh: SloshLimits
    model: SloshModel
    sample_period_s: float = 4e-3
    max_duration_s: float | None = None
    nonlinear: bool = False

    def __post_init__(self) -> None:
        require_positive("distance", self.distance_m, "m")
        require_in_range("sample_period", self.sample_period_s, 1e-5, 0.1, "s")
        if self.max_duration_s is not None:
            require_positive("max_duration", self.max_duration_s, "s")

    def models(self) -> list[SloshModel]:
        """The model at the band's low edge, nominal and high edge (all modes scaled)."""
        band = self.slosh.robustness
        if band == 0.0:
            return [self.model]
        return [scale_frequencies(self.model, factor) for factor in (1.0 - band, 1.0, 1.0 + band)]


def scale_frequencies(model: SloshModel, factor: float) -> SloshModel:
    """``model`` with every mode's frequency multiplied by ``factor``.

    Parameters
    ----------
    model : SloshModel
        The equivalent model.
    factor : float
        Frequency factor (e.g. 0.9 and 1.1 for the edges of a +-10 % band).

    Returns
    -------
    SloshModel
        The same model, every omega scaled (lengths, masses and damping unchanged).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> round(scale_frequencies(model, 1.1).modes[0].frequency_hz / model.modes[0].frequency_hz, 6)
    1.1
    """
    modes = tuple(replace(mode, omega_rad_s=mode.omega_rad_s * factor) for mode in model.modes)
    return replace(model, modes=modes)


class PlanStatus(enum.Enum):
    """Outcome of one method: ``FEASIBLE`` (verified), ``INFEASIBLE`` (a motion that violates
    a limit) or ``FAILED`` (no motion).

    Parameters
    ----------
    value : str
        ``feasible``, ``infeasible`` or ``failed``.
    names, module, qualname, type, start, boundary : optional
        The arguments of Python's functional `enum.Enum` API (not used here).

    Returns
    -------
    PlanStatus

    Examples
    --------
    >>> PlanStatus("feasible") is PlanStatus.FEASIBLE
    True
    """

    FEASIBLE = "feasible"
    INFEASIBLE = "infeasible"
    FAILED = "failed"


@dataclass(frozen=True)
class Verification:
    """Metrics of a sampled export re-simulated (worst over the robustness band).

    Parameters
    ----------
    duration_s : float
        Move duration [s].
    peak_angle_rad, residual_angle_rad : float
        Peak first-mode angle during the move and residual amplitude after it [rad].
    peak_wall_elevation_m : float
        Peak wall elevation (every mode) [m].
    peak_velocity_m_s, peak_acceleration_m_s2, peak_jerk_m_s3 : float
        Machine peaks (the jerk is inf when the acceleration jumps).
    end_error_m : float
        Distance from the target at the end [m].
    violations : tuple of str
        One line per violated limit.

    Returns
    -------
    Verification

    Examples
    --------
    >>> Verification(1.0, 0.01, 0.001, 0.001, 1.0, 5.0, 100.0, 0.0, ()).feasible
    True
    """

    duration_s: float
    peak_angle_rad: float
    residual_angle_rad: float
    peak_wall_elevation_m: float
    peak_velocity_m_s: float
    peak_acceleration_m_s2: float
    peak_jerk_m_s3: float
    end_error_m: float
    violations: tuple[str, ...]

    @property
    def feasible(self) -> bool:
        """True when no limit is violated."""
        return not self.violations


@dataclass(frozen=True, eq=False)
class Candidate:
    """One method's best motion, its verification and its compute time.

    Parameters
    ----------
    method : str
        The method's name (``quintic``, ``shaped-zv``, ``optimal``, ``optimal-smooth``, ...).
    status : PlanStatus
        Verified, violating or failed.
    motion : Motion, optional
        The motion (None when the method failed).
    verification : Verification, optional
        Its re-simulated metrics.
    compute_time_s : float
        Wall-clock time of the method [s].
    message : str
        ``verified``, the violations or why it failed.
    detail : dict
        Method-specific keys (merged into `to_dict`).

    Returns
    -------
    Candidate

    Examples
    --------
    >>> Candidate("optimal", PlanStatus.FAILED, message="no motion").duration_s
    inf
    """

    method: str
    status: PlanStatus
    motion: Motion | None = None
    verification: Verification | None = None
    compute_time_s: float = 0.0
    message: str = ""
    detail: dict[str, Any] = field(default_factory=dict)

    @property
    def feasible(self) -> bool:
        """Verified to meet every limit."""
        return self.status is PlanStatus.FEASIBLE

    @property
    def duration_s(self) -> float:
        """Move duration [s] (inf without a motion)."""
        return self.motion.duration_s if self.motion is not None else math.inf

    def to_dict(self) -> dict[str, Any]:
        """The plan command's keys for this candidate."""
        check = self.verification
        return {
            "method": self.method,
            "duration_s": None if self.motion is None else self.duration_s,
            "peak_angle_deg": None if check is None else math.degrees(check.peak_angle_rad),
            "residual_angle_deg": None if check is None else math.degrees(check.residual_angle_rad),
            "peak_wall_elevation_m": None if check is None else check.peak_wall_elevation_m,
            "peak_velocity_m_s": None if check is None else check.peak_velocity_m_s,
            "peak_acceleration_m_s2": None if check is None else check.peak_acceleration_m_s2,
            # JSON has no infinity: unbounded jerk (acceleration jumps) is null.
            "peak_jerk_m_s3": None
            if check is None or not math.isfinite(check.peak_jerk_m_s3)
            else check.peak_jerk_m_s3,
            "feasible": self.feasible,
            "violations": [] if check is None else list(check.violations),
            "compute_time_s": self.compute_time_s,
            "message": self.message,
            **self.detail,
        }
