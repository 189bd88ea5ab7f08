"""Slosh maps and Fig. 5b as a reader sees them (issue 17): no empty panels, plain colour-bar
ticks, each map hatched by its own limit, every peak marked, units on the axes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sloshkit.calibration import calibrate
from sloshkit.plotting import plot_sweep_map
from sloshkit.report.writer import axis_labels
from sloshkit.sweep import run_sweep


@pytest.fixture(scope="module")
def sweep(seed_model_module):
    return run_sweep(
        seed_model_module,
        ["trapezoidal", "cubic", "quintic", "septic"],
        0.5,
        np.linspace(1.0, 2.5, 6),
        fill_heights_m=[0.03, 0.039, 0.05],
        max_angle_rad=math.radians(60.0),  # never broken here
        max_residual_rad=math.radians(1.0),  # broken by the trapezoid
    )


@pytest.fixture(scope="module")
def seed_model_module():
    from sloshkit.model.geometry import UprightCylinder
    from sloshkit.model.liquids import get_liquid
    from sloshkit.model.modal import model_family

    return model_family(UprightCylinder(0.0205), get_liquid("water-25C"), damping_ratio=0.03)


def _hatched(axis) -> bool:
    return any(getattr(collection, "get_hatch", lambda: None)() for collection in axis.collections)


def test_each_map_is_hatched_by_its_own_limit(sweep):
    peak = plot_sweep_map(sweep, "peak_angle_deg")
    residual = plot_sweep_map(sweep, "residual_angle_deg")
    panels = [axis for axis in peak.axes if axis.get_title() in sweep.laws]
    assert len(panels) == 4 and len(peak.axes) == 5  # 2 x 2 panels + colour bar, none empty
    assert not any(_hatched(axis) for axis in panels)
    hatched = {a.get_title() for a in residual.axes if a.get_title() in sweep.laws and _hatched(a)}
    assert "trapezoidal" in hatched
    assert "hatched: peak above 60°" in peak._suptitle.get_text()


def test_colour_bar_ticks_are_plain_numbers(sweep):
    figure = plot_sweep_map(sweep, "residual_angle_deg")
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(figure).draw()
    bar = figure.axes[-1]
    labels = [text.get_text() for text in bar.get_yticklabels() if text.get_text()]
    assert labels and not any("times" in label or "×" in label or "^" in label for label in labels)
    for entry in axis_labels(figure):
        for key in ("xlabel", "ylabel"):
            if key in entry:
                assert "[" in entry[key] and "]" in entry[key]


def test_fig5b_marks_every_peak_and_has_units():
    t = np.arange(0.0, 4.0, 0.002)
    omega, zeta = 29.66, 0.02
    signal = 1e-3 * np.exp(-zeta * omega * t) * np.cos(omega * np.sqrt(1 - zeta**2) * t)
    result = calibrate(t, signal)
    figure = result.plot(None, signal_label="wall elevation (detrended) [m]")
    axis = figure.axes[0]
    legend = [text.get_text() for text in axis.get_legend().get_texts()]
    marked = next(label for label in legend if label.startswith("peaks and troughs"))
    expected = 2 * (t[-1] - result.signal.time_s[0]) * omega / (2 * math.pi)
    count = int(marked.split("(")[1].rstrip(")"))
    assert count >= int(expected) - 1
    assert axis.get_ylabel() == "wall elevation (detrended) [m]"
