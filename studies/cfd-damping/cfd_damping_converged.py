"""The damping of the seed vial with an uncertainty: step and mesh extrapolation of every run
of the damping study, estimated from the wall force (data/cfd-damping-estimators.json).

1. Every run's damping ratio is re-estimated from its wall force (`PRIMARY` of
   studies/cfd-damping/cfd_damping_estimators.py); the estimator's own scatter is recorded.
2. The coarse uniform mesh (8 cells per radius) is run at steps 2 ms to 62.5 us: its observed
   order in the step (Celik et al. 2008) over each triple of steps, and Richardson from the
   finest triple (`convergence.richardson`), give its zero-step value z8.
3. Every other mesh, run at fewer and larger steps, is extrapolated by *transferring* the
   shape of the coarse mesh's step error: a straight line z_M(dt) = a + c z8(dt) through its
   runs (at steps the coarse mesh also ran), evaluated at z8(0). The uncertainty adds the
   propagated GCI of z8(0) (times c), and how well one line fits (the spread of the
   predictions of its pairs of steps; a mesh with one pair takes the largest relative spread
   seen, a mesh with one step takes c from the others).
4. The zero-step values of a mesh family are extrapolated in the mesh (Richardson/GCI).

Used by cfd_damping_analysis.py (data/cfd-damping.json and the section of README.md).
"""

from __future__ import annotations

import json
import math
import statistics
from pathlib import Path
from typing import Any

from cfd_damping_estimators import PRIMARY, STARTS_S
from cfd_damping_report import MAX_FREQUENCY_ERROR, MAX_LATE_COURANT
from cfd_damping_transfer import finish_transfers, transfer
from convergence import (
    combined_uncertainty,
    fit_error_terms,
    observed_order,
    richardson,
)

from sloshkit.cfd.force_signal import NOISE_RATIO_LIMIT
from sloshkit.cfd.mesh import wall_cell_size_m
from sloshkit.cfd.spec import CaseSpec
from sloshkit.model.liquids import get_liquid

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
OLD_WORK, NEW_WORK = "sloshkit-cfd-damping", "sloshkit-cfd-damping3"
REFERENCE = 8  # cells per radius of the mesh whose step series is extended
#: Exponents of the step error: a sqrt(dt) term and Euler's dt (see `two_term`).
EXPONENTS = (0.5, 1.0)
#: Largest ratio of high- to low-frequency wall force (`noise_ratio`) of a clean run: the
#: limit `cfd analyse` warns above (clean runs stay at or below 0.23, runs with parasitic
#: currents at or above 0.88).
MAX_FORCE_NOISE = NOISE_RATIO_LIMIT
SAFETY = 1.25  # Roache's factor for a form whose orders are supported by the data
#: The estimators whose spread is the estimator's uncertainty: the wall force (where fit and
#: logdec agree within a few per cent at every step), fit and logdec, three window starts.
ESTIMATOR_KEYS = [f"force/{method}/{start:g}" for method in ("fit", "logdec") for start in STARTS_S]
#: Cross-check only: the surface tilt (interface cells only; fit and logdec disagree more).
CROSS_CHECK_KEYS = [
    f"tilt/{method}/{start:g}" for method in ("fit", "logdec") for start in STARTS_S
]


