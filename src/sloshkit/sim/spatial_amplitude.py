"""Amplitude-dependent frequency and damping of the 3-D slosh modes (the free-decay backbone).

Real slosh is not linear at large amplitude: the first mode of an upright cylinder softens
(for fill depths h/R above about 1.05, Faltinsen, Lukovsky & Timokha, J. Fluid Mech. 804
(2016) 608-645, doi:10.1017/jfm.2016.539) and its damping may grow (contact line, breaking).
A free decay measures both directly: `sloshkit.calibration.backbone` fits omega_n and zeta in
sliding windows and gives the lines

    omega(A) = omega_n + k_2 A^2,    zeta(A) = zeta_n + k_1 A

over the amplitudes A the record covers. `AmplitudeDependence` carries them per mode, in
pendulum-angle units, and `simulate_spatial(..., amplitude_dependence=...)` uses them in the
linear 3-D model as an equivalent linearisation (Krylov-Bogoliubov averaging; Nayfeh & Mook,
*Nonlinear Oscillations*, Wiley (1979) §4.1-4.2, doi:10.1002/9783527617586): at every step each
mode's stiffness is K (omega(A) / omega_n)^2 and its damping 2 zeta(A) omega(A), with A the
current amplitude of the wave,

    A^2 = |x|^2 + |x'|^2 / omega(A)^2,    x = theta - theta_qs,

the deviation from the quasi-static equilibrium theta_qs = u / K (the pendulum hanging along the
apparent gravity). Only the wave is affected: a static or slow tilt of the apparent gravity
(A = 0) is unchanged, and so is every small amplitude (the linear model is the limit A -> 0).
A free planar oscillation then follows the backbone it was built from (exact to first order in
the slopes; `tests/sim/test_spatial_amplitude.py`). A is capped at ``amplitude_cap_rad``, the
largest amplitude of the record: the backbone is not extrapolated beyond the data.

A force-sensor record gives amplitudes in newtons. The lateral force of mode n's free
oscillation on the container is m_n L_n omega_n^2 theta (the pendulum's bob acceleration,
Abramson, NASA SP-106 (1966) ch. 6), so `from_force_backbone` converts with that factor.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class AmplitudeDependence:
    """Backbone slopes of each mode (first mode first; missing modes stay linear).

    Attributes
    ----------
    omega_slope_rad_s_per_rad2 : tuple of float
        k_2 of omega(A) = omega_n + k_2 A^2 per mode [rad/s per rad^2] (negative: softening).
    zeta_slope_per_rad : tuple of float
        k_1 of zeta(A) = zeta_n + k_1 A per mode [1/rad].
    amplitude_cap_rad : tuple of float
        Largest amplitude the backbone was measured at, per mode [rad]; A is held there.
    source : str
        Where the slopes come from (shown in results).

    Examples
    --------
    >>> dependence = AmplitudeDependence((-5.0,), (0.0,), (0.3,), "example")
    >>> round(dependence.frequency_rad_s(0, 19.15, 0.2), 3)
    18.95
    """

    omega_slope_rad_s_per_rad2: tuple[float, ...]
    zeta_slope_per_rad: tuple[float, ...]
    amplitude_cap_rad: tuple[float, ...]
    source: str = field(default="backbone")

    def __post_init__(self) -> None:
        sizes = {
            len(self.omega_slope_rad_s_per_rad2),
            len(self.zeta_slope_per_rad),
            len(self.amplitude_cap_rad),
        }
        if len(sizes) != 1:
            raise InputError(
                "amplitude_dependence", sorted(sizes), "needs one slope and cap per mode"
            )
        for values in (self.omega_slope_rad_s_per_rad2, self.zeta_slope_per_rad):
            if not all(math.isfinite(v) for v in values):
                raise InputError("amplitude_dependence", values, "slopes must be finite")
        if not all(math.isfinite(v) and v >= 0.0 for v in self.amplitude_cap_rad):
            raise InputError("amplitude_dependence", self.amplitude_cap_rad, "caps must be >= 0")

    def frequency_rad_s(self, mode_index: int, omega_rad_s: float, amplitude_rad: float) -> float:
        """The backbone omega(A) of mode ``mode_index`` (0-based), A capped [rad/s]."""
        if mode_index >= len(self.omega_slope_rad_s_per_rad2):
            return float(omega_rad_s)
        amplitude = min(float(amplitude_rad), self.amplitude_cap_rad[mode_index])
        return float(omega_rad_s + self.omega_slope_rad_s_per_rad2[mode_index] * amplitude**2)

    def damping_ratio(self, mode_index: int, zeta: float, amplitude_rad: float) -> float:
        """The backbone zeta(A) of mode ``mode_index`` (0-based), A capped, floored at 0."""
        if mode_index >= len(self.zeta_slope_per_rad):
            return float(zeta)
        amplitude = min(float(amplitude_rad), self.amplitude_cap_rad[mode_index])
        return max(0.0, float(zeta + self.zeta_slope_per_rad[mode_index] * amplitude))

    def per_mode(self, count: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Slopes and caps as arrays of length ``count`` (zeros beyond the given modes)."""
        arrays = []
        for values in (
            self.omega_slope_rad_s_per_rad2,
            self.zeta_slope_per_rad,
            self.amplitude_cap_rad,
        ):
            padded = np.zeros(count)
            given = min(count, len(values))
            padded[:given] = values[:given]
            arrays.append(padded)
        return arrays[0], arrays[1], arrays[2]

    def to_dict(self) -> dict[str, object]:
        """JSON-ready description."""
        return {
            "source": self.source,
            "omega_slope_rad_s_per_rad2": list(self.omega_slope_rad_s_per_rad2),
            "zeta_slope_per_rad": list(self.zeta_slope_per_rad),
            "amplitude_cap_rad": list(self.amplitude_cap_rad),
        }


