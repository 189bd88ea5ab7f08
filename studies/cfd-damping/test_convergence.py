"""Richardson/GCI on manufactured data, and the generalised Richardson extrapolation with
assumed exponents (convergence.py).

Run: PYTHONPATH=src python -m pytest studies/cfd-damping/test_convergence.py
studies/cfd-damping/convergence.py
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from convergence import combined_uncertainty, fit_error_terms, observed_order, richardson

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


@pytest.mark.parametrize("order", [1.0, 2.0])
def test_richardson_recovers_a_manufactured_solution(order):
    h = np.array([1.0, 1.3, 1.3 * 1.4])  # unequal refinement ratios
    exact, c = 0.006, 0.002
    values = exact + c * h**order
    study = richardson(values, [h[1] / h[0], h[2] / h[1]])
    assert study.observed and study.behaviour == "monotonic"
    assert study.order == pytest.approx(order, rel=1e-6)
    assert study.extrapolated == pytest.approx(exact, abs=1e-12)
    low, high = study.interval
    assert low <= exact <= high
    assert observed_order(values, [1.3, 1.4]) == pytest.approx(order, rel=1e-6)


def test_richardson_two_levels_oscillation_and_bad_input():
    two = richardson([0.0061, 0.0074], [2.0], order=1.0)
    assert two.extrapolated == pytest.approx(0.0048)
    assert two.safety_factor == 3.0 and not two.observed
    wobbly = richardson([0.0050, 0.0060, 0.0040], [1.4, 1.4])
    assert wobbly.behaviour == "oscillatory"
    assert wobbly.uncertainty == pytest.approx(3.0 * 0.0010)
    with pytest.raises(InputError):
        richardson([0.005, 0.006], [0.5], order=1.0)
    with pytest.raises(InputError):
        richardson([0.005, 0.006], [2.0])
    assert combined_uncertainty(3.0, 4.0) == 5.0
