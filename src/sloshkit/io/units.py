"""Unit parsing at the edge (CLI and scenario files): text like ``20.5mm`` -> SI float.

The numeric core never imports pint; only this module does.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

from sloshkit.errors import InputError

#: SI unit for each kind of quantity the CLI accepts; a bare number is read in this unit.
SI_UNITS: dict[str, str] = {
    "length": "m",
    "volume": "m**3",
    "time": "s",
    "velocity": "m/s",
    "acceleration": "m/s**2",
    "jerk": "m/s**3",
    "angle": "rad",
    "frequency": "Hz",
    "density": "kg/m**3",
    "viscosity": "Pa*s",
    "surface_tension": "N/m",
}


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint

    return pint.UnitRegistry()


def parse_quantity(text: str | float, kind: str, parameter: str) -> float:
    """Parse ``text`` (e.g. ``"20.5mm"``, ``"0.5 m/s"``, ``"5deg"``, ``"2 mL"``) into SI.

    A bare number is taken in the SI unit of ``kind`` (see `SI_UNITS`); angles given bare are
    radians. Raises `InputError` naming ``parameter`` for unparseable text or a wrong dimension.
    """
    target = SI_UNITS[kind]
    if isinstance(text, int | float):
        value = float(text)
    else:
        stripped = text.strip()
        try:
            value = float(stripped)
        except ValueError:
            value = _parse_with_units(stripped, target, kind, parameter)
    if math.isnan(value):
        raise InputError(
            parameter, text, f"must be a number with a {kind} unit, e.g. {_example(kind)}"
        )
    return value


def _parse_with_units(text: str, target: str, kind: str, parameter: str) -> float:
    import pint

    registry = _registry()
    try:
        quantity = registry.Quantity(text.replace("^", "**"))
        return float(quantity.to(target).magnitude)
    except pint.DimensionalityError:
        raise InputError(
            parameter, text, f"must be a {kind} (convertible to {target}), e.g. {_example(kind)}"
        ) from None
    except Exception:  # pint raises several unrelated types for unparseable text
        raise InputError(
            parameter, text, f"could not read it as a {kind}, e.g. {_example(kind)}"
        ) from None


def parse_range(text: str, kind: str, parameter: str) -> tuple[float, float, int]:
    """Parse ``START:STOP:COUNT`` (ends included), e.g. ``10mm:60mm:50``, into SI values."""
    parts = text.split(":")
    if len(parts) == 1:
        value = parse_quantity(parts[0], kind, parameter)
        return value, value, 1
    if len(parts) != 3:
        raise InputError(parameter, text, "must be VALUE or START:STOP:COUNT, e.g. 10mm:60mm:50")
    start = parse_quantity(parts[0], kind, parameter)
    stop = parse_quantity(parts[1], kind, parameter)
    try:
        count = int(parts[2])
    except ValueError:
        raise InputError(parameter, text, "COUNT in START:STOP:COUNT must be an integer") from None
    if count < 1:
        raise InputError(parameter, text, "COUNT in START:STOP:COUNT must be >= 1")
    return start, stop, count


def _example(kind: str) -> str:
    return {
        "length": "20.5mm",
        "volume": "2mL",
        "time": "1.5s",
        "velocity": "0.5m/s",
        "acceleration": "5m/s^2",
        "jerk": "50m/s^3",
        "angle": "5deg",
        "frequency": "4.7Hz",
        "density": "997kg/m^3",
        "viscosity": "0.89mPa*s",
        "surface_tension": "72mN/m",
    }.get(kind, "1")
