"""Running OpenFOAM: with `sloshkit.cfd.processes` (which starts and stops each tool), the only
modules of sloshkit that start processes.

Writes a generated case to disk, then runs blockMesh, checkMesh (poor meshes are refused),
setFields, decomposePar and interFoam (serial, or ``mpirun -np N``), feeding a progress callback
from the solver log. A solver that stops early (exit code 136 is a floating-point exception)
raises `CfdError` with the tail of the log.

Interruptions: each tool runs in a session of its own, every process of which (mpirun and its
ranks) is stopped when sloshkit is interrupted (SIGINT, SIGTERM) or dies; every finished
preparation step leaves a marker, and a resumed run restarts from the latest *complete* time
folder (every field of every processor written to its end), discarding later, half-written ones.

Network: MPI runs use shared memory between the ranks and loopback for anything else, and run
in a private network namespace (``unshare -rn``, loopback only) where the kernel allows it,
because Open MPI 4.1's out-of-band listener binds to every interface.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from functools import cache
from pathlib import Path

from sloshkit.cfd.case import MPI_LOCAL_OPTIONS
from sloshkit.cfd.prepare import (
    expected_cells,
    openfoam_environment,
    require_openfoam,
    write_case,
)
from sloshkit.cfd.processes import interruptible, start_tool
from sloshkit.cfd.state import (
    CfdError,
    CfdInterrupted,
    RunResult,
    RunStatus,
    check_mesh_quality,
    check_processes,
    discard_after,
    latest_complete_time,
    latest_time,
    tail,
    time_folders,
)
from sloshkit.cfd.summary import read_case_summary
from sloshkit.errors import InputError, ValidityWarning

__all__ = [
    "CfdError",
    "CfdInterrupted",
    "RunResult",
    "check_processes",
    "expected_cells",
    "interruptible",
    "latest_complete_time",
    "latest_time",
    "openfoam_environment",
    "require_openfoam",
    "run_case",
    "write_case",
]

TIME_LINE = re.compile(r"^Time = ([0-9.eE+-]+)$")
COURANT_LINE = re.compile(r"^Courant Number mean: \S+ max: (\S+)")


Progress = Callable[[float, float, float | None], None]  # (simulated, end, max Courant)


def _tool(case: Path, command: list[str], log_name: str) -> str:
    log = case / log_name
    holder: list[subprocess.Popen[str]] = []
    with open(log, "w", encoding="utf-8") as stream, interruptible(holder, [0.0]):
        code = start_tool(holder, command, case, stream).wait()
    text = log.read_text(encoding="utf-8", errors="replace")
    if code != 0:
        raise CfdError(f"{command[0]} failed (exit {code}):\n" + tail(text))
    return text


def _marker(case: Path, name: str) -> Path:
    return case / f".sloshkit-{name}-done"


def _prepare(case: Path, processes: int, resume: bool) -> None:
    """blockMesh, checkMesh, setFields and decomposePar, skipping the steps a resumed case
    finished (each finished step leaves a marker)."""
    if not (resume and _marker(case, "fill").is_file()):
        for name in ("mesh", "fill", "decompose"):
            _marker(case, name).unlink(missing_ok=True)
        for processor in case.glob("processor*"):
            shutil.rmtree(processor)
        shutil.rmtree(case / "postProcessing", ignore_errors=True)
        for value, folder in time_folders(case).items():
            if value > 0:
                shutil.rmtree(folder)
        _tool(case, ["blockMesh"], "log.blockMesh")
        check_mesh_quality(_tool(case, ["checkMesh", "-allGeometry"], "log.checkMesh"))
        _marker(case, "mesh").touch()
        _tool(case, ["setFields"], "log.setFields")
        _marker(case, "fill").touch()
    decomposed = _marker(case, "decompose")
    if processes > 1:
        done = decomposed.is_file() and decomposed.read_text(encoding="utf-8") == str(processes)
        if not done:
            if resume and any(time_folders(case / "processor0")):
                _check_no_progress_lost(case, processes)
            decomposed.unlink(missing_ok=True)
            for processor in case.glob("processor*"):
                shutil.rmtree(processor)
            _set_subdomains(case, processes)
            _tool(case, ["decomposePar", "-force"], "log.decomposePar")
            decomposed.write_text(str(processes), encoding="utf-8")


def _check_no_progress_lost(case: Path, processes: int) -> None:
    existing = sorted(case.glob("processor*"))
    if len(existing) != processes and latest_complete_time(case, len(existing) or 1):
        raise InputError(
            "np",
            processes,
            f"must match the case's decomposition ({len(existing)} processes) when resuming",
        )


@cache
def network_namespace_available() -> bool:
    """True when ``unshare -rn`` can start a process in a private network namespace.

    Returns
    -------
    bool

    Examples
    --------
    >>> isinstance(network_namespace_available(), bool)
    True
    """
    unshare = shutil.which("unshare")
    if unshare is None:
        return False
    probe = subprocess.run(
        [unshare, "-rn", sys.executable, "-c", LOOPBACK_UP],
        capture_output=True,
        check=False,
        timeout=30,
    )
    return probe.returncode == 0


#: Brings the loopback interface up in a fresh network namespace, then runs argv[1:].
LOOPBACK_UP = (
    "import fcntl, os, socket, struct, sys\n"
    "s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)\n"
    "fcntl.ioctl(s, 0x8914, struct.pack('16sh', b'lo', 0x1 | 0x8 | 0x40))\n"
    "s.close()\n"
    "len(sys.argv) > 1 and os.execvp(sys.argv[1], sys.argv[1:])\n"
)


def solver_command(processes: int) -> list[str]:
    """interFoam, or mpirun on this host only (see the module notes on the network).

    Parameters
    ----------
    processes : int
        MPI processes (1: serial).

    Returns
    -------
    list of str
        The command (without the namespace wrapper).

    Examples
    --------
    >>> solver_command(1)
    ['interFoam']
    """
    if processes == 1:
        return ["interFoam"]
    command = [
        "mpirun",
        "--oversubscribe",
        *MPI_LOCAL_OPTIONS,
        "-np",
        str(processes),
        "interFoam",
        "-parallel",
    ]
    if network_namespace_available():
        return ["unshare", "-rn", sys.executable, "-c", LOOPBACK_UP, *command]
    warnings.warn(
        "no private network namespace (unshare -rn failed): MPI uses shared memory and "
        "loopback, but Open MPI's out-of-band listener binds to every interface",
        ValidityWarning,
        stacklevel=2,
    )
    return command


def run_case(
    case: Path,
    processes: int = 1,
    resume: bool = False,
    progress: Progress | None = None,
) -> RunResult:
    """Mesh, initialise and run the case written in ``case``.

    ``resume`` continues from the latest complete time folder (later, half-written folders
    are discarded); preparation steps a previous run finished are not repeated.

    Parameters
    ----------
    case : Path
        A case written by `write_case`.
    processes : int
        MPI processes (1: serial).
    resume : bool
        Continue an interrupted run.
    progress : callable, optional
        Called with (simulated time, end time, largest Courant number) as the log grows.

    Returns
    -------
    RunResult

    Raises
    ------
    CfdError
        A tool failed, the mesh was refused, or the solver stopped early.
    CfdInterrupted
        A signal stopped the run.

    Examples
    --------
    >>> from pathlib import Path
    >>> from sloshkit.errors import InputError
    >>> try:  # no case there (or no OpenFOAM): the run cannot start
    ...     run_case(Path("no-such-case"))
    ... except (InputError, CfdError) as error:
    ...     print(type(error).__name__ in ("InputError", "CfdError"))
    True
    """
    require_openfoam(processes)
    summary = read_case_summary(case)
    end = float(summary["end_time_s"])
    check_processes(processes, int(summary["cells"]))
    started = time.perf_counter()
    with interruptible([], [0.0]):
        _prepare(case, processes, resume)
    start = latest_complete_time(case, processes) or 0.0
    discard_after(case, processes, start)
    command = solver_command(processes)
    log_path = case / "log.interFoam"
    simulated = [start]
    courant: float | None = None
    holder: list[subprocess.Popen[str]] = []
    with (
        open(log_path, "a" if resume else "w", encoding="utf-8") as log,
        interruptible(holder, simulated),
    ):
        process = start_tool(holder, command, case, subprocess.PIPE)
        assert process.stdout is not None
        for line in process.stdout:
            log.write(line)
            stripped = line.strip()
            match = TIME_LINE.match(stripped)
            if match:
                simulated[0] = float(match.group(1))
                if progress is not None:
                    progress(simulated[0], end, courant)
                continue
            match = COURANT_LINE.match(stripped)
            if match:
                courant = float(match.group(1))
        code = process.wait()
    wall = time.perf_counter() - started
    # interFoam stops once t >= endTime - deltaT/2 (OpenFOAM's Time::run), so a fixed step
    # that does not divide the end time ends up to half a step short of it.
    reached = simulated[0] >= end - 0.5 * float(summary["delta_t_s"]) - 1e-9
    if code != 0 or not reached:
        text = log_path.read_text(encoding="utf-8", errors="replace")
        reason = (
            "floating-point exception (the solution blew up)"
            if code in (136, -8)
            else f"exit {code}"
        )
        raise CfdError(
            f"interFoam stopped at t = {simulated[0]:.6g} s of {end:g} s ({reason}); log tail:\n"
            + tail(text)
        )
    return RunResult(
        case, RunStatus.COMPLETED, simulated[0], wall, processes, int(summary["cells"])
    )


def _set_subdomains(case: Path, processes: int) -> None:
    path = case / "system" / "decomposeParDict"
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"numberOfSubdomains\s+\d+;", f"numberOfSubdomains {processes};", text)
    text = re.sub(r"n\s+\(1 1 \d+\);", f"n               (1 1 {processes});", text)
    path.write_text(text, encoding="utf-8")
