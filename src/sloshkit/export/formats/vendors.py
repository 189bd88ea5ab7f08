"""The industrial-robot program formats, registered for the exporter and the round trip.

Each entry names the format's `Controller` rules (interpolation period, default point period,
program size, its vendor's built-in arms), the file suffix, the writer and the reader. The
exporter samples the plan at the point period, solves the joints, checks the program size and
writes; the round trip reads the points back and interpolates them at the controller's
interpolation period (`read_interpolated`), where the slosh is re-simulated.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.formats import abb_rapid, fanuc_ls, kuka_krl
from sloshkit.export.formats.controller import Controller, interpolate_points, program_name
from sloshkit.export.ik import JointPath

FloatArray = NDArray[np.float64]

Writer = Callable[[Path, JointPath, Mapping[str, object]], Path]
Reader = Callable[[Path], tuple[FloatArray, FloatArray]]


@dataclass(frozen=True)
class ProgramFormat:
    """One robot-program format.

    Attributes
    ----------
    controller : Controller
        Timing and size rules.
    suffix : str
        The file suffix (``.ls``).
    write : callable
        (path, joints, metadata) -> path.
    read : callable
        path -> (point times [s], joint angles [rad]).
    name_limit : int
        Longest program name (the file's stem).

    Examples
    --------
    >>> PROGRAM_FORMATS["kuka-krl"].check_target(Path("move.src"))
    'move'
    """

    controller: Controller
    suffix: str
    write: Writer
    read: Reader
    name_limit: int

    def check_target(self, path: Path) -> str:
        """The program name the file ``path`` gives (`InputError` on ``out`` before any work
        when the stem is not a valid name or the suffix is not the format's)."""
        if path.suffix.lower() != self.suffix:
            raise InputError(
                "out", str(path), f"a {self.controller.format} file ends {self.suffix}"
            )
        return program_name(path.stem, self.name_limit)


#: The formats by name (``--format``).
PROGRAM_FORMATS: dict[str, ProgramFormat] = {
    "fanuc-ls": ProgramFormat(
        fanuc_ls.CONTROLLER,
        ".ls",
        fanuc_ls.write_fanuc_ls,
        fanuc_ls.read_fanuc_ls,
        fanuc_ls.NAME_LIMIT,
    ),
    "abb-rapid": ProgramFormat(
        abb_rapid.CONTROLLER,
        ".mod",
        abb_rapid.write_abb_rapid,
        abb_rapid.read_abb_rapid,
        abb_rapid.NAME_LIMIT,
    ),
    "kuka-krl": ProgramFormat(
        kuka_krl.CONTROLLER,
        ".src",
        kuka_krl.write_kuka_krl,
        kuka_krl.read_kuka_krl,
        kuka_krl.NAME_LIMIT,
    ),
}


def default_robot(fmt: str) -> str | None:
    """The built-in arm a format uses when neither ``--robot`` nor ``--urdf`` is given.

    Parameters
    ----------
    fmt : str
        The format.

    Returns
    -------
    str or None
        None for a format that is not a robot program.

    Examples
    --------
    >>> default_robot("fanuc-ls"), default_robot("urscript")
    ('lrmate200id', None)
    """
    entry = PROGRAM_FORMATS.get(fmt)
    return None if entry is None else entry.controller.robots[0]


def read_interpolated(fmt: str, path: str | Path) -> tuple[FloatArray, FloatArray]:
    """A program's points joined by the spline and sampled on the round trip's grid: the
    controller's interpolation period, subdivided to 2 ms or less
    (`sloshkit.export.formats.controller.Controller.round_trip_step_s`), so every
    interpolation instant is on it (the motion the round trip re-simulates;
    `sloshkit.export.formats.controller.interpolate_points`).

    Parameters
    ----------
    fmt : str
        The format.
    path : str or pathlib.Path
        The program file.

    Returns
    -------
    tuple of numpy.ndarray
        Times [s] (step: `Controller.round_trip_step_s`) and joint angles (samples, 6) [rad].

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(4) * 0.04
    >>> q = np.zeros((4, 6))
    >>> joints = JointPath(t, q, q, q, tuple("abcdef"))
    >>> out = fanuc_ls.write_fanuc_ls(pathlib.Path(tempfile.mkdtemp()) / "m.ls", joints, {})
    >>> read_interpolated("fanuc-ls", out)[0].size  # 0.12 s every 2 ms
    61
    """
    entry = PROGRAM_FORMATS[fmt]
    time, position = entry.read(Path(path))
    return interpolate_points(time, position, entry.controller.round_trip_step_s)


__all__ = ["PROGRAM_FORMATS", "ProgramFormat", "default_robot", "read_interpolated"]
