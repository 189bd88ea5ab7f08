"""The ``tilt`` method's improvement (`sloshkit.plan.path_tilt`): the local searches of
``retime`` run on the tilted export."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan import path_tilt
from sloshkit.plan.path import path_from_waypoints
from sloshkit.plan.path_limits import kinematics
from sloshkit.plan.path_result import verify
from sloshkit.plan.path_tilt import improved_tilt, plan_tilt
from sloshkit.plan.retime import family_member
from sloshkit.plan.spatial import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.plan.tilt import peak_tilt_rad
from sloshkit.sim.spatial import simulate_spatial


@pytest.fixture(scope="module")
def robot_vial() -> SloshModel:
    """The measured series' cylinder: R = 49 mm, h = 80 mm, water, zeta = 0.0066."""
    return equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )


def test_improved_tilt_is_never_slower_and_meets_its_limits_when_simulated_again(
    robot_vial: SloshModel, monkeypatch: pytest.MonkeyPatch
) -> None:
    """On a bend, the family's tilted plan improved by the searches on the tilted export
    (seeded also from another timing of the path) is no slower than the plain tilted plan,
    and its export, simulated again with the nonlinear 3-D model, meets the slosh, Cartesian
    and tilt limits and ends on the path's end. A small budget keeps the test short."""
    monkeypatch.setattr(path_tilt, "TILT_SAMPLE_BUDGET", 60_000)
    path = path_from_waypoints([[0, 0, 0], [0.25, 0, 0], [0.25, 0.15, 0]], blend_radius_m=0.04)
    problem = PathProblem(
        path,
        CartesianLimits(1.5, 8.0, 80.0),
        SpatialSloshLimits(0.008, 0.0015),
        robot_vial,
        max_tilt_rad=math.radians(20.0),
    )
    family = plan_tilt(problem, verify, improve=False)
    assert family.feasible
    other = family_member(problem, 2.0, None)
    found = improved_tilt(problem, family, [other], verify)
    assert found.feasible and found.method == "tilt"
    assert found.duration_s < family.duration_s  # 1.44 s against 1.89 s when written
    assert found.compute_time_s >= family.compute_time_s
    poses = found.poses
    assert poses is not None
    trajectory = PoseTrajectory(poses.time_s, poses.position_m, poses.quaternion_xyzw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(robot_vial, trajectory, nonlinear=True, cutoff_hz=None)
    assert response.peak_slosh_height_m <= 0.008
    assert response.residual_slosh_height_m <= 0.0015
    peaks = kinematics(poses)
    assert peaks["velocity"] <= 1.5 * (1 + 1e-6)
    assert peaks["acceleration"] <= 8.0 * (1 + 1e-6)
    assert peaks["jerk"] <= 80.0 * (1 + 1e-6)
    assert peak_tilt_rad(poses) <= math.radians(20.0) * (1 + 1e-6)
    assert np.allclose(poses.position_m[-1], [0.25, 0.15, 0.0], atol=1e-6)
