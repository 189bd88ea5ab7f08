"""The minimum-time timing of a 3-D path on the export grid, by sequential second-order-cone
programming.

The decision variables are the path parameter s_k at every sample t_k = k Ts of the export grid
(k = 0..N, s_0 = 0, s_N = S: the whole path; the samples are the export, `_poses_of`). Every
quantity the verification checks is a function of these samples:

- the Cartesian velocity, acceleration and jerk of the reference point and the container's
  angular velocity and acceleration, by finite differences of the samples with the ends _held at
  rest (as `sloshkit.plan.path_limits.kinematics` measures them);
- the slosh of every mode n of every model of the robustness band: the damped spherical
  pendulum the verification simulates (`sloshkit.sim.spatial`; Abramson, NASA SP-106 (1966)
  ch. 6; Dodge, SwRI (2000) ch. 3), driven by kappa_n g - a_hinge at its hinge in the
  container's non-spinning frame, from rest in the first pose, integrated by the 3-D
  simulation's Runge-Kutta kernel along the sampled drive (`sloshkit.plan.path_pendulums`);
  the wall height |sum_n e_n tan(deflection_n)| at every sample and the residual
  sum_n e_n |[A_n B_n]|_2 (the semi-major axis of each mode's free oscillation) `HOLD`
  samples after the move, scaled back to its end (as `sloshkit.sim.spatial_response.
  SpatialResponse` measures them). On the export this equals `simulate_spatial(...,
  nonlinear=True, cutoff_hz=None)` to the accuracy of the spline differentiation (0.04 % of
  the peak on the test's corner path).

For a fixed N each program linearises these functions around the current samples: the force
derivatives banded, by colouring; the pendulums as the time-varying linear system of one
Runge-Kutta period differentiated along the current track (`path_pendulums.step_jacobians`),
their states variables of banded dynamics rows. Every norm stays an exact second-order cone
(the semi-major axis of a 2 x 2 matrix as half the sum of two norms): the program maximises the
largest common margin sigma of all limits (value <= limit (1 - margin + sigma)) over the
samples within a trust region on their speed change (sequential convex programming: Mao, Szmuk
& Acikmese, IEEE CDC (2016), doi:10.1109/CDC.2016.7798816; Nocedal & Wright, *Numerical
Optimization*, 2nd ed. (2006) §18); solved by Clarabel (Goulart & Chen, arXiv:2405.12762
(2024)). Polyhedral (LP) facets of the 3-D norms let the iterates break the jerk limit in
directions no facet covered, so the norms are cones. The minimum time comes from programs
whose sample period is a variable too, h (1 + epsilon) (free final time by time dilation:
Szmuk & Acikmese, AIAA GNC (2018), doi:10.2514/6.2018-0617), minimising epsilon plus an
exact penalty of the limits still exceeded: first on a grid four times coarser than the
export's (programs a quarter the size; a bracketed search over N finds its start), then on the
export's period from that timing spread by a cubic B-spline, then on the export grid itself
(`_free_time`).

The programs model what the verification simulates without its smoothing filter; the
verification, which also simulates the export through that filter, can still exceed a slosh
limit by a percent or two. The program's limit is then moved by regula falsi (`_next_limit`)
and the search restarts from the last samples on the export's period (`plan_optimal`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import sparse
from scipy.spatial.transform import Rotation

from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.plan.path_pendulums import (
    mode_slope,
    pendulum_track,
    period_jacobian,
    slope_jacobian,
    step_jacobians,
)
from sloshkit.sim.metrics import free_oscillation_components
from sloshkit.sim.spatial_response import ellipse_semi_major

FloatArray = NDArray[np.float64]
#: Relative margin the programs keep from every limit (the export is then verified exactly).
PROGRAM_MARGIN = 2e-3
#: _Samples of rest after the move before its free oscillation is measured (the 3-D
#: simulation's `sloshkit.sim.spatial_response.SpatialResponse.free_amplitudes_rad` waits
#: max(window / 2, 4) + 1 samples for an unsmoothed drive).
HOLD = 5


@dataclass(frozen=True)
class _ProgramLimits:
    """The limits the program imposes (SI), the slosh ones already tightened as asked.

    Parameters
    ----------
    max_velocity_m_s, max_acceleration_m_s2, max_jerk_m_s3 : float
        Cartesian limits of the reference point.
    max_angular_velocity_rad_s, max_angular_acceleration_rad_s2 : float or None
        Angular limits of the container (None: none).
    max_height_m, max_residual_height_m : float
        Linear wall height during the move and residual bound after it [m].
    max_tilt_rad, max_tilt_rate_rad_s, max_tilt_acceleration_rad_s2 : float
        Tilt limits (used only when the program tilts).
    """

    max_velocity_m_s: float
    max_acceleration_m_s2: float
    max_jerk_m_s3: float
    max_angular_velocity_rad_s: float | None
    max_angular_acceleration_rad_s2: float | None
    max_height_m: float
    max_residual_height_m: float
    max_tilt_rad: float = 0.0
    max_tilt_rate_rad_s: float = math.pi
    max_tilt_acceleration_rad_s2: float = math.radians(1000.0)


@dataclass(frozen=True, eq=False)
class _Samples:
    """Path parameter [m] and tilt rotation vector [rad] at samples ``period_s`` apart (the
    export's period, or a dilated one while the duration is free, `_dilated_search`)."""

    s_m: FloatArray
    tilt_rad: FloatArray
    period_s: float

    @property
    def steps(self) -> int:
        """N, the number of sample periods."""
        return int(self.s_m.size - 1)


@dataclass(frozen=True, eq=False)
class _JointMap:
    """An arm's joints along the (untilted) path: q(s) [rad] by the cubic spline through the
    export's IK at ``s_m``, and the joints' speed limits [rad/s]."""

    s_m: FloatArray
    joints_rad: FloatArray
    limits_rad_s: FloatArray

    def spline(self) -> Any:
        from scipy.interpolate import CubicSpline

        return CubicSpline(self.s_m, self.joints_rad, axis=0)


#: Spacing of the path parameter at which the arm's IK is solved for the programs [m].
JOINT_GRID_M = 0.005


def _joint_map(problem: Any, check: Any) -> _JointMap | str:
    """The arm's joints along the path from ``check`` (`sloshkit.plan.path_result.
    JointSpeedCheck`) every `JOINT_GRID_M` (at least 50 points), or the IK's message when it
    fails: the untilted poses are the path's whatever the timing, so no plan can pass."""
    from sloshkit.errors import InputError
    from sloshkit.motion.poses import PoseTrajectory

    length = problem.path.length_m
    count = max(50, math.ceil(length / JOINT_GRID_M) + 1)
    s = np.linspace(0.0, length, count)
    rotation = problem.path.orientation(s)
    poses = PoseTrajectory(np.arange(count) * 1e-3, problem.path.position(s), rotation.as_quat())
    try:
        joints = check.joint_positions(poses)
    except InputError as error:
        return f"robot: {error}"
    return _JointMap(s, joints, np.asarray(check.joint_speed_limits_rad_s, dtype=float))


def _poses_of(path: Any, samples: _Samples, centre_height_m: float) -> tuple[FloatArray, Rotation]:
    """Reference-point positions and container orientations of the samples.

    The tilt rotation R_t = exp([r_x, r_y, 0]) acts on the path's orientation R_p(s) about the
    tilt centre c = (0, 0, h_c) of the container frame: q = R_t R_p, P = p(s) + R_p c - q c
    (the centre stays on the path; `sloshkit.plan.tilt` uses the same convention).
    """
    base = path.orientation(samples.s_m)
    position = path.position(samples.s_m)
    if not np.any(samples.tilt_rad):
        return position, base
    rotvec = np.column_stack((samples.tilt_rad, np.zeros(samples.s_m.size)))
    rotation = Rotation.from_rotvec(rotvec) * base
    if centre_height_m:
        centre = np.array([0.0, 0.0, centre_height_m])
        position = position + base.apply(centre) - rotation.apply(centre)
    return position, rotation


def _with_rest(samples: _Samples) -> _Samples:
    """The samples followed by `HOLD` samples of rest at the last pose."""
    s = np.concatenate((samples.s_m, np.repeat(samples.s_m[-1:], HOLD)))
    tilt = np.concatenate((samples.tilt_rad, np.repeat(samples.tilt_rad[-1:], HOLD, axis=0)))
    return _Samples(s, tilt, samples.period_s)


def _model_drive(model: Any, force: FloatArray) -> tuple[FloatArray, FloatArray]:
    """One band model's drive (modes, K, 3) and rest force (modes, 3) from `_PathProgram.forces`:
    kappa_n g - a_hinge with kappa_n = omega_n^2 L_n / g (`sloshkit.sim.spatial_drive`)."""
    kappa = np.array([m.omega_rad_s**2 * m.length_m / model.gravity_m_s2 for m in model.modes])
    drive = force[:-1] + (kappa - 1.0)[:, None, None] * force[-1][None]
    return drive, kappa[:, None] * force[-1, 0][None]


def _mode_arrays(model: Any) -> tuple[FloatArray, FloatArray, FloatArray]:
    """L_n [m], omega_n [rad/s] and zeta_n of a model's modes."""
    modes = model.modes
    return (
        np.array([m.length_m for m in modes]),
        np.array([m.omega_rad_s for m in modes]),
        np.array([m.damping_ratio for m in modes]),
    )


def _held(values: FloatArray, pad: int) -> FloatArray:
    """``values`` with ``pad`` copies of the first and last rows (at rest before and after)."""
    return np.concatenate((values[:1],) * pad + (values,) + (values[-1:],) * pad)


@dataclass(frozen=True, eq=False)
class _Evaluation:
    """Everything the limits see, for one set of samples.

    ``velocity`` ... ``jerk``: finite differences of the positions (rows for the padded
    grid), ``omega``/``alpha``: angular velocity and acceleration, ``force``: specific force
    per mode and gravity in N (`_PathProgram.forces`), ``wall``: wall height vectors per band
    model (models, N + 1, 2), ``amplitude``: free-oscillation vectors (models, modes, 4) scaled
    by e_n; ``joint``: the arm's joint speeds over their limits (N, dof; empty without an
    arm); ``unit``, ``rate``, ``drive``: each model's pendulum tracks and their drive
    (models, modes, N + 1, 3; `sloshkit.plan.path_pendulums`). N counts the rest samples.
    """

    velocity: FloatArray
    acceleration: FloatArray
    jerk: FloatArray
    omega: FloatArray
    alpha: FloatArray
    force: FloatArray
    wall: FloatArray = field(default_factory=lambda: np.empty(0))
    amplitude: FloatArray = field(default_factory=lambda: np.empty(0))
    joint: FloatArray = field(default_factory=lambda: np.empty(0))
    unit: FloatArray = field(default_factory=lambda: np.empty(0))
    rate: FloatArray = field(default_factory=lambda: np.empty(0))
    drive: FloatArray = field(default_factory=lambda: np.empty(0))


class _PathProgram:
    """The sequential cone programs of one path problem (module docstring).

    Parameters
    ----------
    path : Path
        The geometry.
    models : list of SloshModel
        The band's models (all share the bob heights; only the frequencies differ).
    limits : _ProgramLimits
        Limits, slosh ones as the program should impose them.
    sample_period_s : float
        Export sample period Ts [s].
    tilt : bool
        Whether the tilt angles are variables.
    centre_height_m : float
        Tilt centre above the container bottom [m].
    joints : _JointMap, optional
        An arm's joints along the path: their speeds are limited too.
    """

    def __init__(
        self,
        path: Any,
        models: list[Any],
        limits: _ProgramLimits,
        sample_period_s: float,
        tilt: bool = False,
        centre_height_m: float = 0.0,
        joints: _JointMap | None = None,
    ) -> None:
        self.path, self.models, self.limits = path, models, limits
        self.joints = joints
        self.joint_spline: Any = None if joints is None else joints.spline()
        self.ts, self.tilt, self.centre = sample_period_s, tilt, centre_height_m
        self.modes = models[0].modes
        self.gravity = np.array([0.0, 0.0, -models[0].gravity_m_s2])
        self.programs = 0
        self._kernels: dict[int, list[list[tuple[FloatArray, FloatArray]]]] = {}

    # ----------------------------------------------------------------- evaluation
    def forces(self, samples: _Samples) -> tuple[FloatArray, dict[str, FloatArray]]:
        """Specific force g - a_hinge at each mode's hinge in N, and g itself in N, (modes + 1,
        N + 1, 3) [m/s^2], with the kinematics (`sloshkit.sim.spatial_drive`: a mode whose
        omega_n^2 L_n differs from g adds (kappa_n - 1) times the last row).
        """
        ts = samples.period_s
        position, rotation = _poses_of(self.path, samples, self.centre)
        quaternion = rotation.as_quat()
        padded = _held(position, 2)
        velocity = np.diff(padded, axis=0) / ts
        acceleration = np.diff(velocity, axis=0) / ts
        jerk = np.diff(acceleration, axis=0) / ts
        increments = Rotation.from_quat(quaternion[1:]) * Rotation.from_quat(quaternion[:-1]).inv()
        omega = np.concatenate((np.zeros((1, 3)), increments.as_rotvec() / ts, np.zeros((1, 3))))
        alpha = np.diff(omega, axis=0) / ts
        body = Rotation.from_quat(quaternion[:-1]).inv() * Rotation.from_quat(quaternion[1:])
        spin = np.concatenate(([0.0], np.cumsum(body.as_rotvec()[:, 2])))
        frame = rotation * Rotation.from_rotvec(np.column_stack((0 * spin, 0 * spin, -spin)))
        to_frame = frame.inv()
        axis = rotation.apply([0.0, 0.0, 1.0])
        force = np.empty((len(self.modes) + 1, samples.s_m.size, 3))
        for index, mode in enumerate(self.modes):
            point = _held(position + mode.pivot_height_m * axis, 1)
            hinge = (point[2:] - 2.0 * point[1:-1] + point[:-2]) / ts**2
            force[index] = to_frame.apply(self.gravity - hinge)
        force[-1] = to_frame.apply(self.gravity)
        kinematic = {
            "velocity": velocity,
            "acceleration": acceleration,
            "jerk": jerk,
            "omega": omega,
            "alpha": alpha,
            "position": position,
        }
        return force, kinematic

    def evaluate(self, samples: _Samples) -> _Evaluation:
        """Kinematics, forces, pendulum tracks, wall heights and residual amplitudes."""
        samples = _with_rest(samples)
        force, kinematic = self.forces(samples)
        steps = samples.steps
        count = len(self.modes)
        walls = np.zeros((len(self.models), steps + 1, 2))
        amplitudes = np.zeros((len(self.models), count, 4))
        units = np.zeros((len(self.models), count, steps + 1, 3))
        rates = np.zeros_like(units)
        drives = np.zeros_like(units)
        for m, model in enumerate(self.models):
            drive, rest = _model_drive(model, force)
            unit, rate = pendulum_track(drive, rest, *_mode_arrays(model), samples.period_s)
            units[m], rates[m], drives[m] = unit, rate, drive
            for n, mode in enumerate(model.modes):
                walls[m] += mode.wall_elevation_factor_m * mode_slope(unit[n])
                # the free oscillation HOLD samples after the move (as the 3-D simulation
                # measures its residual), about the rest direction, scaled back to the end
                final = drive[n, -1]
                offset = unit[n, -1, :2] - final[:2] / np.linalg.norm(final)
                cosine, sine = free_oscillation_components(
                    offset, rate[n, -1, :2], mode.omega_rad_s, mode.damping_ratio
                )
                back = math.exp(mode.damping_ratio * mode.omega_rad_s * HOLD * samples.period_s)
                amplitudes[m, n] = (
                    back * mode.wall_elevation_factor_m * np.concatenate((cosine, sine))
                )
        joint = np.empty(0)
        if self.joints is not None:
            # the joints' speeds as differences of the samples, over their limits
            q = self.joint_spline(samples.s_m)
            joint = np.diff(q, axis=0) / (samples.period_s * self.joints.limits_rad_s)
        return _Evaluation(
            kinematic["velocity"],
            kinematic["acceleration"],
            kinematic["jerk"],
            kinematic["omega"],
            kinematic["alpha"],
            force,
            walls,
            amplitudes,
            joint,
            units,
            rates,
            drives,
        )

    def worst(self, evaluation: _Evaluation, samples: _Samples) -> dict[str, float]:
        """Each limited quantity's peak divided by its limit."""
        lim = self.limits
        ratios = {
            "velocity": _peak(evaluation.velocity) / lim.max_velocity_m_s,
            "acceleration": _peak(evaluation.acceleration) / lim.max_acceleration_m_s2,
            "jerk": _peak(evaluation.jerk) / lim.max_jerk_m_s3,
            "peak slosh": _peak(evaluation.wall) / lim.max_height_m,
            "residual slosh": _residual_height(evaluation.amplitude) / lim.max_residual_height_m,
        }
        if evaluation.joint.size:
            ratios["joint speed"] = float(np.max(np.abs(evaluation.joint)))
        if lim.max_angular_velocity_rad_s is not None:
            ratios["angular velocity"] = _peak(evaluation.omega) / lim.max_angular_velocity_rad_s
        if lim.max_angular_acceleration_rad_s2 is not None:
            ratios["angular acceleration"] = (
                _peak(evaluation.alpha) / lim.max_angular_acceleration_rad_s2
            )
        if self.tilt:
            tilt = _held(samples.tilt_rad, 2)
            rate = np.diff(tilt, axis=0) / samples.period_s
            ratios["tilt"] = _peak(samples.tilt_rad) / lim.max_tilt_rad
            ratios["tilt rate"] = _peak(rate) / lim.max_tilt_rate_rad_s
            ratios["tilt acceleration"] = (
                _peak(np.diff(rate, axis=0) / samples.period_s) / lim.max_tilt_acceleration_rad_s2
            )
        return ratios

    # ----------------------------------------------------------------- linearisation
    def jacobians(self, samples: _Samples) -> list[_Bands]:
        """Banded derivatives of the samples' positions, angular velocities and forces with
        respect to each variable block (s, then r_x, r_y with tilt).

        Every quantity at sample k depends on the samples k-1..k+1 only (positions on k, the
        angular velocity on k-1 and k, the forces on k-1..k+1 through the second difference),
        so perturbing every third sample at once separates the bands (Curtis, Powell & Reid,
        IMA J. Appl. Math. 13 (1974) 117-119); central differences. The spin about the axis is
        recomputed: a sample's change moves only its own spin when the axis keeps its direction
        (the increments telescope; holding it fixed rotated N by the yaw change instead).
        """
        samples = _with_rest(samples)
        n = samples.s_m.size
        columns: list[int | None] = [None] + ([0, 1] if self.tilt else [])
        bands = []
        for column in columns:
            step = 1e-7 * max(self.path.length_m, 1.0) if column is None else 1e-7
            force = np.zeros((3, len(self.modes) + 1, n, 3))
            position = np.zeros((n, 3))
            omega = np.zeros((2, n + 1, 3))
            for colour in range(3):
                chosen = np.arange(colour, n, 3)
                plus, minus, width = _perturbed(samples, chosen, column, step, self.path.length_m)
                (fp, kp), (fm, km) = self.forces(plus), self.forces(minus)
                dforce = fp - fm
                position[chosen] = (kp["position"] - km["position"])[chosen] / width[chosen, None]
                domega = kp["omega"] - km["omega"]
                for offset in (-1, 0, 1):
                    k = chosen - offset  # the force at k sees the perturbed sample k + offset
                    k = k[(k >= 0) & (k < n)]
                    force[offset + 1][:, k] = dforce[:, k] / width[k + offset][None, :, None]
                # omega row i (1..n-1) uses samples i-1 and i
                own = chosen[(chosen >= 1) & (chosen <= n - 1)]
                omega[1][own] = domega[own] / width[own, None]
                prev = chosen[chosen + 1 <= n - 1] + 1
                omega[0][prev] = domega[prev] / width[prev - 1, None]
            bands.append(_Bands(position, omega, force))
        return bands

    def iterate(self, samples: _Samples) -> _Iterate:
        """The samples with their exact evaluation and ratios to the limits."""
        evaluation = self.evaluate(samples)
        return _Iterate(samples, evaluation, self.worst(evaluation, samples))


@dataclass(frozen=True, eq=False)
class _Iterate:
    """_Samples, their evaluation and each limited quantity's peak over its limit."""

    samples: _Samples
    evaluation: _Evaluation
    ratios: dict[str, float]

    @property
    def excess(self) -> float:
        """The largest ratio of a quantity to its limit (<= 1: every limit met)."""
        return max(self.ratios.values())

    @property
    def feasible(self) -> bool:
        """Every limit met (to 1e-9)."""
        return self.excess <= 1.0 + 1e-9

    @property
    def reach(self) -> float:
        """s_N [m]."""
        return float(self.samples.s_m[-1])


@dataclass(frozen=True, eq=False)
class _Bands:
    """Derivatives of one variable block: ``position`` (n, 3) d P_k / d x_k, ``omega``
    (2, n + 1, 3) d w_i / d x_{i-1} and d w_i / d x_i, ``force`` (3, modes, n, 2)
    d f_k / d x_{k+o} for o = -1, 0, 1."""

    position: FloatArray
    omega: FloatArray
    force: FloatArray


def _vector_cones(
    conic: _Conic, r_idx: list[Any], c_idx: list[Any], v_idx: list[Any], scaled: Any, keep: float
) -> None:
    """One 4-D cone per row of ``scaled`` (values over their limit, (rows, 3)): the linearised
    vector within keep + sigma, its entries gathered in the index lists."""
    rows = scaled.shape[0]
    b = np.zeros((rows, 4))
    b[:, 0] = keep
    b[:, 1:] = scaled
    conic.add(
        "soc",
        np.concatenate(r_idx),
        np.concatenate(c_idx),
        np.concatenate(v_idx),
        b.ravel(),
        [4] * rows,
    )


def _perturbed(
    samples: _Samples, chosen: Any, column: int | None, step: float, length_m: float
) -> tuple[_Samples, _Samples, FloatArray]:
    """The samples with the ``chosen`` ones moved by +- ``step`` in s (kept on [0, S]: one-sided
    at the ends, where the path is clipped) or in a tilt angle, and each sample's width of the
    difference (plus - minus; 1 where not perturbed)."""
    s_plus, s_minus = samples.s_m.copy(), samples.s_m.copy()
    tilt_plus, tilt_minus = samples.tilt_rad.copy(), samples.tilt_rad.copy()
    width = np.ones(samples.s_m.size)
    if column is None:
        s_plus[chosen] = np.minimum(s_plus[chosen] + step, length_m)
        s_minus[chosen] = np.maximum(s_minus[chosen] - step, 0.0)
        width[chosen] = s_plus[chosen] - s_minus[chosen]
    else:
        tilt_plus[chosen, column] += step
        tilt_minus[chosen, column] -= step
        width[chosen] = 2.0 * step
    period = samples.period_s
    return _Samples(s_plus, tilt_plus, period), _Samples(s_minus, tilt_minus, period), width


def _residual_height(amplitude: FloatArray) -> float:
    """The residual bound of the worst band model: sum_n e_n |M_n|_2 with M_n = [A_n B_n] the
    free oscillation's cosine and sine vectors (its semi-major axis,
    `sloshkit.sim.spatial_response.ellipse_semi_major`), from (models, modes, 4) [m]."""
    semi = ellipse_semi_major(amplitude[..., :2], amplitude[..., 2:])
    return float(np.max(np.sum(semi, axis=1)))


def _peak(values: FloatArray) -> float:
    """Largest Euclidean norm along the last axis."""
    return float(np.max(np.linalg.norm(values, axis=-1))) if values.size else 0.0


#: Finite-difference weights of orders 0..3 (the forward differences of the padded samples).
_WEIGHTS = {0: (1.0,), 1: (-1.0, 1.0), 2: (1.0, -2.0, 1.0), 3: (-1.0, 3.0, -3.0, 1.0)}


#: Relative width of the bracket on N at which the search stops (the smallest feasible N is kept).
SEARCH_TOLERANCE = 2e-3
#: Durations solved per search, at most.
MAX_SEARCH = 14
#: Searches of `plan_optimal`, each with the program's slosh limits moved towards the values
#: at which the verification meets its limits (`_next_limit`), at most.
TIGHTENINGS = 5
#: A verified plan whose peak or residual is within this fraction of its limit ends them.
LIMIT_TOLERANCE = 0.02
#: Weight of the limits' excess sigma against the relative period change while the duration
#: is free (an exact penalty needs more than the multiplier, about 1/2: the duration scales
#: about as the square root of the ratio to a limit).
PENALTY = 10.0


class _Conic:
    """Rows b - A x in a cone, gathered by kind: equalities, inequalities, second-order cones."""

    def __init__(self) -> None:
        self.parts: dict[str, list[tuple[Any, Any, Any, Any]]] = {
            "zero": [],
            "nonneg": [],
            "soc": [],
        }
        self.soc_dims: list[int] = []

    def add(self, kind: str, r: Any, c: Any, v: Any, b: Any, dims: list[int] | None = None) -> None:
        """Rows with local indices r: b_r - sum A_rc x_c in the cone (``dims``: the sizes of
        consecutive second-order cones)."""
        self.parts[kind].append(
            (
                np.asarray(r, dtype=int),
                np.asarray(c, dtype=int),
                np.asarray(v, dtype=float),
                np.asarray(b, dtype=float),
            )
        )
        if dims is not None:
            self.soc_dims += dims

    def assemble(self, columns: int) -> tuple[Any, Any, list[Any]]:
        import clarabel

        rows, cols, vals, rhs, cones = [], [], [], [], []
        offset = 0
        for kind in ("zero", "nonneg", "soc"):
            count = 0
            for r, c, v, b in self.parts[kind]:
                rows.append(r + offset + count)
                cols.append(c)
                vals.append(v)
                rhs.append(b)
                count += b.size
            if count:
                if kind == "zero":
                    cones.append(clarabel.ZeroConeT(count))
                elif kind == "nonneg":
                    cones.append(clarabel.NonnegativeConeT(count))
            offset += count
        cones += [clarabel.SecondOrderConeT(d) for d in self.soc_dims]
        matrix = sparse.coo_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(offset, columns),
        ).tocsc()
        return matrix, np.concatenate(rhs), cones


