"""3-D path planning: geometry, the linear screen against the 1-D model, tilt compensation,
re-simulated exports, and clear failures."""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from sloshkit.errors import InputError, ValidityWarning
from sloshkit.io.poses import read_pose_file
from sloshkit.io.waypoints import read_waypoints
from sloshkit.model.modal import SloshModel
from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.motion.laws import s_curve
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.path.geometry import path_from_poses, path_from_waypoints
from sloshkit.plan.path.planner import linear_verifier, plan_path
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits, sample_path
from sloshkit.plan.path.screen import linear_screen
from sloshkit.plan.path.tilt_compensation import tilt_compensated
from sloshkit.plan.path.timing import Timing
from sloshkit.sim.spatial import simulate_spatial
from tests.conftest import run_entry_point
from tests.plan.plan_checks import assert_export_meets_limits

DATA = Path(__file__).parents[1] / "data" / "measured-3d" / "poses"


def test_clothoid_blend_has_continuous_curvature_peaking_at_one_over_r() -> None:
    path = path_from_waypoints([[0, 0, 0], [0.4, 0, 0], [0.4, 0.4, 0]], blend_radius_m=0.05)
    s = np.linspace(0.0, path.length_m, 4001)
    curvature = path.curvature(s)
    assert curvature.max() == pytest.approx(20.0, rel=0.02)
    # Continuous: no jump larger than the spline's resolution between neighbours.
    assert np.max(np.abs(np.diff(curvature))) < 0.5
    assert np.allclose(path.position(path.length_m), [0.4, 0.4, 0.0], atol=1e-9)
    with pytest.raises(InputError, match="blend_radius"):
        path_from_waypoints([[0, 0, 0], [0.05, 0, 0], [0.05, 0.05, 0]], blend_radius_m=0.2)


def test_waypoint_file_units_and_pose_paths(tmp_path: Path) -> None:
    csv = tmp_path / "w.csv"
    csv.write_text("x [mm],y [mm],z [mm],yaw [deg]\n0,0,0,0\n300,0,0,90\n")
    points, yaw = read_waypoints(csv)
    assert points[1].tolist() == [0.3, 0.0, 0.0]
    assert yaw is not None and yaw[1] == pytest.approx(math.pi / 2)
    # A half circle of radius 0.3 m: length pi * 0.3 and curvature 1/0.3.
    t = np.linspace(0.0, 1.0, 401)
    positions = np.c_[0.3 * np.cos(np.pi * t), 0.3 * np.sin(np.pi * t), 0 * t]
    path = path_from_poses(positions, np.tile([0.0, 0.0, 0.0, 1.0], (t.size, 1)))
    assert path.length_m == pytest.approx(math.pi * 0.3, rel=1e-4)
    assert np.median(path.curvature(np.linspace(0.1, 0.8, 50))) == pytest.approx(1 / 0.3, rel=1e-3)


def test_straight_path_screen_equals_one_dimensional_model(robot_vial: SloshModel) -> None:
    """On a straight path the 3-D linear screen is the 1-D linear model of the same move:
    peak and residual wall height agree to 1 % (the 1-D export and filter are the same)."""
    from sloshkit.sim.discretisation import linear_mode_response
    from sloshkit.sim.metrics import free_amplitude

    motion = s_curve(0.3, 1.0, 3.0, 30.0)
    path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    poses = sample_path(path, motion, 2e-3)
    screen = linear_screen([robot_vial], poses)
    velocity = np.gradient(poses.position_m[:, 0], 2e-3)
    velocity = np.concatenate(([0.0], np.diff(poses.position_m[:, 0]) / 2e-3))
    wall = np.zeros_like(velocity)
    residual = 0.0
    for mode in robot_vial.modes:
        theta, rate = linear_mode_response(
            velocity, 2e-3, mode.omega_rad_s, mode.damping_ratio, mode.length_m
        )
        wall += mode.wall_elevation_factor_m * theta
        residual += mode.wall_elevation_factor_m * float(
            free_amplitude(theta[-1], rate[-1], mode.omega_rad_s, mode.damping_ratio)
        )
    assert screen.peak_height_m == pytest.approx(np.max(np.abs(wall)), rel=0.01)
    assert screen.residual_height_m == pytest.approx(residual, rel=0.02, abs=2e-5)


