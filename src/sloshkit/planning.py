"""Plan the fastest rest-to-rest move that keeps the slosh within limits.

Methods (all verified the same way, see `verify`):

- the seed paper's laws (``trapezoidal``, ``cubic``, ``quintic``, ``septic``) at their shortest
  duration that meets the limits, found by a scan on the fast path and a bisection;
- ``shaped``: a time-optimal jerk-limited S-curve (ruckig) convolved with an input shaper (ZV,
  ZVD, EI on the first mode, or ZV on modes 1 and 2), whose acceleration and jerk limits are
  searched so that the shaped move meets every limit (a vectorised grid, then a bisection);
- ``optimal``: minimum-time control by direct multiple shooting in casadi/IPOPT (jerk as the
  control, piecewise constant; states position, velocity, acceleration and every mode's angle
  and rate, for each frequency of the robustness band), with the slosh limits as path
  constraints and the residual amplitude as a terminal constraint, warm-started from the best
  fast method; linear or nonlinear pendulums (Betts, *Practical Methods for Optimal Control*,
  2nd ed., SIAM (2010) ch. 4);
- ``auto``: all of the above, the fastest that passes verification.

Verification never trusts a planner's internal model: the motion is sampled at the controller's
period, and the exported velocity samples (linear between samples) are simulated again with the
exact discretisation of every mode, for every frequency of the robustness band.
"""

from __future__ import annotations

import enum
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.batch import batch_metrics
from sloshkit.dynamics import free_amplitude, linear_mode_response
from sloshkit.errors import InputError, require_in_range, require_positive
from sloshkit.modal import SloshModel
from sloshkit.motion.laws import Motion, _piecewise_constant_jerk, make_law, s_curve
from sloshkit.motion.shaping import Shaper, make_shaper, shape_motion, zv

FloatArray = NDArray[np.float64]
PAPER_LAWS: tuple[str, ...] = ("trapezoidal", "cubic", "quintic", "septic")
SHAPERS: tuple[str, ...] = ("zv", "zvd", "ei", "zv2")
METHODS: tuple[str, ...] = ("auto", "paper", *PAPER_LAWS, "fast", "shaped", "optimal")
#: Relative margin the searches keep from each slosh limit, so that the sampled export (which
#: the verification simulates) still meets it.
SEARCH_MARGIN = 0.01


@dataclass(frozen=True)
class MachineLimits:
    """Machine limits (SI): velocity [m/s], acceleration [m/s^2], jerk [m/s^3]."""

    max_velocity_m_s: float
    max_acceleration_m_s2: float
    max_jerk_m_s3: float

    def __post_init__(self) -> None:
        require_positive("vmax", self.max_velocity_m_s, "m/s")
        require_positive("amax", self.max_acceleration_m_s2, "m/s^2")
        require_positive("jmax", self.max_jerk_m_s3, "m/s^3")


@dataclass(frozen=True)
class SloshLimits:
    """Slosh limits: first-mode angle during the move, its residual amplitude after it [rad],
    optionally the wall elevation [m]; ``robustness`` is the relative frequency band (e.g. 0.1
    for +-10 %) over which they must hold."""

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
    """What to plan: distance [m], limits, the model, the controller sample period [s] and
    optionally the longest acceptable duration [s]."""

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
    """``model`` with every mode's frequency multiplied by ``factor``."""
    modes = tuple(replace(mode, omega_rad_s=mode.omega_rad_s * factor) for mode in model.modes)
    return replace(model, modes=modes)


class PlanStatus(enum.Enum):
    """Outcome of one method."""

    FEASIBLE = "feasible"
    INFEASIBLE = "infeasible"
    FAILED = "failed"


@dataclass(frozen=True)
class Verification:
    """Metrics of a sampled export re-simulated (worst over the robustness band)."""

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
    """One method's best motion, its verification and its compute time."""

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


# ---------------------------------------------------------------------------------------------
# Export and verification
# ---------------------------------------------------------------------------------------------


