"""Atomic file writing shared by every layer: CSV of named columns or rows, strict JSON.

Every writer writes a temporary file in the target folder and renames it, so a failure never
leaves a half-written file. Readers and parsers of user files live in `sloshkit.io`.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import IO, Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


@contextlib.contextmanager
def atomic_open(
    path: str | Path, mode: str = "w", encoding: str | None = "utf-8"
) -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path``; rename it onto ``path`` only if the block succeeds.

    Parameters
    ----------
    path : str or Path
        Target file (its folder is created).
    mode : str
        File mode (``"w"``, ``"wb"``).
    encoding : str, optional
        Text encoding (ignored in binary mode).

    Yields
    ------
    file object
        The temporary file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_open(target) as stream:
    ...     _ = stream.write("done")
    >>> target.read_text()
    'done'
    """
    target = Path(path)
    if target.exists() and not target.is_file():  # never rename over /dev/null, a FIFO, ...
        raise InputError("path", str(target), "exists and is not a regular file")
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{target.name}.", dir=target.parent)
    os.close(handle)
    try:  # an existing file keeps its permissions; a new one gets the usual 0666 & ~umask
        permissions = os.stat(target).st_mode & 0o7777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        permissions = 0o666 & ~umask
    os.chmod(temporary, permissions)  # mkstemp creates 0600
    try:
        with open(temporary, mode, encoding=None if "b" in mode else encoding) as stream:
            yield stream
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)
        raise


def write_columns_csv(
    path: str | Path, columns: Mapping[str, Sequence[float] | FloatArray]
) -> Path:
    """Write equal-length named columns as CSV with a header row (full float precision).

    Parameters
    ----------
    path : str or Path
        Target file (written atomically).
    columns : mapping of str to array
        Named columns.

    Returns
    -------
    Path
        The file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = write_columns_csv(pathlib.Path(tempfile.mkdtemp()) / "a.csv", {"t_s": [0, 0.5]})
    >>> path.read_text().splitlines()
    ['t_s', '0', '0.5']
    """
    names = list(columns)
    arrays = [np.asarray(columns[name], dtype=float) for name in names]
    with atomic_open(path, "w") as stream:
        stream.write(",".join(names) + "\n")
        np.savetxt(stream, np.column_stack(arrays), delimiter=",", fmt="%.10g")
    return Path(path)


def write_rows_csv(path: str | Path, rows: Sequence[Mapping[str, object]]) -> Path:
    """Write a list of dicts as CSV (columns in the first row's key order), atomically.

    Parameters
    ----------
    path : str or Path
        Target file.
    rows : sequence of mapping
        The rows.

    Returns
    -------
    Path
        The file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = write_rows_csv(pathlib.Path(tempfile.mkdtemp()) / "r.csv", [{"law": "cubic"}])
    >>> path.read_text().splitlines()
    ['law', 'cubic']
    """
    if not rows:
        raise InputError("rows", 0, "nothing to write")
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    with atomic_open(path, "w") as stream:
        stream.write(buffer.getvalue())
    return Path(path)


def json_safe(payload: Any) -> Any:
    """``payload`` with non-finite floats (an unbounded jerk, say) as None: JSON has no inf.

    Parameters
    ----------
    payload : object
        Nested dicts, lists, tuples, numbers, paths.

    Returns
    -------
    object
        The same structure with numpy scalars as Python numbers and inf/nan as None.

    Examples
    --------
    >>> json_safe({"jerk_m_s3": float("inf"), "values": (1.0, 2)})
    {'jerk_m_s3': None, 'values': [1.0, 2]}
    """
    if isinstance(payload, float):
        return payload if np.isfinite(payload) else None
    if isinstance(payload, np.floating):
        return json_safe(float(payload))
    if isinstance(payload, np.integer):
        return int(payload)
    if isinstance(payload, dict):
        return {key: json_safe(value) for key, value in payload.items()}
    if isinstance(payload, list | tuple):
        return [json_safe(value) for value in payload]
    if isinstance(payload, Path):
        return str(payload)
    return payload


def write_json(path: str | Path, payload: object) -> Path:
    """Write ``payload`` as indented, strict JSON (non-finite numbers as null), atomically.

    Parameters
    ----------
    path : str or Path
        Target file.
    payload : object
        JSON-able data (see `json_safe`).

    Returns
    -------
    Path
        The file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = write_json(pathlib.Path(tempfile.mkdtemp()) / "a.json", {"x_m": float("nan")})
    >>> path.read_text().split()
    ['{', '"x_m":', 'null', '}']
    """
    with atomic_open(path, "w") as stream:
        json.dump(json_safe(payload), stream, indent=2, allow_nan=False)
        stream.write("\n")
    return Path(path)
