"""The minimum-time timing (and tilt) of a 3-D path as one sequential linear program.

The decision variables are the path parameter s_k and, with tilt, two tilt angles r_k (a
horizontal rotation vector) at every sample t_k = k Ts of the export grid, k = 0..N. The export
is the pose sequence P_k = P(s_k, r_k), q_k = q(s_k, r_k) (`poses_of`): the container on the
path, tilted about its tilt centre, which stays on the path. Everything the verification
checks is a function of these samples:

- the Cartesian velocity, acceleration and jerk of the reference point by finite differences
  of the samples, the ends held at rest (as `sloshkit.plan.path_limits.kinematics` measures
  them), the angular velocity and acceleration of the container, the tilt, its rate and its
  acceleration;
- the slosh of every mode n of every model of the robustness band: a linear spherical pendulum
  phi'' + 2 zeta w phi' + w^2 phi = f_lat / L_n driven by the specific force f = g - a_B at its
  bob point B_n (second difference of the sampled bob positions), in the container frame without
  its spin (Abramson, NASA SP-106 (1966) ch. 6; Dodge, SwRI (2000) ch. 3), discretised exactly
  (`sloshkit.sim.discretisation.linear_mode_response`, first-order hold of the equivalent
  velocity); the wall height |sum_n e_n phi_n| at every sample and the residual bound
  sum_n e_n |(A_n, B_n)| of the free oscillation after the last sample.

Each linear program linearises these functions around the current samples (sequential convex
programming with a trust region: Nocedal & Wright, *Numerical Optimization*, 2nd ed. (2006)
ch. 18; Mao, Szmuk & Acikmese, "Successive convexification of non-convex optimal control
problems", IEEE CDC (2016), doi:10.1109/CDC.2016.7798816). The slosh responses are linear in the
forces, so their rows are the products of the pendulums' Toeplitz kernels with the banded
force Jacobians (condensed: the pendulum states are not variables, only the samples where a
limit is near get a row). Norm limits (|v| <= vmax, the wall height, ...) are tangent facets in
the direction of the current value, plus facets added at every sample where an accepted step
broke the limit (cutting planes, Kelley 1960), so the LP stays small; the accepted iterate is
evaluated exactly and kept only when it meets every limit.

For N samples the program maximises the reach s_N along the path (the move of N steps that
gets furthest, at rest at both ends); the minimum time is the smallest N whose reach is the
whole path (`minimum_time_samples`: a secant search on the reach), the same construction as
the 1-D planner's (`sloshkit.plan.export_grid`). At that N a last program fixes s_N = S and
minimises the total variation of the path jerk (a smooth move of the same duration).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import sparse
from scipy.spatial.transform import Rotation

from sloshkit.highs import new_highs
from sloshkit.model.theory import GRAVITY_M_S2

FloatArray = NDArray[np.float64]
GRAVITY_VECTOR = np.array([0.0, 0.0, -GRAVITY_M_S2])
#: Relative margin the program keeps from every limit (the export is then verified exactly).
PROGRAM_MARGIN = 2e-3
#: A wall height, residual or kinematic quantity above this fraction of its limit gets a row.
ACTIVE_FRACTION = 0.6
#: Sequential programs per reach evaluation, at most.
MAX_ITERATIONS = 30


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
class Samples:
    """Path parameter [m] and tilt rotation vector [rad] at the export samples."""

    s_m: FloatArray
    tilt_rad: FloatArray

    @property
    def steps(self) -> int:
        """N, the number of sample periods."""
        return int(self.s_m.size - 1)


def poses_of(
    path: Any, samples: Samples, centre_height_m: float
) -> tuple[FloatArray, Rotation]:
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


def _held(values: FloatArray, pad: int) -> FloatArray:
    """``values`` with ``pad`` copies of the first and last rows (at rest before and after)."""
    return np.concatenate((values[:1],) * pad + (values,) + (values[-1:],) * pad)


@dataclass(frozen=True, eq=False)
class Evaluation:
    """Everything the limits see, for one set of samples.

    ``velocity`` ... ``jerk``: finite differences of the positions (rows for the padded
    grid), ``omega``/``alpha``: angular velocity and acceleration, ``force``: lateral specific
    force per mode (modes, N + 1, 2), ``wall``: wall height vectors per band model
    (models, N + 1, 2), ``amplitude``: free-oscillation vectors (models, modes, 4) scaled by
    e_n.
    """

    velocity: FloatArray
    acceleration: FloatArray
    jerk: FloatArray
    omega: FloatArray
    alpha: FloatArray
    force: FloatArray
    wall: FloatArray = field(default_factory=lambda: np.empty(0))
    amplitude: FloatArray = field(default_factory=lambda: np.empty(0))


class PathProgram:
    """The sequential linear program of one path problem (module docstring).

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
    """

    def __init__(
        self,
        path: Any,
        models: list[Any],
        limits: ProgramLimits,
        sample_period_s: float,
        tilt: bool = False,
        centre_height_m: float = 0.0,
    ) -> None:
        self.path, self.models, self.limits = path, models, limits
        self.ts, self.tilt, self.centre = sample_period_s, tilt, centre_height_m
        self.modes = models[0].modes
        self.programs = 0
        self._kernels: dict[int, list[list[tuple[FloatArray, FloatArray]]]] = {}

    # ----------------------------------------------------------------- evaluation
    def forces(
        self, samples: Samples, spin: FloatArray | None = None
    ) -> tuple[FloatArray, dict[str, FloatArray]]:
        """Lateral specific force of each mode (modes, N + 1, 2) and the kinematics.

        ``spin`` (the container's accumulated rotation about its own axis [rad]) is taken as
        given when passed (the derivatives hold it fixed: it depends on every earlier sample).
        """
        ts = self.ts
        position, rotation = poses_of(self.path, samples, self.centre)
        quaternion = rotation.as_quat()
        padded = _held(position, 2)
        velocity = np.diff(padded, axis=0) / ts
        acceleration = np.diff(velocity, axis=0) / ts
        jerk = np.diff(acceleration, axis=0) / ts
        increments = Rotation.from_quat(quaternion[1:]) * Rotation.from_quat(quaternion[:-1]).inv()
        omega = np.concatenate((np.zeros((1, 3)), increments.as_rotvec() / ts, np.zeros((1, 3))))
        alpha = np.diff(omega, axis=0) / ts
        if spin is None:
            body = Rotation.from_quat(quaternion[:-1]).inv() * Rotation.from_quat(quaternion[1:])
            spin = np.concatenate(([0.0], np.cumsum(body.as_rotvec()[:, 2])))
        frame = rotation * Rotation.from_rotvec(np.column_stack((0 * spin, 0 * spin, -spin)))
        axis = rotation.apply([0.0, 0.0, 1.0])
        force = np.empty((len(self.modes), samples.s_m.size, 2))
        for index, mode in enumerate(self.modes):
            point = _held(position + mode.bob_height_m * axis, 1)
            bob = (point[2:] - 2.0 * point[1:-1] + point[:-2]) / ts**2
            force[index] = frame.inv().apply(GRAVITY_VECTOR - bob)[:, :2]
        kinematic = {
            "velocity": velocity,
            "acceleration": acceleration,
            "jerk": jerk,
            "omega": omega,
            "alpha": alpha,
            "position": position,
            "spin": spin,
        }
        return force, kinematic

    def kernels(self, steps: int) -> list[list[tuple[FloatArray, FloatArray]]]:
        """Per band model and mode, the responses (angle, rate) of the pendulum to a unit
        step of the force excess at sample 1 (the Toeplitz kernels of the linear map)."""
        if steps not in self._kernels:
            from sloshkit.sim.discretisation import linear_mode_response

            impulse = np.zeros(steps + 1)
            impulse[1] = 1.0
            # Equivalent velocity w = -cumulative trapezoid of the force excess.
            velocity = -np.concatenate(([0.0], np.cumsum(0.5 * (impulse[1:] + impulse[:-1]))))
            velocity *= self.ts
            self._kernels[steps] = [
                [
                    linear_mode_response(
                        velocity, self.ts, mode.omega_rad_s, mode.damping_ratio, mode.length_m
                    )
                    for mode in model.modes
                ]
                for model in self.models
            ]
        return self._kernels[steps]

    def evaluate(self, samples: Samples) -> Evaluation:
        """Kinematics, forces, wall heights and residual amplitudes of the samples."""
        force, kinematic = self.forces(samples)
        steps = samples.steps
        kernels = self.kernels(steps)
        excess = force - force[:, :1]
        walls = np.zeros((len(self.models), steps + 1, 2))
        amplitudes = np.zeros((len(self.models), len(self.modes), 4))
        for m, model in enumerate(self.models):
            for n, mode in enumerate(model.modes):
                angle_kernel, rate_kernel = kernels[m][n]
                theta = _causal(angle_kernel, excess[n])
                rate = _causal(rate_kernel, excess[n])
                stiffness = mode.length_m * mode.omega_rad_s**2
                phi = theta + force[n, 0] / stiffness
                walls[m] += mode.wall_elevation_factor_m * phi
                cosine = phi[-1] - force[n, -1] / stiffness
                damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
                sine = (rate[-1] + mode.damping_ratio * mode.omega_rad_s * cosine) / damped
                amplitudes[m, n] = mode.wall_elevation_factor_m * np.concatenate((cosine, sine))
        return Evaluation(
            kinematic["velocity"],
            kinematic["acceleration"],
            kinematic["jerk"],
            kinematic["omega"],
            kinematic["alpha"],
            force,
            walls,
            amplitudes,
        )

    def worst(self, evaluation: Evaluation, samples: Samples) -> dict[str, float]:
        """Each limited quantity's peak divided by its limit."""
        lim = self.limits
        ratios = {
            "velocity": _peak(evaluation.velocity) / lim.max_velocity_m_s,
            "acceleration": _peak(evaluation.acceleration) / lim.max_acceleration_m_s2,
            "jerk": _peak(evaluation.jerk) / lim.max_jerk_m_s3,
            "peak slosh": _peak(evaluation.wall) / lim.max_height_m,
            "residual slosh": float(
                np.max(np.sum(np.linalg.norm(evaluation.amplitude, axis=2), axis=1))
            )
            / lim.max_residual_height_m,
        }
        if lim.max_angular_velocity_rad_s is not None:
            ratios["angular velocity"] = _peak(evaluation.omega) / lim.max_angular_velocity_rad_s
        if lim.max_angular_acceleration_rad_s2 is not None:
            ratios["angular acceleration"] = (
                _peak(evaluation.alpha) / lim.max_angular_acceleration_rad_s2
            )
        if self.tilt:
            tilt = _held(samples.tilt_rad, 2)
            rate = np.diff(tilt, axis=0) / self.ts
            ratios["tilt"] = _peak(samples.tilt_rad) / lim.max_tilt_rad
            ratios["tilt rate"] = _peak(rate) / lim.max_tilt_rate_rad_s
            ratios["tilt acceleration"] = (
                _peak(np.diff(rate, axis=0) / self.ts) / lim.max_tilt_acceleration_rad_s2
            )
        return ratios


    # ----------------------------------------------------------------- linearisation
    def jacobians(self, samples: Samples) -> list[Bands]:
        """Banded derivatives of the samples' positions, angular velocities and forces with
        respect to each variable block (s, then r_x, r_y with tilt).

        Every quantity at sample k depends on the samples k-1..k+1 only (positions on k, the
        angular velocity on k-1 and k, the forces on k-1..k+1 through the second difference),
        so perturbing every third sample at once separates the bands (Curtis, Powell & Reid,
        IMA J. Appl. Math. 13 (1974) 117-119); central differences, the spin held fixed.
        """
        n = samples.s_m.size
        _, base = self.forces(samples)
        spin = base["spin"]
        columns: list[int | None] = [None] + ([0, 1] if self.tilt else [])
        bands = []
        for column in columns:
            step = 1e-7 * max(self.path.length_m, 1.0) if column is None else 1e-7
            force = np.zeros((3, len(self.modes), n, 2))
            position = np.zeros((n, 3))
            omega = np.zeros((2, n + 1, 3))
            for colour in range(3):
                chosen = np.arange(colour, n, 3)
                plus, minus = _perturbed(samples, chosen, column, step)
                (fp, kp), (fm, km) = self.forces(plus, spin), self.forces(minus, spin)
                dforce = (fp - fm) / (2.0 * step)
                position[chosen] = ((kp["position"] - km["position"]) / (2.0 * step))[chosen]
                domega = (kp["omega"] - km["omega"]) / (2.0 * step)
                for offset in (-1, 0, 1):
                    k = chosen - offset  # the force at k sees the perturbed sample k + offset
                    k = k[(k >= 0) & (k < n)]
                    force[offset + 1][:, k] = dforce[:, k]
                # omega row i (1..n-1) uses samples i-1 and i
                own = chosen[(chosen >= 1) & (chosen <= n - 1)]
                omega[1][own] = domega[own]
                prev = chosen[chosen + 1 <= n - 1] + 1
                omega[0][prev] = domega[prev]
            bands.append(Bands(position, omega, force))
        return bands

    def responses(self, steps: int) -> list[list[tuple[FloatArray, FloatArray]]]:
        """Per band model and mode, the dense maps (N+1, N+1) from the forces f_0..f_N to the
        deflection phi_k and its rate (`kernels` arranged as Toeplitz matrices; the first
        column carries f_0, which sets the initial rest and is the reference of the excess)."""
        cache = self.__dict__.setdefault("_responses", {})
        if steps not in cache:
            kernels = self.kernels(steps)
            n = steps + 1
            index = np.arange(n)[:, None] - np.arange(n)[None, :] + 1
            maps = []
            for m, model in enumerate(self.models):
                per_mode = []
                for k, mode in enumerate(model.modes):
                    angle, rate = kernels[m][k]
                    a = np.where(index >= 1, angle[np.clip(index, 0, steps)], 0.0)
                    r = np.where(index >= 1, rate[np.clip(index, 0, steps)], 0.0)
                    a[:, 0] = 0.0
                    r[:, 0] = 0.0
                    stiffness = mode.length_m * mode.omega_rad_s**2
                    a[:, 0] = 1.0 / stiffness - a[:, 1:].sum(axis=1)
                    r[:, 0] = -r[:, 1:].sum(axis=1)
                    per_mode.append((a, r))
                maps.append(per_mode)
            cache[steps] = maps
        return cache[steps]  # type: ignore[no-any-return]



    # ----------------------------------------------------------------- the iteration
    def improve(
        self, start: Samples, fixed_end: bool = False, trust_m: float | None = None
    ) -> Iterate:
        """Sequential LPs from ``start`` with N fixed: the furthest reach (or, with
        ``fixed_end``, the earliest progress of a move ending at S). A step is accepted when
        its exact evaluation meets every limit, or breaks them less than the current iterate;
        the trust region doubles after a full accepted step and halves after a rejected one.

        Returns the best iterate that meets every limit (or, when none does, the last one)."""
        length = self.path.length_m
        current = self.iterate(start)
        best = current
        trust = trust_m if trust_m is not None else 0.05 * length
        cuts: dict[str, list[tuple[int, int, FloatArray]]] = {}
        for _ in range(MAX_ITERATIONS):
            candidate = self.step(current.samples, current.evaluation, trust, fixed_end, cuts)
            if candidate is None:
                trust *= 0.5
                if trust < 1e-7 * length:
                    break
                continue
            trial = self.iterate(candidate)
            _remember(cuts, trial, self.limits)
            if trial.feasible or trial.excess < current.excess:
                moved = float(np.max(np.abs(trial.samples.s_m - current.samples.s_m)))
                gain = trial.reach - current.reach
                current = trial
                if current.feasible and (not best.feasible or current.reach >= best.reach - 1e-12):
                    best = current
                if moved > 0.5 * trust:
                    trust *= 2.0
                if current.feasible and moved < 1e-5 * length and abs(gain) < 1e-6 * length:
                    break
            else:
                trust *= 0.5
                if trust < 1e-7 * length:
                    break
        return best

    def iterate(self, samples: Samples) -> Iterate:
        """The samples with their exact evaluation and ratios to the limits."""
        evaluation = self.evaluate(samples)
        return Iterate(samples, evaluation, self.worst(evaluation, samples))

    # ----------------------------------------------------------------- one program
    def step(
        self,
        samples: Samples,
        evaluation: Evaluation,
        trust_m: float,
        fixed_end: bool,
        cuts: dict[str, list[tuple[int, int, FloatArray]]],
    ) -> Samples | None:
        """One LP around ``samples`` (trust region ``trust_m`` on s); None when it failed."""
        lim, ts = self.limits, self.ts
        n = samples.s_m.size
        steps = n - 1
        keep = 1.0 - PROGRAM_MARGIN
        bands = self.jacobians(samples)
        nb = len(bands)
        t_base = nb * steps
        slack = t_base + len(self.models) * len(self.modes)
        rows = _Rows(slack + 1)

        def var(block: int, k: Any) -> Any:
            return block * steps + (np.asarray(k) - 1)

        # Cartesian kinematics: differences of the positions, ends held at rest.
        derivative = [b.position for b in bands]
        tangent = _tangent_facets(self.path, samples.s_m)
        for key, order, values, limit in (
            ("velocity", 1, evaluation.velocity, lim.max_velocity_m_s),
            ("acceleration", 2, evaluation.acceleration, lim.max_acceleration_m_s2),
            ("jerk", 3, evaluation.jerk, lim.max_jerk_m_s3),
        ):
            # The facets along the path's tangent (both ways) at every row bound the
            # tangential part everywhere; the current direction where the quantity is near its
            # limit and the directions earlier iterates broke refine the norm.
            directions = _active(values, limit) + cuts.get(key, []) + tangent[order]
            _difference_rows(rows, directions, values, order, derivative, var, n, ts, limit * keep, slack)
        # Angular velocity and acceleration of the container.
        for key, limit, order in (
            ("omega", lim.max_angular_velocity_rad_s, 1),
            ("alpha", lim.max_angular_acceleration_rad_s2, 2),
        ):
            if limit is not None:
                values = evaluation.omega if order == 1 else evaluation.alpha
                directions = _active(values, limit) + cuts.get(key, [])
                _angular_rows(rows, directions, values, order, bands, var, n, ts, limit * keep, slack)
        # Tilt, its rate and acceleration: differences of the tilt variables.
        if self.tilt:
            tilt = samples.tilt_rad
            unit = [np.zeros((n, 2))] + [np.tile(np.eye(2)[c], (n, 1)) for c in range(2)]
            padded = _held(tilt, 2)
            rate = np.diff(padded, axis=0) / ts
            for key, order, values, limit in (
                ("tilt", 0, tilt, lim.max_tilt_rad),
                ("tilt rate", 1, rate, lim.max_tilt_rate_rad_s),
                ("tilt acceleration", 2, np.diff(rate, axis=0) / ts, lim.max_tilt_acceleration_rad_s2),
            ):
                directions = _active(values, limit) + cuts.get(key, []) + _axes(values.shape[0])
                _difference_rows(rows, directions, values, order, unit, var, n, ts, limit * keep, slack)
        # Slosh: the wall height at the active samples, the residual bound after the move.
        self._slosh_rows(rows, evaluation, bands, var, n, t_base, slack, cuts, keep)
        # Monotone progress: s_{k+1} >= s_k, with s_0 = 0 fixed.
        s = samples.s_m
        k = np.arange(1, n - 1)
        rows.add(
            np.repeat(np.arange(k.size), 2),
            np.column_stack((var(0, k + 1), var(0, k))).ravel(),
            np.tile([1.0, -1.0], k.size),
            s[k] - s[k + 1],
            np.full(k.size, np.inf),
        )
        length = self.path.length_m
        col_lo = np.full(rows.columns, -np.inf)
        col_hi = np.full(rows.columns, np.inf)
        sk = var(0, np.arange(1, n))
        col_lo[sk] = np.maximum(-trust_m, -s[1:])
        col_hi[sk] = np.minimum(trust_m, length - s[1:])
        end = var(0, n - 1)
        if fixed_end:
            col_lo[end] = col_hi[end] = length - s[-1]
        for block in range(1, nb):
            cols = var(block, np.arange(1, n))
            radians = max(trust_m / max(length, 1e-9), 0.01)
            col_lo[cols], col_hi[cols] = -radians, radians
            last = var(block, n - 1)
            col_lo[last] = col_hi[last] = -samples.tilt_rad[-1, block - 1]
        col_lo[t_base:] = 0.0
        cost = np.zeros(rows.columns)
        if fixed_end:
            cost[sk] = -1.0 / n  # among the moves of this duration, the earliest progress
        else:
            cost[end] = -1.0
        cost[slack] = 100.0 * length
        solution = _solve_lp(cost, col_lo, col_hi, rows)
        self.programs += 1
        if solution is None:
            return None
        new_s = np.concatenate(([0.0], s[1:] + solution[sk]))
        new_s = np.clip(np.maximum.accumulate(new_s), 0.0, length)
        tilt = samples.tilt_rad.copy()
        for block in range(1, nb):
            tilt[1:, block - 1] += solution[var(block, np.arange(1, n))]
        tilt[0] = tilt[-1] = 0.0
        return Samples(new_s, tilt)

    def _slosh_rows(
        self,
        rows: _Rows,
        evaluation: Evaluation,
        bands: list[Bands],
        var: Any,
        n: int,
        t_base: int,
        slack: int,
        cuts: dict[str, list[tuple[int, int, FloatArray]]],
        keep: float,
    ) -> None:
        """Wall-height facets at the samples near the limit and the residual's lifted norms."""
        lim = self.limits
        steps = n - 1
        maps = self.responses(steps)
        height = lim.max_height_m * keep
        for m, model in enumerate(self.models):
            wall = evaluation.wall[m]
            directions = _peaks(wall, lim.max_height_m) + [
                d for d in cuts.get("wall", []) if d[0] == m
            ]
            if directions:
                ks = np.array([d[1] for d in directions])
                us = np.array([d[2] for d in directions])
                dense = []
                for band in bands:
                    block = np.zeros((ks.size, n))
                    for k, mode in enumerate(model.modes):
                        angle = maps[m][k][0][ks]  # (rows, n): d phi_K / d f_i
                        for offset in (-1, 0, 1):
                            along = us @ band.force[offset + 1][k].T  # u . d f_i / d x_{i+o}
                            _shift_add(block, mode.wall_elevation_factor_m * angle * along, offset)
                    dense.append(block[:, 1:])
                rows.add_dense(
                    np.hstack(dense),
                    np.full(ks.size, -np.inf),
                    height - np.sum(us * wall[ks], axis=1),
                    [(slack, -lim.max_height_m)],
                )
            # Residual: t_{m,k} >= d . a_{m,k} for a set of unit directions d, sum_k t <= r.
            for k, mode in enumerate(model.modes):
                amplitude = self._amplitude_rows(maps[m][k], mode, bands, k, n)
                a0 = evaluation.amplitude[m, k]
                directions = [d[2] for d in cuts.get("residual", []) if d[0] == m and d[1] == k]
                directions += list(np.vstack((np.eye(4), -np.eye(4))))
                norm = float(np.linalg.norm(a0))
                if norm > 1e-12:
                    directions.append(a0 / norm)
                facets = np.array(directions)
                rows.add_dense(
                    facets @ amplitude,
                    np.full(len(facets), -np.inf),
                    -(facets @ a0),
                    [(t_base + m * len(self.modes) + k, -1.0)],
                )
            count = len(model.modes)
            rows.add(
                np.zeros(count, dtype=int),
                t_base + m * count + np.arange(count),
                np.ones(count),
                [-np.inf],
                [lim.max_residual_height_m * keep],
                [(slack, -lim.max_residual_height_m)],
            )

    def _amplitude_rows(
        self, maps: tuple[FloatArray, FloatArray], mode: Any, bands: list[Bands], k: int, n: int
    ) -> FloatArray:
        """d a / d x (4, blocks x N) of mode ``k``'s scaled free-oscillation vector
        e (A_x, A_y, B_x, B_y) after the last sample (`Evaluation.amplitude`)."""
        steps = n - 1
        stiffness = mode.length_m * mode.omega_rad_s**2
        damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
        decay = mode.damping_ratio * mode.omega_rad_s
        angle_last, rate_last = maps[0][steps], maps[1][steps]
        out = []
        for band in bands:
            block = np.zeros((4, n))
            for offset in (-1, 0, 1):
                f = band.force[offset + 1][k]  # (n, 2): d f_i / d x_{i+offset}
                for c in range(2):
                    cosine = angle_last * f[:, c]
                    cosine[steps] -= f[steps, c] / stiffness
                    sine = (rate_last * f[:, c] + decay * cosine) / damped
                    scaled = mode.wall_elevation_factor_m * np.vstack((cosine, sine))
                    _shift_add(block[c : c + 1], scaled[:1], offset)
                    _shift_add(block[2 + c : 3 + c], scaled[1:], offset)
            out.append(block[:, 1:])
        return np.hstack(out)


@dataclass(frozen=True, eq=False)
class Iterate:
    """Samples, their evaluation and each limited quantity's peak over its limit."""

    samples: Samples
    evaluation: Evaluation
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


def _remember(
    cuts: dict[str, list[tuple[int, int, FloatArray]]], trial: Iterate, limits: ProgramLimits
) -> None:
    """Add facets where the trial broke a limit (in the direction it broke it)."""
    evaluation = trial.evaluation
    keep = 1.0 - PROGRAM_MARGIN
    checks = [
        ("velocity", evaluation.velocity, limits.max_velocity_m_s, 0),
        ("acceleration", evaluation.acceleration, limits.max_acceleration_m_s2, 0),
        ("jerk", evaluation.jerk, limits.max_jerk_m_s3, 0),
    ]
    if limits.max_angular_velocity_rad_s is not None:
        checks.append(("omega", evaluation.omega, limits.max_angular_velocity_rad_s, 0))
    if limits.max_angular_acceleration_rad_s2 is not None:
        checks.append(("alpha", evaluation.alpha, limits.max_angular_acceleration_rad_s2, 0))
    checks += [("wall", wall, limits.max_height_m, m) for m, wall in enumerate(evaluation.wall)]
    for key, values, limit, model in checks:
        norms = np.linalg.norm(values, axis=-1)
        for k in np.flatnonzero(norms > limit * keep):
            cuts.setdefault(key, []).append((model, int(k), values[k] / norms[k]))
    for m, per_mode in enumerate(evaluation.amplitude):
        for k, vector in enumerate(per_mode):
            norm = float(np.linalg.norm(vector))
            if norm > 1e-12:
                cuts.setdefault("residual", []).append((m, k, vector / norm))


@dataclass(frozen=True, eq=False)
class Bands:
    """Derivatives of one variable block: ``position`` (n, 3) d P_k / d x_k, ``omega``
    (2, n + 1, 3) d w_i / d x_{i-1} and d w_i / d x_i, ``force`` (3, modes, n, 2)
    d f_k / d x_{k+o} for o = -1, 0, 1."""

    position: FloatArray
    omega: FloatArray
    force: FloatArray


def _perturbed(
    samples: Samples, chosen: FloatArray, column: int | None, step: float
) -> tuple[Samples, Samples]:
    """The samples with the ``chosen`` ones moved by +- ``step`` in s or in a tilt angle."""
    out = []
    for sign in (1.0, -1.0):
        s, tilt = samples.s_m.copy(), samples.tilt_rad.copy()
        if column is None:
            s[chosen] += sign * step
        else:
            tilt[chosen, column] += sign * step
        out.append(Samples(s, tilt))
    return out[0], out[1]


def _causal(kernel: FloatArray, excess: FloatArray) -> FloatArray:
    """sum_{i>=1} kernel[k - i + 1] excess_i for every k (both on axis 0 of ``excess``)."""
    n = excess.shape[0]
    out = np.zeros_like(excess)
    for column in range(excess.shape[1]):
        full = np.convolve(kernel[1:], excess[1:, column])[: n - 1]
        out[1:, column] = full
    return out


def _peak(values: FloatArray) -> float:
    """Largest Euclidean norm along the last axis."""
    return float(np.max(np.linalg.norm(values, axis=-1))) if values.size else 0.0


def _shift_add(target: FloatArray, term: FloatArray, offset: int) -> None:
    """target[:, i + offset] += term[:, i] (in place, columns outside dropped)."""
    n = term.shape[1]
    if offset >= 0:
        target[:, offset:] += term[:, : n - offset]
    else:
        target[:, :offset] += term[:, -offset:]


class _Rows:
    """The rows of one LP as sparse triplets, with their bounds."""

    def __init__(self, columns: int) -> None:
        self.columns = columns
        self.count = 0
        self._r: list[FloatArray] = []
        self._c: list[FloatArray] = []
        self._v: list[FloatArray] = []
        self.lower: list[FloatArray] = []
        self.upper: list[FloatArray] = []

    def add(
        self,
        r: Any,
        c: Any,
        v: Any,
        lo: Any,
        hi: Any,
        extra: list[tuple[int, float]] = (),  # type: ignore[assignment]
    ) -> None:
        """Rows lo <= A x <= hi with local row indices ``r``; ``extra`` adds (column, value)
        to every one of the new rows."""
        lo = np.atleast_1d(np.asarray(lo, dtype=float))
        hi = np.atleast_1d(np.asarray(hi, dtype=float))
        base = self.count
        self._r.append(np.asarray(r, dtype=int) + base)
        self._c.append(np.asarray(c, dtype=int))
        self._v.append(np.asarray(v, dtype=float))
        local = np.arange(lo.size)
        for column, value in extra:
            self._r.append(local + base)
            self._c.append(np.full(lo.size, column))
            self._v.append(np.full(lo.size, value))
        self.lower.append(lo)
        self.upper.append(hi)
        self.count += lo.size

    def add_dense(
        self, matrix: FloatArray, lo: Any, hi: Any, extra: list[tuple[int, float]] = ()  # type: ignore[assignment]
    ) -> None:
        """Rows whose coefficients on the first columns are ``matrix``."""
        r, c = np.nonzero(matrix)
        self.add(r, c, matrix[r, c], lo, hi, extra)

    def matrix(self) -> Any:
        """The constraint matrix (compressed columns)."""
        return sparse.coo_matrix(
            (np.concatenate(self._v), (np.concatenate(self._r), np.concatenate(self._c))),
            shape=(self.count, self.columns),
        ).tocsc()


def _active(values: FloatArray, limit: float) -> list[tuple[int, int, FloatArray]]:
    """(0, row, unit direction) of every row whose norm exceeds `ACTIVE_FRACTION` of ``limit``."""
    norms = np.linalg.norm(values, axis=-1)
    return [(0, int(k), values[k] / norms[k]) for k in np.flatnonzero(norms > ACTIVE_FRACTION * limit)]


def _axes(count: int) -> list[tuple[int, int, FloatArray]]:
    """The +-x and +-y facets of every row (a box inside which the norm facets refine)."""
    return [(0, k, sign * np.eye(2)[c]) for k in range(count) for c in range(2) for sign in (1.0, -1.0)]


#: Finite-difference weights of orders 0..3 (the forward differences of the padded samples).
_WEIGHTS = {0: (1.0,), 1: (-1.0, 1.0), 2: (1.0, -2.0, 1.0), 3: (-1.0, 3.0, -3.0, 1.0)}


def _difference_rows(
    rows: _Rows,
    directions: list[tuple[int, int, FloatArray]],
    values: FloatArray,
    order: int,
    derivative: list[FloatArray],
    var: Any,
    n: int,
    ts: float,
    limit: float,
    slack: int,
) -> None:
    """Facets u . Q_i <= limit of the order-th difference Q of sampled values (held at rest
    beyond both ends: row i of order d covers padded samples i..i+d, sample k = i + j - pad).

    ``derivative[b]`` (n, dim) is d value_k / d x_{b,k}; order 0 is the samples themselves.
    """
    if not directions:
        return
    pad = 2 if order > 0 else 0
    index = np.array([d[1] for d in directions])
    units = np.array([d[2] for d in directions])
    count = index.size
    r_all, c_all, v_all = [], [], []
    for j, weight in enumerate(_WEIGHTS[order]):
        k = np.clip(index + j - pad, 0, n - 1)
        moving = k >= 1
        for block, d in enumerate(derivative):
            coefficient = weight / ts**order * np.sum(units * d[k], axis=1)
            use = moving & (coefficient != 0.0)
            r_all.append(np.flatnonzero(use))
            c_all.append(var(block, k[use]))
            v_all.append(coefficient[use])
    rows.add(
        np.concatenate(r_all),
        np.concatenate(c_all),
        np.concatenate(v_all),
        np.full(count, -np.inf),
        limit - np.sum(units * values[index], axis=1),
        [(slack, -limit)],
    )


def _angular_rows(
    rows: _Rows,
    directions: list[tuple[int, int, FloatArray]],
    values: FloatArray,
    order: int,
    bands: list[Bands],
    var: Any,
    n: int,
    ts: float,
    limit: float,
    slack: int,
) -> None:
    """Facets of the angular velocity w_i (order 1; rows 0..n, w_i from samples i-1, i) or of
    its difference (w_{i+1} - w_i) / Ts (order 2)."""
    if not directions:
        return
    index = np.array([d[1] for d in directions])
    units = np.array([d[2] for d in directions])
    r_all, c_all, v_all = [], [], []
    terms = [(0, 1.0)] if order == 1 else [(1, 1.0 / ts), (0, -1.0 / ts)]
    for shift, weight in terms:
        row = index + shift  # the omega row
        for band_slot, sample_shift in ((0, -1), (1, 0)):
            k = row + sample_shift
            ok = (row >= 1) & (row <= n - 1) & (k >= 1) & (k <= n - 1)
            for block, band in enumerate(bands):
                d = band.omega[band_slot][np.clip(row, 0, n)]
                coefficient = weight * np.sum(units * d, axis=1)
                use = ok & (coefficient != 0.0)
                r_all.append(np.flatnonzero(use))
                c_all.append(var(block, k[use]))
                v_all.append(coefficient[use])
    rows.add(
        np.concatenate(r_all),
        np.concatenate(c_all),
        np.concatenate(v_all),
        np.full(index.size, -np.inf),
        limit - np.sum(units * values[index], axis=1),
        [(slack, -limit)],
    )


def _solve_lp(cost: FloatArray, col_lo: FloatArray, col_hi: FloatArray, rows: _Rows) -> Any:
    """Solve min cost x over the rows and bounds with HiGHS; None unless optimal."""
    import highspy

    highs = new_highs()
    inf = highspy.kHighsInf
    matrix = rows.matrix()
    lp = highspy.HighsLp()
    lp.num_col_ = cost.size
    lp.num_row_ = rows.count
    lp.col_cost_ = cost
    lp.col_lower_ = np.where(np.isfinite(col_lo), col_lo, -inf)
    lp.col_upper_ = np.where(np.isfinite(col_hi), col_hi, inf)
    lower, upper = np.concatenate(rows.lower), np.concatenate(rows.upper)
    lp.row_lower_ = np.where(np.isfinite(lower), lower, -inf)
    lp.row_upper_ = np.where(np.isfinite(upper), upper, inf)
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.start_ = matrix.indptr
    lp.a_matrix_.index_ = matrix.indices
    lp.a_matrix_.value_ = matrix.data
    import os
    for option in os.environ.get("SK_HIGHS", "").split(","):
        if option:
            key, value = option.split("=")
            highs.setOptionValue(key, int(value) if value.isdigit() else value)
    highs.passModel(lp)
    if os.environ.get("SK_DUMP"):
        highs.writeModel(os.environ["SK_DUMP"])
    highs.run()
    if highs.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return None
    return np.asarray(highs.getSolution().col_value, dtype=float)


def _tangent_facets(path: Any, s_m: FloatArray) -> dict[int, list[tuple[int, int, FloatArray]]]:
    """Facets +-t (path tangent at the row's middle sample) for every row of the padded first,
    second and third differences (row i of order d spans samples i - 2 .. i - 2 + d)."""
    n = s_m.size
    tangent = path.tangent(s_m)
    out: dict[int, list[tuple[int, int, FloatArray]]] = {}
    for order in (1, 2, 3):
        count = n + 4 - order
        middle = np.clip(np.arange(count) + order // 2 - 2 + (order % 2) * 0, 0, n - 1)
        facets = []
        for i in range(count):
            t = tangent[middle[i]]
            if np.any(t):
                facets.append((0, i, t))
                if order > 1:
                    facets.append((0, i, -t))
        out[order] = facets
    return out


def _peaks(values: FloatArray, limit: float) -> list[tuple[int, int, FloatArray]]:
    """(0, row, direction) at the local maxima of the norm above half the limit and their
    neighbours (an oscillating wall height needs rows only near its crests)."""
    norms = np.linalg.norm(values, axis=-1)
    padded = np.concatenate(([-1.0], norms, [-1.0]))
    crest = (norms >= padded[:-2]) & (norms >= padded[2:]) & (norms > 0.5 * limit)
    rows = np.flatnonzero(crest)
    rows = np.unique(np.clip(np.concatenate((rows - 1, rows, rows + 1)), 0, norms.size - 1))
    return [(0, int(k), values[k] / norms[k]) for k in rows if norms[k] > 0]
