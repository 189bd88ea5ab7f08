"""Units at the edge (CLI and scenario files): text like ``20.5mm`` -> SI float.

The grammar is strict on purpose: a decimal number, an optional exponent and one unit from a
fixed table, nothing else (no arithmetic, no expression evaluation, no locale commas)::

    quantity := number [unit]
    number   := [+-] digits [. digits] [(e|E) [+-] digits]
    unit     := a name from `UNITS` for the quantity's kind (``m/s^2``, ``mPa*s``, ``deg``, ...)

Parsing is a single anchored regular expression and a dictionary look-up, so any text costs
microseconds (the old pint evaluation turned ``9**9**9 m`` into a 100 % CPU hang). Numbers that
are not normal doubles (``1e-320``, ``1e400``, results that underflow to 0 or overflow to inf)
are refused instead of silently becoming 0 or inf.
"""

from __future__ import annotations

import math
import re
import sys

from sloshkit.errors import InputError

#: SI unit for each kind of quantity; a bare number is read in this unit.
SI_UNITS: dict[str, str] = {
    "length": "m",
    "volume": "m^3",
    "time": "s",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "jerk": "m/s^3",
    "angle": "rad",
    "angular_velocity": "rad/s",
    "angular_acceleration": "rad/s^2",
    "frequency": "Hz",
    "density": "kg/m^3",
    "viscosity": "Pa*s",
    "surface_tension": "N/m",
    "fraction": "1",
}

_LENGTH = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "km": 1e3, "in": 0.0254, "ft": 0.3048}
_TIME = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9, "min": 60.0, "h": 3600.0}


def _rates(power: int) -> dict[str, float]:
    suffix = "" if power == 1 else f"^{power}"
    return {
        f"{length}/{time}{suffix}": scale / step**power
        for length, scale in _LENGTH.items()
        for time, step in _TIME.items()
    }


#: The accepted unit names per kind, with their factor to SI (after `_normalise`).
UNITS: dict[str, dict[str, float]] = {
    "length": dict(_LENGTH),
    "volume": {
        "m^3": 1.0,
        "cm^3": 1e-6,
        "mm^3": 1e-9,
        "cc": 1e-6,
        "L": 1e-3,
        "l": 1e-3,
        "mL": 1e-6,
        "ml": 1e-6,
        "uL": 1e-9,
        "ul": 1e-9,
    },
    "time": dict(_TIME),
    "velocity": {**_rates(1), "km/h": 1.0 / 3.6},
    "acceleration": _rates(2),
    "jerk": _rates(3),
    "angle": {
        "rad": 1.0,
        "mrad": 1e-3,
        "deg": math.pi / 180.0,
        "degree": math.pi / 180.0,
        "degrees": math.pi / 180.0,
        "°": math.pi / 180.0,
        "arcmin": math.pi / 10800.0,
    },
    "angular_velocity": {
        "rad/s": 1.0,
        "deg/s": math.pi / 180.0,
        "°/s": math.pi / 180.0,
        "rpm": 2.0 * math.pi / 60.0,
    },
    "angular_acceleration": {
        "rad/s^2": 1.0,
        "rad/s2": 1.0,
        "deg/s^2": math.pi / 180.0,
        "deg/s2": math.pi / 180.0,
        "°/s^2": math.pi / 180.0,
    },
    "frequency": {"Hz": 1.0, "mHz": 1e-3, "kHz": 1e3, "rpm": 1.0 / 60.0},
    "density": {
        "kg/m^3": 1.0,
        "g/cm^3": 1e3,
        "g/mL": 1e3,
        "g/ml": 1e3,
        "kg/L": 1e3,
        "kg/l": 1e3,
        "g/L": 1.0,
        "g/l": 1.0,
    },
    "viscosity": {
        "Pa*s": 1.0,
        "mPa*s": 1e-3,
        "uPa*s": 1e-6,
        "P": 0.1,
        "cP": 1e-3,
        "poise": 0.1,
        "centipoise": 1e-3,
    },
    "surface_tension": {"N/m": 1.0, "mN/m": 1e-3, "dyn/cm": 1e-3},
    "fraction": {"%": 1e-2, "percent": 1e-2},
}

_EXAMPLES: dict[str, str] = {
    "length": "20.5mm",
    "volume": "2mL",
    "time": "1.5s",
    "velocity": "0.5m/s",
    "acceleration": "5m/s^2",
    "jerk": "50m/s^3",
    "angle": "5deg",
    "angular_velocity": "180deg/s",
    "angular_acceleration": "1000deg/s^2",
    "frequency": "4.7Hz",
    "density": "997kg/m^3",
    "viscosity": "0.89mPa*s",
    "surface_tension": "72mN/m",
    "fraction": "10%",
}

#: Longest text accepted for one quantity (a guard against pasted files, not a real limit).
MAX_TEXT_LENGTH = 64

