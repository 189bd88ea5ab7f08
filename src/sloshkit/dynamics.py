"""Equations of motion of the equivalent pendulums, simulation and slosh metrics.

One convention for every model: x is the container's position along the move [m], theta_n the
angle of mode n's pendulum [rad] (positive when the bob swings towards +x, i.e. it lags the
container with theta < 0 while accelerating forward), omega_n, zeta_n and L_n from the
`SloshModel`.

Models
------
- ``linear`` (seed paper eq. 7, per mode; Ibrahim 2005 §6.2):
  theta'' + 2 zeta omega theta' + omega^2 theta = -x''/L.
- ``nonlinear`` (large-angle pendulum in the container frame; Ibrahim 2005 §6.2):
  theta'' + 2 zeta omega theta' + omega^2 sin(theta) = -(x''/L) cos(theta).
- `simulate_cart_pendulum`: the seed paper's cart-pendulum eqs. 4-5, generalised to all modes,
  driven by a force on the cart (see its docstring).

The paper prints a cos^2(theta) factor on the damper of eq. 5; we put the damper on the
pendulum's relative rotation, c_theta theta' with c_theta = 2 zeta omega m L^2, which is what a
rotational damper in the hinge (the paper's Simscape revolute joint) does and which reduces to
eq. 7 when linearised.

Fast linear path
----------------
The linear equation is rewritten with y = theta' + v/L so that it is driven by the container's
velocity v (continuous for every rest-to-rest law) instead of its acceleration:
theta' = y - v/L, y' = -omega^2 theta - 2 zeta omega (y - v/L). It is discretised exactly for a
velocity that is linear between samples (first-order hold, Franklin, Powell & Workman, *Digital
Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2): exact for the trapezoidal law and
second-order accurate for the others. The resulting recursion is a second-order IIR filter run
by `scipy.signal.lfilter`, vectorised over any number of cases that share a mode.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp
from scipy.linalg import expm
from scipy.signal import lfilter, ss2tf

from sloshkit.errors import InputError, require_positive, warn_validity
from sloshkit.modal import SloshModel
from sloshkit.motion.laws import Motion

FloatArray = NDArray[np.float64]
ModelKind = Literal["linear", "nonlinear"]
MODEL_KINDS: tuple[str, ...] = ("linear", "nonlinear")

#: Default tolerance for the settling time: 0.1 degree of the first mode [rad].
DEFAULT_SETTLE_TOLERANCE_RAD = math.radians(0.1)


# ---------------------------------------------------------------------------------------------
# Fast exact-discretisation path (linear)
# ---------------------------------------------------------------------------------------------


@lru_cache(maxsize=4096)
def velocity_driven_discretisation(
    omega_rad_s: float, damping_ratio: float, length_m: float, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(phi, gamma, g1) of the first-order-hold discretisation in the shifted state z.

    With s_k = (theta_k, y_k), y = theta' + v/L, and velocity samples u_k: z_k = s_k - g1 u_k,
    z_{k+1} = phi z_k + gamma u_k, s_k = z_k + g1 u_k, z_0 = 0 for a start from rest.
    """
    w, z, length, h = omega_rad_s, damping_ratio, length_m, sample_period_s
    a_matrix = np.array([[0.0, 1.0], [-(w**2), -2.0 * z * w]])
    b_vector = np.array([-1.0 / length, 2.0 * z * w / length])
    augmented = np.zeros((4, 4))
    augmented[:2, :2] = a_matrix
    augmented[:2, 2] = b_vector
    augmented[2, 3] = 1.0
    exponential = expm(augmented * h)
    phi = exponential[:2, :2]
    gamma_hold = exponential[:2, 2]  # integral of e^{As} B over one step
    gamma_ramp = exponential[:2, 3] / h  # integral of e^{As} B (h - s) / h
    g0 = gamma_hold - gamma_ramp
    g1 = gamma_ramp
    return phi, phi @ g1 + g0, g1


