"""The report's markup lives in jinja2 templates with autoescaping: user text is never markup."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import sloshkit.report
from sloshkit.report.writer import ReportWriter, render

HOSTILE = '<script>alert("x")</script> & <b>bold</b>'


def test_user_text_is_escaped_everywhere(tmp_path):
    writer = ReportWriter(tmp_path)
    table = writer.table("t", [{"liquid": HOSTILE, "rho": 997.0}], caption=HOSTILE)
    note = writer.warning_note("Section", [HOSTILE], about=HOSTILE)
    writer.section(HOSTILE, table + note)
    page = writer.finish(
        tmp_path / "out", HOSTILE, render("intro.html.j2", description=HOSTILE)
    ).read_text(encoding="utf-8")
    assert "<script>" not in page and "<b>bold</b>" not in page
    assert page.count("&lt;script&gt;") >= 5  # title, intro, caption, cell, warning, heading


def test_no_markup_is_built_in_python():
    # HTML tags may appear in docstrings and comments, not in the code's strings.
    folder = Path(sloshkit.report.__file__).parent
    tag = re.compile(r"</?(p|b|li|ul|div|section|table|tr|td|code|pre|a|span|h\d)[ >]")
    offenders = []
    for path in folder.glob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        docstrings = {
            id(node.body[0].value)
            for node in ast.walk(tree)
            if isinstance(node, ast.Module | ast.FunctionDef | ast.ClassDef)
            and node.body
            and isinstance(node.body[0], ast.Expr)
            and isinstance(node.body[0].value, ast.Constant)
        }
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Constant)
                and isinstance(node.value, str)
                and id(node) not in docstrings
                and tag.search(node.value)
            ):
                offenders.append(f"{path.name}:{node.lineno}")
    assert offenders == []