def test_straight_path_plan_matches_one_dimensional_planner(robot_vial: SloshModel) -> None:
    """The 3-D planner on a straight 0.3 m path against the 1-D planner with the same limits
    (peak wall elevation, residual): the 1-D answer run along the path gives the same peak
    wall height in the 3-D screen (1 %), and the 3-D retime duration is within 20 % of the
    1-D shaped one (different families: capped time-optimal profile with a box filter vs
    S-curves with four shapers and searched jerk)."""
    from sloshkit.plan.line.planner import plan
    from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits

    height, residual_height = 0.008, 0.001
    factor = robot_vial.modes[0].wall_elevation_factor_m
    one_d = plan(
        PlanProblem(
            0.3,
            MachineLimits(2.0, 10.0, 100.0),
            SloshLimits(1.0, residual_height / factor, height),
            robot_vial,
        ),
        "shaped",
    )
    problem = PathProblem(
        path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
        CartesianLimits(2.0, 10.0, 100.0),
        SpatialSloshLimits(height, residual_height),
        robot_vial,
    )
    three_d = plan_path(problem, "retime", verifier=linear_verifier)
    assert one_d.feasible and three_d.feasible
    assert three_d.chosen is not None and one_d.chosen is not None
    assert three_d.chosen.duration_s == pytest.approx(one_d.chosen.duration_s, rel=0.2)
    assert one_d.chosen.motion is not None and one_d.chosen.verification is not None
    along = sample_path(problem.path, one_d.chosen.motion, problem.sample_period_s)
    assert linear_screen([robot_vial], along).peak_height_m == pytest.approx(
        one_d.chosen.verification.peak_wall_elevation_m, rel=0.01
    )


@pytest.mark.slow
def test_every_plan_meets_its_limits_when_its_export_is_simulated_again(
    robot_vial: SloshModel, tmp_path: Path
) -> None:
    problem = PathProblem(
        path_from_waypoints([[0, 0, 0], [0.3, 0, 0], [0.3, 0.2, 0.05]], blend_radius_m=0.05),
        CartesianLimits(1.5, 8.0, 80.0),
        SpatialSloshLimits(0.01, 0.002),
        robot_vial,
    )
    result = plan_path(problem, "auto")
    assert result.feasible
    for candidate in result.candidates:
        assert candidate.feasible, candidate.message
        out = result.to_csv(tmp_path / "plan.csv") if candidate is result.chosen else None
        poses = candidate.poses
        assert poses is not None
        machine = CartesianLimits(1.5, 8.0, 80.0)
        assert_export_meets_limits(robot_vial, poses, 0.01, 0.002, machine)
        if out is not None:
            back = read_pose_file(out)
            p, q = back.position_m, back.quaternion_xyzw
            assert np.allclose(p, poses.position_m) and np.allclose(q, poses.quaternion_xyzw)
            assert np.allclose(p[-1], [0.3, 0.2, 0.05], atol=1e-6)


