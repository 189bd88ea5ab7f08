"""The report writer: sections, figures (PNG + SVG) and tables (CSV + JSON) staged in a folder,
rendered to HTML with the jinja2 templates in ``report/templates/``."""

from __future__ import annotations

import base64
import contextlib
import functools
import io
import json
import math
import os
import platform
import re
import warnings
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

import jinja2
import jinja2.ext
import markupsafe

from sloshkit.errors import ValidityWarning
from sloshkit.files import write_json, write_rows_csv

#: The templates and the style sheet of the report.
TEMPLATES = Path(__file__).parent / "templates"


def anchor(title: str) -> str:
    """The HTML id of a section: its title in lower case, spaces as hyphens.

    Parameters
    ----------
    title : str
        The section's title.

    Returns
    -------
    str

    Examples
    --------
    >>> anchor("Fastest safe move")
    'fastest-safe-move'
    """
    return title.lower().replace(" ", "-")


class _JoinedLines(jinja2.ext.Extension):
    """Templates are written over several lines for reading; the page is one line of HTML.

    A line break between markup (a line ending in ``>``, ``}}`` or ``%}`` and the next
    starting with ``<`` or ``{``) renders as nothing, any other one (inside text) as one
    space, as HTML reads it.
    """

    def preprocess(self, source: str, name: str | None, filename: str | None = None) -> str:
        source = source.removesuffix("\n")
        source = re.sub(r"(?<=[>}])\n[ \t]*(?=[<{])", "", source)
        return re.sub(r"[ \t]*\n[ \t]*", " ", source)


@functools.lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
        extensions=[_JoinedLines],
    )
    environment.filters["fmt"] = format
    environment.filters["anchor"] = anchor
    return environment


def render(template: str, **values: Any) -> markupsafe.Markup:
    """Render ``templates/<template>``: every value is HTML-escaped (user text is never
    interpreted as markup) unless it is already rendered markup (`markupsafe.Markup`, as
    `render`, `ReportWriter.table` and `ReportWriter.figure` return).

    Templates format numbers with the ``fmt`` filter (``{{ x|fmt(".3f") }}`` is
    ``format(x, ".3f")``) and make section ids with ``anchor``.

    Parameters
    ----------
    template : str
        Path of the template below ``report/templates/``.
    **values
        The template's variables.

    Returns
    -------
    markupsafe.Markup
        The HTML.

    Examples
    --------
    >>> render("warning.html.j2", messages=["<script> & co"], about="")
    Markup('<div class="warning" role="note"><b>Validity warning:</b><ul><li>&lt;script&gt; &amp; co</li></ul></div>')
    """
    return markupsafe.Markup(_environment().get_template(template).render(**values))


@dataclass
class ReportWriter:
    """Collects sections, figures (PNG + SVG) and tables (CSV + JSON) in a staging folder.

    Attributes
    ----------
    staging : pathlib.Path
        The staging folder.
    sections : list of markupsafe.Markup
        The rendered sections, in order.
    figure_names, table_names : list of str
        What was written to figures/ and tables/.
    contents : list of tuple
        (anchor, title) of each section, for the table of contents.
    facts : dict
        Headline figures the sections found, for the summary.
    warnings : list of tuple
        (section title, message) of every validity warning shown.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> writer = ReportWriter(folder / "staging")
    >>> table = writer.table("masses", [{"mode": 1, "mass [g]": 12.3456}], "Slosh masses")
    >>> writer.section("Model", table)
    >>> report = writer.finish(folder / "out", "A report", render("intro.html.j2", description=""))
    >>> sorted(p.name for p in (folder / "out" / "tables").iterdir())
    ['masses.csv', 'masses.json']
    >>> '<td>12.35</td>' in report.read_text(encoding="utf-8")
    True
    """

    staging: Path
    sections: list[markupsafe.Markup] = field(default_factory=list)
    figure_names: list[str] = field(default_factory=list)
    table_names: list[str] = field(default_factory=list)
    #: (anchor, title) of each section, for the table of contents.
    contents: list[tuple[str, str]] = field(default_factory=list)
    #: Headline figures the sections found, for the summary at the top.
    facts: dict[str, Any] = field(default_factory=dict)
    #: (section title, message) of every validity warning shown in the report.
    warnings: list[tuple[str, str]] = field(default_factory=list)

    def section(self, title: str, body: markupsafe.Markup) -> None:
        """Add a section (an ``<h2>`` title and ``body``, rendered markup) to the page."""
        self.contents.append((anchor(title), title))
        self.sections.append(
            render("section.html.j2", anchor=anchor(title), title=title, body=body)
        )

    def warning_note(
        self, section: str, messages: Sequence[str], about: str = ""
    ) -> markupsafe.Markup:
        """HTML of the validity warnings about the numbers just above (empty when none)."""
        unique = list(dict.fromkeys(messages))
        if not unique:
            return markupsafe.Markup("")
        self.warnings.extend((section, message) for message in unique)
        return render("warning.html.j2", messages=unique, about=about)

    def table(
        self,
        name: str,
        rows: Sequence[dict[str, Any]],
        caption: str,
        formats: dict[str, str] | None = None,
    ) -> markupsafe.Markup:
        """Write tables/NAME.csv and .json; return the HTML table."""

        write_rows_csv(self.staging / "tables" / f"{name}.csv", list(rows))
        write_json(self.staging / "tables" / f"{name}.json", list(rows))
        self.table_names.append(name)
        columns = list(rows[0])
        formats = formats or {}
        cells = [[_cell(row[c], formats.get(c)) for c in columns] for row in rows]
        return render("table.html.j2", name=name, caption=caption, columns=columns, rows=cells)

    def figure(self, name: str, figure: Any, caption: str) -> markupsafe.Markup:
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

    def finish(
        self,
        out_dir: Path,
        title: str,
        intro: markupsafe.Markup,
        summary: markupsafe.Markup | None = None,
        before_keeping: Callable[[], None] | None = None,
    ) -> Path:
        """Write report.html (summary and table of contents first) and move everything into
        ``out_dir`` (report.html last); ``before_keeping`` is called before the first move."""
        page = render(
            "page.html.j2",
            title=title,
            css=markupsafe.Markup((TEMPLATES / "report.css").read_text(encoding="utf-8")),
            intro=intro,
            summary=summary or "",
            contents=self.contents,
            sections=self.sections,
        )
        write_json(
            self.staging / "warnings.json",
            [{"section": section, "message": message} for section, message in self.warnings],
        )
        (self.staging / "report.html").write_text(page, encoding="utf-8")
        if before_keeping is not None:
            before_keeping()
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
    for the report, instead of printing or dropping them.

    Yields
    ------
    list of str
        The messages, filled when the block ends.

    Examples
    --------
    >>> from sloshkit.errors import warn_validity
    >>> with recorded_warnings() as found:
    ...     warn_validity("shallow fill")
    ...     warn_validity("shallow fill")
    >>> found
    ['shallow fill']
    """
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
    """The text of a table cell (escaped by the template)."""
    if value is None:
        return "–"
    if isinstance(value, float):
        if not math.isfinite(value):
            return "∞"
        return format(value, fmt or ".4g")
    return str(value)


def versions() -> dict[str, str]:
    """Versions of sloshkit and of the packages behind the numbers.

    Returns
    -------
    dict of str
        Package (and ``python``, ``platform``) -> version.

    Examples
    --------
    >>> found = versions()
    >>> "numpy" in found and found["python"].count(".") == 2
    True
    """
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
