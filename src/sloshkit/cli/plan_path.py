"""``sloshkit plan --path / --path-from-poses``: slosh-safe timing (and tilt) of a 3-D path.

Called by `sloshkit.cli.plan.plan_command` when a path is given; the 1-D ``plan --distance``
is unchanged.

The options become a `sloshkit.plan.path.problem.PathProblem` in
`sloshkit.io.plan_requests.path_problem_request` (angular limits default to 180 deg/s and
1000 deg/s^2 there; ``none`` lifts a limit), a pose file's own timing the reference candidate
in `sloshkit.plan.path.problem.reference_timing`. With ``--robot`` (or ``--urdf``) every
candidate is also solved for the arm's joints as ``sloshkit export`` solves them, with the
export's ``--base-pose``/``--tool-offset``/``--tool-rotation`` (`sloshkit.export.path_robot`):
a plan the arm cannot run is not feasible (joint speeds too high are slowed down uniformly and
verified again).
"""

from __future__ import annotations

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
from sloshkit.io.checks import naming
from sloshkit.io.plan_requests import path_problem_request, require_options
from sloshkit.io.poses import read_pose_file
from sloshkit.io.units import parse_quantity
from sloshkit.io.waypoints import read_waypoints, require_path_work
from sloshkit.model.modal import SloshModel
from sloshkit.plan.path.geometry import path_from_poses, path_from_waypoints
from sloshkit.plan.path.planner import PATH_METHODS, plan_path
from sloshkit.plan.path.problem import reference_timing
from sloshkit.plan.path.result import verify
from sloshkit.plan.path.timing import Timing


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
    export_settings: Any = None,
) -> None:
    """Parse the 3-D options, plan, print and export (exit 1 when nothing is feasible).

    Parameters
    ----------
    model : SloshModel
        The container model (from the model options).
    path_file : Path or None
        ``--path``: waypoints (CSV or TOML).
    poses_file : Path or None
        ``--path-from-poses``: a pose file whose geometry is re-timed.
    blend_radius : str
        ``--blend-radius`` (corner clothoids of waypoint paths).
    max_slosh_height, max_residual_height : str
        ``--max-slosh-height``, ``--max-residual-height`` (required).
    max_surface_angle : str or None
        ``--max-surface-angle``.
    vmax, amax, jmax : str
        ``--vmax``, ``--amax``, ``--jmax`` (required).
    max_angular_velocity, max_angular_acceleration : str or None
        ``--max-angular-velocity``, ``--max-angular-acceleration`` (None: the defaults
        `sloshkit.io.plan_requests.DEFAULT_ANGULAR_VELOCITY` and
        ``DEFAULT_ANGULAR_ACCELERATION``; ``none``: no limit).
    tilt_compensation : bool
        ``--tilt-compensation``: ``auto`` and ``optimal`` may tilt (``tilt`` always does).
    max_tilt, tilt_centre : str
        ``--max-tilt``, ``--tilt-centre``.
    method : str
        ``--method``: auto, retime, shaped, tilt or optimal.
    band : float
        ``--robust`` as a fraction.
    sample_period : str
        ``--sample-period``.
    out, plot : Path or None
        ``--out`` pose CSV, ``--plot`` figure.
    json_output : bool
        ``--json``.
    export_settings : ExportSettings, optional
        The export option group; with ``--robot``/``--urdf`` every candidate is checked for the
        arm's joints (`sloshkit.export.path_robot.robot_verifier`).

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.errors import InputError
    >>> try:
    ...     run_path_plan(None, path_file=None, poses_file=None, blend_radius="50mm",
    ...                   max_slosh_height="15mm", max_residual_height="2mm",
    ...                   max_surface_angle=None, vmax="2m/s", amax="10m/s^2", jmax="100m/s^3",
    ...                   max_angular_velocity=None, max_angular_acceleration=None,
    ...                   tilt_compensation=False, max_tilt="30deg", tilt_centre="0mm",
    ...                   method="auto", band=0.0, sample_period="4ms", out=None, plot=None,
    ...                   json_output=True)
    ... except InputError as error:
    ...     print(error.parameter)
    path
    """
    if (path_file is None) == (poses_file is None):
        raise InputError("path", "both or none", "give exactly one of --path, --path-from-poses")
    require_options(
        [
            ("--vmax", vmax),
            ("--amax", amax),
            ("--jmax", jmax),
            ("--max-slosh-height", max_slosh_height),
            ("--max-residual-height", max_residual_height),
        ]
    )
    if method not in PATH_METHODS:
        raise InputError("method", method, "with a path: " + ", ".join(PATH_METHODS))
    reference: Timing | None = None
    if poses_file is not None:
        trajectory = read_pose_file(poses_file, parameter="path_from_poses")
        positions, quaternions = trajectory.position_m, trajectory.quaternion_xyzw
        path = path_from_poses(positions, quaternions, name=poses_file.name)
        reference = reference_timing(trajectory, path)
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
        radius = parse_quantity(blend_radius, "length", "blend_radius")
        with naming("path", path_file, keep=("blend_radius",)):  # errors name --path, the file
            path = path_from_waypoints(points, radius, yaw, path_file.name)
    # the planner's work grows with the samples: refuse a path far too long before any of it
    require_path_work(
        path.length_m,
        parse_quantity(str(vmax), "velocity", "vmax"),
        parse_quantity(sample_period, "time", "sample_period"),
        "path" if path_file is not None else "path_from_poses",
        path_file if path_file is not None else poses_file,
        sample_period,
    )
    problem = path_problem_request(
        model,
        path,
        vmax=str(vmax),
        amax=str(amax),
        jmax=str(jmax),
        max_angular_velocity=max_angular_velocity,
        max_angular_acceleration=max_angular_acceleration,
        max_slosh_height=str(max_slosh_height),
        max_residual_height=str(max_residual_height),
        max_surface_angle=max_surface_angle,
        band=band,
        sample_period=sample_period,
        max_tilt=max_tilt,
        tilt_centre=tilt_centre,
    )
    verifier = _robot_verifier(export_settings)
    with stderr.status("planning the path") as status:
        result = plan_path(
            problem,
            method,
            reference=reference,
            progress=lambda text: status.update(text),
            verifier=verify if verifier is None else verifier,
            tilt=tilt_compensation or method == "tilt",
        )
    warn_if_planned_upright(result)
    warn_if_beyond_small_amplitude(result)
    if result.feasible:
        if out is not None:
            from sloshkit.cli.plan_files import plan_file_header
            from sloshkit.export.headers import write_plan_csv

            header = plan_file_header(None, model, problem.slosh, problem.sample_period_s)
            write_plan_csv(out, result.columns(), header)
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


