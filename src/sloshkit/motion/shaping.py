"""Input shapers: impulse sequences that cancel the residual vibration of a mode.

A shaped command is the convolution of a motion with impulses A_i at t_i (sum A_i = 1): the
position becomes sum_i A_i s(t - t_i). Convolution with positive impulses of unit sum keeps
the peak velocity, acceleration and jerk at or below those of the unshaped motion, and lengthens
the move by the shaper's duration.

References
----------
- N. C. Singer, W. P. Seering, "Preshaping command inputs to reduce system vibration",
  J. Dyn. Sys., Meas., Control 112 (1990) 76-82 (ZV, ZVD, residual vibration formula).
- W. Singhose, W. Seering, N. Singer, "Residual vibration reduction using vector diagrams to
  generate shaping inputs", J. Mech. Des. 116 (1994) 654-659 (EI shaper).
- W. Singhose, E. Crain, W. Seering, "Convolved and simultaneous two-mode input shapers",
  IEE Proc. Control Theory Appl. 144 (1997) 515-520 (multi-mode by convolution).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sloshkit.errors import InputError, require_in_range, require_positive
from sloshkit.motion.profile import Motion, PiecewisePolynomial

FloatArray = NDArray[np.float64]
SHAPER_NAMES: tuple[str, ...] = ("zv", "zvd", "ei")


@dataclass(frozen=True)
class Shaper:
    """Impulse amplitudes (sum 1) and times [s] (first at 0).

    Parameters
    ----------
    name : str
        The shaper's name.
    amplitudes : numpy.ndarray
        Impulse amplitudes A_i (sum 1).
    times_s : numpy.ndarray
        Impulse times t_i [s], the first at 0.

    References
    ----------
    Singer, N. C., W. P. Seering, Preshaping command inputs to reduce system vibration, J. Dyn.
    Syst. Meas. Control 112 (1990) 76-82, doi:10.1115/1.2894142.

    Examples
    --------
    >>> from sloshkit import zv
    >>> zv(10.0, 0.0).amplitudes.tolist()
    [0.5, 0.5]
    """

    name: str
    amplitudes: FloatArray
    times_s: FloatArray

    @property
    def duration_s(self) -> float:
        """Time of the last impulse [s] (what the shaper adds to a move)."""
        return float(self.times_s[-1])

    def convolve(self, other: Shaper) -> Shaper:
        """The shaper that applies ``self`` then ``other`` (multi-mode shaping)."""
        amplitudes = np.outer(self.amplitudes, other.amplitudes).ravel()
        times = np.add.outer(self.times_s, other.times_s).ravel()
        order = np.argsort(times, kind="stable")
        times, amplitudes = times[order], amplitudes[order]
        merged_t: list[float] = []
        merged_a: list[float] = []
        for t, a in zip(times, amplitudes, strict=True):
            if merged_t and abs(t - merged_t[-1]) < 1e-12:
                merged_a[-1] += a
            else:
                merged_t.append(float(t))
                merged_a.append(float(a))
        return Shaper(f"{self.name}*{other.name}", np.array(merged_a), np.array(merged_t))


#: Largest residual of the extra-insensitive shaper's equations accepted from `_newton`.
NEWTON_TOLERANCE = 1e-10


def _newton(
    equations: Callable[[FloatArray], FloatArray], start: FloatArray, iterations: int = 30
) -> tuple[FloatArray, bool]:
    """A root of a square system by full Newton steps with a central-difference Jacobian
    (Dennis & Schnabel, *Numerical Methods for Unconstrained Optimization and Nonlinear
    Equations*, SIAM (1996) §5.1); (root, converged).

    Newton steps are taken while they reduce the largest residual; the best point is the root
    when that residual is below `NEWTON_TOLERANCE` (the equations' own rounding floor is about
    1e-12). A step that does not reduce a larger residual means the start is too far from the
    root for plain Newton: not converged (the caller falls back to a trust-region solver).
    """
    x = np.asarray(start, dtype=float).copy()
    f = equations(x)
    norm = float(np.max(np.abs(f)))
    for _ in range(iterations):
        jacobian = np.empty((f.size, x.size))
        for column in range(x.size):
            step = 1e-6 * max(abs(x[column]), 1e-3)
            shifted = x.copy()
            shifted[column] += step
            above = equations(shifted)
            shifted[column] -= 2.0 * step
            jacobian[:, column] = (above - equations(shifted)) / (2.0 * step)
        try:
            trial = x + np.linalg.solve(jacobian, -f)
        except np.linalg.LinAlgError:
            break
        trial_f = equations(trial)
        trial_norm = float(np.max(np.abs(trial_f)))
        if not trial_norm < norm:  # also NaN: x is as good as Newton gets
            break
        x, f, norm = trial, trial_f, trial_norm
    return x, norm < NEWTON_TOLERANCE


def _damped_half_period(omega_rad_s: float, damping_ratio: float) -> tuple[float, float]:
    omega = require_positive("omega", omega_rad_s, "rad/s")
    zeta = require_in_range("damping_ratio", damping_ratio, 0.0, 0.99)
    k = math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta**2))
    return math.pi / (omega * math.sqrt(1.0 - zeta**2)), k


def zv(omega_rad_s: float, damping_ratio: float) -> Shaper:
    """Zero-vibration shaper: [1, K]/(1+K) at [0, T_d/2], K = exp(-zeta pi / sqrt(1-zeta^2)).

    Parameters
    ----------
    omega_rad_s : float
        Natural frequency of the mode to cancel [rad/s].
    damping_ratio : float
        Its damping ratio.

    Returns
    -------
    Shaper
        Two impulses.

    References
    ----------
    Singer, N. C., W. P. Seering, Preshaping command inputs to reduce system vibration, J. Dyn.
    Syst. Meas. Control 112 (1990) 76-82, doi:10.1115/1.2894142.

    Examples
    --------
    >>> import math
    >>> from sloshkit import zv
    >>> shaper = zv(2 * math.pi, 0.0)
    >>> shaper.times_s.tolist()
    [0.0, 0.5]
    """
    half, k = _damped_half_period(omega_rad_s, damping_ratio)
    return Shaper("zv", np.array([1.0, k]) / (1.0 + k), np.array([0.0, half]))


def zvd(omega_rad_s: float, damping_ratio: float) -> Shaper:
    """Zero-vibration-and-derivative shaper: [1, 2K, K^2]/(1+K)^2 at [0, T_d/2, T_d].

    Parameters
    ----------
    omega_rad_s : float
        Natural frequency of the mode to cancel [rad/s].
    damping_ratio : float
        Its damping ratio.

    Returns
    -------
    Shaper
        Three impulses.

    References
    ----------
    Singer, N. C., W. P. Seering, Preshaping command inputs to reduce system vibration, J. Dyn.
    Syst. Meas. Control 112 (1990) 76-82, doi:10.1115/1.2894142.

    Examples
    --------
    >>> import math
    >>> from sloshkit import zvd
    >>> zvd(2 * math.pi, 0.0).amplitudes.tolist()
    [0.25, 0.5, 0.25]
    """
    half, k = _damped_half_period(omega_rad_s, damping_ratio)
    return Shaper(
        "zvd", np.array([1.0, 2.0 * k, k * k]) / (1.0 + k) ** 2, np.array([0.0, half, 2 * half])
    )


def ei(omega_rad_s: float, damping_ratio: float, tolerance: float = 0.05) -> Shaper:
    """Extra-insensitive shaper: residual vibration ``tolerance`` (V) at the design frequency.

    The residual vibration has zero slope at the design frequency (a hump) and is zero at two
    frequencies on either side, which widens the insensitive band. Undamped, the closed form is
    [(1+V)/4, (1-V)/2, (1+V)/4] at [0, T/2, T]. With damping the three amplitudes, the two later
    impulse times and the two zero frequencies are solved together (seven equations: unit sum, V
    and dV/domega at the design frequency, real and imaginary parts of the vibration vector at
    each zero), started from the undamped solution.

    Parameters
    ----------
    omega_rad_s : float
        Design frequency [rad/s].
    damping_ratio : float
        Damping ratio of the mode.
    tolerance : float
        Residual vibration V at the design frequency (1e-4 .. 0.5).

    Returns
    -------
    Shaper
        Three impulses.

    References
    ----------
    Singhose, W., W. Seering, N. Singer, Residual vibration reduction using vector diagrams to
    generate shaped inputs, J. Mech. Des. 116 (1994) 654-659, doi:10.1115/1.2919428.

    Examples
    --------
    >>> import math
    >>> from sloshkit import ei
    >>> [round(float(a), 4) for a in ei(2 * math.pi, 0.0).amplitudes]
    [0.2625, 0.475, 0.2625]
    """
    _, _ = _damped_half_period(omega_rad_s, damping_ratio)
    vtol = require_in_range("tolerance", tolerance, 1e-4, 0.5)
    period = 2.0 * math.pi / omega_rad_s
    amplitudes0 = np.array([(1 + vtol) / 4, (1 - vtol) / 2, (1 + vtol) / 4])
    if damping_ratio == 0.0:
        return Shaper("ei", amplitudes0, np.array([0.0, period / 2, period]))
    zero_ratio = math.acos(-(1 - vtol) / (1 + vtol)) / math.pi

    def vector(amplitudes: FloatArray, times: FloatArray, omega: float) -> complex:
        damped = omega * math.sqrt(1.0 - damping_ratio**2)
        weights = amplitudes * np.exp(damping_ratio * omega * (times - times[-1]))
        return complex(np.sum(weights * np.exp(1j * damped * times)))

    def equations(unknowns: FloatArray) -> FloatArray:
        a1, a2, a3, t2, t3, low, high = unknowns
        amplitudes = np.array([a1, a2, a3])
        times = np.array([0.0, t2, t3])
        shaper = Shaper("ei", amplitudes, times)
        step = 1e-5 * omega_rad_s
        slope = (
            residual_vibration(shaper, omega_rad_s + step, damping_ratio)
            - residual_vibration(shaper, omega_rad_s - step, damping_ratio)
        ) / (2 * step)
        zero_low = vector(amplitudes, times, low * omega_rad_s)
        zero_high = vector(amplitudes, times, high * omega_rad_s)
        return np.array(
            [
                a1 + a2 + a3 - 1.0,
                float(residual_vibration(shaper, omega_rad_s, damping_ratio)) - vtol,
                float(slope) * omega_rad_s,
                zero_low.real,
                zero_low.imag,
                zero_high.real,
                zero_high.imag,
            ]
        )

    start = np.array([*amplitudes0, period / 2, period, zero_ratio, 2.0 - zero_ratio])
    unknowns, converged = _newton(equations, start)
    if not converged or min(unknowns[:3]) <= 0:
        # The trust region of scipy.optimize (slow to import) where plain Newton fails.
        from scipy.optimize import least_squares

        solution = least_squares(equations, start, xtol=1e-15, ftol=1e-15, gtol=1e-15)
        unknowns, converged = solution.x, bool(solution.success)
    a1, a2, a3, t2, t3, _, _ = unknowns
    if not converged or np.max(np.abs(equations(unknowns))) > 1e-8 or min(a1, a2, a3) <= 0:
        raise InputError(
            "damping_ratio", damping_ratio, "no extra-insensitive shaper found; use zv or zvd"
        )
    amplitudes = np.array([a1, a2, a3])
    return Shaper("ei", amplitudes / amplitudes.sum(), np.array([0.0, t2, t3]))


def make_shaper(name: str, omega_rad_s: float, damping_ratio: float) -> Shaper:
    """A shaper by name: ``zv``, ``zvd`` or ``ei``.

    Parameters
    ----------
    name : str
        zv, zvd or ei.
    omega_rad_s : float
        The mode's natural frequency [rad/s].
    damping_ratio : float
        Its damping ratio.

    Returns
    -------
    Shaper

    References
    ----------
    Singer, N. C. and Seering, W. P., Preshaping command inputs to reduce system vibration,
    J. Dyn. Sys., Meas., Control 112 (1990) 76, doi:10.1115/1.2894142.

    Examples
    --------
    A ZV shaper's second impulse comes half a damped period later:

    >>> import math
    >>> shaper = make_shaper("zv", 2 * math.pi, 0.0)
    >>> shaper.times_s.tolist(), shaper.amplitudes.tolist()
    ([0.0, 0.5], [0.5, 0.5])
    """
    if name == "zv":
        return zv(omega_rad_s, damping_ratio)
    if name == "zvd":
        return zvd(omega_rad_s, damping_ratio)
    if name == "ei":
        return ei(omega_rad_s, damping_ratio)
    raise InputError("shaper", name, "must be one of " + ", ".join(SHAPER_NAMES))


def residual_vibration(shaper: Shaper, omega_rad_s: ArrayLike, damping_ratio: float) -> FloatArray:
    """Percentage residual vibration V (0..1) of a mode after the impulses, relative to a
    single unit impulse (Singer & Seering 1990 eq. 4):
    V = exp(-zeta w t_N) sqrt((sum A_i e^{zeta w t_i} cos w_d t_i)^2 + (... sin ...)^2).

    Parameters
    ----------
    shaper : Shaper
        The impulses.
    omega_rad_s : array_like
        Natural frequencies of the mode [rad/s].
    damping_ratio : float
        Its damping ratio.

    Returns
    -------
    numpy.ndarray
        V for each frequency.

    References
    ----------
    Singer, N. C. and Seering, W. P., J. Dyn. Sys., Meas., Control 112 (1990) 76,
    doi:10.1115/1.2894142.

    Examples
    --------
    Zero at the design frequency; a ZVD shaper is more robust to a 20 % error than a ZV:

    >>> residual_vibration(zv(30.0, 0.02), [30.0, 36.0], 0.02).round(3).tolist()
    [0.0, 0.297]
    >>> residual_vibration(zvd(30.0, 0.02), [36.0], 0.02).round(3).tolist()
    [0.089]
    """
    omega = np.asarray(omega_rad_s, dtype=float)[..., None]
    damped = omega * math.sqrt(1.0 - damping_ratio**2)
    t = shaper.times_s
    weight = shaper.amplitudes * np.exp(damping_ratio * omega * t)
    cosine = np.sum(weight * np.cos(damped * t), axis=-1)
    sine = np.sum(weight * np.sin(damped * t), axis=-1)
    tail = np.exp(-damping_ratio * omega[..., 0] * t[-1])
    return np.asarray(tail * np.hypot(cosine, sine), dtype=float)


def shape_motion(motion: Motion, shaper: Shaper) -> Motion:
    """sum_i A_i s(t - t_i) as an exact piecewise polynomial (duration T + t_N).

    Each piece of the result is re-expanded from the pieces of the shifted components, chosen by
    the piece's midpoint (robust to rounding at coinciding breakpoints).

    Parameters
    ----------
    motion : Motion
        The unshaped move.
    shaper : Shaper
        The input shaper.

    Returns
    -------
    Motion
        The shaped move, longer by the shaper's duration.

    References
    ----------
    Singer, N. C., W. P. Seering, Preshaping command inputs to reduce system vibration, J. Dyn.
    Syst. Meas. Control 112 (1990) 76-82, doi:10.1115/1.2894142.

    Examples
    --------
    >>> import math
    >>> from sloshkit import quintic, shape_motion, zv
    >>> shaped = shape_motion(quintic(0.1, 1.0), zv(2 * math.pi, 0.0))
    >>> shaped.duration_s, round(shaped.distance_m, 12)
    (1.5, 0.1)
    """
    pp = motion.position_pp
    end = motion.duration_s
    order = pp.c.shape[0] - 1
    breaks = np.unique(np.concatenate([pp.x + delay for delay in shaper.times_s]))
    breaks = breaks[np.concatenate(([True], np.diff(breaks) > 1e-12))]
    coefficients = np.zeros((order + 1, breaks.size - 1))
    for j in range(breaks.size - 1):
        middle = 0.5 * (breaks[j] + breaks[j + 1])
        for amplitude, delay in zip(shaper.amplitudes, shaper.times_s, strict=True):
            local = middle - delay
            if local <= 0.0:
                continue
            if local >= end:
                coefficients[order, j] += amplitude * motion.distance_m
                continue
            piece = int(
                np.clip(np.searchsorted(pp.x, local, side="right") - 1, 0, pp.c.shape[1] - 1)
            )
            shift = float(breaks[j] - delay - pp.x[piece])
            # Taylor coefficients p^(k)(shift) / k! of the piece: its derivatives term by
            # term, each evaluated by Horner's rule (plain floats: a few terms per piece).
            derivative = [float(c) for c in pp.c[:, piece]]
            for k in range(order + 1):
                value = 0.0
                for c in derivative:
                    value = value * shift + c
                coefficients[order - k, j] += amplitude * value / math.factorial(k)
                top = len(derivative) - 1
                derivative = [c * (top - i) for i, c in enumerate(derivative[:-1])]
    return Motion(f"{motion.name}+{shaper.name}", PiecewisePolynomial(coefficients, breaks))
