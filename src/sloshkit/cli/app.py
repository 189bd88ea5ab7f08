"""The ``sloshkit`` command line (typer + rich): parses units, calls the core, prints results.

Exit codes: 0 success; 1 no feasible result (e.g. a plan that cannot meet the limits) or a
failure of the machine (disk full, out of memory); 2 invalid input, one line on stderr naming
the parameter, value and valid range (also for typer/click usage errors); 3 an internal error
(a bug: one line, ``SLOSHKIT_DEBUG=1`` shows the traceback); 130/143 interrupted by
SIGINT/SIGTERM (no partial output is left).
"""

from __future__ import annotations

import errno
import os
import sys
import warnings
from collections.abc import Sequence
from typing import Annotated

import typer

from sloshkit.cli import messages, signals
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
    rich_markup_mode=None,
)


stdout = messages.console()
stderr = messages.console(stderr=True)


def _version(value: bool) -> None:
    if value:
        from sloshkit import __version__

        stdout.print(f"sloshkit {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    ctx: typer.Context,
    version: Annotated[
        bool,
        typer.Option("--version", callback=_version, is_eager=True, help="Print the version."),
    ] = False,
    max_memory: Annotated[
        str | None,
        typer.Option(
            "--max-memory",
            help="Largest memory one request may use, e.g. 8GiB (default: half the RAM; "
            "also SLOSHKIT_MAX_MEMORY).",
        ),
    ] = None,
) -> None:
    """sloshkit: the sloshing toolkit (see the README for a tour)."""
    ctx.with_resource(recording())
    if max_memory is not None:
        from sloshkit.budget import ENVIRONMENT_VARIABLE, parse_bytes

        os.environ[ENVIRONMENT_VARIABLE] = str(parse_bytes(max_memory))


def _parameter_spelling(application: typer.Typer, argv: Sequence[str]) -> dict[str, str]:
    """Python parameter name -> how the user writes it (``fill_height`` -> ``--fill-height``,
    ``plan_file`` -> ``PLAN_FILE``) for the command that ``argv`` invokes."""
    import typer.main

    command = typer.main.get_command(application)
    for word in argv:
        nested = getattr(command, "commands", None)
        if not isinstance(nested, dict):
            break
        if word in nested:
            command = nested[word]
    spelling: dict[str, str] = {}
    for parameter in command.params:
        if parameter.name is None:
            continue
        long_names = [o for o in parameter.opts if o.startswith("--")]
        if long_names:
            spelling[parameter.name] = long_names[0]
        elif parameter.param_type_name == "argument":
            spelling[parameter.name] = parameter.name.upper()
    return spelling


def _as_written(failure: InputError, application: typer.Typer, argv: Sequence[str]) -> str:
    """The error's message with its parameter named as the user wrote it: the option, when the
    message starts with the Python name of an option given on the command line (a value from a
    file keeps the file's key), or the argument as the usage line names it."""
    message = str(failure)
    if not message.startswith(f"{failure.parameter} = "):
        return message
    try:
        written = _parameter_spelling(application, argv).get(failure.parameter)
    except Exception:  # the message as it is is still right
        return message
    if written is None or (
        written.startswith("--")
        and not any(word == written or word.startswith(written + "=") for word in argv)
    ):
        return message  # not an option the user gave (a default, or a key of a file)
    return written + message[len(failure.parameter) :]


def _show_warning(message, category, filename, lineno, file=None, line=None):  # type: ignore[no-untyped-def]
    prefix = "warning" if category is ValidityWarning else category.__name__
    messages.warning(stderr, message, prefix)


