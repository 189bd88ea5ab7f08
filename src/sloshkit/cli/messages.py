"""One formatter for everything the CLI says on stderr: never interprets user text.

Messages are rich `Text` objects (no console markup, no emoji codes, no highlighting), so a
value like ``[/red]`` or ``:x:`` typed by the user prints exactly as typed. Each message is one
line: line breaks inside user text are shown as ``\\n``.
"""

from __future__ import annotations

import sys

from rich.console import Console
from rich.text import Text


def console(stderr: bool = False) -> Console:
    """A console that prints text literally (no markup, no emoji, no highlighting).

    Parameters
    ----------
    stderr : bool
        Print on standard error instead of standard output.

    Returns
    -------
    rich.console.Console
        The console (160 columns when not a terminal and $COLUMNS is unset, so tables stay
        readable in logs).

    Examples
    --------
    >>> console().print("[red]x[/red] :x:")
    [red]x[/red] :x:
    """
    # $COLUMNS when usable (e.g. COLUMNS=80 when piping), else the terminal's width, else 160
    # columns; COLUMNS=0 or text never makes the lines vanish (sloshkit.cli.display).
    from sloshkit.cli.display import console_width

    stream = sys.stderr if stderr else sys.stdout
    width = console_width(stream)
    return Console(
        stderr=stderr,
        width=width,
        markup=False,
        emoji=False,
        highlight=False,
        soft_wrap=stderr,
    )


def one_line(text: object) -> str:
    """``text`` as one line: line breaks and other control characters made visible.

    Parameters
    ----------
    text : object
        Any value (shown with ``str``).

    Returns
    -------
    str

    Examples
    --------
    >>> one_line("a\\nb\\x1b[31m")
    'a\\\\nb\\\\x1b[31m'
    """
    shown = str(text).replace("\r\n", "\n")
    out = []
    for char in shown:
        if char == "\n":
            out.append("\\n")
        elif char == "\t":
            out.append(" ")
        elif ord(char) < 32 or ord(char) == 127:
            out.append(f"\\x{ord(char):02x}")
        else:
            out.append(char)
    return "".join(out)


def labelled(label: str, style: str, text: object) -> Text:
    """``label: text`` with only the label styled; ``text`` is taken literally.

    Parameters
    ----------
    label : str
        ``error``, ``warning``, ...
    style : str
        The rich style of the label.
    text : object
        The message (never interpreted as markup).

    Returns
    -------
    rich.text.Text

    Examples
    --------
    >>> labelled("error", "red", "[/red]").plain
    'error: [/red]'
    """
    return Text.assemble((f"{label}:", style), " ", one_line(text))


def error(target: Console, text: object) -> None:
    """Print ``error: text`` (one line) on ``target``.

    Parameters
    ----------
    target : rich.console.Console
        Usually the CLI's stderr console.
    text : object
        The message (taken literally).

    Returns
    -------
    None

    Examples
    --------
    >>> error(console(), "radius = '[/red]' is invalid")
    error: radius = '[/red]' is invalid
    """
    target.print(labelled("error", "red", text))


def warning(target: Console, text: object, label: str = "warning") -> None:
    """Print ``warning: text`` (one line) on ``target``.

    Parameters
    ----------
    target : rich.console.Console
        Usually the CLI's stderr console.
    text : object
        The message (taken literally).
    label : str
        The label (``warning``, or a warning class name).

    Returns
    -------
    None

    Examples
    --------
    >>> warning(console(), "motion file does not end at rest")
    warning: motion file does not end at rest
    """
    target.print(labelled(label, "yellow", text))
