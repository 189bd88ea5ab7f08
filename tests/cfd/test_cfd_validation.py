"""CFD comparison, calibration window and mesh limits without OpenFOAM: synthetic cases whose
probe output encodes a known wall elevation."""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from sloshkit.cfd.case import SCALE, CaseSpec, Harmonic
from sloshkit.cfd.mesh import probe_columns
from sloshkit.cfd.pipeline import analyse, model_wall_elevation, validate
from sloshkit.cfd.run import write_case
from sloshkit.cfd.state import MIN_DETERMINANT, CfdError, check_mesh_quality
from sloshkit.cfd.validation import CfdValidation
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model

WATER = get_liquid("water-25C")
MODEL = equivalent_model(UprightCylinder(0.0205), WATER, 0.039, damping_ratio=0.006)


def synthetic_case(folder: Path, end_time_s: float, elevation_of=None, force_of=None) -> Path:
    """A finished-looking harmonic case whose wall elevation at +-x is the pendulum model's
    (or ``elevation_of(t)``), written as alpha probes, tilt and force files (the force zero,
    or ``force_of(t)`` [N])."""
    excitation = Harmonic(0.001, 3.0, 0.5)
    spec = CaseSpec(0.0205, 0.039, WATER, excitation, cells_per_radius=4, end_time_s=end_time_s)
    case = write_case(spec, folder)
    t = np.arange(0.0, end_time_s + 1e-9, 2e-3)
    if elevation_of is None:
        eta = model_wall_elevation(MODEL, t, excitation.acceleration(t))
    else:
        eta = elevation_of(t)
    z, dz = probe_columns(spec)
    rows = []
    for time, value in zip(t, eta, strict=True):
        plus = np.clip((0.039 + value - (z - dz / 2)) / dz, 0, 1)
        minus = np.clip((0.039 - value - (z - dz / 2)) / dz, 0, 1)
        rows.append(" ".join(f"{v:.12g}" for v in [time, *plus, *minus]))
    forces = f"0 (0 0 0) (0 0 0)\n{end_time_s} (0 0 0) (0 0 0)\n"
    if force_of is not None:  # the case's millimetre units: N' = N * SCALE**4 (cfd/results.py)
        forces = "".join(
            f"{time:.12g} ({f * SCALE**4:.12g} 0 0) (0 0 0)\n"
            for time, f in zip(t, force_of(t), strict=True)
        )
    for name, file_name, text in (
        ("wallProbes", "alpha.water", "\n".join(rows)),
        ("surfaceTilt", "volFieldValue.dat", f"0 (0 0 -1000)\n{end_time_s} (0 0 -1000)\n"),
        ("wallForces", "force.dat", forces),
    ):
        target = case / "postProcessing" / name / "0"
        target.mkdir(parents=True)
        (target / file_name).write_text("# synthetic\n" + text + "\n")
    return case


def test_validate_takes_model_then_case_and_returns_the_result_protocol(tmp_path):
    case = synthetic_case(tmp_path / "c", 3.0)
    result = validate(MODEL, case)
    assert isinstance(result, CfdValidation)
    payload = result.to_dict()
    # The JSON keys of `sloshkit cfd validate --json` (1-D): v1's, plus damping_signal.
    assert list(payload) == [
        "case",
        "comparison",
        "correlation",
        "damping_signal",
        "excitation_end_s",
    ]
    assert payload["damping_signal"] == "wall_elevation"  # the synthetic force is zero
    assert set(payload["comparison"]) == {
        "omega_n_rad_s",
        "damping_ratio",
        "peak_elevation_m",
        "residual_elevation_m",
    }
    # The CFD side went through the alpha-probe encoding: it must reproduce the model.
    assert payload["correlation"] > 0.9999
    for row in payload["comparison"].values():
        assert abs(row["relative_difference"]) < 0.02
    assert payload["comparison"]["damping_ratio"]["model"] == pytest.approx(0.006, rel=0.1)
    frame = result.to_pandas()
    assert list(frame.columns) == ["time_s", "cfd_elevation_m", "model_elevation_m"]
    written = result.to_csv(tmp_path / "v.csv")
    assert written.read_text().splitlines()[0] == "time_s,cfd_elevation_m,model_elevation_m"
    figure = result.plot(path=tmp_path / "v.png")
    assert (tmp_path / "v.png").stat().st_size > 1000
    assert figure.axes[0].get_lines()


def test_validate_with_the_arguments_swapped_fails_loudly(tmp_path):
    case = synthetic_case(tmp_path / "c", 1.0)
    with pytest.raises(TypeError, match="v1 order"):
        validate(case, MODEL)  # type: ignore[arg-type]


