"""Export a plan to a controller format and check the round trip (the ``export`` command's core).

Frames: the plan's poses are the container's bottom centre in the *path* frame; ``Mounting``
places the path in the robot's base frame (``T_base_path``) and the container in the flange
frame (``T_flange_container``), so the flange must follow
``T_base_flange = T_base_path T_path_container inv(T_flange_container)``.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.approach import approach_settle_time
from sloshkit.export.formats.vendors import PROGRAM_FORMATS
from sloshkit.export.frames import Mounting, invert, matrices_to_poses, poses_to_matrices
from sloshkit.export.ik import JointPath, joint_limit_violations, solve_joint_path
from sloshkit.export.kinematics import Arm, robot_names
from sloshkit.export.plans import LinePlan, PoseStream, line_to_poses, read_plan, require_rest
from sloshkit.export.readback import JOINT_FORMATS, read_joint_samples, rebuild_container_poses
from sloshkit.export.roundtrip import (
    RoundTrip,
    compare_line,
    compare_spatial,
    container_poses_in_path,
)
from sloshkit.model.modal import SloshModel
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.plan.line.problem import SloshLimits
from sloshkit.plan.path.problem import SpatialSloshLimits
from sloshkit.version import __version__

FloatArray = NDArray[np.float64]

#: Sample streams (a controller or drive plays them at the file's period) ...
STREAM_FORMATS = ("pose-csv", "joint-csv", "ros2", "ros2-bag", "urscript", "cam-table")
#: ... and industrial-robot programs of timed joint moves (`sloshkit.export.formats.vendors`).
FORMATS = (*STREAM_FORMATS, *PROGRAM_FORMATS)
SUFFIXES = {
    "pose-csv": ".poses.csv",
    "joint-csv": ".joints.csv",
    "ros2": ".ros2.yaml",
    "ros2-bag": ".bag",
    "urscript": ".script",
    "cam-table": ".cam.csv",
    **{name: entry.suffix for name, entry in PROGRAM_FORMATS.items()},
}


def path_beside(base: Path, fmt: str) -> Path:
    """Where an export of ``base`` (a plan file, or ``plan --out``) goes by default: beside it,
    its stem followed by the format's suffix (`SUFFIXES`).

    Parameters
    ----------
    base : Path
        The plan file the export is made from.
    fmt : str
        The export format (a key of `FORMATS`).

    Returns
    -------
    Path

    Examples
    --------
    >>> path_beside(Path("runs/plan.csv"), "urscript").as_posix()
    'runs/plan.script'
    """
    return base.with_name(base.stem + SUFFIXES.get(fmt, ""))


@dataclass(frozen=True)
class ExportResult:
    """What was exported, and the round trip when checked.

    Attributes
    ----------
    format : str
        One of `FORMATS`.
    path : pathlib.Path
        The written file.
    samples : int
        Number of samples written.
    sample_period_s : float
        Their period [s].
    joints : JointPath or None
        The joint path for joint formats.
    round_trip : RoundTrip or None
        The check (None when not run).
    notes : tuple of str
        Remarks (e.g. why a check was not possible).
    written : bool
        False when the file was removed again (its round trip failed).

    Examples
    --------
    >>> from pathlib import Path
    >>> result = ExportResult("pose-csv", Path("move.poses.csv"), 251, 0.004)
    >>> result.to_dict()["samples"], result.to_dict()["format"]
    (251, 'pose-csv')
    """

    format: str
    path: Path
    samples: int
    sample_period_s: float
    joints: JointPath | None = None
    round_trip: RoundTrip | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)
    written: bool = True

    @property
    def passed(self) -> bool:
        """False only when a round trip ran and failed."""
        return self.round_trip is None or self.round_trip.passed

    def to_dict(self) -> dict[str, Any]:
        """The export command's JSON (unit-suffixed keys)."""
        return {
            "format": self.format,
            "path": str(self.path),
            "samples": self.samples,
            "sample_period_s": self.sample_period_s,
            "joints": None if self.joints is None else self.joints.to_dict(),
            "round_trip": None if self.round_trip is None else self.round_trip.to_dict(),
            "passed": self.passed,
            "written": self.written,
            "notes": list(self.notes),
        }