def load_runs() -> list[dict[str, Any]]:
    """Every run of the study (sessions 2 and 3) with its family and re-estimated damping."""
    estimates = {
        (r["work"], r["case"]): r
        for r in json.loads((DATA / "cfd-damping-estimators.json").read_text())
    }
    runs = []
    sources = (
        ("cfd-damping-study.json", "uniform", OLD_WORK, ""),
        ("cfd-damping-graded.json", "graded 0.1", OLD_WORK, "-graded"),
        ("cfd-damping-converge.json", None, NEW_WORK, None),
    )
    for name, family, work, suffix in sources:
        path = DATA / name
        for row in json.loads(path.read_text()) if path.is_file() else []:
            step_ms = round(row.get("max_step_s", row.get("step_ms", 0) * 1e-3) * 1e3, 6)
            case = (
                row["key"]
                if "key" in row
                else f"n{row['cells_per_radius']}-dt{step_ms:g}ms{suffix}"
            )
            grading = float(row.get("wall_grading") or 1.0)
            scheme = row.get("ddt_scheme") or "Euler"
            label = family or (
                f"graded {grading:g}" if grading < 1.0 else "uniform" if scheme == "Euler"
                else "uniform CN 0.9"
            )  # fmt: skip
            if grading < 1.0 and scheme != "Euler":
                label += " CN 0.9"
            if row.get("momentum_predictor"):
                label += " predictor"
            if row.get("surface_refinement", 2) != 2:
                label += f" band R/{row['surface_refinement']}N"
            if row.get("tilt_deg", 3.0) != 3.0:
                label += f" tilt {row['tilt_deg']:g} deg"
            estimate = estimates.get((work, case), {})
            runs.append(
                {
                    "family": label,
                    "case": case,
                    "cells_per_radius": int(row["cells_per_radius"]),
                    "radial_cells": row.get("radial_cells"),
                    "cells": row.get("cells"),
                    "wall_cell_m": row.get("wall_cell_m") or wall_cell(row),
                    "step_s": step_ms * 1e-3,
                    "ddt_scheme": scheme,
                    "failed": row.get("failed"),
                    "max_courant_late": row.get("max_courant_late"),
                    "frequency_error": row.get("frequency_error"),
                    "cpu_s": row.get("cpu_s"),
                    "zeta_probe_fit": row.get("damping_ratio"),
                    "zeta": estimate.get("primary", math.nan),
                    "estimator_scatter": estimate.get("scatter", math.nan),
                    "force_noise_ratio": estimate.get("force_noise_ratio", math.nan),
                    "estimates": estimate.get("estimates", {}),
                }
            )
    return sorted(runs, key=lambda r: (r["family"], r["cells_per_radius"], -r["step_s"]))


def wall_cell(row: dict[str, Any]) -> float:
    """Radial size of the wall cells of a run's mesh [m] (for rows that did not record it)."""
    spec = CaseSpec(
        0.0205,
        0.039,
        get_liquid("water-25C"),
        cells_per_radius=int(row["cells_per_radius"]),
        wall_grading=float(row.get("wall_grading") or 1.0),
        radial_cells=row.get("radial_cells"),
    )
    return wall_cell_size_m(spec)


def problem(run: dict[str, Any]) -> str | None:
    """Why a run is left out of the extrapolation (None: usable)."""
    if run["failed"]:
        return f"failed: {run['failed']}"
    if (run["max_courant_late"] or 0.0) > MAX_LATE_COURANT:
        return f"parasitic currents: largest Courant number {run['max_courant_late']:.2f} late"
    if run["force_noise_ratio"] > MAX_FORCE_NOISE:
        return (
            f"parasitic currents: wall-force noise above 15 Hz {run['force_noise_ratio']:.1f}× "
            "the slosh signal"
        )
    if abs(run["frequency_error"] or 0.0) > MAX_FREQUENCY_ERROR:
        return f"frequency {100 * run['frequency_error']:+.1f} % from theory"
    if not math.isfinite(run["zeta"]):
        return "no free decay in the wall force (the amplitude grows or the fit fails)"
    return None


def series(
    runs: list[dict[str, Any]], family: str, cells: int, key: str = ""
) -> dict[float, float]:
    """Damping by step of one mesh (usable runs; ``key`` picks an estimator, else primary)."""
    out = {}
    for run in runs:
        if run["family"] == family and run["cells_per_radius"] == cells and not problem(run):
            value = run["estimates"].get(key, math.nan) if key else run["zeta"]
            if math.isfinite(value):
                out[run["step_s"]] = float(value)
    return out


def step_study(values: dict[float, float]) -> dict[str, Any]:
    """Observed orders of consecutive triples of halved steps, Richardson of the finest."""
    steps = sorted(values, reverse=True)
    orders = []
    for a, b, c in zip(steps, steps[1:], steps[2:], strict=False):
        orders.append(
            {
                "steps_s": [a, b, c],
                "order": observed_order([values[c], values[b], values[a]], [b / c, a / b]),
            }
        )
    finest = steps[-3:][::-1]
    study = richardson([values[s] for s in finest], [finest[1] / finest[0], finest[2] / finest[1]])
    return {
        "steps_s": steps,
        "values": [values[s] for s in steps],
        "orders": orders,
        "zero_step": study.to_dict(),
    }


