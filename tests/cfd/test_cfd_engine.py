"""OpenFOAM for real (CI installs Debian's openfoam): a tiny case meshed, filled, run for a few
steps serially and on 2 MPI ranks, and its output parsed. The full calibration is a documented
command (docs/cfd.md), not a CI test."""

from __future__ import annotations

import json
import math
import shutil
import subprocess

import numpy as np
import pytest
from typer.testing import CliRunner

from sloshkit.cfd.analysis import read_finished_signals
from sloshkit.cfd.case import CaseSpec, FreeDecay, Harmonic
from sloshkit.cfd.foam import read_scalar_internal_field
from sloshkit.cfd.results import read_signals
from sloshkit.cfd.run import expected_cells, openfoam_environment, run_case, write_case
from sloshkit.cli import app
from sloshkit.model.liquids import get_liquid

pytestmark = pytest.mark.skipif(
    shutil.which("interFoam") is None, reason="OpenFOAM is not installed (make test installs it)"
)


def tiny(**kwargs) -> CaseSpec:
    settings = dict(
        radius_m=0.0205,
        fill_height_m=0.039,
        liquid=get_liquid("water-25C"),
        cells_per_radius=4,
        end_time_s=0.01,
        delta_t_s=1e-3,
        write_interval_s=0.01,
    )
    settings.update(kwargs)
    return CaseSpec(**settings)


def test_dictionaries_parse_with_foam_dictionary(tmp_path):
    case = write_case(tiny(excitation=Harmonic(0.01, 1.0, 0.01)), tmp_path / "case")
    for name in (
        "system/controlDict",
        "system/fvSchemes",
        "system/fvSolution",
        "system/blockMeshDict",
        "system/setFieldsDict",
        "constant/transportProperties",
        "constant/fvOptions",
    ):
        completed = subprocess.run(
            ["foamDictionary", "-expand", name],
            cwd=case,
            env=openfoam_environment(),
            capture_output=True,
            text=True,
            check=False,
        )
        assert completed.returncode == 0, (
            f"{name}: {completed.stdout[-500:]}{completed.stderr[-500:]}"
        )


def test_serial_run_mesh_fill_and_signals(tmp_path):
    spec = tiny(excitation=FreeDecay(math.radians(3.0)))
    case = write_case(spec, tmp_path / "case")
    result = run_case(case)
    assert result.simulated_s == pytest.approx(0.01)
    log = (case / "log.checkMesh").read_text()
    assert f"cells:            {expected_cells(spec)}" in log
    # Fill volume equals pi R^2 h within one cell layer of the surface.
    subprocess.run(
        ["postProcess", "-func", "writeCellVolumes", "-time", "0"],
        cwd=case,
        env=openfoam_environment(),
        capture_output=True,
        check=True,
    )
    volumes = read_scalar_internal_field((case / "0" / "V").read_text())
    alpha = read_scalar_internal_field((case / "0" / "alpha.water").read_text(), cells=volumes.size)
    liquid = float(np.sum(alpha * volumes)) * 1e-9  # mm^3 -> m^3
    mesh_area = np.sum(volumes) * 1e-9 / spec.height_m
    layer = mesh_area * spec.radius_m / (2 * spec.cells_per_radius)
    assert abs(liquid - mesh_area * spec.fill_height_m) <= layer
    signals = read_signals(case)
    assert signals.time_s.size == 10
    assert abs(signals.elevation_m[0]) == pytest.approx(
        0.98 * 0.0205 * math.tan(math.radians(3)), rel=0.35
    )
    assert math.degrees(signals.tilt_rad[0]) == pytest.approx(3.0, abs=1.5)
    assert np.all(np.isfinite(signals.force_x_n))