@dataclass(frozen=True, eq=False)
class _Step:
    """A cone program's samples, its predicted margin sigma and predicted residual ratio."""

    samples: _Samples
    sigma: float
    residual: float


def _cone_step(
    program: _PathProgram,
    samples: _Samples,
    evaluation: Any,
    trust: float,
    residual_trust: float = 1.0,
    dilation_trust: float | None = None,
) -> _Step | None:
    """One cone program around ``samples`` (module docstring), or None when the solver failed.
    ``trust``: the largest change of a step's speed [m/s] (a sample moves by at most 0.02 s
    times it); ``residual_trust``: the largest change of each free-oscillation entry e_n A, e_n B
    over the residual limit (the residual is the most sensitive quantity: a millimetre's shift
    of the samples near the end moves it by millimetres). With ``dilation_trust`` the sample
    period is a variable too, h (1 + epsilon) with |epsilon| <= dilation_trust, and the program
    minimises epsilon + `PENALTY` (sigma_k + sigma_w + sigma_r), each sigma >= 0, instead of
    maximising the margin: an exact penalty of the limits it cannot meet yet (Mao, Szmuk &
    Acikmese (2016)), with one slack for the kinematic limits, one for the wall height and one
    for the residual, so that a limit still exceeded does not loosen the others."""
    import clarabel

    lim, ts = program.limits, samples.period_s
    dilate = dilation_trust is not None
    n = samples.s_m.size
    steps = n - 1
    keep = 1.0 - PROGRAM_MARGIN
    band = program.jacobians(samples)[0]
    derivative = band.position
    unit = lim.max_jerk_m_s3 * ts**3
    sigma = steps
    models, modes = len(program.models), len(program.modes)
    state_base = steps + 1
    last = steps + HOLD  # the pendulums run on through the rest samples after the move
    total = last + 1

    # deviations of the pendulum states x = (u, u') per (model, mode) at samples 1..last
    def state(m: int, k: int, comp: Any, i: Any) -> Any:
        return state_base + ((m * modes + k) * 6 + np.asarray(comp)) * last + (np.asarray(i) - 1)

    t_base = state_base + models * modes * 6 * last
    dilation = t_base + 2 * models * modes  # epsilon's column, when the period is free
    columns = dilation + (3 if dilate else 0)
    # the slacks of the wall heights and of the residual: sigma's own column unless dilated
    wall_sigma, residual_sigma = (dilation + 1, dilation + 2) if dilate else (sigma, sigma)
    conic = _Conic()

    def d(i: Any) -> Any:
        return np.asarray(i) - 1

    # the end sample is fixed: d_N = (S - s_N) / unit -> an equality
    conic.add("zero", [0], [d(steps)], [1.0], [(program.path.length_m - samples.s_m[-1]) / unit])
    # ------------------------------------------------ pendulum dynamics, linearised
    # dx_{k+1} = A_k dx_k + B_k df_k + E_k df_{k+1} (`path_pendulums.step_jacobians`), the
    # force deviations df_j = sum_o G_o[j] d_{j+o} banded (`_PathProgram.jacobians`), x_0 fixed
    period = np.arange(last)
    for m, model in enumerate(program.models):
        lengths, omegas, zetas = _mode_arrays(model)
        a_k, b_k, e_k = step_jacobians(
            evaluation.unit[m], evaluation.rate[m], evaluation.drive[m], lengths, omegas, zetas, ts
        )
        kappa = omegas**2 * lengths / model.gravity_m_s2
        if dilate:
            # x_{k+1} moves with the period directly and through the hinge accelerations
            # (proportional to 1 / h^2: d f_n / d epsilon = 2 (R g - f_n), the gravity row
            # unchanged)
            along = period_jacobian(
                evaluation.unit[m],
                evaluation.rate[m],
                evaluation.drive[m],
                lengths,
                omegas,
                zetas,
                ts,
            )
            pull = 2.0 * (evaluation.force[-1][None] - evaluation.force[:-1])
        for q in range(modes):
            r_list = [period * 6 + row for row in range(6)]
            c_list = [state(m, q, row, period + 1) for row in range(6)]
            v_list = [np.ones(last) for _ in range(6)]
            later = period >= 1
            for row in range(6):
                for col in range(6):
                    r_list.append(period[later] * 6 + row)
                    c_list.append(state(m, q, col, period[later]))
                    v_list.append(-a_k[q, later, row, col])
            for shift, matrix in ((0, b_k[q]), (1, e_k[q])):
                force_at = period + shift
                for o in (-1, 0, 1):
                    gain = (
                        band.force[o + 1][q, force_at]
                        + (kappa[q] - 1.0) * band.force[o + 1][-1, force_at]
                    )
                    coefficient = np.einsum("kac,kc->ka", matrix, gain) * unit
                    sample = force_at + o
                    ok = (sample >= 1) & (sample <= steps)
                    for row in range(6):
                        r_list.append(period[ok] * 6 + row)
                        c_list.append(d(sample[ok]))
                        v_list.append(-coefficient[ok, row])
            if dilate:
                total_change = (
                    along[q]
                    + np.einsum("kac,kc->ka", b_k[q], pull[q, :last])
                    + np.einsum("kac,kc->ka", e_k[q], pull[q, 1 : last + 1])
                )
                for row in range(6):
                    r_list.append(period * 6 + row)
                    c_list.append(np.full(last, dilation))
                    v_list.append(-total_change[:, row])
            conic.add(
                "zero",
                np.concatenate(r_list),
                np.concatenate(c_list),
                np.concatenate(v_list),
                np.zeros(6 * last),
            )
    # ------------------------------------------------ wall cones at every sample 1..last
    moved = np.arange(1, total)
    count = moved.size
    for m, model in enumerate(program.models):
        r_list = [np.arange(count) * 3]
        c_list = [np.full(count, wall_sigma)]
        v_list = [-np.ones(count)]
        wall_b = np.zeros((count, 3))
        wall_b[:, 0] = keep
        wall_b[:, 1:] = evaluation.wall[m, 1:] / lim.max_height_m
        for q, mode in enumerate(model.modes):
            slope = slope_jacobian(evaluation.unit[m, q, 1:])  # (count, 2, 3)
            e = mode.wall_elevation_factor_m / lim.max_height_m
            for row in range(2):
                for comp in range(3):
                    r_list.append(np.arange(count) * 3 + 1 + row)
                    c_list.append(state(m, q, comp, moved))
                    v_list.append(-e * slope[:, row, comp])
        conic.add(
            "soc",
            np.concatenate(r_list),
            np.concatenate(c_list),
            np.concatenate(v_list),
            wall_b.ravel(),
            [3] * count,
        )
    # ------------------------------------------------ residual cones and their sum
    for m, model in enumerate(program.models):
        for q, mode in enumerate(model.modes):
            damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
            sig = mode.damping_ratio * mode.omega_rad_s
            back = math.exp(mode.damping_ratio * mode.omega_rad_s * HOLD * ts)
            e = back * mode.wall_elevation_factor_m / lim.max_residual_height_m
            # |e_n [A_n B_n]|_2 (the semi-major axis) of M = [[a, b], [c, d]] = [A B] is
            # (|(a + d, c - b)| + |(a - d, b + c)|) / 2 (a 2 x 2 matrix is a rotation-scaling
            # plus a reflection-scaling whose scales add: Horn & Johnson, *Matrix Analysis*,
            # 2nd ed. (2013) §7.3): two cones t1, t2, linear in the lateral deviations at
            # `last`, A = du, B = (du' + sig du) / damped (`free_oscillation_components`)
            cols = [int(state(m, q, c, last)) for c in (0, 1, 3, 4)]  # du_x, du_y, du'_x, du'_y
            # a, b, c, d as coefficients of (du_x, du_y, du'_x, du'_y)
            a_, c_ = np.array([e, 0.0, 0.0, 0.0]), np.array([0.0, e, 0.0, 0.0])
            b_ = e * np.array([sig / damped, 0.0, 1.0 / damped, 0.0])
            d_ = e * np.array([0.0, sig / damped, 0.0, 1.0 / damped])
            amp = evaluation.amplitude[m, q] / lim.max_residual_height_m  # A_x, A_y, B_x, B_y
            av, cv, bv, dv = amp
            for cone, (first, second, first_b, second_b) in enumerate(
                ((a_ + d_, c_ - b_, av + dv, cv - bv), (a_ - d_, b_ + c_, av - dv, bv + cv))
            ):
                cone_rows = [0] + [1] * 4 + [2] * 4
                cone_columns = [t_base + 2 * (m * modes + q) + cone, *cols, *cols]
                values = np.concatenate(([-1.0], -first, -second))
                conic.add("soc", cone_rows, cone_columns, values, [0.0, first_b, second_b], [3])
            # the residual's own trust region: |change of each entry| <= residual_trust
            for entry in (a_, b_, c_, d_):
                conic.add(
                    "nonneg",
                    [0] * 4 + [1] * 4,
                    cols + cols,
                    np.concatenate((entry, -entry)),
                    [residual_trust, residual_trust],
                )
        # sum (t1 + t2) / 2 <= keep + sigma
        conic.add(
            "nonneg",
            np.zeros(2 * modes + 1, dtype=int),
            np.concatenate((t_base + 2 * m * modes + np.arange(2 * modes), [residual_sigma])),
            np.concatenate((np.full(2 * modes, 0.5), [-1.0])),
            [keep],
        )
    # ------------------------------------------------ kinematic cones
    for order, values, limit in (
        (1, evaluation.velocity, lim.max_velocity_m_s),
        (2, evaluation.acceleration, lim.max_acceleration_m_s2),
        (3, evaluation.jerk, lim.max_jerk_m_s3),
    ):
        rows = values.shape[0]
        r_idx, c_idx, v_idx = [np.arange(rows) * 4], [np.full(rows, sigma)], [np.full(rows, -1.0)]
        for j, weight in enumerate(_WEIGHTS[order]):
            k = np.clip(np.arange(rows) + j - 2, 0, total - 1)
            moving = (k >= 1) & (k <= steps)
            for c in range(3):
                coefficient = weight / ts**order * derivative[k, c] * unit / limit
                use = moving & (coefficient != 0.0)
                r_idx.append(np.flatnonzero(use) * 4 + 1 + c)
                c_idx.append(d(k[use]))
                v_idx.append(-coefficient[use])
        if dilate:  # a difference of order p scales as h^-p
            for c in range(3):
                r_idx.append(np.arange(rows) * 4 + 1 + c)
                c_idx.append(np.full(rows, dilation))
                v_idx.append(order * values[:, c] / limit)
        _vector_cones(conic, r_idx, c_idx, v_idx, values / limit, keep)
    # ------------------------------------------------ angular velocity and acceleration cones
    angular: tuple[tuple[int, FloatArray, float | None], ...] = (
        (1, evaluation.omega, lim.max_angular_velocity_rad_s),
        (2, evaluation.alpha, lim.max_angular_acceleration_rad_s2),
    )
    for order, values, angular_limit in angular:
        if angular_limit is None:
            continue
        rows = values.shape[0]
        r_idx, c_idx, v_idx = [np.arange(rows) * 4], [np.full(rows, sigma)], [np.full(rows, -1.0)]
        # omega row i = samples i-1 (band slot 0) and i (slot 1); alpha row i = (w_{i+1} - w_i) / T
        terms = [(0, 1.0)] if order == 1 else [(1, 1.0 / ts), (0, -1.0 / ts)]
        for shift, weight in terms:
            w_row = np.arange(rows) + shift
            for slot, sample_shift in ((0, -1), (1, 0)):
                k = w_row + sample_shift
                ok = (w_row >= 1) & (w_row <= total - 1) & (k >= 1) & (k <= steps)
                for c in range(3):
                    coefficient = np.zeros(rows)
                    coefficient[ok] = weight * band.omega[slot][w_row[ok], c] * unit / angular_limit
                    use = ok & (coefficient != 0.0)
                    r_idx.append(np.flatnonzero(use) * 4 + 1 + c)
                    c_idx.append(d(k[use]))
                    v_idx.append(-coefficient[use])
        if dilate:
            for c in range(3):
                r_idx.append(np.arange(rows) * 4 + 1 + c)
                c_idx.append(np.full(rows, dilation))
                v_idx.append(order * values[:, c] / angular_limit)
        _vector_cones(conic, r_idx, c_idx, v_idx, values / angular_limit, keep)
    # ------------------------------------------------ the arm's joint speeds
    if program.joints is not None:
        # (q(s_{k+1}) - q(s_k)) / (h limit) within keep + sigma on both sides, linear in
        # d_k, d_{k+1} through dq/ds; a free period scales it as 1 / h
        slope = program.joint_spline(samples.s_m, 1)[:n] / (ts * program.joints.limits_rad_s)
        joint = evaluation.joint[: n - 1]
        dof = joint.shape[1]
        for sign in (1.0, -1.0):
            rows = np.arange((n - 1) * dof).reshape(n - 1, dof)
            r_idx, c_idx, v_idx = (
                [rows.ravel()],
                [np.full(rows.size, sigma)],
                [np.full(rows.size, -1.0)],
            )
            for shift, weight in ((1, 1.0), (0, -1.0)):
                k = np.arange(n - 1) + shift  # the sample each difference moves with
                ok = (k >= 1) & (k <= steps)
                r_idx.append(rows[ok].ravel())
                c_idx.append(np.repeat(d(k[ok]), dof))
                v_idx.append((sign * weight * slope[k[ok]] * unit).ravel())
            if dilate:
                r_idx.append(rows.ravel())
                c_idx.append(np.full(rows.size, dilation))
                v_idx.append(-(sign * joint).ravel())
            conic.add(
                "nonneg",
                np.concatenate(r_idx),
                np.concatenate(c_idx),
                np.concatenate(v_idx),
                (keep - sign * joint).ravel(),
            )
    # ------------------------------------------------ monotone progress and trust region
    s = samples.s_m
    inner = np.arange(1, n - 1)
    pairs = np.column_stack((d(inner + 1), d(inner))).ravel()
    local = np.repeat(np.arange(inner.size), 2)
    ones = np.tile([-1.0, 1.0], inner.size)
    conic.add("nonneg", local, pairs, ones, (s[inner + 1] - s[inner]) / unit)
    step_change = np.full(inner.size, trust * ts / unit)
    conic.add("nonneg", local, pairs, -ones, step_change)
    conic.add("nonneg", local, pairs, ones, step_change)
    shift = min(0.02 * trust, 0.2 * program.path.length_m) / unit
    idx = np.arange(steps)
    conic.add(
        "nonneg",
        idx,
        idx,
        np.ones(steps),
        np.minimum(shift, (program.path.length_m - s[1:]) / unit),
    )
    conic.add("nonneg", idx, idx, -np.ones(steps), np.minimum(shift, s[1:] / unit))
    objective = np.zeros(columns)
    objective[sigma] = 1.0
    if dilate:
        slacks = [sigma, wall_sigma, residual_sigma]
        conic.add("nonneg", [0, 1, 2], slacks, [-1.0] * 3, [0.0] * 3)
        conic.add("nonneg", [0, 1], [dilation, dilation], [1.0, -1.0], [dilation_trust] * 2)
        objective[slacks] = PENALTY
        objective[dilation] = 1.0
    matrix, rhs, cones = conic.assemble(columns)
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    # The linearisation is re-evaluated exactly after each solve: 1e-6 is ample.
    settings.tol_gap_abs = settings.tol_gap_rel = 1e-6
    settings.tol_feas = 1e-7
    solver = clarabel.DefaultSolver(
        sparse.csc_matrix((columns, columns)), objective, matrix, rhs, cones, settings
    )
    result = solver.solve()
    program.programs += 1
    if str(result.status) not in ("Solved", "AlmostSolved"):
        return None
    x = np.asarray(result.x)
    new_s = np.concatenate(([0.0], s[1:] + x[:steps] * unit))
    new_s = np.clip(np.maximum.accumulate(new_s), 0.0, program.path.length_m)
    residual = max(
        0.5 * float(np.sum(x[t_base + 2 * m * modes : t_base + 2 * (m + 1) * modes]))
        for m in range(models)
    )
    new_period = ts * (1.0 + float(x[dilation])) if dilate else ts
    margin = max(float(x[sigma]), float(x[wall_sigma]), float(x[residual_sigma]))
    return _Step(_Samples(new_s, samples.tilt_rad.copy(), new_period), margin, residual)