def test_tilt_compensation_of_constant_horizontal_acceleration(robot_vial: SloshModel) -> None:
    """Feddema et al. (1997): tilt atan(a/g) under a constant acceleration a, and the liquid
    stays calm: a smooth rest-to-rest move whose acceleration holds 3 m/s^2 for 1 s keeps
    under 2 % of the untilted quasi-static height during the hold and leaves under 3 % of it
    as residual (nonlinear 3-D model)."""
    ts, accel = 2e-3, 3.0
    t = np.arange(0.0, 4.5, ts)

    def up(time: np.ndarray) -> np.ndarray:
        return 0.5 * (1 - np.cos(np.pi * np.clip(time / 0.5, 0.0, 1.0)))

    def pulse(time: np.ndarray) -> np.ndarray:  # 0 -> 1 over 0.5 s, hold 1 s, -> 0
        return up(time) - up(time - 1.5)

    a = accel * (pulse(t) - pulse(t - 2.0))
    velocity = np.cumsum(a) * ts
    x = np.cumsum(velocity) * ts
    rest = np.tile([0.0, 0.0, 0.0, 1.0], (t.size, 1))
    poses = PoseTrajectory(t, np.c_[x, 0 * t, 0 * t], rest)
    tilted = tilt_compensated(poses, robot_vial.modes[0].bob_height_m, math.radians(30), 0.0, 0.03)
    axis = tilted.rotation.apply([0.0, 0.0, 1.0])
    hold = (tilted.time_s > 0.75 + 0.09) & (tilted.time_s < 1.25 + 0.09)  # + padding
    angle = np.degrees(np.arctan2(axis[hold, 0], axis[hold, 2]))
    assert angle == pytest.approx(math.degrees(math.atan(accel / GRAVITY_M_S2)), abs=0.05)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        plain = simulate_spatial(robot_vial, poses, nonlinear=True, cutoff_hz=None)
        calm = simulate_spatial(robot_vial, tilted, nonlinear=True, cutoff_hz=None)
    quasi_static = 0.9 * robot_vial.radius_m * accel / GRAVITY_M_S2
    assert plain.peak_slosh_height_m > quasi_static
    during = (calm.time_s > 0.9) & (calm.time_s < 1.4)  # the hold, after the padding
    assert np.max(calm.slosh_height_m[during]) < 0.02 * quasi_static
    # What remains comes from the 0.5 s ramps of the tilt (its angular acceleration).
    assert calm.peak_slosh_height_m < 0.15 * plain.peak_slosh_height_m
    assert calm.residual_slosh_height_m < 0.03 * quasi_static


def test_plan_path_cli_json_export_and_failure(tmp_path: Path) -> None:
    waypoints = tmp_path / "w.csv"
    waypoints.write_text("x [mm],y [mm],z [mm]\n0,0,0\n250,0,0\n250,150,0\n")
    common = [
        "plan",
        "--path",
        str(waypoints),
        "--radius",
        "49mm",
        "--fill-height",
        "80mm",
        "--liquid",
        "water-20C",
        "--damping-ratio",
        "0.0066",
        "--vmax",
        "1.5m/s",
        "--amax",
        "8m/s^2",
        "--jmax",
        "80m/s^3",
        "--max-residual-height",
        "2mm",
        "--method",
        "shaped",
        "--json",
    ]
    out = tmp_path / "plan.csv"
    done = run_entry_point(*common, "--max-slosh-height", "12mm", "--out", str(out))
    assert done.returncode == 0, done.stderr
    payload = json.loads(done.stdout)
    assert set(payload) == {
        "method",
        "duration_s",
        "peak_slosh_height_m",
        "residual_slosh_height_m",
        "peak_tilt_deg",
        "peak_slosh_angle_deg",
        "max_path_deviation_m",
        "feasible",
        "candidates",
        "warnings",  # every --json object carries the command's validity warnings (issue 17)
    }
    assert payload["feasible"] and payload["peak_slosh_height_m"] <= 0.012
    # beyond small-amplitude theory the plan says so (stderr and JSON)
    beyond = payload["peak_slosh_angle_deg"] > 15.0
    assert any("slosh angle reaches" in w for w in payload["warnings"]) == beyond
    lines = out.read_text().splitlines()
    assert lines[2] == "t,x,y,z,qx,qy,qz,qw"  # after the plan header and the units (issue 24)
    assert '"max_slosh_height_m": 0.012' in lines[0]
    failed = run_entry_point(*common, "--max-slosh-height", "0.0001mm")
    assert failed.returncode == 1
    assert "no method meets the limits" in failed.stderr
    # the method names the limit that binds it at its slowest try (issue 25)
    assert "peak slosh height" in failed.stderr
    assert "against its 0.0001 mm limit" in failed.stderr
    both = run_entry_point(
        *common,
        "--max-slosh-height",
        "12mm",
        "--path-from-poses",
        str(DATA / "TRD_2D_0.3m_2.4s_270deg.csv"),
    )
    assert both.returncode == 2 and "exactly one of --path" in both.stderr


