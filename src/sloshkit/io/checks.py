"""Checks at the file edge shared by every reader of user files: the option a file came from
named in each error (`naming`), finite numbers (`require_finite_rows`), strictly increasing
time stamps (`require_increasing_rows`) and magnitudes a container move can have
(`require_bounded_rows`)."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


@contextlib.contextmanager
def naming(parameter: str, path: str | Path, keep: tuple[str, ...] = ()) -> Iterator[None]:
    """Name the option a file came from in every `InputError` raised while it is read.

    Errors found inside a file (a NaN in a column, a time stamp that goes back, a unit that
    is not a time) are raised by lower layers under their own names (``position``,
    ``time``, ``file``); inside this block they are raised again under ``parameter`` (the
    option, e.g. ``pose_file``) with the file and the original detail, so the one error line
    names what the user typed.

    Parameters
    ----------
    parameter : str
        The option or argument that named the file.
    path : str or Path
        The file.
    keep : tuple of str
        Parameters whose errors pass unchanged (other options checked inside the block).

    Yields
    ------
    None

    Examples
    --------
    >>> from sloshkit.errors import InputError
    >>> try:
    ...     with naming("pose_file", "move.csv"):
    ...         raise InputError("time", "0.2 s at data row 12", "must increase strictly")
    ... except InputError as error:
    ...     print(error)
    pose_file = 'move.csv' is invalid: time 0.2 s at data row 12: must increase strictly
    """
    try:
        yield
    except InputError as error:
        if error.parameter == parameter or error.parameter in keep:
            raise
        detail = error.value if isinstance(error.value, str) else str(error.value)
        label = "" if error.parameter == "file" else error.parameter
        if detail.startswith(str(path)):  # the file's own name (``path:row``) says no more
            rest = detail[len(str(path)) :].lstrip(":")
            detail, label = (f"data row {rest}" if rest else ""), ""
        where = " ".join(part for part in (label, detail) if part)
        raise InputError(
            parameter, str(path), f"{where}: {error.valid}" if where else error.valid, error.hint
        ) from None


def require_finite_rows(
    data: FloatArray, columns: dict[str, int], parameter: str, path: str | Path
) -> None:
    """`InputError` naming the first data row and column holding NaN or an infinity.

    Parameters
    ----------
    data : ndarray
        A table from `sloshkit.io.tables.read_table`.
    columns : dict of str to int
        The columns used (header name -> index).
    parameter : str
        The option that named the file.
    path : str or Path
        The file.

    Returns
    -------
    None

    Examples
    --------
    >>> import numpy as np
    >>> require_finite_rows(np.array([[0.0, 1.0]]), {"t": 0, "x": 1}, "pose_file", "a.csv")
    """
    for name, index in columns.items():
        bad = ~np.isfinite(data[:, index])
        if np.any(bad):
            row = int(np.argmax(bad))
            raise InputError(
                parameter,
                str(path),
                f"column {name!r} holds {float(data[row, index])} in data row {row + 1}; "
                "every value must be a finite number",
            )


def require_increasing_rows(
    time_s: FloatArray, column: str, parameter: str, path: str | Path, minimum_rows: int = 2
) -> None:
    """`InputError` unless the time column has ``minimum_rows`` rows and strictly increases.

    Parameters
    ----------
    time_s : ndarray
        The time column [s].
    column : str
        Its header name (for the message).
    parameter : str
        The option that named the file.
    path : str or Path
        The file.
    minimum_rows : int
        Fewest data rows accepted.

    Returns
    -------
    None

    Examples
    --------
    >>> import numpy as np
    >>> require_increasing_rows(np.array([0.0, 0.1, 0.2]), "t", "pose_file", "a.csv")
    """
    if time_s.size < minimum_rows:
        raise InputError(
            parameter, str(path), f"has {time_s.size} data row(s); at least {minimum_rows} needed"
        )
    steps = np.diff(time_s)
    if np.any(steps <= 0.0):
        row = int(np.argmax(steps <= 0.0)) + 2
        kind = "repeats" if steps[row - 2] == 0.0 else "goes back in"
        raise InputError(
            parameter,
            str(path),
            f"data row {row} {kind} time ({column} = {time_s[row - 1]:.9g} s after "
            f"{time_s[row - 2]:.9g} s); time stamps must increase strictly",
        )


def require_bounded_rows(
    values: FloatArray, column: str, bound: float, unit: str, parameter: str, path: str | Path
) -> None:
    """`InputError` naming the first row whose magnitude exceeds ``bound`` (SI).

    Parameters
    ----------
    values : ndarray
        A column in SI units.
    column : str
        Its header name.
    bound : float
        Largest magnitude accepted.
    unit : str
        SI unit of the column (for the message).
    parameter : str
        The option that named the file.
    path : str or Path
        The file.

    Returns
    -------
    None

    Examples
    --------
    >>> import numpy as np
    >>> require_bounded_rows(np.array([0.0, 0.3]), "x", 1e6, "m", "pose_file", "a.csv")
    """
    bad = np.abs(values) > bound
    if np.any(bad):
        row = int(np.argmax(bad))
        raise InputError(
            parameter,
            str(path),
            f"column {column!r} reaches {values[row]:.3g} {unit} in data row {row + 1}; "
            f"at most {bound:g} {unit} (are the units in the header right?)",
        )
