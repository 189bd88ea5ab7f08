"""File input at the edge: numeric tables (CSV or whitespace), their columns and units, user
motions. Readers are named ``read_*``; the atomic writers are in `sloshkit.files`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.motion.recorded import from_samples

FloatArray = NDArray[np.float64]


def read_table(path: str | Path) -> tuple[list[str], FloatArray]:
    """Read a numeric table: CSV (comma or semicolon) or whitespace-separated, ``#`` comments
    skipped; with semicolons, decimal commas are accepted.

    The first non-comment line is a header when it is not numeric; otherwise columns are named
    by their index (``"0"``, ``"1"``, ...). OpenFOAM function-object files (``# Time ...``
    headers, vectors in parentheses) are read too: parentheses are dropped, vector components
    become separate columns, and a last comment line naming the columns is used as the header.
    Raises `InputError` for a missing or empty file or non-numeric cells.

    Parameters
    ----------
    path : str or Path
        The file (a UTF-8 byte-order mark is removed).

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
    source = Path(path)
    if not source.is_file():
        raise InputError("file", str(source), "does not exist or is not a file")
    from sloshkit.budget import require_memory

    # Text, lines and rows of Python floats: about 20 bytes per byte of text.
    require_memory("file", str(source), 20.0 * source.stat().st_size, "table parsed in memory")
    text = source.read_text(encoding="utf-8", errors="replace").removeprefix("\ufeff")
    last_comment = ""
    lines: list[str] = []
    for raw in text.splitlines():
        stripped = raw.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            last_comment = stripped.lstrip("#").strip()
            continue
        lines.append(stripped.replace("(", " ").replace(")", " "))
    if not lines:
        raise InputError("file", str(source), "has no data rows")
    # semicolon CSV (spreadsheet exports; decimal commas allowed), comma CSV, or whitespace
    delimiter = ";" if ";" in lines[0] else ("," if "," in lines[0] else None)
    first = _split(lines[0], delimiter)
    header: list[str] | None = None
    if not _is_numeric(first):
        header = [name.strip() for name in first]
        lines = lines[1:]
    if not lines:
        raise InputError("file", str(source), "has a header but no data rows")
    rows = []
    for number, line in enumerate(lines, start=1):
        cells = _split(line, delimiter)
        try:
            rows.append([float(cell) if cell.strip() else float("nan") for cell in cells])
        except ValueError:
            raise InputError(
                "file", f"{source}:{number}", f"row is not numeric: {line[:60]!r}"
            ) from None
    width = max(len(row) for row in rows)
    if any(len(row) != width for row in rows):
        raise InputError("file", str(source), "rows have different numbers of columns")
    data = np.asarray(rows, dtype=float)
    if header is None and last_comment:
        candidate = last_comment.split()
        header = candidate if len(candidate) == width else None
    if header is None or len(header) != width:
        header = [str(index) for index in range(width)]
    return header, data


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

#: What a container move plausibly spans (SI); beyond it a motion file was most likely written
#: in other units (ms, mm) without saying so in its header.
PLAUSIBLE_MOVE = {"duration_s": 60.0, "travel_m": 5.0, "acceleration_m_s2": 500.0}


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


def read_motion_file(path: str | Path, name: str | None = None) -> Any:
    r"""A user motion from a table with a time column and a position or acceleration column.

    Column names decide, with their units: time ``t``/``time``, position ``x``/``position``,
    or acceleration ``a``/``acceleration``, each optionally with a unit in brackets (``t [ms]``,
    ``x [mm]``, ``a [m/s^2]``) or as a suffix (``t_ms``, ``x_mm``, ``a_m_s2``); a name without a
    unit is SI (s, m, m/s^2). Without a header, column 0 is time [s] and column 1 position [m].
    A move that looks implausible in SI (longer than a minute, farther than 5 m, above
    500 m/s^2) raises a `ValidityWarning` that suggests writing the units in the header.
    See `sloshkit.motion.recorded.from_samples` for the interpolation.

    Parameters
    ----------
    path : str or Path
        CSV or whitespace table.
    name : str, optional
        Name of the motion (default ``file:PATH``).

    Returns
    -------
    Motion
        The rest-to-rest motion.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> u = [t / 2000 for t in range(0, 2001, 100)]
    >>> rows = "\n".join(f"{2000 * v},{20 * (10 * v**3 - 15 * v**4 + 6 * v**5)}" for v in u)
    >>> _ = (folder / "move.csv").write_text("t [ms],x [mm]\n" + rows + "\n")
    >>> motion = read_motion_file(folder / "move.csv")
    >>> round(motion.duration_s, 3), round(motion.distance_m, 3)
    (2.0, 0.02)
    """
    header, data = read_table(path)
    label = name or f"file:{path}"
    time_index = find_column(header, TIME_NAMES)
    time_s = column_si(header, data, 0 if time_index is None else time_index, "time")
    position = find_column(header, POSITION_NAMES)
    acceleration = find_column(header, ACCELERATION_NAMES)
    if position is not None:
        values = column_si(header, data, position, "length")
        motion = from_samples(time_s, position_m=values, name=label)
        _warn_unless_at_rest(motion, time_s, path, values)
    elif acceleration is not None:
        values = column_si(header, data, acceleration, "acceleration")
        motion = from_samples(time_s, acceleration_m_s2=values, name=label)
        _warn_unless_at_rest(motion, time_s, path)
    else:
        if data.shape[1] < 2:
            raise InputError("file", str(path), "needs a time column and a position column")
        values = column_si(header, data, 1, "length")
        motion = from_samples(time_s, position_m=values, name=label)
        _warn_unless_at_rest(motion, time_s, path, values)
    check_plausible_move(motion, str(path))
    return motion


