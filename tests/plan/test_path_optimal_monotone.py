"""Monotone in the limits: looser limits never give the programs of ``retime`` a longer plan
(issue #25; `sloshkit.plan.path.optimal.plan_programs`, upright).

On a short corner path (0.15 m, a 90 deg clothoid corner, 0.12 m, turning 90 deg about z) with
the measured series' vial, at a 10 ms export period. The planner is a local sequential
program, so this is checked, not guaranteed: hypothesis found a pair of limits where the looser
one's plan was 6 % longer with the cone programs that the spline transcription replaced
(1.20 s at 6 mm and 10 m/s^2, 1.27 s at 6.78 mm and 20 m/s^2); the test keeps that pair as
its first example. Derandomised, so that CI runs the same examples every time. The measured
TRD_2D turn under issue #25's limits keeps the largest failure the benchmark found (a height
limit 1 % looser gave a plan 131 % longer).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from sloshkit.io.poses import read_pose_file
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.geometry import path_from_poses, path_from_waypoints
from sloshkit.plan.path.minimum_time import TOLERANCE
from sloshkit.plan.path.optimal import plan_programs
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.plan.path.result import verify

MODEL = equivalent_model(
    UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
)
PATH = path_from_waypoints(
    [[0, 0, 0], [0.15, 0, 0], [0.15, 0.12, 0]], yaw_rad=[0.0, 0.0, math.pi / 2]
)
PERIOD_S = 0.01


def _duration(height_m: float, acceleration_m_s2: float, angle_deg: float | None = None) -> float:
    problem = PathProblem(
        PATH,
        CartesianLimits(2.0, acceleration_m_s2, 10.0 * acceleration_m_s2),
        SpatialSloshLimits(height_m, 0.001, None if angle_deg is None else math.radians(angle_deg)),
        MODEL,
        sample_period_s=PERIOD_S,
    )
    found = plan_programs(problem, verify)[0]
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


@pytest.mark.slow
def test_a_looser_surface_angle_never_gives_a_longer_plan() -> None:
    """The surface-angle limit is a limit of the programs like the heights: under 15 mm (a
    21 deg slope on this vial) the plans under 8, 11 and 14 deg get no longer, and each
    meets its angle (`plan_programs` returns only verified plans)."""
    durations = [_duration(0.015, 10.0, angle) for angle in (8.0, 11.0, 14.0)]
    assert durations[0] >= durations[1] >= durations[2]
    assert durations[0] > _duration(0.015, 10.0)  # the angle binds


TRD_POSES = Path(__file__).parents[1] / "data" / "measured-3d" / "poses"


@pytest.mark.slow
def test_a_one_percent_looser_height_limit_does_not_double_the_measured_turns_plan() -> None:
    """The measured TRD_2D path (0.3 m arc and a 270 deg turn) under issue #25's limits: under
    15.15 mm instead of 15 mm the first duration's programs end at twice the limits, and the
    longer durations used to start from those splines stretched, which made them worse,
    until the search fell back to the shaped start and ended at 4.832 s instead of 2.088 s.
    Each longer duration that the carried splines miss is now tried from the start
    stretched to it (`sloshkit.plan.path.minimum_time.shortest`); the looser plan may differ
    from the tighter one only by the search's bracket (`TOLERANCE` of N)."""
    trajectory = read_pose_file(TRD_POSES / "TRD_2D_0.3m_2.4s_270deg.csv")
    path = path_from_poses(trajectory.position_m, trajectory.quaternion_xyzw)

    def duration(height_m: float) -> float:
        problem = PathProblem(
            path,
            CartesianLimits(2.0, 10.0, 100.0, None, None),
            SpatialSloshLimits(height_m, 0.002),
            MODEL,
            sample_period_s=4e-3,
        )
        found = plan_programs(problem, verify)[0]
        assert found.feasible, found.message
        return float(found.duration_s)

    tight, loose = duration(0.015), duration(0.01515)
    assert loose <= tight * (1.0 + TOLERANCE) + 1e-9
    assert tight < 2.2
