"""Reading sloshkit's CSV files: ``# key: value`` metadata lines, a header row, numbers."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


def read_csv_table(path: str | Path) -> tuple[list[str], FloatArray]:
    r"""A sloshkit CSV: ``#`` lines skipped, a header row, then numeric rows (2-D array).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    tuple
        (column names, values (rows, columns)).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
    >>> _ = out.write_text("# note: x\nt_s,a\n0,1\n0.5,2\n")
    >>> read_csv_table(out)
    (['t_s', 'a'], array([[0. , 1. ],
           [0.5, 2. ]]))
    """
    source = Path(path)
    if not source.is_file():
        raise InputError("file", str(source), "does not exist or is not a file")
    lines = [
        line.strip()
        for line in source.read_text(encoding="utf-8", errors="replace").splitlines()
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if len(lines) < 2:
        raise InputError("file", str(source), "needs a header row and data rows")
    header = [name.strip() for name in lines[0].split(",")]
    rows = []
    for number, line in enumerate(lines[1:], start=2):
        cells = line.split(",")
        try:
            row = [float(cell) for cell in cells]
        except ValueError:
            raise InputError(
                "file", f"{source}:{number}", f"row is not numeric: {line[:60]!r}"
            ) from None
        if len(row) != len(header):
            raise InputError("file", f"{source}:{number}", f"needs {len(header)} columns")
        rows.append(row)
    return header, np.asarray(rows, dtype=float)
