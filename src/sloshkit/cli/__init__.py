"""The ``sloshkit`` command line (typer + rich): thin commands over the library.

`sloshkit.cli.app` holds the typer application; each command group is a module that registers
its commands on import; `sloshkit.cli.options` and `sloshkit.cli.moves` hold the option groups
shared by commands.

Start-up stays short because nothing heavy is imported before it is needed: `main` imports only
the module of the command being run, and ``sloshkit --help`` is drawn from `COMMANDS` (the
short help of every command, checked against the commands themselves by the tests) without
importing any command module. ``from sloshkit.cli import app`` gives the full application (every
command module imported), as the tests use it. typer is pinned below 0.29 (pyproject.toml): from
0.29 on typer validates every option value with a pydantic adapter, which costs a third of
``sloshkit model`` (docs/performance.md).
"""

from __future__ import annotations

import importlib
import sys
from types import ModuleType
from typing import Any

import sloshkit.cli.app  # noqa: F401 - registers the application module; see below

# Importing the submodule bound the package attribute ``app`` to it; ``app`` is the typer
# application (see `__getattr__`).
del globals()["app"]

#: Command (or command group) -> (module, short help), in the order of ``sloshkit --help``.
COMMANDS: dict[str, tuple[str, str]] = {
    "model": (
        "sloshkit.cli.model",
        "Equivalent pendulum model of a filled upright cylinder or real container.",
    ),
    "simulate": (
        "sloshkit.cli.simulate",
        "Slosh response of the container to one motion law, or to a 3-D pose trajectory.",
    ),
    "compare": (
        "sloshkit.cli.simulate",
        "All laws on the same move, side by side (the seed paper's Figs. 7-9).",
    ),
    "sweep": (
        "sloshkit.cli.sweep",
        "Slosh maps over fill height x move duration x law (linear fast path).",
    ),
    "calibrate": (
        "sloshkit.cli.calibrate",
        "Natural frequency and damping from a record (camera, force sensor, CFD probe).",
    ),
    "export": (
        "sloshkit.cli.export",
        "Write a plan in a controller's format and check the round trip.",
    ),
    "plan": (
        "sloshkit.cli.plan",
        "The fastest move that keeps the slosh within limits, verified by simulation.",
    ),
    "reproduce": (
        "sloshkit.cli.report",
        "Rebuild the seed paper end to end on the analytic model and write a report.",
    ),
    "run": (
        "sloshkit.cli.report",
        "Run a scenario file's analyses (model, calibrate, compare, sweep, plan) into a report.",
    ),
    "cfd": (
        # cfd_sweep imports cli.cfd (run, analyse, validate) and adds ``cfd sweep`` to it.
        "sloshkit.cli.cfd_sweep",
        "The volume-of-fluid step with OpenFOAM (interFoam): generate, run, analyse, validate.",
    ),
}


def _app_module() -> ModuleType:
    """`sloshkit.cli.app`, the module that holds the typer application."""
    return sys.modules["sloshkit.cli.app"]


def load_commands() -> Any:
    """Import every command module (registering its commands) and return the typer app.

    Returns
    -------
    typer.Typer
        The application with every command.

    Examples
    --------
    >>> import sys
    >>> load_commands().info.name  # imports every command module: about a second
    'sloshkit'
    >>> all(module in sys.modules for module, _ in COMMANDS.values())
    True
    """
    for module, _ in COMMANDS.values():
        importlib.import_module(module)
    return _app_module().app


def __getattr__(name: str) -> Any:
    if name == "app":
        application = load_commands()
        globals()["app"] = application
        return application
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _help_app() -> Any:
    """An application with the real root options and help, and placeholder commands that carry
    only their short help: ``sloshkit --help`` without importing the command modules."""
    import typer

    real = _app_module().app
    stand_in = typer.Typer(
        name=real.info.name,
        help=real.info.help,
        no_args_is_help=True,
        add_completion=False,
        pretty_exceptions_enable=False,
        rich_markup_mode=None,
    )
    stand_in.callback()(_app_module()._root)
    for command, (_, short) in COMMANDS.items():
        stand_in.command(command, help=short)(lambda: None)
    return stand_in


def main() -> None:
    """Entry point: import the command being run (or none, for the root help) and run it.

    The command line is ``sys.argv``; the process exits with the command's exit code (see
    `sloshkit.cli.app`). File descriptor 1 is routed to stderr so that only the result reaches
    stdout (`sloshkit.cli.streams`). The console script starts one step earlier, in
    `sloshkit.entry.main`, which handles signals before this package is imported.

    Returns
    -------
    None
        Never returns normally: raises SystemExit with the exit code.

    Examples
    --------
    >>> import sys
    >>> saved, sys.argv = sys.argv, ["sloshkit", "model", "--modes", "0"]
    >>> try:
    ...     main()
    ... except SystemExit as stop:
    ...     code = stop.code
    ... finally:
    ...     sys.argv = saved
    >>> code
    2
    """
    from sloshkit.cli import streams

    streams.protect_stdout()
    words = [word for word in sys.argv[1:] if not word.startswith("-")]
    if words and words[0] in COMMANDS:
        importlib.import_module(COMMANDS[words[0]][0])
        _app_module().main()
    elif not words and all(word in ("--help", "-h", "--version") for word in sys.argv[1:]):
        _app_module().main(_help_app())
    else:  # an unknown command: the full application says which exist
        load_commands()
        _app_module().main()


__all__ = ["COMMANDS", "app", "load_commands", "main"]