def _straight_request(tmp_path: Path, *options: str) -> tuple[str, ...]:
    """``plan --path`` of a straight 0.1 m move of the measured series' vial under issue #25's
    limits (15 mm / 2 mm, 2 m/s, 10 m/s^2, 100 m/s^3), JSON out, with ``options``."""
    waypoints = tmp_path / "w.csv"
    waypoints.write_text("x [mm],y [mm],z [mm]\n0,0,0\n100,0,0\n")
    return (
        "plan", "--path", str(waypoints), "--radius", "49mm", "--fill-height", "80mm",
        "--liquid", "water-20C", "--max-slosh-height", "15mm", "--max-residual-height", "2mm",
        "--vmax", "2m/s", "--amax", "10m/s^2", "--jmax", "100m/s^3", "--json", *options,
    )  # fmt: skip


@pytest.mark.slow
def test_optimal_with_tilt_compensation_tilts_and_is_faster(tmp_path: Path) -> None:
    """``--method optimal --tilt-compensation`` (``tilt``): the tilt is a variable of the
    programs, so the verified plan tilts (within ``--max-tilt``), is zero at both ends and is
    shorter than the upright optimum of the same problem; stdout is the JSON alone."""
    common = _straight_request(tmp_path, "--max-tilt", "20deg", "--method", "optimal")
    upright = run_entry_point(*common)
    tilted = run_entry_point(*common, "--tilt-compensation", "--out", str(tmp_path / "plan.csv"))
    assert upright.returncode == 0 and tilted.returncode == 0, tilted.stderr
    flat, tilt = json.loads(upright.stdout), json.loads(tilted.stdout)
    assert flat["feasible"] and tilt["feasible"]
    assert flat["peak_tilt_deg"] == 0.0 and 0.5 < tilt["peak_tilt_deg"] <= 20.0 + 1e-6
    assert tilt["duration_s"] < flat["duration_s"]
    # optimal is tilt with --tilt-compensation, else retime; both the programs' plans
    assert (flat["method"], tilt["method"]) == ("retime", "tilt")
    assert flat["candidates"][0]["source"] == tilt["candidates"][0]["source"] == "program"
    assert not any("--tilt-compensation" in w for w in tilt["warnings"])
    # 15 mm at the wall of a 49 mm radius is a surface slope beyond small-amplitude theory
    for plan in (flat, tilt):
        assert plan["peak_slosh_angle_deg"] > 15.0
        assert any("beyond small-amplitude theory" in w for w in plan["warnings"])
    poses = read_pose_file(tmp_path / "plan.csv")
    quaternion_xy = poses.quaternion_xyzw[:, :2]  # zero when upright (the path does not turn)
    assert np.abs(quaternion_xy[[0, -1]]).max() < 1e-9 and np.abs(quaternion_xy).max() > 1e-3


def test_angular_limits_parse_rad_and_deg() -> None:
    from sloshkit.io.requests import angular_rate_request

    assert angular_rate_request("90deg/s", 1, "w") == pytest.approx(math.pi / 2)
    assert angular_rate_request("2 rad/s**2", 2, "a") == pytest.approx(2.0)
    assert angular_rate_request(None, 1, "w") is None
    with pytest.raises(InputError, match="angular rate"):
        angular_rate_request("5 furlongs", 1, "max_angular_velocity")