def two_term(values: dict[float, float]) -> dict[str, Any]:
    """Zero-step value from z(dt) = z0 + a sqrt(dt) + b dt (`fit_error_terms`) over all steps,
    with its checks: the fit over the coarser steps predicting the finest (a test of the form)
    and the half-range of z0 over the fits of the finest 3, 4, ... steps."""
    steps = sorted(values)
    fit = fit_error_terms([values[s] for s in steps], steps, EXPONENTS)
    out: dict[str, Any] = {
        "extrapolated": fit.extrapolated,
        "coefficients": list(fit.coefficients),
        "exponents": list(EXPONENTS),
        "residual_rms": fit.residual_rms,
        "points": len(steps),
    }
    if len(steps) >= 4:
        coarse = fit_error_terms([values[s] for s in steps[1:]], steps[1:], EXPONENTS)
        out["prediction_of_finest"] = coarse.predict(steps[0])
        out["finest"] = values[steps[0]]
        out["prediction_error"] = coarse.predict(steps[0]) - values[steps[0]]
        subsets = [
            fit_error_terms([values[s] for s in steps[:k]], steps[:k], EXPONENTS).extrapolated
            for k in range(3, len(steps) + 1)
        ]
        out["zero_step_of_finest_subsets"] = subsets
        out["subset_spread"] = 0.5 * (max(subsets) - min(subsets))
    return out


def own_fit(runs: list[dict[str, Any]], family: str, cells: int) -> dict[str, Any]:
    """Two-term zero-step value of a mesh run at three steps or more, with its uncertainty:
    `SAFETY` x root-sum-square of the subset spread, the prediction error of the finest step
    and the spread over the wall-force estimators."""
    values = series(runs, family, cells)
    terms = two_term(values)
    by_estimator = {}
    for key in ESTIMATOR_KEYS:
        other = series(runs, family, cells, key)
        if set(values) <= set(other):
            by_estimator[key] = two_term({s: other[s] for s in values})["extrapolated"]
    spread = (
        0.5 * (max(by_estimator.values()) - min(by_estimator.values()))
        if by_estimator
        else math.nan
    )
    parts = {
        "subset_spread": terms.get("subset_spread", math.nan),
        "prediction_error": abs(terms.get("prediction_error", math.nan)),
        "estimator_spread": spread,
    }
    return {
        "extrapolated": terms["extrapolated"],
        "uncertainty": SAFETY
        * combined_uncertainty(*(v for v in parts.values() if math.isfinite(v))),
        "two_term": terms,
        "zero_step_by_estimator": by_estimator,
        "uncertainty_parts": parts,
    }


def _split(name: str) -> tuple[str, int]:
    family, cells = name.split("|")
    return family, int(cells)


def _kind(name: str) -> str:
    """uniform or graded."""
    return name.split("|")[0].split(" ")[0]


def mesh_study(family: dict[str, dict[str, Any]]) -> dict[str, Any] | None:
    """Richardson in the mesh over a family's zero-step values (finest = most cells per
    radius; spacing ~ 1 / cells per radius), with the step uncertainty of the finest mesh."""
    usable = {int(n): r for n, r in family.items() if "extrapolated" in r}
    meshes = sorted(usable, reverse=True)[:3]
    if len(meshes) < 2:
        return None
    values = [usable[n]["extrapolated"] for n in meshes]
    ratios = [meshes[i] / meshes[i + 1] for i in range(len(meshes) - 1)]
    study = richardson(values, ratios) if len(values) == 3 else richardson(values, ratios, 1.0)
    step = usable[meshes[0]]["uncertainty"]
    total = combined_uncertainty(study.uncertainty, step)
    return {
        "cells_per_radius": meshes,
        "mesh": study.to_dict(),
        "finest_zero_step": values[0],
        "step_uncertainty_finest": step,
        "uncertainty": total,
        "interval": [values[0] - total, values[0] + total],
    }


