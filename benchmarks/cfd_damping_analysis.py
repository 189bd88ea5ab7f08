"""Analysis of the CFD damping study (benchmarks/cfd_damping_study.py): Richardson
extrapolation in time step and mesh, GCI, boundary-layer theory, figure and the docs section.

Reads docs/cfd-damping-study.json (uniform O-grids) and docs/cfd-damping-graded.json (wall-
graded O-grids), writes docs/cfd-damping.json (every number of the section), the figure
docs/figures/cfd_damping_study.png, and the text between the markers
``<!-- damping-study:start -->`` and ``<!-- damping-study:end -->`` of docs/cfd.md.

Run: PYTHONPATH=src python benchmarks/cfd_damping_analysis.py
"""

from __future__ import annotations

import json
import math
import statistics
from pathlib import Path
from typing import Any

from cfd_damping_report import MAX_FREQUENCY_ERROR, MAX_LATE_COURANT, render, render_stability
from scipy import integrate
from scipy.special import j1, jvp

from sloshkit.cfd.convergence import combined_uncertainty, observed_order, richardson
from sloshkit.cfd.mesh import wall_cell_size_m
from sloshkit.cfd.spec import CaseSpec
from sloshkit.model.liquids import get_liquid
from sloshkit.model.theory import damping_ratio_correlation

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
RADIUS_M, FILL_M, GRAVITY = 0.0205, 0.039, 9.81
XI_1 = 1.8411837813406593  # first zero of J1'
START, END = "<!-- damping-study:start -->", "<!-- damping-study:end -->"
WALL_START, WALL_END = "<!-- wall-stability:start -->", "<!-- wall-stability:end -->"


def stokes_layer_damping(radius_m: float, fill_m: float, nu_m2_s: float) -> dict[str, float]:
    """First-mode damping ratio of a clean upright cylinder from laminar boundary-layer
    theory: Stokes layers on the side wall and the bottom, free-slip (clean) surface, plus the
    weak dissipation of the irrotational flow in the bulk.

    The mean dissipation of a Stokes layer per unit wall area is rho U^2 sqrt(nu omega / 8)
    for a tangential slip velocity of amplitude U (Landau & Lifshitz, *Fluid Mechanics*,
    2nd ed., §24), so zeta = sqrt(nu / (8 omega)) S / V with S the wall integral of the
    squared tangential velocity of the inviscid mode and V its volume integral (Case &
    Parkinson, J. Fluid Mech. 2 (1957) 172, doi:10.1017/S0022112057000063; Miles, J. Fluid
    Mech. 3 (1958) 233, doi:10.1017/S0022112058000032). The bulk term is Lamb's 2 nu k^2 decay
    rate of the amplitude (Lamb, *Hydrodynamics*, 6th ed., §348), with k = xi_1 / R.
    """
    k = XI_1 / radius_m
    omega = math.sqrt(GRAVITY * k * math.tanh(k * fill_m))

    def f(z: float) -> float:
        return math.cosh(k * z) / math.cosh(k * fill_m)

    def df(z: float) -> float:
        return k * math.sinh(k * z) / math.cosh(k * fill_m)

    jr = float(j1(XI_1))
    side = (
        math.pi
        * radius_m
        * jr**2
        * integrate.quad(lambda z: df(z) ** 2 + f(z) ** 2 / radius_m**2, 0.0, fill_m)[0]
    )
    bottom = (
        math.pi
        * f(0.0) ** 2
        * integrate.quad(
            lambda r: (k**2 * jvp(1, k * r) ** 2 + (j1(k * r) / r) ** 2) * r, 1e-12, radius_m
        )[0]
    )
    volume = (
        math.pi
        * k
        * math.tanh(k * fill_m)
        * integrate.quad(lambda r: j1(k * r) ** 2 * r, 0.0, radius_m)[0]
    )
    factor = math.sqrt(nu_m2_s / (8.0 * omega)) / volume
    bulk = 2.0 * nu_m2_s * k**2 / omega
    return {
        "omega_rad_s": omega,
        "stokes_layer_thickness_m": math.sqrt(2.0 * nu_m2_s / omega),
        "side_wall": factor * side,
        "bottom": factor * bottom,
        "bulk": bulk,
        "total": factor * (side + bottom) + bulk,
    }


def wall_cell(row: dict[str, Any]) -> float:
    """Radial size of the wall cells of a run's mesh [m] (recomputed for rows without it)."""
    if row.get("wall_cell_m") is not None:
        return float(row["wall_cell_m"])
    spec = CaseSpec(
        RADIUS_M,
        FILL_M,
        get_liquid("water-25C"),
        cells_per_radius=int(row["cells_per_radius"]),
        wall_grading=float(row.get("wall_grading") or 1.0),
        radial_cells=row.get("radial_cells"),
    )
    return wall_cell_size_m(spec)