def model_summary(model: SloshModel) -> str:
    """One-line description of a slosh model for file headers (SI).

    Parameters
    ----------
    model : SloshModel
        The model.

    Returns
    -------
    str
        A JSON object on one line.

    Examples
    --------
    >>> import json
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> summary = json.loads(model_summary(model))
    >>> summary["liquid"], round(summary["first_mode_frequency_hz"], 2)
    ('water-25C', 4.72)
    """
    first = model.modes[0]
    return json.dumps(
        {
            "radius_m": model.radius_m,
            "fill_height_m": model.fill_height_m,
            "liquid": model.liquid.name,
            "modes": len(model.modes),
            "first_mode_frequency_hz": round(first.frequency_hz, 9),
            "first_mode_damping_ratio": round(first.damping_ratio, 9),
        }
    )


def limits_summary(limits: SloshLimits | SpatialSloshLimits) -> str:
    """One-line description of slosh limits for file headers (degrees and metres, as named).

    Parameters
    ----------
    limits : SloshLimits
        The limits.

    Returns
    -------
    str
        A JSON object on one line.

    Examples
    --------
    >>> import math
    >>> from sloshkit import SloshLimits
    >>> limits_summary(SloshLimits(math.radians(10), math.radians(1)))
    '{"max_angle_deg": 10.0, "max_residual_deg": 1.0, "max_wall_elevation_m": null}'
    """
    if isinstance(limits, SpatialSloshLimits):
        return json.dumps(
            {
                "max_slosh_height_m": limits.max_height_m,
                "max_residual_height_m": limits.max_residual_height_m,
                "max_surface_angle_deg": None
                if limits.max_surface_angle_rad is None
                else round(math.degrees(limits.max_surface_angle_rad), 9),
            }
        )
    return json.dumps(
        {
            "max_angle_deg": round(math.degrees(limits.max_angle_rad), 9),
            "max_residual_deg": round(math.degrees(limits.max_residual_rad), 9),
            "max_wall_elevation_m": limits.max_wall_elevation_m,
        }
    )