def _margin_at(
    program: _PathProgram,
    start: _Samples,
    trust: float = 0.1,
    iterations: int = 8,
    tolerance: float = 2e-3,
    enough: float = 0.0,
) -> tuple[_Iterate, float]:
    """The samples of N steps (N from ``start``) whose largest ratio to a limit is least:
    cone programs (`_cone_step`) from ``start``, a step kept when its exact evaluation is
    better (the trust region then grows by half, else it halves). The residual's own trust
    region halves when its prediction missed the exact residual by more than a quarter of the
    predicted change (and 0.02), else grows by half. Stops when a step gains less than a
    quarter of ``tolerance`` and its prediction was right to ``tolerance``, or as soon as the
    largest ratio is at most ``enough``.
    Returns the best iterate and its largest ratio."""
    current = program.iterate(start)
    residual_trust = 1.0
    for _ in range(iterations):
        if current.excess <= enough:
            break
        step = _cone_step(program, current.samples, current.evaluation, trust, residual_trust)
        if step is None:
            trust *= 0.5
            continue
        trial = program.iterate(step.samples)
        before, after = current.ratios["residual slosh"], trial.ratios["residual slosh"]
        if abs(after - step.residual) > max(0.25 * abs(step.residual - before), 0.02):
            residual_trust *= 0.5
        else:
            residual_trust = min(1.5 * residual_trust, 2.0)
        if trial.excess < current.excess:
            gain = current.excess - trial.excess
            current = trial
            trust = min(trust * 1.5, 1.0)
            if (
                gain < 0.25 * tolerance
                and abs(trial.excess - (1.0 - PROGRAM_MARGIN + step.sigma)) < tolerance
            ):
                break
        else:
            trust *= 0.5
            if trust < 1e-3:
                break
    return current, current.excess


