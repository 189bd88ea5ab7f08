"""The rounds of the path programs: with an arm, a round whose export's IK breaks a joint
speed limit that the programs' joint model met is not a verified plan, and the next round
limits the joints to the fraction the verification asks for; each export is verified once;
`tilt` alone searches tilted from the capped timing and is never slower than the upright
programs."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from sloshkit.plan.path.joints import JointMap, joint_excess
from sloshkit.plan.path.minimum_time import knot_count
from sloshkit.plan.path.optimal import TILTED_KNOT_SPACING_S, plan_programs
from sloshkit.plan.path.problem import PathProblem
from sloshkit.plan.path.program import PathProgram, ProgramLimits
from sloshkit.plan.path.result import Verification, verify
from sloshkit.plan.path.starts import capped_start
from sloshkit.plan.path.transcription import SplineTranscription
from tests.plan.plan_checks import straight_problem


@pytest.fixture
def straight() -> PathProblem:
    return straight_problem()


def _verification(violations: tuple[str, ...], stretch: float) -> Verification:
    return Verification(0.014, 0.0019, 0.0, 0.0, violations, required_stretch=stretch)


def test_the_joint_excess_is_the_verifications_stretch_only_for_a_joint_speed() -> None:
    joint = _verification(("joint speed wrist_3_joint 3.28 > 3.14 rad/s",), 1.043)
    assert joint_excess(joint) == pytest.approx(1.043)
    slosh = _verification(("peak slosh height 15.2 > 15 mm",), 1.01)
    assert joint_excess(slosh) == 1.0
    assert joint_excess(_verification((), 1.0)) == 1.0


def test_a_program_with_scaled_joint_limits_reads_their_ratio_scaled(straight) -> None:
    """The transcription's joint speeds over their limits scale with 1 / fraction: the same
    timing reads 1 / 0.9 times the ratio under 0.9 of the limits."""
    s = np.linspace(0.0, straight.path.length_m, 31)
    joints = JointMap(s, np.column_stack((4.0 * s, -2.0 * s)), np.array([3.14, 2.0]))
    limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.01, 0.002)
    timing = capped_start(straight)

    def joint_ratios(joint_map: JointMap) -> np.ndarray:
        program = PathProgram(
            straight.path, straight.models(), limits, straight.sample_period_s, joints=joint_map
        )
        return SplineTranscription(program).iterate(timing).evaluation.joint

    full, tighter = joint_ratios(joints), joint_ratios(joints.scaled(0.9))
    assert np.max(np.abs(full)) > 0.0
    np.testing.assert_allclose(tighter, full / 0.9)
    assert joints.limits_rad_s.tolist() == [3.14, 2.0]


def test_each_export_is_verified_once(straight) -> None:
    """A round's plan is verified in the round and again as the returned candidate; the second
    is the first's verification (with an arm, a verification is mostly the export's IK)."""
    seen: list[bytes] = []

    def counted(problem, poses, tilted):
        seen.append(poses.position_m.tobytes() + poses.time_s.tobytes() + bytes([tilted]))
        return verify(problem, poses, tilted)

    upright, _ = plan_programs(straight, counted)
    assert upright.feasible and upright.detail["rounds"]
    assert seen and len(set(seen)) == len(seen)


def test_a_program_started_from_the_last_ones_rows_has_the_same_optimum(straight) -> None:
    """The rows a program needed are carried to the next (at its N's samples): the program's
    optimum is the same as from the first rows alone (the generation adds whatever binds),
    in no more solves."""
    limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.01, 0.002)
    program = PathProgram(straight.path, straight.models(), limits, straight.sample_period_s)
    timing = capped_start(straight)
    fresh = SplineTranscription(program)
    alone = fresh.step(timing, fresh.iterate(timing), 0.02)
    carried = SplineTranscription(program)
    other = timing.on_steps(timing.steps + 7)
    carried.step(other, carried.iterate(other), 0.02)
    before = carried.programs
    again = carried.step(timing, carried.iterate(timing), 0.02)
    assert alone is not None and again is not None
    assert again.predicted == pytest.approx(alone.predicted, abs=1e-6)
    assert carried.programs - before <= fresh.programs


@pytest.mark.parametrize("max_tilt_deg", [0.5, 30.0])
def test_tilt_alone_is_never_slower_than_the_upright_programs(straight, max_tilt_deg) -> None:
    """Without ``retime`` wanted, the tilted search starts from the capped timing instead of
    the upright plan, and the upright rounds only look below the tilted plan: with a tilt that
    barely helps (0.5 deg) as with a free one, the tilted plan is verified and no longer than
    the upright programs' plan (and shorter with 30 deg, its splines with the large-angle
    tilted rounds' finer knots)."""
    problem = replace(straight, max_tilt_rad=math.radians(max_tilt_deg))
    upright, _ = plan_programs(problem, verify)
    none, tilted = plan_programs(problem, verify, tilt=True, retime=False)
    assert none is None
    assert upright.feasible and tilted.feasible
    assert tilted.duration_s <= upright.duration_s + 1e-9
    if max_tilt_deg > 10.0:
        assert tilted.detail["tilted"] and tilted.duration_s < 0.9 * upright.duration_s
        fine = knot_count(tilted.duration_s, TILTED_KNOT_SPACING_S)
        assert tilted.detail["knots"] == fine > upright.detail["knots"]
