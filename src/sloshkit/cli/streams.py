"""Standard output carries the result and nothing else.

C and Fortran libraries (HiGHS prints a banner from inside ``highspy.Highs()``, before any
option can silence it), numba, MPI launchers and child processes write to file descriptor 1
directly, past ``sys.stdout``. The entry point therefore points descriptor 1 at standard error
for the whole life of the process and gives ``sys.stdout`` a private duplicate of the original
descriptor: whatever a library or a subprocess writes lands on stderr, and only what sloshkit
prints as its result reaches stdout. Descriptor 1 is never restored, because a C library's
buffered output is flushed at process exit, after the result.
"""

from __future__ import annotations

import io
import os
import sys


def protect_stdout() -> bool:
    """Route file descriptor 1 to stderr; ``sys.stdout`` keeps the original stdout.

    Call once, first thing in the console entry point. The duplicate is not inherited by
    child processes, so they, like C libraries, write to stderr.

    Returns
    -------
    bool
        Whether the guard is in place (False when stdout or stderr has no descriptor, e.g.
        replaced by a test harness, or descriptor 1 is closed).

    Examples
    --------
    >>> import contextlib, io
    >>> with contextlib.redirect_stdout(io.StringIO()):  # no descriptor: left alone
    ...     guarded = protect_stdout()
    >>> guarded
    False
    """
    try:
        stdout_fd = sys.stdout.fileno()
        stderr_fd = sys.stderr.fileno()
    except (AttributeError, OSError, ValueError):
        return False
    if stdout_fd != 1:
        return False
    try:
        sys.stdout.flush()
        result_fd = os.dup(1)
    except OSError:
        return False
    os.set_inheritable(result_fd, False)
    os.dup2(stderr_fd, 1)
    previous = sys.stdout
    sys.stdout = io.TextIOWrapper(
        io.FileIO(result_fd, "w", closefd=True),
        encoding=previous.encoding,
        errors=previous.errors,
        line_buffering=bool(getattr(previous, "line_buffering", False)),
    )
    return True


__all__ = ["protect_stdout"]
