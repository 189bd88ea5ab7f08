"""The benchmark's independent reference (benchmarks/ocp_reference.py) against exact answers."""

from __future__ import annotations

import dataclasses
import math
import sys
import warnings
from pathlib import Path

import pytest

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.plan.line.planner import plan
from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
from sloshkit.plan.path.geometry import path_from_waypoints
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.sim.spatial import simulate_spatial

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from ocp_reference import reference_optimum, reference_solution

VMAX, AMAX, JMAX = 2.0, 10.0, 100.0
HEIGHT_M, RESIDUAL_M = 0.015, 0.002


def _first_mode_model() -> SloshModel:
    """The benchmark's cylinder (R 49 mm, h 80 mm, water) with its first mode only: the 1-D
    planner's residual limit concerns the first mode only, the 3-D problem's every mode."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        model = equivalent_model(
            UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
        )
    return dataclasses.replace(model, modes=model.modes[:1])


def _problem(end_m: list[float], **options: float) -> PathProblem:
    """The benchmark's limits on a straight path from the origin to ``end_m``, first mode."""
    return PathProblem(
        path_from_waypoints([[0.0, 0.0, 0.0], end_m]),
        CartesianLimits(VMAX, AMAX, JMAX),
        SpatialSloshLimits(HEIGHT_M, RESIDUAL_M),
        _first_mode_model(),
        **options,
    )


@pytest.mark.parametrize("distance_m", [0.3])
def test_a_straight_path_takes_the_one_dimensional_optimum(distance_m: float) -> None:
    """Along a straight line the 3-D problem is the 1-D one: wall height e_1 |phi| <= h is the
    angle limit h / e_1, the residual e_1 sqrt(A^2 + B^2) <= r the residual angle r / e_1. The
    1-D planner transcribes it on its 4 ms export grid, the reference in continuous time."""
    model = _first_mode_model()
    wall = model.modes[0].wall_elevation_factor_m
    straight = _problem([distance_m, 0.0, 0.0])
    reference = reference_optimum(straight)
    line = PlanProblem(
        distance_m,
        MachineLimits(VMAX, AMAX, JMAX),
        SloshLimits(HEIGHT_M / wall, RESIDUAL_M / wall),
        model,
        4e-3,
    )
    optimum = plan(line, "optimal", smooth=False).chosen
    assert reference.converged, reference.status
    assert optimum is not None and optimum.feasible
    assert reference.duration_s == pytest.approx(optimum.duration_s, rel=5e-3)
    assert reference.peak_height_m == pytest.approx(HEIGHT_M, rel=1e-3)  # the slosh binds


@pytest.mark.slow
def test_the_nonlinear_reference_agrees_with_the_verification() -> None:
    """The nonlinear reference's optimum, exported on the 4 ms grid and simulated by the
    planner's verification model (`simulate_spatial(nonlinear=True)`, exact differentiation),
    reaches the reference's own peak and residual (the limits it binds) to 0.2 mm; the linear
    model on the same poses does not (it misses the peak by more), so the agreement is the
    nonlinear model's. A straight lifting move with the first mode only keeps it fast."""
    model = _first_mode_model()
    lift = _problem([0.2, 0.0, 0.05])
    solution = reference_solution(lift, slosh_model="nonlinear")
    optimum = solution.optimum
    assert optimum.converged, optimum.status
    assert optimum.slosh_model == "nonlinear"
    assert optimum.peak_height_m == pytest.approx(HEIGHT_M, rel=1e-3)  # the slosh binds
    poses = solution.pose_samples(lift, lift.sample_period_s)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        exact = simulate_spatial(model, poses, nonlinear=True, cutoff_hz=None)
        linear = simulate_spatial(model, poses, nonlinear=False, cutoff_hz=None)
    assert exact.peak_slosh_height_m == pytest.approx(optimum.peak_height_m, abs=2e-4)
    assert exact.residual_slosh_height_m == pytest.approx(optimum.residual_height_m, abs=2e-4)
    assert abs(linear.peak_slosh_height_m - optimum.peak_height_m) > 2e-4


@pytest.mark.slow
def test_the_tilted_reference_is_shorter_and_agrees_with_the_simulation() -> None:
    """With the tilt free (up to 30 deg) the reference's straight move is shorter than the
    upright one, converged from its coarse solution's exact start, and its export, simulated
    by the planner's verification model, reaches the reference's own peak (the limit it binds)
    and residual to 0.3 mm. (The linear reference leaves out the tilting frame's Euler,
    centrifugal and Coriolis terms, which the simulation's models keep: its tilted residual is
    not the simulation's.)"""
    model = _first_mode_model()
    straight = _problem([0.3, 0.0, 0.0], max_tilt_rad=math.radians(30.0))
    upright = reference_optimum(straight, interval_s=8e-3, slosh_model="nonlinear")
    solution = reference_solution(straight, tilt=True, interval_s=8e-3, slosh_model="nonlinear")
    tilted = solution.optimum
    assert tilted.converged, tilted.status
    assert tilted.tilt and tilted.duration_s < 0.95 * upright.duration_s
    assert tilted.duration_s / tilted.intervals <= 8e-3
    assert tilted.peak_height_m == pytest.approx(HEIGHT_M, rel=1e-3)
    poses = solution.pose_samples(straight, straight.sample_period_s)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        exact = simulate_spatial(model, poses, nonlinear=True, cutoff_hz=None)
    assert exact.peak_slosh_height_m == pytest.approx(tilted.peak_height_m, abs=3e-4)
    assert exact.residual_slosh_height_m == pytest.approx(tilted.residual_height_m, abs=3e-4)
