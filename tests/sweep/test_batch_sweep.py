"""Fast path and sweeps: equal to the single-case simulation, CSV contract, safe region."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from conftest import run_entry_point, seed_vial_table3
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from sloshkit.cli import app
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model, model_family
from sloshkit.motion import make_law
from sloshkit.motion.sampling import steps_for
from sloshkit.motion.scaling import scaled_velocity_samples, unit_duration_shape
from sloshkit.sim.batch import batch_metrics
from sloshkit.sim.simulate import simulate
from sloshkit.sweep import run_sweep

LAWS = ["trapezoidal", "cubic", "quintic", "septic", "minimum-jerk"]


@pytest.mark.filterwarnings("ignore::sloshkit.errors.ValidityWarning")
@settings(max_examples=25, deadline=None)
@given(
    law=st.sampled_from(LAWS),
    durations=st.lists(st.floats(0.3, 2.5), min_size=1, max_size=4),
    distance=st.floats(0.01, 1.0),
    fill=st.floats(0.01, 0.08),
    zeta=st.floats(0.0, 0.1),
    dt=st.sampled_from([1e-3, 2e-3, 4e-3]),
    use_numba=st.booleans(),
)
def test_fast_path_equals_single_case_simulation(
    law, durations, distance, fill, zeta, dt, use_numba
):
    model = equivalent_model(
        UprightCylinder(0.0205), get_liquid("water-20C"), fill, damping_ratio=zeta
    )
    shape = unit_duration_shape(make_law(law, distance, duration_s=1.0)).derivative_pp(1)
    block = np.asarray(durations)
    velocity = scaled_velocity_samples(shape, block, dt, steps_for(block.max(), dt))
    metrics = batch_metrics(model, velocity, block, dt, use_numba=use_numba)
    for index, duration in enumerate(block):
        single = simulate(
            model,
            make_law(law, distance, duration_s=duration),
            sample_period_s=dt,
            settle_time_s=0.0,
        )
        assert metrics.peak_angle_rad[index] == pytest.approx(
            single.peak_angle_rad, rel=1e-8, abs=1e-15
        )
        assert metrics.residual_angle_rad[index] == pytest.approx(
            single.residual_angle_rad, rel=1e-7, abs=1e-15
        )
        assert metrics.peak_wall_elevation_m[index] == pytest.approx(
            single.peak_wall_elevation_m, rel=1e-8, abs=1e-15
        )
        assert metrics.residual_wall_elevation_m[index] == pytest.approx(
            single.residual_wall_elevation_m, rel=1e-7, abs=1e-15
        )


def test_numba_and_lfilter_paths_agree():
    model = seed_vial_table3()
    shape = unit_duration_shape(make_law("septic", 0.5, duration_s=1.0)).derivative_pp(1)
    block = np.linspace(0.8, 2.0, 13)
    velocity = scaled_velocity_samples(shape, block, 1e-3, steps_for(2.0, 1e-3))
    compiled = batch_metrics(model, velocity, block, 1e-3)
    plain = batch_metrics(model, velocity, block, 1e-3, use_numba=False)
    for field in (
        "peak_angle_rad",
        "residual_angle_rad",
        "peak_wall_elevation_m",
        "residual_wall_elevation_m",
    ):
        np.testing.assert_allclose(getattr(compiled, field), getattr(plain, field), rtol=1e-9)


def test_unit_duration_shape_preserves_the_law():
    law = make_law(
        "s-curve", 0.5, max_velocity_m_s=1.0, max_acceleration_m_s2=5.0, max_jerk_m_s3=50.0
    )
    unit = unit_duration_shape(law)
    assert unit.duration_s == pytest.approx(1.0)
    t = np.linspace(0, law.duration_s, 50)
    np.testing.assert_allclose(unit.position(t / law.duration_s), law.position(t), atol=1e-12)


def test_sweep_summary_agrees_with_per_case_metrics():
    result = run_sweep(
        model_family(UprightCylinder(0.0205), get_liquid("water-25C"), damping_ratio=0.03),
        ["quintic", "septic"],
        0.5,
        np.linspace(1.0, 2.5, 16),
        fill_heights_m=[0.02, 0.039],
        max_angle_rad=math.radians(10.0),
        max_residual_rad=math.radians(1.0),
        chunk_cases=5,
    )
    rows = result.rows()
    assert len(rows) == result.cases == 2 * 2 * 16
    safe_rows = [r for r in rows if r["peak_angle_deg"] <= 10.0 and r["residual_angle_deg"] <= 1.0]
    summary = result.summary()
    assert summary["safe_cases"] == len(safe_rows)
    for best in summary["shortest_safe"]:
        candidates = [
            r["duration_s"] for r in safe_rows if r["fill_height_m"] == best["fill_height_m"]
        ]
        assert best["duration_s"] == (min(candidates) if candidates else None)
    # Spot check a case against the single-case simulation.
    row = rows[7]
    model = equivalent_model(
        UprightCylinder(0.0205), get_liquid("water-25C"), row["fill_height_m"], damping_ratio=0.03
    )
    single = simulate(model, make_law(row["law"], 0.5, duration_s=row["duration_s"]))
    assert row["residual_angle_deg"] == pytest.approx(
        np.degrees(single.residual_angle_rad), rel=1e-7
    )


def test_sweep_by_peak_acceleration():
    result = run_sweep(
        model_family(UprightCylinder(0.0205), get_liquid("water-25C")),
        ["trapezoidal", "quintic"],
        0.5,
        peak_accelerations_m_s2=[1.0, 2.0],
        fill_heights_m=[0.039],
    )
    np.testing.assert_allclose(result.peak_acceleration_m_s2, [[1.0, 2.0], [1.0, 2.0]])
    assert result.durations_s[0, 0] == pytest.approx(1.5)  # trapezoid: a = 4.5 D / T^2


def test_sweep_cli_writes_csv_and_maps(tmp_path):
    runner = CliRunner()
    result = runner.invoke(
        app,
        [
            "sweep",
            "--distance",
            "0.5m",
            "--fill-height",
            "20mm:40mm:3",
            "--duration",
            "1s:2s:5",
            "--laws",
            "trapezoidal,septic",
            "--damping-ratio",
            "0.03",
            "--max-angle",
            "12deg",
            "--max-residual",
            "1deg",
            "--out",
            str(tmp_path),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    assert summary["cases"] == 30
    with open(tmp_path / "sweep.csv", newline="") as stream:
        reader = csv.DictReader(stream)
        assert reader.fieldnames[:7] == [
            "law",
            "fill_height_m",
            "duration_s",
            "omega_1_rad_s",
            "peak_angle_deg",
            "residual_angle_deg",
            "peak_wall_elevation_m",
        ]
        rows = list(reader)
    assert len(rows) == 30
    assert sorted({float(r["fill_height_m"]) for r in rows}) == pytest.approx([0.02, 0.03, 0.04])
    assert sum(r["safe"] == "True" for r in rows) == summary["safe_cases"]
    for name in ("peak_angle_map.png", "residual_angle_map.png"):
        assert (tmp_path / name).stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--fill-height", "10mm:60mm"], "--fill-height"),
        (["--duration", "1s:2s:x"], "duration"),
        (["--laws", "warp"], "laws"),
        (["--laws", "s-curve"], "s-curve"),
    ],
)
def test_sweep_bad_input(args, needle):

    proc = run_entry_point("sweep", *args)
    assert proc.returncode == 2, proc.stderr
    assert needle in proc.stderr
    assert "Traceback" not in proc.stderr
