"""The output-path layer (`sloshkit.io.outputs`): probed writability and all-or-nothing writes."""

from __future__ import annotations

import stat
from pathlib import Path

import pytest

from sloshkit.errors import InputError
from sloshkit.io.outputs import all_or_nothing, check_file, check_folder


def test_a_failed_block_restores_replaced_files_and_removes_new_ones(tmp_path: Path) -> None:
    old = tmp_path / "old.csv"
    old.write_text("the user's data\n")
    old.chmod(0o640)
    new = tmp_path / "new.png"
    with pytest.raises(RuntimeError), all_or_nothing(old, new, None):
        old.write_text("half written")
        new.write_bytes(b"\x89PNG")
        raise RuntimeError("the figure failed")
    assert old.read_text() == "the user's data\n"
    assert stat.S_IMODE(old.stat().st_mode) == 0o640
    assert not new.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.csv"]  # no backup left


def test_a_successful_block_keeps_everything_and_leaves_no_backup(tmp_path: Path) -> None:
    old = tmp_path / "old.csv"
    old.write_text("v1\n")
    with all_or_nothing(old, tmp_path / "new.csv"):
        old.write_text("v2\n")
        (tmp_path / "new.csv").write_text("x\n")
    assert old.read_text() == "v2\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.csv", "old.csv"]


def test_an_interruption_in_the_block_also_restores(tmp_path: Path) -> None:
    target = tmp_path / "plan.script"
    with pytest.raises(KeyboardInterrupt), all_or_nothing(target):
        target.write_text("def move():\n")
        raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(not Path("/proc/self").exists(), reason="needs Linux /proc and /sys")
@pytest.mark.parametrize("path", ["/proc/sloshkit.csv", "/sys/sloshkit.csv", "/proc/version"])
def test_virtual_file_systems_are_refused_even_for_root(path: str) -> None:
    with pytest.raises(InputError, match=r"csv|version"):
        check_file(path, "csv")


@pytest.mark.skipif(not Path("/proc/self").exists(), reason="needs Linux /proc and /sys")
def test_a_folder_under_proc_is_refused_and_the_probe_leaves_nothing(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="does not take new files"):
        check_folder("/proc/sloshkit-out", "out")
    assert check_file(tmp_path / "a.csv", "csv") == tmp_path / "a.csv"
    assert list(tmp_path.iterdir()) == []
