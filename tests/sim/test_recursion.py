"""The modal cumulative-sum recursion of `run_recursion` against `scipy.signal.lfilter` of the
same discretisation (the transfer function from ss2tf): an independent evaluation."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.signal import lfilter, ss2tf

from sloshkit.sim.discretisation import run_recursion, velocity_driven_discretisation


def filtered(phi, gamma, g1, u, row):
    selector = np.zeros((1, 2))
    selector[0, row] = 1.0
    b, a = ss2tf(phi, gamma[:, None], selector, np.array([[g1[row]]]))
    return lfilter(b[0], a, u, axis=-1)


@settings(max_examples=40, deadline=None)
@given(
    omega=st.floats(1.0, 300.0),
    zeta=st.one_of(st.just(0.0), st.just(1.0), st.floats(0.0, 2.0)),
    step=st.sampled_from([1e-4, 1e-3, 2e-3, 4e-3, 8e-3]),
    count=st.integers(1, 3000),
)
def test_recursion_equals_the_iir_filter(omega, zeta, step, count):
    phi, gamma, g1 = velocity_driven_discretisation(omega, zeta, 0.01, step)
    u = np.cumsum(np.random.default_rng(count).normal(size=(2, count)), axis=-1)
    first, second = run_recursion(phi, gamma, g1, u)
    for row, ours in enumerate((first, second)):
        reference = filtered(phi, gamma, g1, u, row)
        scale = max(float(np.max(np.abs(reference))), 1e-300)
        assert np.max(np.abs(ours - reference)) <= 1e-9 * scale
        assert ours.shape == u.shape


def test_a_long_lightly_damped_record_keeps_its_precision():
    """200,000 samples at zeta = 0.01: several blocks would be needed only for heavy damping;
    the single block's scaled terms grow by e^(zeta omega T) = e^60 and lose nothing."""
    phi, gamma, g1 = velocity_driven_discretisation(30.0, 0.01, 0.01, 1e-3)
    u = np.sin(np.arange(200_000) * 1e-3 * 29.0)
    first, _ = run_recursion(phi, gamma, g1, u)
    reference = filtered(phi, gamma, g1, u, 0)
    assert np.max(np.abs(first - reference)) <= 1e-10 * np.max(np.abs(reference))
