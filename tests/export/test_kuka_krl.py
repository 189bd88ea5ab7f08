"""KUKA KRL (``kuka-krl``): the parser against a program typed from the KSS 8.3 manual
(tests/export/data/vendors/demo.src and demo.dat), and the writer against the parser."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sloshkit.errors import InputError
from sloshkit.export.formats.kuka_krl import dat_path, parse_krl, read_kuka_krl, write_kuka_krl
from sloshkit.export.ik import JointPath

DATA = Path(__file__).parent / "data" / "vendors"


def _joints(count: int = 6, period: float = 0.012) -> JointPath:
    q = np.cumsum(np.random.default_rng(2).normal(0.0, 0.01, (count, 6)), axis=0)
    return JointPath(np.arange(count) * period, q, 0 * q, 0 * q, tuple("abcdef"))


def _texts() -> tuple[str, str]:
    return (DATA / "demo.src").read_text(), (DATA / "demo.dat").read_text()


def test_the_manual_program_parses_with_its_time_block() -> None:
    program = parse_krl(*_texts(), "demo")
    assert program.name == "demo"
    assert program.points["XP4"] == [30.0, -60.0, 75.0, 0.0, 60.0, 15.0]  # GLOBAL AXIS
    assert [motion[2] for motion in program.motions] == [False, True, True, True, True]
    assert [motion[3] for motion in program.motions] == [None, 22.2, 20.2, None, 57.6]
    assert program.motions[3][1] == [25.0, -65.0, 78.0, 0.0, 58.0, 12.0]
    assert program.block_time_s == 3.9
    assert program.system == {"$VEL_AXIS[1]": 20.0, "$ACC_AXIS[1]": 20.0}


def test_a_part_shared_by_two_segments_cannot_be_timed_point_by_point(tmp_path: Path) -> None:
    for name in ("demo.src", "demo.dat"):
        (tmp_path / name).write_text((DATA / name).read_text())
    with pytest.raises(InputError, match="TIME_BLOCK PART > 0"):
        read_kuka_krl(tmp_path / "demo.src")


@pytest.mark.parametrize(
    ("change_src", "change_dat", "message"),
    [
        (lambda t: t.replace("DEF demo( )", "DEF other( )"), None, "DEF other but DEFDAT demo"),
        (lambda t: t.replace("SPTP XP3", "SPTP XP9"), None, "does not declare"),
        (lambda t: t.replace("ENDSPLINE\n", ""), None, "not closed"),
        (lambda t: t.replace("  TIME_BLOCK START\n", ""), None, "TIME_BLOCK"),
        (lambda t: t.replace("SPTP XP1", "LIN XP1"), None, "SPTP spline programs"),
        (None, lambda t: t.replace("A6 10.0,", ""), "lacks A6"),
        (None, lambda t: t.replace("ENDDAT", ""), "DEFDAT <name> ... ENDDAT"),
    ],
)
def test_malformed_programs_are_refused_with_the_reason(change_src, change_dat, message) -> None:
    src, dat = _texts()
    src = change_src(src) if change_src else src
    dat = change_dat(dat) if change_dat else dat
    with pytest.raises(InputError, match=message):
        parse_krl(src, dat, "demo")


def test_written_programs_read_back_to_the_written_points(tmp_path: Path) -> None:
    joints = _joints()
    out = write_kuka_krl(tmp_path / "move.src", joints, {"robot": "kr6r900"})
    assert dat_path(out).is_file()
    time, position = read_kuka_krl(out)
    assert time == pytest.approx(joints.time_s, abs=1e-9)
    assert np.abs(position - joints.position_rad).max() < np.radians(1e-5)
    program = parse_krl(out.read_text(), dat_path(out).read_text())
    assert program.block_time_s == pytest.approx(0.06)
    assert sum(motion[3] or 0.0 for motion in program.motions) == pytest.approx(100.0)
    assert program.system["$VEL_AXIS[6]"] == 10.0


def test_a_program_without_its_data_list_is_refused(tmp_path: Path) -> None:
    out = write_kuka_krl(tmp_path / "move.src", _joints(), {})
    dat_path(out).unlink()
    with pytest.raises(InputError, match=r"move\.dat"):
        read_kuka_krl(out)
