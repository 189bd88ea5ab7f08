"""sloshkit: sloshing of liquids in moving containers.

Model (`equivalent_model`), simulate (`simulate`), sweep (`run_sweep`), plan (`plan`; 3-D
paths: `plan_path`) and calibrate (`calibrate`) the slosh of a liquid in an upright cylinder
moved by a robot or a slide. SI units and radians throughout the Python API.

The names below are the curated public API; they are imported on first use, so
``import sloshkit`` stays cheap.

Examples
--------
>>> import sloshkit as sk
>>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
...                             fill_height_m=0.039)
>>> round(model.modes[0].frequency_hz, 3)
4.72
>>> response = sk.simulate(model, sk.quintic(0.1, 1.0))
>>> response.peak_angle_rad < 0.1
True
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from sloshkit.version import __version__

#: Public name -> module that defines it.
_API: dict[str, str] = {
    # errors
    "InputError": "sloshkit.errors",
    "ValidityWarning": "sloshkit.errors",
    # model
    "UprightCylinder": "sloshkit.model.geometry",
    "Liquid": "sloshkit.model.liquids",
    "LIQUIDS": "sloshkit.model.liquids",
    "get_liquid": "sloshkit.model.liquids",
    "SloshMode": "sloshkit.model.modal",
    "SloshModel": "sloshkit.model.modal",
    "equivalent_model": "sloshkit.model.modal",
    "ProfileContainer": "sloshkit.model.profile",
    "catalogue_container": "sloshkit.model.catalogue",
    "read_profile_file": "sloshkit.io.profiles",
    # motion
    "Motion": "sloshkit.motion.profile",
    "LAW_NAMES": "sloshkit.motion.laws",
    "make_law": "sloshkit.motion.laws",
    "trapezoidal": "sloshkit.motion.laws",
    "cubic": "sloshkit.motion.laws",
    "quintic": "sloshkit.motion.laws",
    "septic": "sloshkit.motion.laws",
    "minimum_jerk": "sloshkit.motion.laws",
    "s_curve": "sloshkit.motion.laws",
    "from_samples": "sloshkit.motion.recorded",
    "Shaper": "sloshkit.motion.shaping",
    "zv": "sloshkit.motion.shaping",
    "zvd": "sloshkit.motion.shaping",
    "ei": "sloshkit.motion.shaping",
    "shape_motion": "sloshkit.motion.shaping",
    "PoseTrajectory": "sloshkit.motion.poses",
    "poses_from_law": "sloshkit.motion.pose_builders",
    # simulation
    "simulate": "sloshkit.sim.simulate",
    "SloshResponse": "sloshkit.sim.response",
    "simulate_spatial": "sloshkit.sim.spatial",
    "SpatialResponse": "sloshkit.sim.spatial_response",
    # sweeps, planning, calibration
    "run_sweep": "sloshkit.sweep",
    "SweepResult": "sloshkit.sweep",
    "plan": "sloshkit",  # the callable package sloshkit.plan (see its docstring)
    "PlanResult": "sloshkit.plan.line.planner",
    "PlanProblem": "sloshkit.plan.line.problem",
    "MachineLimits": "sloshkit.plan.line.problem",
    "SloshLimits": "sloshkit.plan.line.problem",
    "plan_path": "sloshkit.plan.path.planner",
    "PathPlanResult": "sloshkit.plan.path.result",
    "PathProblem": "sloshkit.plan.path.problem",
    "CartesianLimits": "sloshkit.plan.path.problem",
    "SpatialSloshLimits": "sloshkit.plan.path.problem",
    "path_from_waypoints": "sloshkit.plan.path.geometry",
    "path_from_poses": "sloshkit.plan.path.geometry",
    "calibrate": "sloshkit.calibration",
    "CalibrationResult": "sloshkit.calibration",
    # files and controller export
    "export_plan": "sloshkit.export.exporter",
    "read_model_file": "sloshkit.io.models",
    "write_model_file": "sloshkit.io.models",
    "read_pose_file": "sloshkit.io.poses",
}

__all__ = [
    "LAW_NAMES",
    "LIQUIDS",
    "CalibrationResult",
    "CartesianLimits",
    "InputError",
    "Liquid",
    "MachineLimits",
    "Motion",
    "PathPlanResult",
    "PathProblem",
    "PlanProblem",
    "PlanResult",
    "PoseTrajectory",
    "ProfileContainer",
    "Shaper",
    "SloshLimits",
    "SloshMode",
    "SloshModel",
    "SloshResponse",
    "SpatialResponse",
    "SpatialSloshLimits",
    "SweepResult",
    "UprightCylinder",
    "ValidityWarning",
    "__version__",
    "calibrate",
    "catalogue_container",
    "cubic",
    "ei",
    "equivalent_model",
    "export_plan",
    "from_samples",
    "get_liquid",
    "make_law",
    "minimum_jerk",
    "path_from_poses",
    "path_from_waypoints",
    "plan",
    "plan_path",
    "poses_from_law",
    "quintic",
    "read_model_file",
    "read_pose_file",
    "read_profile_file",
    "run_sweep",
    "s_curve",
    "septic",
    "shape_motion",
    "simulate",
    "simulate_spatial",
    "trapezoidal",
    "write_model_file",
    "zv",
    "zvd",
]


def __getattr__(name: str) -> Any:
    """Import a public name from its module on first use (PEP 562)."""
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'sloshkit' has no attribute {name!r}")
    if module == __name__:  # a callable subpackage
        value = importlib.import_module(f"{__name__}.{name}")
    else:
        value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})


if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from sloshkit.calibration import CalibrationResult, calibrate
    from sloshkit.errors import InputError, ValidityWarning
    from sloshkit.export.exporter import export_plan
    from sloshkit.io.models import read_model_file, write_model_file
    from sloshkit.io.poses import read_pose_file
    from sloshkit.io.profiles import read_profile_file
    from sloshkit.model.catalogue import catalogue_container
    from sloshkit.model.geometry import UprightCylinder
    from sloshkit.model.liquids import LIQUIDS, Liquid, get_liquid
    from sloshkit.model.modal import SloshMode, SloshModel, equivalent_model
    from sloshkit.model.profile import ProfileContainer
    from sloshkit.motion.laws import (
        LAW_NAMES,
        cubic,
        make_law,
        minimum_jerk,
        quintic,
        s_curve,
        septic,
        trapezoidal,
    )
    from sloshkit.motion.pose_builders import poses_from_law
    from sloshkit.motion.poses import PoseTrajectory
    from sloshkit.motion.profile import Motion
    from sloshkit.motion.recorded import from_samples
    from sloshkit.motion.shaping import Shaper, ei, shape_motion, zv, zvd
    from sloshkit.plan.line.planner import PlanResult, plan
    from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
    from sloshkit.plan.path.geometry import path_from_poses, path_from_waypoints
    from sloshkit.plan.path.planner import plan_path
    from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    from sloshkit.plan.path.result import PathPlanResult
    from sloshkit.sim.response import SloshResponse
    from sloshkit.sim.simulate import simulate
    from sloshkit.sim.spatial import simulate_spatial
    from sloshkit.sim.spatial_response import SpatialResponse
    from sloshkit.sweep import SweepResult, run_sweep