def _rescaled(samples: _Samples, steps: int, period_s: float | None = None) -> _Samples:
    """The same timing shape on ``steps`` sample periods of ``period_s`` (default: the
    samples' own): s and the tilt over normalised time by the clamped cubic spline through the
    samples (C2 and at rest at both ends, so that a coarse timing's jerk carries over to a finer
    grid; de Boor, *A Practical Guide to Splines* (1978) ch. IV), s kept monotone on [0, S]."""
    from scipy.interpolate import CubicSpline

    old = samples.s_m.size - 1
    u_old, u_new = np.arange(old + 1) / old, np.arange(steps + 1) / steps
    clamped = ((1, 0.0), (1, 0.0))
    s = CubicSpline(u_old, samples.s_m, bc_type=clamped)(u_new)
    s = np.clip(np.maximum.accumulate(s), samples.s_m[0], samples.s_m[-1])
    s[-1] = samples.s_m[-1]
    still = ((1, np.zeros(2)), (1, np.zeros(2)))
    tilt = CubicSpline(u_old, samples.tilt_rad, axis=0, bc_type=still)(u_new)
    return _Samples(s, tilt, samples.period_s if period_s is None else period_s)


def _smoothed(samples: _Samples, steps: int, period_s: float) -> _Samples:
    """A coarse timing on ``steps`` finer periods: the uniform cubic B-spline whose control
    points are the samples (each end repeated twice more, so the curve starts and ends at
    rest), its parameter spread over the same duration. The B-spline's third derivative on each
    segment is the third difference of its control points, so the finer grid sees no more
    jerk (in s) than the coarse one (de Boor, *A Practical Guide to Splines* (1978) ch. IX);
    an interpolating spline amplifies the coarse grid's alternating jerk up to threefold."""
    points = np.concatenate((samples.s_m[:1].repeat(2), samples.s_m, samples.s_m[-1:].repeat(2)))
    parameter = 1.0 + np.arange(steps + 1) / steps * (points.size - 3)
    index = np.clip(np.floor(parameter).astype(int), 1, points.size - 3)
    t = parameter - index
    weights = (
        (1.0 - t) ** 3 / 6.0,
        (3.0 * t**3 - 6.0 * t**2 + 4.0) / 6.0,
        (-3.0 * t**3 + 3.0 * t**2 + 3.0 * t + 1.0) / 6.0,
        t**3 / 6.0,
    )
    s = sum(w * points[index + j - 1] for j, w in enumerate(weights))
    s = np.clip(np.maximum.accumulate(s), samples.s_m[0], samples.s_m[-1])
    s[-1] = samples.s_m[-1]
    tilt = _rescaled(samples, steps).tilt_rad
    return _Samples(s, tilt, period_s)


