"""Terminal tables: human labels with units for the JSON keys, and numbers formatted to fit
80 columns (units go in the row or column label, so cells hold only numbers)."""

from __future__ import annotations

import math
import os
from collections.abc import MutableMapping
from typing import TextIO

#: Narrowest and widest console accepted from $COLUMNS or $TERMINAL_WIDTH [characters];
#: outside them (0, negative, text) the console falls back to `FALLBACK_WIDTH`.
MIN_WIDTH = 40
MAX_WIDTH = 1000
#: Width of a console that is not a terminal, or whose $COLUMNS is unusable.
FALLBACK_WIDTH = 160

#: Environment variables that set the console width (rich reads COLUMNS, typer's help
#: TERMINAL_WIDTH).
WIDTH_VARIABLES = ("COLUMNS", "TERMINAL_WIDTH")


def usable_width(text: str | None) -> int | None:
    """The width a $COLUMNS value asks for, or None when it is unusable (absent, not an integer,
    or outside [`MIN_WIDTH`, `MAX_WIDTH`]).

    Parameters
    ----------
    text : str or None
        The variable's value.

    Returns
    -------
    int or None

    Examples
    --------
    >>> usable_width("100"), usable_width("0"), usable_width("-5"), usable_width("abc")
    (100, None, None, None)
    """
    if text is None or not text.strip().isdigit():
        return None
    width = int(text.strip())
    return width if MIN_WIDTH <= width <= MAX_WIDTH else None


def sane_width_environment(environ: MutableMapping[str, str] | None = None) -> dict[str, str]:
    """Replace unusable console widths in the environment by `FALLBACK_WIDTH`, so every console
    (sloshkit's, typer's help, rich's progress) has room for its lines: ``COLUMNS=0`` would
    make rich print nothing, errors included.

    Parameters
    ----------
    environ : mutable mapping, optional
        The environment (default `os.environ`).

    Returns
    -------
    dict of str to str
        The values replaced (to restore them afterwards).

    Examples
    --------
    >>> environment = {"COLUMNS": "0"}
    >>> sane_width_environment(environment), environment
    ({'COLUMNS': '0'}, {'COLUMNS': '160'})
    """
    target = os.environ if environ is None else environ
    replaced = {}
    for name in WIDTH_VARIABLES:
        value = target.get(name)
        if value is not None and usable_width(value) is None:
            replaced[name] = value
            target[name] = str(FALLBACK_WIDTH)
    return replaced


def console_width(stream: TextIO, environ: MutableMapping[str, str] | None = None) -> int | None:
    """The width of a sloshkit console on ``stream``: $COLUMNS when usable; for a terminal
    without $COLUMNS None (rich follows the terminal), with an unusable one the terminal's
    width now; else `FALLBACK_WIDTH` (also for a stream that is not a terminal).

    Parameters
    ----------
    stream : text stream
        sys.stdout or sys.stderr.
    environ : mutable mapping, optional
        The environment (default `os.environ`).

    Returns
    -------
    int or None

    Examples
    --------
    >>> import io
    >>> pipe = io.StringIO()
    >>> console_width(pipe, {"COLUMNS": "0"}), console_width(pipe, {"COLUMNS": "90"})
    (160, 90)
    """
    target = os.environ if environ is None else environ
    width = usable_width(target.get("COLUMNS"))
    if width is not None:
        return width
    try:
        if stream.isatty():
            if "COLUMNS" not in target:
                return None
            return usable_width(str(os.get_terminal_size(stream.fileno()).columns)) or (
                FALLBACK_WIDTH
            )
    except (OSError, ValueError, AttributeError):
        pass
    return FALLBACK_WIDTH


#: Libraries whose log records never reach stderr: sloshkit reports their failures itself,
#: in one line (Dask's worker and scheduler chatter, matplotlib's font cache notes).
QUIET_LOGGERS = ("distributed", "dask", "tornado", "bokeh", "matplotlib", "numba", "asyncio")


