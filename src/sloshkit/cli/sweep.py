"""``sloshkit sweep``: slosh maps over fill height x duration x law."""

from __future__ import annotations

import typing
import warnings
from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cli import signals
from sloshkit.cli.app import app, stderr, stdout
from sloshkit.cli.moves import AccelFraction, Amax, Distance, Jmax, SamplePeriod, Vmax
from sloshkit.cli.options import (
    ContainerName,
    DampingLawOpt,
    DampingRatio,
    Density,
    Json,
    LiquidName,
    Modes,
    ProfileFile,
    Radius,
    Sigma,
    SurfaceTension,
    Viscosity,
    WallHeight,
    print_json,
)
from sloshkit.errors import ValidityWarning
from sloshkit.io.command_requests import MoveRequest, sweep_grid_request
from sloshkit.io.model_options import vessel_request
from sloshkit.io.outputs import check_folder, staged_folder
from sloshkit.io.requests import damping_law_request, liquid_request
from sloshkit.io.units import parse_quantity
from sloshkit.model.modal import model_family
from sloshkit.sweep import describe_rate, run_sweep

MaxAngle = Annotated[
    str | None, typer.Option("--max-angle", help="Limit on the peak slosh angle, e.g. 5deg.")
]


MaxResidual = Annotated[
    str | None,
    typer.Option("--max-residual", help="Limit on the residual slosh amplitude, e.g. 0.25deg."),
]


@app.command("sweep")
def sweep_command(
    distance: Distance = "0.5m",
    fill_height: Annotated[
        str | None, typer.Option("--fill-height", help="Range START:STOP:COUNT, e.g. 10mm:60mm:50.")
    ] = None,
    fill_volume: Annotated[
        str | None,
        typer.Option("--fill-volume", help="Range of volumes instead, e.g. 5mL:50mL:10."),
    ] = None,
    duration: Annotated[
        str | None, typer.Option("--duration", help="Range START:STOP:COUNT, e.g. 0.5s:3s:200.")
    ] = None,
    peak_acceleration: Annotated[
        str | None,
        typer.Option(
            "--peak-acceleration", help="Range of peak accelerations instead of durations."
        ),
    ] = None,
    laws: Annotated[str, typer.Option("--laws", help="Comma-separated law names.")] = (
        "trapezoidal,cubic,quintic,septic"
    ),
    max_angle: MaxAngle = None,
    max_residual: MaxResidual = None,
    vmax: Vmax = None,
    amax: Amax = None,
    jmax: Jmax = None,
    accel_fraction: AccelFraction = None,
    sample_period: SamplePeriod = "1ms",
    radius: Radius = "20.5mm",
    wall_height: WallHeight = None,
    container_name: ContainerName = None,
    profile: ProfileFile = None,
    liquid: LiquidName = "water-25C",
    density: Density = None,
    viscosity: Viscosity = None,
    sigma: Sigma = None,
    modes: Modes = 3,
    damping_law: DampingLawOpt = "seed",
    damping_ratio: DampingRatio = None,
    surface_tension_correction: SurfaceTension = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Folder for sweep.csv and maps.")
    ] = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace the files of a non-empty --out folder.")
    ] = False,
    json_output: Json = False,
) -> None:
    """Slosh maps over fill height x move duration x law (linear fast path).

    A range is START:STOP:COUNT with both ends included. Writes sweep.csv (one row a case),
    peak_angle_map.png and residual_angle_map.png into --out, marking the region that meets
    --max-angle and --max-residual.

    Example:

      sloshkit sweep --distance 0.5m --fill-height 10mm:60mm:50 --duration 0.5s:3s:200
      --laws trapezoidal,cubic,quintic,septic --max-angle 10deg --max-residual 1deg --out maps/
    """
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    check_folder(out, "out", overwrite)
    container = vessel_request(radius, wall_height, container_name, profile)
    grid = sweep_grid_request(
        container,
        fill_height,
        fill_volume,
        duration,
        peak_acceleration,
        real=container_name is not None or profile is not None,
    )
    heights, durations, accelerations = grid
    request = MoveRequest.parse(distance, None, None, vmax, amax, jmax, accel_fraction)
    limits = None
    if request.vmax is not None and request.amax is not None and request.jmax is not None:
        limits = (request.vmax, request.amax, request.jmax)
    names = [name.strip() for name in laws.split(",") if name.strip()]
    with Progress(
        TextColumn("sweep"),
        BarColumn(),
        TextColumn("{task.completed:,}/{task.total:,} cases"),
        TimeRemainingColumn(),
        console=stderr,
        transient=True,
    ) as bar:
        task = bar.add_task("sweep", total=1)

        def advance(done: int, total: int) -> None:
            bar.update(task, completed=done, total=total)
            signals.check()  # between chunks: the numba kernel never sees the signal

        with signals.deferred():
            result = run_sweep(
                model_family(
                    container,
                    liquid_request(
                        liquid, density, viscosity, sigma, surface_tension_parameter="sigma"
                    ),
                    n_modes=modes,
                    damping_law=damping_law_request(damping_law),
                    damping_ratio=damping_ratio,
                    surface_tension=surface_tension_correction,
                ),
                names,
                request.distance_m,
                durations,
                accelerations,
                fill_heights_m=heights,
                s_curve_limits=limits,
                acceleration_fraction=accel_fraction,
                sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
                max_angle_rad=None
                if max_angle is None
                else parse_quantity(max_angle, "angle", "max_angle"),
                max_residual_rad=None
                if max_residual is None
                else parse_quantity(max_residual, "angle", "max_residual"),
                progress=advance,
            )
    no_limits = max_angle is None and max_residual is None
    if no_limits:
        warnings.warn(
            "no limits given (--max-angle, --max-residual): no case is judged safe or unsafe; "
            "'shortest' is simply the shortest duration swept",
            ValidityWarning,
            stacklevel=1,
        )
    summary = result.summary()
    if out is not None:
        with staged_folder(out, signals.check) as staging:
            result.to_csv(staging / "sweep.csv")
            maps = result.plot_maps(staging)
        summary["csv"] = str(out / "sweep.csv")
        summary["maps"] = [str(out / path.name) for path in maps]
    if json_output:
        print_json(summary)
        return
    stderr.print(describe_rate(result))
    table = Table(
        title=f"Shortest move per fill height ({summary['cases']:,} cases; no limits given)"
        if no_limits
        else f"Shortest safe move per fill height ({summary['safe_cases']:,} of "
        f"{summary['cases']:,} cases safe)"
    )
    table.add_column(Text("fill height [mm]"), justify="right")
    table.add_column(Text("ω₁ [rad/s]"), justify="right")
    table.add_column(
        Text("shortest duration [s]" if no_limits else "shortest safe duration [s]"),
        justify="right",
    )
    table.add_column("law")
    for row, omega in zip(result.shortest_safe(), result.omega_1_rad_s, strict=True):
        shortest = row["duration_s"]
        table.add_row(
            f"{1e3 * float(typing.cast(float, row['fill_height_m'])):.1f}",
            f"{omega:.2f}",
            "none" if shortest is None else f"{float(typing.cast(float, shortest)):.3f}",
            str(row["law"] or "-"),
        )
    stdout.print(table)
    if out is not None:
        stdout.print(
            f"wrote {summary['csv']} and {', '.join(typing.cast(list[str], summary['maps']))}"
        )