def _dilated_search(
    program: _PathProgram,
    start: _Samples,
    iterations: int = 12,
    trust: float = 0.1,
    dilation_trust: float = 0.05,
    tolerance: float = 1e-3,
) -> _Iterate:
    """The shortest samples of N steps (N from ``start``) whose period is free: cone programs
    (`_cone_step` with ``dilation_trust``) from ``start``, a step kept when its exact merit
    ln h + `PENALTY` max(0, ratio - 1 + `PROGRAM_MARGIN`) falls (the trust regions of the
    speed and of epsilon then grow by half, else they halve). Stops when a kept step shortens
    the period by less than ``tolerance`` with every limit met."""
    keep = 1.0 - PROGRAM_MARGIN

    def merit(iterate: _Iterate) -> float:
        return math.log(iterate.samples.period_s) + PENALTY * max(0.0, iterate.excess - keep)

    current = program.iterate(start)
    for _ in range(iterations):
        # the residual's own trust region stays open: the penalty must be able to remove an
        # excess residual, and the merit test rejects a step that mispredicted it
        step = _cone_step(program, current.samples, current.evaluation, trust, 1.0, dilation_trust)
        if step is None:
            trust, dilation_trust = 0.5 * trust, 0.5 * dilation_trust
            continue
        trial = program.iterate(step.samples)
        gain = merit(current) - merit(trial)
        if gain > 0.0:
            shortened = current.samples.period_s - trial.samples.period_s
            current = trial
            trust, dilation_trust = min(1.5 * trust, 1.0), min(1.5 * dilation_trust, 0.2)
            if current.feasible and shortened < tolerance * current.samples.period_s:
                break
        else:
            trust, dilation_trust = 0.5 * trust, 0.5 * dilation_trust
            if trust < 1e-3:
                break
    return current


