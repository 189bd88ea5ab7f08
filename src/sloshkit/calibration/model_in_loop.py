"""sloshkit's own models in the loop of `identify_simulated`: the 1-D model along a motion with
the clock offset between motion and record fitted, and the 3-D model along robot poses.

Both simulate trial models (mode 1 at the trial omega_n, every mode at the trial zeta) and hand
the response to `sloshkit.calibration.simulated.identify_simulated`, which fits omega_n, zeta and
(optionally) the clock offset by variable projection (Golub & Pereyra, Inverse Problems 19
(2003) R1, doi:10.1088/0266-5611/19/2/201).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.calibration.applied import AppliedMotion
from sloshkit.calibration.forced import ForcedIdentification
from sloshkit.calibration.simulated import identify_simulated
from sloshkit.errors import ValidityWarning
from sloshkit.model.modal import SloshModel
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.simulate import simulate
from sloshkit.sim.spatial import simulate_spatial

FloatArray = NDArray[np.float64]


def trial_model(model: SloshModel, omega_rad_s: float, damping_ratio: float) -> SloshModel:
    """``model`` with mode 1 at ``omega_rad_s`` and every mode at ``damping_ratio``.

    Parameters
    ----------
    model : SloshModel
        The model (its theory starts the search).
    omega_rad_s : float
        Trial natural frequency of mode 1 [rad/s].
    damping_ratio : float
        Trial damping ratio of every mode.

    Returns
    -------
    SloshModel

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> trial = trial_model(model, 28.0, 0.02)
    >>> trial.modes[0].omega_rad_s, [mode.damping_ratio for mode in trial.modes]
    (28.0, [0.02, 0.02, 0.02])
    """
    trial = model.with_mode(1, omega_rad_s=omega_rad_s)
    for mode in trial.modes:
        trial = trial.with_mode(mode.n, damping_ratio=damping_ratio)
    return trial


def _around_theory(model: SloshModel) -> dict[str, Any]:
    """The search of `identify_simulated` centred on the model's first mode: omega_n within
    0.7-1.4 of theory, zeta from the model's (at least 1e-3)."""
    theory = model.modes[0]
    return {
        "omega_guess_rad_s": theory.omega_rad_s,
        "zeta_guess": max(theory.damping_ratio, 1e-3),
        "omega_range": (0.7, 1.4),
    }


def identify_line(
    model: SloshModel,
    applied: AppliedMotion,
    time_s: FloatArray,
    values: FloatArray,
    *,
    delay_s: float,
    signal_kind: str = "height",
    require_constrained: bool = True,
    source: str = "",
) -> ForcedIdentification:
    """The 1-D model along the motion, with the clock offset (record time minus motion-file
    time) fitted around ``delay_s``.

    Parameters
    ----------
    model : SloshModel
        The container's model (its theory starts the search).
    applied : AppliedMotion
        The motion in the record's clock at the offset ``delay_s``.
    time_s, values : numpy.ndarray
        The record: wall elevation [m] (``height``) or first-mode angle [rad] (``angle``).
    delay_s : float
        First guess of the clock offset [s]; the fit searches +-0.5 s around it.
    signal_kind : str
        height or angle.
    require_constrained : bool
        Raise `InputError` when the record does not constrain omega_n or zeta.
    source : str
        Where the record came from.

    Returns
    -------
    ForcedIdentification
        With ``delay_s`` and its interval.

    References
    ----------
    Golub & Pereyra, Inverse Problems 19 (2003) R1, doi:10.1088/0266-5611/19/2/201; the model:
    seed paper eq. 7 (`sloshkit.sim.simulate`).

    Examples
    --------
    A record of the model itself (mode 1 at 0.95 of theory), 0.2 s late on the motion's clock:

    >>> import numpy as np
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             0.039, 1, damping_ratio=0.02)
    >>> move = sk.quintic(0.02, 0.5)
    >>> truth = trial_model(model, 0.95 * model.modes[0].omega_rad_s, 0.02)
    >>> record = sk.simulate(truth, move, sample_period_s=0.008, settle_time_s=1.0)
    >>> found = identify_line(model, AppliedMotion(move, 0.15), record.time_s + 0.2,
    ...                       record.wall_elevation_m, delay_s=0.15)
    >>> round(found.omega_n_rad_s / truth.modes[0].omega_rad_s, 3), round(found.delay_s, 3)
    (1.0, 0.2)
    """
    file_start = applied.start_s - delay_s
    step = float(np.median(np.diff(time_s)))
    sample_period = min(0.004, max(0.001, 0.5 * step))
    settle = max(0.0, float(time_s[-1]) - applied.end_s + 0.5)

    def simulate_line(omega: float, zeta: float) -> tuple[FloatArray, FloatArray]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            response = simulate(
                trial_model(model, omega, zeta),
                applied.motion,
                sample_period_s=sample_period,
                settle_time_s=settle,
            )
        signal = response.wall_elevation_m if signal_kind == "height" else response.angle_rad[0]
        return response.time_s + file_start, signal

    return identify_simulated(
        simulate_line,
        time_s,
        values,
        **_around_theory(model),
        delay_s=delay_s,
        fit_delay=True,
        signal_kind=signal_kind,
        motion_span_s=(file_start, file_start + applied.motion.duration_s),
        require_constrained=require_constrained,
        source=source,
        notes=applied.notes,
    )