def table(rows: list[dict[str, Any]]) -> dict[int, dict[float, dict[str, Any]]]:
    """Rows by cells per radius, then by step [s]."""
    result: dict[int, dict[float, dict[str, Any]]] = {}
    for row in rows:
        result.setdefault(int(row["cells_per_radius"]), {})[float(row["max_step_s"])] = row
    return result


def step_orders(rows: list[dict[str, Any]]) -> dict[int, float]:
    """Observed order in the time step of every mesh run at three steps."""
    orders = {}
    for cells, by_step in table(usable(rows)).items():
        steps = sorted(by_step)
        if len(steps) >= 3:
            values = [by_step[s]["damping_ratio"] for s in steps[:3]]
            orders[cells] = observed_order(values, [steps[1] / steps[0], steps[2] / steps[1]])
    return orders


def usable(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Runs that finished without parasitic currents (late Courant number within
    `MAX_LATE_COURANT`, frequency within `MAX_FREQUENCY_ERROR` of theory)."""
    return [
        r
        for r in rows
        if "failed" not in r
        and r.get("max_courant_late", 0.0) <= MAX_LATE_COURANT
        and abs(r["frequency_error"]) <= MAX_FREQUENCY_ERROR
    ]


def family(rows: list[dict[str, Any]], name: str, pooled_order: float) -> dict[str, Any]:
    """Time-step and mesh extrapolation of one mesh family (failed runs and runs with
    parasitic currents, see `usable`, are listed and left out)."""
    good = usable(rows)
    excluded = [r for r in rows if r not in good]
    runs = table(good)
    orders = step_orders(rows)
    step_order_used = min(max(pooled_order, 0.5), 4.0)
    per_mesh = {}
    for cells, by_step in sorted(runs.items()):
        steps = sorted(by_step)
        if len(steps) < 2:
            continue
        values = [by_step[s]["damping_ratio"] for s in steps]
        ratios = [steps[i + 1] / steps[i] for i in range(len(steps) - 1)]
        if len(values) >= 3:
            study = richardson(values[:3], ratios[:2])
        else:
            study = richardson(values[:2], ratios[:1], order=step_order_used)
        per_mesh[cells] = {
            "steps_s": steps,
            "damping_ratios": values,
            "frequencies_hz": [by_step[s]["frequency_hz"] for s in steps],
            "frequency_errors": [by_step[s]["frequency_error"] for s in steps],
            "cells": by_step[steps[0]]["cells"],
            "wall_cell_m": wall_cell(by_step[steps[0]]),
            "zero_step": study.to_dict(),
        }
    result: dict[str, Any] = {
        "name": name,
        "excluded": [
            {
                "cells_per_radius": r["cells_per_radius"],
                "step_s": r["max_step_s"],
                "max_courant_late": r.get("max_courant_late"),
                "frequency_error": r.get("frequency_error"),
                "damping_ratio": r.get("damping_ratio"),
                "failed": r.get("failed"),
            }
            for r in excluded
        ],
        "observed_step_orders": {str(k): v for k, v in orders.items()},
        "step_order_used": step_order_used,
        "meshes": {str(k): v for k, v in per_mesh.items()},
    }
    meshes = sorted(per_mesh, reverse=True)  # finest first
    if len(meshes) >= 2:
        values = [per_mesh[n]["zero_step"]["extrapolated"] for n in meshes[:3]]
        ratios = [meshes[i] / meshes[i + 1] for i in range(len(values) - 1)]
        mesh = richardson(values, ratios) if len(values) == 3 else richardson(values, ratios, 1.0)
        finest = per_mesh[meshes[0]]["zero_step"]
        total = combined_uncertainty(mesh.uncertainty, finest["uncertainty"])
        result["mesh"] = mesh.to_dict()
        result["damping_ratio"] = {
            "finest_mesh_zero_step": values[0],
            "richardson": mesh.extrapolated,
            "uncertainty": total,
            "interval": [values[0] - total, values[0] + total],
            "contains_richardson": abs(mesh.extrapolated - values[0]) <= total,
        }
    return result


def figure(
    uniform: dict[str, Any],
    graded: dict[str, Any],
    theory: dict[str, float],
    backward: list[dict[str, Any]],
) -> None:
    """ζ against the step for every mesh, the zero-step values, and theory."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axis = plt.subplots(figsize=(8, 4.6), layout="constrained")
    for study, style in ((uniform, "o--"), (graded, "s-")):
        for cells, mesh in study["meshes"].items():
            steps = [0.0, *(1e3 * s for s in mesh["steps_s"])]
            zeta = [mesh["zero_step"]["extrapolated"], *mesh["damping_ratios"]]
            label = f"{study['name']}, {cells} cells/radius ({mesh['cells']:,} cells)"
            (line,) = axis.plot(steps, zeta, style, label=label, markersize=5)
            axis.errorbar(
                [0.0],
                [mesh["zero_step"]["extrapolated"]],
                yerr=[[mesh["zero_step"]["uncertainty"]], [mesh["zero_step"]["uncertainty"]]],
                color=line.get_color(),
                capsize=3,
                alpha=0.5,
            )
    if backward:
        axis.plot(
            [1e3 * r["step_s"] for r in backward],
            [r["damping_ratio"] for r in backward],
            "kx",
            label="backward for U, uniform 8 cells/radius",
        )
    for key, colour in (("boundary_layer_theory", "k"), ("seed_eq2", "grey")):
        axis.axhline(theory[key], color=colour, linestyle=":", linewidth=1.2)
        axis.annotate(key.replace("_", " "), (2.05, theory[key]), fontsize=8, va="center")
    axis.set_xlabel("time step [ms] (0: extrapolated, with its GCI)")
    axis.set_ylabel("damping ratio ζ₁ [-]")
    axis.set_xlim(-0.1, 2.6)
    axis.grid(alpha=0.3)
    axis.legend(fontsize=7, loc="lower right")
    axis.set_title("CFD damping of the seed vial against mesh and time step (Euler, 2 s decay)")
    fig.savefig(DOCS / "figures" / "cfd_damping_study.png", dpi=110)


def main() -> None:
    uniform_rows = json.loads((DOCS / "cfd-damping-study.json").read_text())
    graded_path = DOCS / "cfd-damping-graded.json"
    graded_rows = json.loads(graded_path.read_text()) if graded_path.is_file() else []
    nu = get_liquid("water-25C").kinematic_viscosity_m2_s
    layer = stokes_layer_damping(RADIUS_M, FILL_M, nu)
    theory = {
        "boundary_layer_theory": layer["total"],
        "seed_eq2": damping_ratio_correlation(RADIUS_M, FILL_M, nu, "seed"),
        "sp106": damping_ratio_correlation(RADIUS_M, FILL_M, nu, "sp106"),
        "stephens": damping_ratio_correlation(RADIUS_M, FILL_M, nu, "stephens"),
    }
    measured = [
        p
        for p in (*step_orders(uniform_rows).values(), *step_orders(graded_rows).values())
        if math.isfinite(p)
    ]
    pooled = statistics.median(measured) if measured else 1.0
    uniform = family(uniform_rows, "uniform", pooled)
    graded = family(graded_rows, "wall-graded", pooled)
    backward_path = DOCS / "cfd-damping-backward.json"
    backward = json.loads(backward_path.read_text()) if backward_path.is_file() else []
    adaptive_path = DOCS / "cfd-damping-adaptive.json"
    adaptive = json.loads(adaptive_path.read_text()) if adaptive_path.is_file() else []
    document = {
        "case": "seed vial R 20.5 mm, h 39 mm, water 25 C / air, 3 deg tilt, 2 s free decay, "
        "Euler, fixed step, 3 pressure correctors, serial",
        "theory": theory,
        "boundary_layer_terms": layer,
        "uniform": uniform,
        "graded": graded,
        "backward": [
            {
                "cells_per_radius": r["cells_per_radius"],
                "step_s": r["max_step_s"],
                "damping_ratio": r["damping_ratio"],
                "frequency_hz": r["frequency_hz"],
                "calibration_error": r.get("calibration_error"),
            }
            for r in backward
        ],
        "adaptive": [
            {
                "cells_per_radius": r["cells_per_radius"],
                "failed": r.get("failed"),
                "damping_ratio": r.get("damping_ratio"),
            }
            for r in adaptive
        ],
    }
    (DOCS / "cfd-damping.json").write_text(json.dumps(document, indent=2) + "\n")
    figure(uniform, graded, theory, document["backward"])
    section = render(document)
    grading = json.loads((DOCS / "cfd-wall-grading.json").read_text())
    wall_section = render_stability(grading.get("instability_diagnosis", []))
    text = (DOCS / "cfd.md").read_text()
    for start, end, body in ((START, END, section), (WALL_START, WALL_END, wall_section)):
        if start in text:
            head, rest = text.split(start, 1)
            text = head + start + "\n" + body + "\n" + end + rest.split(end, 1)[1]
    (DOCS / "cfd.md").write_text(text)
    print(wall_section)
    print(section)


if __name__ == "__main__":
    main()