def estimator_check(runs: list[dict[str, Any]]) -> dict[str, Any]:
    """Fit against log decrement (window from 0.5 s) on the probe elevation and on the wall
    force, over the usable uniform Euler runs: the worst ratio and the worst relative gap."""
    worst_ratio, worst_case, worst_force = 1.0, "", 0.0
    for run in runs:
        e = run["estimates"]
        if run["family"] != "uniform" or problem(run):
            continue
        fit, logdec = e.get("elevation/fit/0.5", math.nan), e.get("elevation/logdec/0.5", math.nan)
        if fit > 0 and logdec > 0 and max(fit / logdec, logdec / fit) > worst_ratio:
            worst_ratio = max(fit / logdec, logdec / fit)
            worst_case = (
                f"{run['cells_per_radius']}/radius at {1e3 * run['step_s']:g} ms: "
                f"{fit:.4f} against {logdec:.4f}"
            )
        force = abs(e["force/fit/0.5"] - e["force/logdec/0.5"]) / e["force/fit/0.5"]
        worst_force = max(worst_force, force)
    halves = [
        (r["estimates"]["force/fit/first-half"], r["estimates"]["force/fit/second-half"])
        for r in runs
        if not problem(r) and r["family"] != "uniform CN 0.9"
    ]
    relative_halves = [abs(a - b) / (0.5 * (a + b)) for a, b in halves if a > 0 and b > 0]
    return {
        "probe_worst_ratio": worst_ratio,
        "probe_worst_case": worst_case,
        "force_worst_relative": worst_force,
        "force_halves_worst_relative": max(relative_halves),
        "force_halves_median_relative": statistics.median(relative_halves),
    }


#: The families and steps the step-error transfer below is built for; session 4's variants
#: (momentum predictor, finer surface band, larger tilt, Crank-Nicolson on a graded mesh) and its
#: 4 ms steps are analysed on their own (studies/cfd-damping/cfd_damping_graded_family.py).
TRANSFER_FAMILIES = ("uniform", "uniform CN 0.9", "graded 0.1", "graded 0.25")
LARGEST_TRANSFER_STEP_S = 2e-3