#: Sample period of the first, coarse free-time search [s] (about 20 samples per period of
#: the fundamental mode of a vial; the export grid then refines it).
COARSE_PERIOD_S = 0.016
#: Export-grid durations tried after the free-time searches, at most.
EXPORT_TRIES = 4


def _free_time(
    program: _PathProgram, start: _Samples, log: Any = None, coarse: bool = True
) -> tuple[_Iterate, list[tuple[int, float]]]:
    """The fewest export samples whose timing meets every limit.

    1. On a grid of `COARSE_PERIOD_S` (when ``coarse``; its programs are a quarter the size):
       the bracketed search over N (`_minimum_time`), then the same N with the period free
       (`_dilated_search`): the coarse minimum time.
    2. On the export's period Ts: that timing spread (`_smoothed`) over the steps of its
       duration, the period free again (the finer grid sees the higher modes' residual the
       coarse one smooths away).
    3. On the export grid: N, the steps of that duration
       (`sloshkit.motion.sampling.steps_to_reach`); its best margin (`_margin_at`, ended when
       every limit is met with half `PROGRAM_MARGIN` to spare), N increased while a limit is
       still exceeded (at most `EXPORT_TRIES`).

    Returns the feasible iterate and the (N, r) pairs tried on the export grid; raises
    `RuntimeError` when none met the limits."""
    from sloshkit.motion.sampling import steps_to_reach

    ts = start.period_s
    duration = start.steps * ts
    factor = max(1, int(COARSE_PERIOD_S / ts + 1e-9)) if coarse else 1

    def free(samples: _Samples, steps: int, iterations: int, trust: float) -> _Iterate:
        length = samples.steps * samples.period_s
        spread = _smoothed if steps > samples.steps else _rescaled
        found = _dilated_search(
            program, spread(samples, steps, length / steps), iterations, trust, 0.5 * trust
        )
        if log:
            log(
                f"free period at N = {steps}: {found.samples.steps * found.samples.period_s:.4f}"
                f" s, largest ratio {found.excess:.4f} ({program.programs} programs)"
            )
        return found

    current = start
    if factor > 1:
        coarse_steps = steps_to_reach(duration, factor * ts)
        found, _ = _minimum_time(program, _rescaled(start, coarse_steps, factor * ts), log)
        # the coarse grid's own minimum, its period free
        current = free(found.samples, found.samples.steps, 25, 0.1).samples
    # on the export's period; it starts near its optimum: a quarter of the trust regions
    duration = current.steps * current.period_s
    found = free(current, steps_to_reach(duration, ts), 8, 0.025)
    current, duration = found.samples, found.samples.steps * found.samples.period_s
    steps = steps_to_reach(duration, ts)
    history: list[tuple[int, float, _Iterate]] = []
    for _ in range(EXPORT_TRIES):
        # enough margin that the verification's finer checks pass as well
        iterate, ratio = _margin_at(
            program, _rescaled(current, steps, ts), iterations=4, enough=1.0 - 0.5 * PROGRAM_MARGIN
        )
        history.append((steps, ratio, iterate))
        if log:
            log(f"N = {steps}: largest ratio to a limit {ratio:.4f} ({program.programs} programs)")
        if ratio <= 1.0:
            return iterate, [(h[0], h[1]) for h in history]
        current = iterate.samples
        # half the step of r ~ (N0 / N)^2: near r = 1 the margin program, not the duration,
        # is what fell short
        steps += max(1, math.ceil(0.5 * steps * (math.sqrt(ratio) - 1.0)))
    worst = min(history, key=lambda h: h[1])[2]
    binding = max(worst.ratios, key=lambda key: worst.ratios[key])
    raise RuntimeError(f"no timing up to {steps * ts:.3g} s meets the limits (binding: {binding})")