def export_samples(motion: Motion, sample_period_s: float) -> dict[str, FloatArray]:
    """Samples at t = k Ts from 0 until the first sample at or after T, at rest on the target
    from T on (columns ``t_s, position_m, velocity_m_s, acceleration_m_s2, jerk_m_s3``)."""
    count = math.ceil(motion.duration_s / sample_period_s - 1e-9)
    t = np.arange(count + 1, dtype=float) * sample_period_s
    jerk = motion.jerk(t)
    jerk[t >= motion.duration_s - 1e-12] = 0.0
    return {
        "t_s": t,
        "position_m": motion.position(t),
        "velocity_m_s": motion.velocity(t),
        "acceleration_m_s2": motion.acceleration(t),
        "jerk_m_s3": jerk,
    }


def verify(motion: Motion, problem: PlanProblem) -> Verification:
    """Re-simulate the sampled export of ``motion`` and check every limit.

    The exported velocity samples are taken as linear between samples (what the exact
    first-order-hold discretisation assumes) and simulated for each model of the band. The
    residual amplitude is taken from the state at the last sample, when the move is over. With
    ``problem.nonlinear`` the exported accelerations drive the large-angle pendulums instead.
    """
    samples = export_samples(motion, problem.sample_period_s)
    velocity = samples["velocity_m_s"]
    ts = problem.sample_period_s
    peak_angle = residual = peak_wall = 0.0
    if problem.nonlinear:
        peak_angle, residual, peak_wall = _verify_nonlinear(samples, problem)
    for model in [] if problem.nonlinear else problem.models():
        wall = np.zeros_like(velocity)
        for row, mode in enumerate(model.modes):
            theta, rate = linear_mode_response(
                velocity, ts, mode.omega_rad_s, mode.damping_ratio, mode.length_m
            )
            wall += mode.wall_elevation_factor_m * theta
            if row == 0:
                peak_angle = max(peak_angle, float(np.max(np.abs(theta))))
                residual = max(
                    residual,
                    float(
                        free_amplitude(theta[-1], rate[-1], mode.omega_rad_s, mode.damping_ratio)
                    ),
                )
        peak_wall = max(peak_wall, float(np.max(np.abs(wall))))
    machine, slosh = problem.machine, problem.slosh
    peaks = {
        "velocity": float(np.max(np.abs(velocity))),
        "acceleration": float(np.max(np.abs(samples["acceleration_m_s2"]))),
        "jerk": motion.peak_jerk_m_s3,
    }
    end_error = abs(float(samples["position_m"][-1]) - problem.distance_m)
    violations = []
    checks = [
        ("peak angle", peak_angle, slosh.max_angle_rad, math.degrees, "deg"),
        ("residual angle", residual, slosh.max_residual_rad, math.degrees, "deg"),
        ("velocity", peaks["velocity"], machine.max_velocity_m_s, float, "m/s"),
        ("acceleration", peaks["acceleration"], machine.max_acceleration_m_s2, float, "m/s^2"),
        ("jerk", peaks["jerk"], machine.max_jerk_m_s3, float, "m/s^3"),
    ]
    if slosh.max_wall_elevation_m is not None:
        checks.append(("wall elevation", peak_wall, slosh.max_wall_elevation_m, float, "m"))
    if problem.max_duration_s is not None:
        checks.append(("duration", motion.duration_s, problem.max_duration_s, float, "s"))
    for name, value, limit, unit_of, unit in checks:
        # 1e-7: the optimiser meets its bounds to solver precision.
        if value > limit * (1.0 + 1e-7):
            violations.append(f"{name} {unit_of(value):.4g} > {unit_of(limit):.4g} {unit}")
    if end_error > 1e-6 * problem.distance_m:
        violations.append(f"ends {end_error:.3g} m from the target")
    return Verification(
        duration_s=motion.duration_s,
        peak_angle_rad=peak_angle,
        residual_angle_rad=residual,
        peak_wall_elevation_m=peak_wall,
        peak_velocity_m_s=peaks["velocity"],
        peak_acceleration_m_s2=peaks["acceleration"],
        peak_jerk_m_s3=peaks["jerk"],
        end_error_m=end_error,
        violations=tuple(violations),
    )


