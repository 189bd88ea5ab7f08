"""Monotone in the limits: looser limits never give ``optimal`` a longer plan (issue #25).

On a short corner path (0.15 m, a 90 deg clothoid corner, 0.12 m, turning 90 deg about z) with
the measured series' vial, at a 10 ms export period. The planner is a local sequential
program, so this is checked, not guaranteed: hypothesis found a pair of limits where the looser
one's plan was 6 % longer with the cone programs that the spline transcription replaced
(1.20 s at 6 mm and 10 m/s^2, 1.27 s at 6.78 mm and 20 m/s^2); the test keeps that pair as
its first example. Derandomised, so that CI runs the same examples every time.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.geometry import path_from_waypoints
from sloshkit.plan.path.optimal import plan_optimal
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.plan.path.result import verify

MODEL = equivalent_model(
    UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
)
PATH = path_from_waypoints(
    [[0, 0, 0], [0.15, 0, 0], [0.15, 0.12, 0]], yaw_rad=[0.0, 0.0, math.pi / 2]
)
PERIOD_S = 0.01


def _duration(height_m: float, acceleration_m_s2: float) -> float:
    problem = PathProblem(
        PATH,
        CartesianLimits(2.0, acceleration_m_s2, 10.0 * acceleration_m_s2),
        SpatialSloshLimits(height_m, 0.001),
        MODEL,
        sample_period_s=PERIOD_S,
    )
    found = plan_optimal(problem, verify)
    assert found.feasible, found.message
    return float(found.duration_s)


@pytest.mark.slow
@settings(
    max_examples=3, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)
@given(
    height_mm=st.floats(6.0, 12.0),
    looser_height=st.floats(1.0, 1.4),
    acceleration=st.sampled_from([5.0, 10.0]),
    looser_acceleration=st.sampled_from([1.0, 1.5, 2.0]),
)
# found by hypothesis: 6 mm at 10 m/s^2 gives 1.20 s, 6.78 mm at 20 m/s^2 gives 1.27 s
@example(height_mm=6.0, looser_height=1.13, acceleration=10.0, looser_acceleration=2.0)
def test_looser_limits_never_give_a_longer_optimal_plan(
    height_mm: float, looser_height: float, acceleration: float, looser_acceleration: float
) -> None:
    """Each plan verified with the nonlinear 3-D model; the looser one (wall height and
    acceleration, with the jerk ten times it) no longer than the tighter."""
    tight = _duration(height_mm * 1e-3, acceleration)
    loose = _duration(height_mm * looser_height * 1e-3, acceleration * looser_acceleration)
    assert loose <= tight + 1e-9
