"""The ``tilt`` method (`sloshkit.plan.path.planner.plan_tilt`): the programs with the tilt
free, floored by the tilted and upright families."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sloshkit.model.modal import SloshModel
from sloshkit.plan.path.geometry import path_from_waypoints
from sloshkit.plan.path.planner import plan_path
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.plan.path.search import upright_family
from sloshkit.plan.path.tilt import tilted_family
from sloshkit.plan.path.tilt_compensation import peak_tilt_rad
from tests.plan.plan_checks import assert_export_meets_limits


@pytest.mark.slow
def test_tilt_is_never_slower_than_retime_or_the_families_and_meets_its_limits(
    robot_vial: SloshModel,
) -> None:
    """On a bend, ``tilt`` is no slower than ``retime`` and than either family's verified
    member, its compute includes the families', and its export, simulated again with the
    nonlinear 3-D model, meets the slosh, Cartesian and tilt limits and ends on the path's
    end."""
    path = path_from_waypoints([[0, 0, 0], [0.25, 0, 0], [0.25, 0.15, 0]], blend_radius_m=0.04)
    machine = CartesianLimits(1.5, 8.0, 80.0)
    problem = PathProblem(
        path,
        machine,
        SpatialSloshLimits(0.008, 0.0015),
        robot_vial,
        sample_period_s=0.01,
        max_tilt_rad=math.radians(20.0),
    )
    result = plan_path(problem, "auto", tilt=True)
    found = {c.method: c for c in result.candidates}
    tilt, retime = found["tilt"], found["retime"]
    assert tilt.feasible and retime.feasible
    assert tilt.duration_s <= retime.duration_s
    tilted, upright = tilted_family(problem), upright_family(problem)
    assert tilted.feasible and upright.feasible
    assert tilt.duration_s <= min(tilted.duration_s, upright.duration_s)
    assert result.chosen is not None and result.chosen.duration_s <= tilt.duration_s
    poses = tilt.poses
    assert poses is not None
    assert_export_meets_limits(robot_vial, poses, 0.008, 0.0015, machine)
    assert peak_tilt_rad(poses) <= math.radians(20.0) * (1 + 1e-6)
    assert np.allclose(poses.position_m[-1], [0.25, 0.15, 0.0], atol=1e-6)
