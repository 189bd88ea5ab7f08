"""ABB RAPID (``abb-rapid``): the parser against a module typed from the RAPID reference
manual (tests/export/data/vendors/demo.mod), and the writer against the parser."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sloshkit.errors import InputError
from sloshkit.export.formats.abb_rapid import parse_rapid, read_abb_rapid, write_abb_rapid
from sloshkit.export.ik import JointPath

DATA = Path(__file__).parent / "data" / "vendors"


def _joints(count: int = 6, period: float = 0.02) -> JointPath:
    q = np.cumsum(np.random.default_rng(1).normal(0.0, 0.01, (count, 6)), axis=0)
    return JointPath(np.arange(count) * period, q, 0 * q, 0 * q, tuple("abcdef"))


def test_the_manual_module_parses_with_every_argument() -> None:
    module = parse_rapid((DATA / "demo.mod").read_text(), "demo.mod")
    assert module.name == "demo"
    assert module.data["calib_pos"][:2] == ("CONST", "jointtarget")
    assert module.data["p50"][2][0] == [10.0, 20.5, -30.0, 0.0, 45.0, 90.0]
    assert module.data["grip2"][0] == "PERS"
    assert len(module.data["path"][2]) == 2
    moves = module.routines["main"]
    assert [move.zone for move in moves] == ["fine", "z50", "fine", "z10", "fine"]
    assert [move.time_s for move in moves] == [None, None, 5.0, 2.5, 0.5]
    assert moves[2].switches == ("Conc", "NoEOffs") and moves[2].tool == "grip2"
    assert moves[3].target[0] == [5.0, 5.0, 5.0, 0.0, 5.0, 0.0]
    assert moves[4].target == "path{2}"


def test_a_move_without_a_time_is_refused_by_the_round_trip_reader() -> None:
    with pytest.raises(InputError, match=r"needs \\T"):
        read_abb_rapid(DATA / "demo.mod")


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda text: text.replace("ENDMODULE", ""), "MODULE <name> ... ENDMODULE"),
        (lambda text: text.replace("path{2}", "path{3}", 1), "is given 2 values"),
        (
            lambda text: text.replace("MoveAbsJ p50, v1000, z50", "MoveL p50, v1000, z50"),
            "MoveAbsJ programs only",
        ),
        (lambda text: text.replace("[[0, 0, 0, 0, 0, 0],", "[[0, 0, 0, 0, 0, 0]"), "expected"),
        (lambda text: text.replace("  ENDPROC\n", ""), "ENDPROC"),
        (lambda text: text.replace("v1000\\T:=5", "v1000\\Q:=5"), "speed option"),
    ],
)
def test_malformed_modules_are_refused_with_the_reason(change, message: str) -> None:
    with pytest.raises(InputError, match=message):
        parse_rapid(change((DATA / "demo.mod").read_text()), "demo.mod")


def test_written_modules_read_back_to_the_written_points(tmp_path: Path) -> None:
    joints = _joints()
    out = write_abb_rapid(tmp_path / "move.mod", joints, {"robot": "irb120"})
    time, position = read_abb_rapid(out)
    assert time == pytest.approx(joints.time_s, abs=1e-12)
    assert np.abs(position - joints.position_rad).max() < np.radians(1e-5)
    module = parse_rapid(out.read_text())
    moves = module.routines["move_move"]
    assert [move.zone for move in moves] == ["fine"] + ["z0"] * 4 + ["fine"]
    assert all(move.switches == ("NoEOffs",) for move in moves)
    assert module.data["move_q"][2][0][1] == [9e9] * 6
    assert out.read_text().splitlines()[1] == "  ! robot: irb120"
