"""The rounds of the path programs with an arm: a round whose export's IK breaks a joint speed
limit that the programs' joint model met is not a verified plan, and the next round limits the
joints to the fraction the verification asks for."""

from __future__ import annotations

import numpy as np
import pytest

from sloshkit.plan.path.joints import JointMap
from sloshkit.plan.path.optimal import _joint_excess, _Rounds
from sloshkit.plan.path.planner import _example_problem
from sloshkit.plan.path.result import Verification
from sloshkit.plan.path.starts import capped_start


def _verification(violations: tuple[str, ...], stretch: float) -> Verification:
    return Verification(0.014, 0.0019, 0.0, 0.0, violations, required_stretch=stretch)


def test_the_joint_excess_is_the_verifications_stretch_only_for_a_joint_speed() -> None:
    joint = _verification(("joint speed wrist_3_joint 3.28 > 3.14 rad/s",), 1.043)
    assert _joint_excess(joint) == pytest.approx(1.043)
    slosh = _verification(("peak slosh height 15.2 > 15 mm",), 1.01)
    assert _joint_excess(slosh) == 1.0
    assert _joint_excess(_verification((), 1.0)) == 1.0


def test_a_rounds_programs_limit_the_joints_to_the_fraction_asked() -> None:
    """The transcription's joint speeds over their limits scale with 1 / fraction: the same
    timing reads 1 / 0.9 times the ratio under 0.9 of the limits."""
    problem = _example_problem()
    s = np.linspace(0.0, problem.path.length_m, 31)
    joints = JointMap(s, np.column_stack((4.0 * s, -2.0 * s)), np.array([3.14, 2.0]))
    rounds = _Rounds(problem, None, joints, None)
    limits = rounds.limits()
    timing = capped_start(problem)
    full = rounds.transcription(limits, False).iterate(timing)
    tighter = rounds.transcription(limits, False, joint_fraction=0.9).iterate(timing)
    assert np.max(np.abs(full.evaluation.joint)) > 0.0
    np.testing.assert_allclose(tighter.evaluation.joint, full.evaluation.joint / 0.9)
    assert rounds.joints is joints and joints.limits_rad_s.tolist() == [3.14, 2.0]
