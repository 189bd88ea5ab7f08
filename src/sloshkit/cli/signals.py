"""SIGINT/SIGTERM for the CLI: stop cleanly, exit 130/143, leave no partial output.

The handler raises `Interrupted` (a `KeyboardInterrupt`, so no ``except Exception`` swallows it);
``finally`` blocks and the atomic writers then remove temporary files and staging folders.
Inside `deferred` blocks (compiled numba kernels, which must not see an exception raised in the
middle of a call) the signal is only recorded, and `check` raises it between chunks.
A signal that lands inside a callback Python cannot propagate from (a weakref or import-lock
callback, a ``__del__``) would only be printed as "Exception ignored ... Traceback"; the
unraisable hook installed with the handlers swallows that print and re-delivers the signal to
the main thread, so it is raised again at the next safe point.
"""

from __future__ import annotations

import _thread
import contextlib
import signal
import sys
from collections.abc import Callable, Iterator
from types import FrameType
from typing import Any

HANDLED = (signal.SIGINT, signal.SIGTERM)


class Interrupted(KeyboardInterrupt):
    """The process received SIGINT or SIGTERM; the exit code is 128 + signal number.

    A `KeyboardInterrupt`, so code that cleans up on Ctrl-C (the CFD runner stops its MPI
    processes and reports how to ``--resume``) does the same on SIGTERM.

    Parameters
    ----------
    signum : int
        The signal number.

    Examples
    --------
    >>> import signal
    >>> Interrupted(signal.SIGTERM).exit_code
    143
    """

    def __init__(self, signum: int) -> None:
        self.signum = signum
        super().__init__(f"interrupted by {signal.Signals(signum).name}")

    @property
    def exit_code(self) -> int:
        """130 for SIGINT, 143 for SIGTERM (the shell convention 128 + N)."""
        return 128 + self.signum


_state: dict[str, Any] = {"received": None, "depth": 0, "reported": False, "hint": None}


def _handler(signum: int, frame: FrameType | None) -> None:
    if _state["received"] is None:
        _state["received"] = signum
    if _state["depth"] == 0:
        raise Interrupted(signum)


def received() -> int | None:
    """The first signal received since `installed`, or None.

    Returns
    -------
    int or None
        The signal number.

    Examples
    --------
    >>> received() is None
    True
    """
    return _state["received"]  # type: ignore[no-any-return]


def reported() -> None:
    """Say that the command has told the user about the interruption itself (e.g. how to
    ``--resume``), so the entry point adds no second line.

    Returns
    -------
    None

    Examples
    --------
    >>> with installed():
    ...     reported()
    ...     was_reported()
    True
    """
    _state["reported"] = True


def was_reported() -> bool:
    """True when the command reported the interruption itself (see `reported`).

    Returns
    -------
    bool

    Examples
    --------
    >>> was_reported()
    False
    """
    return bool(_state["reported"])


def set_hint(hint: str | None) -> None:
    """What the interruption line says to do next (e.g. how to ``--resume``), wherever in the
    command the signal lands, instead of "no partial output was written".

    Parameters
    ----------
    hint : str or None
        The advice, or None for the default line.

    Returns
    -------
    None

    Examples
    --------
    >>> with installed():
    ...     set_hint("continue with: sloshkit cfd run --case c --resume")
    ...     hint()
    'continue with: sloshkit cfd run --case c --resume'
    """
    _state["hint"] = hint


def hint() -> str | None:
    """The advice set by `set_hint` for this command, or None.

    Returns
    -------
    str or None

    Examples
    --------
    >>> hint() is None
    True
    """
    return _state["hint"]  # type: ignore[no-any-return]


def check() -> None:
    """Raise `Interrupted` if a signal arrived (call between chunks of work).

    Returns
    -------
    None

    Examples
    --------
    >>> check()  # no signal: nothing happens
    """
    if _state["received"] is not None:
        raise Interrupted(_state["received"])


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Record signals instead of raising them inside the block; raise on leaving it.

    Yields
    ------
    None

    Examples
    --------
    >>> import os, signal
    >>> with installed():
    ...     try:
    ...         with deferred():
    ...             os.kill(os.getpid(), signal.SIGTERM)  # recorded, not raised here
    ...             inside = "still running"
    ...     except Interrupted as stop:
    ...         print(inside, stop.exit_code)
    still running 143
    """
    _state["depth"] += 1
    try:
        yield
    finally:
        _state["depth"] -= 1
    check()


def _redeliver_unraisable(previous: Callable[[Any], object]) -> Callable[[Any], None]:
    """An unraisable hook: an `Interrupted` raised where Python cannot propagate it is sent to
    the main thread again (`_thread.interrupt_main`, 10 ms later from a timer thread) instead of
    printed. Once a signal has been received, other unraisable exceptions are dropped: they are
    finalizers of objects the interruption tore down (llvmlite's ``ObjectRef.__del__`` when
    numba was compiling), and the command's one line already says it was interrupted.
    Otherwise they go to ``previous``."""

    def hook(unraisable: Any) -> None:
        if isinstance(unraisable.exc_value, Interrupted):
            # From another thread, a moment later: delivered inside this hook, the handler's
            # exception would be unraisable again.
            import threading

            later = threading.Timer(0.01, _thread.interrupt_main, (unraisable.exc_value.signum,))
            later.daemon = True
            later.start()
            return
        if _state["received"] is not None:
            return
        previous(unraisable)

    return hook


@contextlib.contextmanager
def installed(restore: bool = True) -> Iterator[None]:
    """Install the handlers for the block (main thread only) and restore the previous ones.

    With ``restore=False`` (the console entry point, which exits right after) the signals are
    ignored on leaving instead: the command has finished and written its output, and a signal
    in the last milliseconds of interpreter shutdown must not turn it into a crash (Python
    re-raises an uncaught Ctrl-C as a death by SIGINT).

    Parameters
    ----------
    restore : bool
        Restore the previous handlers on leaving (else ignore SIGINT/SIGTERM from then on).

    Yields
    ------
    None

    Examples
    --------
    >>> import signal
    >>> with installed():
    ...     signal.getsignal(signal.SIGTERM).__name__
    '_handler'
    """
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {sig: signal.getsignal(sig) for sig in HANDLED}
    previous_hook = sys.unraisablehook
    _state.update(received=None, depth=0, reported=False, hint=None)
    for sig in HANDLED:
        signal.signal(sig, _handler)
    sys.unraisablehook = _redeliver_unraisable(previous_hook)
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler if restore else signal.SIG_IGN)
        sys.unraisablehook = previous_hook
        _state.update(received=None, depth=0, reported=False, hint=None)  # nothing leaks
