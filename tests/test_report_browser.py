"""The reproduction report in a real browser: headless Chromium (Debian's chromium and
chromium-driver, installed by `make test`) loads report.html with no console errors, every
figure renders and every table is present."""

from __future__ import annotations

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
        assert len(sizes) >= 6  # Figs. 5b, 7, 8, two slosh maps, the plan
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
        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        assert errors == []
    finally:
        driver.quit()
