"""OpenFOAM dictionary syntax: a small writer and a reader for uniform/nonuniform fields.

The writer turns nested Python values into dictionary text: ``dict`` -> ``{ key value; }``,
``list``/``tuple`` of numbers -> ``(a b c)``, `Raw` -> verbatim text. Strings are written as
words (quote them yourself when OpenFOAM wants a string).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

HEADER = """/*--------------------------------*- C++ -*----------------------------------*\\
  Written by sloshkit for OpenFOAM v1912 (interFoam)
\\*---------------------------------------------------------------------------*/
"""


@dataclass(frozen=True)
class Raw:
    """Text written verbatim (block lists, tables, #include lines).

    Parameters
    ----------
    text : str
        The text, as OpenFOAM should read it.

    Returns
    -------
    Raw

    Examples
    --------
    >>> format_value(Raw("(0 0 -9810)"))
    '(0 0 -9810)'
    """

    text: str


def format_value(value: Any, indent: int = 0) -> str:
    """One value in OpenFOAM syntax.

    Parameters
    ----------
    value : Any
        `Raw`, bool, int, float, str, mapping (a sub-dictionary) or list/tuple.
    indent : int
        Nesting level of a sub-dictionary (4 spaces each).

    Returns
    -------
    str

    Examples
    --------
    >>> format_value([1, 2.5, True])
    '(1 2.5 true)'
    """
    pad = "    " * indent
    if isinstance(value, Raw):
        return value.text
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | np.integer):
        return str(int(value))
    if isinstance(value, float | np.floating):
        return format_number(float(value))
    if isinstance(value, str):
        return value
    if isinstance(value, Mapping):
        inner = "".join(format_entry(k, v, indent + 1) for k, v in value.items())
        return "\n" + pad + "{\n" + inner + pad + "}"
    if isinstance(value, list | tuple):
        return "(" + " ".join(format_value(item, indent) for item in value) + ")"
    raise TypeError(f"cannot write {type(value).__name__} as OpenFOAM syntax")


def format_number(value: float) -> str:
    """Shortest round-tripping text of a float (no trailing .0 noise).

    Parameters
    ----------
    value : float

    Returns
    -------
    str

    Examples
    --------
    >>> format_number(9810.0), format_number(1e-07)
    ('9810', '1e-07')
    """
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def format_entry(key: str, value: Any, indent: int = 0) -> str:
    r"""``key value;`` (or ``key { ... }`` for a dictionary).

    Parameters
    ----------
    key : str
    value : Any
        See `format_value`.
    indent : int
        Nesting level.

    Returns
    -------
    str
        The entry with its newline.

    Examples
    --------
    >>> format_entry("nCorrectors", 3)
    'nCorrectors     3;\n'
    """
    pad = "    " * indent
    if isinstance(value, Mapping):
        return f"{pad}{key}{format_value(value, indent)}\n"
    return f"{pad}{key:<15} {format_value(value, indent)};\n"


def foam_file(
    class_name: str, object_name: str, entries: Mapping[str, Any], location: str = ""
) -> str:
    """A complete dictionary file with its FoamFile header.

    Parameters
    ----------
    class_name : str
        ``dictionary``, ``volScalarField``, ...
    object_name : str
        The file's object name.
    entries : Mapping
        Its entries (see `format_value`).
    location : str
        Its folder in the case (``system``, ``constant``, ``0``), if any.

    Returns
    -------
    str

    Examples
    --------
    >>> text = foam_file("dictionary", "g", {"value": Raw("(0 0 -9810)")}, "constant")
    >>> text.splitlines()[-1]
    'value           (0 0 -9810);'
    """
    header = {"version": 2.0, "format": "ascii", "class": class_name}
    if location:
        header["location"] = f'"{location}"'
    header["object"] = object_name
    body = "".join(format_entry(k, v) for k, v in entries.items())
    return HEADER + format_entry("FoamFile", header) + "\n" + body


_FIELD = re.compile(
    r"internalField\s+(?:uniform\s+(?P<uniform>[^;]+);|nonuniform\s+List<scalar>\s*(?P<count>\d+)\s*\((?P<values>[^)]*)\))",
    re.S,
)


def read_scalar_internal_field(text: str, cells: int | None = None) -> NDArray[np.float64]:
    """The internalField of a volScalarField file (uniform or nonuniform List<scalar>).

    Parameters
    ----------
    text : str
        The field file's text.
    cells : int, optional
        Cell count, needed to expand a uniform field.

    Returns
    -------
    ndarray
        One value per cell.

    Raises
    ------
    ValueError
        No scalar internalField, or a list shorter or longer than its header says.

    Examples
    --------
    >>> read_scalar_internal_field("internalField nonuniform List<scalar> 2 (0 1);")
    array([0., 1.])
    >>> read_scalar_internal_field("internalField uniform 0.5;", cells=3)
    array([0.5, 0.5, 0.5])
    """
    match = _FIELD.search(text)
    if match is None:
        raise ValueError("no scalar internalField found")
    if match.group("uniform") is not None:
        if cells is None:
            raise ValueError("a uniform field needs the cell count")
        return np.full(cells, float(match.group("uniform")))
    values = np.array(match.group("values").split(), dtype=float)
    if values.size != int(match.group("count")):
        raise ValueError(f"field lists {values.size} values, header says {match.group('count')}")
    return values