def _verify_nonlinear(
    samples: dict[str, FloatArray], problem: PlanProblem
) -> tuple[float, float, float]:
    """Peak angle, residual and peak wall elevation of the exported acceleration samples
    (cubic spline) with the large-angle pendulums, worst over the band."""
    import warnings

    from sloshkit.dynamics import simulate
    from sloshkit.errors import ValidityWarning
    from sloshkit.motion.laws import from_samples

    motion = from_samples(samples["t_s"], acceleration_m_s2=samples["acceleration_m_s2"])
    peak = residual = wall = 0.0
    for model in problem.models():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            response = simulate(motion, model, "nonlinear", problem.sample_period_s, 0.0)
        peak = max(peak, float(np.max(np.abs(response.angle_rad[0]))))
        residual = max(residual, response.residual_angle_rad)
        wall = max(wall, float(np.max(np.abs(response.wall_elevation_m))))
    return peak, residual, wall


def _candidate(
    method: str, motion: Motion, problem: PlanProblem, started: float, **detail: Any
) -> Candidate:
    check = verify(motion, problem)
    status = PlanStatus.FEASIBLE if check.feasible else PlanStatus.INFEASIBLE
    message = "verified" if check.feasible else "violates " + "; ".join(check.violations)
    return Candidate(method, status, motion, check, time.perf_counter() - started, message, detail)


# ---------------------------------------------------------------------------------------------
# Fast screening of many candidate motions at once
# ---------------------------------------------------------------------------------------------


def _screen(
    velocities: FloatArray, durations: FloatArray, problem: PlanProblem, dt: float
) -> NDArray[np.bool_]:
    """Slosh feasibility of many (samples x cases) velocity histories, with the search margin."""
    keep = np.ones(durations.size, dtype=bool)
    slosh = problem.slosh
    for model in problem.models():
        metrics = batch_metrics(model, velocities, durations, dt)
        keep &= metrics.peak_angle_rad <= slosh.max_angle_rad * (1 - SEARCH_MARGIN)
        keep &= metrics.residual_angle_rad <= slosh.max_residual_rad * (1 - SEARCH_MARGIN)
        if slosh.max_wall_elevation_m is not None:
            keep &= metrics.peak_wall_elevation_m <= slosh.max_wall_elevation_m * (
                1 - SEARCH_MARGIN
            )
    return keep


def _velocity_matrix(
    motions: Sequence[Motion], dt: float, shaper: Shaper | None = None
) -> tuple[FloatArray, FloatArray]:
    """Velocity samples (samples x cases) of each motion, optionally shaped, and durations."""
    extra = 0.0 if shaper is None else shaper.duration_s
    durations = np.array([m.duration_s + extra for m in motions])
    steps = math.ceil(float(durations.max()) / dt - 1e-9) + 2
    t = np.arange(steps, dtype=float) * dt
    matrix = np.zeros((steps, len(motions)))
    delays = np.zeros(1) if shaper is None else shaper.times_s
    amplitudes = np.ones(1) if shaper is None else shaper.amplitudes
    for column, motion in enumerate(motions):
        local = t[:, None] - delays[None, :]
        inside = (local >= 0.0) & (local <= motion.duration_s)
        values = np.zeros_like(local)
        values[inside] = motion.derivative_pp(1)(local[inside])
        matrix[:, column] = values @ amplitudes
    return matrix, durations


def _machine_floor(shape: Motion, limits: MachineLimits) -> float:
    """Shortest duration at which a time-scaled law meets the velocity, acceleration and jerk
    limits (its shape given for T = 1 s)."""
    floors = [
        shape.peak_velocity_m_s / limits.max_velocity_m_s,
        math.sqrt(shape.peak_acceleration_m_s2 / limits.max_acceleration_m_s2),
    ]
    if math.isfinite(shape.peak_jerk_m_s3):
        floors.append((shape.peak_jerk_m_s3 / limits.max_jerk_m_s3) ** (1.0 / 3.0))
    return max(floors)


