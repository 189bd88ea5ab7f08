"""Output paths: checked before any work, written all or nothing.

Every ``--csv``, ``--out``, ``--model-file-out`` and ``--plot`` goes through `check_file` or
`check_folder` at the start of its command, so a bad path costs nothing: an existing folder
where a file is expected, a file where a folder is expected, a folder without write permission
or on a read-only file system, an unknown figure extension, or a non-empty folder that sloshkit
did not write (replaced only with ``--overwrite``, as ``cfd run`` does). Folders of several
outputs are written through `staged_folder`: everything goes to a hidden staging folder beside
the target and is moved into place only when the command succeeds; an error or an interruption
(SIGINT/SIGTERM raise in the CLI) removes the staging folder.
"""

from __future__ import annotations

import contextlib
import contextvars
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path

from sloshkit.errors import InputError
from sloshkit.io.utf8_names import require_encodable

#: Figure formats matplotlib writes without extra packages.
FIGURE_SUFFIXES: tuple[str, ...] = (".png", ".svg", ".pdf", ".jpg", ".jpeg", ".eps", ".ps")

#: Model file formats (`sloshkit.io.models.write_model_file`).
MODEL_SUFFIXES: tuple[str, ...] = (".toml", ".json")

#: File sloshkit leaves in each output folder it wrote; such a folder may be rewritten.
MARKER = ".sloshkit-output"

#: The line every exported file carries in its first `MARK_BYTES` (``# format: sloshkit
#: urscript``): an existing file at a default output path is replaced only when it has it.
FILE_MARK = b"format: sloshkit "
MARK_BYTES = 4096


def written_by_sloshkit(path: Path | str) -> bool:
    """Whether a file carries sloshkit's mark (`FILE_MARK`) in its first `MARK_BYTES`.

    Parameters
    ----------
    path : Path or str
        An existing file.

    Returns
    -------
    bool

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.script").write_text("def move():\\n  # format: sloshkit urscript\\n")
    >>> _ = (folder / "mine.script").write_text("def move():\\n  movej(home)\\n")
    >>> written_by_sloshkit(folder / "a.script"), written_by_sloshkit(folder / "mine.script")
    (True, False)
    """
    try:
        with open(path, "rb") as handle:
            return FILE_MARK in handle.read(MARK_BYTES)
    except OSError:
        return False


#: The words of the command line being run (set by the CLI, `command_line`): every existing
#: file they name is an input the command's outputs must not replace.
_COMMAND_WORDS: contextvars.ContextVar[tuple[str, ...]] = contextvars.ContextVar(
    "sloshkit_command_words", default=()
)


@contextlib.contextmanager
def command_line(argv: list[str]) -> Iterator[None]:
    """Let `check_file` see the command line while a command runs: an output path that is
    also a file named elsewhere on it (``simulate --pose-file move.csv --csv move.csv``, any
    spelling of the same file, a link to it) is refused.

    Parameters
    ----------
    argv : list of str
        The command line without the program name.

    Yields
    ------
    None

    Examples
    --------
    >>> import tempfile, pathlib
    >>> move = pathlib.Path(tempfile.mkdtemp()) / "move.csv"
    >>> _ = move.write_text("t,x\\n0,0\\n")
    >>> with command_line(["simulate", "--pose-file", str(move), "--csv", str(move)]):
    ...     try:
    ...         check_file(move, "csv")
    ...     except InputError as error:
    ...         print(error.valid.split(";")[0])
    is also named as an input of the command
    """
    token = _COMMAND_WORDS.set(tuple(argv))
    try:
        yield
    finally:
        _COMMAND_WORDS.reset(token)


def _named_files(target: Path) -> list[str]:
    """The command-line words that name ``target`` (an existing file)."""
    named = []
    for word in _COMMAND_WORDS.get():
        value = word.partition("=")[2] if word.startswith("--") else word
        value = value.removeprefix("file:")
        if value and not value.startswith("-"):
            candidate = Path(value)
            with contextlib.suppress(OSError, ValueError):
                if candidate.is_file() and os.path.samefile(candidate, target):
                    named.append(value)
    return named


def _same_file(first: Path, second: Path) -> bool:
    try:
        if first.exists() and second.exists():
            return os.path.samefile(first, second)
    except OSError:
        pass
    return os.path.abspath(first) == os.path.abspath(second)


def _existing_ancestor(path: Path, parameter: str) -> Path:
    """The nearest existing ancestor of ``path``; `InputError` if it is not a folder."""
    for parent in path.absolute().parents:
        if parent.exists():
            if not parent.is_dir():
                raise InputError(parameter, str(path), f"{parent} is a file, not a folder")
            return parent
    return Path(path.absolute().anchor)


