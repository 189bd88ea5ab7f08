"""The model of the 3-D path program: the path parameter at the samples, and everything the
verification checks as functions of them, with their derivatives.

The decision variables are the path parameter s_k at every sample t_k = k h of a uniform grid
(k = 0..N, s_0 = 0, s_N = S: the whole path; on the export's grid the samples are the export,
`sloshkit.plan.path.samples`). Every quantity the verification checks is a function of these
samples (`PathProgram.evaluate`):

- the Cartesian velocity, acceleration and jerk of the reference point and the container's
  angular velocity and acceleration, by finite differences of the samples with the ends held at
  rest (as `sloshkit.plan.path.limits.kinematics` measures them);
- the slosh of every mode n of every model of the robustness band: the damped spherical
  pendulum the verification simulates (`sloshkit.sim.spatial`; Abramson, NASA SP-106 (1966)
  ch. 6; Dodge, SwRI (2000) ch. 3), driven by kappa_n g - a_hinge at its hinge in the
  container's non-spinning frame, from rest in the first pose, integrated by the 3-D
  simulation's Runge-Kutta kernel along the sampled drive (`sloshkit.plan.path.pendulums`);
  the wall height |sum_n e_n tan(deflection_n)| at every sample and the residual
  sum_n e_n |[A_n B_n]|_2 (the semi-major axis of each mode's free oscillation) `HOLD`
  samples after the move, scaled back to its end (as `sloshkit.sim.spatial_response.
  SpatialResponse` measures them). On the export this equals `simulate_spatial(...,
  nonlinear=True, cutoff_hz=None)` to the accuracy of the spline differentiation (0.04 % of
  the peak on the test's corner path);
- with an arm, its joint speeds, from the export's IK along the path and, when the program
  tilts, its quadratic model in the tilt (`sloshkit.plan.path.joints.joint_map`).

`PathProgram.jacobians` differentiates the positions, angular velocities and forces banded, by
colouring; `sloshkit.plan.path.transcription` builds one program from them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.plan.path.axial_turn import spin_changes
from sloshkit.plan.path.forces import held, specific_forces, turned_about_axis
from sloshkit.plan.path.joints import JointMap, JointModel
from sloshkit.plan.path.pendulums import at_rest, mode_slope, pendulum_track
from sloshkit.plan.path.samples import PathSamples
from sloshkit.sim.metrics import free_oscillation_components
from sloshkit.sim.spatial_response import ellipse_semi_major

FloatArray = NDArray[np.float64]


#: PathSamples of rest after the move before its free oscillation is measured (the 3-D
#: simulation's `sloshkit.sim.spatial_response.SpatialResponse.free_amplitudes_rad` waits
#: max(window / 2, 4) + 1 samples for an unsmoothed drive).
HOLD = 5


@dataclass(frozen=True)
class ProgramLimits:
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
    max_surface_angle_rad : float, optional
        The first mode's deflection (the surface's slope at the wall, atan |u_lat / u_z|)
        [rad]; None: not limited.

    Examples
    --------
    >>> ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002).max_tilt_rad
    0.0
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
    max_surface_angle_rad: float | None = None


def _with_rest(samples: PathSamples) -> PathSamples:
    """The samples followed by `HOLD` samples of rest at the last pose."""
    s = np.concatenate((samples.s_m, np.repeat(samples.s_m[-1:], HOLD)))
    tilt = np.concatenate((samples.tilt_rad, np.repeat(samples.tilt_rad[-1:], HOLD, axis=0)))
    return PathSamples(s, tilt, samples.period_s)


def _model_drive(model: Any, force: FloatArray) -> tuple[FloatArray, FloatArray]:
    """One band model's drive (modes, K, 3) and rest force (modes, 3) from `PathProgram.forces`:
    kappa_n g - a_hinge with kappa_n = omega_n^2 L_n / g (`sloshkit.sim.spatial_drive`)."""
    kappa = np.array([m.omega_rad_s**2 * m.length_m / model.gravity_m_s2 for m in model.modes])
    drive = force[:-1] + (kappa - 1.0)[:, None, None] * force[-1][None]
    return drive, kappa[:, None] * force[-1, 0][None]


def mode_arrays(model: Any) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The lengths, frequencies and damping ratios of a model's modes.

    Parameters
    ----------
    model : SloshModel
        The model.

    Returns
    -------
    tuple of numpy.ndarray
        L_n [m], omega_n [rad/s] and zeta_n.

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> [round(float(w), 1) for w in mode_arrays(model)[1]]
    [19.2, 32.7, 41.3]
    """
    modes = model.modes
    return (
        np.array([m.length_m for m in modes]),
        np.array([m.omega_rad_s for m in modes]),
        np.array([m.damping_ratio for m in modes]),
    )