def export_plan(
    plan: LinePlan | PoseStream | str | Path,
    fmt: str,
    out: str | Path,
    *,
    arm: Arm | None = None,
    mounting: Mounting = Mounting(),  # noqa: B008 - frozen dataclass
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0),
    sample_period_s: float | None = None,
    model: SloshModel | None = None,
    limits: SloshLimits | SpatialSloshLimits | None = None,
    check: bool = True,
    lookahead_time_s: float = 0.05,
    gain: float = 500.0,
) -> ExportResult:
    """Write ``plan`` in format ``fmt`` to ``out`` and, with ``check``, verify the round trip.

    Parameters
    ----------
    plan : a `LinePlan`, a `PoseStream`, or a CSV file of either (`read_plan`)
    fmt : one of `FORMATS`
    out : output file
    arm : the arm, for joint formats (`sloshkit.export.kinematics.load_arm`)
    mounting : container in the flange and path in the base (`Mounting`)
    axis : direction of a 1-D plan in the path frame
    sample_period_s : output sample period [s] (default the plan's; ``urscript`` is always
        0.002 s; robot programs: a whole multiple of the controller's interpolation period,
        default one point per period)
    model : slosh model for the round trip (required by ``check``)
    limits : slosh limits the plan was made for (`SloshLimits`, or `SpatialSloshLimits` for a
        3-D plan; checked on the export; written to headers)
    check : parse the file back, rebuild the motion and compare the slosh (`RoundTrip`)
    lookahead_time_s, gain : ``servoj`` parameters for ``urscript`` (whose program also waits
        `approach_settle_time` after its approach and holds its last target)

    Raises
    ------
    InputError
        For an unknown format, a plan not at rest at both ends (`require_rest`), an arm that
        cannot follow it.

    Returns
    -------
    ExportResult

    References
    ----------
    See `sloshkit.export.roundtrip` and the format modules in `sloshkit.export.formats`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(101) * 0.004
    >>> s = t / t[-1]
    >>> x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> v = 0.2 / t[-1] * 30 * s**2 * (1 - s) ** 2
    >>> a = 0.2 / t[-1] ** 2 * 60 * s * (1 - s) * (1 - 2 * s)
    >>> plan = LinePlan(t, x, v, a)
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "move.cam.csv"
    >>> export_plan(plan, "cam-table", out, model=model).passed
    True
    """
    if fmt not in FORMATS:
        raise InputError("format", fmt, "must be one of " + ", ".join(FORMATS))
    source = read_plan(plan) if isinstance(plan, str | Path) else plan
    require_rest(source, source.source or "python")
    stream = (
        line_to_poses(source, np.asarray(axis, dtype=float))
        if isinstance(source, LinePlan)
        else source
    )
    if check and model is None:
        raise InputError("model", None, "the round-trip check needs a slosh model")
    period = _output_period(fmt, stream, sample_period_s)
    planned = stream
    stream = stream.resample(period)
    if fmt in PROGRAM_FORMATS:  # refuse a bad name or a program too long before any IK
        PROGRAM_FORMATS[fmt].check_target(Path(out))
        PROGRAM_FORMATS[fmt].controller.check_size(int(stream.time_s.size), period)
    metadata = _metadata(fmt, stream, period, model, limits, mounting, arm)
    base_to_path = mounting.base_to_path
    container = base_to_path[None] @ poses_to_matrices(stream.position_m, stream.quaternion_xyzw)
    joints: JointPath | None = None
    approach_notes: list[str] = []
    path = Path(out)
    from sloshkit.export.formats import cam_table, joint_csv, pose_csv, ros2, urscript

    if fmt == "pose-csv":
        position, quaternion = matrices_to_poses(container)
        placed = PoseStream(
            PoseTrajectory(stream.time_s, position, quaternion), stream.source, stream.metadata
        )
        pose_csv.write_pose_csv(path, placed, metadata)
    elif fmt == "cam-table":
        if stream.line is None:
            raise InputError("format", fmt, "a cam table needs a 1-D plan (t_s, position_m)")
        cam_table.write_cam_table(path, stream.line, metadata)
    else:
        if arm is None:
            raise InputError("robot", None, f"format {fmt} needs an arm (--robot or --urdf)")
        if fmt in PROGRAM_FORMATS:
            PROGRAM_FORMATS[fmt].controller.check_robot(arm.name, robot_names())
        flange = container @ invert(mounting.flange_to_container)[None]
        joints = solve_joint_path(arm, flange, stream.time_s)
        if fmt in PROGRAM_FORMATS:
            PROGRAM_FORMATS[fmt].write(path, joints, metadata)
        elif fmt == "joint-csv":
            joint_csv.write_joint_csv(path, joints, metadata)
        elif fmt == "ros2":
            ros2.write_ros2_yaml(path, joints, arm.base_link, metadata)
        elif fmt == "ros2-bag":
            from sloshkit.export.formats.ros2_bag import write_ros2_bag

            write_ros2_bag(path, joints, arm.base_link, metadata)
        else:
            settle, note = approach_settle_time(
                arm, joints.position_rad[0], mounting, model, limits
            )
            approach_notes.append(note)
            metadata["approach_settle_s"] = format(settle, ".6g")
            urscript.write_urscript(
                path, joints, metadata, lookahead_time_s, gain, settle_time_s=settle
            )
    notes: list[str] = [note for note in approach_notes if note]
    if fmt in PROGRAM_FORMATS:
        rule = PROGRAM_FORMATS[fmt].controller
        notes.append(
            f"{stream.time_s.size} points every {1e3 * period:g} ms ({rule.language} "
            f"interpolates every {1e3 * rule.interpolation_period_s:g} ms); the round trip joins "
            f"them by a spline and re-simulates every {1e3 * rule.round_trip_step_s:g} ms"
        )
    trip = None
    if check and model is not None:
        trip, note = check_round_trip(
            fmt, path, planned, model, arm=arm, mounting=mounting, limits=limits
        )
        notes += [note] if note else []
    return ExportResult(fmt, path, int(stream.time_s.size), period, joints, trip, tuple(notes))