def test_analyse_starts_one_period_after_the_excitation(tmp_path):
    case = synthetic_case(tmp_path / "c", 3.0)
    calibration = analyse(case).calibration
    window_start = calibration.to_dict()["window_s"][0]
    period = 2 * math.pi / MODEL.modes[0].omega_rad_s
    assert 0.5 + 0.9 * period <= window_start <= 0.5 + 1.6 * period
    assert calibration.damping_ratio == pytest.approx(0.006, rel=0.1)


def test_a_short_forced_run_says_it_is_too_short(tmp_path):
    case = synthetic_case(tmp_path / "c", 0.6)
    with pytest.raises(InputError, match=r"too short to calibrate.*--end-time"):
        analyse(case)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = validate(MODEL, case)
    assert any(issubclass(w.category, ValidityWarning) for w in caught)
    assert result.comparison["damping_ratio"]["cfd"] is None
    assert result.comparison["peak_elevation_m"]["relative_difference"] == pytest.approx(
        0.0, abs=0.02
    )
    json.dumps(result.to_dict())  # still a JSON document


CHECKMESH = """    cells:            33840
    Mesh non-orthogonality Max: 30.6 average: 5.2
    Max skewness = 0.50 OK.
    Max aspect ratio = {aspect} OK.
    Cell determinant (wellposedness) : minimum: {determinant} average: 0.5
{flag}"""


def test_mesh_limit_is_the_measured_determinant_not_checkmesh_s_own():
    stable = CHECKMESH.format(
        aspect=19.0,
        determinant=9.4e-4,
        flag=" ***Cells with small determinant (< 0.001) found, number of cells: 96\n"
        "Failed 1 mesh checks.",
    )
    with pytest.warns(ValidityWarning, match="marginal"):
        assert check_mesh_quality(stable)["min_determinant"] == pytest.approx(9.4e-4)
    unstable = CHECKMESH.format(aspect=19.0, determinant=2.3e-4, flag="")
    assert 2.3e-4 < MIN_DETERMINANT < 9.4e-4
    with pytest.raises(CfdError, match="determinant"):
        check_mesh_quality(unstable)
    thin = CHECKMESH.format(aspect=29.6, determinant=1.4e-3, flag="")
    with pytest.raises(CfdError, match="aspect ratio"):
        check_mesh_quality(thin)
    other = CHECKMESH.format(aspect=2.0, determinant=0.3, flag=" ***Zero or negative cell volume")
    with pytest.raises(CfdError, match="failed mesh checks"):
        check_mesh_quality(other)


def test_a_case_with_empty_probe_files_is_unfinished(tmp_path):
    case = synthetic_case(tmp_path / "c", 1.0)
    (case / "postProcessing" / "wallProbes" / "0" / "alpha.water").write_text("# Probe 0\n")
    with pytest.raises(InputError, match=r"is unfinished \(no probe data yet"):
        analyse(case)


def test_a_run_stopped_in_its_last_step_is_unfinished(tmp_path):
    """Stopped one 2 ms step before its 1 s end, a run is unfinished (CI once saw such a run
    analysed as if finished); with an adaptive step, the resampled grid may stop short of the
    solver's last probe time, which must not make a finished run look unfinished."""
    case = synthetic_case(tmp_path / "c", 1.0)
    probes = case / "postProcessing" / "wallProbes" / "0" / "alpha.water"
    lines = probes.read_text().splitlines()
    probes.write_text("\n".join(lines[:-1]) + "\n")
    with pytest.raises(InputError, match=r"is unfinished \(simulated 0.998 of 1 s\)"):
        analyse(case)
    adaptive = synthetic_case(tmp_path / "a", 1.0)
    probes = adaptive / "postProcessing" / "wallProbes" / "0" / "alpha.water"
    header, first, *rows = probes.read_text().splitlines()
    first = first.replace("0 ", "0.0001 ", 1)  # an adaptive first step: the grid is shifted
    probes.write_text("\n".join([header, first, *rows]) + "\n")
    assert analyse(adaptive).signals.time_s[-1] < 1.0 - 1e-3  # resampled short of the end


OMEGA = MODEL.modes[0].omega_rad_s


def damped_force(zeta: float, noise_n: float = 0.0):
    """A free-decay wall force from the excitation's end (0.5 s) with damping ratio ``zeta``,
    plus ``noise_n`` [N] of 120 Hz content (what parasitic currents add)."""

    def force_of(t):
        after = np.clip(t - 0.5, 0.0, None)
        omega_d = OMEGA * math.sqrt(1 - zeta**2)
        decay = 2e-4 * np.exp(-zeta * OMEGA * after) * np.cos(omega_d * after)
        return decay + noise_n * np.sin(2 * math.pi * 120.0 * t)

    return force_of