def plan_paper_law(law: str, problem: PlanProblem, grid: int = 400) -> Candidate:
    """The shortest duration at which a paper law meets the limits (scan, then bisection).

    Laws with acceleration jumps have unbounded jerk: they are reported with the duration that
    meets the other limits, and flagged infeasible under a jerk limit.
    """
    from sloshkit.batch import scaled_velocity_samples, steps_for
    from sloshkit.sweep import unit_duration_shape

    started = time.perf_counter()
    shape = unit_duration_shape(make_law(law, problem.distance_m, duration_s=1.0))
    floor = _machine_floor(shape, problem.machine)
    dt = problem.sample_period_s  # screen on the grid the verification uses
    velocity_pp = shape.derivative_pp(1)
    upper = floor
    for _ in range(6):  # widen the scan until something is feasible
        upper *= 4.0
        durations = np.linspace(floor, upper, grid)
        velocity = scaled_velocity_samples(velocity_pp, durations, dt, steps_for(upper, dt))
        feasible = _screen(velocity, durations, problem, dt)
        if feasible.any():
            break
    else:
        return Candidate(
            law,
            PlanStatus.INFEASIBLE,
            None,
            None,
            time.perf_counter() - started,
            f"no duration up to {upper:.3g} s meets the slosh limits",
        )
    first = int(np.argmax(feasible))
    if first == 0:
        best = float(durations[0])
    else:
        low, high = float(durations[first - 1]), float(durations[first])
        for _ in range(30):
            middle = 0.5 * (low + high)
            single = scaled_velocity_samples(
                velocity_pp, np.array([middle]), dt, steps_for(middle, dt)
            )
            if _screen(single, np.array([middle]), problem, dt)[0]:
                high = middle
            else:
                low = middle
        best = high
    for attempt in range(first, durations.size):
        duration = best if attempt == first else float(durations[attempt])
        if attempt > first and not feasible[attempt]:
            continue
        candidate = _candidate(
            law, make_law(law, problem.distance_m, duration_s=duration), problem, started
        )
        if candidate.feasible or not _only_slosh_violations(candidate):
            return candidate
    return candidate


def _only_slosh_violations(candidate: Candidate) -> bool:
    check = candidate.verification
    return check is not None and all(
        v.startswith(("peak angle", "residual angle", "wall elevation")) for v in check.violations
    )


# ---------------------------------------------------------------------------------------------
# Shaped S-curves
# ---------------------------------------------------------------------------------------------


def shaper_for(name: str, model: SloshModel) -> Shaper:
    """A shaper on the first mode (``zv``, ``zvd``, ``ei``) or ``zv2``: ZV on modes 1 and 2."""
    first = model.modes[0]
    if name == "zv2":
        if len(model.modes) < 2:
            return zv(first.omega_rad_s, first.damping_ratio)
        second = model.modes[1]
        shaper = zv(first.omega_rad_s, first.damping_ratio).convolve(
            zv(second.omega_rad_s, second.damping_ratio)
        )
        return Shaper("zv2", shaper.amplitudes, shaper.times_s)
    return make_shaper(name, first.omega_rad_s, first.damping_ratio)


