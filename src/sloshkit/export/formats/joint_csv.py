"""``joint-csv``: joint positions, velocities and accelerations on the controller grid.

Columns ``t_s``, then ``<joint>_rad`` for every joint, then ``<joint>_rad_s`` and
``<joint>_rad_s2`` (SI; prismatic joints in m, m/s, m/s^2 under the same suffixes), after
``# key: value`` metadata lines naming the robot, frames and sample period.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from sloshkit.errors import InputError
from sloshkit.export.formats.common import header_lines, rows_csv
from sloshkit.export.ik import JointPath
from sloshkit.files import atomic_open


def write_joint_csv(path: str | Path, joints: JointPath, metadata: Mapping[str, object]) -> Path:
    """Write a joint path as CSV with a metadata header.

    Parameters
    ----------
    path : output file
    joints : the joint samples
    metadata : header lines

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.1
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_joint_csv(pathlib.Path(tempfile.mkdtemp()) / "j.csv", path, {})
    >>> out.read_text().splitlines()[0]
    't_s,j1_rad,j1_rad_s,j1_rad_s2'
    """
    with atomic_open(path) as handle:
        handle.write(header_lines(metadata) + rows_csv(joints.columns()))
    return Path(path)


def read_joint_csv(path: str | Path) -> JointPath:
    """The joint path of a ``joint-csv`` file.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    JointPath

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.1
    >>> path = JointPath(t, t[:, None], 0 * t[:, None], 0 * t[:, None], ("j1",))
    >>> out = write_joint_csv(pathlib.Path(tempfile.mkdtemp()) / "j.csv", path, {})
    >>> read_joint_csv(out).position_rad[:, 0]
    array([0. , 0.1, 0.2])
    """
    from sloshkit.export.tables import read_csv_table

    header, data = read_csv_table(path)
    if not header or header[0] != "t_s":
        raise InputError("file", str(path), "is not a joint CSV (first column t_s)")
    names = tuple(name[: -len("_rad")] for name in header[1:] if name.endswith("_rad"))
    expected = ["t_s"] + [
        f"{name}_{suffix}" for suffix in ("rad", "rad_s", "rad_s2") for name in names
    ]
    if not names or header != expected:
        raise InputError("file", str(path), "columns must be t_s, <joint>_rad, _rad_s, _rad_s2")
    count = len(names)
    return JointPath(
        time_s=np.asarray(data[:, 0], dtype=float),
        position_rad=np.asarray(data[:, 1 : 1 + count], dtype=float),
        velocity_rad_s=np.asarray(data[:, 1 + count : 1 + 2 * count], dtype=float),
        acceleration_rad_s2=np.asarray(data[:, 1 + 2 * count :], dtype=float),
        joint_names=names,
    )
