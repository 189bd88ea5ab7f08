"""The result protocol (sloshkit.results): to_dict, to_pandas, to_csv and plot through the
registry, without pyplot."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import dataclass

import numpy as np
import pytest

from sloshkit.motion.laws import quintic
from sloshkit.results import ResultMixin, plotter_for
from sloshkit.sim.simulate import simulate


@dataclass
class Decay(ResultMixin):
    t: np.ndarray

    def columns(self):
        return {"t_s": self.t, "angle_rad": np.exp(-self.t)}


def test_mixin_exports_from_columns(tmp_path):
    result = Decay(np.array([0.0, 0.5, 1.0]))
    assert result.to_dict() == {"t_s": [0.0, 0.5, 1.0], "angle_rad": list(np.exp(-result.t))}
    path = result.to_csv(tmp_path / "decay.csv")
    assert path.read_text().splitlines()[0] == "t_s,angle_rad"
    np.testing.assert_allclose(np.loadtxt(path, delimiter=",", skiprows=1)[:, 1], np.exp(-result.t))
    frame = result.to_pandas()
    assert list(frame.columns) == ["t_s", "angle_rad"] and len(frame) == 3


def test_to_pandas_says_how_to_install_pandas(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas raises ImportError
    with pytest.raises(ImportError, match="pip install pandas"):
        Decay(np.zeros(2)).to_pandas()


def test_unregistered_result_has_no_plot():
    with pytest.raises(TypeError, match="no plotting function registered for Decay"):
        plotter_for(Decay)


def test_plot_returns_a_figure_drawn_without_pyplot(seed_model_table3, tmp_path):
    from matplotlib.figure import Figure

    response = simulate(seed_model_table3, quintic(0.1, 1.0), settle_time_s=0.5)
    figure = response.plot(path=tmp_path / "response.png")
    assert isinstance(figure, Figure) and len(figure.axes) == 3
    assert (tmp_path / "response.png").stat().st_size > 10_000
    # Into a caller's axes: the panels share its area, in its figure.
    outer = Figure()
    ax = outer.add_subplot(1, 2, 2)
    assert response.plot(ax) is outer
    assert len(outer.axes) == 3


def test_plotting_selects_no_backend_and_core_imports_no_matplotlib():
    code = (
        "import sys, sloshkit as sk\n"
        "m = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid('water-25C'), 0.039)\n"
        "r = sk.simulate(m, sk.quintic(0.1, 1.0))\n"
        "assert 'matplotlib' not in sys.modules\n"
        "r.plot()\n"
        "print('matplotlib.pyplot' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
