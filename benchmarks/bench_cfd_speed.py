"""Speed benchmark of the CFD step: 2 s of free decay of the seed paper's vial.

Target (issue #18): at least 15,000 cells, at most 70 s of wall clock with ``--np 2``, first-mode
frequency within 0.5 % of linear theory (4.720 Hz). The machine is shared, so the script reports
the wall clock *and* the CPU time of the OpenFOAM processes, and the load average before and
after the run (a load above the core count means other work competed for the cores).

Run: PYTHONPATH=src python benchmarks/bench_cfd_speed.py [--cells-per-radius 11] [--np 2]
     [--max-step-ms 2] [--max-courant 0.5] [--json benchmarks/results/cfd-speed.json]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import resource
import time
from pathlib import Path

import numpy as np
from scipy.signal import find_peaks

from sloshkit.cfd.case import FreeDecay
from sloshkit.cfd.pipeline import RECOMMENDED, analyse, case_spec, run
from sloshkit.cfd.results import read_signals
from sloshkit.errors import InputError
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model


def children_cpu_s() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def envelope_estimate(case: Path) -> dict[str, float]:
    """Frequency (mean peak spacing) and a signed damping ratio (least-squares slope of the
    log of the peaks of the antisymmetric wall elevation after 0.3 s; negative when the
    amplitude grows) of a record the calibration refuses."""
    signals = read_signals(case)
    t, y = signals.time_s, signals.elevation_m
    peaks, _ = find_peaks(y)
    peaks = peaks[t[peaks] > 0.3]
    omega = 2 * math.pi / float(np.mean(np.diff(t[peaks])))
    slope = float(np.polyfit(t[peaks], np.log(y[peaks]), 1)[0])
    return {"frequency_hz": omega / (2 * math.pi), "damping_ratio": -slope / omega}


def late_courant(case: Path) -> float:
    """Largest Courant number over the second half of the steps of a finished run (after the
    start-up transient: parasitic currents show here)."""
    text = (case / "log.interFoam").read_text()
    values = [float(v) for v in re.findall(r"^Courant Number mean: \S+ max: (\S+)", text, re.M)]
    return max(values[len(values) // 2 :]) if values else math.nan


def result_wall_cell(case: Path) -> float:
    """The radial size of the wall cells of a written case [m]."""
    return float(json.loads((case / "sloshkit-case.json").read_text())["wall_cell_m"])


def bench(
    case: Path,
    cells_per_radius: int,
    processes: int,
    end_time_s: float,
    max_step_s: float,
    max_courant: float,
    max_alpha_courant: float,
    pressure_correctors: int = RECOMMENDED["pressure_correctors"],
    adjust_time_step: bool = True,
    wall_grading: float = 1.0,
    radial_cells: int | None = None,
    ddt_scheme: str = "Euler",
    momentum_predictor: bool = False,
    surface_refinement: int = 2,
    tilt_deg: float = 3.0,
) -> dict[str, object]:
    """Run one free decay and return its timings and calibration."""
    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    spec = case_spec(
        model,
        FreeDecay(math.radians(tilt_deg)),
        cells_per_radius=cells_per_radius,
        end_time_s=end_time_s,
        delta_t_s=max_step_s,
        processes=processes,
        max_courant=max_courant,
        max_alpha_courant=max_alpha_courant,
        pressure_correctors=pressure_correctors,
        adjust_time_step=adjust_time_step,
        wall_grading=wall_grading,
        radial_cells=radial_cells,
        ddt_scheme=ddt_scheme,
        momentum_predictor=momentum_predictor,
        surface_refinement=surface_refinement,
    )
    load_before = os.getloadavg()
    cpu_before = children_cpu_s()
    started = time.perf_counter()
    result = run(spec, case, overwrite=True)
    wall = time.perf_counter() - started
    cpu = children_cpu_s() - cpu_before
    load_after = os.getloadavg()
    try:
        payload = analyse(case).to_dict()
    except InputError as error:  # e.g. a growing amplitude: no free decay to calibrate
        payload = envelope_estimate(case)
        payload["calibration_error"] = str(error)
    theory = model.modes[0].frequency_hz
    frequency = float(payload["frequency_hz"])
    steps = sum(
        1
        for line in (case / "log.interFoam").read_text().splitlines()
        if line.startswith("Time = ") and "accelerations" not in line
    )
    return {
        "cells": result.cells,
        "cells_per_radius": cells_per_radius,
        "processes": processes,
        "simulated_s": result.simulated_s,
        "max_step_s": max_step_s,
        "max_courant": max_courant,
        "max_alpha_courant": max_alpha_courant,
        "pressure_correctors": pressure_correctors,
        "adjust_time_step": adjust_time_step,
        "ddt_scheme": ddt_scheme,
        "momentum_predictor": momentum_predictor,
        "surface_refinement": surface_refinement,
        "tilt_deg": tilt_deg,
        "wall_grading": wall_grading,
        "radial_cells": radial_cells,
        "wall_cell_m": result_wall_cell(case),
        "time_steps": steps,
        "max_courant_late": late_courant(case),
        "wall_clock_s": wall,
        "cpu_s": cpu,
        "load_average_before": load_before,
        "load_average_after": load_after,
        "cores": os.cpu_count(),
        "frequency_hz": frequency,
        "theory_frequency_hz": theory,
        "frequency_error": frequency / theory - 1.0,
        "damping_ratio": payload["damping_ratio"],
        "calibration_error": payload.get("calibration_error"),
        "meets_target": bool(
            result.cells >= 15_000 and wall <= 70.0 and abs(frequency / theory - 1) <= 0.005
        ),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells-per-radius", type=int, default=11)
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--end-time", type=float, default=2.0)
    parser.add_argument("--max-step-ms", type=float, default=RECOMMENDED["delta_t_s"] * 1e3)
    parser.add_argument("--max-courant", type=float, default=RECOMMENDED["max_courant"])
    parser.add_argument("--max-alpha-courant", type=float, default=RECOMMENDED["max_alpha_courant"])
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-bench"))
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()
    row = bench(
        args.work / f"n{args.cells_per_radius}-np{args.np}-dt{args.max_step_ms:g}ms",
        args.cells_per_radius,
        args.np,
        args.end_time,
        args.max_step_ms * 1e-3,
        args.max_courant,
        args.max_alpha_courant,
    )
    print(json.dumps(row, indent=2))
    if args.json is not None:
        args.json.write_text(json.dumps(row, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
