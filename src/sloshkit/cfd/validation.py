"""The result of comparing a CFD case with the pendulum model for the same motion.

`CfdValidation` follows the shared result protocol (`sloshkit.results.ResultMixin`):
``to_dict`` is the JSON document of ``sloshkit cfd validate --json``, ``columns`` /
``to_pandas`` / ``to_csv`` hold the two compared series, and ``plot`` draws the seed paper's
Fig. 9 with `sloshkit.plotting.cfd.plot_cfd_validation` (named in `sloshkit.results.PLOTS`
and imported by name when a figure is drawn, so this module never imports matplotlib).
`validate` (re-exported by `sloshkit.cfd.pipeline`) builds it.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.special import j1

from sloshkit.calibration import CalibrationResult, calibrate
from sloshkit.cfd.analysis import analyse, excitation_end, read_finished_signals
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.model.modal import SloshModel
from sloshkit.motion.recorded import from_samples
from sloshkit.results import ResultMixin
from sloshkit.sim.simulate import simulate

#: Kinds of comparison: the 1-D wall elevation, or the 3-D slosh height of a pose trajectory.
KINDS = ("wall-elevation", "poses")


def comparison_row(cfd: float | None, model: float | None) -> dict[str, float | None]:
    """One row of a comparison: both values and the relative difference to the model.

    Parameters
    ----------
    cfd : float or None
        The CFD value (None when it could not be measured).
    model : float or None
        The model value.

    Returns
    -------
    dict
        ``cfd``, ``model`` and ``relative_difference`` ((cfd - model) / model, or None).

    Examples
    --------
    >>> comparison_row(1.1, 1.0)["relative_difference"]  # doctest: +ELLIPSIS
    0.100000...
    >>> comparison_row(None, 1.0)["relative_difference"] is None
    True
    """
    difference = None
    if cfd is not None and model is not None and model != 0.0:
        difference = (cfd - model) / model
    return {"cfd": cfd, "model": model, "relative_difference": difference}


def require_model_first(model: object, case: object) -> None:
    """Refuse the v1 argument order ``(case, model)`` with a `TypeError` saying so.

    Parameters
    ----------
    model : object
        What was passed as the model.
    case : object
        What was passed as the case folder.

    Returns
    -------
    None

    Raises
    ------
    TypeError
        ``model`` is a path (or ``case`` is not one).

    Examples
    --------
    >>> require_model_first(Path("case"), None)
    Traceback (most recent call last):
    ...
    TypeError: validate takes (model, case); got a path first (the v1 order was (case, model))
    """
    if isinstance(model, str | Path) or not isinstance(case, str | Path):
        raise TypeError(
            "validate takes (model, case); got a path first (the v1 order was (case, model))"
        )


@dataclass(frozen=True, eq=False)
class CfdValidation(ResultMixin):
    """A finished CFD case against the equivalent pendulum model for the same motion.

    Parameters
    ----------
    case : str
        The case folder.
    comparison : dict
        Quantity name (with its unit) -> `comparison_row`.
    correlation : float or None
        Correlation of the two compared series over the whole record.
    time_s : ndarray
        Sample times of the CFD record [s].
    cfd_elevation_m, model_elevation_m : ndarray
        The compared series [m]: the wall elevation at 0.98 R (1-D), or the slosh height, the
        largest wall elevation over the probe columns (poses).
    excitation_end_s : float
        When the container stops moving [s] (0 for a free decay).
    kind : str
        ``wall-elevation`` or ``poses`` (see `KINDS`).
    extra : dict
        Further JSON keys: ``damping_signal`` (1-D: the CFD signal of frequency and damping,
        see `sloshkit.cfd.analysis.analyse`), or those of a pose comparison
        (``wall_correlation``, ``probe_angles_deg``, ``quantity_label``).

    Returns
    -------
    CfdValidation

    References
    ----------
    De Simone et al. (2024), the seed paper, Table 4 and Fig. 9.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> result = CfdValidation("c", {"damping_ratio": comparison_row(0.005, 0.006)}, 0.99,
    ...                        t, 1e-3 * t, 1e-3 * t, 0.5)
    >>> sorted(result.to_dict())
    ['case', 'comparison', 'correlation', 'excitation_end_s']
    >>> list(result.columns())
    ['time_s', 'cfd_elevation_m', 'model_elevation_m']
    """

    case: str
    comparison: dict[str, dict[str, float | None]]
    correlation: float | None
    time_s: NDArray[np.float64]
    cfd_elevation_m: NDArray[np.float64]
    model_elevation_m: NDArray[np.float64]
    excitation_end_s: float
    kind: str = "wall-elevation"
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def quantity_label(self) -> str:
        """Axis label of the compared series."""
        return str(self.extra.get("quantity_label", "wall elevation at 0.98 R [mm]"))

    def columns(self) -> dict[str, NDArray[np.float64]]:
        """The compared series: ``time_s``, ``cfd_elevation_m``, ``model_elevation_m``."""
        return {
            "time_s": self.time_s,
            "cfd_elevation_m": self.cfd_elevation_m,
            "model_elevation_m": self.model_elevation_m,
        }

    def to_dict(self) -> dict[str, Any]:
        """The JSON document of ``sloshkit cfd validate --json`` (no series)."""
        payload: dict[str, Any] = {"case": self.case}
        if self.kind == "poses":
            payload["kind"] = self.kind
        payload.update(comparison=self.comparison, correlation=self.correlation)
        payload.update(self.extra)
        payload["excitation_end_s"] = self.excitation_end_s
        return payload


def model_wall_elevation(
    model: SloshModel, time_s: np.ndarray, acceleration: np.ndarray, x_over_r: float = 0.98
) -> np.ndarray:
    """The pendulum model's wall elevation at x = x_over_r R for a sampled container
    acceleration: each mode scaled by J1(xi_n x/R)/J1(xi_n) (the linear mode shape).

    Parameters
    ----------
    model : SloshModel
        The pendulum model.
    time_s : ndarray
        Sample times [s].
    acceleration : ndarray
        Container acceleration along x at those times [m/s^2].
    x_over_r : float
        Where the elevation is read, as a fraction of the radius.

    Returns
    -------
    ndarray
        Wall elevation [m].

    References
    ----------
    Ibrahim, *Liquid Sloshing Dynamics* (2005), §2.3 (mode shapes J1(xi_n r/R) of the upright
    cylinder).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(0.0, 0.5, 0.002)
    >>> elevation = model_wall_elevation(model, t, np.where(t < 0.1, 1.0, 0.0))
    >>> bool(np.abs(elevation).max() > 0.0), elevation.shape
    (True, (250,))
    """

    motion = from_samples(time_s, acceleration_m_s2=acceleration, name="cfd excitation")
    dt = float(np.median(np.diff(time_s)))
    response = simulate(model, motion, sample_period_s=dt, settle_time_s=0.0)
    shape = np.array([j1(m.bessel_root * x_over_r) / j1(m.bessel_root) for m in model.modes])
    factors = np.array([m.wall_elevation_factor_m for m in model.modes]) * shape
    elevation = factors @ response.angle_rad
    return np.asarray(np.interp(time_s, response.time_s, elevation), dtype=float)


def validate(model: SloshModel, case: Path) -> CfdValidation:
    """Compare a finished case with the pendulum model for the same motion.

    The model is driven by the container acceleration the case was driven with (read back
    from its table) and read at the probes' radius through the linear mode shapes; both
    records are calibrated the same way (`analyse`: the CFD's frequency and damping come from
    its wall force when it has one, named by ``damping_signal``; the residual amplitude always
    from its wall elevation). A forced run that ends too soon after
    its excitation still compares the peak elevation during it, with ``None`` for frequency,
    damping and residual amplitude and a `ValidityWarning`.

    Parameters
    ----------
    model : SloshModel
        The equivalent pendulum model of the same container, fill and liquid.
    case : Path
        A finished case (``sloshkit cfd run`` or ``cfd validate``).

    Returns
    -------
    CfdValidation
        ``comparison`` rows ``omega_n_rad_s``, ``damping_ratio``, ``peak_elevation_m`` (during
        the excitation) and ``residual_elevation_m`` (fitted amplitude after it), the
        correlation of the two wall elevations, ``damping_signal`` (``wall_force``,
        ``wall_elevation``, or None without a free decay) and both series.

    Raises
    ------
    InputError
        Not a finished sloshkit case.

    References
    ----------
    De Simone et al. (2024), the seed paper, Table 4 and Fig. 9.

    Examples
    --------
    >>> from pathlib import Path
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> validate(model, Path("no-such-case"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: case = 'no-such-case' is invalid: is not a sloshkit CFD case ...
    """
    require_model_first(model, case)
    case = Path(case)
    signals = read_finished_signals(case)
    summary = dict(signals.summary)
    t = signals.time_s
    acceleration = _excitation_acceleration(case, t)
    predicted = model_wall_elevation(model, t, acceleration)
    end = excitation_end(summary)
    during = t <= max(end, t[0])
    cfd_fit: CalibrationResult | None = None
    cfd_elevation_fit: CalibrationResult | None = None
    model_fit: CalibrationResult | None = None
    damping_signal: str | None = None
    try:
        analysis = analyse(case)
        cfd_fit = analysis.calibration
        damping_signal = analysis.damping_signal
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            cfd_elevation_fit = cfd_fit if damping_signal == "wall_elevation" else None
            if cfd_elevation_fit is None:  # the residual amplitude is an elevation [m]
                try:
                    cfd_elevation_fit = calibrate(
                        t,
                        signals.elevation_m,
                        forcing_end_s=end if end > 0 else None,
                        source=f"{case} (CFD wall elevation)",
                    )
                except InputError:
                    cfd_elevation_fit = None
            model_fit = calibrate(
                t, predicted, forcing_end_s=end if end > 0 else None, source="pendulum model"
            )
    except InputError as error:
        warnings.warn(
            f"no free decay to compare (frequency, damping, residual): {error}",
            ValidityWarning,
            stacklevel=2,
        )

    def value(result: CalibrationResult | None, key: str) -> float | None:
        if result is None:
            return None
        if key == "amplitude":
            amplitude = result.estimates["fit"].amplitude
            return None if amplitude is None else float(amplitude)
        return float(getattr(result, key))

    comparison = {
        "omega_n_rad_s": comparison_row(
            value(cfd_fit, "omega_n_rad_s"), value(model_fit, "omega_n_rad_s")
        ),
        "damping_ratio": comparison_row(
            value(cfd_fit, "damping_ratio"), value(model_fit, "damping_ratio")
        ),
        "peak_elevation_m": comparison_row(
            float(np.max(np.abs(signals.elevation_m[during]))) if end > 0 else None,
            float(np.max(np.abs(predicted[during]))) if end > 0 else None,
        ),
        "residual_elevation_m": comparison_row(
            value(cfd_elevation_fit, "amplitude"), value(model_fit, "amplitude")
        ),
    }
    correlation = float(np.corrcoef(signals.elevation_m, predicted)[0, 1])
    return CfdValidation(
        case=str(case),
        comparison=comparison,
        correlation=correlation,
        time_s=np.asarray(t, dtype=float),
        cfd_elevation_m=np.asarray(signals.elevation_m, dtype=float),
        model_elevation_m=np.asarray(predicted, dtype=float),
        excitation_end_s=end,
        extra={"damping_signal": damping_signal},
    )


def _excitation_acceleration(case: Path, t: np.ndarray) -> np.ndarray:
    """The container acceleration the case was driven with, read back from its table [m/s^2]."""
    text = (case / "constant" / "acceleration.dat").read_text(encoding="utf-8")
    rows = [line for line in text.splitlines() if line.startswith("(") and "((" in line]
    times = np.array([float(row[1:].split()[0]) for row in rows])
    values = np.array([float(row.split("((")[1].split()[0]) for row in rows]) / 1000.0
    return np.asarray(np.interp(t, times, values), dtype=float)