@dataclass(frozen=True, eq=False)
class _ProgramEvaluation:
    """Everything the limits see, for one set of samples.

    ``velocity`` ... ``jerk``: finite differences of the positions (rows for the padded
    grid), ``omega``/``alpha``: angular velocity and acceleration, ``force``: specific force
    per mode and gravity in N (`PathProgram.forces`), ``wall``: wall height vectors per band
    model (models, N + 1, 2), ``amplitude``: free-oscillation vectors (models, modes, 4) scaled
    by e_n; ``joint``: the arm's joint speeds over their limits (N, dof; empty without an
    arm); ``unit``, ``rate``: each model's pendulum tracks (models, modes, N + 1, 3), ``drive``
    their drive (models, modes, N + 1, 7: the specific force, then N's lateral angular
    velocity and its derivative; `sloshkit.plan.path.pendulums`). N counts the rest samples.
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


class PathProgram:
    """The sequential cone programs of one path problem (module docstring).

    Parameters
    ----------
    path : Path
        The geometry.
    models : list of SloshModel
        The band's models (all share the bob heights; only the frequencies differ).
    limits : ProgramLimits
        Limits, slosh ones as the program should impose them.
    sample_period_s : float
        Export sample period Ts [s].
    tilt : bool
        Whether the tilt angles are variables.
    centre_height_m : float
        Tilt centre above the container bottom [m].
    joints : JointMap, optional
        An arm's joints along the path (`joint_map`): their speeds are limited too.
    linear : bool
        Whether the slosh is the small-angle pendulums' (`sloshkit.plan.path.pendulums.
        linear_track`) instead of the large-angle ones the verification simulates.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> path = path_from_waypoints([[0, 0, 0], [0.1, 0, 0]])
    >>> program = PathProgram(path, [model], limits, 0.01)
    >>> t = np.arange(61) / 60  # a quintic rest-to-rest timing of 0.6 s
    >>> samples = PathSamples(0.1 * t**3 * (10 - 15 * t + 6 * t**2), np.zeros((61, 2)), 0.01)
    >>> iterate = program.iterate(samples)
    >>> iterate.feasible, max(iterate.ratios, key=iterate.ratios.__getitem__)
    (True, 'peak slosh')
    """

    def __init__(
        self,
        path: Any,
        models: list[Any],
        limits: ProgramLimits,
        sample_period_s: float,
        tilt: bool = False,
        centre_height_m: float = 0.0,
        joints: JointMap | None = None,
        linear: bool = False,
    ) -> None:
        self.path, self.models, self.limits = path, models, limits
        self.joints, self.linear = joints, linear
        self.joint_model: JointModel | None = None if joints is None else joints.model()
        self.ts, self.tilt, self.centre = sample_period_s, tilt, centre_height_m
        self.modes = models[0].modes
        self.gravity = np.array([0.0, 0.0, -models[0].gravity_m_s2])
        self.programs = 0
        self._kernels: dict[int, list[list[tuple[FloatArray, FloatArray]]]] = {}

    # ----------------------------------------------------------------- evaluation
    def forces(self, samples: PathSamples) -> tuple[FloatArray, dict[str, FloatArray]]:
        """Specific force g - a_hinge at each mode's hinge in N, and g itself in N, (modes + 1,
        N + 1, 3) [m/s^2], with the kinematics (`sloshkit.plan.path.forces.specific_forces`
        for one set of samples; `sloshkit.sim.spatial_drive`: a mode whose omega_n^2 L_n
        differs from g adds (kappa_n - 1) times the last row).
        """
        force, kinematic = self._batch([samples.s_m], [samples.tilt_rad], samples.period_s)
        return force[0], {key: value[0] for key, value in kinematic.items()}

    def _batch(
        self, s_m: list[FloatArray], tilt_rad: list[FloatArray], period_s: float
    ) -> tuple[FloatArray, dict[str, FloatArray]]:
        """`specific_forces` of sample sets of one length."""
        return specific_forces(
            self.path,
            self.modes,
            self.gravity,
            np.stack(s_m),
            np.stack(tilt_rad),
            period_s,
            self.centre,
        )

    def evaluate(self, samples: PathSamples) -> _ProgramEvaluation:
        """Kinematics, forces, pendulum tracks, wall heights and residual amplitudes."""
        samples = _with_rest(samples)
        force, kinematic = self.forces(samples)
        steps = samples.steps
        count = len(self.modes)
        walls = np.zeros((len(self.models), steps + 1, 2))
        amplitudes = np.zeros((len(self.models), count, 4))
        units = np.zeros((len(self.models), count, steps + 1, 3))
        rates = np.zeros_like(units)
        drives = np.zeros((len(self.models), count, steps + 1, 7))
        turning = kinematic["tilt_rates"]
        for m, model in enumerate(self.models):
            drive, rest = _model_drive(model, force)
            drive = np.concatenate((drive, np.broadcast_to(turning, (count, *turning.shape))), -1)
            unit, rate = pendulum_track(
                drive, rest, *mode_arrays(model), samples.period_s, self.linear
            )
            units[m], rates[m], drives[m] = unit, rate, drive
            for n, mode in enumerate(model.modes):
                walls[m] += mode.wall_elevation_factor_m * mode_slope(unit[n])
                # the free oscillation HOLD samples after the move (as the 3-D simulation
                # measures its residual), about the rest direction, scaled back to the end
                final = drive[n, -1, :3]
                offset = unit[n, -1, :2] - at_rest(final, self.linear, n)
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
            q = self.joint_model.at(samples.s_m, samples.tilt_rad)[0]  # type: ignore[union-attr]
            joint = np.diff(q, axis=0) / (samples.period_s * self.joints.limits_rad_s)
        return _ProgramEvaluation(
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

    def worst(self, evaluation: _ProgramEvaluation, samples: PathSamples) -> dict[str, float]:
        """Each limited quantity's peak divided by its limit."""
        lim = self.limits
        ratios = {
            "velocity": _peak_norm(evaluation.velocity) / lim.max_velocity_m_s,
            "acceleration": _peak_norm(evaluation.acceleration) / lim.max_acceleration_m_s2,
            "jerk": _peak_norm(evaluation.jerk) / lim.max_jerk_m_s3,
            "peak slosh": _peak_norm(evaluation.wall) / lim.max_height_m,
            "residual slosh": _residual_height(evaluation.amplitude) / lim.max_residual_height_m,
        }
        if evaluation.joint.size:
            ratios["joint speed"] = float(np.max(np.abs(evaluation.joint)))
        if lim.max_surface_angle_rad is not None:
            slope = _peak_norm(mode_slope(evaluation.unit[:, 0]))
            ratios["surface angle"] = slope / math.tan(lim.max_surface_angle_rad)
        if lim.max_angular_velocity_rad_s is not None:
            ratios["angular velocity"] = (
                _peak_norm(evaluation.omega) / lim.max_angular_velocity_rad_s
            )
        if lim.max_angular_acceleration_rad_s2 is not None:
            ratios["angular acceleration"] = (
                _peak_norm(evaluation.alpha) / lim.max_angular_acceleration_rad_s2
            )
        if self.tilt:
            tilt = held(samples.tilt_rad, 2)
            rate = np.diff(tilt, axis=0) / samples.period_s
            ratios["tilt"] = _peak_norm(samples.tilt_rad) / lim.max_tilt_rad
            ratios["tilt rate"] = _peak_norm(rate) / lim.max_tilt_rate_rad_s
            ratios["tilt acceleration"] = (
                _peak_norm(np.diff(rate, axis=0) / samples.period_s)
                / lim.max_tilt_acceleration_rad_s2
            )
        return ratios

    # ----------------------------------------------------------------- linearisation
    def jacobians(self, samples: PathSamples) -> list[_ProgramBands]:
        """Banded derivatives of the samples' positions, angular velocities and forces with
        respect to each variable block (s, then r_x, r_y with tilt).

        Positions depend on sample k, the angular velocity on k-1 and k, the forces on k-1..k+1
        (the second difference) and, when the axis tilts, through N's turn about it on every
        earlier sample (``spin``, the turn per unit of the variable, and
        `sloshkit.plan.path.axial_turn`); perturbing every third sample at once separates the
        bands (Curtis, Powell & Reid, IMA J. Appl. Math. 13 (1974) 117-119), one-sided
        differences (backward at the path's end; error about 1e-7 relative).
        """
        samples = _with_rest(samples)
        n = samples.s_m.size
        columns: list[int | None] = [None] + ([0, 1] if self.tilt else [])
        bands = []
        base_force, base_kinematic = self.forces(samples)
        # every perturbed set of every column in one batch (`sloshkit.plan.path.forces`)
        perturbed = [
            (column, colour, *self._perturbation(samples, column, colour))
            for column in columns
            for colour in range(3)
        ]
        moved_force, moved_kinematic = self._batch(
            [moved.s_m for *_, moved, _ in perturbed],
            [moved.tilt_rad for *_, moved, _ in perturbed],
            samples.period_s,
        )
        turn_force, turn_rates = turned_about_axis(base_force, base_kinematic["tilt_rates"])
        for column in columns:
            force = np.zeros((3, len(self.modes) + 1, n, 3))
            rates = np.zeros((3, n, 4))
            position = np.zeros((n, 3))
            omega = np.zeros((2, n + 1, 3))
            spin = np.zeros(n)
            for index, (moved_column, colour, _, width) in enumerate(perturbed):
                if moved_column != column:
                    continue
                chosen = np.arange(colour, n, 3)
                dforce = moved_force[index] - base_force
                drates = moved_kinematic["tilt_rates"][index] - base_kinematic["tilt_rates"]
                dposition = moved_kinematic["position"][index] - base_kinematic["position"]
                position[chosen] = dposition[chosen] / width[chosen, None]
                # N's turn about the axis (`sloshkit.plan.path.axial_turn`): each perturbed
                # sample's, and what those two or more before k left at k (not k's band)
                dspin = moved_kinematic["spin"][index] - base_kinematic["spin"]
                moved_spin, earlier = spin_changes(dspin, chosen)
                spin[chosen] = moved_spin / width[chosen]
                dforce = dforce - earlier[None, :, None] * turn_force
                drates = drates - earlier[:, None] * turn_rates
                domega = moved_kinematic["omega"][index] - base_kinematic["omega"]
                for offset in (-1, 0, 1):
                    k = chosen - offset  # the force at k sees the perturbed sample k + offset
                    k = k[(k >= 0) & (k < n)]
                    force[offset + 1][:, k] = dforce[:, k] / width[k + offset][None, :, None]
                    rates[offset + 1][k] = drates[k] / width[k + offset][:, None]
                # omega row i (1..n-1) uses samples i-1 and i
                own = chosen[(chosen >= 1) & (chosen <= n - 1)]
                omega[1][own] = domega[own] / width[own, None]
                prev = chosen[chosen + 1 <= n - 1] + 1
                omega[0][prev] = domega[prev] / width[prev - 1, None]
            bands.append(_ProgramBands(position, omega, force, rates, spin))
        return bands

    def _perturbation(
        self, samples: PathSamples, column: int | None, colour: int
    ) -> tuple[PathSamples, FloatArray]:
        """Every third sample from ``colour`` moved in s (``column`` None) or a tilt angle."""
        step = 1e-7 * max(self.path.length_m, 1.0) if column is None else 1e-7
        chosen = np.arange(colour, samples.s_m.size, 3)
        return samples.perturbed(chosen, column, step, self.path.length_m)

    def iterate(self, samples: PathSamples) -> ProgramIterate:
        """The samples with their exact evaluation and ratios to the limits."""
        evaluation = self.evaluate(samples)
        return ProgramIterate(samples, evaluation, self.worst(evaluation, samples))


@dataclass(frozen=True, eq=False)
class ProgramIterate:
    """Samples, their exact evaluation and each limited quantity's peak over its limit.

    Parameters
    ----------
    samples : PathSamples
        The samples.
    evaluation : _ProgramEvaluation
        Everything the limits see (`PathProgram.evaluate`).
    ratios : dict
        Each limited quantity's peak over its limit (`PathProgram.worst`).

    Examples
    --------
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> program = PathProgram(sk.path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model],
    ...                       ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002), 0.01)
    >>> t = np.arange(61) / 60  # a quintic rest-to-rest timing of 0.6 s
    >>> samples = PathSamples(0.1 * t**3 * (10 - 15 * t + 6 * t**2), np.zeros((61, 2)), 0.01)
    >>> iterate = program.iterate(samples)
    >>> round(float(iterate.samples.s_m[-1]), 3), iterate.ratios["velocity"] < 1.0
    (0.1, True)
    """

    samples: PathSamples
    evaluation: _ProgramEvaluation
    ratios: dict[str, float]

    @property
    def excess(self) -> float:
        """The largest ratio of a quantity to its limit (<= 1: every limit met)."""
        return max(self.ratios.values())

    @property
    def feasible(self) -> bool:
        """Every limit met (to 1e-9)."""
        return self.excess <= 1.0 + 1e-9


@dataclass(frozen=True, eq=False)
class _ProgramBands:
    """Derivatives of one variable block: ``position`` (n, 3) d P_k / d x_k, ``omega``
    (2, n + 1, 3) d w_i / d x_{i-1} and d w_i / d x_i, ``force`` (3, modes, n, 2)
    d f_k / d x_{k+o} for o = -1, 0, 1, ``rates`` (3, n, 4) the same of N's lateral angular
    velocity and its derivative (the drive's last four components), ``spin`` (n,) N's turn
    about the axis at the later samples (`sloshkit.plan.path.axial_turn`)."""

    position: FloatArray
    omega: FloatArray
    force: FloatArray
    rates: FloatArray
    spin: FloatArray


def _residual_height(amplitude: FloatArray) -> float:
    """The residual bound of the worst band model: sum_n e_n |M_n|_2 with M_n = [A_n B_n] the
    free oscillation's cosine and sine vectors (its semi-major axis,
    `sloshkit.sim.spatial_response.ellipse_semi_major`), from (models, modes, 4) [m]."""
    semi = ellipse_semi_major(amplitude[..., :2], amplitude[..., 2:])
    return float(np.max(np.sum(semi, axis=1)))


def _peak_norm(values: FloatArray) -> float:
    """Largest Euclidean norm along the last axis."""
    return float(np.max(np.linalg.norm(values, axis=-1))) if values.size else 0.0


__all__ = [
    "HOLD",
    "PathProgram",
    "ProgramIterate",
    "ProgramLimits",
    "mode_arrays",
]