def force_per_radian(model: SloshModel, mode_index: int = 0) -> float:
    """Lateral force of a free oscillation of one mode per radian of amplitude [N/rad].

    m_n L_n omega_n^2 (Abramson, NASA SP-106 (1966) ch. 6: the pendulum's bob acceleration);
    m_n g for the theoretical omega_n.

    Parameters
    ----------
    model : SloshModel
        The equivalent model.
    mode_index : int
        Which mode (0: the first).

    Returns
    -------
    float
        Force amplitude per radian of pendulum amplitude [N/rad].

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1)
    >>> round(force_per_radian(model), 3)
    1.637
    """
    mode = model.modes[mode_index]
    return float(mode.slosh_mass_kg * mode.length_m * mode.omega_rad_s**2)


def from_force_backbone(
    model: SloshModel,
    omega_slope_rad_s_per_n2: float,
    zeta_slope_per_n: float,
    largest_amplitude_n: float,
    source: str,
) -> AmplitudeDependence:
    """First-mode `AmplitudeDependence` from the backbone of a force-sensor free decay.

    Parameters
    ----------
    model : the container's model (its first mode converts newtons to radians)
    omega_slope_rad_s_per_n2 : slope of omega_n against (force amplitude)^2 [rad/s per N^2]
        (`sloshkit.calibration.backbone.Backbone.omega_slope_rad_s_per_amplitude2`)
    zeta_slope_per_n : slope of zeta against the force amplitude [1/N]
    largest_amplitude_n : largest force amplitude of the record's windows [N]
    source : where the record comes from

    Returns
    -------
    AmplitudeDependence
        With k_2 [rad/s per rad^2] = slope times F_1^2 and k_1 = slope times F_1,
        F_1 = `force_per_radian`.

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1)
    >>> dependence = from_force_backbone(model, -1.0, 0.0, 0.5, "example")
    >>> slope, cap = dependence.omega_slope_rad_s_per_rad2[0], dependence.amplitude_cap_rad[0]
    >>> round(slope, 3), round(cap, 3)
    (-2.68, 0.305)
    """
    per_radian = force_per_radian(model)
    return AmplitudeDependence(
        (float(omega_slope_rad_s_per_n2) * per_radian**2,),
        (float(zeta_slope_per_n) * per_radian,),
        (float(largest_amplitude_n) / per_radian,),
        source,
    )


def amplitude_pendulums(
    force: FloatArray,
    rest_force: FloatArray,
    tilt_rate: FloatArray,
    tilt_accel: FloatArray,
    model: SloshModel,
    dependence: AmplitudeDependence,
    sample_period_s: float,
) -> tuple[FloatArray, FloatArray]:
    """Linear 2-D pendulums with the backbone's omega(A), zeta(A) (modes, steps, 2).

    The arguments are those of `sloshkit.sim.spatial_kernels.linear_pendulums`, with the
    modes' L_n, omega_n, zeta_n from ``model``; see the module docstring for the model.

    Parameters
    ----------
    force : numpy.ndarray
        Specific force at each mode's hinge (modes, steps, 3) in the non-spinning frame
        [m/s^2] (`sloshkit.sim.spatial_drive.SpatialDrive`).
    rest_force : numpy.ndarray
        The same at rest in the first pose (modes, 3).
    tilt_rate, tilt_accel : numpy.ndarray
        Lateral angular velocity (steps, 2) [rad/s] and its derivative [rad/s^2].
    model : SloshModel
        The modes' L_n, omega_n and damping ratios.
    dependence : AmplitudeDependence
        The first mode's frequency and damping slopes and the amplitude cap.
    sample_period_s : float
        Step [s].

    Returns
    -------
    tuple of numpy.ndarray
        Angles [rad] and rates [rad/s] in the non-spinning frame.

    Examples
    --------
    A constant lateral acceleration 0.1 g: the equilibrium is the linear one (A = 0 there).

    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1,
    ...                          damping_ratio=0.3)
    >>> steps, g = 2000, model.gravity_m_s2
    >>> force = np.tile([-0.1 * g, 0.0, -g], (1, steps, 1))
    >>> still = np.zeros((steps, 2))
    >>> dependence = AmplitudeDependence((-5.0,), (0.01,), (0.3,))
    >>> angle, _ = amplitude_pendulums(force, np.array([[0.0, 0.0, -g]]), still, still,
    ...                                model, dependence, 1e-3)
    >>> angle[0, -1].round(4).tolist()
    [-0.1, 0.0]
    """
    from sloshkit.sim.spatial_kernels import STIFFNESS_FLOOR, kernels

    modes = model.modes[: force.shape[0]]
    omega = np.array([mode.omega_rad_s for mode in modes])
    omega_slope, zeta_slope, cap = dependence.per_mode(len(modes))
    angle, rate = kernels()["linear_amplitude"](
        np.ascontiguousarray(force),
        np.ascontiguousarray(rest_force),
        np.ascontiguousarray(tilt_rate),
        np.ascontiguousarray(tilt_accel),
        np.array([mode.length_m for mode in modes]),
        omega,
        np.array([mode.damping_ratio for mode in modes]),
        STIFFNESS_FLOOR * omega**2,
        omega_slope,
        zeta_slope,
        cap,
        float(sample_period_s),
    )
    return np.asarray(angle, dtype=float), np.asarray(rate, dtype=float)
