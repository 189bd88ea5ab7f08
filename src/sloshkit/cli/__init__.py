"""The ``sloshkit`` command line (typer + rich): thin commands over the library.

`sloshkit.cli.app` holds the typer application; each command group is a module that registers
its commands on import; `sloshkit.cli.options` and `sloshkit.cli.moves` hold the option groups
shared by commands.

Start-up stays short because nothing heavy is imported before it is needed: `main` imports only
the module of the command being run, and ``sloshkit --help`` is drawn from `COMMANDS` (the
short help of every command, checked against the commands themselves by the tests) without
importing any command module. ``from sloshkit.cli import app`` gives the full application (every
command module imported), as the tests use it. `main` also lets option values that already have
their option's plain type through without typer's pydantic validation (`pass_plain_values`).
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


def _plain_type(annotation: Any) -> type | None:
    """``str``, ``int``, ``float`` or ``Path`` for an annotation that is one of them (or it |
    None)."""
    import types
    import typing
    from pathlib import Path

    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        rest = [arg for arg in typing.get_args(annotation) if arg is not type(None)]
        annotation = rest[0] if len(rest) == 1 else None
    return annotation if annotation in (str, int, float, Path) else None


def _validated_plainly(parameter: Any, ctx: Any, value: Any) -> tuple[bool, Any]:
    """(True, what typer's validation returns) without pydantic, for an optional,
    single-valued option without parser, bounds or choices whose value is None or already of
    the option's plain type (a default, or the text given to a string option), or a text given
    to a path option (converted as pydantic does, ``Path(text)``, then typer's own path checks);
    (False, None) for anything else."""
    descriptor: Any = getattr(parameter, "type_descriptor", None)
    info = getattr(descriptor, "parameter_info", None)
    if info is None or parameter.required or parameter.nargs != 1 or parameter.multiple:
        return False, None
    if getattr(info, "parser", None) is not None or getattr(info, "click_type", None) is not None:
        return False, None
    if getattr(info, "min", None) is not None or getattr(info, "max", None) is not None:
        return False, None
    plain = _plain_type(descriptor.annotation)
    if value is None or (plain is not None and type(value) is plain):
        return True, value
    if plain is not None and plain.__name__ == "Path" and type(value) is str:
        if getattr(info, "path_type", None) is not None:
            return False, None
        try:
            from typer._param_types import coerce_cli_path
        except ImportError:  # pragma: no cover - another typer
            return False, None
        return True, coerce_cli_path(plain(value), info, path_type=plain, param=parameter, ctx=ctx)
    return False, None


def pass_plain_values() -> bool:
    """Let option values that need no validation through typer without pydantic.

    typer validates every option value with a pydantic ``TypeAdapter`` built on first use;
    importing pydantic and building the adapters is about a third of ``sloshkit model``. A
    value that is None or already has its option's plain type (``str``, ``int``, ``float``),
    such as a default or the text given to one of sloshkit's unit-bearing string options,
    comes out of that validation unchanged, so it is passed through; a path given as text is
    converted as pydantic converts it (``Path(text)``) and checked by typer's own path checks.
    Every other value (a number typed on the command line, a choice) takes typer's own path,
    with its own error messages.

    Returns
    -------
    bool
        Whether the pass-through is installed (False when this typer has no such validation).

    Examples
    --------
    >>> pass_plain_values()
    True
    """
    try:
        from typer.core import _TyperParameter
    except ImportError:  # pragma: no cover - typer without pydantic validation
        return False
    validate = _TyperParameter.__dict__.get("process_value")
    if validate is None or not hasattr(_TyperParameter, "get_runtime_param"):
        return False  # pragma: no cover - another typer: leave it alone
    if getattr(validate, "passes_plain_values", False):
        return True

    def process_value(self: Any, ctx: Any, value: Any) -> Any:
        plain, checked = _validated_plainly(self, ctx, value)
        if not plain:
            return validate(self, ctx, value)
        value = checked
        if self.callback is not None:
            value = self.callback(ctx, self, value)
        return value

    process_value.passes_plain_values = True  # type: ignore[attr-defined]
    setattr(_TyperParameter, "process_value", process_value)  # noqa: B010 - typed as a method
    return True


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
    pass_plain_values()
    words = [word for word in sys.argv[1:] if not word.startswith("-")]
    if words and words[0] in COMMANDS:
        importlib.import_module(COMMANDS[words[0]][0])
        _app_module().main()
    elif not words and all(word in ("--help", "-h", "--version") for word in sys.argv[1:]):
        _app_module().main(_help_app())
    else:  # an unknown command: the full application says which exist
        load_commands()
        _app_module().main()


__all__ = ["COMMANDS", "app", "load_commands", "main", "pass_plain_values"]
