"""Identification with any simulator in the loop, and a clock offset between motion and record.

`identify_forced` drives the 1-D model itself. Other simulators (a 3-D slosh model driven by
robot poses, a nonlinear model) plug in here as a function ``simulate(omega_n, zeta) ->
(time_s, response)`` on the motion's clock. The record is explained by

    y(t) = g r(t - tau; omega_n, zeta) + c + d t

with the gain g, offset c and drift d eliminated by variable projection, and (omega_n, zeta)
and optionally the clock offset tau fitted by `scipy.optimize.least_squares` after a grid
search. Camera and robot clocks are often not synchronised: with ``fit_delay`` tau is found
within +-``delay_range_s`` of the given ``delay_s`` (one simulation serves every tau, so this
costs nothing extra). Intervals, fit quality and the refusal of unconstrained parameters are
those of `sloshkit.calibration.forced`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from sloshkit.calibration.forced import ForcedIdentification
from sloshkit.calibration.separable import constraint_flags, fit_statistics
from sloshkit.calibration.signals import uniform_signal
from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]
Simulator = Callable[[float, float], tuple[FloatArray, FloatArray]]


def identify_simulated(
    simulate: Simulator,
    time_s: FloatArray,
    values: FloatArray,
    *,
    omega_guess_rad_s: float,
    zeta_guess: float = 0.01,
    delay_s: float = 0.0,
    fit_delay: bool = False,
    delay_range_s: float = 0.5,
    omega_range: tuple[float, float] = (0.7, 1.4),
    signal_kind: str = "height",
    motion_span_s: tuple[float, float] | None = None,
    require_constrained: bool = True,
    source: str = "",
    notes: tuple[str, ...] = (),
) -> ForcedIdentification:
    """Fit omega_n, zeta (and the clock offset) of a simulator to a record.

    Parameters
    ----------
    simulate : (omega_n [rad/s], zeta) -> (time [s], response) on the motion's clock, from
        rest; the response is held at its first value before and its last value after
    time_s, values : the record
    omega_guess_rad_s, zeta_guess : centre of the search (e.g. the model's theory)
    delay_s : record time minus motion time [s] (the clock offset)
    fit_delay : fit the clock offset within +-``delay_range_s`` of ``delay_s``
    delay_range_s : half-width of the clock offset's search range [s]
    omega_range : search range as factors of ``omega_guess_rad_s``
    signal_kind : label of the signal (height, angle, force)
    motion_span_s : start and end of the motion on its clock [s] (default: the simulation's)
    require_constrained : raise `InputError` when omega_n or zeta is not constrained
    source, notes : provenance of the record

    Returns
    -------
    ForcedIdentification (``linear``: gain, offset, drift_per_record; ``delay_s``).

    References
    ----------
    Golub & Pereyra, Inverse Problems 19 (2003) R1, doi:10.1088/0266-5611/19/2/201.

    Examples
    --------
    >>> import numpy as np
    >>> def simulate(omega, zeta):
    ...     t = np.arange(0, 3, 0.005)
    ...     damped = omega * np.sqrt(1 - zeta**2)
    ...     return t, np.where(t > 1, np.exp(-zeta * omega * (t - 1)) * np.sin(damped * (t - 1)), 0)
    >>> t = np.arange(0, 3, 0.005)
    >>> record = 2 * np.interp(t - 0.3, *simulate(20.0, 0.02), left=0) + 0.1
    >>> found = identify_simulated(simulate, t, record, omega_guess_rad_s=18.0, delay_s=0.25,
    ...                            fit_delay=True, delay_range_s=0.1)
    >>> round(found.omega_n_rad_s, 3), round(found.damping_ratio, 4), round(found.delay_s, 3)
    (20.0, 0.02, 0.3)
    """
    t, y, prepared = uniform_signal(time_s, values)
    if float(np.std(y)) == 0.0:
        raise InputError("signal", "constant", "has no response to the motion")
    spread = float(np.std(y))
    tau = (t - t[0]) / max(1e-12, float(t[-1] - t[0]))
    cache: dict[tuple[float, float], tuple[FloatArray, FloatArray]] = {}

    def response(omega: float, zeta: float) -> tuple[FloatArray, FloatArray]:
        key = (round(omega, 10), round(zeta, 12))
        if key not in cache:
            sim_t, sim_y = simulate(omega, zeta)
            cache[key] = (np.asarray(sim_t, dtype=float), np.asarray(sim_y, dtype=float))
        return cache[key]

    def design_at(parameters: FloatArray) -> FloatArray:
        omega, zeta = float(parameters[0]), float(parameters[1])
        delay = float(parameters[2]) if fit_delay else delay_s
        sim_t, sim_y = response(omega, zeta)
        shifted = np.interp(t - delay, sim_t, sim_y)
        return np.column_stack((shifted, np.ones_like(t), tau))

    def residual(parameters: FloatArray) -> FloatArray:
        design = design_at(parameters)
        coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
        return np.asarray((y - design @ coefficients) / spread, dtype=float)

    delays = (
        np.arange(delay_s - delay_range_s, delay_s + delay_range_s + 1e-9, 0.01)
        if fit_delay
        else np.array([delay_s])
    )
    best = (np.inf, omega_guess_rad_s, delay_s)
    for omega in omega_guess_rad_s * np.geomspace(omega_range[0], omega_range[1], 25):
        for delay in delays:
            trial = residual(np.array([omega, zeta_guess, delay]))
            cost = float(trial @ trial)
            if cost < best[0]:
                best = (cost, float(omega), float(delay))
    low = [omega_range[0] * omega_guess_rad_s, 1e-4]
    high = [omega_range[1] * omega_guess_rad_s, 0.5]
    start = [best[1], zeta_guess]
    scale = [best[1], 0.01]
    if fit_delay:
        low.append(delay_s - delay_range_s)
        high.append(delay_s + delay_range_s)
        start.append(best[2])
        scale.append(0.05)
    solution = least_squares(
        residual,
        np.clip(start, np.array(low) * 1.0001, np.array(high) * 0.9999),
        bounds=(low, high),
        x_scale=np.array(scale),
        diff_step=1e-5,
        max_nfev=200,
    )
    fit = fit_statistics(y, design_at, np.asarray(solution.x, dtype=float))
    omega, zeta = float(solution.x[0]), float(solution.x[1])
    half = fit.half_width
    count = 3 if fit_delay else 2
    linear, linear_intervals = fit.linear_parameters(
        ("gain", "offset", "drift_per_record"), first=count
    )
    constrained, message = constraint_flags(
        omega, zeta, half[0], half[1], "gain", linear["gain"], half[count], require_constrained
    )
    delay = float(solution.x[2]) if fit_delay else delay_s
    sim_t, _ = response(omega, zeta)
    span = (float(sim_t[0]), float(sim_t[-1])) if motion_span_s is None else motion_span_s
    return ForcedIdentification.from_fit(
        fit,
        t,
        y,
        signal_kind=signal_kind,
        omega_n_rad_s=omega,
        damping_ratio=zeta,
        constrained=constrained,
        linear=(linear, linear_intervals),
        motion_span_s=(span[0] + delay, span[1] + delay),
        source=source,
        notes=tuple(prepared) + tuple(notes),
        warnings=(message,) if message else (),
        delay_s=delay,
        delay_fitted=fit_delay,
    )
