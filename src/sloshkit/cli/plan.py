"""``sloshkit plan``: the fastest move within slosh and machine limits."""

from __future__ import annotations

import typing
from pathlib import Path
from typing import Annotated

import typer
from rich import box
from rich.table import Table
from rich.text import Text

from sloshkit.cli import signals
from sloshkit.cli.app import app, stderr, stdout
from sloshkit.cli.export import (
    RoundTripFailed,
    check_export_request,
    run_export,
    show_export,
    with_export_options,
)
from sloshkit.cli.messages import error
from sloshkit.cli.moves import Amax, Distance, Jmax, Vmax
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.cli.sweep import MaxAngle, MaxResidual
from sloshkit.errors import InputError
from sloshkit.export.settings import ExportSettings
from sloshkit.io.outputs import all_or_nothing, check_file
from sloshkit.io.plan_requests import line_plan_request
from sloshkit.io.requests import fraction_request
from sloshkit.model.modal import SloshModel
from sloshkit.plan.line.planner import plan


@app.command("plan")
@with_model_options
@with_export_options
def plan_command(
    context: typer.Context,
    slosh_model: SloshModel,
    export_settings: ExportSettings,
    distance: Distance = "0.5m",
    max_angle: MaxAngle = None,
    max_residual: MaxResidual = None,
    max_wall_elevation: Annotated[
        str | None, typer.Option("--max-wall-elevation", help="Limit on the wall elevation.")
    ] = None,
    vmax: Vmax = None,
    amax: Amax = None,
    jmax: Jmax = None,
    method: Annotated[
        str,
        typer.Option(
            "--method",
            help="auto, paper, trapezoidal, cubic, quintic, septic, fast, shaped, optimal; "
            "with a path: auto (the minimum-time programs only on moves of at most 600 "
            "samples, with --robot 300), retime (minimum time, upright), shaped, tilt "
            "(minimum time with the tilt), optimal (tilt with --tilt-compensation, else "
            "retime).",
        ),
    ] = "auto",
    robust: Annotated[
        str,
        typer.Option("--robust", help="Frequency band the limits must hold over, e.g. 10%."),
    ] = "0%",
    sample_period: Annotated[
        str, typer.Option("--sample-period", help="Controller sample period, e.g. 4ms.")
    ] = "4ms",
    nonlinear_optimal: Annotated[
        bool,
        typer.Option("--nonlinear-optimal", help="Optimal control with nonlinear pendulums."),
    ] = False,
    smooth: Annotated[
        bool,
        typer.Option(
            "--smooth/--time-optimal",
            help="Optimal method: the smooth variant (default: 0.5 % above the minimum time, "
            "least jerk variation, no chattering) or the bang-bang time-optimal move.",
        ),
    ] = True,
    max_duration: Annotated[
        str | None, typer.Option("--max-duration", help="Longest acceptable move, e.g. 2s.")
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Trajectory CSV at the sample period.")
    ] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Figure of the candidates.")] = None,
    export: Annotated[
        str | None,
        typer.Option(
            "--export",
            help="Also write the chosen move for a controller (see 'sloshkit export'): "
            "pose-csv, joint-csv, ros2, ros2-bag, urscript, cam-table, fanuc-ls, abb-rapid or "
            "kuka-krl.",
        ),
    ] = None,
    json_output: Json = False,
    path: Annotated[
        Path | None,
        typer.Option(
            "--path", help="3-D: waypoints (CSV x,y,z[,yaw] with units in the header, or TOML)."
        ),
    ] = None,
    path_from_poses: Annotated[
        Path | None,
        typer.Option("--path-from-poses", help="3-D: re-time the path of a pose file."),
    ] = None,
    blend_radius: Annotated[
        str, typer.Option("--blend-radius", help="3-D: corner blend radius, e.g. 50mm.")
    ] = "50mm",
    max_slosh_height: Annotated[
        str | None, typer.Option("--max-slosh-height", help="3-D: peak slosh height, e.g. 15mm.")
    ] = None,
    max_residual_height: Annotated[
        str | None,
        typer.Option("--max-residual-height", help="3-D: residual slosh height, e.g. 2mm."),
    ] = None,
    max_surface_angle: Annotated[
        str | None,
        typer.Option("--max-surface-angle", help="3-D: peak first-mode surface angle, e.g. 20deg."),
    ] = None,
    max_angular_velocity: Annotated[
        str | None,
        typer.Option(
            "--max-angular-velocity",
            help="3-D: container angular speed (default 180deg/s; 'none' for no limit).",
        ),
    ] = None,
    max_angular_acceleration: Annotated[
        str | None,
        typer.Option(
            "--max-angular-acceleration",
            help="3-D: angular acceleration (default 1000deg/s^2; 'none' for no limit).",
        ),
    ] = None,
    tilt_compensation: Annotated[
        bool,
        typer.Option(
            "--tilt-compensation",
            help="3-D: let auto and optimal tilt the container (tilt always does).",
        ),
    ] = False,
    max_tilt: Annotated[
        str, typer.Option("--max-tilt", help="3-D: largest tilt from vertical, e.g. 30deg.")
    ] = "30deg",
    tilt_centre: Annotated[
        str,
        typer.Option("--tilt-centre", help="3-D: rotation centre above the container bottom."),
    ] = "0mm",
) -> None:
    """The fastest move that keeps the slosh within limits, verified by simulation.

    Every candidate is re-simulated from its sampled export. Exit code 1 when no method meets
    the limits.

    Example:

      sloshkit plan --distance 0.5m --max-angle 5deg --max-residual 0.25deg --vmax 1.5m/s
      --amax 20m/s^2 --jmax 500m/s^3 --damping-ratio 0.03 --out traj.csv --plot plan.png

    With --path or --path-from-poses the timing (and, with --tilt-compensation, the tilt) of a
    3-D path is planned instead (methods auto, retime, shaped, tilt, optimal; limits
    --max-slosh-height, --max-residual-height); the export is a pose file (t,x,y,z,qx,qy,qz,qw).
    """
    check_file(out, "out")
    check_file(plot, "plot", "figure")
    if export is not None and path is None and path_from_poses is None:
        target = _export_target(out, export)  # as _export_chosen names it
        assert target is not None
        check_export_request(  # before planning; the default path never replaces a user file
            export,
            target,
            export_settings,
            "export",
            inputs=(("out", out), ("urdf", export_settings.urdf)),
            chosen=False,
        )
    if path is not None or path_from_poses is not None:
        from sloshkit.cli.plan_path import run_path_plan

        if export is not None:
            raise InputError(
                "export", export, "not available with --path yet; --out writes the pose CSV"
            )
        run_path_plan(
            slosh_model,
            path_file=path,
            poses_file=path_from_poses,
            blend_radius=blend_radius,
            max_slosh_height=max_slosh_height,
            max_residual_height=max_residual_height,
            max_surface_angle=max_surface_angle,
            vmax=vmax,
            amax=amax,
            jmax=jmax,
            max_angular_velocity=max_angular_velocity,
            max_angular_acceleration=max_angular_acceleration,
            tilt_compensation=tilt_compensation,
            max_tilt=max_tilt,
            tilt_centre=tilt_centre,
            method=method,
            band=fraction_request(robust, "robust"),
            sample_period=sample_period,
            out=out,
            plot=plot,
            json_output=json_output,
            export_settings=export_settings,
        )
        return

    problem = line_plan_request(
        slosh_model,
        distance,
        vmax,
        amax,
        jmax,
        max_angle,
        max_residual,
        max_wall_elevation,
        robust,
        sample_period,
        max_duration,
    )

    def progress(text: str) -> None:
        status.update(text)
        signals.check()  # between candidates: compiled kernels never see the signal

    with stderr.status("planning") as status, signals.deferred():
        result = plan(problem, method, nonlinear_optimal, progress=progress, smooth=smooth)
    payload = result.to_dict()
    exported = None
    # The trajectory, its figure and its export are kept together or not at all (a signal or a
    # failed round trip after the CSV was written must not leave the CSV behind).
    try:
        with all_or_nothing(out, plot, _export_target(out, export), before_keeping=signals.check):
            if result.feasible:
                if out is not None:
                    from sloshkit.cli.plan_files import plan_file_header
                    from sloshkit.export.headers import write_plan_csv

                    header = plan_file_header(
                        context, slosh_model, problem.slosh, problem.sample_period_s
                    )
                    write_plan_csv(out, result.columns(), header)
                if plot is not None:
                    result.plot(plot)
            if result.feasible and export is not None:
                exported = _export_chosen(
                    result, problem, export, out, export_settings, slosh_model
                )
                payload["export"] = exported.to_dict()
                if not exported.passed:  # nothing is kept: neither the export nor the plan
                    raise RoundTripFailed(exported)
    except RoundTripFailed:
        pass
    if json_output:
        print_json(payload)
    else:
        table = Table(
            title=f"Plans for a {1e3 * problem.distance_m:.0f} mm move",
            caption="T: duration; θ₁: first-mode slosh angle; "
            "resid.: amplitude left after the move; "
            "ok: verified against the limits",
            box=box.SIMPLE_HEAD,
            pad_edge=False,
        )
        table.add_column("method", no_wrap=True)
        for header_text in (
            "T\n[s]",
            "peak\nθ₁ [°]",
            "resid.\nθ₁ [°]",
            "peak v\n[m/s]",
            "peak a\n[m/s²]",
            "peak j\n[m/s³]",
            "ok",
            "cpu\n[s]",
        ):
            table.add_column(Text(header_text), justify="right", no_wrap=True)
        for candidate in payload["candidates"]:

            def show(value: float | None, fmt: str) -> str:
                return "-" if value is None else format(value, fmt)

            table.add_row(
                candidate["method"],
                show(candidate["duration_s"], ".4f"),
                show(candidate["peak_angle_deg"], ".2f"),
                show(candidate["residual_angle_deg"], ".2f"),
                show(candidate["peak_velocity_m_s"], ".3f"),
                show(candidate["peak_acceleration_m_s2"], ".3g"),
                "∞"
                if candidate["peak_jerk_m_s3"] is None and candidate["duration_s"]
                else show(candidate["peak_jerk_m_s3"], ".3g"),
                "yes" if candidate["feasible"] else "no",
                f"{candidate['compute_time_s']:.2g}",
            )
        stdout.print(table)
        if result.feasible:
            stdout.print(
                f"chosen: {payload['method']}"
                + (f" ({payload['variant']})" if payload["variant"] else "")
                + f", {payload['duration_s']:.4f} s"
                + (
                    f", {payload['speed_up_over_best_paper_law']:.2f}x faster than the best "
                    "paper law"
                    if payload["speed_up_over_best_paper_law"]
                    else ""
                )
                + (
                    f"; wrote {out}"
                    if out is not None and (exported is None or exported.passed)
                    else ""
                )
            )
    if exported is not None and not json_output:
        show_export(exported)
    if exported is not None and not exported.passed:
        raise typer.Exit(1)
    if not result.feasible:
        messages = "; ".join(f"{c.method}: {c.message}" for c in result.candidates)
        error(stderr, f"no method meets the limits ({messages})")
        raise typer.Exit(1)


def _export_chosen(
    result: typing.Any,
    problem: typing.Any,
    fmt: str,
    out: Path | None,
    settings: ExportSettings,
    model: SloshModel,
) -> typing.Any:
    """Export the chosen move beside ``--out`` (or as ``plan<suffix>``), with its limits."""
    from sloshkit.export.plans import LinePlan

    samples = result.samples()
    base = out if out is not None else Path("plan.csv")
    target = _export_target(out, fmt)
    assert target is not None
    line = LinePlan(
        samples["t_s"],
        samples["position_m"],
        samples["velocity_m_s"],
        samples["acceleration_m_s2"],
        source=base.name,
    )
    return run_export(line, fmt, target, settings, model, problem.slosh, None)


def _export_target(out: Path | None, fmt: str | None) -> Path | None:
    """Where ``plan --export FMT`` writes: beside ``--out`` (or ``plan.csv``), with the
    format's suffix; None without ``--export``."""
    if fmt is None:
        return None
    from sloshkit.export.exporter import path_beside

    return path_beside(out if out is not None else Path("plan.csv"), fmt)
