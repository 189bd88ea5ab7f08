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
    """Record (and still show, once each) every warning raised inside the block."""
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
    """A JSON object payload with the command's ``warnings`` list added (other payloads as is)."""
    if not isinstance(payload, dict):
        return payload
    earlier = [str(text) for text in payload.get("warnings", [])]
    return {**payload, "warnings": earlier + [text for text in RECORDED if text not in earlier]}


#: Bare numbers are SI; beyond these a length is implausible for a container or a move [m].
PLAUSIBLE_BARE_LENGTH_M: dict[str, float] = {
    "radius": 1.0,
    "fill_height": 2.0,
    "wall_height": 2.0,
    "distance": 10.0,
}


def check_bare_length(text: str | None, value_m: float, parameter: str) -> None:
    """Warn when ``text`` is a bare number (read in metres) that is implausible for
    ``parameter``, e.g. ``--radius 20.5`` (20.5 m): most likely millimetres were meant."""
    if text is None or parameter not in PLAUSIBLE_BARE_LENGTH_M:
        return
    try:
        float(text)
    except ValueError:
        return
    if abs(value_m) > PLAUSIBLE_BARE_LENGTH_M[parameter]:
        warnings.warn(
            f"--{parameter.replace('_', '-')} {text} has no unit and is read as {value_m:g} m "
            f"(a bare number is SI); write the unit, e.g. {text}mm",
            ValidityWarning,
            stacklevel=2,
        )
