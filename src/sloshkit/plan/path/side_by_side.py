"""Two searches of one plan at once: one in a second thread beside the caller's
(`side_by_side`; `sloshkit.plan.path.optimal.plan_programs` runs the upright rounds beside
the tilted ones).

Clarabel releases the GIL while it solves, which is about 60 % of a path program's time,
so two searches share the machine's cores instead of taking turns.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any


class Abandoned(Exception):
    """The search in front failed or was interrupted: the one beside it stops (raised by
    its progress function, `side_by_side`).

    Examples
    --------
    >>> issubclass(Abandoned, Exception) and not issubclass(Abandoned, KeyboardInterrupt)
    True
    """


def side_by_side(
    background: Callable[[Callable[[str], None]], Any],
    foreground: Callable[[Future[Any]], None],
    log: Callable[[str], None] | None,
    prefix: str,
) -> Any:
    """``background(its_log)`` in a second thread while ``foreground(job)`` runs in this one
    (it may wait for ``job.result()``); the background's result once both are done.

    The background's progress lines go to ``log`` with ``prefix``. When ``foreground``
    raises (a signal's `KeyboardInterrupt` included), the background stops at its next
    progress line (`Abandoned`) and the exception propagates; the background's own
    exceptions propagate from ``job.result()``.

    Parameters
    ----------
    background : callable
        Receives its log function; its result is returned.
    foreground : callable
        Receives the background's `concurrent.futures.Future`.
    log : callable or None
        Where the background's progress lines go.
    prefix : str
        Put before each of them.

    Returns
    -------
    object
        ``background``'s result.

    Examples
    --------
    >>> lines = []
    >>> def counted(log):
    ...     log("counting")
    ...     return sum(range(10))
    >>> side_by_side(counted, lambda job: None, lines.append, "beside: "), lines
    (45, ['beside: counting'])
    """
    stop = threading.Event()

    def background_log(line: str) -> None:
        if stop.is_set():
            raise Abandoned
        if log:
            log(prefix + line)

    with ThreadPoolExecutor(max_workers=1) as pool:
        job = pool.submit(background, background_log)
        try:
            foreground(job)
            return job.result()
        except BaseException:
            stop.set()
            raise


__all__ = ["Abandoned", "side_by_side"]
