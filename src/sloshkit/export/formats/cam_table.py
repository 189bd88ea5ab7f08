"""``cam-table``: a 1-D slide move as a position-versus-time cam table for servo drives.

CSV columns ``t_s,position_m,velocity_m_s,acceleration_m_s2`` on the chosen grid (the master
axis is time; drives that take only position use the first two columns), after ``# key: value``
metadata lines. No PLCopen XML: PLCopen's TC6 XML schema exchanges IEC 61131-3 programs and has
no cam-profile element (cam tables are vendor-specific data types behind ``MC_CamTableSelect``,
PLCopen Motion Control Part 1), and there is no maintained Python writer of a vendor-neutral
cam format to build on.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from sloshkit.errors import InputError
from sloshkit.export.formats.common import header_lines, rows_csv
from sloshkit.export.plans import LinePlan, read_plan
from sloshkit.files import atomic_open


def write_cam_table(path: str | Path, line: LinePlan, metadata: Mapping[str, object]) -> Path:
    """Write the 1-D move as a cam table CSV.

    Parameters
    ----------
    path : output file
    line : the move on the drive's grid
    metadata : header lines

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib, numpy as np
    >>> t = np.arange(3) * 0.1
    >>> out = write_cam_table(pathlib.Path(tempfile.mkdtemp()) / "c.csv", LinePlan(t, t, t, t), {})
    >>> out.read_text().splitlines()[0]
    't_s,position_m,velocity_m_s,acceleration_m_s2'
    """
    columns = {
        "t_s": line.time_s,
        "position_m": line.position_m,
        "velocity_m_s": line.velocity_m_s,
        "acceleration_m_s2": line.acceleration_m_s2,
    }
    with atomic_open(path) as handle:
        handle.write(header_lines(metadata) + rows_csv(columns))
    return Path(path)


def read_cam_table(path: str | Path) -> LinePlan:
    """The 1-D move of a cam table CSV.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    LinePlan

    Examples
    --------
    >>> import tempfile, pathlib, numpy as np
    >>> t = np.arange(3) * 0.1
    >>> out = write_cam_table(pathlib.Path(tempfile.mkdtemp()) / "c.csv", LinePlan(t, t, t, t), {})
    >>> read_cam_table(out).position_m
    array([0. , 0.1, 0.2])
    """
    plan = read_plan(path)
    if not isinstance(plan, LinePlan):
        raise InputError("file", str(path), "is not a cam table (t_s, position_m, ...)")
    return plan
