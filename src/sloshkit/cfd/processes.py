"""Starting and stopping OpenFOAM's processes so that nothing outlives an interruption.

Each tool (blockMesh, interFoam, mpirun, ...) leads a session of its own
(``start_new_session``), gets SIGTERM if sloshkit dies (Linux ``PR_SET_PDEATHSIG``), and is
registered before any stop signal can be delivered (signals are held back while it starts).
Stopping waits for every process of the tool's session: Open MPI's mpirun puts each rank in a
process group of its own and may exit before its ranks, so a process-group signal alone leaves
ranks running. With `sloshkit.cfd.run`, the only modules of sloshkit that start processes.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import threading
import time
from pathlib import Path
from typing import Any

from sloshkit.cfd.prepare import openfoam_environment
from sloshkit.cfd.state import CfdInterrupted

__all__ = ["interruptible", "session_members", "start_tool", "stop_session"]


def _set_parent_death_signal() -> None:  # pragma: no cover - runs in the child
    """Linux: the tool gets SIGTERM when sloshkit dies (even by SIGKILL)."""
    with contextlib.suppress(Exception):
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


@contextlib.contextmanager
def interruptible(process_holder: list[subprocess.Popen[str]], where: list[float]) -> Any:
    """Turn SIGTERM, SIGHUP and SIGINT into `CfdInterrupted` inside the block; on any exit,
    stop the process groups of the tools in ``process_holder`` (mpirun and its ranks) and wait
    for them. ``where[0]`` is the simulated time reported with the interruption.

    Parameters
    ----------
    process_holder : list of subprocess.Popen
        The running tools (filled by the caller while the block runs).
    where : list of float
        ``where[0]``: the simulated time to report.

    Returns
    -------
    context manager

    Raises
    ------
    CfdInterrupted
        On SIGTERM, SIGHUP or SIGINT inside the block.

    Examples
    --------
    >>> with interruptible([], [0.0]):
    ...     pass
    """
    previous: dict[signal.Signals, Any] = {}

    def handler(signum: int, frame: Any) -> None:
        raise CfdInterrupted(signum, where[0])

    in_main = threading.current_thread() is threading.main_thread()
    if in_main:
        for signum in (signal.SIGTERM, signal.SIGHUP):
            previous[signum] = signal.signal(signum, handler)
    try:
        yield
    except KeyboardInterrupt:
        raise CfdInterrupted(signal.SIGINT, where[0]) from None
    finally:
        for process in process_holder:
            stop_session(process)
        for number, old in previous.items():
            signal.signal(number, old)


def stop_session(process: subprocess.Popen[str], grace_s: float = 10.0) -> None:
    """Stop a tool and everything it started, and wait until they are gone.

    SIGTERM to the tool's process group (mpirun forwards it to its ranks), then a wait for every
    live process of the tool's session; after ``grace_s``, SIGKILL to each of them and a wait of
    up to 5 s more.

    Parameters
    ----------
    process : subprocess.Popen
        A tool started by `start_tool` (it leads its own session).
    grace_s : float
        How long the tool and its children may take to stop after SIGTERM [s].

    Returns
    -------
    None

    Examples
    --------
    >>> import sys
    >>> holder = []
    >>> tool = start_tool(holder, [sys.executable, "-c", "import time; time.sleep(30)"],
    ...                   Path("."), subprocess.DEVNULL)
    >>> stop_session(tool)
    >>> tool.returncode == -signal.SIGTERM and session_members(tool.pid) == []
    True
    """
    session = process.pid
    if process.poll() is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(session, signal.SIGTERM)
    deadline = time.monotonic() + grace_s
    for kill in (False, True):
        if kill:
            for pid in [*session_members(session), process.pid]:
                with contextlib.suppress(ProcessLookupError, PermissionError):
                    os.kill(pid, signal.SIGKILL)
            deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline:
            with contextlib.suppress(subprocess.TimeoutExpired):
                process.wait(timeout=0.05)
            if process.returncode is not None and not session_members(session):
                return


def session_members(session: int) -> list[int]:
    """The live (not zombie) processes of a session, read from ``/proc`` (Linux).

    Parameters
    ----------
    session : int
        Session id (the pid of the process that started the session).

    Returns
    -------
    list of int
        Their pids; empty where ``/proc`` cannot be read.

    Examples
    --------
    >>> session_members(-1)
    []
    """
    members = []
    with contextlib.suppress(OSError):
        for entry in os.scandir("/proc"):
            if not entry.name.isdigit():
                continue
            try:
                with open(f"/proc/{entry.name}/stat", encoding="ascii", errors="replace") as f:
                    stat = f.read()
            except OSError:
                continue
            # "pid (comm) state ppid pgrp session ...": comm may hold spaces and parentheses.
            fields = stat[stat.rfind(")") + 2 :].split()
            if len(fields) > 3 and fields[0] != "Z" and int(fields[3]) == session:
                members.append(int(entry.name))
    return members


_STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM, signal.SIGHUP}


def start_tool(
    holder: list[subprocess.Popen[str]], command: list[str], case: Path, stdout: Any
) -> subprocess.Popen[str]:
    """Start a tool in ``case`` and append it to ``holder``, with stop signals held back
    meanwhile: an interruption cannot fall between the fork and the tool's registration (it
    would leave the tool running unseen); a signal that came meanwhile is delivered right after.

    Parameters
    ----------
    holder : list of subprocess.Popen
        Where the tool is registered (the list given to `interruptible`).
    command : list of str
        The command line.
    case : Path
        Working directory.
    stdout : file or int
        Where the tool's output (stdout and stderr) goes.

    Returns
    -------
    subprocess.Popen
        The running tool, leader of its own session, with the OpenFOAM environment.

    Examples
    --------
    >>> import sys
    >>> holder = []
    >>> tool = start_tool(holder, [sys.executable, "-c", "pass"], Path("."), subprocess.DEVNULL)
    >>> tool.wait(), holder == [tool]
    (0, True)
    """
    # Held back at the Python level, not with pthread_sigmask: a signal blocked in the main
    # thread is taken by another thread (rich's progress refresher), and Python then runs the
    # handler in the main thread anyway, possibly inside Popen after the fork (CI saw mpirun
    # and its ranks outlive a SIGTERM that way).
    held: list[int] = []
    previous: dict[signal.Signals, Any] = {}
    if threading.current_thread() is threading.main_thread():
        for signum in _STOP_SIGNALS:
            previous[signum] = signal.signal(signum, lambda number, frame: held.append(number))
    try:
        process = subprocess.Popen(
            command,
            cwd=case,
            env=openfoam_environment(),
            stdout=stdout,
            stderr=subprocess.STDOUT,
            text=True,
            bufsize=1,
            start_new_session=True,
            preexec_fn=_set_parent_death_signal,
        )
        holder.append(process)
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        if held:
            signal.raise_signal(held[0])  # now the caller's handler stops the registered tool
    return process