def identify_spatial(
    model: SloshModel,
    poses: PoseTrajectory,
    time_s: FloatArray,
    values: FloatArray,
    *,
    delay_s: float = 0.0,
    fit_delay: bool = False,
    require_constrained: bool = True,
    source: str = "",
) -> ForcedIdentification:
    """The 3-D model along the poses against a slosh-height record.

    Parameters
    ----------
    model : SloshModel
        The container's model (its theory starts the search).
    poses : PoseTrajectory
        The container's poses on the motion's clock.
    time_s, values : numpy.ndarray
        The record of the slosh height [m] (the largest wall elevation over the circumference).
    delay_s : float
        Record time minus pose time [s] (the clock offset, or its first guess).
    fit_delay : bool
        Fit the clock offset within +-0.5 s of ``delay_s``.
    require_constrained : bool
        Raise `InputError` when the record does not constrain omega_n or zeta.
    source : str
        Where the record came from.

    Returns
    -------
    ForcedIdentification

    References
    ----------
    The model: `sloshkit.sim.spatial`; the fit: Golub & Pereyra, Inverse Problems 19 (2003) R1,
    doi:10.1088/0266-5611/19/2/201.

    Examples
    --------
    A record of the 3-D model itself with the damping ratio at 0.03:

    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             0.039, 1, damping_ratio=0.01)
    >>> poses = sk.poses_from_law(sk.quintic(0.02, 0.5), (1, 1, 0), sample_period_s=0.008)
    >>> truth = trial_model(model, model.modes[0].omega_rad_s, 0.03)
    >>> record = sk.simulate_spatial(truth, poses, settle_time_s=0.6, sample_period_s=0.008)
    >>> found = identify_spatial(model, poses, record.time_s, record.slosh_height_m)
    >>> round(found.damping_ratio, 3)
    0.03
    """
    step = float(np.median(np.diff(time_s)))
    sample_period = min(0.008, max(0.002, 0.5 * step))
    settle = max(0.0, float(time_s[-1]) - delay_s - poses.end_s + 0.5)

    def simulate_height(omega: float, zeta: float) -> tuple[FloatArray, FloatArray]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            response = simulate_spatial(
                trial_model(model, omega, zeta),
                poses,
                settle_time_s=settle,
                sample_period_s=sample_period,
            )
        return response.time_s, response.slosh_height_m

    return identify_simulated(
        simulate_height,
        time_s,
        values,
        **_around_theory(model),
        delay_s=delay_s,
        fit_delay=fit_delay,
        signal_kind="height",
        motion_span_s=(poses.start_s, poses.end_s),
        require_constrained=require_constrained,
        source=source,
        notes=(f"3-D slosh model along the poses of {poses.name}; slosh height = the largest "
               "wall elevation over the circumference",),
    )  # fmt: skip