def quiet_library_logging() -> None:
    """Send the log records of `QUIET_LOGGERS` nowhere (a NullHandler, no propagation), and give
    the root logger a NullHandler so Python's last-resort handler prints nothing either.

    Returns
    -------
    None

    Examples
    --------
    >>> import logging
    >>> quiet_library_logging()
    >>> logging.getLogger("matplotlib").propagate
    False
    """
    import logging

    for name in QUIET_LOGGERS:
        logger = logging.getLogger(name)
        logger.handlers[:] = [logging.NullHandler()]
        logger.propagate = False
    root = logging.getLogger()
    if not root.handlers:
        root.addHandler(logging.NullHandler())


#: JSON key -> (human label, unit shown, factor from the key's unit to the shown unit).
LABELS: dict[str, tuple[str, str, float]] = {
    "duration_s": ("duration", "s", 1.0),
    "peak_angle_deg": ("peak slosh angle θ₁", "°", 1.0),
    "residual_angle_deg": ("residual slosh angle θ₁", "°", 1.0),
    "peak_wall_elevation_m": ("peak wall elevation η", "mm", 1e3),
    "peak_slosh_height_m": ("peak slosh height", "mm", 1e3),
    "residual_slosh_height_m": ("residual slosh height", "mm", 1e3),
    "peak_tilt_deg": ("peak surface tilt", "°", 1.0),
    "simulated_time_s": ("simulated time", "s", 1.0),
    "residual_wall_elevation_m": ("residual wall elevation η", "mm", 1e3),
    "settling_time_s": ("settling time", "s", 1.0),
    "peak_velocity_m_s": ("peak velocity", "m/s", 1.0),
    "peak_acceleration_m_s2": ("peak acceleration", "m/s²", 1.0),
    "peak_jerk_m_s3": ("peak jerk", "m/s³", 1.0),
    "compute_time_s": ("compute time", "s", 1.0),
    "omega_n_rad_s": ("natural pulsation ω_n", "rad/s", 1.0),
    "frequency_hz": ("frequency f_n", "Hz", 1.0),
    "damping_ratio": ("damping ratio ζ", "-", 1.0),
}

_SUFFIXES: tuple[tuple[str, str, float], ...] = (
    ("_m_s3", "m/s³", 1.0),
    ("_m_s2", "m/s²", 1.0),
    ("_m_s", "m/s", 1.0),
    ("_rad_s", "rad/s", 1.0),
    ("_deg", "°", 1.0),
    ("_rad", "rad", 1.0),
    ("_hz", "Hz", 1.0),
    ("_s", "s", 1.0),
    ("_m", "mm", 1e3),
)


def label(key: str, *, with_unit: bool = True) -> str:
    """The human label of a JSON key, with its unit in brackets: ``"peak jerk [m/s³]"``.

    Parameters
    ----------
    key : str
        A JSON key with its unit suffix.
    with_unit : bool
        Append the unit in brackets.

    Returns
    -------
    str

    Examples
    --------
    >>> label("peak_jerk_m_s3"), label("peak_slosh_height_m"), label("duration_s", with_unit=False)
    ('peak jerk [m/s³]', 'peak slosh height [mm]', 'duration')
    """
    text, unit, _ = _describe(key)
    return f"{text} [{unit}]" if with_unit and unit else text


def value(key: str, number: float | None, digits: int = 4) -> str:
    """A number of ``key`` in the label's unit, without the unit (``None``/inf as ``∞``/``-``).

    Parameters
    ----------
    key : str
        The JSON key (its suffix gives the unit).
    number : float or None
        The SI value.
    digits : int
        Significant digits.

    Returns
    -------
    str

    Examples
    --------
    >>> value("peak_slosh_height_m", 0.0012345), value("peak_jerk_m_s3", None)
    ('1.234', '∞')
    """
    if number is None:
        return "∞" if "jerk" in key else "-"
    if not math.isfinite(number):
        return "∞"
    return f"{number * _describe(key)[2]:.{digits}g}"


def _describe(key: str) -> tuple[str, str, float]:
    if key in LABELS:
        return LABELS[key]
    for suffix, unit, factor in _SUFFIXES:
        if key.endswith(suffix):
            return key[: -len(suffix)].replace("_", " "), unit, factor
    return key.replace("_", " "), "", 1.0
