"""FANUC TP (``fanuc-ls``): the parser against programs typed from the FANUC manual
(tests/export/data/vendors), the writer against the parser, and the J2/J3 interaction."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sloshkit.errors import InputError
from sloshkit.export.formats.fanuc_ls import (
    REMARK_WIDTH,
    from_controller_deg,
    parse_tp,
    read_fanuc_ls,
    to_controller_deg,
    write_fanuc_ls,
)
from sloshkit.export.ik import JointPath

DATA = Path(__file__).parent / "data" / "vendors"


def _joints(count: int = 6, period: float = 0.016, seed: int = 0) -> JointPath:
    rng = np.random.default_rng(seed)
    q = np.cumsum(rng.normal(0.0, 0.01, (count, 6)), axis=0)
    time = np.arange(count) * period
    return JointPath(time, q, 0 * q, 0 * q, tuple(f"joint_{i}" for i in range(1, 7)))


def test_the_manual_program_parses_with_every_field() -> None:
    program = parse_tp((DATA / "PICK.ls").read_text(), "PICK.ls")
    assert program.name == "PICK"
    assert program.attributes["LINE_COUNT"] == "5"
    assert program.attributes["DEFAULT_GROUP"] == "1,*,*,*,*"
    assert program.remarks == ["Move to the part "]
    kinds = [(m.kind, m.position, m.speed, m.unit, m.termination) for m in program.motions]
    assert kinds == [
        ("J", 1, 100.0, "%", "FINE"),
        ("J", 2, 500.0, "msec", "CNT100"),
        ("L", 3, 100.0, "mm/sec", "FINE"),
    ]
    assert program.positions[1] == [0.0, -1.908, -14.27, -0.0, -27.007, 0.0]
    assert sorted(program.positions) == [1, 2, 3]


def test_a_program_with_a_linear_move_is_not_a_timed_joint_program() -> None:
    with pytest.raises(InputError, match="joint moves with a time"):
        read_fanuc_ls(DATA / "PICK.ls")


def test_timed_moves_give_the_point_times_and_serial_j3() -> None:
    time, joints = read_fanuc_ls(DATA / "TIMED.ls")
    assert time.tolist() == pytest.approx([0.0, 0.5, 2.0])
    # FANUC's J3 is from the horizontal: the serial angle is J3 + J2.
    assert np.degrees(joints[:, 2]).tolist() == pytest.approx([0.0, 25.0, 40.0])
    assert np.degrees(joints[:, 1]).tolist() == pytest.approx([0.0, 20.0, 30.0])


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda text: text.replace("/END\n", ""), "ends with /END"),
        (lambda text: text.replace("   3:J P[3]", "   4:J P[3]"), "line number 4, expected 3"),
        (lambda text: text.replace("1.5sec FINE", "1.5sec CNT150"), "CNT takes 0..100"),
        (lambda text: text.replace("LINE_COUNT\t= 3", "LINE_COUNT\t= 4"), "LINE_COUNT 4"),
        (lambda text: text.replace("J P[3] 1.5sec", "J P[9] 1.5sec"), "P\\[9\\]"),
        (lambda text: text.replace("J1=    20.000 deg", "X=    20.000  mm"), "Cartesian"),
        (lambda text: text.replace("/MN", "/POS\n/MN", 1), "out of order"),
        (lambda text: text.replace("/PROG  TIMED", "/PROG  timed"), "not a TP program name"),
        (
            lambda text: text.replace("   2:J P[2] 500msec CNT100    ;", "   2:J P[2] fast ;"),
            "not a TP instruction",
        ),
    ],
)
def test_malformed_programs_are_refused_with_the_reason(change, message: str) -> None:
    text = change((DATA / "TIMED.ls").read_text())
    with pytest.raises(InputError, match=message):
        parse_tp(text, "TIMED.ls")


def test_written_programs_read_back_to_the_written_points(tmp_path: Path) -> None:
    joints = _joints()
    out = write_fanuc_ls(tmp_path / "move.ls", joints, {"robot": "lrmate200id"})
    time, position = read_fanuc_ls(out)
    assert time == pytest.approx(joints.time_s, abs=1e-12)
    assert np.abs(position - joints.position_rad).max() < np.radians(1e-5)  # 5 decimals
    program = parse_tp(out.read_text())
    assert program.name == "MOVE"
    assert [m.termination for m in program.motions] == ["FINE"] + ["CNT100"] * 4 + ["FINE"]
    assert {m.unit for m in program.motions[1:]} == {"msec"}
    assert all(len(line) <= REMARK_WIDTH for line in program.remarks)
    assert "".join(program.remarks).replace(" ", "") == "robot:lrmate200id"


def test_the_j2_j3_interaction_inverts() -> None:
    q = np.random.default_rng(3).uniform(-1.0, 1.0, (20, 6))
    assert from_controller_deg(to_controller_deg(q)) == pytest.approx(q)
    level = np.radians([[0.0, 35.0, 35.0, 0.0, 0.0, 0.0]])  # forearm kept level
    assert to_controller_deg(level)[0, 2] == pytest.approx(0.0)


def test_program_names_and_sizes_are_checked(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="program name"):
        write_fanuc_ls(tmp_path / "1move.ls", _joints(), {})
    with pytest.raises(InputError, match="more than the 2000"):
        write_fanuc_ls(tmp_path / "long.ls", _joints(2001), {})
    assert not (tmp_path / "long.ls").exists()
