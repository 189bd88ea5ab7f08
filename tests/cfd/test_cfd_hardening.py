"""CFD faults and interruptions for real (issue #16): a run killed by a signal at an arbitrary
moment resumes from its latest complete time folder and ends where an uninterrupted run ends;
bad --np values, missing mpirun, empty or unfinished cases end in one line and exit 2 without
leaving files; MPI opens no socket reachable from other hosts."""

from __future__ import annotations

import json
import os
import random
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from conftest import run_entry_point

from sloshkit.cfd.pipeline import read_finished_signals
from sloshkit.cfd.results import read_function_object, read_signals
from sloshkit.cfd.run import check_processes
from sloshkit.errors import InputError, ValidityWarning

needs_openfoam = pytest.mark.skipif(
    shutil.which("interFoam") is None, reason="OpenFOAM is not installed (make test installs it)"
)
ENTRY = [sys.executable, "-c", "from sloshkit.cli import main; main()"]
TINY = ["--cells-per-radius", "4", "--delta-t", "2ms", "--tilt", "4deg"]


def one_line_error(result: subprocess.CompletedProcess[str], *words: str) -> None:
    assert result.returncode == 2, result.stdout + result.stderr
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, result.stderr
    assert "Traceback" not in result.stderr
    for word in words:
        assert word in lines[0], lines[0]


def test_np_limits_refuse_absurd_values_and_warn_beyond_the_cores():
    check_processes(2, 768, cores=2)
    with pytest.warns(ValidityWarning, match="more than the 2 cores"):
        check_processes(3, 15_000, cores=2)
    with pytest.raises(InputError, match=r"np = 64 is invalid: must be between 1 and 8"):
        check_processes(64, 15_000, cores=2)
    with pytest.raises(InputError, match=r"at least 250 cells each"):
        check_processes(4, 768, cores=2)


def test_cli_refuses_absurd_np_without_writing_anything(tmp_path):
    result = run_entry_point("cfd", "run", "--case", str(tmp_path / "c"), "--np", "64", *TINY)
    one_line_error(result, "np = 64", "must be between 1 and")
    assert not (tmp_path / "c").exists()


def test_cli_refuses_a_bad_surface_refinement_without_writing_anything(tmp_path):
    case = str(tmp_path / "c")
    result = run_entry_point("cfd", "run", "--case", case, "--surface-refinement", "0", *TINY)
    one_line_error(result, "--surface-refinement = '0'", "must be between 1 and 8")
    assert not (tmp_path / "c").exists()


@needs_openfoam
def test_missing_mpirun_is_one_line_and_leaves_no_files(tmp_path):
    tools = tmp_path / "bin"
    tools.mkdir()
    for tool in ("blockMesh", "checkMesh", "setFields", "interFoam", "decomposePar"):
        (tools / tool).symlink_to(shutil.which(tool))
    environment = {**os.environ, "PATH": f"{tools}{os.pathsep}{Path(sys.executable).parent}"}
    result = subprocess.run(
        [*ENTRY, "cfd", "run", "--case", str(tmp_path / "c"), "--np", "2", *TINY],
        capture_output=True,
        text=True,
        env=environment,
        check=False,
    )
    one_line_error(result, "np = 2", "needs mpirun")
    assert not (tmp_path / "c").exists()


def test_validate_reuse_of_an_empty_folder_is_one_line(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    result = run_entry_point("cfd", "validate", "--case", str(empty), "--reuse")
    one_line_error(result, "is not a sloshkit CFD case")
    assert list(empty.iterdir()) == []


def test_reproduce_does_not_start_a_run_in_a_named_empty_case(tmp_path):
    empty = tmp_path / "emptydir"
    empty.mkdir()
    started = time.perf_counter()
    result = run_entry_point("reproduce", "--cfd-case", str(empty), "--out", str(tmp_path / "r"))
    one_line_error(result, "cfd-case", "must be a finished sloshkit CFD case")
    assert time.perf_counter() - started < 60
    assert list(empty.iterdir()) == []
    assert not (tmp_path / "r").exists()


def test_overwrite_never_empties_a_folder_that_is_not_a_sloshkit_case(tmp_path):
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / "thesis.tex").write_text("precious")
    result = run_entry_point("cfd", "run", "--case", str(folder), "--overwrite", *TINY)
    one_line_error(result, "not a sloshkit case")
    assert (folder / "thesis.tex").read_text() == "precious"


