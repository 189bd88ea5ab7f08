"""The amplitude dependence of the 3-D model's first mode from a force-sensor free decay.

`decay_amplitude_dependence` runs the sliding-window `sloshkit.calibration.backbone.backbone`
on the lateral force of a free decay and converts its lines omega(F) = omega_0 + k_2 F^2 and
zeta(F) = zeta_0 + k_1 F to pendulum-angle units with the first mode's force per radian
(`sloshkit.sim.spatial_amplitude.from_force_backbone`), ready for
``simulate_spatial(..., amplitude_dependence=...)``. Nothing is fitted to a slosh-height record.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sloshkit.calibration.backbone import Backbone, backbone
from sloshkit.calibration.window import prepare_signal
from sloshkit.model.modal import SloshModel
from sloshkit.sim.spatial_amplitude import AmplitudeDependence, from_force_backbone

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class DecayAmplitudeDependence:
    """A free decay's backbone and the first-mode `AmplitudeDependence` made from it.

    Attributes
    ----------
    dependence : AmplitudeDependence
        Pendulum-angle units, first mode; a slope the backbone does not flag as dependent
        (`Backbone.omega_dependent`, `Backbone.zeta_dependent`) is set to 0.
    curve : Backbone
        The per-window fits (force units).
    omega_slope_se_rad_s_per_n2, zeta_slope_se_per_n : float
        Standard errors of the two slopes (weighted least squares, weights F^2 as in
        `backbone`).

    Examples
    --------
    Made by `decay_amplitude_dependence`; a linear decay gives no dependence:

    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1)
    >>> t = np.arange(0.0, 8.0, 0.002)
    >>> decay = 0.4 * np.exp(-0.13 * t) * np.cos(19.15 * t)
    >>> found = decay_amplitude_dependence(model, t, decay, 0.0)
    >>> type(found).__name__, found.dependence.zeta_slope_per_rad[0]
    ('DecayAmplitudeDependence', 0.0)
    """

    dependence: AmplitudeDependence
    curve: Backbone
    omega_slope_se_rad_s_per_n2: float
    zeta_slope_se_per_n: float


def _slope_error(x: FloatArray, y: FloatArray, weight: FloatArray) -> float:
    """Standard error of the slope of a weighted least-squares line y = a + b x."""
    design = np.column_stack((np.ones_like(x), x)) * np.sqrt(weight)[:, None]
    target = y * np.sqrt(weight)
    parameters, *_ = np.linalg.lstsq(design, target, rcond=None)
    residual = target - design @ parameters
    covariance = np.linalg.pinv(design.T @ design) * float(residual @ residual)
    return float(np.sqrt(max(covariance[1, 1], 0.0) / max(1, x.size - 2)))


def decay_amplitude_dependence(
    model: SloshModel,
    time_s: FloatArray,
    force_n: FloatArray,
    start_s: float,
    *,
    lowpass_hz: float = 8.0,
    source: str = "force-sensor free decay",
) -> DecayAmplitudeDependence:
    """First-mode amplitude dependence from the lateral force of a free decay.

    Parameters
    ----------
    model : the container's model (first mode: omega guess, force per radian)
    time_s, force_n : the record [s], [N] (lateral force along the decay's direction)
    start_s : start of the free decay (after the motion) [s]
    lowpass_hz : zero-phase low-pass before the backbone [Hz] (below the second mode's
        interference, above the first mode)
    source : label carried into the results

    Returns
    -------
    DecayAmplitudeDependence

    References
    ----------
    `sloshkit.calibration.backbone` (Feldman 2011 §5); `sloshkit.sim.spatial_amplitude`.

    Examples
    --------
    A linear decay gives (nearly) flat lines:

    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1)
    >>> t = np.arange(0.0, 8.0, 0.002)
    >>> force = 0.4 * np.exp(-0.13 * t) * np.cos(19.15 * t)
    >>> found = decay_amplitude_dependence(model, t, force, 0.0)
    >>> abs(found.dependence.omega_slope_rad_s_per_rad2[0]) < 0.05
    True
    """
    omega = model.modes[0].omega_rad_s
    zeta = model.modes[0].damping_ratio
    prepared, _ = prepare_signal(
        np.asarray(time_s, dtype=float),
        np.asarray(force_n, dtype=float),
        start_s=start_s,
        lowpass_hz=lowpass_hz,
    )
    curve = backbone(prepared, omega, zeta)
    weight = curve.amplitude**2
    # a trend the backbone does not find significant (`backbone.SIGNIFICANCE`) is left out
    dependence = from_force_backbone(
        model,
        curve.omega_slope_rad_s_per_amplitude2 if curve.omega_dependent else 0.0,
        curve.zeta_slope_per_amplitude if curve.zeta_dependent else 0.0,
        float(np.max(curve.amplitude)),
        source,
    )
    return DecayAmplitudeDependence(
        dependence,
        curve,
        _slope_error(curve.amplitude**2, curve.omega_n_rad_s, weight),
        _slope_error(curve.amplitude, curve.damping_ratio, weight),
    )
