"""Result of a 3-D slosh simulation: pendulum states, wall elevation, slosh height, metrics.

See `sloshkit.sim.spatial` for the model and the height mapping. Frames: N is the container's
non-spinning frame (tilts with the container axis, does not follow its spin about the axis);
C is the container frame. Angles in C differ from N by the spin angle phi about the axis:
v_C = Rz(-phi) v_N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import NDArray

from sloshkit.model.modal import SloshModel
from sloshkit.results import ResultMixin
from sloshkit.sim.metrics import free_oscillation_components, wall_elevation_factors
from sloshkit.sim.spatial_kernels import LARGE_ANGLE_MODES

if TYPE_CHECKING:
    from sloshkit.sim.spatial_drive import SpatialDrive

FloatArray = NDArray[np.float64]
HeightMapping = Literal["modal", "planar"]
HEIGHT_MAPPINGS: tuple[str, ...] = ("modal", "planar")


def _rotate(vectors: FloatArray, angle: FloatArray) -> FloatArray:
    """Rotate 2-D vectors (..., M, 2) by angle (M,) about z."""
    cos_a, sin_a = np.cos(angle), np.sin(angle)
    x, y = vectors[..., 0], vectors[..., 1]
    return np.stack((cos_a * x - sin_a * y, sin_a * x + cos_a * y), axis=-1)


def ellipse_semi_major(first: FloatArray, second: FloatArray) -> FloatArray:
    """Largest |A cos t + B sin t| over t for 2-D vectors A, B (..., 2): the semi-major axis.

    It is the square root of the largest eigenvalue of A A^T + B B^T.

    Parameters
    ----------
    first, second : numpy.ndarray
        A and B (..., 2).

    Returns
    -------
    numpy.ndarray
        The semi-major axes (...).

    Examples
    --------
    A circle of radius 2, and a line of half-length 5:

    >>> import numpy as np
    >>> ellipse_semi_major(np.array([[2.0, 0.0], [3.0, 0.0]]),
    ...                    np.array([[0.0, 2.0], [4.0, 0.0]])).tolist()
    [2.0, 5.0]
    """
    sxx = first[..., 0] ** 2 + second[..., 0] ** 2
    syy = first[..., 1] ** 2 + second[..., 1] ** 2
    sxy = first[..., 0] * first[..., 1] + second[..., 0] * second[..., 1]
    mean = 0.5 * (sxx + syy)
    spread = np.sqrt(0.25 * (sxx - syy) ** 2 + sxy**2)
    return np.asarray(np.sqrt(np.maximum(mean + spread, 0.0)), dtype=float)


@dataclass(frozen=True, eq=False)
class SpatialResponse(ResultMixin):
    """Slosh response to a 3-D pose trajectory (arrays over time; modes on the first axis).

    Attributes
    ----------
    model : the `SloshModel` simulated
    drive : the `sloshkit.sim.spatial_drive.SpatialDrive` (specific forces, tilt rates, spin angle)
    pendulum : (modes, M, 3) hinge-to-bob unit vectors in N for the large-angle modes
        (`large_angle`), (theta_x, theta_y, -1) for the linear ones
    pendulum_rate : (modes, M, 3) their time derivatives in N
    nonlinear : which model was run
    motion_end_s : time of the last pose [s]; the container rests afterwards
    height_mapping : ``"modal"`` (sum over the simulated modes, as in 1-D) or ``"planar"``
        (plus the quasi-static remainder of the modes not simulated: exact planar statics)
    amplitude_model : ``"none"`` (linear in amplitude) or the source of the backbone used
        (`sloshkit.sim.spatial_amplitude`)
    motion_name : label of the pose trajectory
    elapsed_s : wall-clock time of the simulation [s]

    Built by `sloshkit.sim.spatial.simulate_spatial`, not directly.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> response = sk.simulate_spatial(model, sk.poses_from_law(sk.septic(0.1, 1.5)))
    >>> sorted(response.to_dict())[:3]
    ['amplitude_model', 'duration_s', 'height_mapping']
    """

    model: SloshModel
    drive: SpatialDrive
    pendulum: FloatArray
    pendulum_rate: FloatArray
    nonlinear: bool
    motion_end_s: float
    height_mapping: HeightMapping = "modal"
    amplitude_model: str = "none"
    motion_name: str = ""
    elapsed_s: float = float("nan")

    # -- time series ------------------------------------------------------------------------

    @property
    def time_s(self) -> FloatArray:
        """Sample times (pose clock) [s]."""
        return self.drive.time_s

    @property
    def kind(self) -> str:
        """``"nonlinear"`` or ``"linear"``."""
        return "nonlinear" if self.nonlinear else "linear"

    @cached_property
    def angle_rad(self) -> FloatArray:
        """Pendulum deflection as a 2-D vector in N, (modes, M, 2) [rad]: theta (linear), or
        the polar angle from the axis times the unit direction of the bob (nonlinear)."""
        lateral = self.pendulum[..., :2]
        if not self.nonlinear:
            return np.asarray(lateral, dtype=float)
        radius = np.hypot(lateral[..., 0], lateral[..., 1])
        polar = np.arctan2(radius, -self.pendulum[..., 2])
        scale = np.where(radius > 1e-15, polar / np.maximum(radius, 1e-300), 1.0)
        scale = np.where(self.large_angle[:, None], scale, 1.0)
        return np.asarray(lateral * scale[..., None], dtype=float)

    @property
    def large_angle(self) -> NDArray[np.bool_]:
        """Per mode, whether it was simulated as a large-angle pendulum (`nonlinear`: the
        first `sloshkit.sim.spatial_kernels.LARGE_ANGLE_MODES`; the others are linear, their
        ``pendulum`` (theta_x, theta_y, -1))."""
        count = self.pendulum.shape[0]
        return np.arange(count) < (LARGE_ANGLE_MODES if self.nonlinear else 0)

    @property
    def rate_rad_s(self) -> FloatArray:
        """Rate of the lateral pendulum coordinates in N, (modes, M, 2) [rad/s]."""
        return np.asarray(self.pendulum_rate[..., :2], dtype=float)

    @property
    def angle_container_rad(self) -> FloatArray:
        """`angle_rad` in the container frame C (follows the spin about the axis) [rad]."""
        return _rotate(self.angle_rad, -self.drive.spin_angle_rad)

    @cached_property
    def mode_slope(self) -> FloatArray:
        """Per-mode surface-slope vector used by the height mapping, (modes, M, 2) in N [-]."""
        lateral = self.pendulum[..., :2]
        if not self.nonlinear:
            return np.asarray(lateral, dtype=float)
        # tan of the deflection, capped at 84 deg (beyond it the model is invalid and warns)
        axial = np.maximum(-self.pendulum[..., 2], 0.1)
        return np.asarray(lateral / axial[..., None], dtype=float)

    @cached_property
    def quasi_static_slope(self) -> FloatArray:
        """f_lat / |f_z| at the free-surface centre, (M, 2) in N: the slope of a surface
        normal to the apparent gravity [-]."""
        force = self.drive.specific_force_m_s2[-1]
        axial = np.maximum(-force[:, 2], 1e-9)
        return np.asarray(force[:, :2] / axial[:, None], dtype=float)

    @property
    def truncation_factor_m(self) -> float:
        """R - sum_n 2R/(xi_n^2 - 1): wall height per unit slope carried by unmodelled modes."""
        return self.model.radius_m - sum(m.wall_elevation_factor_m for m in self.model.modes)

    def _modal_vector(self) -> FloatArray:
        factors = wall_elevation_factors(self.model)
        return np.asarray(np.einsum("n,nmk->mk", factors, self.mode_slope), dtype=float)

    @cached_property
    def planar_vector_m(self) -> FloatArray:
        """Wall-elevation vector with the quasi-static remainder of the unmodelled modes,
        (M, 2) in N [m]: exact (R tan psi) for a static or slow tilt of the apparent gravity."""
        remainder = self.truncation_factor_m * self.quasi_static_slope
        return np.asarray(self._modal_vector() + remainder, dtype=float)

    @cached_property
    def elevation_vector_m(self) -> FloatArray:
        """Wall-elevation vector in N with the chosen ``height_mapping``, (M, 2) [m]:
        eta(alpha) = vector . (cos alpha, sin alpha)."""
        if self.height_mapping == "planar":
            return self.planar_vector_m
        return self._modal_vector()

    @cached_property
    def slosh_height_m(self) -> FloatArray:
        """Maximum over the circumference of the wall elevation above the rest level (M,) [m]."""
        vector = self.elevation_vector_m
        return np.asarray(np.hypot(vector[:, 0], vector[:, 1]), dtype=float)

    def wall_elevation_m(self, angle_rad: float) -> FloatArray:
        """Wall elevation at the wall angle ``angle_rad`` of the container frame (from its x
        axis towards its y axis) along the container axis (M,) [m]."""
        direction = float(angle_rad) + self.drive.spin_angle_rad
        vector = self.elevation_vector_m
        return np.asarray(
            vector[:, 0] * np.cos(direction) + vector[:, 1] * np.sin(direction), dtype=float
        )

    @property
    def surface_tilt_rad(self) -> FloatArray:
        """Tilt of the mean surface plane (planar mapping), components in C (M, 2) [rad]:
        atan(eta_x / R), atan(eta_y / R); a static tilt psi gives psi exactly."""
        vector = _rotate(self.planar_vector_m, -self.drive.spin_angle_rad)
        return np.asarray(np.arctan(vector / self.model.radius_m), dtype=float)

    @cached_property
    def slosh_force_n(self) -> FloatArray:
        """Force of the sloshing masses on the container beyond rigid-body inertia, world
        frame (M, 3) [N]: -sum_n m_n L_n (bob acceleration relative to N), from the
        pendulum states by central differences of the bob velocity."""
        masses = np.array([m.slosh_mass_kg * m.length_m for m in self.model.modes])
        rate = self.pendulum_rate
        accel = np.gradient(rate, self.time_s, axis=1)
        force_n = -np.einsum("n,nmk->mk", masses, accel)
        if not self.nonlinear:
            force_n[:, 2] = 0.0
        planar = _rotate(force_n[:, :2], -self.drive.spin_angle_rad)
        body = np.column_stack((planar, force_n[:, 2]))
        matrix = self.drive.kinematics.rotation_matrix
        stride = max(
            1,
            round(
                (self.time_s[1] - self.time_s[0])
                / (self.drive.kinematics.time_s[1] - self.drive.kinematics.time_s[0])
            ),
        )
        matrix = matrix[::stride][: self.time_s.size]
        return np.asarray(np.einsum("kij,kj->ki", matrix, body), dtype=float)

    @property
    def path_m(self) -> FloatArray:
        """Bottom-centre positions on the simulation grid (M, 3) [m]."""
        kinematics = self.drive.kinematics
        stride = max(
            1,
            round(
                (self.time_s[1] - self.time_s[0]) / (kinematics.time_s[1] - kinematics.time_s[0])
            ),
        )
        return np.asarray(kinematics.position_m[::stride][: self.time_s.size], dtype=float)

    # -- metrics ----------------------------------------------------------------------------

    @property
    def duration_s(self) -> float:
        """Duration of the pose trajectory [s]."""
        return self.motion_end_s - float(self.time_s[0])

    @property
    def peak_slosh_height_m(self) -> float:
        """Largest slosh height over the simulated time (motion and settling) [m]."""
        return float(np.max(self.slosh_height_m))

    @property
    def peak_angle_rad(self) -> float:
        """Largest first-mode deflection |theta_1| over the simulated time [rad]."""
        angle = self.angle_rad[0]
        return float(np.max(np.hypot(angle[:, 0], angle[:, 1])))

    @cached_property
    def free_amplitudes_rad(self) -> FloatArray:
        """Per mode, the semi-major axis of the free oscillation left at the end [rad].

        Taken from the state at the first sample where the (smoothed) drive is at rest, a
        differentiation half-window (at least 5 samples) after the last pose, relative to the
        equilibrium of the container resting in its final pose (the drive of the last sample),
        and scaled back to the end of the motion by exp(zeta omega lag) (exact when linear)."""
        kinematics = self.drive.kinematics
        step = float(kinematics.time_s[1] - kinematics.time_s[0])
        settled = (max(kinematics.window // 2, 4) + 1) * step
        index = int(np.searchsorted(self.time_s, self.motion_end_s + settled - 1e-12))
        index = min(index, self.time_s.size - 1)
        lag = float(self.time_s[index]) - self.motion_end_s
        force = self.drive.specific_force_m_s2[:, -1]
        amplitudes = []
        for row, mode in enumerate(self.model.modes):
            if self.large_angle[row]:  # deflection from the unit vector along f
                equilibrium = force[row, :2] / max(float(np.linalg.norm(force[row])), 1e-9)
            else:
                equilibrium = force[row, :2] / max(-force[row, 2], 1e-9)
            offset = self.pendulum[row, index, :2] - equilibrium
            rate = self.pendulum_rate[row, index, :2]
            offset, quadrature = free_oscillation_components(
                offset, rate, mode.omega_rad_s, mode.damping_ratio
            )
            semi = float(ellipse_semi_major(offset, quadrature))
            amplitudes.append(semi * math.exp(mode.damping_ratio * mode.omega_rad_s * lag))
        return np.asarray(amplitudes)

    @property
    def residual_angle_rad(self) -> float:
        """Amplitude of the first mode's free oscillation left at the end of the motion [rad]."""
        return float(self.free_amplitudes_rad[0])

    @property
    def residual_slosh_height_m(self) -> float:
        """Bound on the slosh height of the free oscillation left at the end of the motion:
        sum_n 2R/(xi_n^2 - 1) A_n (A_n: semi-major axis of mode n's free motion) [m]."""
        factors = wall_elevation_factors(self.model)
        return float(factors @ self.free_amplitudes_rad)

    @property
    def peak_tilt_rad(self) -> float:
        """Largest tilt of the container axis from the vertical [rad]."""
        axis = self.drive.kinematics.rotation_matrix[:, 2, 2]
        return float(np.arccos(np.clip(np.min(axis), -1.0, 1.0)))

    def metrics(self) -> dict[str, float | str]:
        """The scalar results with unit-suffixed keys (JSON of ``simulate --pose-file``)."""
        return {
            "duration_s": self.duration_s,
            "peak_slosh_height_m": self.peak_slosh_height_m,
            "residual_slosh_height_m": self.residual_slosh_height_m,
            "peak_angle_deg": math.degrees(self.peak_angle_rad),
            "residual_angle_deg": math.degrees(self.residual_angle_rad),
            "peak_tilt_deg": math.degrees(self.peak_tilt_rad),
            "simulated_time_s": float(self.time_s[-1] - self.time_s[0]),
            "model": self.kind,
            "height_mapping": self.height_mapping,
            "amplitude_model": self.amplitude_model,
        }

    def columns(self) -> dict[str, FloatArray]:
        """Time series as named columns (SI units in the names)."""
        path = self.path_m
        tilt = self.surface_tilt_rad
        data: dict[str, FloatArray] = {
            "t_s": self.time_s,
            "x_m": path[:, 0],
            "y_m": path[:, 1],
            "z_m": path[:, 2],
            "slosh_height_m": self.slosh_height_m,
            "surface_tilt_rad": np.arctan(np.hypot(*np.tan(tilt).T)),
            "surface_tilt_x_rad": tilt[:, 0],
            "surface_tilt_y_rad": tilt[:, 1],
        }
        angle = self.angle_container_rad
        for index, mode in enumerate(self.model.modes):
            data[f"angle_{mode.n}_x_rad"] = angle[index, :, 0]
            data[f"angle_{mode.n}_y_rad"] = angle[index, :, 1]
        force = self.slosh_force_n
        for axis, name in enumerate("xyz"):
            data[f"slosh_force_{name}_n"] = force[:, axis]
        return data

    def to_dict(self, include_series: bool = False) -> dict[str, Any]:
        """JSON-ready metrics (and the `columns` as lists when ``include_series``)."""
        payload: dict[str, Any] = dict(self.metrics())
        if include_series:
            payload["series"] = {key: value.tolist() for key, value in self.columns().items()}
        return payload