def _run_cli(case: Path, *extra: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [*ENTRY, "cfd", "run", "--case", str(case), *TINY, *extra],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


@needs_openfoam
def test_unwritten_case_is_reported_unfinished(tmp_path):
    from sloshkit.cfd.case import CaseSpec
    from sloshkit.cfd.run import write_case
    from sloshkit.model.liquids import get_liquid

    spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=4, end_time_s=0.3)
    write_case(spec, tmp_path / "c")
    result = run_entry_point("cfd", "analyse", str(tmp_path / "c"))
    one_line_error(result, "is unfinished (simulated 0 of 0.3 s)", "--resume")


OPTIONS = ("--end-time", "0.3s", "--np", "2")


@pytest.fixture(scope="module")
def reference_run(tmp_path_factory):
    """An uninterrupted 2-rank run, and how long it took [s]."""
    reference = tmp_path_factory.mktemp("cfd") / "reference"
    completed = _run_cli(reference, *OPTIONS)
    started = _started_work(completed, reference)
    _, err = completed.communicate(timeout=600)
    assert completed.returncode == 0, err
    return reference, time.perf_counter() - started


def _started_work(process: subprocess.Popen[str], case: Path) -> float:
    """When the command began writing its case (after Python's start-up and imports)."""
    while process.poll() is None and not any(
        entry.name.startswith((case.name, f".{case.name}.staging"))
        for entry in case.parent.iterdir()
    ):
        time.sleep(0.01)
    return time.perf_counter()


@needs_openfoam
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_run_killed_at_an_arbitrary_moment_resumes_to_the_same_result(
    tmp_path, reference_run, signum
):
    """A real 2-rank run is stopped by a signal at a random moment (from meshing to the last
    steps); `--resume` completes it, and its signals match an uninterrupted run."""
    options = OPTIONS
    reference, duration = reference_run
    delay = random.uniform(0.05, 0.9) * duration
    case = tmp_path / "interrupted"
    process = _run_cli(case, *options)
    _started_work(process, case)
    time.sleep(delay)
    process.send_signal(signum)
    _, err = process.communicate(timeout=120)
    context = f"signal {signum} after {delay:.2f} s of a {duration:.2f} s run: {err}"
    if process.returncode != 0:  # the run had not finished when the signal came
        assert process.returncode == 128 + signum, context
        assert "Traceback" not in err and "--resume" in err, context
        # One line says what happened; warnings printed before the signal came may precede it.
        lines = [
            line
            for line in err.splitlines()
            if line.strip() and not line.lstrip().startswith("warning:")
        ]
        assert len(lines) == 1, context
        # Nothing of the run is left running.
        assert _processes_working_in(case) == [], context
        if (case / "sloshkit-case.json").is_file() and _simulated(case) < 0.3 - 1e-6:
            unfinished = run_entry_point("cfd", "analyse", str(case))
            one_line_error(unfinished, "is unfinished")
    resumed = run_entry_point("cfd", "run", "--case", str(case), "--resume", "--json")
    if not (case / "sloshkit-case.json").is_file():  # stopped before the case was written
        resumed = run_entry_point("cfd", "run", "--case", str(case), *TINY, *options, "--json")
    assert resumed.returncode == 0, context + resumed.stderr
    assert json.loads(resumed.stdout)["simulated_s"] == pytest.approx(0.3)
    ours, theirs = read_finished_signals(case), read_signals(reference)
    assert np.all(np.diff(ours.time_s) > 0), context
    common = np.linspace(0.0, 0.3, 151)
    difference = np.interp(common, ours.time_s, ours.elevation_m) - np.interp(
        common, theirs.time_s, theirs.elevation_m
    )
    amplitude = float(np.max(np.abs(theirs.elevation_m)))
    assert np.max(np.abs(difference)) < 0.02 * amplitude, context
    # Fields (and grad(alpha.water)) are written at write times only.
    times = sorted(p.name for p in (case / "processor0").iterdir() if p.name[0].isdigit())
    assert len(times) <= 10, times


def _simulated(case: Path) -> float:
    """How far the solver got: its last probe time (0 without any) [s]. Not the end of
    `read_signals`' series, which is resampled at the median step and may stop a step short."""
    try:
        return float(read_function_object(case, "wallProbes", "alpha.water")[-1, 0])
    except (InputError, IndexError):
        return 0.0


def _processes_working_in(folder: Path) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if os.readlink(entry / "cwd") == str(folder):
                    found.append(int(entry.name))
            except OSError:
                continue
    return found


def _process_tree(root: int) -> list[int]:
    tree, stack = [], [root]
    while stack:
        pid = stack.pop()
        tree.append(pid)
        try:
            for task in Path(f"/proc/{pid}/task").iterdir():
                stack.extend(int(child) for child in (task / "children").read_text().split())
        except OSError:
            continue
    return tree


LOOPBACK = ("0100007F", "00000000000000000000000001000000")  # 127.0.0.1, ::1 in /proc/net


