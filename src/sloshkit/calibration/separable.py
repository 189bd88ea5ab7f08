"""Statistics of a separable least-squares fit: the shared core of the forced-response
identifications (`sloshkit.calibration.forced`, `sloshkit.calibration.simulated`).

A record y is explained as design(p) c with nonlinear parameters p (omega_n, zeta, a clock
offset) and linear coefficients c (gain, offset, drift) eliminated by variable projection
(Golub & Pereyra, Inverse Problems 19 (2003) R1, doi:10.1088/0266-5611/19/2/201). The 95 %
intervals come from the Gauss-Newton covariance of all parameters at the solution (Ljung,
*System Identification*, 2nd ed. (1999) §9.3); a parameter whose interval is wider than
`UNCONSTRAINED_OMEGA` (omega) or `UNCONSTRAINED_RELATIVE` (zeta, slosh mass, gain) of its value
is not constrained by the record.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]

#: omega_n is unconstrained when its 95 % half-interval exceeds this fraction of it.
UNCONSTRAINED_OMEGA = 0.02
#: zeta and the slosh mass are unconstrained beyond this fraction.
UNCONSTRAINED_RELATIVE = 0.5


@dataclass(frozen=True, eq=False)
class FitStatistics:
    """Linear coefficients, prediction, 95 % half-widths (nonlinear parameters first, then the
    linear ones) and the fit quality of a separable least-squares solution.

    Attributes
    ----------
    coefficients : numpy.ndarray
        The linear coefficients c.
    predicted : numpy.ndarray
        design(p) c.
    half_width : numpy.ndarray
        95 % half-widths: the nonlinear parameters', then the linear ones'.
    r2, nrmse, slosh_r2 : float
        R^2, RMS error over the record's range, and the part of what the nuisance columns
        leave that the first column explains.

    Examples
    --------
    >>> import numpy as np
    >>> fit = FitStatistics(np.array([2.0, 0.5]), np.zeros(3), np.array([0.1, 0.2, 0.3]),
    ...                     0.99, 0.01, 0.98)
    >>> fit.linear_parameters(["gain", "offset"], first=1)
    ({'gain': 2.0, 'offset': 0.5}, {'gain': (1.8, 2.2), 'offset': (0.2, 0.8)})
    """

    coefficients: FloatArray
    predicted: FloatArray
    half_width: FloatArray
    r2: float
    nrmse: float
    slosh_r2: float

    def linear_parameters(
        self, names: list[str] | tuple[str, ...], *, first: int
    ) -> tuple[dict[str, float], dict[str, tuple[float, float]]]:
        """The linear coefficients by name and their 95 % intervals (their half-widths start at
        index ``first`` of `half_width`, after the nonlinear parameters).

        Parameters
        ----------
        names : sequence of str
            Names of the linear coefficients, in the design's column order.
        first : int
            How many nonlinear parameters come first in `half_width`.

        Returns
        -------
        tuple of dict
            {name: value} and {name: (low, high)}.

        Examples
        --------
        >>> import numpy as np
        >>> fit = FitStatistics(np.array([3.0]), np.zeros(2), np.array([0.1, 0.5]), 1.0, 0.0, 1.0)
        >>> fit.linear_parameters(["gain"], first=1)
        ({'gain': 3.0}, {'gain': (2.5, 3.5)})
        """
        values = {name: float(c) for name, c in zip(names, self.coefficients, strict=True)}
        intervals = {
            name: (float(c - h), float(c + h))
            for name, c, h in zip(names, self.coefficients, self.half_width[first:], strict=True)
        }
        return values, intervals


def fit_statistics(
    y: FloatArray, design_at: Callable[[FloatArray], FloatArray], nonlinear: FloatArray
) -> FitStatistics:
    """Statistics of y ~ design(p) c at the solution p = ``nonlinear``.

    The Jacobian of the full model in every parameter (nonlinear ones by central differences,
    linear ones exact) gives the Gauss-Newton covariance s^2 (J^T J)^-1 with s^2 the residual
    variance, and Student-t 95 % half-widths (Ljung, *System Identification* (1999) §9.3).
    ``slosh_r2`` is the fraction of what the nuisance terms (all columns but the first) leave
    that the first column (the slosh response) explains.

    Parameters
    ----------
    y : numpy.ndarray
        The record.
    design_at : callable
        p -> design matrix (columns: the slosh response first, then the nuisance terms).
    nonlinear : numpy.ndarray
        The solution p.

    Returns
    -------
    FitStatistics

    Examples
    --------
    A decay rate k fitted to y = c exp(-k t) + noise: the interval holds the true rate.

    >>> import numpy as np
    >>> t = np.linspace(0.0, 2.0, 200)
    >>> y = 3.0 * np.exp(-1.5 * t) + np.random.default_rng(0).normal(0.0, 0.01, t.size)
    >>> fit = fit_statistics(y, lambda p: np.exp(-p[0] * t)[:, None], np.array([1.5]))
    >>> bool(abs(fit.coefficients[0] - 3.0) < 0.01), bool(fit.half_width[0] < 0.02)
    (True, True)
    >>> round(fit.r2, 3)
    1.0
    """
    design = design_at(nonlinear)
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    predicted = design @ coefficients
    columns = []
    for index, value in enumerate(nonlinear):
        step = 1e-6 * max(abs(float(value)), 1e-3)
        up, down = nonlinear.astype(float), nonlinear.astype(float)
        up[index] += step
        down[index] -= step
        columns.append((design_at(up) @ coefficients - design_at(down) @ coefficients) / (2 * step))
    jacobian = np.column_stack((*columns, design))
    rest = y - predicted
    dof = max(1, y.size - jacobian.shape[1])
    covariance = np.linalg.pinv(jacobian.T @ jacobian) * float(rest @ rest) / dof
    half = float(stats.t.ppf(0.975, dof)) * np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    target = coefficients[0] * design[:, 0] + rest
    return FitStatistics(
        coefficients=np.asarray(coefficients, dtype=float),
        predicted=np.asarray(predicted, dtype=float),
        half_width=np.asarray(half, dtype=float),
        r2=1.0 - float(rest @ rest) / float(np.sum((y - y.mean()) ** 2)),
        nrmse=math.sqrt(float(np.mean(rest**2))) / float(np.ptp(y)),
        slosh_r2=1.0
        - float(rest @ rest) / max(1e-300, float(np.sum((target - target.mean()) ** 2))),
    )


def constraint_flags(
    omega: float,
    zeta: float,
    omega_half: float,
    zeta_half: float,
    scale_name: str,
    scale: float,
    scale_half: float,
    require_constrained: bool,
) -> tuple[dict[str, bool], str]:
    """Which parameters the record constrains (`UNCONSTRAINED_OMEGA`,
    `UNCONSTRAINED_RELATIVE`) and the warning; raises `InputError` when omega_n or zeta is
    loose and ``require_constrained``.

    Parameters
    ----------
    omega, zeta : float
        The solution [rad/s], [-].
    omega_half, zeta_half : float
        Their 95 % half-widths.
    scale_name : str
        Name of the scale parameter (gain or slosh_mass).
    scale, scale_half : float
        Its value and half-width.
    require_constrained : bool
        Raise `InputError` when omega_n or zeta is loose.

    Returns
    -------
    tuple
        ({name: constrained}, warning message or "").

    Examples
    --------
    >>> constraint_flags(20.0, 0.02, 0.1, 0.002, "gain", 1.0, 0.01, True)
    ({'omega_n': True, 'damping_ratio': True, 'gain': True}, '')
    >>> flags, message = constraint_flags(20.0, 0.02, 1.0, 0.05, "gain", 1.0, 0.01, False)
    >>> flags["omega_n"], message.startswith("the record does not constrain omega_n")
    (False, True)
    """
    constrained = {
        "omega_n": bool(omega_half <= UNCONSTRAINED_OMEGA * omega),
        "damping_ratio": bool(zeta_half <= UNCONSTRAINED_RELATIVE * zeta and zeta > 1.1e-4),
        scale_name: bool(scale_half <= UNCONSTRAINED_RELATIVE * abs(scale)),
    }
    loose = [name for name, ok in constrained.items() if not ok]
    if not loose:
        return constrained, ""
    message = (
        f"the record does not constrain {', '.join(loose)} (95 % intervals: omega_n "
        f"{omega - omega_half:.4g}-{omega + omega_half:.4g} rad/s, zeta {zeta - zeta_half:.3g}-"
        f"{zeta + zeta_half:.3g}): the motion barely excites the mode (too slow, or the "
        "record is too short or too noisy)"
    )
    if require_constrained and ("omega_n" in loose or "damping_ratio" in loose):
        raise InputError("record", "unconstrained", message)
    return constrained, message