def _minimum_time(
    program: _PathProgram, start: _Samples, log: Any = None
) -> tuple[_Iterate, list[tuple[int, float]]]:
    """The fewest steps N whose best samples (`_margin_at`) meet every limit.

    r(N), the largest ratio to a limit, falls about as (N0 / N)^2 when the slosh or the
    acceleration binds: the next N solves r = 1 on the secant of log r against log N through the
    last two, kept inside the bracket of solved N (the largest infeasible, the smallest
    feasible) and within 20 % of the last; the search stops when the bracket is
    `SEARCH_TOLERANCE` wide. Each r(N) starts from the nearest feasible samples _rescaled
    (from the start while none is).

    Returns the best feasible iterate and the (N, r) pairs tried; raises `RuntimeError` when
    no N up to four times the start's meets the limits."""
    history: list[tuple[int, float, _Iterate]] = []
    steps = start.steps
    guess = start
    for _ in range(MAX_SEARCH):
        steps_now = _rescaled(guess, steps)
        iterate, ratio = _margin_at(program, steps_now)
        history.append((steps, ratio, iterate))
        if log:
            log(
                f"N = {steps} of {steps_now.period_s * 1e3:.4g} ms: largest ratio to a limit "
                f"{ratio:.4f} ({program.programs} programs)"
            )
        feasible = [h for h in history if h[1] <= 1.0]
        infeasible = [h for h in history if h[1] > 1.0]
        low = max((h[0] for h in infeasible), default=0)
        high = min((h[0] for h in feasible), default=None)
        if high is not None and high - low <= max(1, int(SEARCH_TOLERANCE * high)):
            break
        if len(history) == 1 or abs(math.log(history[-1][1] / history[-2][1])) < 1e-9:
            target = steps * math.sqrt(ratio)
        else:
            (n1, r1, _), (n2, r2, _) = history[-2], history[-1]
            slope = math.log(r2 / r1) / math.log(n2 / n1)
            target = n2 * (r2 ** (-1.0 / slope) if slope < -0.1 else math.sqrt(r2))
        target = min(max(target, 0.8 * steps), 1.25 * steps)
        new = math.ceil(target)
        upper = high - 1 if high is not None else 4 * start.steps
        new = min(max(new, low + 1), upper)
        if any(h[0] == new for h in history):
            new = (low + upper + 1) // 2
        if any(h[0] == new for h in history) or new > 4 * start.steps:
            break
        # from the nearest feasible samples: stretching an infeasible iterate carries its
        # broken residual along (from none yet, the start stretched)
        solved = [h for h in history if h[1] <= 1.0]
        guess = min(solved, key=lambda h: abs(h[0] - new))[2].samples if solved else start
        steps = new
    feasible = [h for h in history if h[1] <= 1.0]
    if not feasible:
        worst = min(history, key=lambda h: h[1])
        binding = max(worst[2].ratios, key=lambda key: worst[2].ratios[key])
        raise RuntimeError(
            f"no timing up to {max(h[0] for h in history) * program.ts:.3g} s meets the limits "
            f"(binding: {binding})"
        )
    best = min(feasible, key=lambda h: h[0])
    return best[2], [(h[0], h[1]) for h in history]


