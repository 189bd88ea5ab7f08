"""The report writer: sections, figures (PNG + SVG) and tables (CSV + JSON) staged in a folder,
rendered to HTML with the jinja2 templates in ``report/templates/``."""

from __future__ import annotations

import base64
import contextlib
import functools
import html
import io
import json
import math
import os
import platform
import warnings
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

import jinja2
import markupsafe

from sloshkit.errors import ValidityWarning
from sloshkit.files import write_json, write_rows_csv

#: The templates and the style sheet of the report.
TEMPLATES = Path(__file__).parent / "templates"


@functools.lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
    )


def render(template: str, **values: Any) -> str:
    """Render ``templates/<template>`` (HTML-escaped unless a value is `markupsafe.Markup`)."""
    return _environment().get_template(template).render(**values)


@dataclass
class ReportWriter:
    """Collects sections, figures (PNG + SVG) and tables (CSV + JSON) in a staging folder."""

    staging: Path
    sections: list[str] = field(default_factory=list)
    figure_names: list[str] = field(default_factory=list)
    table_names: list[str] = field(default_factory=list)
    #: (anchor, title) of each section, for the table of contents.
    contents: list[tuple[str, str]] = field(default_factory=list)
    #: Headline figures the sections found, for the summary at the top.
    facts: dict[str, Any] = field(default_factory=dict)
    #: (section title, message) of every validity warning shown in the report.
    warnings: list[tuple[str, str]] = field(default_factory=list)

    def section(self, title: str, body: str) -> None:
        anchor = title.lower().replace(" ", "-")
        self.contents.append((anchor, title))
        self.sections.append(
            render("section.html.j2", anchor=anchor, title=title, body=markupsafe.Markup(body))
        )

    def warning_note(self, section: str, messages: Sequence[str], about: str = "") -> str:
        """HTML of the validity warnings about the numbers just above (empty when none)."""
        unique = list(dict.fromkeys(messages))
        if not unique:
            return ""
        self.warnings.extend((section, message) for message in unique)
        items = "".join(f"<li>{html.escape(message)}</li>" for message in unique)
        lead = f"Validity warning{'s' if len(unique) > 1 else ''}" + (
            f" ({html.escape(about)})" if about else ""
        )
        return f'<div class="warning" role="note"><b>{lead}:</b><ul>{items}</ul></div>'

    def table(
        self,
        name: str,
        rows: Sequence[dict[str, Any]],
        caption: str,
        formats: dict[str, str] | None = None,
    ) -> str:
        """Write tables/NAME.csv and .json; return the HTML table."""

        write_rows_csv(self.staging / "tables" / f"{name}.csv", list(rows))
        write_json(self.staging / "tables" / f"{name}.json", list(rows))
        self.table_names.append(name)
        columns = list(rows[0])
        formats = formats or {}
        cells = [
            [markupsafe.Markup(_cell(row[c], formats.get(c))) for c in columns] for row in rows
        ]
        return render("table.html.j2", name=name, caption=caption, columns=columns, rows=cells)

    def figure(self, name: str, figure: Any, caption: str) -> str:
        """Write figures/NAME.png and .svg; return the HTML figure with the PNG embedded."""
        folder = self.staging / "figures"
        folder.mkdir(parents=True, exist_ok=True)
        buffer = io.BytesIO()
        figure.savefig(buffer, format="png", dpi=110, bbox_inches="tight")
        (folder / f"{name}.png").write_bytes(buffer.getvalue())
        figure.savefig(folder / f"{name}.svg", format="svg", bbox_inches="tight")
        axes = axis_labels(figure)
        write_json(folder / f"{name}.axes.json", axes)
        self.figure_names.append(name)
        data = base64.b64encode(buffer.getvalue()).decode("ascii")
        return render(
            "figure.html.j2", name=name, caption=caption, data=data, axes=json.dumps(axes)
        )

    def finish(self, out_dir: Path, title: str, intro: str, summary: str = "") -> Path:
        """Write report.html (summary and table of contents first) and move everything into
        ``out_dir`` (report.html last)."""
        page = render(
            "page.html.j2",
            title=title,
            css=markupsafe.Markup((TEMPLATES / "report.css").read_text(encoding="utf-8")),
            intro=markupsafe.Markup(intro),
            summary=markupsafe.Markup(summary),
            contents=self.contents,
            sections=[markupsafe.Markup(section) for section in self.sections],
        )
        write_json(
            self.staging / "warnings.json",
            [{"section": section, "message": message} for section, message in self.warnings],
        )
        (self.staging / "report.html").write_text(page, encoding="utf-8")
        out_dir.mkdir(parents=True, exist_ok=True)
        for path in sorted(self.staging.rglob("*")):
            if path.is_file() and path.name != "report.html":
                target = out_dir / path.relative_to(self.staging)
                target.parent.mkdir(parents=True, exist_ok=True)
                os.replace(path, target)
        os.replace(self.staging / "report.html", out_dir / "report.html")
        return out_dir / "report.html"


@contextlib.contextmanager
def recorded_warnings() -> Iterator[list[str]]:
    """Collect the `ValidityWarning` messages raised inside the block (each once, in order)
    for the report, instead of printing or dropping them."""
    messages: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ValidityWarning)
        try:
            yield messages
        finally:
            for item in caught:
                if issubclass(item.category, ValidityWarning):
                    text = str(item.message)
                    if text not in messages:
                        messages.append(text)


def axis_labels(figure: Any) -> list[dict[str, str]]:
    """The x and y labels of every visible panel of a matplotlib figure (colour bars included),
    a panel without its own label taking the label of the panels it shares that axis with.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure.

    Returns
    -------
    list of dict
        One ``{"title", "xlabel", "ylabel"}`` per panel that shows tick labels on that axis
        (a colour bar has only the axis carrying its scale).

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> figure = Figure()
    >>> axis = figure.subplots()
    >>> _ = axis.set_xlabel("time [s]"), axis.set_ylabel("angle [°]")
    >>> axis_labels(figure)
    [{'title': '', 'xlabel': 'time [s]', 'ylabel': 'angle [°]'}]
    """
    found = []
    for axis in figure.axes:
        if not axis.get_visible():
            continue
        entry = {"title": axis.get_title()}
        for name, ticks, shared in (
            ("xlabel", axis.xaxis, axis.get_shared_x_axes()),
            ("ylabel", axis.yaxis, axis.get_shared_y_axes()),
        ):
            shown = [tick for tick in ticks.get_ticklabels() if tick.get_visible()]
            if not ticks.get_visible() or not any(tick.get_text() for tick in shown):
                continue
            labels = [ticks.get_label_text()] + [
                (other.xaxis if name == "xlabel" else other.yaxis).get_label_text()
                for other in shared.get_siblings(axis)
            ]
            entry[name] = next((text for text in labels if text), "")
        found.append(entry)
    return found


def _cell(value: Any, fmt: str | None) -> str:
    if value is None:
        return "–"
    if isinstance(value, float):
        if not math.isfinite(value):
            return "∞"
        return format(value, fmt or ".4g")
    return html.escape(str(value))


def versions() -> dict[str, str]:
    """Versions of sloshkit and of the packages behind the numbers."""
    found = {"python": platform.python_version(), "platform": platform.platform()}
    for package in (
        "sloshkit",
        "numpy",
        "scipy",
        "numba",
        "ruckig",
        "casadi",
        "matplotlib",
        "pint",
    ):
        try:
            found[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            found[package] = "not installed"
    return found
