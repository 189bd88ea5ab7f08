"""A check and a problem shared by the 3-D path-planning tests (the vial is `robot_vial` of
tests/conftest.py)."""

from __future__ import annotations

import warnings

from sloshkit.errors import ValidityWarning
from sloshkit.model.modal import SloshModel
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.limits import kinematics
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.sim.spatial import simulate_spatial


def assert_export_meets_limits(
    model: SloshModel,
    poses: PoseTrajectory | None,
    peak_m: float,
    residual_m: float,
    machine: CartesianLimits | None = None,
) -> None:
    """A plan's sampled export, simulated again with the nonlinear 3-D model, keeps the slosh
    limits (and, given ``machine``, the Cartesian speed, acceleration and jerk limits)."""
    assert poses is not None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(model, poses, nonlinear=True, cutoff_hz=None)
    assert response.peak_slosh_height_m <= peak_m
    assert response.residual_slosh_height_m <= residual_m
    if machine is not None:
        peaks = kinematics(poses)
        assert peaks["velocity"] <= machine.max_velocity_m_s * (1 + 1e-6)
        assert peaks["acceleration"] <= machine.max_acceleration_m_s2 * (1 + 1e-6)
        assert peaks["jerk"] <= machine.max_jerk_m_s3 * (1 + 1e-6)


def straight_problem() -> PathProblem:
    """0.3 m straight, the measured series' vial (R 49 mm, 80 mm of water), 10 mm / 2 mm,
    2 m/s, 10 m/s^2, 100 m/s^3, 10 ms (the planner's docstring examples' problem)."""
    import numpy as np

    from sloshkit.model.geometry import UprightCylinder
    from sloshkit.model.liquids import get_liquid
    from sloshkit.model.modal import equivalent_model
    from sloshkit.plan.path.geometry import path_from_waypoints

    model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    path = path_from_waypoints(np.array([[0.0, 0.0, 0.0], [0.3, 0.0, 0.0]]))
    limits, slosh = CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002)
    return PathProblem(path, limits, slosh, model, sample_period_s=0.01)