def plan_shaped(problem: PlanProblem, shapers: Sequence[str] = SHAPERS) -> Candidate:
    """Shaped S-curves: for each shaper, a grid over the S-curve's acceleration and jerk limits
    screened at once on the fast path, then a bisection on the acceleration; the fastest
    verified result."""
    started = time.perf_counter()
    machine = problem.machine
    dt = problem.sample_period_s  # screen on the grid the verification uses
    best: Candidate | None = None
    tried: list[str] = []
    for name in shapers:
        shaper = shaper_for(name, problem.model)
        accelerations = machine.max_acceleration_m_s2 * np.geomspace(1e-3, 1.0, 40)
        jerks = machine.max_jerk_m_s3 * np.array([1.0, 0.2, 0.04])
        bases: list[Motion] = []
        settings: list[tuple[float, float]] = []
        for jerk in jerks:
            for acceleration in accelerations:
                bases.append(
                    s_curve(problem.distance_m, machine.max_velocity_m_s, acceleration, jerk)
                )
                settings.append((acceleration, jerk))
        velocity, durations = _velocity_matrix(bases, dt, shaper)
        feasible = _screen(velocity, durations, problem, dt)
        if not feasible.any():
            tried.append(f"{name}: nothing feasible")
            continue
        index = int(np.argmin(np.where(feasible, durations, np.inf)))
        acceleration, jerk = settings[index]
        # Bisection on the acceleration between the best feasible and the next grid value.
        ratio = float(accelerations[1] / accelerations[0])
        low, high = acceleration, min(machine.max_acceleration_m_s2, acceleration * ratio)
        for _ in range(14):
            if high - low <= 1e-4 * low:
                break
            middle = 0.5 * (low + high)
            base = s_curve(problem.distance_m, machine.max_velocity_m_s, middle, jerk)
            single, duration = _velocity_matrix([base], dt, shaper)
            if _screen(single, duration, problem, dt)[0] and duration[0] <= durations[index] + 1e-9:
                low = middle
            else:
                high = middle
        base = s_curve(problem.distance_m, machine.max_velocity_m_s, low, jerk)
        candidate = _candidate(
            f"shaped-{name}",
            shape_motion(base, shaper),
            problem,
            started,
            shaper=name,
            base_acceleration_m_s2=low,
            base_jerk_m_s3=jerk,
        )
        tried.append(f"{name}: {candidate.duration_s:.4f} s")
        if best is None or (candidate.feasible, -candidate.duration_s) > (
            best.feasible,
            -best.duration_s,
        ):
            best = candidate
    if best is None:
        return Candidate(
            "shaped",
            PlanStatus.INFEASIBLE,
            None,
            None,
            time.perf_counter() - started,
            "no shaped S-curve meets the limits (" + "; ".join(tried) + ")",
        )
    return replace(
        best,
        compute_time_s=time.perf_counter() - started,
        detail={**best.detail, "shapers_tried": tried},
    )


# ---------------------------------------------------------------------------------------------
# Time-optimal control (casadi / IPOPT)
# ---------------------------------------------------------------------------------------------


def plan_optimal(
    problem: PlanProblem,
    warm_start: Motion | None = None,
    nonlinear: bool = False,
    intervals: int | None = None,
    attempts: int = 4,
) -> Candidate:
    """Minimum-time move by direct multiple shooting (RK4, 2 sub-steps, piecewise-constant
    jerk), solved by IPOPT. Path constraints hold at the nodes; if the verified export still
    violates a slosh limit, the limits are tightened by the violation and the problem solved
    again (up to ``attempts`` times)."""
    started = time.perf_counter()
    try:
        import casadi as ca
    except ImportError:  # pragma: no cover - casadi is in the optional extra
        return Candidate(
            "optimal", PlanStatus.FAILED, message="casadi is not installed: pip install casadi"
        )
    if warm_start is None:
        warm_start = plan_shaped(problem, ("zv",)).motion or s_curve(
            problem.distance_m,
            problem.machine.max_velocity_m_s,
            problem.machine.max_acceleration_m_s2,
            problem.machine.max_jerk_m_s3,
        )
    count = intervals or int(
        np.clip(round(warm_start.duration_s / problem.sample_period_s), 60, 240)
    )
    tightening = 1.0
    last: Candidate | None = None
    for attempt in range(attempts):
        solution = _solve_ocp(ca, problem, warm_start, count, nonlinear, tightening)
        if solution is None:
            break
        durations, jerks, stats = solution
        motion = _piecewise_constant_jerk("optimal", [durations] * count, list(jerks))
        motion = Motion("optimal", motion.position_pp)
        candidate = _candidate(
            "optimal",
            motion,
            problem,
            started,
            intervals=count,
            ipopt_status=stats,
            model="nonlinear" if nonlinear else "linear",
            tightening=tightening,
        )
        last = candidate
        if candidate.feasible or not _only_slosh_violations(candidate):
            return candidate
        check = candidate.verification
        assert check is not None
        ratios = [
            check.peak_angle_rad / problem.slosh.max_angle_rad,
            check.residual_angle_rad / problem.slosh.max_residual_rad,
        ]
        if problem.slosh.max_wall_elevation_m is not None:
            ratios.append(check.peak_wall_elevation_m / problem.slosh.max_wall_elevation_m)
        tightening *= 1.0 / max(ratios) * (0.999 - 0.002 * attempt)
        warm_start = motion
    if last is not None:
        return replace(last, compute_time_s=time.perf_counter() - started)
    return Candidate(
        "optimal",
        PlanStatus.FAILED,
        None,
        None,
        time.perf_counter() - started,
        "IPOPT found no solution",
    )


