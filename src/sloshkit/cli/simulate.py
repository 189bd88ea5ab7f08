"""``sloshkit simulate`` and ``sloshkit compare``: one move, or several laws side by side."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cli import display, signals
from sloshkit.cli.app import app, stdout
from sloshkit.cli.moves import (
    SIMULATION_OPTIONS,
    metrics_json,
    with_move_options,
    with_simulation_options,
)
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.cli.simulate_poses import (
    HeightMappingOpt,
    PoseFile,
    ToolOffset,
    report_poses,
    simulate_poses,
)
from sloshkit.errors import InputError
from sloshkit.files import write_json, write_rows_csv
from sloshkit.io.command_requests import MoveRequest, simulate_with_options
from sloshkit.io.outputs import all_or_nothing, check_file, check_folder, staged_folder
from sloshkit.model.modal import SloshModel
from sloshkit.motion.laws import LAW_NAMES
from sloshkit.plotting import plot_law_comparison, plot_slosh_comparison


@app.command("simulate")
@with_model_options
@with_move_options()
@with_simulation_options
def simulate_command(
    slosh_model: SloshModel,
    request: MoveRequest,
    simulation: dict[str, Any],
    law: Annotated[
        str, typer.Option("--law", help="Law: " + ", ".join(LAW_NAMES) + ", file:PATH.")
    ] = "quintic",
    csv: Annotated[Path | None, typer.Option("--csv", help="Write the time series as CSV.")] = None,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="Write a figure (PNG/SVG/PDF).")
    ] = None,
    json_output: Json = False,
    pose_file: PoseFile = None,
    tool_offset: ToolOffset = None,
    height_mapping: HeightMappingOpt = "modal",
) -> None:
    """Slosh response of the container to one motion law, or to a 3-D pose trajectory.

    Examples:

      sloshkit simulate --law quintic --distance 0.5m --duration 1.5s --json

      sloshkit simulate --law s-curve --distance 0.5m --vmax 1m/s --amax 5m/s^2 --jmax 50m/s^3

      sloshkit simulate --law file:move.csv --model nonlinear --plot slosh.png

      sloshkit simulate --pose-file move.csv --radius 49mm --fill-height 80mm --json
    """
    check_file(csv, "csv")
    check_file(plot, "plot", "figure")
    if pose_file is not None:
        if law != "quintic":
            raise InputError(
                "law", law, "cannot be combined with --pose-file (the file is the move)"
            )
        response_3d, messages = simulate_poses(
            slosh_model,
            pose_file,
            simulation,
            tool_offset=tool_offset,
            height_mapping=height_mapping,
            sample_period_explicit=simulation["sample_period"]
            != SIMULATION_OPTIONS["sample_period"][1],
        )
        # a failing figure leaves no CSV behind, nor does a signal a library swallowed
        with all_or_nothing(csv, plot, before_keeping=signals.check):
            report_poses(response_3d, messages, csv=csv, plot=plot, json_output=json_output)
        return
    if tool_offset is not None:
        raise InputError("tool_offset", tool_offset, "needs --pose-file")
    motion = request.law(law)
    response = simulate_with_options(motion, slosh_model, **simulation)
    model_kind = simulation["model_kind"]
    # a failing figure leaves no CSV behind, nor does a signal a library swallowed
    with all_or_nothing(csv, plot, before_keeping=signals.check):
        if csv is not None:
            response.to_csv(csv)
        if plot is not None:
            response.plot(plot)
    if json_output:
        print_json({"law": motion.name, "model": model_kind, **metrics_json(response)})
        return
    table = Table(
        title=f"{motion.name} move of {1e3 * motion.distance_m:.1f} mm, {model_kind} model"
    )
    table.add_column("quantity")
    table.add_column("value", justify="right")
    for key, number in response.metrics().items():
        table.add_row(Text(display.label(key)), display.value(key, number))
    stdout.print(table)


COMPARE_LAWS = "trapezoidal,cubic,quintic,septic,s-curve"


@app.command("compare")
@with_model_options
@with_move_options("0.5m/s")
@with_simulation_options
def compare_command(
    slosh_model: SloshModel,
    request: MoveRequest,
    simulation: dict[str, Any],
    laws: Annotated[str, typer.Option("--laws", help="Comma-separated law names.")] = COMPARE_LAWS,
    out: Annotated[
        Path | None, typer.Option("--out", help="Folder for compare.csv, compare.json, figures.")
    ] = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace the files of a non-empty --out folder.")
    ] = False,
    json_output: Json = False,
) -> None:
    """All laws on the same move, side by side (the seed paper's Figs. 7-9).

    Polynomial laws take the trapezoid's duration (same peak velocity for the trapezoid); the
    s-curve takes the trapezoid's peak velocity and acceleration and a 0.1 s jerk time unless
    --vmax/--amax/--jmax are given.

    Example:

      sloshkit compare --distance 0.5m --peak-velocity 0.5m/s --out compare/
    """
    check_folder(out, "out", overwrite)
    names = [name.strip() for name in laws.split(",") if name.strip()]
    if not names:
        raise InputError("laws", laws, "give at least one law name")
    motions = [request.law(name) for name in names]
    responses = [simulate_with_options(motion, slosh_model, **simulation) for motion in motions]
    model_kind = simulation["model_kind"]
    rows = [
        {"law": motion.name, **metrics_json(response)}
        for motion, response in zip(motions, responses, strict=True)
    ]
    payload = {"distance_m": request.distance_m, "model": model_kind, "laws": rows}
    if out is not None:
        with staged_folder(out, signals.check) as staging:
            write_rows_csv(staging / "compare.csv", rows)
            write_json(staging / "compare.json", payload)
            plot_law_comparison(motions, staging / "fig7_laws.png")
            plot_slosh_comparison(responses, staging / "fig8_slosh.png")
    if json_output:
        print_json(payload)
        return
    table = Table(
        title=f"Motion laws compared: {1e3 * request.distance_m:.0f} mm move, {model_kind} model"
    )
    table.add_column("quantity")
    for motion in motions:
        table.add_column(Text(motion.name), justify="right")
    for key in responses[0].metrics() if responses else ():
        table.add_row(
            Text(display.label(key)),
            *(display.value(key, response.metrics()[key]) for response in responses),
        )
    stdout.print(table)
    if out is not None:
        stdout.print(f"wrote {out}/compare.csv, compare.json, fig7_laws.png, fig8_slosh.png")
