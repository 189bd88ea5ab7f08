"""``sloshkit reproduce`` and ``sloshkit run``: the reproduction report from a scenario."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from sloshkit.cfd.case import FreeDecay
from sloshkit.cfd.pipeline import analyse, case_spec
from sloshkit.cli import signals
from sloshkit.cli.app import app, stderr, stdout
from sloshkit.cli.cfd import run_with_progress
from sloshkit.cli.options import Json, print_json
from sloshkit.errors import InputError
from sloshkit.io.outputs import check_folder, mark_folder
from sloshkit.io.scenario import read_scenario
from sloshkit.model.modal import SloshModel
from sloshkit.report.build import build_report
from sloshkit.report.paper import paper_scenario


def _run_report(
    scenario: Any, out: Path, cfd_calibration: Any = None, json_output: bool = False
) -> None:
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    with (
        Progress(
            SpinnerColumn(),
            TextColumn("{task.description}"),
            TimeElapsedColumn(),
            console=stderr,
            transient=True,
        ) as bar,
        signals.deferred(),
    ):
        task = bar.add_task("starting", total=None)

        def progress(text: str) -> None:
            bar.update(task, description=text)
            signals.check()  # between sections: compiled kernels never see the signal

        path = build_report(
            scenario,
            out,
            progress=progress,
            cfd_calibration=cfd_calibration,
            command="sloshkit " + " ".join(sys.argv[1:]),
            before_keeping=signals.check,
        )
    mark_folder(out)
    noted = json.loads((out / "warnings.json").read_text(encoding="utf-8"))
    report_warnings = [f"{item['section']}: {item['message']}" for item in noted]
    if json_output:
        print_json(
            {
                "report": str(path),
                "figures": sorted(str(p) for p in (out / "figures").glob("*")),
                "tables": sorted(str(p) for p in (out / "tables").glob("*")),
                "warnings": report_warnings,
            }
        )
    else:
        if report_warnings:
            stderr.print(
                f"{len(report_warnings)} validity warning(s) in the report, next to the numbers "
                "they qualify (listed in its summary)",
                highlight=False,
            )
        stdout.print(f"report: {path.resolve()}")


@app.command("reproduce")
def reproduce_command(
    out: Annotated[
        Path, typer.Option("--out", help="Folder for report.html, figures/, tables/.")
    ] = Path("sloshkit-report"),
    cfd: Annotated[
        bool,
        typer.Option(
            "--cfd",
            help="Also run the OpenFOAM free-decay calibration "
            "(case in OUT/../sloshkit-cfd-free-decay).",
        ),
    ] = False,
    cfd_case: Annotated[
        Path | None,
        typer.Option("--cfd-case", help="Reuse a finished OpenFOAM case for the calibration."),
    ] = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace the files of a non-empty --out folder.")
    ] = False,
    json_output: Json = False,
) -> None:
    """Rebuild the seed paper end to end on the analytic model and write a report.

    Model (Table 3), calibration (Table 4, Fig. 5b), motion laws (Figs. 7-9), slosh maps and the
    planner's fastest safe move, with every difference from the paper explained.

    Example:

      sloshkit reproduce --out report/
    """

    check_folder(out, "out", overwrite)
    scenario = paper_scenario()
    calibration = None
    if cfd or cfd_case is not None:
        calibration = _cfd_free_decay(
            scenario.model,
            cfd_case or out.parent / "sloshkit-cfd-free-decay",
            may_run=cfd_case is None,
        )
    _run_report(scenario, out, calibration, json_output)


def _cfd_free_decay(slosh_model: SloshModel, case: Path, may_run: bool = True) -> Any:
    """Calibration from a free-decay CFD case: reused when it has results, else (``may_run``)
    run with the recommended settings on 2 MPI ranks (about a minute), with a progress bar.
    A case named with --cfd-case is only reused: it must hold a finished sloshkit case."""
    from sloshkit.cfd.requests import require_cylinder

    require_cylinder(slosh_model)
    if not may_run and not (case / "sloshkit-case.json").is_file():
        raise InputError(
            "cfd-case",
            str(case),
            "must be a finished sloshkit CFD case",
            f"run one with: sloshkit cfd run --case {case} --np 2; or use --cfd",
        )
    if not (case / "postProcessing").is_dir():
        stderr.print(f"running the OpenFOAM free decay in {case} (a few minutes)")
        run_with_progress(case_spec(slosh_model, FreeDecay(), processes=2), case, False, True)
    return analyse(case).calibration


@app.command("run")
def run_command(
    scenario_file: Annotated[Path, typer.Argument(help="Scenario TOML (see examples/).")],
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", help="Report folder (default: the file's name, in the working folder)."
        ),
    ] = None,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace the files of a non-empty --out folder.")
    ] = False,
    json_output: Json = False,
) -> None:
    """Run a scenario file's analyses (model, calibrate, compare, sweep, plan) into a report.

    Example:

      sloshkit run examples/vial-2ml.toml --out vial-2ml-report/
    """

    target = out or Path(scenario_file.stem + "-report")
    check_folder(target, "out", overwrite)
    scenario = read_scenario(scenario_file)
    calibration = None
    if "cfd" in scenario.analyses:
        case = scenario.cfd.get("case")
        calibration = _cfd_free_decay(
            scenario.model,
            scenario_file.parent / str(case or scenario_file.stem + "-cfd-free-decay"),
        )
    _run_report(scenario, target, calibration, json_output)
