"""Reports: run a scenario's analyses and write a self-contained HTML report, with every
figure as PNG and SVG and every table as CSV and JSON.

Output is staged in a temporary folder beside the target and moved in only when everything has
been produced, ``report.html`` last, so a failure never leaves a half-written report.
"""

from __future__ import annotations

import datetime as dt
import json
import shutil
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import markupsafe

from sloshkit.io.scenario import Scenario
from sloshkit.report.model_sections import write_model_sections
from sloshkit.report.motion_sections import law_label, write_motion_sections
from sloshkit.report.writer import ReportWriter, render, versions

Progress = Callable[[str], None]


def summary_html(writer: ReportWriter, scenario: Scenario) -> markupsafe.Markup:
    """The summary at the top of the report: the headline move, the key model figures, the
    paper's conclusion in numbers and how many validity warnings the sections carry.

    Parameters
    ----------
    writer : ReportWriter
        The writer after every section (its ``facts`` and ``warnings``).
    scenario : Scenario
        The scenario.

    Returns
    -------
    markupsafe.Markup
        The summary section's HTML.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit.report.paper import paper_scenario
    >>> writer = ReportWriter(pathlib.Path(tempfile.mkdtemp()))
    >>> writer.warnings.append(("Slosh maps", "<large angles>"))
    >>> html = summary_html(writer, paper_scenario())
    >>> '1 validity warning</span>' in html, '<a href="#slosh-maps">Slosh maps</a>' in html
    (True, True)
    """
    plan = writer.facts.get("plan")
    best = plan.get("best_paper_law") if plan else None
    return render(
        "summary.html.j2",
        plan=plan,
        best={"label": law_label(best[0]), "duration_s": best[1]} if best else None,
        plan_requested="plan" in scenario.analyses,
        distance_m=scenario.distance_m,
        model=writer.facts.get("model"),
        ratio=writer.facts.get("residual_ratio_trapezoid_septic"),
        warning_count=len(writer.warnings),
        warning_sections=list(dict.fromkeys(section for section, _ in writer.warnings)),
    )


def build_report(
    scenario: Scenario,
    out_dir: str | Path,
    progress: Progress | None = None,
    cfd_calibration: Any | None = None,
    command: str = "",
    before_keeping: Callable[[], None] | None = None,
) -> Path:
    """Run the scenario's analyses and write ``out_dir/report.html`` with figures and tables.

    Parameters
    ----------
    scenario : Scenario
        What to analyse (`sloshkit.io.scenario`).
    out_dir : str or pathlib.Path
        The report's folder (report.html, figures/, tables/).
    progress : callable, optional
        Called with the name of each step as it starts.
    cfd_calibration : CalibrationResult, optional
        A calibration from a CFD run, used instead of the scenario's data.
    command : str
        The command line recorded in the report (default: ``sys.argv``).
    before_keeping : callable, optional
        Called when the report is complete in its staging folder, before anything moves into
        ``out_dir``; an exception it raises (the CLI's `sloshkit.cli.signals.check`: an
        interruption recorded while the page was written) leaves ``out_dir`` untouched.

    Returns
    -------
    pathlib.Path
        The report.html written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit.io.scenario import parse_scenario
    >>> scenario = parse_scenario({"name": "vial", "analyses": ["model"],
    ...                            "container": {"radius": "20.5mm"}, "fill": {"height": "39mm"},
    ...                            "move": {"distance": "0.2m", "duration": "1s"}})
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "report"
    >>> report = build_report(scenario, out, command="example")
    >>> sorted(path.name for path in (out / "tables").iterdir())[:2]
    ['model.csv', 'model.json']
    >>> '<section id="equivalent-model">' in report.read_text(encoding="utf-8")
    True
    """
    say = progress or (lambda _: None)
    target = Path(out_dir)
    target.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.staging-", dir=target.parent))
    try:
        writer = ReportWriter(staging)
        # One model for the whole report: a calibration's damping and omega_1 reach the model
        # table and the summary as well as the laws, maps and plan.
        model = write_model_sections(writer, scenario, cfd_calibration, say)
        write_motion_sections(writer, scenario, model, say)
        meta = {
            "date_utc": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
            "command": command or " ".join(sys.argv),
            "scenario": scenario.source or "built in",
            **versions(),
        }
        inputs = json.dumps(scenario.raw, indent=2, default=str)
        writer.section(
            "Inputs and versions",
            render(
                "sections/inputs.html.j2",
                table=writer.table(
                    "versions",
                    [{"item": k, "value": v} for k, v in meta.items()],
                    "Reproducibility",
                ),
                inputs=inputs,
            ),
        )
        intro = render("intro.html.j2", description=scenario.description)
        say("writing the report")
        return writer.finish(
            target, scenario.name, intro, summary_html(writer, scenario), before_keeping
        )
    finally:
        shutil.rmtree(staging, ignore_errors=True)