def _require_writable(folder: Path, path: Path, parameter: str) -> None:
    """Refuse a folder nobody can write into: permissions, a read-only file system, or a
    pseudo file system such as /proc or /sys (where ``os.access`` says yes to root).

    The probe is an unnamed temporary file (``O_TMPFILE`` where the file system has it, else
    a named one removed at once), so nothing is left in the folder.
    """
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(
            parameter,
            str(path),
            f"folder {folder} is not writable (permissions or a read-only file system)",
        )
    try:
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as error:
        raise InputError(
            parameter,
            str(path),
            f"folder {folder} does not take new files ({error.strerror or error}); "
            "a read-only or virtual file system such as /proc or /sys",
        ) from None


def check_file(
    path: Path | str | None,
    parameter: str,
    kind: str = "file",
    *,
    inputs: tuple[tuple[str, Path | str | None], ...] = (),
    chosen: bool = True,
) -> Path | None:
    """Check an output file path before any work; return it (None passes through).

    The one output-path rule: an output is never one of the command's input files (the same
    file by any name, links included), and an output path sloshkit picked itself (a default
    beside the input, ``chosen=False``) never replaces an existing file that sloshkit did not
    write (`written_by_sloshkit`); a path the user named replaces the file there.

    Parameters
    ----------
    path : Path, str or None
        The path given by the user.
    parameter : str
        Its option name, for the message (``"csv"``, ``"plot"``, ...).
    kind : str
        ``"file"`` (any), ``"figure"`` (a `FIGURE_SUFFIXES` extension) or ``"model"``
        (``.toml``/``.json``).
    inputs : tuple of (str, path) pairs
        The command's input files with their option names (None skipped).
    chosen : bool
        The user named the path (False: a default picked by sloshkit).

    Returns
    -------
    Path or None
        ``path`` as a `Path`.

    Raises
    ------
    InputError
        For a folder, a parent that is a file, a read-only file or folder, a wrong extension,
        a name that is not UTF-8, an input file, or (for a default path) a user's file.

    References
    ----------
    POSIX.1-2017, ``rename()``: atomic replacement within one file system.

    Examples
    --------
    >>> check_file("figure.png", "plot", "figure")
    PosixPath('figure.png')
    """
    if path is None:
        return None
    target = Path(path)
    if str(path).strip() == "" or target.name in ("", ".", ".."):
        raise InputError(parameter, str(path), "must name a file")
    require_encodable(path, parameter)
    for option, source in inputs:
        if source is not None and _same_file(target, Path(source)):
            raise InputError(
                parameter,
                str(path),
                f"is the input {option} {str(source)!r}; an output never replaces an input",
                "name another file with --out",
            )
    if target.is_file() and len(_named_files(target)) > (1 if chosen else 0):
        raise InputError(
            parameter,
            str(path),
            "is also named as an input of the command; an output never replaces an input",
            "name another file",
        )
    if not chosen and target.is_file() and not written_by_sloshkit(target):
        raise InputError(
            parameter,
            str(path),
            "exists and was not written by sloshkit; the default output never replaces it",
            "name it with --out to replace it",
        )
    if target.is_dir():
        raise InputError(parameter, str(path), "is a folder; give a file name")
    if target.exists() and not target.is_file():
        raise InputError(parameter, str(path), "is not a regular file (a device or a pipe)")
    suffixes = {"figure": FIGURE_SUFFIXES, "model": MODEL_SUFFIXES}.get(kind)
    if suffixes is not None and target.suffix.lower() not in suffixes:
        raise InputError(
            parameter,
            str(path),
            f"unknown {kind} extension {target.suffix or '(none)'!r}; use " + ", ".join(suffixes),
        )
    folder = _existing_ancestor(target, parameter)
    if target.exists() and not os.access(target, os.W_OK):
        raise InputError(parameter, str(path), "exists and is read-only")
    _require_writable(folder, target, parameter)
    return target


def check_folder(path: Path | str | None, parameter: str, overwrite: bool = False) -> Path | None:
    """Check an output folder before any work; return it (None passes through).

    A folder that exists must be empty, hold a previous sloshkit output (`MARKER`), or
    ``overwrite`` must be set.

    Parameters
    ----------
    path : Path, str or None
        The folder given by the user.
    parameter : str
        Its option name (``"out"``).
    overwrite : bool
        Allow replacing files in a non-empty folder not written by sloshkit.

    Returns
    -------
    Path or None
        ``path`` as a `Path`.

    Examples
    --------
    >>> check_folder("new-report", "out")
    PosixPath('new-report')
    """
    if path is None:
        return None
    target = Path(path)
    if str(path).strip() == "":
        raise InputError(parameter, str(path), "must name a folder")
    require_encodable(path, parameter)
    if target.exists() and not target.is_dir():
        raise InputError(parameter, str(path), "is a file; give a folder")
    if target.is_dir():
        entries = [entry.name for entry in target.iterdir()]
        if entries and MARKER not in entries and not overwrite:
            raise InputError(
                parameter,
                str(path),
                "exists and is not empty (use --overwrite to replace its files)",
            )
        _require_writable(target, target, parameter)
    else:
        _require_writable(_existing_ancestor(target, parameter), target, parameter)
    return target