def warn_if_planned_upright(result: Any) -> None:
    """Warn (`sloshkit.errors.ValidityWarning`: stderr and JSON ``warnings``) when ``tilt``'s
    programs were asked to tilt with an arm and planned upright, the reason its candidate
    carries (the arm cannot reach the tilted probes of its joint model:
    `sloshkit.plan.path.joints.joint_map`).

    Parameters
    ----------
    result : PathPlanResult
        The plan; its ``tilt`` candidate's ``detail["upright"]`` holds the reason.

    Examples
    --------
    >>> import warnings
    >>> from types import SimpleNamespace
    >>> tilted = SimpleNamespace(method="tilt", detail={"stretch": 1.0})
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_if_planned_upright(SimpleNamespace(candidates=[tilted]))
    >>> caught
    []
    """
    import warnings

    from sloshkit.errors import ValidityWarning

    for candidate in result.candidates:
        reason = (candidate.detail or {}).get("upright")
        if candidate.method == "tilt" and reason:
            warnings.warn(
                f"--tilt-compensation with --robot/--urdf: the tilt's programs planned the "
                f"container upright ({reason})",
                ValidityWarning,
                stacklevel=1,
            )


def warn_if_beyond_small_amplitude(result: Any) -> None:
    """Warn (`sloshkit.errors.ValidityWarning`: stderr and JSON ``warnings``) when the chosen
    plan's verification drove the first mode beyond small-amplitude theory
    (`sloshkit.sim.simulate.LARGE_ANGLE_DEG`): the limits hold in the pendulum model, and
    the CFD of such plans shows waves that it does not have (docs/planning-3d.md,
    "Limitations").

    Parameters
    ----------
    result : PathPlanResult
        The plan; its chosen candidate's verification holds the angle.

    Examples
    --------
    >>> import warnings
    >>> from types import SimpleNamespace
    >>> check = SimpleNamespace(peak_slosh_angle_rad=0.37)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_if_beyond_small_amplitude(SimpleNamespace(chosen=SimpleNamespace(
    ...         verification=check)))
    >>> str(caught[0].message)[:58]
    "the plan's slosh angle reaches 21.2 deg (> 15 deg): beyond"
    """
    import math
    import warnings

    from sloshkit.errors import ValidityWarning
    from sloshkit.sim.simulate import LARGE_ANGLE_DEG

    check = None if result.chosen is None else result.chosen.verification
    if check is None:
        return
    angle = math.degrees(check.peak_slosh_angle_rad)
    if angle > LARGE_ANGLE_DEG:
        warnings.warn(
            f"the plan's slosh angle reaches {angle:.1f} deg (> {LARGE_ANGLE_DEG:g} deg): beyond "
            "small-amplitude theory; the limits hold in the pendulum model, which has no "
            "swirl, breaking or axisymmetric waves (see the CFD of such plans in "
            f"docs/planning-3d.md); --max-surface-angle {LARGE_ANGLE_DEG:g}deg keeps a plan "
            "within it",
            ValidityWarning,
            stacklevel=1,
        )


def _robot_verifier(settings: Any) -> Any:
    """`sloshkit.export.path_robot.robot_verifier` when ``--robot`` or ``--urdf`` is given."""
    if settings is None or (settings.robot is None and settings.urdf is None):
        return None
    from sloshkit.export.kinematics import load_arm
    from sloshkit.export.path_robot import robot_verifier

    seed = None if settings.seed_rad is None else np.asarray(settings.seed_rad)
    arm = load_arm(settings.robot, settings.urdf, settings.base_link, settings.tip_link, seed)
    return robot_verifier(arm, settings.mounting)


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