def _solve_ocp(
    ca: Any, problem: PlanProblem, guess: Motion, count: int, nonlinear: bool, tightening: float
) -> tuple[float, FloatArray, str] | None:
    """Build the multiple-shooting NLP with casadi SX expressions and solve it with IPOPT.

    Returns (interval length [s], jerk per interval [m/s^3], IPOPT status) or None.
    """
    models = problem.models()
    modes = [mode for model in models for mode in model.modes]
    first_rows = [sum(len(m.modes) for m in models[:i]) for i in range(len(models))]
    size = len(modes)
    width = 3 + 2 * size
    machine, slosh = problem.machine, problem.slosh
    omega = ca.DM([m.omega_rad_s for m in modes])
    zeta = ca.DM([m.damping_ratio for m in modes])
    length = ca.DM([m.length_m for m in modes])

    state_symbol = ca.SX.sym("x", width)
    jerk_symbol = ca.SX.sym("u")
    step_symbol = ca.SX.sym("h")
    acceleration = state_symbol[2]
    theta = state_symbol[3 : 3 + size]
    rate = state_symbol[3 + size :]
    if nonlinear:
        second = (
            -2 * zeta * omega * rate
            - omega**2 * ca.sin(theta)
            - acceleration / length * ca.cos(theta)
        )
    else:
        second = -2 * zeta * omega * rate - omega**2 * theta - acceleration / length
    derivative = ca.Function(
        "f",
        [state_symbol, jerk_symbol],
        [ca.vertcat(state_symbol[1], acceleration, jerk_symbol, rate, second)],
    )
    state = state_symbol
    sub = step_symbol / 2
    for _ in range(2):  # RK4, two sub-steps per interval
        k1 = derivative(state, jerk_symbol)
        k2 = derivative(state + sub / 2 * k1, jerk_symbol)
        k3 = derivative(state + sub / 2 * k2, jerk_symbol)
        k4 = derivative(state + sub * k3, jerk_symbol)
        state = state + sub / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    advance = ca.Function("F", [state_symbol, jerk_symbol, step_symbol], [state])

    duration = ca.SX.sym("T")
    states = ca.SX.sym("X", width, count + 1)
    controls = ca.SX.sym("U", count)
    step = duration / count
    shooting = advance.map(count)(states[:, :-1], controls.T, ca.repmat(step, 1, count))
    constraints = [ca.vec(states[:, 1:] - shooting)]
    low = [np.zeros(width * count)]
    high = [np.zeros(width * count)]

    def add(expression: Any, lower: float | FloatArray, upper: float | FloatArray) -> None:
        constraints.append(ca.vec(expression))
        n = int(ca.vec(expression).shape[0])
        low.append(np.broadcast_to(np.asarray(lower, dtype=float), (n,)).copy())
        high.append(np.broadcast_to(np.asarray(upper, dtype=float), (n,)).copy())

    for row in first_rows:
        mode = modes[row]
        damped = mode.omega_rad_s * math.sqrt(1 - mode.damping_ratio**2)
        theta_end = states[3 + row, count]
        quadrature = (
            states[3 + size + row, count] + mode.damping_ratio * mode.omega_rad_s * theta_end
        ) / damped
        add(theta_end**2 + quadrature**2, -np.inf, (slosh.max_residual_rad * tightening) ** 2)
    if slosh.max_wall_elevation_m is not None:
        limit = slosh.max_wall_elevation_m * tightening
        for index, model in enumerate(models):
            factors = [mode.wall_elevation_factor_m for mode in model.modes]
            wall = sum(f * states[3 + first_rows[index] + i, :] for i, f in enumerate(factors))
            add(wall, -limit, limit)

    # Bounds on the decision variables: start at rest, end at rest on the target, limits.
    state_low = np.full((width, count + 1), -np.inf)
    state_high = np.full((width, count + 1), np.inf)
    state_low[1, :], state_high[1, :] = -machine.max_velocity_m_s, machine.max_velocity_m_s
    state_low[2, :], state_high[2, :] = (
        -machine.max_acceleration_m_s2,
        machine.max_acceleration_m_s2,
    )
    angle_limit = slosh.max_angle_rad * tightening
    for row in first_rows:
        state_low[3 + row, :], state_high[3 + row, :] = -angle_limit, angle_limit
    state_low[:, 0] = state_high[:, 0] = 0.0
    state_low[0, count] = state_high[0, count] = problem.distance_m
    state_low[1:3, count] = state_high[1:3, count] = 0.0

    variables = ca.vertcat(duration, ca.vec(states), controls)
    variable_low = np.concatenate(
        ([1e-3], state_low.ravel(order="F"), np.full(count, -machine.max_jerk_m_s3))
    )
    variable_high = np.concatenate(
        ([np.inf], state_high.ravel(order="F"), np.full(count, machine.max_jerk_m_s3))
    )
    regularisation = 1e-6 * duration * ca.sumsqr(controls / machine.max_jerk_m_s3) / count
    solver = ca.nlpsol(
        "plan",
        "ipopt",
        {"x": variables, "f": duration + regularisation, "g": ca.vertcat(*constraints)},
        {
            "print_time": False,
            "ipopt": {
                "print_level": 0,
                "sb": "yes",
                "max_iter": 3000,
                "tol": 1e-9,
                "acceptable_tol": 1e-7,
                "bound_relax_factor": 0.0,
            },
        },
    )

    # Warm start from the guess, stretched onto the grid, with its simulated slosh.
    t_guess = np.linspace(0.0, guess.duration_s, count + 1)
    initial_states = np.zeros((width, count + 1))
    initial_states[0] = guess.position(t_guess)
    initial_states[1] = guess.velocity(t_guess)
    initial_states[2] = guess.acceleration(t_guess)
    velocity_guess = initial_states[1]
    for row, mode in enumerate(modes):
        theta_guess, rate_guess = linear_mode_response(
            velocity_guess,
            guess.duration_s / count,
            mode.omega_rad_s,
            mode.damping_ratio,
            mode.length_m,
        )
        initial_states[3 + row] = theta_guess
        initial_states[3 + size + row] = rate_guess
    initial = np.concatenate(
        (
            [guess.duration_s],
            initial_states.ravel(order="F"),
            guess.jerk(0.5 * (t_guess[:-1] + t_guess[1:])),
        )
    )
    result = solver(
        x0=initial,
        lbx=variable_low,
        ubx=variable_high,
        lbg=np.concatenate(low),
        ubg=np.concatenate(high),
    )
    status = str(solver.stats().get("return_status", ""))
    if not solver.stats().get("success", False) and status not in ("Solved_To_Acceptable_Level",):
        return None
    solution = np.asarray(result["x"], dtype=float).ravel()
    return float(solution[0]) / count, solution[-count:], status


