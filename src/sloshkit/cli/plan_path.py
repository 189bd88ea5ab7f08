"""``sloshkit plan --path / --path-from-poses``: slosh-safe timing (and tilt) of a 3-D path.

Called by `sloshkit.cli.plan.plan_command` when a path is given; the 1-D ``plan --distance``
is unchanged.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import typer
from rich import box
from rich.table import Table
from rich.text import Text

from sloshkit.budget import require_samples
from sloshkit.cli import messages
from sloshkit.cli.app import stderr, stdout
from sloshkit.cli.options import print_json
from sloshkit.errors import InputError
from sloshkit.io.poses import read_pose_file
from sloshkit.io.units import parse_bounded, parse_quantity
from sloshkit.io.waypoints import read_waypoints
from sloshkit.model.modal import SloshModel
from sloshkit.plan.path import generalised_arc_length, path_from_poses, path_from_waypoints
from sloshkit.plan.path_planner import plan_path
from sloshkit.plan.retime import Timing
from sloshkit.plan.spatial import CartesianLimits, PathProblem, SpatialSloshLimits


def _quantity(text: str | None, kind: str, name: str) -> float | None:
    return None if text is None else parse_quantity(text, kind, name)


def _angular(text: str | None, power: int, name: str) -> float | None:
    """``90deg/s``, ``2rad/s``, ``300deg/s^2`` (``s**2``, ``s2`` too) or a bare number in
    rad/s^power, in the strict unit grammar (`sloshkit.io.units`; finite, > 0)."""
    if text is None:
        return None
    kind = "angular_velocity" if power == 1 else "angular_acceleration"
    try:
        return parse_bounded(text, kind, name, 0.0, math.inf)
    except InputError as error:
        example = "90deg/s" if power == 1 else "300deg/s^2"
        raise InputError(
            name, text, f"must be an angular rate > 0, e.g. {example}", error.valid
        ) from None


def _reference_timing(time_s: Any, positions: Any, quaternions: Any, length_m: float) -> Timing:
    """The pose file's own timing s(t), from its first moving sample (rest before dropped)."""
    from scipy.spatial.transform import Rotation

    s = generalised_arc_length(positions, Rotation.from_quat(quaternions))
    start = max(int(np.argmax(s > 1e-9)) - 1, 0)
    moving = np.concatenate(([True], np.diff(s[start:]) > 0.0))
    t = (time_s[start:] - time_s[start])[moving]
    return Timing.from_samples("pose file", t, s[start:][moving] / s[-1] * length_m)


def run_path_plan(
    model: SloshModel,
    *,
    path_file: Path | None,
    poses_file: Path | None,
    blend_radius: str,
    max_slosh_height: str | None,
    max_residual_height: str | None,
    max_surface_angle: str | None,
    vmax: str | None,
    amax: str | None,
    jmax: str | None,
    max_angular_velocity: str | None,
    max_angular_acceleration: str | None,
    tilt_compensation: bool,
    max_tilt: str,
    tilt_centre: str,
    method: str,
    band: float,
    sample_period: str,
    out: Path | None,
    plot: Path | None,
    json_output: bool,
) -> None:
    """Parse the 3-D options, plan, print and export (exit 1 when nothing is feasible)."""
    if (path_file is None) == (poses_file is None):
        raise InputError("path", "both or none", "give exactly one of --path, --path-from-poses")
    missing = [
        name
        for name, value in (
            ("--vmax", vmax),
            ("--amax", amax),
            ("--jmax", jmax),
            ("--max-slosh-height", max_slosh_height),
            ("--max-residual-height", max_residual_height),
        )
        if value is None
    ]
    if missing:
        raise InputError("plan", "incomplete", "needs " + ", ".join(missing))
    if method not in ("auto", "retime", "shaped", "tilt"):
        raise InputError("method", method, "with a path: auto, retime, shaped or tilt")
    reference: Timing | None = None
    if poses_file is not None:
        trajectory = read_pose_file(poses_file, parameter="path_from_poses")
        time_s = trajectory.time_s
        positions, quaternions = trajectory.position_m, trajectory.quaternion_xyzw
        path = path_from_poses(positions, quaternions, name=poses_file.name)
        reference = _reference_timing(time_s, positions, quaternions, path.length_m)
        # the planner samples (and may stretch) the file's own timing at the sample period
        require_samples(
            "path_from_poses",
            f"{trajectory.duration_s:.4g} s at {sample_period}",
            trajectory.duration_s / parse_quantity(sample_period, "time", "sample_period"),
            64,
            "path samples",
        )
    else:
        assert path_file is not None
        points, yaw = read_waypoints(path_file)
        path = path_from_waypoints(
            points, parse_quantity(blend_radius, "length", "blend_radius"), yaw, path_file.name
        )
    problem = PathProblem(
        path=path,
        machine=CartesianLimits(
            parse_quantity(str(vmax), "velocity", "vmax"),
            parse_quantity(str(amax), "acceleration", "amax"),
            parse_quantity(str(jmax), "jerk", "jmax"),
            _angular(max_angular_velocity, 1, "max_angular_velocity"),
            _angular(max_angular_acceleration, 2, "max_angular_acceleration"),
        ),
        slosh=SpatialSloshLimits(
            parse_quantity(str(max_slosh_height), "length", "max_slosh_height"),
            parse_quantity(str(max_residual_height), "length", "max_residual_height"),
            _quantity(max_surface_angle, "angle", "max_surface_angle"),
            band,
        ),
        model=model,
        sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
        max_tilt_rad=parse_quantity(max_tilt, "angle", "max_tilt"),
        tilt_centre_height_m=parse_quantity(tilt_centre, "length", "tilt_centre"),
    )
    with stderr.status("planning the path") as status:
        result = plan_path(
            problem,
            method,
            reference=reference,
            progress=lambda text: status.update(text),
            tilt=tilt_compensation or method == "tilt",
        )
    if result.feasible:
        if out is not None:
            result.to_csv(out)
        if plot is not None:
            result.plot(path=plot)
    payload = result.to_dict()
    if json_output:
        print_json(payload)
    else:
        _print_table(payload, path.length_m, out if result.feasible else None)
    if not result.feasible:
        messages.error(stderr, f"no method meets the limits ({result.reason()})")
        raise typer.Exit(1)


def _print_table(payload: dict[str, Any], length_m: float, out: Path | None) -> None:
    table = Table(
        title=f"Plans for a {length_m:.3f} m path",
        caption="T: duration; residual: slosh height left after the move; "
        "ok: verified against the limits",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
    )
    table.add_column("method", no_wrap=True)
    for header in (
        "T\n[s]",
        "peak height\n[mm]",
        "residual\n[mm]",
        "tilt\n[°]",
        "ok",
        "cpu\n[s]",
    ):
        table.add_column(Text(header), justify="right", no_wrap=True)

    def show(value: float | None, scale: float, fmt: str) -> str:
        return "-" if value is None else format(value * scale, fmt)

    for candidate in payload["candidates"]:
        table.add_row(
            candidate["method"],
            show(candidate["duration_s"], 1.0, ".3f"),
            show(candidate["peak_slosh_height_m"], 1e3, ".2f"),
            show(candidate["residual_slosh_height_m"], 1e3, ".2f"),
            show(candidate["peak_tilt_deg"], 1.0, ".1f"),
            "yes" if candidate["feasible"] else "no",
            f"{candidate['compute_time_s']:.2g}",
        )
    stdout.print(table)
    if payload["feasible"]:
        stdout.print(
            f"chosen: {payload['method']}, {payload['duration_s']:.3f} s"
            + (f"; wrote {out}" if out is not None else "")
        )
