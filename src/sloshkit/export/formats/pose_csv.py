"""``pose-csv``: the container's pose stream, ``t,x,y,z,qx,qy,qz,qw``, with a metadata header.

Units: t [s], x y z [m] (container bottom centre), quaternion (x, y, z, w) [-] rotating the
container frame into the frame named in the header's ``frame`` line (scalar last). Readers
that skip ``#`` lines (numpy, pandas ``comment="#"``, ``sloshkit`` itself) load it as is.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from sloshkit.errors import InputError
from sloshkit.export.formats.common import header_lines, rows_csv
from sloshkit.export.plans import PoseStream, read_plan
from sloshkit.files import atomic_open

UNITS = "t [s]; x, y, z [m]; qx, qy, qz, qw [-] (unit quaternion, scalar last)"


def write_pose_csv(path: str | Path, stream: PoseStream, metadata: Mapping[str, object]) -> Path:
    """Write the pose stream with ``metadata`` as ``# key: value`` lines first.

    Parameters
    ----------
    path : output file
    stream : the poses (already in the frame the metadata names)
    metadata : header lines (format, units, frames, sample period, model, limits, version)

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib, numpy as np
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> upright = np.tile([0, 0, 0, 1.0], (3, 1))
    >>> stream = PoseStream(PoseTrajectory(np.arange(3) * 0.1, np.zeros((3, 3)), upright))
    >>> out = write_pose_csv(pathlib.Path(tempfile.mkdtemp()) / "p.csv", stream, {"units": UNITS})
    >>> out.read_text().splitlines()[1]
    't,x,y,z,qx,qy,qz,qw'
    """
    with atomic_open(path) as handle:
        handle.write(header_lines(metadata) + rows_csv(stream.poses.columns()))
    return Path(path)


def read_pose_csv(path: str | Path) -> PoseStream:
    """The pose stream of a ``pose-csv`` file (metadata in ``.metadata``).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    PoseStream

    Examples
    --------
    >>> import tempfile, pathlib, numpy as np
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> upright = np.tile([0, 0, 0, 1.0], (3, 1))
    >>> stream = PoseStream(PoseTrajectory(np.arange(3) * 0.1, np.ones((3, 3)), upright))
    >>> out = write_pose_csv(pathlib.Path(tempfile.mkdtemp()) / "p.csv", stream, {})
    >>> read_pose_csv(out).position_m[2]
    array([1., 1., 1.])
    """
    plan = read_plan(path)
    if not isinstance(plan, PoseStream):
        raise InputError("file", str(path), "is not a pose stream (t,x,y,z,qx,qy,qz,qw)")
    return plan
