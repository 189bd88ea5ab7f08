"""Issue 30 as the user meets it: the process's exit code, its stderr, its memory and the files
it leaves, for the families the table of `test_hostile_inputs.py` cannot hold (byte names,
environment variables, files of a million rows, a real export of a unit-bearing pose file).
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hostile_fixtures import POSE_HEADER, make_spatial_fixtures

from sloshkit.export.plans import read_plan
from sloshkit.io.tables import MAX_TABLE_ROWS

ENTRY = [sys.executable, "-c", "from sloshkit.cli import main; main()"]


def run(
    *args: str | bytes, cwd: Path, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ENTRY, *args],
        capture_output=True,
        text=True,
        errors="replace",
        cwd=cwd,
        env={**os.environ, **(env or {})},
        timeout=300,  # a hang guard, not a speed test
        check=False,
    )


def one_error(result: subprocess.CompletedProcess[str], *words: str, code: int = 2) -> str:
    assert result.returncode == code, result.stderr
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert "Traceback" not in result.stderr + result.stdout
    for word in words:
        assert word in lines[0], lines[0]
    return lines[0]


def snapshot(folder: Path) -> dict[str, tuple[int, int]]:
    return {
        str(path.relative_to(folder)): (path.stat().st_size, path.stat().st_mtime_ns)
        for path in sorted(folder.rglob("*"))
    }


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    place = tmp_path_factory.mktemp("hardening")
    make_spatial_fixtures(place)
    return place


# -- family 6: console width ------------------------------------------------------------------


@pytest.mark.parametrize("columns", ["0", "-5", "abc", "1", "99999999"])
def test_an_unusable_console_width_keeps_every_error_line(folder: Path, columns: str) -> None:
    result = run("model", "--radius", "abc", cwd=folder, env={"COLUMNS": columns})
    one_error(result, "radius = 'abc'")


@pytest.mark.parametrize("variable", ["COLUMNS", "TERMINAL_WIDTH"])
def test_help_is_whole_with_a_zero_console_width(folder: Path, variable: str) -> None:
    result = run("--help", cwd=folder, env={variable: "0"})
    assert result.returncode == 0
    assert "simulate" in result.stdout and "export" in result.stdout
    assert len(result.stdout) > 1000


def test_warnings_reach_stderr_with_a_zero_console_width(tmp_path: Path) -> None:
    rows = "".join(f"{0.01 * k:.2f},{0.005 * k:.4f}\n" for k in range(101))
    (tmp_path / "ramp.csv").write_text("t,x\n" + rows)
    result = run("simulate", "--law", "file:ramp.csv", "--json", cwd=tmp_path, env={"COLUMNS": "0"})
    assert result.returncode == 0, result.stderr
    assert "does not end at rest" in result.stderr


# -- family 7: names that are not UTF-8 -------------------------------------------------------


@pytest.mark.parametrize(
    ("args", "option"),
    [
        ([b"reproduce", b"--out", b"rep\xff"], "out"),
        ([b"simulate", b"--csv", b"x\xff.csv"], "csv"),
        ([b"compare", b"--laws", b"quintic", b"--out", b"c\xfe"], "out"),
        ([b"export", b"plan_good.csv", b"--out", b"x\xff.csv"], "out"),
        ([b"export", b"plan_good.csv", b"--out=x\xff.csv"], "out"),
        ([b"export", b"plan\xff.csv", b"--out", b"x.csv"], "argument"),  # written as metadata
        ([b"simulate", b"--pose-file", b"p\xff.csv", b"--json"], "pose-file"),
        ([b"model", b"--liquid", b"w\xff"], "liquid"),
    ],
)
def test_an_output_name_that_is_not_utf8_is_refused_before_any_work(
    folder: Path, args: list[bytes], option: str
) -> None:
    before = snapshot(folder)
    result = subprocess.run(
        [*(part.encode() for part in ENTRY), *args],
        capture_output=True,
        text=True,
        errors="replace",
        cwd=folder,
        timeout=300,
        check=False,
    )
    line = one_error(result, f"{option} = b'", "not valid UTF-8 (byte 0x")
    assert "\\udc" not in line  # the bytes as given, not Python's surrogate escapes
    assert snapshot(folder) == before


# -- family 2: one reader, one set of bounds --------------------------------------------------


def test_a_table_past_the_row_bound_is_refused_while_read_and_in_bounded_memory(
    tmp_path: Path,
) -> None:
    """A pose file of MAX_TABLE_ROWS + 1 rows: refused at its last row, the process's peak
    memory far below what parsing it whole would take (issue 30: 5-8 GiB for 10 M rows)."""
    count = MAX_TABLE_ROWS + 1
    t = np.arange(count) * 1e-3
    lines = "\n".join(f"{v:.3f},0,0,0,0,0,0,1" for v in t)
    (tmp_path / "long.csv").write_text(POSE_HEADER + "\n" + lines + "\n")
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    result = run("simulate", "--pose-file", "long.csv", cwd=tmp_path)
    one_error(result, "--pose-file = 'long.csv'", f"more than {MAX_TABLE_ROWS} data rows")
    peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if peak_kib > before:  # this child set the peak: it is the child's own
        assert peak_kib < 1_000_000, peak_kib  # < 1 GiB (kB on Linux)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["long.csv"]


def test_export_reads_pose_headers_with_units_as_every_command(tmp_path: Path) -> None:
    """The same poses in SI and in ms/mm/deg headers export the same stream; a quaternion of
    norm 1.0005 (inside the 1e-3 tolerance of every other reader) is accepted."""
    t = np.arange(0.0, 1.0 + 1e-9, 0.004)
    s = t / t[-1]
    x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    si = "".join(f"{a:.6f},{b:.9f},0,0,0,0,0,1.0005\n" for a, b in zip(t, x, strict=True))
    (tmp_path / "si.csv").write_text(POSE_HEADER + "\n" + si)
    mm = "".join(f"{1e3 * a:.6f},{1e3 * b:.9f},0,0,0,0,0\n" for a, b in zip(t, x, strict=True))
    (tmp_path / "mm.csv").write_text("t [ms],x [mm],y [mm],z [mm],roll [deg],pitch,yaw\n" + mm)
    first, second = read_plan(tmp_path / "si.csv"), read_plan(tmp_path / "mm.csv")
    np.testing.assert_allclose(first.time_s, second.time_s, atol=1e-12)
    np.testing.assert_allclose(first.position_m, second.position_m, rtol=0, atol=1e-9)  # printed
    np.testing.assert_allclose(first.quaternion_xyzw, second.quaternion_xyzw, atol=1e-12)
    # No plan header: the model is given (issue 24: no silent default container).
    result = run(
        "export", "mm.csv", "--out", "mm.poses.csv", "--radius", "20.5mm", "--json", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "mm.poses.csv").is_file()


def test_a_one_d_plan_with_units_in_its_header_exports_as_its_si_twin(folder: Path) -> None:
    si, mm = read_plan(folder / "plan_good.csv"), read_plan(folder / "plan_mm.csv")
    np.testing.assert_allclose(si.position_m, mm.position_m, atol=1e-12)
    np.testing.assert_allclose(si.acceleration_m_s2, mm.acceleration_m_s2, atol=1e-9)


# -- family 9: outputs over inputs ------------------------------------------------------------


def test_export_never_replaces_its_input_nor_a_users_file(tmp_path: Path, folder: Path) -> None:
    for name in ("plan_good.csv", "plan_good.script", "plan_user.csv", "plan_user.poses.csv"):
        (tmp_path / name).write_bytes((folder / name).read_bytes())
    before = snapshot(tmp_path)
    one_error(run("export", "plan_good.script", "--format", "urscript", cwd=tmp_path), "out")
    one_error(run("export", "plan_good.csv", "--out", "plan_good.csv", cwd=tmp_path), "out")
    one_error(run("export", "plan_user.csv", cwd=tmp_path), "not written by sloshkit")
    assert snapshot(tmp_path) == before
    # its own output, at the default path, may be rewritten; a file named by --out is replaced
    model = ("--radius", "20.5mm")  # the fixtures carry no plan header (issue 24)
    assert run("export", "plan_good.csv", *model, cwd=tmp_path).returncode == 0
    assert run("export", "plan_good.csv", *model, cwd=tmp_path).returncode == 0
    result = run("export", "plan_user.csv", "--out", "plan_user.poses.csv", *model, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "format: sloshkit pose-csv" in (tmp_path / "plan_user.poses.csv").read_text()


def test_an_output_that_is_a_link_to_the_input_is_refused(tmp_path: Path, folder: Path) -> None:
    (tmp_path / "plan.csv").write_bytes((folder / "plan_good.csv").read_bytes())
    (tmp_path / "other.csv").symlink_to(tmp_path / "plan.csv")
    one_error(run("export", "plan.csv", "--out", "other.csv", cwd=tmp_path), "is the input")


# -- family 11: library log lines stay off stderr -----------------------------------------------


def test_library_log_records_never_reach_stderr(tmp_path: Path) -> None:
    code = (
        "import logging\n"
        "from sloshkit.cli.app import run\n"
        "run(['--version'])\n"
        "logging.getLogger('matplotlib.font_manager').warning('building the font cache')\n"
        "logging.getLogger('numba.core').error('a numba note')\n"
        "import distributed\n"
        "from sloshkit.cfd.scheduler import quiet_dask_logging\n"
        "quiet_dask_logging()  # distributed installs its own stderr handler when imported\n"
        "logging.getLogger('distributed.worker').warning('worker chatter')\n"
        "logging.getLogger('distributed').error('scheduler chatter')\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=False
    )
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
