"""Mesh, time-step and scheme study of the CFD free decay of the seed paper's vial.

Runs interFoam free decays (3 deg tilt, water, laminar, no surface tension) for several mesh
resolutions and time steps, calibrates frequency and damping from each, extrapolates the damping
to zero time step (Euler adds damping proportional to the step), times serial against --np 2,
and writes data/cfd-study.json and figures/cfd_study.png.

Run (about 30 min on 2 cores): .venv/bin/python studies/cfd-damping/cfd_study.py [--end-time 2]
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.cfd.case import FreeDecay
from sloshkit.cfd.pipeline import analyse, case_spec, run

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--end-time", type=float, default=2.0)
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-study"))
    parser.add_argument("--cells", type=int, nargs="+", default=[8, 10, 12])
    parser.add_argument("--steps-ms", type=float, nargs="+", default=[1.0, 0.5, 0.25])
    args = parser.parse_args()
    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    runs = []
    plan = [(n, dt, 2, "Euler") for n in args.cells for dt in args.steps_ms]
    plan.append((10, 0.5, 1, "Euler"))  # serial timing
    plan.append((10, 1.0, 2, "CrankNicolson 0.9"))  # scheme comparison
    for cells, step_ms, processes, scheme in plan:
        tag = f"n{cells}-dt{step_ms:g}ms-np{processes}-{scheme.split()[0]}"
        case = args.work / tag
        spec = case_spec(
            model,
            FreeDecay(math.radians(3.0)),
            cells_per_radius=cells,
            end_time_s=args.end_time,
            delta_t_s=step_ms * 1e-3,
            ddt_scheme=scheme,
            processes=processes,
        )
        started = time.perf_counter()
        try:
            result = run(spec, case, overwrite=True)
            analysis = analyse(case)
            payload = analysis.to_dict()
            row = {
                "tag": tag,
                "cells_per_radius": cells,
                "cells": result.cells,
                "delta_t_s": step_ms * 1e-3,
                "processes": processes,
                "ddt": scheme,
                "wall_clock_s": result.wall_clock_s,
                "simulated_s": result.simulated_s,
                "frequency_hz": payload["frequency_hz"],
                "damping_ratio": payload["damping_ratio"],
                "status": "completed",
            }
        except Exception as error:
            row = {
                "tag": tag,
                "cells_per_radius": cells,
                "delta_t_s": step_ms * 1e-3,
                "processes": processes,
                "ddt": scheme,
                "wall_clock_s": time.perf_counter() - started,
                "status": f"failed: {error}"[:300],
            }
        runs.append(row)
        print(json.dumps(row), flush=True)
        write(runs, model)


def write(runs: list[dict], model) -> None:
    theory_hz = model.modes[0].frequency_hz
    extrapolated = {}
    for cells in sorted({r["cells_per_radius"] for r in runs}):
        points = [
            (r["delta_t_s"], r["damping_ratio"])
            for r in runs
            if r["cells_per_radius"] == cells
            and r.get("status") == "completed"
            and r["processes"] == 2
            and r["ddt"] == "Euler"
        ]
        if len(points) >= 2:
            steps, zetas = np.array(points).T
            slope, intercept = np.polyfit(steps, zetas, 1)
            extrapolated[str(cells)] = {
                "zeta_at_zero_step": float(intercept),
                "slope_per_s": float(slope),
            }
    document = {
        "theory_frequency_hz": theory_hz,
        "correlation_damping_ratio": model.modes[0].damping_ratio,
        "paper_damping_ratio": 0.03,
        "runs": runs,
        "extrapolated": extrapolated,
    }
    (DATA / "cfd-study.json").write_text(json.dumps(document, indent=2))
    plot(document)


def plot(document: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [
        r
        for r in document["runs"]
        if r.get("status") == "completed" and r["processes"] == 2 and r["ddt"] == "Euler"
    ]
    figure, axes = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    for cells in sorted({r["cells_per_radius"] for r in runs}):
        rows = sorted(
            (r for r in runs if r["cells_per_radius"] == cells), key=lambda r: r["delta_t_s"]
        )
        steps = [1e3 * r["delta_t_s"] for r in rows]
        axes[0].plot(
            steps,
            [r["frequency_hz"] for r in rows],
            "o-",
            label=f"{cells} cells/radius ({rows[0]['cells']} cells)",
        )
        axes[1].plot(steps, [r["damping_ratio"] for r in rows], "o-", label=f"{cells} cells/radius")
        fit = document["extrapolated"].get(str(cells))
        if fit:
            grid = np.linspace(0, max(steps), 20)
            axes[1].plot(
                grid, fit["zeta_at_zero_step"] + fit["slope_per_s"] * grid * 1e-3, ":", color="grey"
            )
    axes[0].axhline(
        document["theory_frequency_hz"], color="black", linestyle="--", label="linear theory"
    )
    axes[0].set_xlabel("time step [ms]")
    axes[0].set_ylabel("first-mode frequency [Hz]")
    axes[1].axhline(
        document["correlation_damping_ratio"],
        color="black",
        linestyle="--",
        label="correlation (paper eq. 2)",
    )
    axes[1].set_xlabel("time step [ms]")
    axes[1].set_ylabel("damping ratio ζ")
    axes[1].set_xlim(left=0)
    for axis in axes:
        axis.grid(alpha=0.3)
        axis.legend(fontsize=8)
    figure.suptitle("CFD free decay of the paper's vial: mesh and time-step study (Euler)")
    figure.savefig(STUDY / "figures" / "cfd_study.png", dpi=110)


if __name__ == "__main__":
    main()
