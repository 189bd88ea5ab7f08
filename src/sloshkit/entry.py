"""The console entry point: signals are handled from its first instruction.

``sloshkit`` (and ``python -m sloshkit``) start here rather than in `sloshkit.cli`, whose import
brings typer and rich: until the command installs its own handlers (`sloshkit.cli.signals`),
SIGINT and SIGTERM print the interruption line and end the process with 130/143. Nothing has
been written while the command's modules are imported, so there is nothing to clean up, and a
Ctrl-C must not print a traceback out of an import (nor a SIGTERM kill the process silently).
"""

from __future__ import annotations

import os
import signal
from types import FrameType

HANDLED = (signal.SIGINT, signal.SIGTERM)


def _exit_at_once(signum: int, frame: FrameType | None) -> None:
    code = 128 + signum
    try:
        os.write(2, f"error: interrupted (exit {code}); no partial output was written\n".encode())
    finally:
        os._exit(code)


def exit_on_signal() -> None:
    """Until the command's handlers take over, SIGINT/SIGTERM end the process at once.

    Returns
    -------
    None

    Examples
    --------
    >>> saved = {sig: signal.getsignal(sig) for sig in HANDLED}
    >>> exit_on_signal()
    >>> signal.getsignal(signal.SIGINT).__name__
    '_exit_at_once'
    >>> for sig, handler in saved.items():
    ...     _ = signal.signal(sig, handler)
    """
    for sig in HANDLED:
        signal.signal(sig, _exit_at_once)


def main() -> None:
    """The ``sloshkit`` command: handle signals, then run `sloshkit.cli.main`.

    Returns
    -------
    None
        Never returns normally: exits with the command's code.

    Examples
    --------
    >>> import sys
    >>> saved, sys.argv = sys.argv, ["sloshkit", "model", "--modes", "0"]
    >>> handlers = {sig: signal.getsignal(sig) for sig in HANDLED}
    >>> try:
    ...     main()
    ... except SystemExit as stop:
    ...     code = stop.code
    ... finally:
    ...     sys.argv = saved
    ...     for sig, handler in handlers.items():
    ...         _ = signal.signal(sig, handler)
    >>> code
    2
    """
    exit_on_signal()
    from sloshkit.cli import main as command_line

    command_line()


__all__ = ["exit_on_signal", "main"]
