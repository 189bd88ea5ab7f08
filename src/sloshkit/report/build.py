"""Reports: run a scenario's analyses and write a self-contained HTML report, with every
figure as PNG and SVG and every table as CSV and JSON.

Output is staged in a temporary folder beside the target and moved in only when everything has
been produced, ``report.html`` last, so a failure never leaves a half-written report.
"""

from __future__ import annotations

import datetime as dt
import html
import json
import shutil
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from sloshkit.io.scenario import Scenario
from sloshkit.report.model_sections import _calibration_section, _model_section
from sloshkit.report.motion_sections import (
    _compare_section,
    _plan_section,
    _sweep_section,
    law_label,
)
from sloshkit.report.writer import ReportWriter, versions

Progress = Callable[[str], None]


def summary_html(writer: ReportWriter, scenario: Scenario) -> str:
    """The summary at the top of the report: the headline move, the key model figures, the
    paper's conclusion in numbers and how many validity warnings the sections carry."""
    items = []
    plan = writer.facts.get("plan")
    if plan:
        best = plan.get("best_paper_law")
        line = (
            f"<b>Fastest verified move: {html.escape(plan['method'])}, "
            f"{plan['duration_s']:.3f} s</b> for the {1e3 * scenario.distance_m:.0f} mm move"
        )
        if plan.get("speed_up") and best:
            line += (
                f" — <b>{plan['speed_up']:.2f}× faster</b> than the best of the paper's laws "
                f"({html.escape(law_label(best[0]))}, {best[1]:.3f} s) under the same limits"
            )
        items.append(line + ' (<a href="#fastest-safe-move">details</a>).')
    elif "plan" in scenario.analyses:
        items.append('<b>No move meets the limits</b> (<a href="#fastest-safe-move">details</a>).')
    model = writer.facts.get("model")
    if model:
        items.append(
            f"First sloshing mode: f₁ = {model['frequency_hz']:.3f} Hz "
            f"(ω₁ = {model['omega_rad_s']:.2f} rad/s), slosh mass {model['slosh_mass_g']:.2f} g, "
            f"pendulum length {model['length_mm']:.2f} mm, damping ratio ζ = "
            f"{model['damping_ratio']:.3g} ({html.escape(model['liquid'])}; "
            '<a href="#equivalent-model">model</a>).'
        )
    ratio = writer.facts.get("residual_ratio_trapezoid_septic")
    if ratio:
        items.append(
            f"At equal duration the trapezoid leaves {ratio:.1f}× the residual slosh of the septic "
            "law (the paper's jerk-continuous law): the paper's conclusion in numbers "
            '(<a href="#motion-laws">motion laws</a>).'
        )
    if writer.warnings:
        sections = list(dict.fromkeys(section for section, _ in writer.warnings))
        links = ", ".join(
            f'<a href="#{section.lower().replace(" ", "-")}">{html.escape(section)}</a>'
            for section in sections
        )
        items.append(
            f'<span class="bad">{len(writer.warnings)} validity warning'
            f"{'s' if len(writer.warnings) > 1 else ''}</span>, shown next to the numbers they "
            f"qualify: {links}."
        )
    else:
        items.append("No validity warnings: every number is inside the model's range.")
    listed = "".join(f"<li>{item}</li>" for item in items)
    return f'<section id="summary"><h2>Summary</h2><ul>{listed}</ul></section>'


def build_report(
    scenario: Scenario,
    out_dir: str | Path,
    progress: Progress | None = None,
    cfd_calibration: Any | None = None,
    command: str = "",
) -> Path:
    """Run the scenario's analyses and write ``out_dir/report.html`` with figures and tables."""
    say = progress or (lambda _: None)
    target = Path(out_dir)
    target.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.staging-", dir=target.parent))
    try:
        writer = ReportWriter(staging)
        model = scenario.model
        if "model" in scenario.analyses:
            say("equivalent model")
            _model_section(writer, scenario)
        if "calibrate" in scenario.analyses or "cfd" in scenario.analyses:
            say("calibration")
            model = _calibration_section(writer, scenario, cfd_calibration)
        if "compare" in scenario.analyses:
            say("motion laws")
            _compare_section(writer, scenario, model)
        if "sweep" in scenario.analyses:
            say("slosh maps")
            _sweep_section(writer, scenario, model)
        if "plan" in scenario.analyses:
            say("planning the fastest safe move")
            _plan_section(writer, scenario, model)
        meta = {
            "date_utc": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
            "command": command or " ".join(sys.argv),
            "scenario": scenario.source or "built in",
            **versions(),
        }
        inputs = json.dumps(scenario.raw, indent=2, default=str)
        writer.section(
            "Inputs and versions",
            writer.table(
                "versions", [{"item": k, "value": v} for k, v in meta.items()], "Reproducibility"
            )
            + "<p>The scenario as read (SI values are converted where the analyses use them):</p>"
            + f"<pre>{html.escape(inputs)}</pre>",
        )
        intro = f"<p>{html.escape(scenario.description)}</p>" if scenario.description else ""
        intro += (
            "<p>Generated by sloshkit. Figures are embedded; PNG and SVG copies are in "
            "<code>figures/</code>, tables as CSV and JSON in <code>tables/</code>.</p>"
        )
        say("writing the report")
        return writer.finish(target, scenario.name, intro, summary_html(writer, scenario))
    finally:
        shutil.rmtree(staging, ignore_errors=True)
