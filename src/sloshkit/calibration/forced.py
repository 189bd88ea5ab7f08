"""Identification of omega_n and zeta from a forced response: simulate the model against the
record of a production move, with or without a free decay after it.

Given the applied motion x(t) and a record y(t) during and after it, the linear first-mode
pendulum (seed paper eq. 7) is simulated for trial (omega_n, zeta) with sloshkit's exact
discretisation (`sloshkit.sim.discretisation.linear_mode_response`; higher modes keep their
theoretical frequencies and take the trial damping, as a calibrated model does), and the
record is explained by

- ``angle``:  y = g theta_1 + c + d t,
- ``height``: y = g sum_n e_n theta_n + c + d t (e_n the wall-elevation factors),
- ``force``:  y = m_1 s(t) + beta a(t) + c + d t, with
  s = sum_n (m_n / m_1) L_n (omega_n^2 theta_n + 2 zeta omega_n theta_n') the slosh force per
  unit first-mode mass beyond the liquid's rigid inertia and beta = -(rigid mass below the
  sensor) the rigid-body part m_total a, which is removed by being fitted.

The gain g, offset c, drift d (and m_1, beta) enter linearly and are eliminated by variable
projection (Golub & Pereyra, Inverse Problems 19 (2003) R1, doi:10.1088/0266-5611/19/2/201);
(omega_n, zeta) are found by a grid search and `scipy.optimize.least_squares`. 95 % intervals
come from the Jacobian of all parameters at the solution (Gauss-Newton covariance scaled by the
residual variance; residual correlation is ignored, so they are lower bounds when the model
misses dynamics; `sloshkit.calibration.separable`). A parameter whose interval is too wide
is not constrained by the record.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from sloshkit.calibration.applied import AppliedMotion
from sloshkit.calibration.separable import FitStatistics, constraint_flags, fit_statistics
from sloshkit.calibration.signals import uniform_signal
from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel
from sloshkit.results import ResultMixin
from sloshkit.sim.discretisation import linear_mode_response

FloatArray = NDArray[np.float64]
SignalKind = Literal["force", "height", "angle"]
SIGNAL_KINDS: tuple[str, ...] = ("force", "height", "angle")


@dataclass(frozen=True, eq=False)
class ForcedIdentification(ResultMixin):
    """omega_n, zeta (and the slosh mass for forces) identified from a forced response.

    Attributes
    ----------
    signal_kind : str
        force, height or angle.
    omega_n_rad_s, damping_ratio : float
        The identified first mode [rad/s] and its damping ratio.
    omega_n_interval, damping_ratio_interval : tuple of float
        Their 95 % intervals.
    r2, nrmse, slosh_r2 : float
        Fit quality: R^2, RMS error over the record's range, and the part of what the nuisance
        terms leave that the slosh response explains.
    constrained : dict
        Which parameters the record constrains.
    linear, linear_intervals : dict
        The linear coefficients (gain or slosh mass, offset, drift) and their intervals.
    time_s, measured, predicted : numpy.ndarray
        The record [s], its values and the model's prediction (signal units).
    motion_span_s : tuple of float
        Start and end of the motion in the record's clock [s].
    source : str
        Where the record came from.
    notes, warnings : tuple of str
        How the record was prepared; what the caller should know.
    delay_s, delay_interval_s : float, tuple of float or None
        Clock offset record - motion [s] and its interval (when fitted).

    Examples
    --------
    See `identify_forced` and `ForcedIdentification.from_fit`; the result follows the result
    protocol:

    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> fit = FitStatistics(np.array([2.0]), t, np.array([0.5, 0.01, 0.1]), 1.0, 0.0, 1.0)
    >>> found = ForcedIdentification.from_fit(
    ...     fit, t, t, signal_kind="height", omega_n_rad_s=20.0, damping_ratio=0.02,
    ...     constrained={}, linear=fit.linear_parameters(["gain"], first=2),
    ...     motion_span_s=(0.0, 0.5))
    >>> sorted(found.columns()), round(found.to_dict()["frequency_hz"], 4)
    (['measured', 'predicted', 'residual', 'time_s'], 3.1831)
    """

    signal_kind: str
    omega_n_rad_s: float
    damping_ratio: float
    omega_n_interval: tuple[float, float]
    damping_ratio_interval: tuple[float, float]
    r2: float
    nrmse: float
    slosh_r2: float
    constrained: dict[str, bool]
    linear: dict[str, float]
    linear_intervals: dict[str, tuple[float, float]]
    time_s: FloatArray
    measured: FloatArray
    predicted: FloatArray
    motion_span_s: tuple[float, float]
    source: str = ""
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = field(default=())
    delay_s: float | None = None
    delay_interval_s: tuple[float, float] | None = None

    @classmethod
    def from_fit(
        cls,
        fit: FitStatistics,
        time_s: FloatArray,
        measured: FloatArray,
        *,
        signal_kind: str,
        omega_n_rad_s: float,
        damping_ratio: float,
        constrained: dict[str, bool],
        linear: tuple[dict[str, float], dict[str, tuple[float, float]]],
        motion_span_s: tuple[float, float],
        source: str = "",
        notes: tuple[str, ...] = (),
        warnings: tuple[str, ...] = (),
        delay_s: float | None = None,
        delay_fitted: bool = False,
    ) -> ForcedIdentification:
        """The result of a separable fit whose nonlinear parameters are (omega_n, zeta[, tau]):
        the one place that turns `FitStatistics` into intervals (nonlinear half-widths
        first, as `fit_statistics` orders them; the clock offset's third when fitted).

        Parameters
        ----------
        fit : FitStatistics
            Statistics at the solution.
        time_s, measured : numpy.ndarray
            The record that was fitted (uniform time [s], signal units).
        signal_kind : str
            force, height or angle.
        omega_n_rad_s, damping_ratio : float
            The solution [rad/s] and [-].
        constrained : dict
            Which parameters the record constrains (`constraint_flags`).
        linear : tuple of dict
            The linear coefficients by name and their 95 % intervals
            (`FitStatistics.linear_parameters`).
        motion_span_s : tuple of float
            Start and end of the motion on the record's clock [s].
        source, notes, warnings : str, tuple of str
            Provenance, notes on the record's preparation and warnings.
        delay_s : float, optional
            The clock offset between motion and record [s], when there is one.
        delay_fitted : bool
            ``delay_s`` was fitted: its interval comes from the third half-width.

        Returns
        -------
        ForcedIdentification

        Examples
        --------
        >>> import numpy as np
        >>> t = np.linspace(0.0, 1.0, 5)
        >>> fit = FitStatistics(np.array([2.0]), t, np.array([0.5, 0.01, 0.1]), 1.0, 0.0, 1.0)
        >>> found = ForcedIdentification.from_fit(
        ...     fit, t, t, signal_kind="height", omega_n_rad_s=20.0, damping_ratio=0.02,
        ...     constrained={}, linear=fit.linear_parameters(["gain"], first=2),
        ...     motion_span_s=(0.0, 0.5))
        >>> found.omega_n_interval, found.damping_ratio_interval, found.linear_intervals
        ((19.5, 20.5), (0.01, 0.03), {'gain': (1.9, 2.1)})
        """
        half = fit.half_width
        return cls(
            signal_kind=signal_kind,
            omega_n_rad_s=omega_n_rad_s,
            damping_ratio=damping_ratio,
            omega_n_interval=(omega_n_rad_s - float(half[0]), omega_n_rad_s + float(half[0])),
            damping_ratio_interval=(
                max(0.0, damping_ratio - float(half[1])),
                damping_ratio + float(half[1]),
            ),
            r2=fit.r2,
            nrmse=fit.nrmse,
            slosh_r2=fit.slosh_r2,
            constrained=constrained,
            linear=linear[0],
            linear_intervals=linear[1],
            time_s=time_s,
            measured=measured,
            predicted=fit.predicted,
            motion_span_s=motion_span_s,
            source=source,
            notes=notes,
            warnings=warnings,
            delay_s=delay_s,
            delay_interval_s=(delay_s - float(half[2]), delay_s + float(half[2]))
            if delay_fitted and delay_s is not None
            else None,
        )

    @property
    def slosh_mass_kg(self) -> float | None:
        """First-mode slosh mass m_1 from a force record [kg] (None for other kinds)."""
        return self.linear.get("slosh_mass_kg")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready result (unit-suffixed keys)."""
        return {
            "method": "forced",
            "signal_kind": self.signal_kind,
            "omega_n_rad_s": self.omega_n_rad_s,
            "frequency_hz": self.omega_n_rad_s / (2 * math.pi),
            "damping_ratio": self.damping_ratio,
            "omega_n_interval_rad_s": list(self.omega_n_interval),
            "damping_ratio_interval": list(self.damping_ratio_interval),
            "r2": self.r2,
            "nrmse": self.nrmse,
            "slosh_r2": self.slosh_r2,
            "constrained": dict(self.constrained),
            **{key: value for key, value in self.linear.items()},
            **{f"{key}_interval": list(value) for key, value in self.linear_intervals.items()},
            "delay_s": self.delay_s,
            "delay_interval_s": None
            if self.delay_interval_s is None
            else list(self.delay_interval_s),
            "record_s": [float(self.time_s[0]), float(self.time_s[-1])],
            "motion_s": list(self.motion_span_s),
            "source": self.source,
            "notes": list(self.notes),
            "warnings": list(self.warnings),
        }

    def columns(self) -> dict[str, FloatArray]:
        """Measured and predicted record over time, and their difference (signal units)."""
        return {
            "time_s": self.time_s,
            "measured": self.measured,
            "predicted": self.predicted,
            "residual": self.measured - self.predicted,
        }

    def provenance(self) -> str:
        """Which identification and record produced the calibration (for model files)."""
        return (
            f"calibration: forced-response identification ({self.signal_kind}) of "
            f"{self.source or 'record'} [{self.time_s[0]:.4g}, {self.time_s[-1]:.4g}] s"
        )

    def calibrated_model(self, model: SloshModel) -> SloshModel:
        """``model`` with mode 1's frequency and every mode's damping ratio replaced."""
        source = self.provenance()
        calibrated = model.with_mode(1, omega_rad_s=self.omega_n_rad_s, source=source)
        for mode in calibrated.modes:
            calibrated = calibrated.with_mode(
                mode.n, damping_ratio=self.damping_ratio, source=source
            )
        return calibrated


def _slosh_columns(
    model: SloshModel,
    kind: str,
    velocity: FloatArray,
    step: float,
    omega: float,
    zeta: float,
    higher_zeta: float | None = None,
) -> FloatArray:
    """The model's response that scales with the gain (or the slosh mass) for trial values;
    modes above the first take ``higher_zeta`` (default the trial ``zeta``)."""
    first = model.modes[0]
    total = np.zeros_like(velocity)
    modes = model.modes[:1] if kind == "angle" else model.modes
    for mode in modes:
        w = omega if mode.n == 1 else mode.omega_rad_s
        z = zeta if mode.n == 1 or higher_zeta is None else higher_zeta
        theta, rate = linear_mode_response(velocity, step, w, z, mode.length_m)
        if kind == "angle":
            total += theta
        elif kind == "height":
            total += mode.wall_elevation_factor_m * theta
        else:
            ratio = mode.slosh_mass_kg / first.slosh_mass_kg
            total += ratio * mode.length_m * (w**2 * theta + 2.0 * z * w * rate)
    return total


def _design(
    model: SloshModel,
    kind: str,
    t: FloatArray,
    velocity: FloatArray,
    acceleration: FloatArray,
    omega: float,
    zeta: float,
    higher_zeta: float | None = None,
) -> FloatArray:
    slosh = _slosh_columns(model, kind, velocity, t[1] - t[0], omega, zeta, higher_zeta)
    tau = (t - t[0]) / max(1e-12, t[-1] - t[0])
    columns = [slosh, np.ones_like(t), tau]
    if kind == "force":
        columns.insert(1, acceleration)
    return np.column_stack(columns)


def identify_forced(
    model: SloshModel,
    applied: AppliedMotion,
    time_s: FloatArray,
    values: FloatArray,
    *,
    signal_kind: SignalKind = "height",
    lowpass_hz: float | None = None,
    require_constrained: bool = True,
    source: str = "",
) -> ForcedIdentification:
    """Fit omega_n and zeta (and for forces the slosh mass) of ``model``'s first mode to a
    record of the response to ``applied`` (see the module docstring).

    Parameters
    ----------
    model : the container's equivalent model (theoretical values start the search)
    applied : the applied motion in the record's clock (starts at or after the record)
    time_s, values : the record; the liquid is assumed at rest at its first sample
    signal_kind : force [N], height [m] or angle [rad]
    lowpass_hz : optional zero-phase low-pass cut-off for the record [Hz]
    require_constrained : raise `InputError` when the record does not constrain omega_n or
        zeta; otherwise return the result with ``constrained`` flags
    source : where the record came from (provenance)

    Returns
    -------
    ForcedIdentification with intervals, R^2, NRMSE and the linear parameters.

    References
    ----------
    Golub & Pereyra, Inverse Problems 19 (2003) R1, doi:10.1088/0266-5611/19/2/201;
    Ljung, *System Identification*, 2nd ed. (1999) §9 (covariance of prediction-error
    estimates); seed paper eq. 7.

    Examples
    --------
    >>> import warnings
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.motion import quintic
    >>> from sloshkit.sim.simulate import simulate
    >>> model = equivalent_model(UprightCylinder(0.04), get_liquid("water-25C"), 0.06, 1,
    ...                          damping_ratio=0.02)
    >>> move = quintic(0.05, 0.5)
    >>> response = simulate(model, move, sample_period_s=0.004, settle_time_s=0.0)
    >>> guess = model.with_mode(1, omega_rad_s=19.0).with_mode(1, damping_ratio=0.05)
    >>> found = identify_forced(guess, AppliedMotion(move), response.time_s,
    ...                         response.wall_elevation_m)
    >>> round(found.omega_n_rad_s / model.modes[0].omega_rad_s, 4), round(found.damping_ratio, 4)
    (1.0, 0.02)
    """
    if signal_kind not in SIGNAL_KINDS:
        raise InputError("signal_kind", signal_kind, "must be one of " + ", ".join(SIGNAL_KINDS))
    t, y, notes = uniform_signal(time_s, values, lowpass_hz)
    if applied.start_s < t[0] - 1e-9:
        raise InputError(
            "motion",
            f"starts at {applied.start_s:.4g} s",
            f"must start at or after the record ({t[0]:.4g} s): the liquid must be at rest "
            "at the record's first sample",
        )
    if applied.start_s > t[-1]:
        raise InputError(
            "motion", f"starts at {applied.start_s:.4g} s", f"after the record ends ({t[-1]:.4g} s)"
        )
    velocity = applied.velocity(t)
    acceleration = applied.acceleration(t)
    kind = str(signal_kind)
    spread = float(np.std(y))
    if spread == 0.0:
        raise InputError("signal", "constant", "has no response to the motion")

    def residual(parameters: FloatArray, higher_zeta: float | None = None) -> FloatArray:
        design = _design(
            model, kind, t, velocity, acceleration, parameters[0], parameters[1], higher_zeta
        )
        coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
        return np.asarray((y - design @ coefficients) / spread, dtype=float)

    theory = model.modes[0]
    best = (math.inf, theory.omega_rad_s, theory.damping_ratio)
    # Coarse grid (1.5 % steps, so the phase of a long record cannot trap the search); the
    # higher modes keep the model's damping here, which reuses their cached discretisation.
    for omega in theory.omega_rad_s * np.geomspace(0.5, 2.0, 95):
        for zeta in (0.005, 0.03):
            trial = residual(np.array([omega, zeta]), theory.damping_ratio)
            cost = float(trial @ trial)
            if cost < best[0]:
                best = (cost, float(omega), zeta)
    low = np.array([0.3 * theory.omega_rad_s, 1e-4])
    high = np.array([3.0 * theory.omega_rad_s, 0.6])
    solution = least_squares(
        residual,
        np.clip([best[1], best[2]], low * 1.0001, high * 0.9999),
        bounds=(low, high),
        x_scale=np.array([best[1], 0.01]),
        diff_step=1e-6,
    )
    omega, zeta = (float(v) for v in solution.x)

    def design_at(parameters: FloatArray) -> FloatArray:
        return _design(model, kind, t, velocity, acceleration, parameters[0], parameters[1])

    fit = fit_statistics(y, design_at, np.array([omega, zeta]))
    names = ["gain" if kind != "force" else "slosh_mass_kg"]
    if kind == "force":
        names.append("rigid_force_per_acceleration_kg")
    names += ["offset", "drift_per_record"]
    linear, linear_intervals = fit.linear_parameters(names, first=2)
    warnings_out: list[str] = []
    if kind == "force":
        # A sensor that reports the force applied to the payload flips both signs.
        rigid = linear["rigid_force_per_acceleration_kg"]
        sign = -1.0 if rigid > 0 else 1.0
        mass = sign * linear["slosh_mass_kg"]
        linear["slosh_mass_kg"] = mass
        linear["rigid_mass_kg"] = abs(rigid)
        lo, hi = linear_intervals["slosh_mass_kg"]
        linear_intervals["slosh_mass_kg"] = (min(sign * lo, sign * hi), max(sign * lo, sign * hi))
        if mass <= 0:
            warnings_out.append(
                "the slosh term has the sign of the rigid inertia: check the force axis"
            )
    scale_name = "slosh_mass" if kind == "force" else "gain"
    scale = linear["slosh_mass_kg"] if kind == "force" else linear["gain"]
    half = fit.half_width
    constrained, message = constraint_flags(
        omega, zeta, half[0], half[1], scale_name, scale, half[2], require_constrained
    )
    if message:
        warnings_out.append(message)
    return ForcedIdentification.from_fit(
        fit,
        t,
        y,
        signal_kind=kind,
        omega_n_rad_s=omega,
        damping_ratio=zeta,
        constrained=constrained,
        linear=(linear, linear_intervals),
        motion_span_s=(applied.start_s, applied.end_s),
        source=source,
        notes=tuple(notes) + applied.notes,
        warnings=tuple(warnings_out),
    )
