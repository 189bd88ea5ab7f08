"""CFD pipeline: case from a model, run, signals, calibration, and comparison with the
equivalent pendulum for the same motion (the seed paper's Table 4 and Figs. 5 and 9)."""

from __future__ import annotations

import json
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.special import j1

from sloshkit.calibration import CalibrationResult, calibrate
from sloshkit.cfd.case import (
    CaseSpec,
    Excitation,
    FreeDecay,
    Harmonic,
    MotionExcitation,
    PoseExcitation,
)
from sloshkit.cfd.results import CfdSignals, read_signals
from sloshkit.cfd.run import (
    RunResult,
    check_processes,
    expected_cells,
    interruptible,
    require_openfoam,
    run_case,
    write_case,
)
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.model.modal import SloshModel
from sloshkit.motion.recorded import from_samples
from sloshkit.sim.simulate import simulate

#: Settings recommended by the mesh and time-step study (docs/cfd.md).
RECOMMENDED: dict[str, Any] = {
    "cells_per_radius": 11,
    "delta_t_s": 2e-3,
    "max_courant": 0.5,
    "max_alpha_courant": 0.5,
    "ddt_scheme": "Euler",
    "end_time_s": 3.0,
    "pressure_correctors": 3,
}


def case_spec(
    model: SloshModel,
    excitation: Excitation,
    cells_per_radius: int = RECOMMENDED["cells_per_radius"],
    end_time_s: float = RECOMMENDED["end_time_s"],
    delta_t_s: float = RECOMMENDED["delta_t_s"],
    ddt_scheme: str = RECOMMENDED["ddt_scheme"],
    processes: int = 1,
    surface_tension: bool = False,
    max_courant: float = RECOMMENDED["max_courant"],
    max_alpha_courant: float = RECOMMENDED["max_alpha_courant"],
    adjust_time_step: bool = True,
    probe_angles: int = 0,
    pressure_correctors: int = RECOMMENDED["pressure_correctors"],
) -> CaseSpec:
    """A case for ``model``'s container, fill and liquid.

    With ``adjust_time_step`` the step follows the Courant limits and never exceeds
    ``delta_t_s``; otherwise it is fixed at ``delta_t_s``.
    """
    return CaseSpec(
        radius_m=model.radius_m,
        fill_height_m=model.fill_height_m,
        liquid=model.liquid,
        excitation=excitation,
        domain_height_m=model.container.wall_height_m,
        cells_per_radius=cells_per_radius,
        end_time_s=end_time_s,
        delta_t_s=delta_t_s,
        ddt_scheme=ddt_scheme,
        processes=processes,
        surface_tension=surface_tension,
        adjust_time_step=adjust_time_step,
        max_courant=max_courant,
        max_alpha_courant=max_alpha_courant,
        probe_angles=probe_angles,
        pressure_correctors=pressure_correctors,
    )


def run(
    spec: CaseSpec, case: Path, resume: bool = False, overwrite: bool = False, progress: Any = None
) -> RunResult:
    """Write (unless resuming) and run a case; record the run in sloshkit-run.json.

    Everything that can be checked before writing is checked first (OpenFOAM and mpirun
    present, a sensible --np), so a refused run leaves no files behind.
    """
    require_openfoam(spec.processes)
    with interruptible([], [0.0]):
        _check_and_write(spec, case, resume, overwrite)
        result = run_case(case, spec.processes, resume=resume, progress=progress)
        record = {
            "simulated_s": result.simulated_s,
            "wall_clock_s": result.wall_clock_s,
            "processes": result.processes,
            "cells": result.cells,
            "finished": time.time(),
        }
        staging = case / "sloshkit-run.json.tmp"
        staging.write_text(json.dumps(record, indent=2), encoding="utf-8")
        staging.replace(case / "sloshkit-run.json")
    return result


