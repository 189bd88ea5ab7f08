"""User motion files (a time column and a position or acceleration column) and the checks
that a motion or a record read from a file is plausible for a container move."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.io.tables import (
    ACCELERATION_NAMES,
    POSITION_NAMES,
    TIME_NAMES,
    column_si,
    find_column,
    read_table,
)
from sloshkit.motion.recorded import from_samples

FloatArray = NDArray[np.float64]

#: What a container move plausibly spans (SI); beyond it a motion file was most likely written
#: in other units (ms, mm) without saying so in its header.
PLAUSIBLE_MOVE = {"duration_s": 60.0, "travel_m": 5.0, "acceleration_m_s2": 500.0}


def read_motion_file(path: str | Path, name: str | None = None) -> Any:
    r"""A user motion from a table with a time column and a position or acceleration column.

    Column names decide, with their units: time ``t``/``time``, position ``x``/``position``,
    or acceleration ``a``/``acceleration``, each optionally with a unit in brackets (``t [ms]``,
    ``x [mm]``, ``a [m/s^2]``) or as a suffix (``t_ms``, ``x_mm``, ``a_m_s2``); a name without a
    unit is SI (s, m, m/s^2). Without a header, column 0 is time [s] and column 1 position [m].
    A move that looks implausible in SI (longer than a minute, farther than 5 m, above
    500 m/s^2) raises a `ValidityWarning` that suggests writing the units in the header.
    See `sloshkit.motion.recorded.from_samples` for the interpolation.

    Parameters
    ----------
    path : str or Path
        CSV or whitespace table.
    name : str, optional
        Name of the motion (default ``file:PATH``).

    Returns
    -------
    Motion
        The rest-to-rest motion.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> u = [t / 2000 for t in range(0, 2001, 100)]
    >>> rows = "\n".join(f"{2000 * v},{20 * (10 * v**3 - 15 * v**4 + 6 * v**5)}" for v in u)
    >>> _ = (folder / "move.csv").write_text("t [ms],x [mm]\n" + rows + "\n")
    >>> motion = read_motion_file(folder / "move.csv")
    >>> round(motion.duration_s, 3), round(motion.distance_m, 3)
    (2.0, 0.02)
    """
    header, data = read_table(path)
    label = name or f"file:{path}"
    time_index = find_column(header, TIME_NAMES)
    time_s = column_si(header, data, 0 if time_index is None else time_index, "time")
    position = find_column(header, POSITION_NAMES)
    acceleration = find_column(header, ACCELERATION_NAMES)
    if position is not None:
        values = column_si(header, data, position, "length")
        motion = from_samples(time_s, position_m=values, name=label)
        _warn_unless_at_rest(motion, time_s, path, values)
    elif acceleration is not None:
        values = column_si(header, data, acceleration, "acceleration")
        motion = from_samples(time_s, acceleration_m_s2=values, name=label)
        _warn_unless_at_rest(motion, time_s, path)
    else:
        if data.shape[1] < 2:
            raise InputError("file", str(path), "needs a time column and a position column")
        values = column_si(header, data, 1, "length")
        motion = from_samples(time_s, position_m=values, name=label)
        _warn_unless_at_rest(motion, time_s, path, values)
    check_plausible_move(motion, str(path))
    return motion


def check_plausible_move(motion: Any, source: str) -> list[str]:
    """Warn (`ValidityWarning`) when a motion read from ``source`` is implausible for a
    container move in SI units (see `PLAUSIBLE_MOVE`): most likely a file in ms or mm whose
    header does not say so.

    Parameters
    ----------
    motion : Motion
        The motion as read.
    source : str
        Where it came from (for the message).

    Returns
    -------
    list of str
        The warning messages (empty when the move is plausible).

    Examples
    --------
    >>> from sloshkit.motion import trapezoidal
    >>> check_plausible_move(trapezoidal(0.5, duration_s=1.5), "move.csv")
    []
    """
    from sloshkit.errors import warn_validity

    findings = []
    if motion.duration_s > PLAUSIBLE_MOVE["duration_s"]:
        findings.append(f"lasts {motion.duration_s:,.4g} s")
    if abs(motion.distance_m) > PLAUSIBLE_MOVE["travel_m"]:
        findings.append(f"travels {motion.distance_m:,.4g} m")
    peak = float(np.max(np.abs(motion.acceleration(np.linspace(0, motion.duration_s, 2001)))))
    if peak > PLAUSIBLE_MOVE["acceleration_m_s2"]:
        findings.append(f"accelerates at {peak:,.4g} m/s^2")
    if not findings:
        return []
    message = (
        f"motion file {source}: the move {' and '.join(findings)}, implausible for a container; "
        "columns without a unit are read as s, m, m/s^2: write units in the header, "
        "e.g. 't [ms],x [mm]'"
    )
    warn_validity(message)
    return [message]


#: A slosh record (a free decay or a move and its decay) longer than this is implausible [s].
PLAUSIBLE_RECORD_S = 600.0


def check_plausible_record(time_s: FloatArray, source: str) -> list[str]:
    """Warn (`ValidityWarning`) when a calibration record's time column, read in seconds, spans
    more than `PLAUSIBLE_RECORD_S`: most likely milliseconds without a unit in the header.

    Parameters
    ----------
    time_s : ndarray
        The record's time column as read [s].
    source : str
        The record's file (for the message).

    Returns
    -------
    list of str
        The warning messages (empty when the span is plausible).

    Examples
    --------
    >>> import numpy as np
    >>> check_plausible_record(np.linspace(0.0, 8.0, 801), "decay.csv")
    []
    """
    from sloshkit.errors import warn_validity

    span = float(np.nanmax(time_s) - np.nanmin(time_s)) if time_s.size else 0.0
    if span <= PLAUSIBLE_RECORD_S:
        return []
    message = (
        f"record {source}: the time column spans {span:,.4g} s, implausible for a slosh record; "
        "if it is in ms, name the column 't [ms]' or pass --time-unit ms"
    )
    warn_validity(message)
    return [message]


#: Velocity at either end of a motion file, relative to its peak, above which it is not at rest.
REST_TOLERANCE = 0.02


def _warn_unless_at_rest(
    motion: Any, time_s: FloatArray, path: str | Path, position_m: FloatArray | None = None
) -> Any:
    """Warn (`ValidityWarning`) when a motion file does not start and end at rest.

    For positions the end velocity is the last difference quotient of the samples (the spline
    then forces a stop that is not in the data); for accelerations it is the integrated
    velocity at the last sample (the container would keep moving).
    """
    from sloshkit.errors import warn_validity

    t = np.asarray(time_s, dtype=float) - float(time_s[0])
    if position_m is not None:
        velocity = np.diff(position_m) / np.diff(t)
        ends = {"start": velocity[0], "end": velocity[-1]}
    else:
        velocity = motion.velocity(t)
        ends = {"end": velocity[-1]}
    peak = float(np.max(np.abs(velocity))) if velocity.size else 0.0
    for where, value in ends.items():
        if peak > 0.0 and abs(float(value)) > REST_TOLERANCE * peak:
            warn_validity(
                f"motion file {path} does not {where} at rest (velocity {float(value):.3g} m/s "
                f"at its {where}, {100 * abs(float(value)) / peak:.0f} % of the peak); the "
                "result assumes a rest-to-rest move"
            )
    return motion
