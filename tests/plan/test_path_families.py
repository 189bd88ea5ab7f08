"""The timing family below a plan already found: ``retime`` and ``tilt`` run their programs
first and screen only the family members that could beat the programs' plan."""

from __future__ import annotations

from dataclasses import replace

import pytest

from sloshkit.plan.path import planner
from sloshkit.plan.path.planner import plan_path
from sloshkit.plan.path.problem import SpatialSloshLimits, sample_path
from sloshkit.plan.path.result import verify
from sloshkit.plan.path.retime import family_member
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import fastest_capped, upright_family
from tests.plan.plan_checks import straight_problem


def _recording_screen(problem, durations):
    models = problem.models()

    def passes(poses):
        durations.append(poses.duration_s)
        return screen_ok(problem, linear_screen(models, poses))

    return passes


def test_a_bounded_cap_search_screens_only_members_shorter_than_the_bound() -> None:
    """With ``slowest_s`` the search screens no member at least that long (they count as
    passing unscreened) and returns a screened member shorter than it, or None; with a bound
    above every member it tries, it is the unbounded search."""
    problem = straight_problem()
    free: list[float] = []
    found = fastest_capped(problem, _recording_screen(problem, free), None)
    assert found is not None
    cap, member = found
    fastest = family_member(problem, problem.machine.max_acceleration_m_s2, None).duration_s
    assert fastest < member.duration_s
    for bound in (0.5 * (fastest + member.duration_s), member.duration_s + 0.1, fastest):
        bounded: list[float] = []
        again = fastest_capped(problem, _recording_screen(problem, bounded), None, slowest_s=bound)
        assert all(duration < bound + problem.sample_period_s for duration in bounded)
        assert len(bounded) < len(free)
        if again is not None:
            poses = sample_path(problem.path, again[1], problem.sample_period_s)
            assert again[1].duration_s < bound
            assert screen_ok(problem, linear_screen(problem.models(), poses))
    assert fastest_capped(problem, _recording_screen(problem, []), None, slowest_s=fastest) is None
    everything: list[float] = []
    same = fastest_capped(problem, _recording_screen(problem, everything), None, slowest_s=1e3)
    assert same is not None and same[0] == cap and everything == free


def test_the_bounded_family_says_that_no_shorter_member_passes() -> None:
    problem = straight_problem()
    family = upright_family(problem, planner.linear_verifier, slowest_s=0.1)
    assert not family.feasible and "shorter than 0.100 s" in family.message


def test_retime_screens_the_family_below_its_programs_plan(monkeypatch) -> None:
    """``retime`` calls its family with the programs' verified duration as the bound, and
    returns the programs' plan (0.87 s against the family's 1.00 s)."""
    problem = straight_problem()
    bounds: list[float | None] = []
    original = planner.upright_family

    def recorded(problem, verifier, slowest_s=None):
        bounds.append(slowest_s)
        return original(problem, verifier, slowest_s)

    monkeypatch.setattr(planner, "upright_family", recorded)
    chosen = plan_path(problem, "retime").chosen
    assert chosen is not None and chosen.feasible and chosen.detail["source"] == "program"
    assert bounds == [pytest.approx(chosen.duration_s)]
    unbounded = original(problem, verify)
    assert unbounded.feasible and chosen.duration_s < unbounded.duration_s


def test_an_impossible_request_still_names_its_binding_limit() -> None:
    """When even the quasi-static member breaks the slosh screen the families run unbounded,
    the programs do not, and the failure names the limit (a 1 um residual limit)."""
    problem = straight_problem()
    tight = SpatialSloshLimits(problem.slosh.max_height_m, 1e-9)
    impossible = replace(problem, slosh=tight)
    slowest = family_member(impossible, 1e-3 * impossible.machine.max_acceleration_m_s2, None)
    poses = sample_path(impossible.path, slowest, impossible.sample_period_s)
    assert not screen_ok(impossible, linear_screen(impossible.models(), poses))
    result = plan_path(impossible, "retime", verifier=planner.linear_verifier)
    assert not result.feasible
    message = result.candidates[0].message
    assert "residual" in message and "program" not in result.candidates[0].detail


def test_a_verification_does_not_stretch_past_a_plan_already_found() -> None:
    """A member that the verification stretches (at amax it breaks the slosh limits) is
    verified once and returned failed when the stretch would reach ``slowest_s``; without
    the bound it is stretched until it passes."""
    import time

    from sloshkit.plan.path.result import verified_candidate
    from sloshkit.plan.path.search import stretcher

    problem = straight_problem()
    poses_for = stretcher(problem, family_member(problem, 10.0, None))
    calls: list[float] = []

    def counted(problem, poses, tilted):
        calls.append(poses.duration_s)
        return planner.linear_verifier(problem, poses, tilted)

    free = verified_candidate("x", problem, poses_for, 1.0, time.perf_counter(), counted, False, {})
    assert free.feasible and free.detail["stretch"] > 1.0 and len(calls) >= 2
    calls.clear()
    bound = poses_for(1.0).duration_s * 1.001
    bounded = verified_candidate(
        "x", problem, poses_for, 1.0, time.perf_counter(), counted, False, {}, bound
    )
    assert not bounded.feasible and len(calls) == 1
    # the candidate is the export that was verified, at its stretch
    assert bounded.detail["stretch"] == 1.0 and bounded.poses.duration_s == calls[0]