def _check_and_write(spec: CaseSpec, case: Path, resume: bool, overwrite: bool) -> None:
    if resume:
        if not (case / "sloshkit-case.json").is_file():
            raise InputError("case", str(case), "has no sloshkit case to resume")
        summary = json.loads((case / "sloshkit-case.json").read_text(encoding="utf-8"))
        check_processes(spec.processes, int(summary["cells"]))
    else:
        check_processes(spec.processes, expected_cells(spec))
        write_case(spec, case, overwrite=overwrite)


def excitation_end(summary: dict[str, Any]) -> float:
    """When the container stops moving in this case [s] (0 for a free decay)."""
    excitation = summary["excitation"]
    if excitation["type"] == "Harmonic":
        return float(excitation["duration_s"])
    if excitation["type"] in ("MotionExcitation", "PoseExcitation"):
        return float(excitation.get("duration_s", 0.0))
    return 0.0


@dataclass(frozen=True, eq=False)
class CfdAnalysis:
    """A case's signals and their calibration."""

    case: Path
    signals: CfdSignals
    calibration: CalibrationResult
    run_record: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        """The calibrate keys plus cells, simulated_s and wall_clock_s."""
        payload = self.calibration.to_dict()
        payload.update(
            cells=self.signals.summary["cells"],
            simulated_s=float(self.signals.time_s[-1]),
            wall_clock_s=self.run_record.get("wall_clock_s"),
            processes=self.run_record.get("processes"),
            case=str(self.case),
        )
        return payload


def analyse(case: Path, method: str = "fit", start_s: float | None = None) -> CfdAnalysis:
    """Calibrate frequency and damping from the antisymmetric wall elevation of a case, over
    the free decay (after the excitation, or from the largest peak).

    Raises `InputError` for a folder that is not a sloshkit case and for an unfinished run
    (saying how far it got), rather than calibrating a truncated record.
    """
    signals = read_finished_signals(case)
    if start_s is None:
        end = excitation_end(dict(signals.summary))
        start_s = end if end > 0 else None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        result = calibrate(
            signals.time_s,
            signals.elevation_m,
            method=method,  # type: ignore[arg-type]
            start_s=start_s,
            source=f"{case} (CFD wall elevation)",
        )
    record_path = case / "sloshkit-run.json"
    record = json.loads(record_path.read_text(encoding="utf-8")) if record_path.is_file() else {}
    return CfdAnalysis(case, signals, result, record)


def read_finished_signals(case: Path) -> CfdSignals:
    """The signals of a finished case; `InputError` when the case is missing or unfinished."""
    summary_path = case / "sloshkit-case.json"
    if not summary_path.is_file():
        raise InputError("case", str(case), "is not a sloshkit CFD case (no sloshkit-case.json)")
    summary = json.loads(summary_path.read_text(encoding="utf-8"))
    end = float(summary["end_time_s"])
    resume = f"continue it with: sloshkit cfd run --case {case} --resume"
    if not (case / "postProcessing" / "wallProbes").is_dir():
        raise InputError("case", str(case), f"is unfinished (simulated 0 of {end:g} s)", resume)
    signals = read_signals(case)
    simulated = float(signals.time_s[-1])
    step = float(summary.get("delta_t_s", 0.0))
    if simulated < end - max(1.5 * step, 1e-6):
        raise InputError(
            "case", str(case), f"is unfinished (simulated {simulated:.4g} of {end:g} s)", resume
        )
    return signals


def model_wall_elevation(
    model: SloshModel, time_s: np.ndarray, acceleration: np.ndarray, x_over_r: float = 0.98
) -> np.ndarray:
    """The pendulum model's wall elevation at x = x_over_r R for a sampled container
    acceleration: each mode scaled by J1(xi_n x/R)/J1(xi_n) (the linear mode shape)."""

    motion = from_samples(time_s, acceleration_m_s2=acceleration, name="cfd excitation")
    dt = float(np.median(np.diff(time_s)))
    response = simulate(model, motion, sample_period_s=dt, settle_time_s=0.0)
    shape = np.array([j1(m.bessel_root * x_over_r) / j1(m.bessel_root) for m in model.modes])
    factors = np.array([m.wall_elevation_factor_m for m in model.modes]) * shape
    elevation = factors @ response.angle_rad
    return np.asarray(np.interp(time_s, response.time_s, elevation), dtype=float)


