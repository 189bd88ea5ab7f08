"""Warnings during one command: shown on stderr once each and kept for the ``--json`` output
(its ``warnings`` list), so a doubtful input never passes silently."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from sloshkit.errors import ValidityWarning

#: The warning messages of the running command, in order, each once.
RECORDED: list[str] = []


@contextmanager
def recording() -> Iterator[list[str]]:
    """Record (and still show, once each) every warning raised inside the block.

    Yields
    ------
    list of str
        The messages (`RECORDED`), in order.

    Examples
    --------
    >>> import warnings
    >>> shown = []
    >>> with warnings.catch_warnings():
    ...     warnings.showwarning = lambda message, *where: shown.append(str(message))
    ...     with recording() as found:
    ...         for _ in range(2):
    ...             warnings.warn("fill below 0.2 R", ValidityWarning)
    >>> found, shown
    (['fill below 0.2 R'], ['fill below 0.2 R'])
    """
    RECORDED.clear()
    with warnings.catch_warnings():
        warnings.simplefilter("always", ValidityWarning)
        show = warnings.showwarning

        def record(
            message: Warning | str,
            category: type[Warning],
            filename: str,
            lineno: int,
            file: Any = None,
            line: str | None = None,
        ) -> None:
            text = str(message)
            if text not in RECORDED:
                RECORDED.append(text)
                show(message, category, filename, lineno, file, line)

        warnings.showwarning = record
        yield RECORDED


def with_warnings(payload: object) -> object:
    """A JSON object payload with the command's ``warnings`` list added (other payloads as is).

    Parameters
    ----------
    payload : object
        The command's JSON payload.

    Returns
    -------
    object

    Examples
    --------
    >>> RECORDED[:] = ["shallow fill"]
    >>> with_warnings({"omega_rad_s": 29.7}), with_warnings([1, 2])
    ({'omega_rad_s': 29.7, 'warnings': ['shallow fill']}, [1, 2])
    >>> RECORDED.clear()
    """
    if not isinstance(payload, dict):
        return payload
    earlier = [str(text) for text in payload.get("warnings", [])]
    return {**payload, "warnings": earlier + [text for text in RECORDED if text not in earlier]}
