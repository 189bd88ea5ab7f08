"""Terminal tables: human labels with units for the JSON keys, and numbers formatted to fit
80 columns (units go in the row or column label, so cells hold only numbers)."""

from __future__ import annotations

import math

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