# ---------------------------------------------------------------------------------------------
# The planner
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class PlanResult:
    """The chosen motion and every candidate tried."""

    problem: PlanProblem
    chosen: Candidate | None
    candidates: tuple[Candidate, ...]

    @property
    def feasible(self) -> bool:
        """True when some method met every limit."""
        return self.chosen is not None and self.chosen.feasible

    def samples(self) -> dict[str, FloatArray]:
        """The chosen motion sampled at the controller period (see `export_samples`)."""
        if self.chosen is None or self.chosen.motion is None:
            raise InputError("plan", "infeasible", "no motion to export")
        return export_samples(self.chosen.motion, self.problem.sample_period_s)

    def to_csv(self, path: str | Path) -> Path:
        """Write the controller samples, atomically."""
        from sloshkit.io import write_columns_csv

        return write_columns_csv(path, self.samples())

    def to_dict(self) -> dict[str, Any]:
        """The plan command's JSON."""
        chosen = (
            self.chosen.to_dict()
            if self.chosen is not None
            else {"method": None, "feasible": False}
        )
        paper = [c for c in self.candidates if c.method in PAPER_LAWS and c.feasible]
        best_paper = min((c.duration_s for c in paper), default=None)
        return {
            **chosen,
            "sample_period_s": self.problem.sample_period_s,
            "speed_up_over_best_paper_law": None
            if best_paper is None or self.chosen is None or not self.chosen.feasible
            else best_paper / self.chosen.duration_s,
            "candidates": [c.to_dict() for c in self.candidates],
        }

    def plot(self, path: str | Path | None = None) -> Any:
        """Velocity, acceleration and slosh angle of the chosen move and the candidates."""
        from sloshkit.plotting import plot_plan

        return plot_plan(self, path)