def run(
    argv: Sequence[str] | None = None,
    application: typer.Typer | None = None,
    *,
    exiting: bool = False,
) -> int:
    """Run ``application`` (default `app`) on ``argv`` (default: ``sys.argv[1:]``) and return
    the exit code.

    Every failure ends in one line on stderr (see the module docstring for the codes); nothing
    raises out of here except on ``SLOSHKIT_DEBUG=1``.

    Parameters
    ----------
    argv : sequence of str, optional
        The command line without the program name.
    application : typer.Typer, optional
        The application (default: `app` with the commands imported so far).
    exiting : bool
        The process exits afterwards (signal handlers are then left in place).

    Returns
    -------
    int
        The exit code: 0 success, 2 bad input, 1 I/O failure, 3 internal error, 128 + signal.

    Examples
    --------
    >>> import sloshkit.cli.model  # registers the command
    >>> run(["model", "--radius", "abc"])  # prints one error line on stderr
    2
    """
    from sloshkit.budget import ENVIRONMENT_VARIABLE
    from sloshkit.cli.display import quiet_library_logging, sane_width_environment

    saved_width = sane_width_environment()  # COLUMNS=0 would hide every line, errors too
    quiet_library_logging()
    saved_memory = os.environ.get(ENVIRONMENT_VARIABLE)
    saved_showwarning = warnings.showwarning
    warnings.showwarning = _show_warning
    try:
        with signals.installed(restore=not exiting):
            try:
                from sloshkit.io.outputs import command_line
                from sloshkit.io.utf8_names import require_encodable_arguments

                words = list(argv) if argv is not None else sys.argv[1:]
                # a name that is not UTF-8 would fail when written into an output, after the work
                require_encodable_arguments(words)
                with command_line(words):  # outputs never replace a file named as an input
                    code = (application or app)(
                        args=list(argv) if argv is not None else None, standalone_mode=False
                    )
                if signals.received() is not None and not signals.was_reported():
                    raise signals.Interrupted(signals.received() or 2)
                return code if isinstance(code, int) else 0
            except BaseException as failure:  # the one place that reports
                words = list(argv) if argv is not None else sys.argv[1:]
                return _report(failure, application or app, words)
    finally:
        warnings.showwarning = saved_showwarning
        os.environ.update(saved_width)
        if saved_memory is None:
            os.environ.pop(ENVIRONMENT_VARIABLE, None)
        else:
            os.environ[ENVIRONMENT_VARIABLE] = saved_memory


def _report(failure: BaseException, application: typer.Typer, argv: Sequence[str]) -> int:
    """Print ``failure`` as one line and return its exit code (``argv``: the command line)."""
    if isinstance(failure, SystemExit):
        return failure.code if isinstance(failure.code, int) else 1
    signum = signals.received()
    if isinstance(failure, KeyboardInterrupt) or signum is not None:  # Interrupted included
        code = 128 + (signum if signum is not None else int(getattr(failure, "signum", 2)))
        advice = signals.hint() or "no partial output was written"
        messages.error(stderr, f"interrupted (exit {code}); {advice}")
        return code
    if isinstance(failure, InputError):
        messages.error(stderr, _as_written(failure, application, argv))
        return 2
    if isinstance(failure, typer.TyperException):
        if type(failure).__name__ == "NoArgsIsHelpError":
            failure.show()  # type: ignore[attr-defined]
            return failure.exit_code
        hint = ""
        context = getattr(failure, "ctx", None)
        if context is not None:
            hint = f" (see '{context.command_path} --help')"
        messages.error(stderr, failure.format_message() + hint)
        return 2 if failure.exit_code == 2 else failure.exit_code
    if isinstance(failure, typer.Exit):
        return failure.exit_code
    if isinstance(failure, typer.Abort):
        messages.error(stderr, "aborted")
        return 130
    if os.environ.get("SLOSHKIT_DEBUG"):
        raise failure
    if isinstance(failure, MemoryError):
        messages.error(stderr, "out of memory; use smaller sizes (see --max-memory)")
        return 1
    if isinstance(failure, OSError):
        if failure.errno == errno.EPIPE:
            return 1
        where = f"{failure.filename}: " if failure.filename else ""
        messages.error(stderr, f"{where}{failure.strerror or failure}")
        return 1
    messages.error(
        stderr,
        f"internal error {type(failure).__name__}: {failure} "
        "(a bug; rerun with SLOSHKIT_DEBUG=1 for the traceback and please report it)",
    )
    return 3


def main(application: typer.Typer | None = None, argv: Sequence[str] | None = None) -> None:
    """Run ``application`` (default `app`) and exit with its code (see `run`).

    `sloshkit.cli.main` is the entry point: it imports the command being run first.

    Parameters
    ----------
    application : typer.Typer, optional
        The application (default `app`).
    argv : sequence of str, optional
        The command line without the program name (default: ``sys.argv[1:]``).

    Examples
    --------
    >>> import sloshkit.cli.model
    >>> try:
    ...     main(argv=["model", "--fill-height", "-1mm"])
    ... except SystemExit as stop:
    ...     print("exit", stop.code)
    exit 2
    """
    sys.exit(run(argv, application, exiting=True))
