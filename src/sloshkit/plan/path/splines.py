"""The timing and tilt of a 3-D move as clamped cubic B-splines of normalised time.

s(t) = sum_i c_i B_i(t / T) on uniform knots over the move's duration T = N Ts (de Boor, *A
Practical Guide to Splines* (1978) ch. IX): the first three coefficients 0 and the last three
the path's length S put the move at rest with zero acceleration at both ends, and increasing
coefficients make s monotone (the B-spline's variation diminishing property, de Boor
ch. XI). The tilt's two angles are two more splines of the same basis, zero in their first and
last three coefficients. `SplineTiming.samples` samples them on the export grid; `fit_timing`
fits them to samples of another timing. The path program's variables
(`sloshkit.plan.path.transcription`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import BSpline

from sloshkit.plan.path.samples import PathSamples

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class SplineTiming:
    """The timing (and tilt) as clamped cubic B-splines of normalised time, on N samples.

    Parameters
    ----------
    coefficients_m : numpy.ndarray
        The path parameter's coefficients c_0..c_{K-1} [m]: 0, 0, 0, ..., S, S, S.
    tilt_rad : numpy.ndarray
        The tilt's coefficients (K, 2) [rad]: zero in the first and last three rows.
    steps : int
        N, the export sample periods of the move.

    Examples
    --------
    >>> import numpy as np
    >>> timing = SplineTiming(np.array([0, 0, 0, 0.5, 1, 1, 1.0]), np.zeros((7, 2)), 50)
    >>> timing.count, round(float(timing.path_parameter(np.array([0.5]))[0]), 3)
    (7, 0.5)
    """

    coefficients_m: FloatArray
    tilt_rad: FloatArray
    steps: int

    @property
    def count(self) -> int:
        """K, the number of coefficients of each spline."""
        return int(self.coefficients_m.size)

    def basis(self, tau: FloatArray, derivative: int = 0) -> FloatArray:
        """The B-spline basis (its ``derivative``-th derivative in tau) at ``tau``, (len, K)."""
        return spline_basis(self.count, tau, derivative)

    def path_parameter(self, tau: FloatArray) -> FloatArray:
        """s at normalised times ``tau`` in [0, 1] [m]."""
        return np.asarray(self.basis(tau) @ self.coefficients_m, dtype=float)

    def samples(self, period_s: float) -> PathSamples:
        """The export samples: s and the tilt at k Ts, k = 0..N (s monotone, on [0, S])."""
        tau = np.arange(self.steps + 1) / self.steps
        basis = self.basis(tau)
        length = float(self.coefficients_m[-1])
        s = np.clip(np.maximum.accumulate(basis @ self.coefficients_m), 0.0, length)
        s[-1] = length
        tilt = basis @ self.tilt_rad
        tilt[0] = tilt[-1] = 0.0
        return PathSamples(s, tilt, period_s)

    def on_steps(self, steps: int) -> SplineTiming:
        """The same splines over another number of samples (a uniform time scaling)."""
        return SplineTiming(self.coefficients_m, self.tilt_rad, steps)


def spline_basis(count: int, tau: FloatArray, derivative: int = 0) -> FloatArray:
    """The clamped cubic B-spline basis on uniform knots over [0, 1] (de Boor (1978) ch. IX).

    Parameters
    ----------
    count : int
        The number of basis functions K (at least 4).
    tau : numpy.ndarray
        Normalised times in [0, 1].
    derivative : int
        The order of the derivative in tau (0: the basis itself).

    Returns
    -------
    numpy.ndarray
        (len(tau), K).

    Examples
    --------
    >>> import numpy as np
    >>> basis = spline_basis(6, np.linspace(0.0, 1.0, 5))
    >>> bool(np.allclose(basis.sum(axis=1), 1.0))  # a partition of unity
    True
    """
    knots = np.concatenate(([0.0] * 3, np.linspace(0.0, 1.0, count - 2), [1.0] * 3))
    spline = BSpline(knots, np.eye(count), 3, extrapolate=False)
    if derivative:
        spline = spline.derivative(derivative)
    values = spline(np.clip(np.asarray(tau, dtype=float), 0.0, 1.0))
    basis: FloatArray = np.nan_to_num(np.asarray(values, dtype=float))
    return basis


def fit_timing(
    tau: FloatArray, s_m: FloatArray, count: int, steps: int, tilt_rad: FloatArray | None = None
) -> SplineTiming:
    """The splines of ``count`` coefficients nearest (least squares) to samples of s (and
    the tilt) at normalised times ``tau``, at rest at both ends, s's coefficients monotone.

    Parameters
    ----------
    tau : numpy.ndarray
        Normalised times in [0, 1] of the samples.
    s_m : numpy.ndarray
        The path parameter there [m]; the last is the path's length.
    count : int
        K (at least 7).
    steps : int
        N of the result.
    tilt_rad : numpy.ndarray, optional
        The tilt there (len, 2) [rad].

    Returns
    -------
    SplineTiming

    Examples
    --------
    >>> import numpy as np
    >>> tau = np.linspace(0.0, 1.0, 201)
    >>> timing = fit_timing(tau, tau**3 * (10 - 15 * tau + 6 * tau**2), 12, 100)
    >>> bool(np.max(np.abs(timing.path_parameter(tau) - tau**3 * (10 - 15 * tau + 6 * tau**2)))
    ...      < 1e-3)
    True
    """
    basis = spline_basis(count, tau)
    free = slice(3, count - 3)
    length = float(s_m[-1])
    fixed = np.zeros(count)
    fixed[-3:] = length
    solution = np.linalg.lstsq(basis[:, free], s_m - basis @ fixed, rcond=None)[0]
    coefficients = fixed.copy()
    coefficients[free] = solution
    coefficients = np.clip(np.maximum.accumulate(coefficients), 0.0, length)
    tilt = np.zeros((count, 2))
    if tilt_rad is not None and np.any(tilt_rad):
        tilt[free] = np.linalg.lstsq(basis[:, free], tilt_rad, rcond=None)[0]
    return SplineTiming(coefficients, tilt, steps)


__all__ = ["SplineTiming", "fit_timing", "spline_basis"]