def test_angular_limits_default_and_none() -> None:
    from sloshkit.io.command_requests import (
        DEFAULT_ANGULAR_ACCELERATION,
        DEFAULT_ANGULAR_VELOCITY,
        path_problem_request,
    )
    from sloshkit.io.requests import angular_rate_request

    assert angular_rate_request(DEFAULT_ANGULAR_VELOCITY, 1, "w") == pytest.approx(math.pi)
    assert angular_rate_request(DEFAULT_ANGULAR_ACCELERATION, 2, "a") == pytest.approx(
        math.radians(1000)
    )
    assert angular_rate_request("none", 1, "w") is None
    options = {
        "vmax": "2m/s",
        "amax": "10m/s^2",
        "jmax": "100m/s^3",
        "max_slosh_height": "15mm",
        "max_residual_height": "2mm",
        "max_surface_angle": None,
        "band": 0.0,
        "sample_period": "4ms",
        "max_tilt": "30deg",
        "tilt_centre": "0mm",
    }
    path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    defaults = path_problem_request(
        None, path, max_angular_velocity=None, max_angular_acceleration=None, **options
    ).machine
    assert defaults.max_angular_velocity_rad_s == pytest.approx(math.pi)
    assert defaults.max_angular_acceleration_rad_s2 == pytest.approx(math.radians(1000))
    unlimited = path_problem_request(
        None, path, max_angular_velocity="none", max_angular_acceleration="none", **options
    ).machine
    assert unlimited.max_angular_velocity_rad_s is None
    assert unlimited.max_angular_acceleration_rad_s2 is None


def test_robot_check_refuses_fast_joints_and_slows_the_plan_down(robot_vial: SloshModel) -> None:
    """A yaw of 90 degrees in 0.5 s along a 50 mm move needs the UR5e's wrist_3 at about
    1.9x its 3.14 rad/s: the robot-aware verification names the joint, the stretch loop slows
    the export down until every joint is within its limit, and the export still ends on the
    path's last pose."""
    from sloshkit.export.frames import Mounting
    from sloshkit.export.kinematics import load_arm
    from sloshkit.export.path_robot import joint_speed_ratio, robot_verifier
    from sloshkit.plan.path.result import linear_verifier, verified_candidate
    from sloshkit.plan.path.search import stretcher
    from sloshkit.plan.path.timing import Timing

    arm, mounting = load_arm("ur5e"), Mounting(base_xyz_m=(-0.45, -0.13, 0.3))
    path = path_from_waypoints([[0, 0, 0], [0.05, 0, 0]], yaw_rad=[0.0, math.pi / 2], name="turn")
    problem = PathProblem(
        path,
        CartesianLimits(2.0, 20.0, 1000.0),
        SpatialSloshLimits(1.0, 1.0),
        robot_vial,
        sample_period_s=0.01,
    )
    t = np.linspace(0.0, 0.5, 101)
    timing = Timing.from_samples(
        "fast", t, path.length_m * (t / 0.5) ** 3 * (10 - 15 * t / 0.5 + 6 * (t / 0.5) ** 2)
    )
    poses_for = stretcher(problem, timing)
    ratio, joint = joint_speed_ratio(arm, mounting, poses_for(1.0))
    assert ratio > 1.2 and joint.startswith("wrist_3_joint")
    check = robot_verifier(arm, mounting, linear_verifier)
    first = check(problem, poses_for(1.0), False)
    assert not first.feasible and first.violations[-1].startswith("joint speed wrist_3_joint")
    assert first.required_stretch == pytest.approx(ratio)
    found = verified_candidate("retime", problem, poses_for, 1.0, 0.0, check, False, {})
    assert found.feasible, found.message
    assert found.detail["stretch"] >= ratio
    assert joint_speed_ratio(arm, mounting, found.poses)[0] <= 1.0


