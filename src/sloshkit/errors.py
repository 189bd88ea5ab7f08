"""Errors and warnings that sloshkit raises for user input.

`InputError` is for impossible input (the model cannot be evaluated); the CLI turns it into one
line on stderr and exit code 2. `ValidityWarning` is for input the model accepts but where its
assumptions (linear potential flow, negligible surface tension, ...) become doubtful.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence


class InputError(ValueError):
    """Invalid user input, naming the parameter, its value and the valid range."""

    def __init__(self, parameter: str, value: object, valid: str, hint: str = "") -> None:
        self.parameter = parameter
        self.value = value
        self.valid = valid
        self.hint = hint
        message = f"{parameter} = {_format_value(value)} is invalid: {valid}"
        if hint:
            message += f" ({hint})"
        super().__init__(message)


class ValidityWarning(UserWarning):
    """Input accepted, but outside the range where the model is trustworthy."""


def _format_value(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value) if isinstance(value, str) else str(value)


def require_positive(parameter: str, value: float, unit: str = "") -> float:
    """Return ``value`` as float, or raise `InputError` unless it is finite and > 0."""
    try:
        number = float(value)
    except (TypeError, ValueError) as exc:
        raise InputError(parameter, value, "must be a number") from exc
    if not math.isfinite(number) or number <= 0.0:
        suffix = f" {unit}" if unit else ""
        raise InputError(parameter, f"{number:.6g}{suffix}", "must be finite and > 0")
    return number


def require_in_range(
    parameter: str, value: float, low: float, high: float, unit: str = ""
) -> float:
    """Return ``value`` as float, or raise `InputError` unless low <= value <= high."""
    try:
        number = float(value)
    except (TypeError, ValueError) as exc:
        raise InputError(parameter, value, "must be a number") from exc
    if not (math.isfinite(number) and low <= number <= high):
        suffix = f" {unit}" if unit else ""
        raise InputError(
            parameter, f"{number:.6g}{suffix}", f"must be between {low:g} and {high:g}{suffix}"
        )
    return number


def warn_validity(message: str) -> None:
    """Emit a `ValidityWarning` attributed to the caller of the public function."""
    warnings.warn(message, ValidityWarning, stacklevel=3)


def require_increasing(parameter: str, times: Sequence[float] | object) -> None:
    """Raise `InputError` at the first time stamp that does not increase strictly."""
    import numpy as np

    values = np.asarray(times, dtype=float)
    steps = np.diff(values)
    if np.any(steps <= 0.0):
        row = int(np.argmax(steps <= 0.0)) + 1
        raise InputError(
            parameter,
            f"{values[row]:.6g} s at data row {row + 1}",
            "must increase strictly (duplicate or decreasing time stamp)",
        )
