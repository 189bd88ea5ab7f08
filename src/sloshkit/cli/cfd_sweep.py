"""``sloshkit cfd sweep``: CFD campaigns on Dask (`sloshkit.cfd.campaign`)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cfd.prepare import check_case_path
from sloshkit.cfd.requests import require_cylinder
from sloshkit.cli.app import stderr, stdout
from sloshkit.cli.cfd import cfd_app
from sloshkit.cli.cfd_options import cfd_options, spec_from_options
from sloshkit.cli.options import Json, print_json, with_cylinder_model_options, with_options
from sloshkit.errors import InputError
from sloshkit.io.outputs import check_folder
from sloshkit.io.units import parse_count, parse_quantity
from sloshkit.model.modal import SloshModel

#: Most cases of one campaign (each is a CFD run of minutes to hours).
MAX_CASES = 500


def check_scheduler(address: str, timeout_s: float = 5.0) -> str:
    """Check a Dask scheduler before any case is written: the address, then a Dask handshake
    within ``timeout_s`` (`sloshkit.cfd.scheduler.check_scheduler`; credentials never printed).

    Parameters
    ----------
    address : str
        The ``--scheduler`` option as typed.
    timeout_s : float
        How long to wait for the connection and the scheduler's answer [s].

    Returns
    -------
    str
        The address, unchanged.

    Examples
    --------
    >>> from sloshkit.errors import InputError
    >>> try:
    ...     check_scheduler("tcp://scheduler:8786 x")
    ... except InputError as error:
    ...     print(error.valid)
    must be [tcp://|tls://]HOST:PORT, e.g. tcp://10.0.0.5:8786
    """
    from sloshkit.cfd.scheduler import check_scheduler as handshake

    return handshake(address, timeout_s)


def _split(text: str) -> list[str]:
    return [item.strip() for item in text.split(",") if item.strip()]


@cfd_app.command("sweep")
@with_cylinder_model_options
@with_options(cfd_options("free-decay", "3s"), "case_options", dict)
def cfd_sweep_command(
    slosh_model: SloshModel,
    case_options: dict[str, Any],
    out: Annotated[
        Path, typer.Option("--out", help="Campaign folder (one case folder per case).")
    ] = Path("sloshkit-cfd-campaign"),
    fills: Annotated[
        str | None,
        typer.Option("--fills", help="Fill heights, comma-separated (default: --fill-height)."),
    ] = None,
    liquids: Annotated[
        str | None,
        typer.Option("--liquids", help="Liquid presets, comma-separated (default: --liquid)."),
    ] = None,
    meshes: Annotated[
        str | None,
        typer.Option(
            "--meshes", help="Cells per radius, comma-separated (default: --cells-per-radius)."
        ),
    ] = None,
    workers: Annotated[
        int, typer.Option("--workers", help="Cases run at once on the local Dask cluster.")
    ] = 1,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            help="Address of an existing Dask scheduler (e.g. from dask-jobqueue) instead of "
            "the local cluster.",
        ),
    ] = None,
    json_output: Json = False,
) -> None:
    """Run a CFD campaign (fills x liquids x meshes) on Dask; gather one table (results.csv,
    results.json) and a calibration-versus-fill model. Started again, it skips finished cases
    and resumes half-run ones.

    Example:

      sloshkit cfd sweep --out campaign --fills 30mm,39mm,45mm --meshes 8 --end-time 2s

    \f
    Parameters
    ----------
    slosh_model : SloshModel
        The container, fill and liquid (the model options).
    case_options : dict
        The values of `sloshkit.cli.cfd_options.cfd_options`.
    out : Path
        Campaign folder.
    fills, liquids, meshes : str, optional
        Comma-separated fill heights, liquid presets, cells per radius.
    workers : int
        Cases run at once.
    scheduler : str, optional
        Address of an existing Dask scheduler.
    json_output : bool
        Print JSON.

    Returns
    -------
    None

    Examples
    --------
    >>> from sloshkit.cli.app import run
    >>> run(["cfd", "sweep", "--workers", "0"])  # one line on stderr
    2
    """
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    from sloshkit.cfd.campaign import CampaignCase, run_campaign
    from sloshkit.errors import require_in_range
    from sloshkit.model.liquids import get_liquid
    from sloshkit.model.modal import equivalent_model

    require_cylinder(slosh_model)
    check_case_path(out, "out")  # every case is a folder in it: OpenFOAM's characters only
    check_folder(out, "out", overwrite=True)  # a campaign folder is resumed, so may hold cases
    if scheduler is not None:
        check_scheduler(scheduler)
    require_in_range("workers", workers, 1, 64)
    fill_list = [parse_quantity(text, "length", "fills") for text in _split(fills or "")] or [
        slosh_model.fill_height_m
    ]
    liquid_list = [get_liquid(name) for name in _split(liquids or "")] or [slosh_model.liquid]
    mesh_list = [parse_count(text, "meshes", 3, 60) for text in _split(meshes or "")] or [
        case_options["cells_per_radius"]
    ]
    count = len(fill_list) * len(liquid_list) * len(mesh_list)
    if count > MAX_CASES:
        raise InputError(
            "cases",
            f"{len(fill_list)} fills x {len(liquid_list)} liquids x {len(mesh_list)} meshes",
            f"{count} CFD runs; at most {MAX_CASES} in one campaign (split it)",
        )
    cases = []
    for liquid in liquid_list:
        for fill in fill_list:
            model = equivalent_model(slosh_model.container, liquid, fill)
            for cells in mesh_list:
                spec = spec_from_options(model, {**case_options, "cells_per_radius": cells})
                name = f"{liquid.name}-h{fill * 1e3:g}mm-n{cells}"
                cases.append(CampaignCase(name, spec, model.modes[0].frequency_hz))
    with Progress(
        TextColumn("campaign"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total} cases"),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=stderr,
        transient=True,
    ) as bar:
        task = bar.add_task("campaign", total=len(cases))

        def advance(done: int, total: int, eta: float | None) -> None:
            bar.update(task, completed=done, total=total)

        result = run_campaign(
            cases,
            out,
            workers=workers,
            processes=1 if case_options["np_"] is None else case_options["np_"],
            scheduler=scheduler,
            progress=advance,
        )
    if json_output:
        print_json(result)
        return
    table = Table(title=f"CFD campaign: {out} ({result['skipped']} reused)")
    for header_text in ("case", "status", "f [Hz]", "f / theory", "ζ [-]"):
        table.add_column(Text(header_text), justify="right")
    for row in result["rows"]:
        table.add_row(
            Text(row["case"]),
            Text(row["status"]),
            *(
                "-" if row[k] is None else f"{row[k]:.4g}"
                for k in ("frequency_hz", "frequency_ratio", "damping_ratio")
            ),
        )
    stdout.print(table)
    stdout.print(Text(f"table: {result['csv']}; model: {result['json']}"))
    failed = [row for row in result["rows"] if row["status"] != "completed"]
    if failed:
        for row in failed:
            stderr.print(Text(f"failed: {row['case']}: {row['error']}"), highlight=False)
        raise typer.Exit(1)
