"""The report writer: sections, figures (PNG + SVG) and tables (CSV + JSON) staged in a folder,
rendered to HTML with the jinja2 templates in ``report/templates/``."""

from __future__ import annotations

import base64
import functools
import html
import io
import math
import os
import platform
from collections.abc import Sequence
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

import jinja2
import markupsafe

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

    def section(self, title: str, body: str) -> None:
        anchor = title.lower().replace(" ", "-")
        self.sections.append(
            render("section.html.j2", anchor=anchor, title=title, body=markupsafe.Markup(body))
        )

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
        self.figure_names.append(name)
        data = base64.b64encode(buffer.getvalue()).decode("ascii")
        return render("figure.html.j2", caption=caption, data=data)

    def finish(self, out_dir: Path, title: str, intro: str) -> Path:
        """Write report.html and move everything into ``out_dir`` (report.html last)."""
        page = render(
            "page.html.j2",
            title=title,
            css=markupsafe.Markup((TEMPLATES / "report.css").read_text(encoding="utf-8")),
            intro=markupsafe.Markup(intro),
            sections=[markupsafe.Markup(section) for section in self.sections],
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
