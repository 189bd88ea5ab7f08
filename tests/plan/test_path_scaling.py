"""The duration scaling of the path program's limited quantities
(`sloshkit.plan.path.scaling`)."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from sloshkit.plan.path.scaling import EXPONENTS, TIE, binding

NAMES = sorted(EXPONENTS)


@given(
    st.dictionaries(st.sampled_from(NAMES), st.floats(0.1, 10.0), min_size=1),
    st.randoms(use_true_random=False),
)
def test_the_binding_quantity_does_not_depend_on_the_order_of_the_ratios(ratios, random):
    names = list(ratios)
    random.shuffle(names)
    assert binding({name: ratios[name] for name in names}) == binding(ratios)


@given(st.floats(0.5, 2.0), st.floats(-1.0, 1.0))
def test_ties_at_a_min_max_solution_go_to_the_quantity_uniform_scaling_needs_most(top, wobble):
    # a min-max program leaves its active quantities at one ratio, to rounding
    ratios = {
        "joint speed": top,
        "peak slosh": top * (1.0 + 0.1 * TIE * wobble),
        "jerk": top * (1.0 - 0.1 * TIE * wobble),
        "velocity": 0.5 * top,
    }
    # within 1e-12 of 1 the roots r^(1/p) round to the same double: any tied name is right
    expected = "joint speed" if top > 1.0 + 1e-12 else "jerk" if top < 1.0 - 1e-12 else None
    if expected is None:
        assert binding(ratios) in {"joint speed", "peak slosh", "jerk"}
        return
    assert binding(ratios) == expected


def test_a_clear_largest_ratio_binds_whatever_its_order() -> None:
    assert binding({"joint speed": 0.9, "residual slosh": 1.2, "jerk": 1.19}) == "residual slosh"
