"""Richardson extrapolation and the grid convergence index (GCI) of a CFD quantity.

Used for the CFD damping ratio of the seed vial (``studies/cfd-damping/cfd_damping_analysis.py``):
first in the time step on each mesh, then in the mesh on the step-free values. The procedure
is that of Celik et al. (2008) for three solutions with refinement ratios that need not be
equal; with two solutions (or an order that is assumed rather than observed) Roache's safety
factor 3 replaces 1.25. When the error has two leading terms of different orders (interFoam's
damping in the time step: a sqrt(dt) and a dt term), the observed order drifts with the
spacing and `fit_error_terms` fits both terms instead (generalised Richardson extrapolation).

References
----------
P. J. Roache, *Verification and Validation in Computational Science and Engineering*,
Hermosa (1998), ch. 5; P. J. Roache, "Perspective: a method for uniform reporting of grid
refinement studies", J. Fluids Eng. 116 (1994) 405-413, doi:10.1115/1.2910291; I. B. Celik et
al., "Procedure for estimation and reporting of uncertainty due to discretization in CFD
applications", J. Fluids Eng. 130 (2008) 078001, doi:10.1115/1.2960953.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sloshkit.errors import InputError

#: Roache's safety factors: three solutions with an observed order, and otherwise.
SAFETY_OBSERVED = 1.25
SAFETY_ASSUMED = 3.0


@dataclass(frozen=True)
class Convergence:
    """A Richardson extrapolation with its uncertainty.

    Parameters
    ----------
    values : tuple of float
        The solutions, finest first.
    ratios : tuple of float
        Refinement ratios between neighbours, h_coarse / h_fine (finest pair first).
    order : float
        The order of accuracy used for the extrapolation.
    observed : bool
        Whether ``order`` was observed from three solutions (else assumed).
    behaviour : str
        ``monotonic``, ``oscillatory`` or ``two-level``.
    extrapolated : float
        The Richardson estimate of the zero-spacing value.
    uncertainty : float
        GCI of the finest solution in absolute terms: the converged value is expected in
        ``values[0] +- uncertainty`` (and ``extrapolated`` lies in that band).
    safety_factor : float
        The factor used (`SAFETY_OBSERVED` or `SAFETY_ASSUMED`).

    Returns
    -------
    Convergence

    Examples
    --------
    >>> study = richardson([1.01, 1.04, 1.16], [2.0, 2.0])
    >>> round(study.order, 3), round(study.extrapolated, 4), study.behaviour
    (2.0, 1.0, 'monotonic')
    """

    values: tuple[float, ...]
    ratios: tuple[float, ...]
    order: float
    observed: bool
    behaviour: str
    extrapolated: float
    uncertainty: float
    safety_factor: float

    @property
    def interval(self) -> tuple[float, float]:
        """``values[0] -+ uncertainty``: where the converged value is expected."""
        return (self.values[0] - self.uncertainty, self.values[0] + self.uncertainty)

    def to_dict(self) -> dict[str, object]:
        """JSON-ready form (SI as given).

        Returns
        -------
        dict

        Examples
        --------
        >>> sorted(richardson([1.0, 1.1], [2.0], order=1.0).to_dict())[:3]
        ['behaviour', 'extrapolated', 'interval']
        """
        return {
            "values": list(self.values),
            "ratios": list(self.ratios),
            "order": self.order,
            "order_observed": self.observed,
            "behaviour": self.behaviour,
            "extrapolated": self.extrapolated,
            "uncertainty": self.uncertainty,
            "interval": list(self.interval),
            "safety_factor": self.safety_factor,
        }


def observed_order(values: Sequence[float], ratios: Sequence[float]) -> float:
    """Observed order of accuracy from three solutions (Celik et al. 2008, eqs. 3-4).

    Solves p = |ln|e32/e21| + q(p)| / ln r21 with q(p) = ln((r21^p - s)/(r32^p - s)),
    s = sign(e32/e21), by fixed-point iteration (q = 0 for equal ratios).

    Parameters
    ----------
    values : sequence of float
        f1 (finest), f2, f3.
    ratios : sequence of float
        r21 = h2/h1 and r32 = h3/h2 (both > 1).

    Returns
    -------
    float
        The order p (nan when two solutions coincide).

    References
    ----------
    Celik et al., J. Fluids Eng. 130 (2008) 078001, doi:10.1115/1.2960953.

    Examples
    --------
    >>> round(observed_order([1.01, 1.04, 1.16], [2.0, 2.0]), 6)
    2.0
    >>> round(observed_order([1.1, 1.13, 1.182], [1.3, 1.4]), 6)  # f = 1 + 0.1 h, unequal ratios
    1.0
    """
    f1, f2, f3 = (float(v) for v in values)
    r21, r32 = (float(r) for r in ratios)
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0.0 or e32 == 0.0:
        return math.nan
    s = math.copysign(1.0, e32 / e21)
    order = abs(math.log(abs(e32 / e21))) / math.log(r21)
    for _ in range(200):
        q = math.log(abs((r21**order - s) / (r32**order - s)))
        updated = abs(math.log(abs(e32 / e21)) + q) / math.log(r21)
        if abs(updated - order) < 1e-12:
            return updated
        order = updated
    return order


def richardson(
    values: Sequence[float],
    ratios: Sequence[float],
    order: float | None = None,
    *,
    min_order: float = 0.5,
    max_order: float = 4.0,
) -> Convergence:
    """Richardson extrapolation of two or three solutions and the GCI of the finest.

    With three monotonic solutions the order is observed (`observed_order`) and the safety
    factor is 1.25; an observed order outside [``min_order``, ``max_order``] is replaced by the
    nearer bound and counts as assumed. With two solutions, or when ``order`` is given, the
    order is assumed and the factor is 3. Three oscillatory
    solutions (the differences change sign) have no Richardson estimate: the uncertainty is
    then the safety factor 3 times half their range, about the finest value.

    Parameters
    ----------
    values : sequence of float
        Solutions, finest first (2 or 3).
    ratios : sequence of float
        Refinement ratios h_coarse / h_fine of each neighbouring pair, finest pair first.
    order : float, optional
        The order to assume (e.g. 1 for Euler in time); observed when None.
    min_order, max_order : float
        Bounds on an observed order (Celik et al. advise against extrapolating with an
        implausible one).

    Returns
    -------
    Convergence

    Raises
    ------
    InputError
        Fewer than two solutions, or ratios not above 1.

    References
    ----------
    Roache, J. Fluids Eng. 116 (1994) 405, doi:10.1115/1.2910291; Celik et al., J. Fluids
    Eng. 130 (2008) 078001, doi:10.1115/1.2960953.

    Examples
    --------
    First order in the step: 0.0074 at 2 ms and 0.0061 at 1 ms extrapolate to 0.0048.

    >>> study = richardson([0.0061, 0.0074], [2.0], order=1.0)
    >>> round(study.extrapolated, 4), round(study.uncertainty, 4), study.safety_factor
    (0.0048, 0.0039, 3.0)
    """
    f = [float(v) for v in values]
    r = [float(x) for x in ratios]
    if len(f) not in (2, 3) or len(r) != len(f) - 1:
        raise InputError("values", len(f), "must be 2 or 3 solutions with one ratio per pair")
    if any(not x > 1.0 for x in r):
        raise InputError("ratios", r, "must all be above 1 (coarse / fine spacing)")
    behaviour = "two-level"
    observed = False
    p = order
    if len(f) == 3:
        e21, e32 = f[1] - f[0], f[2] - f[1]
        behaviour = "monotonic" if e21 * e32 > 0 else "oscillatory"
        if behaviour == "oscillatory":
            spread = 0.5 * (max(f) - min(f))
            return Convergence(
                tuple(f),
                tuple(r),
                math.nan if p is None else p,
                False,
                behaviour,
                f[0],
                SAFETY_ASSUMED * spread,
                SAFETY_ASSUMED,
            )
        if p is None:
            measured = observed_order(f, r)
            p = min(max(measured, min_order), max_order)
            # An order outside the plausible range is not credible: treat it as assumed.
            observed = min_order <= measured <= max_order
    if p is None:
        raise InputError("order", None, "must be given for two solutions")
    safety = SAFETY_OBSERVED if observed else SAFETY_ASSUMED
    factor = r[0] ** p - 1.0
    extrapolated = f[0] + (f[0] - f[1]) / factor
    uncertainty = safety * abs(f[0] - f[1]) / factor
    return Convergence(
        tuple(f), tuple(r), float(p), observed, behaviour, extrapolated, uncertainty, safety
    )


def combined_uncertainty(*parts: float) -> float:
    """Root-sum-square of independent uncertainties (mesh and time step).

    Parameters
    ----------
    *parts : float
        The uncertainties.

    Returns
    -------
    float

    References
    ----------
    JCGM 100:2008 (GUM), §5.1.2, uncorrelated input quantities.

    Examples
    --------
    >>> combined_uncertainty(3.0, 4.0)
    5.0
    """
    return math.sqrt(sum(float(x) ** 2 for x in parts))


@dataclass(frozen=True)
class TermFit:
    """A generalised Richardson extrapolation: f(h) = f0 + sum_k a_k h**p_k fitted by least
    squares to solutions at several spacings.

    Parameters
    ----------
    extrapolated : float
        f0, the zero-spacing value.
    exponents : tuple of float
        The exponents p_k of the error terms (assumed, e.g. 1/2 and 1).
    coefficients : tuple of float
        The fitted a_k.
    residual_rms : float
        Root-mean-square misfit of the solutions (0 when as many solutions as unknowns).
    spacings : tuple of float
        The spacings h used.

    Returns
    -------
    TermFit

    Examples
    --------
    >>> fit = fit_error_terms([1.5, 1.25, 1.125], [1.0, 0.5, 0.25], (1.0,))
    >>> round(fit.extrapolated, 6), round(fit.residual_rms, 9)
    (1.0, 0.0)
    """

    extrapolated: float
    exponents: tuple[float, ...]
    coefficients: tuple[float, ...]
    residual_rms: float
    spacings: tuple[float, ...]

    def predict(self, spacing: float) -> float:
        """The fitted f at ``spacing``.

        Parameters
        ----------
        spacing : float
            h (same units as the fit's spacings).

        Returns
        -------
        float

        Examples
        --------
        >>> round(fit_error_terms([1.5, 1.25, 1.125], [1.0, 0.5, 0.25], (1.0,)).predict(0.125), 9)
        1.0625
        """
        terms = (
            a * float(spacing) ** p for a, p in zip(self.coefficients, self.exponents, strict=True)
        )
        return float(self.extrapolated + sum(terms))


def fit_error_terms(
    values: Sequence[float], spacings: Sequence[float], exponents: Sequence[float]
) -> TermFit:
    """Generalised Richardson extrapolation with assumed exponents: least-squares fit of
    f(h) = f0 + sum_k a_k h**p_k.

    For a quantity whose error has two leading terms of different orders (so that the
    observed order of three solutions drifts with h), a single-term Richardson extrapolation
    is biased; fitting both terms with their exponents recovers f0 (Richards 1997; Roache
    1998, ch. 5, "generalized Richardson extrapolation"). With more solutions than unknowns
    the residual tests the assumed form.

    Parameters
    ----------
    values : sequence of float
        The solutions.
    spacings : sequence of float
        Their spacings h (> 0), any order.
    exponents : sequence of float
        The exponents p_k (> 0, distinct).

    Returns
    -------
    TermFit

    Raises
    ------
    InputError
        Fewer solutions than unknowns, or non-positive spacings or exponents.

    References
    ----------
    S. A. Richards, "Completed Richardson extrapolation in space and time", Commun. Numer.
    Methods Eng. 13 (1997) 573-582,
    doi:10.1002/(SICI)1099-0887(199707)13:7<573::AID-CNM84>3.0.CO;2-6;
    P. J. Roache, *Verification and Validation in Computational Science and Engineering*,
    Hermosa (1998), ch. 5.

    Examples
    --------
    f = 2 + 3 sqrt(h) - h at four spacings:

    >>> h = [2.0, 1.0, 0.5, 0.25]
    >>> f = [2 + 3 * x**0.5 - x for x in h]
    >>> round(fit_error_terms(f, h, (0.5, 1.0)).extrapolated, 9)
    2.0
    """
    f = np.asarray(values, dtype=float)
    h = np.asarray(spacings, dtype=float)
    p = tuple(float(x) for x in exponents)
    if f.size != h.size or f.size < len(p) + 1:
        raise InputError(
            "values", f.size, f"must be at least {len(p) + 1} solutions, one per spacing"
        )
    if np.any(h <= 0.0) or any(x <= 0.0 for x in p) or len(set(p)) != len(p):
        raise InputError("spacings", list(h), "must be positive, with distinct positive exponents")
    matrix = np.column_stack([np.ones_like(h), *(h**x for x in p)])
    solution, *_ = np.linalg.lstsq(matrix, f, rcond=None)
    residual = f - matrix @ solution
    return TermFit(
        float(solution[0]),
        p,
        tuple(float(a) for a in solution[1:]),
        float(np.sqrt(np.mean(residual**2))),
        tuple(float(x) for x in h),
    )
