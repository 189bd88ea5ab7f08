"""The timing family as the programs' stand-in: ``retime`` and ``tilt`` run their programs
first and their families only when the programs verify nothing."""

from __future__ import annotations

from dataclasses import replace

import pytest

from sloshkit.plan.path import planner
from sloshkit.plan.path.planner import plan_path
from sloshkit.plan.path.problem import SpatialSloshLimits, sample_path
from sloshkit.plan.path.retime import family_member
from sloshkit.plan.path.screen import linear_screen, screen_ok
from sloshkit.plan.path.search import upright_family
from tests.plan.plan_checks import straight_problem


def _recorded(monkeypatch, name: str, calls: list[str]) -> None:
    """Calls of the planner's ``name`` family, recorded in ``calls``."""
    original = getattr(planner, name)

    def recorded(problem, verifier):
        calls.append(name)
        return original(problem, verifier)

    monkeypatch.setattr(planner, name, recorded)


@pytest.mark.parametrize("method", ["retime", "tilt"])
def test_the_families_do_not_run_after_a_verified_program(monkeypatch, method) -> None:
    """``retime`` and ``tilt`` return the programs' verified plan without running their
    families (0.87 s upright on this move, the family's 1.00 s)."""
    calls: list[str] = []
    for name in ("upright_family", "tilted_family"):
        _recorded(monkeypatch, name, calls)
    problem = straight_problem()
    chosen = plan_path(problem, method).chosen
    assert chosen is not None and chosen.feasible and chosen.detail["source"] == "program"
    assert calls == []
    family = upright_family(problem)
    assert family.feasible and chosen.duration_s < family.duration_s


@pytest.mark.parametrize("method", ["retime", "tilt"])
def test_the_family_is_the_plan_when_the_programs_verify_nothing(monkeypatch, method) -> None:
    """When the programs return no verified plan, the family's member is the plan."""

    def unverified(problem, verifier, say, tilt, retime=True):
        failed = planner.PathCandidate("program", None, None, 0.0, "no round verified a plan")
        return failed, (failed if tilt else None)

    monkeypatch.setattr(planner, "_program_candidates", unverified)
    chosen = plan_path(straight_problem(), method).chosen
    assert chosen is not None and chosen.feasible and chosen.detail["source"] == "family"


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


def test_a_verification_stretches_a_member_until_it_passes() -> None:
    """A member that breaks the slosh limits at amax is stretched by the verification's
    excess and verified again until it passes; the candidate is the last export verified."""
    import time

    from sloshkit.plan.path.result import verified_candidate
    from sloshkit.plan.path.search import stretcher

    problem = straight_problem()
    poses_for = stretcher(problem, family_member(problem, 10.0, None))
    calls: list[float] = []

    def counted(problem, poses, tilted):
        calls.append(poses.duration_s)
        return planner.linear_verifier(problem, poses, tilted)

    found = verified_candidate(
        "x", problem, poses_for, 1.0, time.perf_counter(), counted, False, {}
    )
    assert found.feasible and found.detail["stretch"] > 1.0 and len(calls) >= 2
    assert found.poses.duration_s == calls[-1] > calls[0]