_QUANTITY = re.compile(  # ASCII digits only: no full-width or other-script digits
    r"(?P<number>[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)"
    r"\s*(?P<unit>[^0-9\s+-]\S*(?:\s+\S+)?)?",
    re.ASCII,
)
_SUPERSCRIPTS = str.maketrans({"²": "^2", "³": "^3", "µ": "u", "μ": "u", "·": "*", "⋅": "*"})


def _normalise(unit: str) -> str:
    """One spelling per unit: ``m/s**2`` and ``m/s²`` -> ``m/s^2``; ``mPa s`` -> ``mPa*s``."""
    text = unit.translate(_SUPERSCRIPTS).replace("**", "^")
    return re.sub(r"\s+", "*", text.strip())


def parse_quantity(text: str | float, kind: str, parameter: str) -> float:
    """Parse ``text`` (e.g. ``"20.5mm"``, ``"0.5 m/s"``, ``"5deg"``, ``"2 mL"``) into SI.

    A bare number is taken in the SI unit of ``kind`` (see `SI_UNITS`); bare angles are
    radians. Numbers from files (int or float, not bool) are SI too.

    Parameters
    ----------
    text : str or float
        The quantity as typed, or a number already in SI.
    kind : str
        A key of `SI_UNITS` (``"length"``, ``"time"``, ...).
    parameter : str
        The option or key name, for the error message.

    Returns
    -------
    float
        The value in SI units: finite, and 0 or a normal double.

    Raises
    ------
    InputError
        Naming ``parameter`` for anything but a number and a known unit of ``kind``.

    References
    ----------
    BIPM (2019), The International System of Units (SI), 9th ed., for the unit factors.

    Examples
    --------
    >>> parse_quantity("20.5mm", "length", "radius")
    0.0205
    >>> parse_quantity("5m/s^2", "acceleration", "amax")
    5.0
    """
    if kind not in UNITS:
        raise InputError("kind", kind, "must be one of " + ", ".join(UNITS))
    example = _EXAMPLES[kind]
    if isinstance(text, bool) or not isinstance(text, int | float | str):
        raise InputError(
            parameter, _shown(text), f"must be a number with a {kind} unit, e.g. {example!r}"
        )
    if isinstance(text, int | float):
        return _checked(float(text), text, parameter, kind)
    if len(text) > MAX_TEXT_LENGTH:
        raise InputError(parameter, text[:20] + "...", f"is longer than {MAX_TEXT_LENGTH} chars")
    stripped = text.strip()
    match = _QUANTITY.fullmatch(stripped)
    if match is None:
        raise InputError(
            parameter,
            text,
            f"must be a number and a {kind} unit, e.g. {example!r}",
            _hint(stripped),
        )
    mantissa = float(match.group("number"))
    unit = match.group("unit")
    factor = 1.0
    if unit is not None:
        table = UNITS[kind]
        key = _normalise(unit)
        if key not in table:
            known = next((k for k, units in UNITS.items() if key in units), None)
            valid = (
                f"is {_article(known)} {known}, not {_article(kind)} {kind} (e.g. {example!r})"
                if known
                else f"unknown {kind} unit {unit!r}; use e.g. {example!r} or "
                + ", ".join(list(table)[:6])
            )
            raise InputError(parameter, text, valid, _hint(stripped))
        factor = table[key]
    return _checked(mantissa * factor, text, parameter, kind, nonzero=_nonzero(match))


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"


def _hint(text: str) -> str:
    """A hint for the usual mistakes: a decimal comma, arithmetic."""
    if re.fullmatch(r"[+-]?\d+,\d+.*", text):
        return "use a decimal point, not a comma: " + text.replace(",", ".", 1)
    if re.search(r"\*\*|[()]|[*/^+]\s*[\d.]|\d\s*[*/+]", text):
        return "arithmetic is not evaluated; write one number and a unit"
    return ""


def _nonzero(match: re.Match[str]) -> bool:
    digits = match.group("number").lower().split("e")[0]
    return any(c in "123456789" for c in digits)


def _checked(
    value: float, text: object, parameter: str, kind: str, nonzero: bool | None = None
) -> float:
    """``value`` unless it is NaN, infinite, subnormal, or a non-zero input that became 0."""
    if nonzero is None:
        nonzero = value != 0.0
    if not math.isfinite(value):
        raise InputError(parameter, _shown(text), f"must be a finite {kind}")
    if (nonzero and value == 0.0) or (value != 0.0 and abs(value) < sys.float_info.min):
        raise InputError(
            parameter,
            _shown(text),
            f"is too small to represent (below {sys.float_info.min:.3g} in SI {SI_UNITS[kind]})",
        )
    return value


def _shown(value: object) -> object:
    if isinstance(value, str | int | float):
        return value
    return f"<{type(value).__name__}>"


