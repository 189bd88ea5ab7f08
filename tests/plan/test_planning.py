"""Input shapers against published formulas, and plans that meet their limits when simulated
again independently."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from conftest import run_entry_point, seed_vial_table3
from typer.testing import CliRunner

from sloshkit.cli import app
from sloshkit.errors import InputError
from sloshkit.io.motions import read_motion_file
from sloshkit.motion import s_curve
from sloshkit.motion.shaping import ei, residual_vibration, shape_motion, zv, zvd
from sloshkit.plan.line.optimal import plan_optimal
from sloshkit.plan.line.planner import plan
from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits, scale_frequencies
from sloshkit.plan.line.searches import plan_paper_law, plan_shaped
from sloshkit.plan.line.verification import verify
from sloshkit.sim.simulate import simulate

OMEGA, ZETA = 29.66, 0.03
pytestmark = pytest.mark.filterwarnings("ignore::sloshkit.errors.ValidityWarning")


def test_singer_seering_1990_zv_and_zvd():
    k = math.exp(-ZETA * math.pi / math.sqrt(1 - ZETA**2))
    half = math.pi / (OMEGA * math.sqrt(1 - ZETA**2))
    shaper = zv(OMEGA, ZETA)
    np.testing.assert_allclose(shaper.amplitudes, [1 / (1 + k), k / (1 + k)])
    np.testing.assert_allclose(shaper.times_s, [0, half])
    shaper = zvd(OMEGA, ZETA)
    np.testing.assert_allclose(shaper.amplitudes, np.array([1, 2 * k, k * k]) / (1 + k) ** 2)
    np.testing.assert_allclose(shaper.times_s, [0, half, 2 * half])
    # Zero residual vibration at the design frequency; ZVD also zero slope there.
    for shaper in (zv(OMEGA, ZETA), zvd(OMEGA, ZETA)):
        assert residual_vibration(shaper, OMEGA, ZETA) == pytest.approx(0.0, abs=1e-12)
    eps = 1e-4 * OMEGA
    slope = residual_vibration(zvd(OMEGA, ZETA), [OMEGA - eps, OMEGA + eps], ZETA)
    assert np.all(slope < 1e-6)


def test_singhose_1994_ei_undamped_closed_form_and_damped_conditions():
    vtol = 0.05
    shaper = ei(OMEGA, 0.0, vtol)
    np.testing.assert_allclose(shaper.amplitudes, [(1 + vtol) / 4, (1 - vtol) / 2, (1 + vtol) / 4])
    damped = ei(OMEGA, ZETA, vtol)
    assert damped.amplitudes.sum() == pytest.approx(1.0, abs=1e-10)
    assert residual_vibration(damped, OMEGA, ZETA) == pytest.approx(vtol, abs=1e-8)
    # Vibration dips below V on both sides of the design frequency (two zeros nearby).
    curve = residual_vibration(damped, OMEGA * np.linspace(0.7, 1.3, 601), ZETA)
    assert curve.min() < 1e-3
    assert np.count_nonzero(curve <= vtol) > np.count_nonzero(
        residual_vibration(zvd(OMEGA, ZETA), OMEGA * np.linspace(0.7, 1.3, 601), ZETA) <= vtol
    )


@pytest.mark.parametrize("make", [zv, zvd, ei])
@pytest.mark.parametrize("factor", [0.8, 0.95, 1.0, 1.05, 1.2])
def test_shaped_move_residual_follows_the_insensitivity_curve(make, factor):
    """For the linear model the residual of the shaped move is V(omega) times the unshaped
    residual (V includes the decay over the shaper's length; Singer & Seering 1990)."""
    model = seed_vial_table3()
    true_model = scale_frequencies(model, factor)
    shaper = make(model.modes[0].omega_rad_s, ZETA)
    base = s_curve(0.3, 1.0, 2.0, 40.0)
    unshaped = simulate(true_model, base, settle_time_s=0.0).residual_angle_rad
    shaped = simulate(true_model, shape_motion(base, shaper), settle_time_s=0.0).residual_angle_rad
    mode = true_model.modes[0]
    expected = residual_vibration(shaper, mode.omega_rad_s, ZETA) * unshaped
    assert shaped == pytest.approx(expected, rel=1e-3, abs=1e-6 * unshaped)


def _problem(**overrides):
    settings = dict(
        distance_m=0.5,
        machine=MachineLimits(1.5, 20.0, 500.0),
        slosh=SloshLimits(math.radians(5.0), math.radians(0.25)),
        model=seed_vial_table3(),
        sample_period_s=4e-3,
    )
    settings.update(overrides)
    return PlanProblem(**settings)


def _independent_check(motion, problem):
    """Simulate the motion with `simulate` (1 ms) on every model of the band."""
    for model in problem.models():
        response = simulate(model, motion, sample_period_s=1e-3, settle_time_s=0.0)
        assert response.peak_angle_rad <= problem.slosh.max_angle_rad * 1.01
        assert response.residual_angle_rad <= problem.slosh.max_residual_rad * 1.02
    assert motion.peak_velocity_m_s <= problem.machine.max_velocity_m_s * (1 + 1e-9)
    assert motion.peak_acceleration_m_s2 <= problem.machine.max_acceleration_m_s2 * (1 + 1e-9)
    assert motion.peak_jerk_m_s3 <= problem.machine.max_jerk_m_s3 * (1 + 1e-6)
    assert motion.distance_m == pytest.approx(problem.distance_m, abs=1e-6)


@pytest.mark.parametrize("law", ["quintic", "septic"])
def test_paper_laws_at_their_shortest_feasible_duration(law):
    problem = _problem()
    candidate = plan_paper_law(law, problem)
    assert candidate.feasible
    _independent_check(candidate.motion, problem)
    # Shortest: 1 % faster violates a slosh limit.
    from sloshkit.motion import make_law

    faster = verify(make_law(law, 0.5, duration_s=0.99 * candidate.duration_s), problem)
    assert not faster.feasible


def test_trapezoid_is_infeasible_under_a_jerk_limit():
    candidate = plan_paper_law("trapezoidal", _problem())
    assert not candidate.feasible
    assert "jerk" in candidate.message


@pytest.mark.parametrize("band", [0.0, 0.1])
def test_shaped_plan_meets_limits_and_beats_the_paper_laws(band):
    problem = _problem(slosh=SloshLimits(math.radians(5.0), math.radians(0.25), robustness=band))
    shaped = plan_shaped(problem)
    assert shaped.feasible
    _independent_check(shaped.motion, problem)
    septic = plan_paper_law("septic", problem)
    assert shaped.duration_s < 0.85 * septic.duration_s


def test_optimal_plan_is_verified_and_fastest():
    problem = _problem()
    shaped = plan_shaped(problem, ("zv",))
    optimal = plan_optimal(problem, shaped.motion)
    assert optimal.feasible, optimal.message
    assert optimal.detail["variant"] == "time-optimal"
    _independent_check(optimal.motion, problem)
    assert optimal.duration_s <= shaped.duration_s
    # The quasi-static bound: |a| <= g tan(5 deg) on average gives T >= 2 sqrt(D / (g tan 5)).
    assert optimal.duration_s > 2 * math.sqrt(0.5 / (9.81 * math.tan(math.radians(5.0)))) * 0.9
    # The minimum time of an independent LP bisection and a separate casadi transcription
    # (issue 19) with the slosh checked on the 4 ms grid only: 1.5663 s; checked on the 2 ms
    # slosh grid too (issue 24, a URScript export resamples at 2 ms) the optimum is 0.01 %
    # longer.
    assert optimal.duration_s == pytest.approx(1.56646, rel=2e-5)
    assert optimal.duration_s > 1.5663
    # Minimum: the longest move 0.01 % shorter (a linear program over every move of the
    # class) does not reach the target.
    from sloshkit.plan.line.optimal import exact_grid_for

    grid = exact_grid_for(problem, optimal.detail["steps"] + 4)
    assert grid.longest(optimal.duration_s * (1 - 1e-4)).distance_m < problem.distance_m


def test_smooth_variant_costs_its_stated_price_and_has_a_gentler_jerk():
    from sloshkit.plan.line.optimal import SMOOTH_PRICE

    problem = _problem(distance_m=0.2)
    fastest = plan_optimal(problem)
    smooth = plan_optimal(problem, smooth=True)
    assert fastest.feasible and smooth.feasible, smooth.message
    assert smooth.method == "optimal-smooth" and smooth.detail["variant"] == "smooth"
    _independent_check(smooth.motion, problem)
    assert smooth.duration_s == pytest.approx(fastest.duration_s * (1 + SMOOTH_PRICE), rel=1e-9)
    t = np.arange(0.0, fastest.duration_s, 4e-3)
    rate_fast = np.abs(np.diff(fastest.motion.jerk(t))).sum()
    rate_smooth = np.abs(np.diff(smooth.motion.jerk(t * smooth.duration_s / fastest.duration_s)))
    assert rate_smooth.sum() < 0.5 * rate_fast


def test_smooth_variant_with_the_default_damping_through_the_cli():
    """The correlation's damping (0.009): the smooth program's margin keeps the solver's
    tolerances inside the limits, so the smooth move is the one returned and said so."""
    proc = run_entry_point(
        "plan",
        "--distance",
        "0.1m",
        "--max-angle",
        "5deg",
        "--max-residual",
        "0.25deg",
        "--vmax",
        "1.5m/s",
        "--amax",
        "20m/s^2",
        "--jmax",
        "500m/s^3",
        "--method",
        "optimal",
        "--smooth",
        "--json",
    )
    assert proc.returncode == 0, proc.stderr
    payload = json.loads(proc.stdout)
    assert payload["method"] == "optimal-smooth" and payload["variant"] == "smooth"
    assert payload["feasible"] is True


def test_plan_cli_csv_json_and_independent_resimulation(tmp_path):
    out = tmp_path / "traj.csv"
    result = CliRunner().invoke(
        app,
        [
            "plan",
            "--distance",
            "0.5m",
            "--max-angle",
            "5deg",
            "--max-residual",
            "0.25deg",
            "--vmax",
            "1.5m/s",
            "--amax",
            "20m/s^2",
            "--jmax",
            "500m/s^3",
            "--damping-ratio",
            "0.03",
            "--method",
            "shaped",
            "--sample-period",
            "4ms",
            "--out",
            str(out),
            "--plot",
            str(tmp_path / "plan.png"),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    for key in (
        "method",
        "duration_s",
        "peak_angle_deg",
        "residual_angle_deg",
        "peak_velocity_m_s",
        "peak_acceleration_m_s2",
        "peak_jerk_m_s3",
        "feasible",
        "candidates",
    ):
        assert key in payload
    assert payload["feasible"] is True
    lines = [line for line in out.read_text().splitlines() if not line.startswith("#")]
    assert lines[0] == "t_s,position_m,velocity_m_s,acceleration_m_s2,jerk_m_s3"
    assert out.read_text().startswith("# sloshkit-plan: {")  # model and limits (issue 24)
    data = np.loadtxt(lines[1:], delimiter=",")
    np.testing.assert_allclose(np.diff(data[:, 0]), 0.004, atol=1e-9)
    assert data[0, 0] == 0.0 and data[0, 1] == 0.0
    assert data[-1, 1] == pytest.approx(0.5, abs=1e-9)
    assert data[-1, 2] == 0.0 and data[-1, 3] == 0.0
    # An independent re-simulation of the exported samples (quintic-spline reconstruction).
    motion = read_motion_file(out)
    response = simulate(seed_vial_table3(), motion, sample_period_s=1e-3, settle_time_s=0.0)
    assert math.degrees(response.peak_angle_rad) <= 5.0 * 1.02
    assert math.degrees(response.residual_angle_rad) <= 0.25 * 1.05
    assert (tmp_path / "plan.png").stat().st_size > 10_000


def test_infeasible_request_fails_clearly():
    proc = run_entry_point(
        "plan",
        "--distance",
        "0.5m",
        "--max-angle",
        "0.01deg",
        "--max-residual",
        "0.001deg",
        "--vmax",
        "1m/s",
        "--amax",
        "1m/s^2",
        "--jmax",
        "10m/s^3",
        "--method",
        "fast",
        "--max-duration",
        "2s",
    )
    assert proc.returncode == 1
    assert "no method meets the limits" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_missing_limits_are_input_errors():
    proc = run_entry_point("plan", "--max-angle", "5deg")
    assert proc.returncode == 2
    assert "--vmax" in proc.stderr


def test_unknown_method():
    with pytest.raises(InputError, match="method"):
        plan(_problem(), method="telepathy")


def test_nonlinear_verification_uses_the_large_angle_pendulum():
    """At 5 deg the nonlinear pendulum softens: a move tuned on the linear model is verified
    differently (slightly larger peak) when the problem asks for the nonlinear model."""
    from dataclasses import replace

    problem = _problem()
    motion = plan_shaped(problem, ("zv",)).motion
    linear = verify(motion, problem)
    nonlinear = verify(motion, replace(problem, nonlinear=True))
    assert linear.feasible
    assert nonlinear.peak_angle_rad > linear.peak_angle_rad
    assert nonlinear.peak_angle_rad == pytest.approx(linear.peak_angle_rad, rel=0.05)


def test_optimal_plan_with_a_wall_limit_keeps_every_mode():
    problem = _problem(
        distance_m=0.2,
        slosh=SloshLimits(
            math.radians(5.0), math.radians(0.25), max_wall_elevation_m=0.0015, robustness=0.05
        ),
    )
    optimal = plan_optimal(problem)
    assert optimal.feasible, optimal.message
    check = optimal.verification
    # The wall limit is the active one (5 deg alone would allow a higher wall).
    assert check.peak_wall_elevation_m == pytest.approx(0.0015, rel=1e-4)


def _tight():
    return _problem(slosh=SloshLimits(math.radians(0.05), math.radians(0.001)))


def test_slosh_floor_bounds_every_plan_and_is_the_quasi_static_bound_within_sqrt2():
    from sloshkit.plan.line.work_estimate import slosh_floor_s

    problem = _problem()
    floor = slosh_floor_s(problem)
    assert floor < plan_optimal(problem).duration_s
    # Without damping and residual: T >= sqrt(2 D / (g theta)), sqrt(2) below the quasi-static
    # 2 sqrt(D / (g theta)) of a move accelerating at g theta for half the time; the damping
    # term (2 zeta w theta T, zeta = 0.03) lowers it by a few per cent.
    mode = problem.model.modes[0]
    g = mode.omega_rad_s**2 * mode.length_m
    no_residual = _problem(slosh=SloshLimits(math.radians(5.0), 1e-12))
    quasi_static = 2 * math.sqrt(0.5 / (g * math.radians(5.0)))
    assert slosh_floor_s(no_residual) < quasi_static / math.sqrt(2)
    assert slosh_floor_s(no_residual) == pytest.approx(quasi_static / math.sqrt(2), rel=0.05)


def test_tight_slosh_limits_answer_quickly():
    """0.05 deg peak / 0.001 deg residual over 0.5 m: no move is shorter than 10.8 s. The
    optimal method is refused by name before any program (it used to spend 53 s and fail);
    the paper laws start their scan at the slosh bound."""
    import time

    problem = _tight()
    started = time.perf_counter()
    with pytest.raises(InputError, match="max_angle") as error:
        plan(problem, "optimal")
    assert "10.81 s" in str(error.value)
    quintic = plan_paper_law("quintic", problem)
    assert quintic.feasible and 18.0 < quintic.duration_s < 19.0
    assert time.perf_counter() - started < 10.0


def test_tight_limits_cli_is_one_line_exit_2():
    proc = run_entry_point(
        "plan",
        "--distance",
        "0.5m",
        "--max-angle",
        "0.05deg",
        "--max-residual",
        "0.001deg",
        "--vmax",
        "1.5m/s",
        "--amax",
        "20m/s^2",
        "--jmax",
        "500m/s^3",
        "--method",
        "optimal",
    )
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: --max-angle = ")
    assert "Traceback" not in proc.stderr