def plan(
    problem: PlanProblem,
    method: str = "auto",
    nonlinear_optimal: bool = False,
    progress: Callable[[str], None] | None = None,
) -> PlanResult:
    """Run the requested method(s) and return the fastest verified candidate.

    ``method``: ``auto`` (everything), ``paper`` (the four laws), one law name, ``fast`` (a
    ZV-shaped S-curve only), ``shaped`` (all shapers) or ``optimal`` (warm-started from the
    shaped result).
    """
    if method not in METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(METHODS))
    say = progress or (lambda _: None)
    if nonlinear_optimal and not problem.nonlinear:
        problem = replace(problem, nonlinear=True)  # verify everything with the same model
    candidates: list[Candidate] = []
    laws = PAPER_LAWS if method in ("auto", "paper") else (method,) if method in PAPER_LAWS else ()
    for law in laws:
        say(f"searching the shortest {law} move")
        candidates.append(plan_paper_law(law, problem))
    shaped: Candidate | None = None
    if method == "fast":
        say("searching a ZV-shaped S-curve")
        candidates.append(replace(plan_shaped(problem, ("zv",)), method="fast"))
    if method in ("auto", "shaped", "optimal"):
        say("searching shaped S-curves (ZV, ZVD, EI, two-mode ZV)")
        shaped = plan_shaped(problem)
        if method != "optimal":
            candidates.append(shaped)
    if method in ("auto", "optimal"):
        say("solving the time-optimal control problem (IPOPT)")
        warm = _fastest(candidates + ([shaped] if shaped else []))
        candidates.append(
            plan_optimal(problem, warm.motion if warm else None, nonlinear=nonlinear_optimal)
        )
    chosen = _fastest(candidates)
    if chosen is None:
        chosen = min(candidates, key=lambda c: c.duration_s) if candidates else None
    return PlanResult(problem, chosen, tuple(candidates))


def _fastest(candidates: Sequence[Candidate]) -> Candidate | None:
    feasible = [c for c in candidates if c.feasible and c.motion is not None]
    return min(feasible, key=lambda c: c.duration_s) if feasible else None