def plan_optimal(problem: Any, verifier: Any, log: Any = None) -> Any:
    """The minimum-time timing of the (untilted) path, verified.

    Rounds of the free-time search (`_free_time`): the first from the time-optimal speed
    profile under the quasi-static acceleration that tilts a level surface to the height
    limit (h = R a / g; `sloshkit.plan.retime.capped_timing`), each next one from the last
    one's samples on the export's period with the program's slosh limits moved towards the
    values at which the verification meets its limits (`_next_limit`; at most `TIGHTENINGS`).
    The rounds end when the verified plan's binding slosh is within `LIMIT_TOLERANCE` of its
    limit, when a round one sample shorter failed the verification, or when a round no
    longer shortens the plan; the shortest verified timing is kept. A limit outside the
    program is met by a uniform stretch (`sloshkit.plan.path_result.verified_candidate`); a
    verifier that checks an arm's joint speeds (`sloshkit.plan.path_result.JointSpeedCheck`)
    lends the programs the joints along the path (the export's IK every `JOINT_GRID_M`), and
    they limit the joint speeds themselves.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    verifier : callable
        (problem, poses, tilted) -> Verification.
    log : callable, optional
        Receives one line per solved duration.

    Returns
    -------
    PathCandidate
        Method ``optimal``; ``detail`` has the first search's duration, the programs solved,
        each round's limits and verified slosh, and the search.

    Examples
    --------
    >>> import sloshkit as sk
    >>> from sloshkit.plan.path_result import verify
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

    from sloshkit.plan.path_problem import sample_path
    from sloshkit.plan.path_result import JointSpeedCheck, PathCandidate, verified_candidate
    from sloshkit.plan.retime import capped_timing
    from sloshkit.plan.timing import Timing

    started = time.perf_counter()
    machine, slosh = problem.machine, problem.slosh
    # the program's slosh limits start where `_next_limit` aims: the verification's filtered
    # simulation exceeds the program's model by a percent or so
    aim = 1.0 - 0.5 * LIMIT_TOLERANCE
    limits = _ProgramLimits(
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
        machine.max_angular_velocity_rad_s,
        machine.max_angular_acceleration_rad_s2,
        aim * slosh.max_height_m,
        aim * slosh.max_residual_height_m,
    )
    ts = problem.sample_period_s
    radius = float(problem.model.radius_m)
    cap = min(machine.max_acceleration_m_s2, GRAVITY_M_S2 * slosh.max_height_m / radius)
    first = capped_timing(problem, cap)
    grid = sample_path(problem.path, first, ts)
    s = np.clip(
        first.position(np.minimum(grid.time_s, first.duration_s)), 0.0, problem.path.length_m
    )
    s[-1] = problem.path.length_m
    warm = _Samples(np.maximum.accumulate(s), np.zeros((s.size, 2)), ts)
    joints = _joint_map(problem, verifier) if isinstance(verifier, JointSpeedCheck) else None
    if isinstance(joints, str):
        return PathCandidate("optimal", None, None, time.perf_counter() - started, joints)
    rounds: list[dict[str, float]] = []
    verified: list[tuple[int, _Iterate]] = []
    searches: list[tuple[int, float]] = []
    programs = 0
    for _ in range(TIGHTENINGS):
        program = _PathProgram(problem.path, problem.models(), limits, ts, joints=joints)
        try:
            # a later round starts from the last one's samples, already near its optimum
            best, search = _free_time(program, warm, log, coarse=not rounds)
        except RuntimeError as error:
            if verified:
                break
            return PathCandidate("optimal", None, None, time.perf_counter() - started, str(error))
        warm = best.samples
        searches += search
        programs += program.programs
        check = verifier(problem, _export_poses(problem, best.samples), False)
        rounds.append(
            {
                "duration_s": best.samples.steps * ts,
                "height_limit_m": limits.max_height_m,
                "residual_limit_m": limits.max_residual_height_m,
                "verified_peak_m": check.peak_height_m,
                "verified_residual_m": check.residual_height_m,
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
            verified.append((best.samples.steps, best))
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
            )
            if (
                closest >= 1.0 - LIMIT_TOLERANCE
                or shorter_failed
                or (len(verified) >= 2 and verified[-1][0] >= verified[-2][0])
            ):
                break
        limits = replace(
            limits,
            max_height_m=_next_limit(
                rounds, "height_limit_m", "verified_peak_m", slosh.max_height_m
            ),
            max_residual_height_m=_next_limit(
                rounds, "residual_limit_m", "verified_residual_m", slosh.max_residual_height_m
            ),
        )
    if not verified:
        message = "the verification's slosh exceeds the limits after every tightening"
        return PathCandidate("optimal", None, None, time.perf_counter() - started, message)
    corrected = min(verified, key=lambda pair: pair[0])[1]
    samples = corrected.samples
    timing = Timing.from_samples("optimal", np.arange(samples.s_m.size) * ts, samples.s_m)

    def poses_for(factor: float) -> Any:
        if factor == 1.0:
            return _export_poses(problem, samples)
        return sample_path(problem.path, timing.stretched(factor), ts)

    detail = {
        "first_search_s": rounds[0]["duration_s"],
        "programs": programs,
        "rounds": rounds,
        "search": searches,
    }
    return verified_candidate("optimal", problem, poses_for, 1.0, started, verifier, False, detail)


def _export_poses(problem: Any, samples: _Samples) -> Any:
    """The samples as the export (`sloshkit.motion.poses.PoseTrajectory`, which makes the
    quaternions sign-continuous)."""
    from sloshkit.motion.poses import PoseTrajectory

    position, rotation = _poses_of(problem.path, samples, problem.tilt_centre_height_m)
    time_s = np.arange(samples.s_m.size) * problem.sample_period_s
    return PoseTrajectory(time_s, position, rotation.as_quat())


def _next_limit(
    rounds: list[dict[str, float]], program_key: str, verified_key: str, limit: float
) -> float:
    """The program's next limit: the verification's value is an increasing function v(p) of
    the program's limit p (v = p for a linear verification); regula falsi for v(p) = limit
    (slightly below) on the rounds that bracket it, else p limit / v (at most the limit)."""
    aim = (1.0 - 0.5 * LIMIT_TOLERANCE) * limit
    points = sorted((r[program_key], r[verified_key]) for r in rounds)
    below = [p for p in points if p[1] <= aim]
    above = [p for p in points if p[1] > aim]
    if below and above:
        (p1, v1), (p2, v2) = below[-1], above[0]
        if v2 > v1 and p2 > p1:  # rounds at one program limit bracket nothing
            return p1 + (aim - v1) * (p2 - p1) / (v2 - v1)
    p, v = rounds[-1][program_key], rounds[-1][verified_key]
    return min(limit, p * aim / max(v, 1e-12))