def test_curve_shaper_cancels_more_residual_on_a_circle(robot_vial: SloshModel) -> None:
    """On a full circle of radius 0.3 m the forcing turns at Omega = v / R: the timing shaped
    with the curve shaper (notches at w and w(1 -+ r)) leaves less residual than the one shaped
    with the first-mode ZV at every cap from 2 to 5 m/s^2, and under half of it in total
    (linear screen of the sampled export)."""
    from sloshkit.plan.path.retime import curve_shaper, family_member, first_mode_shaper

    t = np.linspace(0.0, 1.0, 721)
    circle = np.c_[0.3 * np.cos(2 * np.pi * t), 0.3 * np.sin(2 * np.pi * t), 0 * t]
    path = path_from_poses(circle, np.tile([0.0, 0.0, 0.0, 1.0], (t.size, 1)))
    problem = PathProblem(
        path, CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.03, 0.002), robot_vial
    )
    residual = {"zv": [], "curve": []}
    for cap in (2.0, 3.0, 4.0, 5.0):
        for name, shaper in (("zv", first_mode_shaper(problem)), ("curve", curve_shaper(problem))):
            member = family_member(problem, cap, shaper)
            poses = sample_path(path, member, 4e-3)
            residual[name].append(linear_screen([robot_vial], poses).residual_height_m)
    assert all(c < z for c, z in zip(residual["curve"], residual["zv"], strict=True))
    assert sum(residual["curve"]) < 0.5 * sum(residual["zv"])


def test_retime_is_never_slower_than_uniform_scaling_of_the_reference(
    robot_vial: SloshModel,
) -> None:
    """The verified uniform scaling of a reference timing is a seed of ``retime`` (and its
    speed-scaling warp only keeps screened improvements), so ``retime`` is at least as fast;
    its export meets the limits when simulated again with the nonlinear model."""
    path = path_from_waypoints([[0, 0, 0], [0.25, 0, 0], [0.25, 0.15, 0]], blend_radius_m=0.04)
    problem = PathProblem(
        path, CartesianLimits(1.5, 8.0, 80.0), SpatialSloshLimits(0.012, 0.002), robot_vial
    )
    law = s_curve(path.length_m, 1.0, 4.0, 40.0)
    t = np.linspace(0.0, law.duration_s, 201)
    reference = Timing.from_samples("reference", t, law.position(t))
    result = plan_path(problem, "retime", reference=reference)
    found = {candidate.method: candidate for candidate in result.candidates}
    assert found["uniform"].feasible and found["retime"].feasible
    assert found["retime"].duration_s <= found["uniform"].duration_s
    assert_export_meets_limits(robot_vial, found["retime"].poses, 0.012, 0.002)


@pytest.mark.parametrize(
    ("limits", "named"),
    [
        (SpatialSloshLimits(1e-7, 0.002), "peak slosh height"),
        (SpatialSloshLimits(0.015, 1e-9), "residual slosh height"),
    ],
)
def test_an_impossible_request_names_the_limit_that_binds_each_method(
    robot_vial: SloshModel, limits: SpatialSloshLimits, named: str
) -> None:
    """Issue 25: an infeasible request fails with the binding limit named, for each method:
    the limit that the slowest member it tried exceeds most, with its value and the limit."""
    path = path_from_waypoints([[0, 0, 0], [0.15, 0, 0], [0.15, 0.1, 0]], blend_radius_m=0.03)
    problem = PathProblem(
        path, CartesianLimits(2.0, 10.0, 100.0), limits, robot_vial, sample_period_s=0.01
    )
    result = plan_path(problem, method="auto", tilt=True, verifier=linear_verifier)
    assert not result.feasible
    messages = {candidate.method: candidate.message for candidate in result.candidates}
    assert {"retime", "shaped", "tilt"} <= set(messages)
    # asked for by name, retime and tilt fail the same way: no family member is feasible, so
    # their programs do not search ever longer durations
    for method in ("retime", "tilt"):
        alone = plan_path(problem, method=method, verifier=linear_verifier).candidates
        assert [c.method for c in alone] == [method] and not alone[0].feasible
        messages[f"{method} alone"] = alone[0].message
    for method, message in messages.items():
        assert "at the lowest cap" in message or "at that cap" in message, (method, message)
        assert named in message and "against its" in message, (method, message)


