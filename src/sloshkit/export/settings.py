"""How an export reaches its controller: the arm, the mounting, the ``servoj`` parameters and
the round-trip check (`ExportSettings`), built from values in SI with their limits checked
(`export_settings`).

The command line parses the export options (units, vectors, the axis) and calls
`export_settings` (``sloshkit export`` and ``sloshkit plan --export``); a script can call it
with its own numbers.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sloshkit.errors import require_in_range
from sloshkit.export.servoj import GAIN_RANGE, LOOKAHEAD_TIME_RANGE_S

__all__ = ["GAIN_RANGE", "LOOKAHEAD_TIME_RANGE_S", "ExportSettings", "export_settings"]


@dataclass(frozen=True)
class ExportSettings:
    """The export options in SI: how to reach the controller.

    Attributes
    ----------
    robot : str or None
        A built-in arm (``--robot``).
    urdf : pathlib.Path or None
        A URDF file (``--urdf``).
    base_link, tip_link : str or None
        The URDF links the chain runs between.
    seed_rad : tuple of float or None
        IK seed of the first sample [rad].
    mounting : Mounting
        Where the container sits in the flange and the path in the base.
    axis : tuple of float
        Direction of a 1-D move in the path frame.
    lookahead_time_s, gain : float
        URScript ``servoj`` parameters [s], [-].
    check : bool
        Parse the file back and re-simulate.

    Examples
    --------
    >>> from sloshkit.export.frames import Mounting
    >>> settings = ExportSettings(None, None, None, None, None, Mounting(), (1.0, 0.0, 0.0),
    ...                           0.1, 300.0, True)
    >>> settings.arm("pose-csv") is None  # joint formats load the arm (UR5e by default)
    True
    """

    robot: str | None
    urdf: Path | None
    base_link: str | None
    tip_link: str | None
    seed_rad: tuple[float, ...] | None
    mounting: Any
    axis: tuple[float, float, float]
    lookahead_time_s: float
    gain: float
    check: bool

    def arm(self, fmt: str) -> Any:
        """The arm for joint formats (unless ``--urdf`` or ``--robot`` says otherwise: the UR5e,
        or the vendor's built-in arm for a robot program, e.g. lrmate200id for fanuc-ls)."""
        from sloshkit.export.kinematics import load_arm
        from sloshkit.export.readback import JOINT_FORMATS

        if fmt not in JOINT_FORMATS:
            return None
        from sloshkit.export.formats.vendors import default_robot

        default = default_robot(fmt) or "ur5e"
        robot = self.robot if self.robot is not None or self.urdf is not None else default
        seed = None if self.seed_rad is None else tuple(self.seed_rad)
        import numpy as np

        return load_arm(
            robot,
            self.urdf,
            self.base_link,
            self.tip_link,
            None if seed is None else np.asarray(seed),
        )


def export_settings(
    *,
    robot: str | None,
    urdf: Path | None,
    base_link: str | None,
    tip_link: str | None,
    seed_rad: tuple[float, ...] | None,
    tool_offset_m: tuple[float, float, float],
    tool_rpy_rad: tuple[float, float, float],
    base_xyz_m: tuple[float, float, float],
    base_rpy_rad: tuple[float, float, float],
    axis: tuple[float, float, float],
    lookahead_time_s: float,
    gain: float,
    check: bool,
) -> ExportSettings:
    """The export settings of values in SI, the ``servoj`` limits checked.

    Parameters
    ----------
    robot : str or None
        A built-in arm (`sloshkit.export.kinematics.robot_names`).
    urdf : pathlib.Path or None
        A URDF file (instead of ``robot``).
    base_link, tip_link : str or None
        The URDF links the chain runs between.
    seed_rad : tuple of float or None
        IK seed of the first sample [rad].
    tool_offset_m : tuple of float
        The container's bottom centre in the flange frame (x, y, z) [m].
    tool_rpy_rad : tuple of float
        The container frame in the flange frame (roll, pitch, yaw, xyz fixed) [rad].
    base_xyz_m, base_rpy_rad : tuple of float
        The path frame in the robot base [m], [rad].
    axis : tuple of float
        Direction of a 1-D move in the path frame (non-zero).
    lookahead_time_s : float
        URScript ``servoj`` lookahead time, within `LOOKAHEAD_TIME_RANGE_S` [s].
    gain : float
        URScript ``servoj`` gain, within `GAIN_RANGE`.
    check : bool
        Parse the file back and re-simulate.

    Returns
    -------
    ExportSettings

    Raises
    ------
    InputError
        ``lookahead_time`` or ``gain`` outside the ``servoj`` range (named by parameter).

    Examples
    --------
    >>> settings = export_settings(
    ...     robot=None, urdf=None, base_link=None, tip_link=None, seed_rad=None,
    ...     tool_offset_m=(0.0, 0.0, 0.1), tool_rpy_rad=(3.141593, 0.0, 0.0),
    ...     base_xyz_m=(0.0, 0.0, 0.0), base_rpy_rad=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0),
    ...     lookahead_time_s=0.05, gain=500.0, check=True)
    >>> settings.mounting.tool_offset_m, settings.gain
    ((0.0, 0.0, 0.1), 500.0)
    >>> values = dict(robot=None, urdf=None, base_link=None, tip_link=None,
    ...     seed_rad=None, tool_offset_m=(0.0, 0.0, 0.1), tool_rpy_rad=(0.0, 0.0, 0.0),
    ...     base_xyz_m=(0.0, 0.0, 0.0), base_rpy_rad=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0),
    ...     lookahead_time_s=0.05, check=False)
    >>> export_settings(**values, gain=50.0)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: gain = '50' is invalid: must be between 100 and 2000
    """
    from sloshkit.export.frames import Mounting

    lookahead = require_in_range("lookahead_time", lookahead_time_s, *LOOKAHEAD_TIME_RANGE_S, "s")
    checked_gain = require_in_range("gain", gain, *GAIN_RANGE)
    return ExportSettings(
        robot=robot,
        urdf=urdf,
        base_link=base_link,
        tip_link=tip_link,
        seed_rad=seed_rad,
        mounting=Mounting(
            tool_offset_m=tool_offset_m,
            tool_rpy_rad=tool_rpy_rad,
            base_xyz_m=base_xyz_m,
            base_rpy_rad=base_rpy_rad,
        ),
        axis=axis,
        lookahead_time_s=lookahead,
        gain=checked_gain,
        check=bool(check),
    )