def test_a_fixed_step_that_does_not_divide_the_end_time_completes(tmp_path):
    # 0.01 s / 0.7 ms = 14.3 steps: interFoam stops after 14 (t = 9.8 ms), half a step short
    spec = tiny(delta_t_s=7e-4, adjust_time_step=False)
    case = write_case(spec, tmp_path / "case")
    result = run_case(case)
    assert result.simulated_s == pytest.approx(0.0098)
    assert read_signals(case).time_s[-1] == pytest.approx(0.0098)
    assert read_finished_signals(case).time_s[-1] == pytest.approx(0.0098)  # not "unfinished"


def test_parallel_run_and_resume(tmp_path):
    spec = tiny(processes=2, end_time_s=0.005, write_interval_s=0.005)
    case = write_case(spec, tmp_path / "case")
    result = run_case(case, processes=2)
    assert result.simulated_s == pytest.approx(0.005)
    assert (case / "processor1").is_dir()
    # Resume: extend the end time and continue from the last written time.
    control = case / "system" / "controlDict"
    control.write_text(
        control.read_text().replace("endTime         0.005;", "endTime         0.008;")
    )
    summary = json.loads((case / "sloshkit-case.json").read_text())
    summary["end_time_s"] = 0.008
    (case / "sloshkit-case.json").write_text(json.dumps(summary))
    resumed = run_case(case, processes=2, resume=True)
    assert resumed.simulated_s == pytest.approx(0.008)


def test_cli_cfd_run_and_analyse_json(tmp_path):
    runner = CliRunner()
    result = runner.invoke(
        app,
        [
            "cfd",
            "run",
            "--case",
            str(tmp_path / "c"),
            "--cells-per-radius",
            "4",
            "--end-time",
            "1.2s",
            "--delta-t",
            "2ms",
            "--tilt",
            "4deg",
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    for key in (
        "omega_n_rad_s",
        "frequency_hz",
        "damping_ratio",
        "method",
        "window_s",
        "n_peaks",
        "cells",
        "simulated_s",
        "wall_clock_s",
    ):
        assert key in payload
    assert payload["simulated_s"] == pytest.approx(1.2)
    # A 1.2 s record on a 4-cells-per-radius mesh: a rough but real first-mode frequency.
    assert payload["frequency_hz"] == pytest.approx(4.72, rel=0.15)
    analysed = json.loads(
        runner.invoke(app, ["cfd", "analyse", str(tmp_path / "c"), "--json"]).stdout
    )
    assert analysed["frequency_hz"] == pytest.approx(payload["frequency_hz"])
    assert (tmp_path / "c" / "Allrun").is_file()


def test_solver_failure_is_reported_with_the_log(tmp_path):
    from sloshkit.cfd.run import CfdError

    case = write_case(tiny(), tmp_path / "case")
    (case / "system" / "fvSchemes").write_text("broken")
    with pytest.raises(CfdError, match=r"failed \(exit \d+\)") as info:
        run_case(case)
    assert "FOAM FATAL" in str(info.value)  # the log's tail is in the message


def test_cli_cfd_validate_against_the_pendulum(tmp_path):
    """Harmonic excitation on a tiny mesh: the CFD and the pendulum agree in frequency and
    correlate strongly (the full-resolution numbers are in docs/cfd.md)."""
    result = CliRunner().invoke(
        app,
        [
            "cfd",
            "validate",
            "--case",
            str(tmp_path / "h"),
            "--excitation",
            "harmonic",
            "--amplitude",
            "5mm",
            "--excite-time",
            "0.5s",
            "--frequency",
            "2Hz",
            "--end-time",
            "1.5s",
            "--cells-per-radius",
            "4",
            "--delta-t",
            "2ms",
            "--damping-ratio",
            "0.02",
            "--plot",
            str(tmp_path / "fig9.png"),
            "--json",
        ],
    )
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert payload["correlation"] > 0.9
    omega = payload["comparison"]["omega_n_rad_s"]
    assert omega["relative_difference"] == pytest.approx(0.0, abs=0.1)
    assert (tmp_path / "fig9.png").stat().st_size > 10_000
