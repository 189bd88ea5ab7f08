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
    The waypoint format of `sloshkit.plan.path.path_from_waypoints`.

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


def _read_waypoints(source: FilePath) -> tuple[FloatArray, FloatArray | None]:
    if source.suffix.lower() == ".toml":
        document = read_document(source, "path")
        rows = number_rows(document, "", "waypoints", 3)
        if rows is None:
            raise InputError("path", str(source), "needs waypoints = [[x, y, z], ...] in m")
        points = np.asarray(rows, dtype=float).reshape(-1, 3)
        yaw = number_list(document, "", "yaw_deg")
        require_bounded_rows(points.reshape(-1), "waypoints", MAX_COORDINATE_M, "m", "path", source)
        return points, None if yaw is None else np.radians(np.asarray(yaw, dtype=float))
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
    return points, data[:, index] * _scale(header[index], "rad", _ANGLE_UNITS, "path")
