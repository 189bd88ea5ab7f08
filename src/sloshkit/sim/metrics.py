"""Slosh metrics shared by every simulation path: the time grid, the residual amplitude of the
free oscillation left after a move, settling defaults."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.model.modal import SloshModel
from sloshkit.motion.sampling import steps_to_reach

FloatArray = NDArray[np.float64]


#: Default tolerance for the settling time: 0.1 degree of the first mode [rad].
DEFAULT_SETTLE_TOLERANCE_RAD = math.radians(0.1)


def free_oscillation_components(
    angle_rad: Any, rate_rad_s: Any, omega_rad_s: float, damping_ratio: float
) -> tuple[Any, Any]:
    """(A, B) of the free damped oscillation through the state (theta, theta').

    theta(t) = e^{-zeta w t} (A cos w_d t + B sin w_d t) with A = theta and
    B = (theta' + zeta w theta) / w_d, w_d = w sqrt(1 - zeta^2). Plain arithmetic: the arguments
    may be floats, numpy arrays or casadi expressions.

    Parameters
    ----------
    angle_rad : float, array or casadi expression
        Angle theta at the instant considered [rad].
    rate_rad_s : float, array or casadi expression
        Angular rate theta' at that instant [rad/s].
    omega_rad_s : float
        Natural frequency w [rad/s].
    damping_ratio : float
        Damping ratio zeta (< 1).

    Returns
    -------
    tuple
        (A, B) [rad]; the amplitude is sqrt(A^2 + B^2).

    References
    ----------
    Meirovitch, L., *Fundamentals of Vibrations*, McGraw-Hill (2001) §2.5.

    Examples
    --------
    >>> free_oscillation_components(0.0, 2.0, 2.0, 0.0)
    (0.0, 1.0)
    """
    damped = omega_rad_s * math.sqrt(max(1e-300, 1.0 - damping_ratio**2))
    return angle_rad, (rate_rad_s + damping_ratio * omega_rad_s * angle_rad) / damped


def free_amplitude(
    angle_rad: FloatArray | float,
    rate_rad_s: FloatArray | float,
    omega_rad_s: float,
    damping_ratio: float,
) -> FloatArray:
    """Envelope amplitude sqrt(A^2 + B^2) of the free damped oscillation through (theta, theta').

    Parameters
    ----------
    angle_rad : float or array
        Angle theta [rad].
    rate_rad_s : float or array
        Angular rate theta' [rad/s].
    omega_rad_s : float
        Natural frequency [rad/s].
    damping_ratio : float
        Damping ratio (< 1).

    Returns
    -------
    numpy.ndarray
        The amplitude [rad] (see `free_oscillation_components`).

    Examples
    --------
    >>> float(free_amplitude(0.03, 0.0, 5.0, 0.0))
    0.03
    """
    angle, quadrature = free_oscillation_components(
        np.asarray(angle_rad, dtype=float),
        np.asarray(rate_rad_s, dtype=float),
        omega_rad_s,
        damping_ratio,
    )
    return np.asarray(np.hypot(angle, quadrature), dtype=float)


def wall_elevation_factors(model: SloshModel) -> FloatArray:
    """Per mode, the wall elevation per radian of pendulum angle, 2R/(xi_n^2 - 1) [m/rad].

    Parameters
    ----------
    model : SloshModel
        The equivalent model.

    Returns
    -------
    numpy.ndarray
        One factor per mode (see `sloshkit.model.theory.wall_elevation_factor`).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> wall_elevation_factors(model).shape
    (3,)
    """
    return np.array([mode.wall_elevation_factor_m for mode in model.modes])


def wall_elevation(
    factors_m: Sequence[float] | FloatArray,
    angles_rad: Sequence[Any] | FloatArray,
    *,
    nonlinear: bool = False,
    sin: Callable[[Any], Any] = np.sin,
) -> Any:
    """Free-surface elevation at the wall on the +x side: sum_n f_n theta_n [m].

    The linear mode-shape mapping of the equivalent model (f_n = 2R/(xi_n^2 - 1)), with
    sin(theta_n) in place of theta_n for the large-angle pendulums. Plain arithmetic: the angles
    may be numpy rows or casadi expressions.

    Parameters
    ----------
    factors_m : sequence of float
        Per-mode factors f_n [m/rad] (`wall_elevation_factors`).
    angles_rad : sequence
        Per-mode angles theta_n (rows of a (modes, samples) array, or expressions) [rad].
    nonlinear : bool
        Map sin(theta_n) instead of theta_n.
    sin : callable
        The sine of the arithmetic used (when ``nonlinear``).

    Returns
    -------
    float, array or casadi expression
        The wall elevation [m].

    References
    ----------
    Ibrahim, R. A., *Liquid Sloshing Dynamics* (2005) §1.3, doi:10.1017/CBO9780511536656.

    Examples
    --------
    >>> float(wall_elevation([0.02, 0.001], [0.1, 0.2]))
    0.0022
    """
    total: Any = 0.0
    for factor, angle in zip(factors_m, angles_rad, strict=True):
        total = total + float(factor) * (sin(angle) if nonlinear else angle)
    return total


def default_settle_time(model: SloshModel) -> float:
    """Time simulated after the move for plots: 5 first-mode periods, at least 1 s [s].

    Parameters
    ----------
    model : SloshModel
        The equivalent model.

    Returns
    -------
    float
        The settle time [s].

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> round(default_settle_time(model), 3)
    1.059
    """
    return max(1.0, 5.0 * 2.0 * math.pi / model.modes[0].omega_rad_s)


def simulation_grid(
    move_duration_s: float, sample_period_s: float, settle_time_s: float
) -> FloatArray:
    """Uniform times k Ts from 0 to at least T + settle time [s] (shared by all paths).

    Refuses (`InputError`) a grid whose simulation arrays would exceed the memory limit of
    `sloshkit.budget` (about 32 float64 columns per sample for states, metrics and output).

    Parameters
    ----------
    move_duration_s : float
        Move duration T [s].
    sample_period_s : float
        Step Ts [s].
    settle_time_s : float
        Time after the move [s].

    Returns
    -------
    numpy.ndarray
        The grid; its step count is `sloshkit.motion.sampling.steps_to_reach`.

    Examples
    --------
    >>> simulation_grid(0.3, 0.1, 0.0).tolist()
    [0.0, 0.1, 0.2, 0.30000000000000004]
    """
    from sloshkit.budget import require_samples

    total_s = move_duration_s + settle_time_s
    samples = total_s / sample_period_s if sample_period_s > 0.0 else math.inf
    require_samples("sample_period", f"{sample_period_s:.3g} s for {total_s:.3g} s", samples, 32)
    count = steps_to_reach(move_duration_s + settle_time_s, sample_period_s) + 1
    return np.arange(count, dtype=float) * sample_period_s


def residual_from_state(
    time_s: FloatArray,
    angle_rad: FloatArray,
    rate_rad_s: FloatArray,
    move_duration_s: float,
    model: SloshModel,
) -> FloatArray:
    """Per-mode free-oscillation amplitude at T from the state at the first sample t_k >= T.

    The amplitude there is scaled back by exp(zeta omega (t_k - T)), which is exact for the linear
    model (`free_amplitude`).

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s].
    angle_rad, rate_rad_s : numpy.ndarray
        Angles [rad] and rates [rad/s], shape (modes, samples).
    move_duration_s : float
        Move duration T [s].
    model : SloshModel
        The model (frequencies and damping of the modes).

    Returns
    -------
    numpy.ndarray
        Residual amplitude per mode [rad].

    Examples
    --------
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> t = np.arange(3) * 0.1
    >>> residual_from_state(t, np.zeros((3, 3)), np.zeros((3, 3)), 0.1, model).tolist()
    [0.0, 0.0, 0.0]
    """
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
