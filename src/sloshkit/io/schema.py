"""Typed reading of user documents (scenario and model files): one line naming the key.

`read_document` turns a file into a dict or refuses it in one line: missing, too large, binary
(NUL bytes), not UTF-8, nested too deeply, or not valid TOML/JSON. The typed getters (`quantity`,
`integer`, `number`, `boolean`, `text`, `text_list`) read one key of a table and name it with
its table path (``[container] radius``) when its TOML type is wrong: ``radius = true`` is not
1 m, ``laws = "quintic"`` is not a list of letters, ``modes = "three"`` is not a count.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from sloshkit.errors import InputError

#: Largest scenario or model file read (bytes); real ones are a few kB.
MAX_DOCUMENT_BYTES = 4 * 2**20

#: Deepest nesting of tables/arrays accepted (real files use 3).
MAX_DEPTH = 16


def read_document(path: str | Path, parameter: str) -> dict[str, Any]:
    """Read a TOML file (JSON for ``.json``) into a dict, or raise one-line `InputError`.

    Parameters
    ----------
    path : str or Path
        The file.
    parameter : str
        Its option or argument name (``"model_file"``, ``"scenario"``).

    Returns
    -------
    dict
        The parsed document (a table at the top).

    References
    ----------
    TOML v1.0.0 specification, https://toml.io/en/v1.0.0; RFC 8259 (JSON).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> file = pathlib.Path(tempfile.mkdtemp()) / "a.toml"
    >>> _ = file.write_text('[container]\\nradius = "20mm"\\n')
    >>> read_document(file, "scenario")
    {'container': {'radius': '20mm'}}
    """
    import tomllib

    source = Path(path)
    if not source.is_file():
        raise InputError(parameter, str(source), "does not exist or is not a file")
    size = source.stat().st_size
    if size > MAX_DOCUMENT_BYTES:
        raise InputError(
            parameter, str(source), f"is {size:,} bytes; at most {MAX_DOCUMENT_BYTES:,} expected"
        )
    raw = source.read_bytes()
    if b"\x00" in raw:
        raise InputError(parameter, str(source), "is a binary file, not TOML/JSON text")
    try:
        text = raw.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError as error:
        raise InputError(
            parameter, str(source), f"is not UTF-8 text (byte {error.start})"
        ) from None
    depth = _bracket_depth(text)
    if depth > MAX_DEPTH:
        raise InputError(parameter, str(source), f"is nested {depth} deep; at most {MAX_DEPTH}")
    try:
        document = json.loads(text) if source.suffix.lower() == ".json" else tomllib.loads(text)
    except (ValueError, RecursionError) as error:
        kind = "JSON" if source.suffix.lower() == ".json" else "TOML"
        reason = "nested too deeply" if isinstance(error, RecursionError) else str(error)
        raise InputError(parameter, str(source), f"is not valid {kind}: {reason}") from None
    if not isinstance(document, dict):
        raise InputError(parameter, str(source), "must hold a table/object at the top level")
    return document


def _bracket_depth(text: str) -> int:
    """Deepest nesting of brackets and braces (an upper bound outside strings)."""
    depth = deepest = 0
    for char in text:
        if char in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif char in "]}":
            depth = max(0, depth - 1)
    return deepest


def where(table: str, key: str) -> str:
    """The name of a key with its table path: ``[container] radius`` (top level: ``key``).

    Parameters
    ----------
    table : str
        The table's name (``""`` at the top level).
    key : str
        The key.

    Returns
    -------
    str

    Examples
    --------
    >>> where("container", "radius"), where("", "name")
    ('[container] radius', 'name')
    """
    return f"[{table}] {key}" if table else key


def section(document: dict[str, Any], name: str) -> dict[str, Any]:
    """The table ``[name]`` of ``document`` (empty if absent); `InputError` if not a table.

    Parameters
    ----------
    document : dict
        The parsed document (`read_document`).
    name : str
        The table's name.

    Returns
    -------
    dict

    Examples
    --------
    >>> section({"container": {"radius": "20mm"}}, "container")
    {'radius': '20mm'}
    """
    value = document.get(name, {})
    if not isinstance(value, dict):
        raise InputError(f"[{name}]", _shown(value), "must be a table")
    return value


def quantity(table: dict[str, Any], name: str, key: str, kind: str, default: Any = None) -> Any:
    """A quantity with units (text like ``"20mm"``) or a bare SI number; None if absent.

    Parameters
    ----------
    table : dict
        The TOML table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    kind : str
        The quantity kind (`sloshkit.io.units.SI_UNITS`).
    default : str or float, optional
        Used when the key is absent (parsed the same way).

    Returns
    -------
    float or None
        The value in SI units.

    Examples
    --------
    >>> quantity({"radius": "20mm"}, "container", "radius", "length")
    0.02
    """
    from sloshkit.io.units import parse_quantity

    if key not in table:
        return default if default is None else parse_quantity(default, kind, where(name, key))
    return parse_quantity(
        _scalar(table[key], name, key, "a number or text"), kind, where(name, key)
    )


def integer(table: dict[str, Any], name: str, key: str, default: int, low: int, high: int) -> int:
    """An integer in [low, high] (not a bool, not text, not a float).

    Parameters
    ----------
    table : dict
        The TOML table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    default : int
        Used when the key is absent.
    low, high : int
        The accepted range.

    Returns
    -------
    int

    Examples
    --------
    >>> integer({"modes": 3}, "model", "modes", 3, 1, 10)
    3
    """
    value = table.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int):
        raise InputError(where(name, key), _shown(value), f"must be an integer in {low}..{high}")
    if not low <= value <= high:
        raise InputError(where(name, key), value, f"must be between {low} and {high}")
    return value


def number(
    table: dict[str, Any], name: str, key: str, default: float | None = None
) -> float | None:
    """A finite float (int accepted, bool and text refused); None if absent and no default.

    Parameters
    ----------
    table : dict
        The TOML table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    default : float, optional
        Used when the key is absent.

    Returns
    -------
    float or None

    Examples
    --------
    >>> number({"damping_ratio": 0.01}, "model", "damping_ratio")
    0.01
    """
    if key not in table:
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(where(name, key), _shown(value), "must be a number")
    if not math.isfinite(value):
        raise InputError(where(name, key), value, "must be finite")
    return float(value)


def boolean(table: dict[str, Any], name: str, key: str, default: bool = False) -> bool:
    """A TOML boolean (``true``/``false``); text and numbers refused.

    Parameters
    ----------
    table : dict
        The TOML table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    default : bool
        Used when the key is absent.

    Returns
    -------
    bool

    Examples
    --------
    >>> boolean({"robust": True}, "limits", "robust")
    True
    """
    value = table.get(key, default)
    if not isinstance(value, bool):
        raise InputError(where(name, key), _shown(value), "must be true or false")
    return value


def text(table: dict[str, Any], name: str, key: str, default: str | None = None) -> str | None:
    """A string (numbers and tables refused); None if absent and no default.

    Parameters
    ----------
    table : dict
        The TOML table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    default : str, optional
        Used when the key is absent.

    Returns
    -------
    str or None

    Examples
    --------
    >>> text({"preset": "water-25C"}, "liquid", "preset")
    'water-25C'
    """
    value = table.get(key, default)
    if value is None:
        return None
    if not isinstance(value, str):
        raise InputError(where(name, key), _shown(value), "must be text (in quotes)")
    return value


def text_list(
    table: dict[str, Any], name: str, key: str, default: list[str] | tuple[str, ...]
) -> tuple[str, ...]:
    """A list of strings, e.g. ``laws = ["quintic", "septic"]``; a lone string is refused.

    Parameters
    ----------
    table : dict
        The TOML table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    default : list or tuple of str
        Used when the key is absent.

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> text_list({"laws": ["quintic"]}, "move", "laws", ())
    ('quintic',)
    """
    value = table.get(key, list(default))
    if isinstance(value, str):
        raise InputError(
            where(name, key), value, f'must be a list of names, e.g. ["{value}"] (in brackets)'
        )
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise InputError(where(name, key), _shown(value), "must be a list of names in quotes")
    return tuple(value)


def number_list(
    table: dict[str, Any], name: str, key: str, length: int | None = None
) -> list[float] | None:
    """A list of finite numbers (ints or floats; bools, text and NaN refused); None if absent.

    Parameters
    ----------
    table : dict
        The table holding the key.
    name : str
        The table's name (``""`` at the top level), for the message.
    key : str
        The key.
    length : int, optional
        Required number of items.

    Returns
    -------
    list of float or None

    Examples
    --------
    >>> number_list({"yaw_deg": [0, 90.0]}, "", "yaw_deg")
    [0.0, 90.0]
    """
    if key not in table:
        return None
    value = table[key]
    if not isinstance(value, list):
        raise InputError(where(name, key), _shown(value), "must be a list of numbers")
    if length is not None and len(value) != length:
        raise InputError(where(name, key), _shown(value), f"must hold {length} numbers")
    numbers = []
    for index, item in enumerate(value):
        if isinstance(item, bool) or not isinstance(item, int | float):
            raise InputError(
                f"{where(name, key)} item {index + 1}", _shown(item), "must be a number"
            )
        if not math.isfinite(item):
            raise InputError(f"{where(name, key)} item {index + 1}", item, "must be finite")
        numbers.append(float(item))
    return numbers


def number_rows(
    table: dict[str, Any], name: str, key: str, width: int, most: int = 100_000
) -> list[list[float]] | None:
    """A list of rows of ``width`` finite numbers, e.g. ``waypoints = [[0, 0, 0], ...]``.

    Parameters
    ----------
    table : dict
        The table holding the key.
    name : str
        The table's name (``""`` at the top level).
    key : str
        The key.
    width : int
        Numbers per row.
    most : int
        Largest number of rows accepted.

    Returns
    -------
    list of list of float or None
        None if the key is absent.

    Examples
    --------
    >>> number_rows({"waypoints": [[0, 0, 0], [0.1, 0, 0]]}, "", "waypoints", 3)
    [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]]
    """
    if key not in table:
        return None
    value = table[key]
    if not isinstance(value, list):
        raise InputError(where(name, key), _shown(value), f"must be a list of [{width} numbers]")
    if len(value) > most:
        raise InputError(where(name, key), f"{len(value)} rows", f"at most {most:,} rows")
    rows = []
    for index, row in enumerate(value):
        label = f"{where(name, key)} row {index + 1}"
        if not isinstance(row, list) or len(row) != width:
            raise InputError(label, _shown(row), f"must be a list of {width} numbers")
        rows.append(number_list({key: row}, name, key, width) or [])
    return rows


def _scalar(value: Any, name: str, key: str, expected: str) -> Any:
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise InputError(where(name, key), _shown(value), f"must be {expected}")
    return value


class _Shown:
    """A value for a message: its TOML type and a short literal (never a huge dump)."""

    def __init__(self, value: Any) -> None:
        self.value = value

    def __str__(self) -> str:
        literal = repr(self.value)
        if len(literal) > 40:
            literal = literal[:37] + "..."
        names = {bool: "boolean", list: "array", dict: "table", str: "string"}
        return f"{literal} (a {names.get(type(self.value), type(self.value).__name__)})"


def _shown(value: Any) -> Any:
    return _Shown(value)