def check_plausible_move(motion: Any, source: str) -> list[str]:
    """Warn (`ValidityWarning`) when a motion read from ``source`` is implausible for a
    container move in SI units (see `PLAUSIBLE_MOVE`): most likely a file in ms or mm whose
    header does not say so.

    Parameters
    ----------
    motion : Motion
        The motion as read.
    source : str
        Where it came from (for the message).

    Returns
    -------
    list of str
        The warning messages (empty when the move is plausible).

    Examples
    --------
    >>> from sloshkit.motion import trapezoidal
    >>> check_plausible_move(trapezoidal(0.5, duration_s=1.5), "move.csv")
    []
    """
    from sloshkit.errors import warn_validity

    findings = []
    if motion.duration_s > PLAUSIBLE_MOVE["duration_s"]:
        findings.append(f"lasts {motion.duration_s:,.4g} s")
    if abs(motion.distance_m) > PLAUSIBLE_MOVE["travel_m"]:
        findings.append(f"travels {motion.distance_m:,.4g} m")
    peak = float(np.max(np.abs(motion.acceleration(np.linspace(0, motion.duration_s, 2001)))))
    if peak > PLAUSIBLE_MOVE["acceleration_m_s2"]:
        findings.append(f"accelerates at {peak:,.4g} m/s^2")
    if not findings:
        return []
    message = (
        f"motion file {source}: the move {' and '.join(findings)}, implausible for a container; "
        "columns without a unit are read as s, m, m/s^2: write units in the header, "
        "e.g. 't [ms],x [mm]'"
    )
    warn_validity(message)
    return [message]


#: A slosh record (a free decay or a move and its decay) longer than this is implausible [s].
PLAUSIBLE_RECORD_S = 600.0


def check_plausible_record(time_s: FloatArray, source: str) -> list[str]:
    """Warn (`ValidityWarning`) when a calibration record's time column, read in seconds, spans
    more than `PLAUSIBLE_RECORD_S`: most likely milliseconds without a unit in the header.

    Parameters
    ----------
    time_s : ndarray
        The record's time column as read [s].
    source : str
        The record's file (for the message).

    Returns
    -------
    list of str
        The warning messages (empty when the span is plausible).

    Examples
    --------
    >>> import numpy as np
    >>> check_plausible_record(np.linspace(0.0, 8.0, 801), "decay.csv")
    []
    """
    from sloshkit.errors import warn_validity

    span = float(np.nanmax(time_s) - np.nanmin(time_s)) if time_s.size else 0.0
    if span <= PLAUSIBLE_RECORD_S:
        return []
    message = (
        f"record {source}: the time column spans {span:,.4g} s, implausible for a slosh record; "
        "if it is in ms, name the column 't [ms]' or pass --time-unit ms"
    )
    warn_validity(message)
    return [message]


#: Velocity at either end of a motion file, relative to its peak, above which it is not at rest.
REST_TOLERANCE = 0.02


def _warn_unless_at_rest(
    motion: Any, time_s: FloatArray, path: str | Path, position_m: FloatArray | None = None
) -> Any:
    """Warn (`ValidityWarning`) when a motion file does not start and end at rest.

    For positions the end velocity is the last difference quotient of the samples (the spline
    then forces a stop that is not in the data); for accelerations it is the integrated
    velocity at the last sample (the container would keep moving).
    """
    from sloshkit.errors import warn_validity

    t = np.asarray(time_s, dtype=float) - float(time_s[0])
    if position_m is not None:
        velocity = np.diff(position_m) / np.diff(t)
        ends = {"start": velocity[0], "end": velocity[-1]}
    else:
        velocity = motion.velocity(t)
        ends = {"end": velocity[-1]}
    peak = float(np.max(np.abs(velocity))) if velocity.size else 0.0
    for where, value in ends.items():
        if peak > 0.0 and abs(float(value)) > REST_TOLERANCE * peak:
            warn_validity(
                f"motion file {path} does not {where} at rest (velocity {float(value):.3g} m/s "
                f"at its {where}, {100 * abs(float(value)) / peak:.0f} % of the peak); the "
                "result assumes a rest-to-rest move"
            )
    return motion


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