def check_round_trip(
    fmt: str,
    path: str | Path,
    plan: PoseStream,
    model: SloshModel,
    *,
    arm: Arm | None = None,
    mounting: Mounting = Mounting(),  # noqa: B008 - frozen dataclass
    limits: SloshLimits | SpatialSloshLimits | None = None,
) -> tuple[RoundTrip | None, str]:
    """Parse an exported file back, rebuild the container motion and compare its slosh with
    the plan's (`sloshkit.export.roundtrip`); joint files are also checked against the arm's
    joint position and velocity limits and for jumps (`joint_limit_violations`).

    Parameters
    ----------
    fmt : the file's format (one of `FORMATS`)
    path : the exported file
    plan : the pose stream it was exported from (at the plan's own sample period)
    model : the slosh model
    arm, mounting : as given to `export_plan`
    limits : slosh limits to check, if known

    Returns
    -------
    tuple
        The `RoundTrip` (1-D model for a 1-D plan, 3-D model for a pose stream) and a note
        ("" when there is nothing to add).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(101) * 0.004
    >>> s = t / t[-1]
    >>> x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> v = 0.2 / t[-1] * 30 * s**2 * (1 - s) ** 2
    >>> a = 0.2 / t[-1] ** 2 * 60 * s * (1 - s) * (1 - 2 * s)
    >>> plan = LinePlan(t, x, v, a)
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "move.cam.csv"
    >>> _ = export_plan(plan, "cam-table", out, check=False)
    >>> trip, _ = check_round_trip("cam-table", out, line_to_poses(plan, np.ones(3)), model)
    >>> trip.passed
    True
    """
    axis = (1.0, 0.0, 0.0) if plan.axis is None else tuple(float(v) for v in plan.axis)
    time, rebuilt = rebuild_container_poses(fmt, path, arm, mounting, axis)  # type: ignore[arg-type]
    in_path = container_poses_in_path(rebuilt, mounting.base_to_path)
    if plan.line is None:
        trip = compare_spatial(model, plan, time, in_path, limits)
    else:
        trip = compare_line(model, plan, time, in_path, limits)
    if fmt in JOINT_FORMATS and arm is not None:
        joint_time, position = read_joint_samples(fmt, path)
        extra = joint_limit_violations(arm, joint_time, position)
        trip = dataclasses.replace(trip, violations=trip.violations + tuple(extra))
    return trip, ""


def _output_period(fmt: str, stream: PoseStream, requested: float | None) -> float:
    from sloshkit.export.formats.urscript import UR_SAMPLE_PERIOD_S

    if fmt in PROGRAM_FORMATS:
        return PROGRAM_FORMATS[fmt].controller.point_period(requested)
    if fmt == "urscript":
        if requested is not None and abs(requested - UR_SAMPLE_PERIOD_S) > 1e-12:
            raise InputError("sample_period", requested, "urscript streams at 0.002 s (2ms)")
        return UR_SAMPLE_PERIOD_S
    return stream.sample_period_s if requested is None else float(requested)


def _metadata(
    fmt: str,
    stream: PoseStream,
    period: float,
    model: SloshModel | None,
    limits: SloshLimits | SpatialSloshLimits | None,
    mounting: Mounting,
    arm: Arm | None,
) -> dict[str, object]:
    metadata: dict[str, object] = {
        "format": f"sloshkit {fmt}",
        "sloshkit_version": __version__,
        "sample_period_s": format(period, ".12g"),
        "source": Path(stream.source).name if stream.source else "python",
    }
    if stream.line is not None and stream.axis is not None:
        metadata["plan"] = (
            "1-D move along "
            + json.dumps([round(float(value), 12) for value in stream.axis])
            + " of the path frame"
        )
    if fmt == "pose-csv":
        metadata["units"] = "t [s]; x, y, z [m]; qx, qy, qz, qw [-] (unit quaternion, scalar last)"
        metadata["frame"] = (
            "container bottom centre in the robot base frame (the path frame placed by "
            "base_pose); quaternion rotates container axes into that frame; z up"
        )
    elif fmt == "cam-table":
        metadata["units"] = "t_s [s], position_m [m], velocity_m_s [m/s], acceleration_m_s2 [m/s^2]"
        metadata["frame"] = "slide axis, from the start position"
    else:
        if arm is not None:
            metadata["robot"] = arm.name
            metadata["base_link"] = arm.base_link
            metadata["tip_link"] = arm.tip_link
            metadata["joints"] = ",".join(arm.joint_names)
        metadata["units"] = (
            "joint positions [rad]; servoj t and lookahead_time [s]"
            if fmt == "urscript"
            else "joint positions [deg] as the controller counts them; segment times as written"
            if fmt in PROGRAM_FORMATS
            else "time [s]; joint positions [rad], velocities [rad/s], accelerations [rad/s^2]"
        )
    if fmt != "cam-table":
        metadata["mounting"] = json.dumps(
            {key: [round(v, 12) for v in value] for key, value in mounting.to_dict().items()}
        )
    carried = stream.metadata
    if model is not None:
        metadata["model"] = model_summary(model)
    elif "model" in carried:
        metadata["model"] = carried["model"]
    if limits is not None:
        metadata["limits"] = limits_summary(limits)
    elif "limits" in carried:
        metadata["limits"] = carried["limits"]
    return metadata