@contextlib.contextmanager
def staged_folder(
    target: Path | str, before_keeping: Callable[[], None] | None = None
) -> Iterator[Path]:
    """Write a folder's outputs to a staging folder; move them into ``target`` on success.

    Parameters
    ----------
    target : Path or str
        The output folder (created if missing).
    before_keeping : callable, optional
        Called when the block has ended, before anything moves; an exception it raises (the
        CLI's `sloshkit.cli.signals.check`: a signal that library code caught and swallowed
        inside the block) leaves ``target`` untouched.

    Yields
    ------
    Path
        The staging folder to write into (same file system as ``target``).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "out"
    >>> with staged_folder(out) as staging:
    ...     _ = (staging / "a.csv").write_text("x\\n1\\n")
    >>> sorted(p.name for p in out.iterdir())
    ['.sloshkit-output', 'a.csv']
    """
    folder = Path(target)
    folder.absolute().parent.mkdir(parents=True, exist_ok=True)
    staging = Path(
        tempfile.mkdtemp(prefix=f".{folder.absolute().name}.staging-", dir=folder.absolute().parent)
    )
    try:
        yield staging
        if before_keeping is not None:
            before_keeping()
        folder.mkdir(exist_ok=True)
        (staging / MARKER).write_text("written by sloshkit; this folder may be rewritten\n")
        for entry in sorted(staging.rglob("*")):
            destination = folder / entry.relative_to(staging)
            if entry.is_dir():
                destination.mkdir(exist_ok=True)
            else:
                _keep_mode(destination, entry)
                os.replace(entry, destination)
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def mark_folder(folder: Path | str) -> None:
    """Leave the `MARKER` in a folder sloshkit wrote (so a rerun may rewrite it).

    Parameters
    ----------
    folder : Path or str
        The output folder (nothing happens if it does not exist).

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> mark_folder(folder)
    >>> (folder / MARKER).exists()
    True
    """
    marker = Path(folder) / MARKER
    if Path(folder).is_dir() and not marker.exists():
        marker.write_text("written by sloshkit; this folder may be rewritten\n")


def _keep_mode(existing: Path, replacement: Path) -> None:
    with contextlib.suppress(OSError):
        os.chmod(replacement, os.stat(existing).st_mode & 0o7777)


@contextlib.contextmanager
def all_or_nothing(
    *paths: Path | str | None, before_keeping: Callable[[], None] | None = None
) -> Iterator[None]:
    """Keep the files a command writes only if the whole command succeeds.

    A command that writes several files (a CSV, then a figure; an exported program, then its
    round-trip check) runs inside this block: on any exception (an `InputError` found late, an
    interruption) files that did not exist before are removed and files that did are restored
    to their previous content (a copy kept beside them while the block runs).

    Parameters
    ----------
    *paths : Path, str or None
        The output files of the command (None is skipped).
    before_keeping : callable, optional
        Called when the block has ended, still inside it: an exception it raises removes or
        restores the files as any other (the CLI passes `sloshkit.cli.signals.check`, so a
        signal that library code caught and swallowed inside the block still leaves no file).

    Yields
    ------
    None

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "a.csv"
    >>> try:
    ...     with all_or_nothing(out):
    ...         _ = out.write_text("half")
    ...         raise ValueError("a late error")
    ... except ValueError:
    ...     pass
    >>> out.exists()
    False
    """
    targets = [Path(path) for path in paths if path is not None]
    backups: dict[Path, Path | None] = {}
    try:
        for target in targets:
            backups[target] = None
            if target.is_file():
                handle, name = tempfile.mkstemp(prefix=f".{target.name}.keep-", dir=target.parent)
                os.close(handle)
                os.unlink(name)
                # a copy, not a hard link: some writers (matplotlib) write in place
                shutil.copy2(target, name)
                backups[target] = Path(name)
        yield
        if before_keeping is not None:
            before_keeping()
    except BaseException:
        for target, backup in backups.items():
            with contextlib.suppress(OSError):
                if backup is not None:
                    os.replace(backup, target)
                elif target.is_file() or target.is_symlink():
                    target.unlink()
        raise
    finally:
        for backup in backups.values():
            if backup is not None:
                with contextlib.suppress(FileNotFoundError):
                    backup.unlink()