@pytest.mark.slow
def test_auto_runs_the_programs_on_a_short_move_only(
    robot_vial: SloshModel, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``auto`` runs ``retime``'s programs when their first start, the capped time-optimal
    profile, has at most AUTO_OPTIMAL_MAX_SAMPLES samples (with an arm
    AUTO_ARM_OPTIMAL_MAX_SAMPLES), and the chosen plan is then the programs' and no slower than
    any other verified candidate; with the bound below that start's samples ``retime`` is the
    family's member."""
    from sloshkit.plan.path import planner
    from sloshkit.plan.path.search import upright_family
    from sloshkit.plan.path.starts import capped_start

    problem = PathProblem(
        path_from_waypoints([[0, 0, 0], [0.15, 0, 0.05]]),
        CartesianLimits(2.0, 10.0, 100.0),
        SpatialSloshLimits(0.01, 0.002),
        robot_vial,
        sample_period_s=0.01,
    )
    start = capped_start(problem).steps
    assert start <= planner.AUTO_OPTIMAL_MAX_SAMPLES
    result = plan_path(problem, "auto", tilt=False)
    assert [c.method for c in result.candidates] == ["shaped", "retime"]
    feasible = [c for c in result.candidates if c.feasible]
    assert result.chosen is not None and result.chosen.feasible
    assert result.chosen.duration_s == min(c.duration_s for c in feasible)
    # on this move the programs give 0.64 s, the family 0.75 s and shaped 0.96 s
    assert result.chosen.method == "retime" and result.chosen.detail["source"] == "program"
    family = upright_family(problem)
    assert family.feasible and result.chosen.duration_s < family.duration_s
    # without an arm the arm's bound does not apply
    monkeypatch.setattr(planner, "AUTO_ARM_OPTIMAL_MAX_SAMPLES", start - 1)
    again = plan_path(problem, "auto", tilt=False).candidates[1]
    assert again.detail["source"] == "program"
    monkeypatch.setattr(planner, "AUTO_OPTIMAL_MAX_SAMPLES", start - 1)
    without = plan_path(problem, "auto", tilt=False).candidates[1]
    assert without.detail["source"] == "family"
    assert without.duration_s == pytest.approx(family.duration_s)


@pytest.mark.slow
def test_a_surface_angle_limit_is_a_limit_of_the_programs(tmp_path: Path) -> None:
    """``--max-surface-angle`` binds the programs' plan itself (its verified slosh angle
    within the limit, the programs' own plan rather than a slow family member), is never
    shorter than the plan without it, and keeps the plan out of the large-angle warning."""
    common = _straight_request(tmp_path, "--method", "retime")
    free = run_entry_point(*common)
    bound = run_entry_point(*common, "--max-surface-angle", "12deg")
    assert free.returncode == 0 and bound.returncode == 0, bound.stderr
    unlimited, limited = json.loads(free.stdout), json.loads(bound.stdout)
    assert unlimited["peak_slosh_angle_deg"] > 12.0  # the limit binds
    assert limited["feasible"] and limited["peak_slosh_angle_deg"] <= 12.0 + 1e-9
    assert limited["candidates"][0]["source"] == "program"
    assert limited["duration_s"] >= unlimited["duration_s"]
    assert not any("slosh angle reaches" in w for w in limited["warnings"])
    last_round = limited["candidates"][0]["rounds"][-1]
    assert last_round["verified_angle_rad"] <= math.radians(12.0) + 1e-12
