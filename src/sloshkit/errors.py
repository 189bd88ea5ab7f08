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
    """Invalid user input, naming the parameter, its value and the valid range.

    Parameters
    ----------
    parameter : str
        The parameter's name as the user wrote it (an option, a key, a column).
    value : object
        The value given.
    valid : str
        What would be valid.
    hint : str
        Optional advice, in parentheses after the message.

    Examples
    --------
    >>> error = InputError("fill_height", 0.09, "must be below the container height 0.08 m")
    >>> str(error)
    'fill_height = 0.09 is invalid: must be below the container height 0.08 m'
    >>> error.parameter, isinstance(error, ValueError)
    ('fill_height', True)
    """

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
    """Input accepted, but outside the range where the model is trustworthy.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("fill below 0.2 R", ValidityWarning)
    >>> caught[0].category.__name__, issubclass(ValidityWarning, UserWarning)
    ('ValidityWarning', True)
    """


def _format_value(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value) if isinstance(value, str) else str(value)


def require_positive(parameter: str, value: float, unit: str = "") -> float:
    """Return ``value`` as float, or raise `InputError` unless it is finite and > 0.

    Parameters
    ----------
    parameter : str
        Name for the message.
    value : float
        The value to check.
    unit : str
        Unit shown after the value in the message.

    Returns
    -------
    float

    Examples
    --------
    >>> require_positive("radius", 0.02, "m")
    0.02
    >>> require_positive("radius", -1, "m")
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: radius = '-1 m' is invalid: must be finite and > 0
    """
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
    """Return ``value`` as float, or raise `InputError` unless low <= value <= high.

    Parameters
    ----------
    parameter : str
        Name for the message.
    value : float
        The value to check.
    low, high : float
        The closed range.
    unit : str
        Unit shown in the message.

    Returns
    -------
    float

    Examples
    --------
    >>> require_in_range("damping_ratio", 0.02, 0.0, 1.0)
    0.02
    >>> require_in_range("damping_ratio", 1.5, 0.0, 1.0)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: damping_ratio = '1.5' is invalid: must be between 0 and 1
    """
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
    """Emit a `ValidityWarning` attributed to the caller of the public function.

    Parameters
    ----------
    message : str
        What is doubtful and why.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_validity("Bond number 12 < 100: surface tension matters")
    >>> caught[0].category is ValidityWarning, str(caught[0].message)[:11]
    (True, 'Bond number')
    """
    warnings.warn(message, ValidityWarning, stacklevel=3)


def require_increasing(parameter: str, times: Sequence[float] | object) -> None:
    """Raise `InputError` at the first time stamp that does not increase strictly.

    Parameters
    ----------
    parameter : str
        Name for the message (a column, a file).
    times : sequence of float
        The time stamps [s].

    Examples
    --------
    >>> require_increasing("t", [0.0, 0.1, 0.2])
    >>> require_increasing("t", [0.0, 0.1, 0.1])
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: t = ... is invalid: ...
    """
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
