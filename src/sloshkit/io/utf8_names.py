"""Names checked to be valid UTF-8 before any work: every name sloshkit reads or writes may end
up in an output (metadata, JSON, reports), and all of them are UTF-8. A file name with a byte
such as 0xff arrives in Python as a surrogate escape; it is refused with one line that names
its option."""

from __future__ import annotations

import os
from pathlib import Path

from sloshkit.errors import InputError


def require_encodable(path: Path | str, parameter: str) -> None:
    """Refuse a path whose name is not valid UTF-8 (a byte such as 0xff in it), before any work:
    every output that names a path (JSON, CSV metadata, reports) is UTF-8.

    Parameters
    ----------
    path : Path or str
        The path as given (undecodable bytes arrive as surrogate escapes).
    parameter : str
        Its option name.

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.errors import InputError
    >>> try:
    ...     require_encodable("rep\\udcff", "out")
    ... except InputError as error:
    ...     print(error.valid)
    the name is not valid UTF-8 (byte 0xff); rename it with UTF-8 characters only
    """
    text = str(path)
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as error:
        bad = text[error.start]
        code = ord(bad) - 0xDC00 if 0xDC80 <= ord(bad) <= 0xDCFF else ord(bad)
        raise InputError(
            parameter,
            os.fsencode(text),  # shown as the bytes given: b'rep\\xff'
            f"the name is not valid UTF-8 (byte 0x{code:02x}); rename it with UTF-8 "
            "characters only",
        ) from None


def require_encodable_arguments(argv: list[str]) -> None:
    """Refuse a command line holding a word that is not valid UTF-8 (file names with a byte
    such as 0xff arrive as surrogate escapes), naming its option, before any work: every name
    sloshkit reads or writes may end up in an output (metadata, JSON, reports), all UTF-8.

    Parameters
    ----------
    argv : list of str
        The command line without the program name.

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.errors import InputError
    >>> require_encodable_arguments(["export", "plan.csv", "--out", "x.csv"])
    >>> try:
    ...     require_encodable_arguments(["export", "plan\\udcff.csv", "--out", "x.csv"])
    ... except InputError as error:
    ...     print(error.parameter)
    argument
    """
    for index, word in enumerate(argv):
        option, _, value = word.partition("=") if word.startswith("--") else ("", "", word)
        if option and not value:
            continue  # an option name: its value is the next word
        previous = argv[index - 1] if index > 0 else ""
        if not option and previous.startswith("--") and "=" not in previous:
            option = previous
        parameter = option.lstrip("-").replace("-", "_") if option else "argument"
        require_encodable(value, parameter)