def corrupted_elevation(t):
    """The model's elevation (zeta 0.006) with a 0.3 mm staircase: a coarse probe column."""
    eta = model_wall_elevation(MODEL, t, Harmonic(0.001, 3.0, 0.5).acceleration(t))
    return np.round(eta / 3e-4) * 3e-4


def test_analyse_takes_frequency_and_damping_from_the_wall_force(tmp_path):
    case = synthetic_case(tmp_path / "c", 3.0, corrupted_elevation, damped_force(0.003))
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)  # a clean force raises no doubt
        analysis = analyse(case)
    payload = analysis.to_dict()
    assert payload["damping_signal"] == "wall_force"
    assert payload["damping_ratio"] == pytest.approx(0.003, rel=0.05)
    assert payload["omega_n_rad_s"] == pytest.approx(OMEGA, rel=0.005)
    assert payload["force_noise_ratio"] < 0.1
    assert "wall force" in payload["source"]
    # The corrupted elevation alone gives another damping: the force's value is not a fluke.
    elevation_only = analyse(synthetic_case(tmp_path / "e", 3.0, corrupted_elevation))
    assert elevation_only.damping_signal == "wall_elevation"
    assert abs(elevation_only.calibration.damping_ratio - 0.003) > 0.001
    # validate compares the force's damping; its residual amplitude stays an elevation [m].
    result = validate(MODEL, case).to_dict()
    assert result["damping_signal"] == "wall_force"
    assert result["comparison"]["damping_ratio"]["cfd"] == pytest.approx(0.003, rel=0.05)
    assert result["comparison"]["residual_elevation_m"]["cfd"] < 1e-2


def test_analyse_without_force_output_uses_the_elevation(tmp_path):
    analysis = analyse(synthetic_case(tmp_path / "c", 3.0))  # zero force
    payload = analysis.to_dict()
    assert payload["damping_signal"] == "wall_elevation"
    assert payload["force_noise_ratio"] is None
    assert payload["damping_ratio"] == pytest.approx(0.006, rel=0.1)
    # NaN rows are a damaged or diverged output: an error, never a silent switch of signal
    nan_force = synthetic_case(tmp_path / "n", 3.0, force_of=lambda t: np.where(t > 1, np.nan, t))
    with pytest.raises(InputError, match=r"force\.dat holds nan"):
        analyse(nan_force)


def test_a_noisy_wall_force_warns_of_parasitic_currents(tmp_path):
    case = synthetic_case(tmp_path / "c", 3.0, force_of=damped_force(0.003, noise_n=1.5e-4))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        analysis = analyse(case)
    doubts = [str(w.message) for w in caught if issubclass(w.category, ValidityWarning)]
    assert any("parasitic currents" in d for d in doubts)
    payload = analysis.to_dict()
    assert payload["damping_signal"] == "wall_force"
    assert payload["force_noise_ratio"] > 0.5
    assert any("parasitic currents" in w for w in payload["warnings"])


def test_a_step_to_step_oscillation_of_the_wall_force_warns(tmp_path):
    """A sign change at every step, too small for the noise ratio (below its 0.5 limit), is
    what interFoam's step-to-step pressure oscillation looks like at its onset."""
    smooth = damped_force(0.003)

    def force_of(t):
        steps = np.rint((t - t[0]) / (t[1] - t[0]))
        return smooth(t) + 1.2e-5 * (-1.0) ** steps

    case = synthetic_case(tmp_path / "c", 3.0, force_of=force_of)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        payload = analyse(case).to_dict()
    doubts = [str(w.message) for w in caught if issubclass(w.category, ValidityWarning)]
    assert payload["force_noise_ratio"] < 0.5  # the older check does not see it
    assert payload["force_step_alternation"] > 0.01
    assert any("changes sign from step to step" in d for d in doubts)
    assert any("changes sign from step to step" in w for w in payload["warnings"])
    clean = analyse(synthetic_case(tmp_path / "s", 3.0, force_of=smooth)).to_dict()
    assert clean["force_step_alternation"] < 0.004


def test_a_run_whose_time_step_collapsed_is_unfinished_not_an_internal_error(tmp_path):
    """An adaptive step that collapsed to ~1e-70 s logs the same time again and again (seen on
    a diverging graded mesh): the case reads as unfinished instead of asking for an endless
    resampling grid."""
    case = synthetic_case(tmp_path / "c", 1.0)
    probes = case / "postProcessing" / "wallProbes" / "0" / "alpha.water"
    header, *rows = probes.read_text().splitlines()
    probes.write_text("\n".join([header, *rows[:100], *[rows[99]] * 150]) + "\n")
    with pytest.raises(InputError, match=r"is unfinished \(simulated 0.198 of 1 s\)"):
        analyse(case)
