"""What the format writers share: number format and the metadata header."""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: Numbers are written with 12 significant digits: 1e-12 relative, far below what a
#: controller resolves (UR joint encoders resolve about 1e-5 rad).
NUMBER_FORMAT = ".12g"


#: Magnitudes below this are written as 0 (round-off of quantities that are zero).
ZERO_BELOW = 1e-12


def number(value: float) -> str:
    """A float as text (`NUMBER_FORMAT`; magnitudes below `ZERO_BELOW` and ``-0`` as ``0``).

    Parameters
    ----------
    value : float
        The number.

    Returns
    -------
    str

    Examples
    --------
    >>> number(0.1 + 0.2), number(-1e-14)
    ('0.3', '0')
    """
    if abs(float(value)) < ZERO_BELOW:
        return "0"
    return format(float(value), NUMBER_FORMAT)


def numbers(values: Iterable[float]) -> str:
    """Comma-separated `number` list.

    Parameters
    ----------
    values : iterable of float
        The numbers.

    Returns
    -------
    str

    Examples
    --------
    >>> numbers([0.5, -0.0, 1e-15, 2.25])
    '0.5,0,0,2.25'
    """
    return ",".join(number(value) for value in values)


def header_lines(metadata: Mapping[str, object], prefix: str = "# ") -> str:
    r"""``# key: value`` lines (one line per key; newlines in values become spaces).

    Parameters
    ----------
    metadata : mapping
        Keys and values.
    prefix : str
        The comment marker.

    Returns
    -------
    str
        The lines, each ending in a newline.

    Examples
    --------
    >>> header_lines({"law": "quintic", "note": "two\nlines"})
    '# law: quintic\n# note: two lines\n'
    """
    lines = []
    for key, value in metadata.items():
        text = " ".join(str(value).split())
        lines.append(f"{prefix}{key}: {text}\n")
    return "".join(lines)


def rows_csv(columns: Mapping[str, FloatArray]) -> str:
    """A CSV block: the header row, then one row per sample.

    Parameters
    ----------
    columns : mapping
        Column name -> equal-length 1-D arrays.

    Returns
    -------
    str

    Examples
    --------
    >>> import numpy as np
    >>> print(rows_csv({"t_s": np.array([0.0, 0.5]), "x_m": np.array([0.0, 0.1])}), end="")
    t_s,x_m
    0,0
    0.5,0.1
    """
    names = list(columns)
    table = np.column_stack([np.asarray(columns[name], dtype=float) for name in names])
    return ",".join(names) + "\n" + "".join(numbers(row) + "\n" for row in table)
