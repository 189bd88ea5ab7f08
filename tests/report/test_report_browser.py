"""The reproduction report in a real browser: headless Chromium (Debian's chromium and
chromium-driver, installed by `make test`) loads report.html with no console errors, every
figure renders and every table is present."""

from __future__ import annotations

import html
import itertools
import json
import re
import shutil
from pathlib import Path

import pytest

from sloshkit.report import build_report, paper_scenario

CHROMIUM = shutil.which("chromium")
CHROMEDRIVER = shutil.which("chromedriver")


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    return build_report(paper_scenario(), tmp_path_factory.mktemp("reproduce") / "report")


def test_report_files(report):
    folder = report.parent
    for name in ("fig5b_calibration", "fig7_laws", "fig8_slosh", "plan", "sweep_peak_map"):
        assert (folder / "figures" / f"{name}.png").stat().st_size > 10_000
        assert (folder / "figures" / f"{name}.svg").stat().st_size > 10_000
    for name in ("model", "table3_comparison", "table4_calibration", "compare", "plan", "versions"):
        assert (folder / "tables" / f"{name}.csv").is_file()
        assert (folder / "tables" / f"{name}.json").is_file()
    text = report.read_text()
    assert "http://" not in text and "https://" not in text  # self-contained
    assert not list(folder.parent.glob(".*staging*"))
    assert (folder / "figures" / "fig9_cfd_vs_model.png").is_file()  # shipped CFD signals


UNIT = re.compile(r"\[[^\]]+\]")


def _figure_axes_problems(name: str, axes: list[dict[str, str]]) -> list[str]:
    """Every panel's shown axes need a label with a unit in brackets."""
    problems = []
    if not axes:
        problems.append(f"{name}: no panels")
    for panel in axes:
        for key in ("xlabel", "ylabel"):
            if key in panel and not UNIT.search(panel[key]):
                problems.append(f"{name} / {panel['title']!r}: {key} {panel[key]!r} has no unit")
        if "xlabel" not in panel and "ylabel" not in panel:
            problems.append(f"{name} / {panel['title']!r}: no labelled axis")
    return problems


def test_every_figure_has_unit_bearing_axes(report):
    folder = report.parent / "figures"
    sidecars = sorted(folder.glob("*.axes.json"))
    assert len(sidecars) == len(list(folder.glob("*.png")))
    problems = []
    for path in sidecars:
        problems += _figure_axes_problems(path.name, json.loads(path.read_text()))
    assert problems == []


def test_summary_contents_and_warnings(report):
    text = report.read_text()
    summary = text[text.index('<section id="summary">') : text.index("</section>")]
    assert "Fastest verified move" in summary and "faster</b> than the best of the paper" in summary
    assert "f₁ = 4.7" in summary
    assert (
        text.index('id="summary"')
        < text.index('id="contents"')
        < text.index('id="equivalent-model"')
    )
    anchors = re.findall(r'<section id="([^"]+)">', text)
    for anchor in anchors:
        if anchor != "summary":
            assert f'href="#{anchor}"' in text
    assert "septic (the paper's jerk-continuous law)" in html.unescape(text)
    assert "marks the preset" in text  # the asterisk of water-25C* explained
    assert "not self-consistent" in text  # Table 4 comment
    rows = json.loads((report.parent / "tables" / "sweep_shortest_safe.json").read_text())
    keys = [(row["shortest safe duration [s]"], row["law"]) for row in rows]
    assert all(a != b for a, b in itertools.pairwise(keys))  # repeated rows collapsed
    assert sum(row["fill heights"] for row in rows) >= len(rows)


@pytest.mark.skipif(
    CHROMIUM is None or CHROMEDRIVER is None,
    reason="needs Debian's chromium and chromium-driver (make test installs them)",
)
def test_report_renders_in_headless_chromium(report):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in (
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-dev-shm-usage",
    ):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    try:
        driver.get(report.resolve().as_uri())
        state = driver.execute_script("return document.readyState")
        assert state == "complete"
        sizes = driver.execute_script(
            "return Array.from(document.images)"
            ".map(i => [i.complete, i.naturalWidth, i.naturalHeight])"
        )
        assert len(sizes) >= 7  # Figs. 5b, 7, 8, 9, two slosh maps, the plan
        for complete, width, height in sizes:
            assert complete and width > 0 and height > 0
        names = driver.execute_script(
            "return Array.from(document.querySelectorAll('table')).map(t => t.dataset.name)"
        )
        for name in (
            "model",
            "table3_comparison",
            "table4_calibration",
            "compare",
            "plan",
            "versions",
        ):
            assert name in names
        rows = driver.execute_script("return document.querySelectorAll('table tbody tr').length")
        assert rows > 20
        summary = driver.execute_script(
            "const s = document.querySelector('#summary'); return s ? s.innerText : ''"
        )
        assert "Fastest verified move" in summary and "faster" in summary
        links = driver.execute_script(
            "return Array.from(document.querySelectorAll('#contents a'))"
            ".map(a => [a.getAttribute('href'), !!document.querySelector(a.getAttribute('href'))])"
        )
        assert len(links) >= 5 and all(found for _, found in links)
        figures = driver.execute_script(
            "return Array.from(document.querySelectorAll('figure'))"
            ".map(f => [f.dataset.name, JSON.parse(f.dataset.axes)])"
        )
        assert len(figures) == len(sizes)
        problems = [p for name, axes in figures for p in _figure_axes_problems(name, axes)]
        assert problems == []
        wide = driver.execute_script(
            "return Array.from(document.querySelectorAll('pre'))"
            ".filter(p => p.scrollWidth > p.clientWidth + 1).length"
        )
        assert wide == 0  # the scenario dump wraps
        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        assert errors == []
    finally:
        driver.quit()
