"""Generalised Richardson extrapolation with assumed exponents (sloshkit.cfd.convergence)."""

from __future__ import annotations

import math

import pytest

from sloshkit.cfd.convergence import fit_error_terms, richardson
from sloshkit.errors import InputError


def test_two_terms_recover_the_limit_where_one_term_richardson_is_biased() -> None:
    steps = [2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4]
    values = [0.0015 + 0.19 * math.sqrt(h) - 1.3 * h for h in steps]
    fit = fit_error_terms(values, steps, (0.5, 1.0))
    assert fit.extrapolated == pytest.approx(0.0015, abs=1e-12)
    assert fit.coefficients == pytest.approx((0.19, -1.3))
    assert fit.residual_rms < 1e-12
    assert fit.predict(6.25e-5) == pytest.approx(0.0015 + 0.19 * math.sqrt(6.25e-5) - 1.3 * 6.25e-5)
    one_term = richardson(values[-1:-4:-1], [2.0, 2.0])  # finest three
    assert abs(one_term.extrapolated - 0.0015) > 1e-4  # drifting order: single term is off


def test_residual_measures_a_wrong_form_and_bad_input_is_refused() -> None:
    steps = [1.0, 0.5, 0.25, 0.125]
    values = [1.0 + h**2 for h in steps]
    assert fit_error_terms(values, steps, (1.0,)).residual_rms > 1e-3
    with pytest.raises(InputError):
        fit_error_terms([1.0, 2.0], [1.0, 0.5], (0.5, 1.0))
    with pytest.raises(InputError):
        fit_error_terms([1.0, 2.0, 3.0], [1.0, 0.0, 0.5], (1.0,))
