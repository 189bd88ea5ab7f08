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
    """Column by name, or by 0-based index given as text; `InputError` lists the names."""
    if column in header:
        return np.asarray(data[:, header.index(column)], dtype=float)
    if column.lstrip("-").isdigit() and -len(header) <= int(column) < len(header):
        return np.asarray(data[:, int(column)], dtype=float)
    raise InputError(parameter, column, "is not a column; columns are " + ", ".join(header))


def column_name(header: list[str], column: str) -> str:
    """The header name of a column given by name or 0-based index."""
    if column in header:
        return column
    if column.lstrip("-").isdigit() and -len(header) <= int(column) < len(header):
        return header[int(column)]
    return column


def unit_from_name(name: str) -> str | None:
    """A unit written in a column name: ``t [ms]``, ``t(ms)`` or ``t_ms``; None if absent."""
    import re

    match = re.search(r"[\[(]\s*([^\])]+?)\s*[\])]\s*$", name)
    if match:
        return match.group(1)
    match = re.search(r"_(ms|s|us|min)$", name)
    return match.group(1) if match else None


def read_motion_file(path: str | Path, name: str | None = None) -> Any:
    """A user motion from a table with a time column and a position or acceleration column.

    Column names (header) decide: time ``t``, ``t_s`` or ``time``; position ``x``,
    ``position``, ``position_m``; or acceleration ``a``, ``acceleration``,
    ``acceleration_m_s2``. Without a header, column 0 is time and column 1 is position.
    See `sloshkit.motion.laws.from_samples` for the interpolation.
    """

    header, data = read_table(path)
    lowered = [column.lower() for column in header]
    time_index = next((lowered.index(n) for n in ("t", "t_s", "time", "time_s") if n in lowered), 0)
    for names, keyword in (
        (("x", "position", "position_m", "x_m"), "position_m"),
        (("a", "acceleration", "acceleration_m_s2", "a_m_s2"), "acceleration_m_s2"),
    ):
        found = next((lowered.index(n) for n in names if n in lowered), None)
        if found is not None:
            motion = from_samples(
                data[:, time_index], name=name or f"file:{path}", **{keyword: data[:, found]}
            )
            positions = data[:, found] if keyword == "position_m" else None
            return _warn_unless_at_rest(motion, data[:, time_index], path, positions)
    if data.shape[1] < 2:
        raise InputError("file", str(path), "needs a time column and a position column")
    motion = from_samples(data[:, time_index], position_m=data[:, 1], name=name or f"file:{path}")
    if lowered[1] not in ("a", "acceleration", "acceleration_m_s2", "a_m_s2"):
        _warn_unless_at_rest(motion, data[:, time_index], path, data[:, 1])
    return motion


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