@lru_cache(maxsize=4096)
def velocity_driven_filters(
    omega_rad_s: float, damping_ratio: float, length_m: float, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """IIR coefficients (b_theta, a, b_y, a) of the first-order-hold discretisation.

    ``lfilter(b_theta, a, v)`` gives theta_k and ``lfilter(b_y, a, v)`` gives
    y_k = theta'_k + v_k / L for velocity samples v_k starting from rest (v_0 = 0).
    """
    phi, gamma, g1 = velocity_driven_discretisation(
        omega_rad_s, damping_ratio, length_m, sample_period_s
    )
    b_theta, a_theta = ss2tf(phi, gamma[:, None], np.array([[1.0, 0.0]]), np.array([[g1[0]]]))
    b_y, a_y = ss2tf(phi, gamma[:, None], np.array([[0.0, 1.0]]), np.array([[g1[1]]]))
    return (
        np.asarray(b_theta[0], dtype=float),
        np.asarray(a_theta, dtype=float),
        np.asarray(b_y[0], dtype=float),
        np.asarray(a_y, dtype=float),
    )


def linear_mode_response(
    velocity_m_s: FloatArray,
    sample_period_s: float,
    omega_rad_s: float,
    damping_ratio: float,
    length_m: float,
) -> tuple[FloatArray, FloatArray]:
    """Angle and angular rate of one linear mode for velocity samples (last axis = time).

    ``velocity_m_s`` may be 2-D (cases x samples); all cases share the mode. Starts from rest.
    Returns (theta [rad], theta' [rad/s]) with the shape of the input.
    """
    b_theta, a, b_y, _ = velocity_driven_filters(
        float(omega_rad_s), float(damping_ratio), float(length_m), float(sample_period_s)
    )
    theta = lfilter(b_theta, a, velocity_m_s, axis=-1)
    rate = lfilter(b_y, a, velocity_m_s, axis=-1) - velocity_m_s / length_m
    return np.asarray(theta, dtype=float), np.asarray(rate, dtype=float)


def free_amplitude(
    angle_rad: FloatArray | float,
    rate_rad_s: FloatArray | float,
    omega_rad_s: float,
    damping_ratio: float,
) -> FloatArray:
    """Envelope amplitude of the free damped oscillation through the state (theta, theta').

    theta(t) = e^{-zeta w t} (A cos w_d t + B sin w_d t), A = theta, B = (theta' + zeta w theta)
    / w_d; the amplitude is sqrt(A^2 + B^2) [rad].
    """
    damped = omega_rad_s * math.sqrt(max(1e-300, 1.0 - damping_ratio**2))
    angle = np.asarray(angle_rad, dtype=float)
    quadrature = (
        np.asarray(rate_rad_s, dtype=float) + damping_ratio * omega_rad_s * angle
    ) / damped
    return np.asarray(np.hypot(angle, quadrature), dtype=float)


# ---------------------------------------------------------------------------------------------
# Response object
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class SloshResponse:
    """Slosh response to a container motion (arrays over time; modes on the first axis).

    Attributes
    ----------
    time_s : sample times [s], from 0, uniform step
    position_m, velocity_m_s, acceleration_m_s2 : the container's motion
    angle_rad, rate_rad_s : pendulum angle and angular rate, shape (modes, samples)
    move_duration_s : the move's duration T [s]; after T the container rests
    model : the `SloshModel` simulated; kind: ``"linear"`` or ``"nonlinear"``
    residual_amplitude_rad : per mode, amplitude of the free oscillation left at T [rad]
    """

    time_s: FloatArray
    position_m: FloatArray
    velocity_m_s: FloatArray
    acceleration_m_s2: FloatArray
    angle_rad: FloatArray
    rate_rad_s: FloatArray
    move_duration_s: float
    model: SloshModel
    kind: str
    residual_amplitude_rad: FloatArray
    motion_name: str = ""
    peak_jerk_m_s3: float = float("nan")
    settle_tolerance_rad: float = DEFAULT_SETTLE_TOLERANCE_RAD
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def wall_elevation_m(self) -> FloatArray:
        """Free-surface elevation at the wall on the +x side [m]: sum_n 2R/(xi_n^2-1) theta_n for
        the linear model, with sin(theta_n) for the nonlinear one (linear mode-shape mapping,
        see `sloshkit.modal.wall_elevation_factor`)."""
        factors = np.array([mode.wall_elevation_factor_m for mode in self.model.modes])
        angles = self.angle_rad if self.kind == "linear" else np.sin(self.angle_rad)
        return np.asarray(factors @ angles, dtype=float)

    @property
    def angular_acceleration_rad_s2(self) -> FloatArray:
        """theta_n'' from the equation of motion [rad/s^2]."""
        omega = np.array([mode.omega_rad_s for mode in self.model.modes])[:, None]
        zeta = np.array([mode.damping_ratio for mode in self.model.modes])[:, None]
        length = np.array([mode.length_m for mode in self.model.modes])[:, None]
        theta = self.angle_rad
        if self.kind == "linear":
            return np.asarray(
                -2 * zeta * omega * self.rate_rad_s
                - omega**2 * theta
                - self.acceleration_m_s2 / length,
                dtype=float,
            )
        return np.asarray(
            -2 * zeta * omega * self.rate_rad_s
            - omega**2 * np.sin(theta)
            - self.acceleration_m_s2 / length * np.cos(theta),
            dtype=float,
        )

    @property
    def slosh_force_n(self) -> FloatArray:
        """Lateral force of the sloshing liquid on the container beyond rigid-body inertia [N]:
        -sum_n m_n L_n (theta_n'' cos theta_n - theta_n'^2 sin theta_n) (the reaction of the
        bobs' motion relative to the container). The whole liquid pushes with
        -m_F x'' + slosh_force_n."""
        mass = np.array([mode.slosh_mass_kg for mode in self.model.modes])[:, None]
        length = np.array([mode.length_m for mode in self.model.modes])[:, None]
        theta, rate = self.angle_rad, self.rate_rad_s
        relative = self.angular_acceleration_rad_s2 * np.cos(theta) - rate**2 * np.sin(theta)
        return np.asarray(-np.sum(mass * length * relative, axis=0), dtype=float)

    def _during_move(self) -> NDArray[np.bool_]:
        return np.asarray(self.time_s <= self.move_duration_s + 1e-12)

    @property
    def peak_angle_rad(self) -> float:
        """Peak |theta_1| during the move [rad]."""
        return float(np.max(np.abs(self.angle_rad[0, self._during_move()])))

    @property
    def peak_wall_elevation_m(self) -> float:
        """Peak |wall elevation| during the move [m]."""
        return float(np.max(np.abs(self.wall_elevation_m[self._during_move()])))

    @property
    def residual_angle_rad(self) -> float:
        """Amplitude of the first mode's free oscillation left at the end of the move [rad]."""
        return float(self.residual_amplitude_rad[0])

    @property
    def residual_wall_elevation_m(self) -> float:
        """Bound on the wall elevation after the move: sum_n 2R/(xi_n^2-1) A_n [m]."""
        factors = np.array([mode.wall_elevation_factor_m for mode in self.model.modes])
        return float(factors @ self.residual_amplitude_rad)

    @property
    def settling_time_s(self) -> float:
        """Time from the start until |theta_1| stays below the tolerance [s].

        After the move the first mode decays as A_T exp(-zeta omega (t - T)); if A_T is above
        the tolerance the settling time is T + ln(A_T / tol) / (zeta omega) (inf without
        damping), otherwise the last sample during the move above the tolerance.
        """
        tolerance = self.settle_tolerance_rad
        mode = self.model.modes[0]
        amplitude = self.residual_angle_rad
        if amplitude > tolerance:
            decay = mode.damping_ratio * mode.omega_rad_s
            if decay <= 0.0:
                return math.inf
            return self.move_duration_s + math.log(amplitude / tolerance) / decay
        during = self._during_move()
        above = np.nonzero(np.abs(self.angle_rad[0, during]) > tolerance)[0]
        if above.size == 0:
            return 0.0
        index = min(int(above[-1]) + 1, int(np.count_nonzero(during)) - 1)
        return float(self.time_s[index])

    def metrics(self) -> dict[str, float]:
        """The simulate command's JSON keys (SI; angles in degrees as the keys say)."""
        return {
            "duration_s": self.move_duration_s,
            "peak_angle_deg": math.degrees(self.peak_angle_rad),
            "residual_angle_deg": math.degrees(self.residual_angle_rad),
            "peak_wall_elevation_m": self.peak_wall_elevation_m,
            "residual_wall_elevation_m": self.residual_wall_elevation_m,
            "settling_time_s": self.settling_time_s,
            "peak_acceleration_m_s2": float(np.max(np.abs(self.acceleration_m_s2))),
            "peak_jerk_m_s3": self.peak_jerk_m_s3,
        }

    def columns(self) -> dict[str, FloatArray]:
        """Time series as named columns (SI units in the names)."""
        data: dict[str, FloatArray] = {
            "t_s": self.time_s,
            "position_m": self.position_m,
            "velocity_m_s": self.velocity_m_s,
            "acceleration_m_s2": self.acceleration_m_s2,
        }
        for index, mode in enumerate(self.model.modes):
            data[f"angle_{mode.n}_rad"] = self.angle_rad[index]
            data[f"rate_{mode.n}_rad_s"] = self.rate_rad_s[index]
        data["wall_elevation_m"] = self.wall_elevation_m
        data["slosh_force_n"] = self.slosh_force_n
        return data

    def to_csv(self, path: str | Path) -> Path:
        """Write `columns` as CSV, atomically (temporary file, then rename)."""
        from sloshkit.io import write_columns_csv

        return write_columns_csv(path, self.columns())

    def to_pandas(self) -> Any:
        """`columns` as a pandas DataFrame (pandas is optional)."""
        try:
            import pandas as pd
        except ImportError as exc:  # pragma: no cover - depends on the environment
            raise ImportError("to_pandas() needs pandas: pip install pandas") from exc
        return pd.DataFrame(self.columns())

    def plot(self, path: str | Path | None = None) -> Any:
        """Figure of the motion, the slosh angles and the wall elevation; saved if ``path``."""
        from sloshkit.plotting import plot_response

        return plot_response(self, path)


# ---------------------------------------------------------------------------------------------
# Simulation of a container motion
# ---------------------------------------------------------------------------------------------


def default_settle_time(model: SloshModel) -> float:
    """Time simulated after the move for plots: 5 first-mode periods, at least 1 s [s]."""
    return max(1.0, 5.0 * 2.0 * math.pi / model.modes[0].omega_rad_s)


def simulation_grid(
    move_duration_s: float, sample_period_s: float, settle_time_s: float
) -> FloatArray:
    """Uniform times k dt from 0 to at least T + settle time [s] (shared by all paths)."""
    count = math.ceil((move_duration_s + settle_time_s) / sample_period_s - 1e-9) + 1
    return np.arange(count, dtype=float) * sample_period_s


def residual_from_state(
    time_s: FloatArray,
    angle_rad: FloatArray,
    rate_rad_s: FloatArray,
    move_duration_s: float,
    model: SloshModel,
) -> FloatArray:
    """Per-mode free-oscillation amplitude at T, from the state at the first sample t_k >= T
    scaled back by exp(zeta omega (t_k - T)) (exact for the linear model)."""
    index = int(np.searchsorted(time_s, move_duration_s - 1e-12))
    index = min(index, time_s.size - 1)
    lag = time_s[index] - move_duration_s
    amplitudes = []
    for row, mode in enumerate(model.modes):
        amplitude = free_amplitude(
            angle_rad[row, index], rate_rad_s[row, index], mode.omega_rad_s, mode.damping_ratio
        )
        amplitudes.append(float(amplitude) * math.exp(mode.damping_ratio * mode.omega_rad_s * lag))
    return np.asarray(amplitudes)


def simulate(
    motion: Motion,
    model: SloshModel,
    kind: ModelKind = "linear",
    sample_period_s: float = 1e-3,
    settle_time_s: float | None = None,
    settle_tolerance_rad: float = DEFAULT_SETTLE_TOLERANCE_RAD,
) -> SloshResponse:
    """Slosh response of every mode of ``model`` to the container ``motion``.

    Parameters
    ----------
    motion : the container's rest-to-rest motion
    model : equivalent pendulum model
    kind : ``"linear"`` (exact discretisation, fast) or ``"nonlinear"`` (large-angle pendulum,
        integrated with DOP853 piece by piece between the motion's breakpoints)
    sample_period_s : output sample period dt [s]
    settle_time_s : time simulated after the move [s] (default `default_settle_time`)
    settle_tolerance_rad : tolerance on |theta_1| for the settling time [rad]
    """
    if kind not in MODEL_KINDS:
        raise InputError("model", kind, "must be one of " + ", ".join(MODEL_KINDS))
    dt = require_positive("sample_period", sample_period_s, "s")
    settle = default_settle_time(model) if settle_time_s is None else float(settle_time_s)
    if settle < 0.0:
        raise InputError("settle_time", settle, "must be >= 0 s")
    time = simulation_grid(motion.duration_s, dt, settle)
    velocity = motion.velocity(time)
    acceleration = motion.acceleration(time)
    if kind == "linear":
        angle = np.empty((len(model.modes), time.size))
        rate = np.empty_like(angle)
        for row, mode in enumerate(model.modes):
            angle[row], rate[row] = linear_mode_response(
                velocity, dt, mode.omega_rad_s, mode.damping_ratio, mode.length_m
            )
    else:
        angle, rate = _nonlinear_modes(motion, model, time)
    residual = residual_from_state(time, angle, rate, motion.duration_s, model)
    response = SloshResponse(
        time_s=time,
        position_m=motion.position(time),
        velocity_m_s=velocity,
        acceleration_m_s2=acceleration,
        angle_rad=angle,
        rate_rad_s=rate,
        move_duration_s=motion.duration_s,
        model=model,
        kind=kind,
        residual_amplitude_rad=residual,
        motion_name=motion.name,
        peak_jerk_m_s3=motion.peak_jerk_m_s3,
        settle_tolerance_rad=settle_tolerance_rad,
    )
    _warn_beyond_validity(response)
    return response


#: Above this first-mode angle the small-amplitude theory behind the model is doubtful [deg].
LARGE_ANGLE_DEG = 15.0


def _warn_beyond_validity(response: SloshResponse) -> None:
    peak = math.degrees(float(np.max(np.abs(response.angle_rad[0]))))
    if peak > LARGE_ANGLE_DEG:
        warn_validity(
            f"slosh angle reaches {peak:.1f} deg (> {LARGE_ANGLE_DEG:g} deg): beyond "
            "small-amplitude theory; swirl, wave breaking and bubbles are not modelled"
        )
    wall = response.model.container.wall_height_m
    if wall is not None:
        highest = response.model.fill_height_m + float(np.max(np.abs(response.wall_elevation_m)))
        if highest > wall:
            warn_validity(
                f"free surface reaches {1e3 * highest:.1f} mm at the wall, above the "
                f"{1e3 * wall:.1f} mm wall: the liquid may spill"
            )


def _segment_edges(motion: Motion, end_time: float) -> list[float]:
    edges = sorted({0.0, *(float(b) for b in motion.breakpoints_s if 0.0 < b < end_time), end_time})
    if motion.duration_s < end_time:
        edges = sorted({*edges, motion.duration_s})
    return edges


def _nonlinear_modes(
    motion: Motion, model: SloshModel, time: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Large-angle pendulums, one per mode, integrated between breakpoints (DOP853)."""
    angle = np.zeros((len(model.modes), time.size))
    rate = np.zeros_like(angle)
    edges = _segment_edges(motion, float(time[-1]))
    acceleration_pp = motion.derivative_pp(2)
    end_of_move = motion.duration_s
    for row, mode in enumerate(model.modes):
        w, z, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
        state = np.zeros(2)
        for start, stop in itertools.pairwise(edges):
            # Evaluate the acceleration of this piece only: jumps sit on the edges.
            last = float(np.nextafter(stop, start))

            def rhs(
                t: float,
                y: FloatArray,
                start: float = start,
                last: float = last,
                w: float = w,
                z: float = z,
                length: float = length,
            ) -> list[float]:
                moment = min(max(t, start), last)
                accel = float(acceleration_pp(moment)) if moment < end_of_move else 0.0
                return [
                    y[1],
                    -2 * z * w * y[1] - w * w * math.sin(y[0]) - accel / length * math.cos(y[0]),
                ]

            inside = (time >= start) & (time <= stop)
            t_eval = np.union1d(time[inside], [stop])
            solution = solve_ivp(
                rhs, (start, stop), state, method="DOP853", rtol=1e-10, atol=1e-12, t_eval=t_eval
            )
            if not solution.success:  # pragma: no cover - DOP853 does not fail on smooth input
                raise RuntimeError(f"nonlinear integration failed: {solution.message}")
            keep = np.isin(t_eval, time[inside])
            angle[row, inside] = solution.y[0, keep]
            rate[row, inside] = solution.y[1, keep]
            state = solution.y[:, -1]
    return angle, rate


# ---------------------------------------------------------------------------------------------
# The seed paper's cart-pendulum (eqs. 4-5), all modes
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class CartPendulumResponse:
    """Response of the cart-pendulum system to a force on the cart.

    ``position_m``, ``velocity_m_s``: the cart; ``angle_rad``, ``rate_rad_s``: (modes, samples).
    """

    time_s: FloatArray
    position_m: FloatArray
    velocity_m_s: FloatArray
    angle_rad: FloatArray
    rate_rad_s: FloatArray
    acceleration_m_s2: FloatArray


def simulate_cart_pendulum(
    force_n: Callable[[float], float],
    model: SloshModel,
    cart_mass_kg: float,
    duration_s: float,
    sample_period_s: float = 1e-3,
    include_rigid_liquid: bool = True,
) -> CartPendulumResponse:
    """Cart of mass M (plus the rigid liquid m_0) carrying one pendulum per mode, driven by F(t).

    Seed paper eqs. 4-5 (one mode), written for N modes with a hinge damper:

    (M + m_0 + sum m_n) x'' + sum m_n L_n (theta_n'' cos theta_n - theta_n'^2 sin theta_n) = F
    L_n cos(theta_n) x'' + L_n^2 theta_n'' + 2 zeta_n omega_n L_n^2 theta_n'
        + omega_n^2 L_n^2 sin(theta_n) = 0,

    with omega_n^2 L_n in place of g so that a calibrated frequency is honoured. The mass matrix
    is solved at every step (Lagrange's equations; Ibrahim 2005 §6.2; Dodge 2000 §3).
    """
    mass_cart = require_positive("cart_mass", cart_mass_kg, "kg")
    end = require_positive("duration", duration_s, "s")
    dt = require_positive("sample_period", sample_period_s, "s")
    modes = model.modes
    count = len(modes)
    masses = np.array([mode.slosh_mass_kg for mode in modes])
    lengths = np.array([mode.length_m for mode in modes])
    omegas = np.array([mode.omega_rad_s for mode in modes])
    zetas = np.array([mode.damping_ratio for mode in modes])
    total = mass_cart + masses.sum() + (model.rigid_mass_kg if include_rigid_liquid else 0.0)

    def accelerations(t: float, state: FloatArray) -> FloatArray:
        theta = state[2 : 2 + count]
        theta_dot = state[2 + count :]
        matrix = np.zeros((count + 1, count + 1))
        rhs = np.zeros(count + 1)
        matrix[0, 0] = total
        matrix[0, 1:] = masses * lengths * np.cos(theta)
        rhs[0] = force_n(t) + np.sum(masses * lengths * theta_dot**2 * np.sin(theta))
        matrix[1:, 0] = lengths * np.cos(theta)
        matrix[1:, 1:] = np.diag(lengths**2)
        rhs[1:] = -2 * zetas * omegas * lengths**2 * theta_dot - omegas**2 * lengths**2 * np.sin(
            theta
        )
        return np.asarray(np.linalg.solve(matrix, rhs), dtype=float)

    def rhs_function(t: float, state: FloatArray) -> FloatArray:
        second = accelerations(t, state)
        return np.concatenate(([state[1]], [second[0]], state[2 + count :], second[1:]))

    time = np.arange(math.floor(end / dt + 1e-9) + 1, dtype=float) * dt
    solution = solve_ivp(
        rhs_function,
        (0.0, float(time[-1])),
        np.zeros(2 + 2 * count),
        method="DOP853",
        rtol=1e-10,
        atol=1e-12,
        t_eval=time,
        max_step=dt * 10,
    )
    states = solution.y
    cart_acceleration = np.array(
        [accelerations(t, states[:, k])[0] for k, t in enumerate(solution.t)]
    )
    return CartPendulumResponse(
        time_s=solution.t,
        position_m=states[0],
        velocity_m_s=states[1],
        angle_rad=states[2 : 2 + count],
        rate_rad_s=states[2 + count :],
        acceleration_m_s2=cart_acceleration,
    )