def transfer_runs(runs: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The runs of `TRANSFER_FAMILIES` at steps up to `LARGEST_TRANSFER_STEP_S`."""
    return [
        r
        for r in runs
        if r["family"] in TRANSFER_FAMILIES and r["step_s"] <= LARGEST_TRANSFER_STEP_S * 1.000001
    ]


def analyse(theory: dict[str, float]) -> dict[str, Any]:
    """Every number of the converged damping study (module docstring)."""
    runs = transfer_runs(load_runs())
    reference = series(runs, "uniform", REFERENCE)
    study = step_study(reference)
    cross_check = {}
    for key in CROSS_CHECK_KEYS:
        values = series(runs, "uniform", REFERENCE, key)
        if set(reference) <= set(values):
            cross_check[key] = two_term(values)["extrapolated"]
    meshes: dict[str, dict[float, float]] = {}
    for run in runs:
        if run["family"] != "uniform CN 0.9":
            name = f"{run['family']}|{run['cells_per_radius']}"
            meshes.setdefault(name, series(runs, run["family"], run["cells_per_radius"]))
    meshes = {n: v for n, v in meshes.items() if v}
    fits = {
        name: own_fit(runs, *_split(name)) for name, values in meshes.items() if len(values) >= 3
    }
    # A second scheme on the reference mesh: Crank-Nicolson's single-term Richardson, when its
    # order is observed, must agree with Euler's two-term value; their gap adds to the
    # reference's uncertainty (and so to every transferred value).
    cn = series(runs, "uniform CN 0.9", REFERENCE)
    cn_study = step_study(cn) if len(cn) >= 3 else None
    reference_fit = fits[f"uniform|{REFERENCE}"]
    if cn_study is not None and cn_study["zero_step"]["order_observed"]:
        parts = reference_fit["uncertainty_parts"]
        parts["scheme_difference"] = abs(
            reference_fit["extrapolated"] - cn_study["zero_step"]["extrapolated"]
        )
        reference_fit["uncertainty"] = SAFETY * combined_uncertainty(
            *(v for v in parts.values() if math.isfinite(v))
        )
    own, u8 = reference_fit, reference_fit["uncertainty"]
    # The reference of each kind (uniform, graded): its mesh with the most steps.
    references = {"uniform": f"uniform|{REFERENCE}"}
    for name in sorted(fits, key=lambda n: (-len(meshes[n]), n)):
        references.setdefault(_kind(name), name)
    results: dict[str, dict[str, Any]] = {}
    groups = []
    for kind in sorted({_kind(n) for n in meshes}):
        ref = references.get(kind, references["uniform"])
        zr, ur = fits[ref]["extrapolated"], fits[ref]["uncertainty"]
        group = {
            n: transfer(v, meshes[ref], zr, ur) | {"reference": ref}
            for n, v in meshes.items()
            if _kind(n) == kind and n != ref
        }
        for n, r in group.items():
            if r["points"] < 2:
                r["points"], r["steps_s"] = 1, sorted(meshes[n])[:1]
        groups.append((group, ref, zr, ur))
    relative = [
        r["fit_spread"] / abs(r["distance"])
        for group, *_ in groups
        for r in group.values()
        if r["points"] >= 3 and math.isfinite(r["fit_spread"]) and r["distance"] and r["slope"] > 0
    ]
    worst = max(relative) if relative else 0.5
    for group, ref, zr, ur in groups:
        finish_transfers(group, meshes[ref], zr, ur, meshes, worst)
        results.update(group)
        results[ref] = {"steps_s": sorted(meshes[ref]), "points": len(meshes[ref]), **fits[ref]}
    for name, r in results.items():
        if name in fits and "slope" in r:  # own fit first, the transfer as its check
            fit = fits[name]
            r["transfer_extrapolated"] = r.pop("extrapolated")
            r["transfer_uncertainty"] = r.pop("uncertainty")
            if fit["two_term"]["points"] == 3:  # no test of the form on this mesh
                fit["uncertainty_parts"]["transfer_difference"] = abs(
                    fit["extrapolated"] - r["transfer_extrapolated"]
                )
                fit["uncertainty"] = SAFETY * combined_uncertainty(
                    *(v for v in fit["uncertainty_parts"].values() if math.isfinite(v))
                )
            r.update(fit)
    families: dict[str, dict[str, Any]] = {}
    for name, r in sorted(results.items(), key=lambda kv: (kv[0][0] != "u", kv[0])):
        family, cells = name.split("|")
        families.setdefault(family, {})[cells] = r
        sample = next(
            x for x in runs if x["family"] == family and str(x["cells_per_radius"]) == cells
        )
        r.update(
            cells=sample["cells"],
            wall_cell_m=sample["wall_cell_m"],
            radial_cells=sample["radial_cells"],
            values={str(k): v for k, v in sorted(meshes[name].items())},
            frequency_errors=[
                x["frequency_error"]
                for x in runs
                if x["family"] == family and str(x["cells_per_radius"]) == cells
                and not problem(x)
            ],
        )  # fmt: skip
    return {
        "crank_nicolson_steps": cn_study,
        "estimator_check": estimator_check(runs),
        "theory": theory,
        "reference_cells_per_radius": REFERENCE,
        "primary_estimator": "/".join(f"{p:g}" if isinstance(p, float) else p for p in PRIMARY),
        "reference_one_term": study,
        "reference_zero_step_by_estimator": own["zero_step_by_estimator"],
        "reference_zero_step_tilt_cross_check": cross_check,
        "reference_uncertainty": u8,
        "crank_nicolson": {str(k): v for k, v in sorted(cn.items())},
        "families": families,
        "mesh_studies": {f: mesh_study(m) for f, m in families.items()},
        "runs": [
            {k: v for k, v in run.items() if k != "estimates"} | {"problem": problem(run)}
            for run in runs
        ],
    }
