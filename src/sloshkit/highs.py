"""A silent HiGHS solver: the one place that creates ``highspy.Highs``.

HiGHS 1.16 prints its banner ("Running HiGHS ... Copyright ...") on file descriptor 1 from
inside the ``Highs()`` constructor, before ``output_flag`` can be set, once per process. The
command line already keeps stdout for the result (`sloshkit.cli.streams`); this keeps the banner
out of a notebook's or a script's stdout too, by pointing descriptor 1 at the null device while
the first solver is constructed (and flushing C's buffers before it is pointed back).
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import sys
from collections.abc import Iterator
from typing import Any

_state = {"constructed": False}


@contextlib.contextmanager
def _descriptor_1_silenced() -> Iterator[None]:
    try:
        sys.stdout.flush()
        saved = os.dup(1)
    except (OSError, ValueError):  # no descriptor 1: nothing to protect
        yield
        return
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(null, 1)
        finally:
            os.close(null)
        yield
    finally:
        with contextlib.suppress(OSError, AttributeError):
            ctypes.CDLL(None).fflush(None)  # C's buffered banner goes to the null device
        os.dup2(saved, 1)
        os.close(saved)


def new_highs(threads: int = 1) -> Any:
    """A ``highspy.Highs`` with its output off, created without printing anything.

    Parameters
    ----------
    threads : int
        HiGHS threads.

    Returns
    -------
    highspy.Highs
        The solver (``output_flag`` off).

    Examples
    --------
    >>> type(new_highs()).__name__
    'Highs'
    """
    import highspy

    if _state["constructed"]:
        solver = highspy.Highs()  # type: ignore[no-untyped-call]
    else:
        with _descriptor_1_silenced():
            solver = highspy.Highs()  # type: ignore[no-untyped-call]
        _state["constructed"] = True
    solver.setOptionValue("output_flag", False)
    solver.setOptionValue("threads", threads)
    return solver


__all__ = ["new_highs"]