def parse_bounded(
    text: str | float, kind: str, parameter: str, low: float, high: float, low_open: bool = True
) -> float:
    """`parse_quantity`, then ``low < value <= high`` (``low <= value`` with ``low_open=False``).

    Parameters
    ----------
    text : str or float
        The quantity as typed.
    kind : str
        A key of `SI_UNITS`.
    parameter : str
        The option name, for the error message.
    low, high : float
        The accepted range in SI units.
    low_open : bool
        Exclude ``low`` itself (the default: "must be > 0").

    Returns
    -------
    float
        The value in SI units.

    Examples
    --------
    >>> round(parse_bounded("3deg", "angle", "tilt", 0.0, 0.8), 6)
    0.05236
    """
    value = parse_quantity(text, kind, parameter)
    above = value > low if low_open else value >= low
    if not (above and value <= high):
        unit = SI_UNITS[kind]
        opening = "(" if low_open else "["
        raise InputError(
            parameter, text, f"must be in {opening}{low:g}, {high:g}] {unit} (SI)".rstrip()
        )
    return value


def parse_number(text: str | float, parameter: str) -> float:
    """A plain finite number in the strict grammar (no unit, no arithmetic, no ``nan``/``inf``).

    Parameters
    ----------
    text : str or float
        The number as typed.
    parameter : str
        The option name, for the error message.

    Returns
    -------
    float
        The number: finite, 0 or a normal double.

    Examples
    --------
    >>> parse_number(" -0.5 ", "axis")
    -0.5
    """
    if isinstance(text, str):
        stripped = text.strip()
        match = _QUANTITY.fullmatch(stripped) if len(stripped) <= MAX_TEXT_LENGTH else None
        if match is None or match.group("unit") is not None:
            raise InputError(parameter, text, "must be a plain number, e.g. 0.5", _hint(stripped))
        return _checked(float(match.group("number")), text, parameter, "fraction", _nonzero(match))
    if isinstance(text, bool) or not isinstance(text, int | float):
        raise InputError(parameter, _shown(text), "must be a number")
    return _checked(float(text), text, parameter, "fraction")


def parse_count(text: str | int, parameter: str, low: int, high: int) -> int:
    """A whole number in [low, high] typed as text (``"12"``; no sign tricks, no floats).

    Parameters
    ----------
    text : str or int
        The count as typed.
    parameter : str
        The option name, for the error message.
    low, high : int
        The accepted range (ends included).

    Returns
    -------
    int

    Examples
    --------
    >>> parse_count("12", "meshes", 3, 60)
    12
    """
    shown = str(text).strip()
    if isinstance(text, bool) or not re.fullmatch(r"\+?[0-9]{1,12}", shown):
        raise InputError(parameter, text, f"must be a whole number in {low}..{high}")
    count = int(shown)
    if not low <= count <= high:
        raise InputError(parameter, text, f"must be between {low} and {high}")
    return count


def parse_range(text: str, kind: str, parameter: str) -> tuple[float, float, int]:
    """Parse ``START:STOP:COUNT`` (ends included), e.g. ``10mm:60mm:50``, into SI values.

    Parameters
    ----------
    text : str
        ``VALUE`` or ``START:STOP:COUNT``.
    kind : str
        The quantity kind of START and STOP (see `SI_UNITS`).
    parameter : str
        The option name, for the error message.

    Returns
    -------
    tuple of (float, float, int)
        Start and stop in SI, and the count (>= 1).

    References
    ----------
    BIPM (2019), The International System of Units (SI), 9th ed.

    Examples
    --------
    >>> parse_range("10mm:60mm:6", "length", "fill_height")
    (0.01, 0.06, 6)
    """
    if not isinstance(text, str):
        return (*[parse_quantity(text, kind, parameter)] * 2, 1)  # type: ignore[return-value]
    parts = text.split(":")
    if len(parts) == 1:
        value = parse_quantity(parts[0], kind, parameter)
        return value, value, 1
    if len(parts) != 3:
        raise InputError(parameter, text, "must be VALUE or START:STOP:COUNT, e.g. 10mm:60mm:50")
    start = parse_quantity(parts[0], kind, parameter)
    stop = parse_quantity(parts[1], kind, parameter)
    count_text = parts[2].strip()
    if not re.fullmatch(r"\d{1,12}", count_text):
        raise InputError(parameter, text, "COUNT in START:STOP:COUNT must be a whole number >= 1")
    count = int(count_text)
    if count < 1:
        raise InputError(parameter, text, "COUNT in START:STOP:COUNT must be >= 1")
    from sloshkit.budget import require_samples

    # Each value of a range becomes a row of the result maps (about 8 float64 columns).
    require_samples(parameter, text, count, 8, "range values")
    return start, stop, count