def _exposed_sockets(pid: int) -> list[str]:
    """Listening TCP and bound UDP sockets of ``pid`` reachable from another host: bound to a
    non-loopback address in a network namespace that has an interface besides loopback."""
    proc = Path(f"/proc/{pid}")
    try:
        inodes = {
            os.readlink(fd)[8:-1]
            for fd in (proc / "fd").iterdir()
            if os.readlink(fd).startswith("socket:[")
        }
        interfaces = [
            line.split(":")[0].strip()
            for line in (proc / "net" / "dev").read_text().splitlines()[2:]
        ]
        tables = {
            name: (proc / "net" / name).read_text() for name in ("tcp", "tcp6", "udp", "udp6")
        }
    except OSError:
        return []
    exposed = []
    for name, text in tables.items():
        for line in text.splitlines()[1:]:
            fields = line.split()
            address, state, inode = fields[1], fields[3], fields[9]
            if inode not in inodes or (name.startswith("tcp") and state != "0A"):
                continue
            if address.split(":")[0] in LOOPBACK:
                continue
            if set(interfaces) <= {"lo"}:
                continue  # a private network namespace: nothing outside can reach it
            exposed.append(f"{name} {address} (pid {pid}, interfaces {interfaces})")
    return exposed


@needs_openfoam
def test_mpi_run_opens_no_socket_reachable_from_other_hosts(tmp_path):
    process = _run_cli(tmp_path / "c", "--end-time", "0.3s", "--np", "2")
    exposed: list[str] = []
    ranks_seen = 0
    try:
        while process.poll() is None:
            for pid in _process_tree(process.pid):
                exposed += _exposed_sockets(pid)
                try:
                    if Path(f"/proc/{pid}/comm").read_text().strip() == "interFoam":
                        ranks_seen += 1
                except OSError:
                    pass
            time.sleep(0.1)
    finally:
        process.communicate(timeout=300)
    assert process.returncode == 0
    assert ranks_seen > 0, "the MPI ranks were never seen running"
    assert exposed == []


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="Open MPI is not installed")
def test_stopping_mpirun_waits_for_every_rank(tmp_path):
    """Open MPI puts each rank in a process group of its own and mpirun may exit before its
    ranks: the stop waits for (and if need be kills) every process of the tool's session."""
    from sloshkit.cfd import processes
    from sloshkit.cfd.run import solver_command

    holder: list[subprocess.Popen[str]] = []
    command = [*solver_command(2)[:-4], "-np", "2", "sleep", "60"]  # as interFoam runs
    process = processes.start_tool(holder, command, tmp_path, subprocess.DEVNULL)
    deadline = time.monotonic() + 30
    while len(processes.session_members(process.pid)) < 3 and time.monotonic() < deadline:
        time.sleep(0.05)
    ranks = set(processes.session_members(process.pid)) - {process.pid}
    assert len(ranks) == 2
    assert all(os.getpgid(rank) != process.pid for rank in ranks)  # why killpg is not enough
    processes.stop_session(process, grace_s=5.0)
    assert processes.session_members(process.pid) == []
    assert _processes_working_in(tmp_path) == []


def test_a_signal_while_a_tool_starts_still_stops_the_tool(tmp_path, monkeypatch):
    """A stop signal that lands between the fork and the tool's registration is held back until
    the tool is registered, so the interruption stops it instead of leaving it running."""
    from sloshkit.cfd import processes

    real_popen = subprocess.Popen
    started: list[subprocess.Popen[str]] = []

    def popen_then_signal(*args, **kwargs):
        process = real_popen(*args, **kwargs)
        started.append(process)
        os.kill(os.getpid(), signal.SIGTERM)  # the worst moment: before Popen returns
        deadline = time.monotonic() + 0.5
        while time.monotonic() < deadline:  # bytecode, where Python runs a pending handler
            pass
        return process

    # Another thread, as the CLI's progress bar has: a signal blocked in the main thread is
    # taken by it, and Python runs the handler in the main thread all the same.
    other = threading.Thread(target=threading.Event().wait, args=(10.0,), daemon=True)
    other.start()
    monkeypatch.setattr(processes.subprocess, "Popen", popen_then_signal)
    holder: list[subprocess.Popen[str]] = []
    with pytest.raises(processes.CfdInterrupted), processes.interruptible(holder, [0.0]):
        processes.start_tool(holder, ["sleep", "60"], tmp_path, subprocess.DEVNULL)
        time.sleep(5)  # not reached: the held-back signal is delivered on registration
    assert holder == started and started[0].poll() is not None
    assert _processes_working_in(tmp_path) == []
