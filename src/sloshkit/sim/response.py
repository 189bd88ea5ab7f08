"""Response objects of the simulations (time histories and the metrics derived from them)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.model.modal import SloshModel
from sloshkit.results import ResultMixin
from sloshkit.sim.equations import pendulum_angular_acceleration
from sloshkit.sim.metrics import (
    DEFAULT_SETTLE_TOLERANCE_RAD,
    wall_elevation,
    wall_elevation_factors,
)

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class SloshResponse(ResultMixin):
    """Slosh response to a container motion (arrays over time; modes on the first axis).

    Follows the result protocol (`sloshkit.results.ResultMixin`): `columns`, ``to_dict``,
    ``to_pandas``, ``to_csv`` and ``plot``.

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s], from 0, uniform step.
    position_m, velocity_m_s, acceleration_m_s2 : numpy.ndarray
        The container's motion [m, m/s, m/s^2].
    angle_rad, rate_rad_s : numpy.ndarray
        Pendulum angle [rad] and angular rate [rad/s], shape (modes, samples).
    move_duration_s : float
        The move's duration T [s]; after T the container rests.
    model : SloshModel
        The model simulated.
    kind : str
        ``"linear"`` or ``"nonlinear"``.
    residual_amplitude_rad : numpy.ndarray
        Per mode, amplitude of the free oscillation left at T [rad].
    motion_name : str
        Name of the motion.
    peak_jerk_m_s3 : float
        The motion's peak jerk [m/s^3] (inf with acceleration jumps).
    settle_tolerance_rad : float
        Tolerance on abs(theta_1) for `settling_time_s` [rad].
    extra : dict
        Additional data of the simulation.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> response = sk.simulate(model, sk.quintic(0.1, 1.0), sample_period_s=2e-3)
    >>> sorted(response.columns())[:3]
    ['acceleration_m_s2', 'angle_1_rad', 'angle_2_rad']
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
        see `sloshkit.model.modal.wall_elevation_factor`)."""
        return np.asarray(
            wall_elevation(
                wall_elevation_factors(self.model), self.angle_rad, nonlinear=self.kind != "linear"
            ),
            dtype=float,
        )

    @property
    def angular_acceleration_rad_s2(self) -> FloatArray:
        """theta_n'' from the equation of motion [rad/s^2]."""
        omega = np.array([mode.omega_rad_s for mode in self.model.modes])[:, None]
        zeta = np.array([mode.damping_ratio for mode in self.model.modes])[:, None]
        length = np.array([mode.length_m for mode in self.model.modes])[:, None]
        return np.asarray(
            pendulum_angular_acceleration(
                self.angle_rad,
                self.rate_rad_s,
                self.acceleration_m_s2,
                omega,
                zeta,
                length,
                nonlinear=self.kind != "linear",
            ),
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
        """Peak abs(theta_1) during the move [rad]."""
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
        return float(wall_elevation_factors(self.model) @ self.residual_amplitude_rad)

    @property
    def settling_time_s(self) -> float:
        """Time from the start until abs(theta_1) stays below the tolerance [s].

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

    def to_dict(self) -> dict[str, Any]:
        """The metrics (`metrics`), the model kind, the motion's name and the time series."""
        return {
            "kind": self.kind,
            "motion": self.motion_name,
            **self.metrics(),
            "columns": {name: values.tolist() for name, values in self.columns().items()},
        }


@dataclass(frozen=True, eq=False)
class CartPendulumResponse:
    """Response of the cart-pendulum system to a force on the cart.

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s].
    position_m, velocity_m_s, acceleration_m_s2 : numpy.ndarray
        The cart's motion [m, m/s, m/s^2].
    angle_rad, rate_rad_s : numpy.ndarray
        Pendulum angles [rad] and rates [rad/s], shape (modes, samples).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> cart = sk.sim.simulate.simulate_cart_pendulum(
    ...     model, lambda t: 1.0, cart_mass_kg=1.0, duration_s=0.01)
    >>> cart.angle_rad.shape[0]
    3
    """

    time_s: FloatArray
    position_m: FloatArray
    velocity_m_s: FloatArray
    angle_rad: FloatArray
    rate_rad_s: FloatArray
    acceleration_m_s2: FloatArray
