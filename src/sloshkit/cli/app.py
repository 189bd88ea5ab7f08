"""The ``sloshkit`` command line (typer + rich): parses units, calls the core, prints results.

Exit codes: 0 success; 1 no feasible result (e.g. a plan that cannot meet the limits);
2 invalid input (one line on stderr naming the parameter, value and valid range).
"""

from __future__ import annotations

import os
import sys
import warnings
from typing import Annotated

import typer
from rich.console import Console

from sloshkit.cli.notes import recording
from sloshkit.errors import InputError, ValidityWarning

app = typer.Typer(
    name="sloshkit",
    help=(
        "Sloshing of liquids in moving containers: equivalent model, simulation, motion "
        "planning.\n\nExample: sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C"
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


#: Terminal width: the terminal's, or $COLUMNS, else 160 when writing to a pipe or file.
stdout = Console(width=None if sys.stdout.isatty() or "COLUMNS" in os.environ else 160)


def _version(value: bool) -> None:
    if value:
        from sloshkit import __version__

        stdout.print(f"sloshkit {__version__}", highlight=False)
        raise typer.Exit()


@app.callback()
def _root(
    ctx: typer.Context,
    version: Annotated[
        bool,
        typer.Option("--version", callback=_version, is_eager=True, help="Print the version."),
    ] = False,
) -> None:
    """sloshkit: the sloshing toolkit (see the README for a tour)."""
    ctx.with_resource(recording())


stderr = Console(stderr=True, soft_wrap=True)


def _show_warning(message, category, filename, lineno, file=None, line=None):  # type: ignore[no-untyped-def]
    prefix = "warning" if category is ValidityWarning else category.__name__
    stderr.print(f"[yellow]{prefix}:[/yellow] {message}", highlight=False)


def main(application: typer.Typer | None = None) -> None:
    """Run ``application`` (default `app`); user mistakes become one line on stderr and exit
    code 2. `sloshkit.cli.main` is the entry point: it imports the command being run first."""
    warnings.showwarning = _show_warning
    try:
        (application or app)()
    except InputError as error:
        stderr.print(f"[red]error:[/red] {error}", highlight=False)
        raise SystemExit(2) from None