def validate(case: Path, model: SloshModel) -> dict[str, Any]:
    """Compare a finished case with the pendulum model for the same motion: frequency,
    damping, peak elevation during the excitation and residual amplitude after it."""
    analysis = analyse(case)
    signals = analysis.signals
    summary = dict(signals.summary)
    t = signals.time_s
    acceleration = _excitation_acceleration(case, t)
    predicted = model_wall_elevation(model, t, acceleration)
    end = excitation_end(summary)
    during = t <= max(end, t[0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        model_fit = calibrate(
            t, predicted, start_s=end if end > 0 else None, source="pendulum model"
        )
    cfd_fit = analysis.calibration

    def amplitude(result: CalibrationResult) -> float | None:
        fit = result.estimates["fit"]
        return None if fit.amplitude is None else float(fit.amplitude)

    rows = {
        "omega_n_rad_s": (cfd_fit.omega_n_rad_s, model_fit.omega_n_rad_s),
        "damping_ratio": (cfd_fit.damping_ratio, model_fit.damping_ratio),
        "peak_elevation_m": (
            float(np.max(np.abs(signals.elevation_m[during]))) if end > 0 else None,
            float(np.max(np.abs(predicted[during]))) if end > 0 else None,
        ),
        "residual_elevation_m": (amplitude(cfd_fit), amplitude(model_fit)),
    }
    comparison = {}
    for key, (cfd_value, model_value) in rows.items():
        difference = None
        if cfd_value is not None and model_value not in (None, 0.0):
            difference = (cfd_value - model_value) / model_value  # type: ignore[operator]
        comparison[key] = {
            "cfd": cfd_value,
            "model": model_value,
            "relative_difference": difference,
        }
    correlation = float(np.corrcoef(signals.elevation_m, predicted)[0, 1])
    return {
        "case": str(case),
        "comparison": comparison,
        "correlation": correlation,
        "time_s": t,
        "cfd_elevation_m": signals.elevation_m,
        "model_elevation_m": predicted,
        "excitation_end_s": end,
    }


def _excitation_acceleration(case: Path, t: np.ndarray) -> np.ndarray:
    """The container acceleration the case was driven with, read back from its table [m/s^2]."""
    text = (case / "constant" / "acceleration.dat").read_text(encoding="utf-8")
    rows = [line for line in text.splitlines() if line.startswith("(") and "((" in line]
    times = np.array([float(row[1:].split()[0]) for row in rows])
    values = np.array([float(row.split("((")[1].split()[0]) for row in rows]) / 1000.0
    return np.asarray(np.interp(t, times, values), dtype=float)


def excitation_from_options(
    kind: str,
    tilt_rad: float,
    amplitude_m: float,
    frequency_hz: float,
    excite_time_s: float,
    motion: Any = None,
    poses: Any = None,
) -> Excitation:
    """Build the excitation named on the command line."""
    if kind == "poses":
        if poses is None:
            raise InputError("excitation", kind, "needs --pose-file")
        return PoseExcitation(poses)
    if kind == "free-decay":
        return FreeDecay(tilt_rad)
    if kind == "harmonic":
        return Harmonic(amplitude_m, frequency_hz, excite_time_s)
    if kind == "law":
        if motion is None:
            raise InputError("excitation", kind, "needs --law and the move options")
        return MotionExcitation(motion.name, motion.acceleration, motion.duration_s)
    raise InputError("excitation", kind, "must be free-decay, harmonic, law or poses")


def describe(record: dict[str, Any]) -> str:
    """One line about a run's cost."""
    wall = record.get("wall_clock_s")
    simulated = record.get("simulated_s")
    if not wall or not simulated:
        return ""
    return f"{simulated:g} s simulated in {wall:.0f} s wall clock ({wall / simulated:.0f} s per simulated second)"
