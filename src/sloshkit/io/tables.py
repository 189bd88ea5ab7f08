"""File input at the edge: numeric tables (CSV or whitespace), their columns and units.
Readers are named ``read_*``; user motion files are read by `sloshkit.io.motions`; the atomic
writers are in `sloshkit.files`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


#: Most data rows of a table file (pose, plan, motion and record files alike): 1000 s at
#: 1 kHz. Longer files are refused while they are read, before their rows are parsed.
MAX_TABLE_ROWS = 1_000_000

#: Memory a table needs per byte of file, as `sloshkit.budget.require_memory` counts it: every
#: value takes at least 2 bytes of text ("0,") and 8 bytes as a float, held twice (the rows
#: read, then the array).
TABLE_BYTES_PER_FILE_BYTE = 8.0


def read_table(path: str | Path, *, max_rows: int = MAX_TABLE_ROWS) -> tuple[list[str], FloatArray]:
    """Read a numeric table: CSV (comma or semicolon) or whitespace-separated, ``#`` comments
    skipped; with semicolons, decimal commas are accepted.

    The first non-comment line is a header when it is not numeric; otherwise columns are named
    by their index (``"0"``, ``"1"``, ...). OpenFOAM function-object files (``# Time ...``
    headers, vectors in parentheses) are read too: parentheses are dropped, vector components
    become separate columns, and a last comment line naming the columns is used as the header.
    The file is read line by line: one with more than ``max_rows`` data rows is refused when
    its row ``max_rows + 1`` is reached, and its size is checked against the memory limit
    (`TABLE_BYTES_PER_FILE_BYTE`, `sloshkit.budget`) before anything is read.
    Raises `InputError` for a missing or empty file, too many rows or non-numeric cells.

    Parameters
    ----------
    path : str or Path
        The file (a UTF-8 byte-order mark is removed).
    max_rows : int, optional
        Most data rows accepted (default `MAX_TABLE_ROWS`).

    Returns
    -------
    tuple of (list of str, ndarray)
        The column names and the data, one row per data line (empty cells are NaN).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> file = pathlib.Path(tempfile.mkdtemp()) / "a.csv"
    >>> _ = file.write_text("t;x [mm]\\n0;1,5\\n")
    >>> read_table(file)
    (['t', 'x [mm]'], array([[0. , 1.5]]))
    """
    from array import array

    limit = MAX_TABLE_ROWS if max_rows is None else max_rows
    source = Path(path)
    if not source.is_file():
        raise InputError("file", str(source), "does not exist or is not a file")
    from sloshkit.budget import require_memory

    size = source.stat().st_size
    require_memory(
        "file", str(source), TABLE_BYTES_PER_FILE_BYTE * size, f"a {size}-byte table in memory"
    )
    if _data_lines_exceed(source, limit + 1):  # + 1: the header
        raise InputError(
            "file",
            str(source),
            f"has more than {limit} data rows (the most a table may have)",
            "resample it or split it",
        )
    last_comment = ""
    header: list[str] | None = None
    delimiter: str | None = None
    values = array("d")
    width = 0
    rows = 0
    first = True
    with source.open(encoding="utf-8-sig", errors="replace", newline=None) as handle:
        for raw in handle:
            stripped = raw.strip()
            if not stripped:
                continue
            if stripped.startswith("#"):
                last_comment = stripped.lstrip("#").strip()
                continue
            line = stripped.replace("(", " ").replace(")", " ")
            if first:
                first = False
                # semicolon CSV (spreadsheet exports; decimal commas allowed), comma CSV, or
                # whitespace
                delimiter = ";" if ";" in line else ("," if "," in line else None)
                cells = _split(line, delimiter)
                if not _is_numeric(cells):
                    header = [name.strip() for name in cells]
                    continue
            rows += 1
            if rows > limit:
                raise InputError(
                    "file",
                    str(source),
                    f"has more than {limit} data rows (the most a table may have)",
                    "resample it or split it",
                )
            cells = _split(line, delimiter)
            try:
                row = [float(cell) if cell.strip() else float("nan") for cell in cells]
            except ValueError:
                raise InputError(
                    "file", f"{source}:{rows}", f"row is not numeric: {line[:60]!r}"
                ) from None
            if rows == 1:
                width = len(row)
            elif len(row) != width:
                raise InputError("file", str(source), "rows have different numbers of columns")
            values.extend(row)
    if first:
        raise InputError("file", str(source), "has no data rows")
    if rows == 0:
        raise InputError("file", str(source), "has a header but no data rows")
    data = np.frombuffer(values, dtype=float).reshape(rows, width).copy()
    if header is None and last_comment:
        candidate = last_comment.split()
        header = candidate if len(candidate) == width else None
    if header is None or len(header) != width:
        header = [str(index) for index in range(width)]
    return header, data


def _data_lines_exceed(source: Path, count: int) -> bool:
    """Whether ``source`` has more than ``count`` lines that are neither blank nor comments,
    found without parsing a number: newlines are counted in binary chunks first (most files
    stop there), then lines are classified until the count is passed."""
    chunk = 1 << 20
    newlines = 0
    with source.open("rb") as handle:
        while block := handle.read(chunk):
            newlines += block.count(b"\n")
    if newlines + 1 <= count:
        return False
    seen = 0
    with source.open("rb") as handle:
        for raw in handle:
            stripped = raw.strip()
            if stripped and not stripped.startswith(b"#"):
                seen += 1
                if seen > count:
                    return True
    return False


def select_column(header: list[str], data: FloatArray, column: str, parameter: str) -> FloatArray:
    """Column by name, or by 0-based index given as text; `InputError` lists the names.

    Parameters
    ----------
    header : list of str
        The column names.
    data : ndarray
        The table.
    column : str
        A name or an index (``"1"``, ``"-1"``).
    parameter : str
        The option that named the column, for the message.

    Returns
    -------
    ndarray

    Examples
    --------
    >>> import numpy as np
    >>> select_column(["t", "x"], np.array([[0.0, 2.0]]), "1", "signal_column").tolist()
    [2.0]
    """
    if column in header:
        return np.asarray(data[:, header.index(column)], dtype=float)
    if column.lstrip("-").isdigit() and -len(header) <= int(column) < len(header):
        return np.asarray(data[:, int(column)], dtype=float)
    raise InputError(parameter, column, "is not a column; columns are " + ", ".join(header))


def column_name(header: list[str], column: str) -> str:
    """The header name of a column given by name or 0-based index.

    Parameters
    ----------
    header : list of str
        The column names.
    column : str
        A name or an index.

    Returns
    -------
    str

    Examples
    --------
    >>> column_name(["t", "eta [mm]"], "1")
    'eta [mm]'
    """
    if column in header:
        return column
    if column.lstrip("-").isdigit() and -len(header) <= int(column) < len(header):
        return header[int(column)]
    return column


#: Unit suffixes recognised at the end of a column name (``t_ms``, ``x_mm``, ``a_m_s2``),
#: longest first, as pint text.
_SUFFIX_UNITS: tuple[tuple[str, str], ...] = (
    ("_mm_s2", "mm/s^2"),
    ("_m_s2", "m/s^2"),
    ("_mm_s", "mm/s"),
    ("_m_s", "m/s"),
    ("_deg", "deg"),
    ("_rad", "rad"),
    ("_min", "min"),
    ("_ms", "ms"),
    ("_us", "us"),
    ("_mm", "mm"),
    ("_cm", "cm"),
    ("_um", "um"),
    ("_s", "s"),
    ("_m", "m"),
)

#: Column names (without unit) that mean time, position, acceleration in motion and pose files.
TIME_NAMES: tuple[str, ...] = ("t", "time")
POSITION_NAMES: tuple[str, ...] = ("x", "position", "pos")
ACCELERATION_NAMES: tuple[str, ...] = ("a", "acceleration", "acc", "ax")


def unit_from_name(name: str) -> str | None:
    """A unit written in a column name: ``t [ms]``, ``t(ms)``, ``t_ms``, ``a_m_s2``; else None.

    Parameters
    ----------
    name : str
        The column name from a table header.

    Returns
    -------
    str or None
        The unit as text pint reads (``"ms"``, ``"m/s^2"``), or None when the name has none.

    Examples
    --------
    >>> unit_from_name("t [ms]"), unit_from_name("x_mm"), unit_from_name("acceleration_m_s2")
    ('ms', 'mm', 'm/s^2')
    >>> unit_from_name("x") is None
    True
    """
    import re

    match = re.search(r"[\[(]\s*([^\])]+?)\s*[\])]\s*$", name)
    if match:
        return match.group(1)
    lowered = name.strip().lower()
    for suffix, unit in _SUFFIX_UNITS:
        if lowered.endswith(suffix) and len(lowered) > len(suffix):
            return unit
    return None


def base_name(name: str) -> str:
    """A column name without its unit, lower case: ``"T [ms]"`` -> ``"t"``, ``x_mm`` -> ``x``.

    Parameters
    ----------
    name : str
        The column name from a table header.

    Returns
    -------
    str
        The name without a bracketed unit or a unit suffix, in lower case.

    Examples
    --------
    >>> base_name("T [ms]"), base_name("position_m"), base_name("qx")
    ('t', 'position', 'qx')
    """
    import re

    text = re.sub(r"\s*[\[(][^\])]*[\])]\s*$", "", name).strip().lower()
    if text != name.strip().lower():
        return text
    for suffix, _ in _SUFFIX_UNITS:
        if text.endswith(suffix) and len(text) > len(suffix):
            return text[: -len(suffix)]
    return text


def find_column(header: list[str], names: tuple[str, ...]) -> int | None:
    """Index of the first column whose unit-free name is one of ``names``, else None.

    Parameters
    ----------
    header : list of str
        Column names (with or without units).
    names : tuple of str
        Accepted unit-free names, in order of preference.

    Returns
    -------
    int or None
        The column index.

    Examples
    --------
    >>> find_column(["time [ms]", "x [mm]"], ("t", "time"))
    0
    """
    bases = [base_name(column) for column in header]
    return next((bases.index(name) for name in names if name in bases), None)


def column_si(
    header: list[str],
    data: FloatArray,
    index: int,
    kind: str,
    unit: str | None = None,
) -> FloatArray:
    """Column ``index`` converted to SI: by ``unit`` if given, else by the unit in its header
    name, else taken as SI already.

    Parameters
    ----------
    header, data : list of str, ndarray
        A table from `read_table`.
    index : int
        Column index.
    kind : str
        Quantity kind of `sloshkit.io.units.SI_UNITS` (``"time"``, ``"length"``, ...).
    unit : str, optional
        Unit overriding the header's.

    Returns
    -------
    ndarray
        The column in SI units.

    Examples
    --------
    >>> import numpy as np
    >>> column_si(["t [ms]"], np.array([[0.0], [250.0]]), 0, "time").tolist()
    [0.0, 0.25]
    """
    from sloshkit.io.units import parse_quantity

    written = unit or unit_from_name(header[index])
    scale = 1.0 if written is None else parse_quantity(f"1 {written}", kind, header[index])
    return np.asarray(data[:, index], dtype=float) * scale


def _split(line: str, delimiter: str | None) -> list[str]:
    if delimiter == ";":
        return [cell.replace(",", ".") for cell in line.split(";")]
    return line.split(delimiter) if delimiter else line.split()


def _is_numeric(cells: list[str]) -> bool:
    try:
        [float(cell) for cell in cells if cell.strip()]
    except ValueError:
        return False
    return True
