"""Waypoint files for 3-D planning (the file edge; the core takes arrays in SI).

- waypoints: CSV with columns ``x, y, z`` and optionally ``yaw``, units in the header
  (``x [mm]``, ``x_mm``, ``yaw [deg]``; bare names are m and rad), or TOML
  (``waypoints = [[x, y, z], ...]`` in m, optional ``yaw_deg = [...]``);
(pose files are read by `sloshkit.io.poses.read_pose_file`).
"""

from __future__ import annotations

import math
from pathlib import Path as FilePath

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.io.checks import naming, require_bounded_rows, require_finite_rows
from sloshkit.io.schema import number_list, number_rows, read_document
from sloshkit.io.tables import read_table, unit_from_name

FloatArray = NDArray[np.float64]
_LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "cm": 1e-2}
_ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}


def _scale(name: str, default: str, table: dict[str, float], parameter: str) -> float:
    """Factor to SI of the unit written in a column name (``x [mm]``, ``x_mm``)."""
    unit = unit_from_name(name)
    if unit is None and "_" in name:
        unit = name.rsplit("_", 1)[1]
    unit = (unit or default).strip().lower()
    if unit not in table:
        raise InputError(parameter, name, "unit must be one of " + ", ".join(table))
    return table[unit]


def read_waypoints(path: str | FilePath) -> tuple[FloatArray, FloatArray | None]:
    """Waypoints [m] and optional yaw [rad] from a CSV or TOML file (module docstring).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    tuple
        (points (n, 3) [m], yaw (n,) [rad] or None).

    References
    ----------
    The waypoint format of `sloshkit.plan.path.geometry.path_from_waypoints`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "w.csv").write_text("x [mm],y [mm],z [mm]\\n0,0,0\\n300,0,0\\n")
    >>> read_waypoints(folder / "w.csv")[0][1].tolist()
    [0.3, 0.0, 0.0]
    """
    source = FilePath(path)
    with naming("path", source):
        return _read_waypoints(source)


#: Largest waypoint coordinate [m] (beyond it the units are surely wrong).
MAX_COORDINATE_M = 1e6
#: Largest waypoint yaw magnitude [rad]: two turns either way (720 deg). The yaw between
#: waypoints is interpolated, not unwrapped, so a larger value is a spin, surely a unit error.
MAX_YAW_RAD = 4.0 * math.pi
#: Most samples of the fastest traverse a 3-D path plan may need (its length at --vmax,
#: sampled at --sample-period; `require_path_work`): 40 s at 4 ms.
MAX_PATH_SAMPLES = 10_000


#: The default --sample-period of 3-D plans [s]: when the path fits at it, a refusal names
#: --sample-period instead of the path.
DEFAULT_PATH_SAMPLE_PERIOD_S = 0.004


def require_path_work(
    length_m: float,
    vmax_m_s: float,
    sample_period_s: float,
    parameter: str,
    source: object,
    period_text: str = "",
) -> None:
    """Refuse a 3-D path whose plan would need more than `MAX_PATH_SAMPLES` samples even at
    the speed limit (before any planning: the planner's work grows with the samples). The
    error names the path, or ``sample_period`` when the path would fit at the default period.

    Parameters
    ----------
    length_m : float
        The path's length [m].
    vmax_m_s : float
        ``--vmax`` [m/s].
    sample_period_s : float
        ``--sample-period`` [s].
    parameter : str
        The option that named the path (``path`` or ``path_from_poses``).
    source : object
        The file (for the message).
    period_text : str
        ``--sample-period`` as typed.

    Returns
    -------
    None

    Examples
    --------
    >>> require_path_work(0.5, 2.0, 0.004, "path", "w.csv")
    >>> try:
    ...     require_path_work(300.0, 2.0, 0.004, "path", "w.csv")
    ... except InputError as error:
    ...     print(error.valid[:40])
    the path is 300 m long: even at --vmax 2
    """
    if not (vmax_m_s > 0.0 and sample_period_s > 0.0 and math.isfinite(vmax_m_s)):
        return  # the limits' own checks name --vmax and --sample-period
    samples = length_m / vmax_m_s / sample_period_s
    if samples <= MAX_PATH_SAMPLES:
        return
    if length_m / vmax_m_s / DEFAULT_PATH_SAMPLE_PERIOD_S <= MAX_PATH_SAMPLES:
        raise InputError(
            "sample_period",
            period_text or sample_period_s,
            f"gives {samples:.3g} samples on the {length_m:.4g} m path at --vmax "
            f"{vmax_m_s:g} m/s; at most {MAX_PATH_SAMPLES}",
        )
    raise InputError(
        parameter,
        str(source),
        f"the path is {length_m:.4g} m long: even at --vmax {vmax_m_s:g} m/s its plan "
        f"needs {samples:.3g} samples of {sample_period_s * 1e3:g} ms; at most "
        f"{MAX_PATH_SAMPLES}",
        "are the units right? bare numbers are metres: write 'x [mm]' or use mm in TOML",
    )


def _read_waypoints(source: FilePath) -> tuple[FloatArray, FloatArray | None]:
    if source.suffix.lower() == ".toml":
        document = read_document(source, "path")
        rows = number_rows(document, "", "waypoints", 3)
        if rows is None:
            raise InputError("path", str(source), "needs waypoints = [[x, y, z], ...] in m")
        points = np.asarray(rows, dtype=float).reshape(-1, 3)
        yaw = number_list(document, "", "yaw_deg")
        require_bounded_rows(points.reshape(-1), "waypoints", MAX_COORDINATE_M, "m", "path", source)
        if yaw is None:
            return points, None
        yaw_rad = np.radians(np.asarray(yaw, dtype=float))
        require_finite_rows(yaw_rad[:, None], {"yaw_deg": 0}, "path", source)
        _require_yaw(yaw_rad, "yaw_deg", source)
        return points, yaw_rad
    header, data = read_table(source)
    names = [name.split("[")[0].split("(")[0].strip().lower() for name in header]
    base = [name.split("_")[0] for name in names]
    if not all(axis in base for axis in "xyz"):
        raise InputError("path", str(source), "needs columns x, y, z (e.g. 'x [mm]')")
    columns = [base.index(axis) for axis in "xyz"]
    used = {header[c]: c for c in columns}
    if "yaw" in base:
        used[header[base.index("yaw")]] = base.index("yaw")
    require_finite_rows(data, used, "path", source)
    points = np.column_stack(
        [data[:, c] * _scale(header[c], "m", _LENGTH_UNITS, "path") for c in columns]
    )
    for axis, c in zip("xyz", columns, strict=True):
        require_bounded_rows(
            points[:, "xyz".index(axis)], header[c], MAX_COORDINATE_M, "m", "path", source
        )
    if "yaw" not in base:
        return points, None
    index = base.index("yaw")
    yaw_column = data[:, index] * _scale(header[index], "rad", _ANGLE_UNITS, "path")
    _require_yaw(yaw_column, header[index], source)
    return points, yaw_column


def _require_yaw(yaw_rad: FloatArray, column: str, source: FilePath) -> None:
    bad = np.abs(yaw_rad) > MAX_YAW_RAD
    if np.any(bad):
        row = int(np.argmax(bad))
        raise InputError(
            "path",
            str(source),
            f"{column!r} reaches {np.degrees(yaw_rad[row]):.4g} deg at waypoint {row + 1}; "
            f"|yaw| must be at most {np.degrees(MAX_YAW_RAD):g} deg",
            "are the units right? bare yaw is in radians in CSV",
        )
