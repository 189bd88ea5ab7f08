"""Markdown for README.md: the wall-stability table, the run-exclusion limits of the damping
study, and the damping study's conclusions and limits (its tables and figure:
cfd_damping_converged_report.py). Every number comes from the analysis document."""

from __future__ import annotations

import math
from typing import Any

#: A run whose largest Courant number stays above this after the start-up transient, or whose
#: first-mode frequency departs from linear theory by more than `MAX_FREQUENCY_ERROR` (every
#: clean run is within 0.5 %), carries parasitic currents: excluded from the extrapolation.
#: The late Courant number of a clean run grows as its wall cells thin (graded 16/radius 0.40
#: and 20/radius 0.54 at 2 ms, with a wall-force noise ratio of 0.01); the runs with parasitic
#: currents of session 2 stayed at 1.14-2.96 (session 3 used 0.5, which no run reached then).
MAX_LATE_COURANT = 1.0
MAX_FREQUENCY_ERROR = 0.01


def render_stability(rows: list[dict[str, Any]]) -> str:
    """The table of the wall-stability experiments (studies/cfd-damping/cfd_wall_stability.py)."""
    lines = [
        "| experiment (what it tests) | wall cell | min. determinant | max. aspect ratio | "
        "outcome | growth per step | largest Courant at the end |",
        "|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        wall = row["wall_cell_mm"]
        growth = row["growth_per_step"]
        outcome = (
            f"blew up after {row['steps_run']} steps"
            if row["blew_up"]
            else f"ran {row['steps_run']} steps"
        )
        lines.append(
            f"| {row['experiment']} ({row['tests']}) | "
            f"{'-' if wall is None else f'{wall:.3f} mm'} | {row['min_determinant']:.2g} | "
            f"{row['max_aspect_ratio']:.3g} | {outcome} | "
            f"{'-' if growth is None else f'{growth:.3g}'} | {row['courant_last']:.2g} |"
        )
    return "\n".join(lines)


def render_noise(rows: list[dict[str, Any]]) -> str:
    """The table of the wall-force noise experiments (cfd_parasitic_noise.py)."""

    def ratio(row: dict[str, Any], key: str) -> str:
        value = row.get(key)
        return "-" if value is None else f"{value:.2f}"

    lines = [
        "| experiment (what it changes) | outcome | pressure force noise 0.1–0.3 s / "
        "0.3–0.6 s | viscous force noise 0.1–0.3 s / 0.3–0.6 s | largest noise line |",
        "|---|---|---|---|---|",
    ]
    for row in rows:
        outcome = (
            f"blew up at {row['reached_s']:.3f} s"
            if row["blew_up"]
            else f"ran {row['reached_s']:g} s"
        )
        if row["blew_up"]:  # the record ends in the blow-up: its noise says nothing
            row = {k: v for k, v in row.items() if not k.startswith("noise")}
        peak = row.get("noise_peak_hz")
        lines.append(
            f"| {row['experiment']} ({row['tests']}) | {outcome} | "
            f"{ratio(row, 'noise_pressure_0.1_0.3s')} / {ratio(row, 'noise_pressure_0.3_0.6s')} | "
            f"{ratio(row, 'noise_viscous_0.1_0.3s')} / {ratio(row, 'noise_viscous_0.3_0.6s')} | "
            f"{'-' if peak is None else f'{peak:.0f} Hz'} |"
        )
    return "\n".join(lines)


def _f(value: float | None, digits: int = 4) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value:.{digits}f}"


def _ms(step_s: float) -> str:
    return f"{1e3 * step_s:g}"


def reported(document: dict[str, Any]) -> tuple[str, float, float, str]:
    """The damping reported for the seed vial: the mesh extrapolation of the wall-graded
    family with a grading of 0.25 when it has two meshes or more, else the zero-step value of
    the graded mesh with the thinnest wall cell. Returns (what, value, uncertainty, note)."""
    study = document["mesh_studies"].get("graded 0.25")
    if study is not None:
        cells = "/".join(str(c) for c in study["cells_per_radius"])
        return (
            f"wall-graded family (grading 0.25; {cells} cells per radius): finest mesh at zero "
            "step, mesh GCI and its step uncertainty combined",
            study["finest_zero_step"],
            study["uncertainty"],
            "mesh" if study["mesh"]["order_observed"] else "mesh order assumed",
        )
    graded = [
        (m["wall_cell_m"], family, cells, m)
        for family, members in document["families"].items()
        if family.startswith("graded")
        for cells, m in members.items()
        if "extrapolated" in m
    ]
    wall, family, cells, m = min(graded)
    return (
        f"{family} {cells}/radius (wall cell {1e3 * wall:.3f} mm) at zero step; the mesh "
        "part is not known",
        m["extrapolated"],
        m["uncertainty"],
        "no mesh extrapolation",
    )


def conclusions(document: dict[str, Any]) -> list[str]:
    """What the numbers say (every number from ``document``)."""
    theory = document["theory"]
    layer = theory["boundary_layer_theory"]
    check = document["estimator_check"]
    one = document["reference_one_term"]
    member = document["families"]["uniform"][str(document["reference_cells_per_radius"])]
    terms = member["two_term"]
    orders = [o["order"] for o in one["orders"]]
    lines = [
        "**What the study says.**",
        "",
        f"- **The estimator was part of the problem.** On the uniform meshes the fit and the log "
        f"decrement of the probe elevation (window from 0.5 s) differ by up to "
        f"{check['probe_worst_ratio']:.1f}× ({check['probe_worst_case']}); on the wall force "
        f"they agree within {100 * check['force_worst_relative']:.0f} % in every uniform run. "
        "The session-2 numbers, taken from the probe elevation, carried that noise into every "
        "extrapolation. Amplitude dependence: the wall-force fits over the first and the second "
        "half of the window (from 0.5 s) differ by "
        f"{100 * check['force_halves_median_relative']:.0f} % in the median run and "
        f"{100 * check['force_halves_worst_relative']:.0f} % at most (Euler runs used below).",
        f"- **The step does not reach Euler's first order.** The observed order of the 8/radius "
        f"mesh rises from {orders[0]:.2f} to {orders[-1]:.2f} as the step falls to "
        f"{_ms(min(one['steps_s']))} ms. The two-term form ζ₀ + a√Δt + bΔt fits every step "
        f"(rms {terms['residual_rms']:.0e})"
        + (
            f" and predicted the finest from the coarser ones within "
            f"{abs(terms['prediction_error']):.0e}"
            if "prediction_error" in terms
            else ""
        )
        + ": a half-order term dominates at small steps, so the observed order tends to ½, not "
        "1. A √Δt error is what a pressure-correction splitting produces next to a no-slip wall "
        "(a numerical boundary layer of thickness √(νΔt); E & Liu, SIAM J. Numer. Anal. 32 "
        "(1995) 1017) — a likely origin in interFoam's PISO loop, not one proven here. "
        "Single-term Richardson cannot handle it (order below ½, factor 3: "
        f"±{one['zero_step']['uncertainty']:.4f}); the two-term extrapolation can "
        f"(±{member['uncertainty']:.4f}).",
    ]
    cn = document["crank_nicolson"]
    euler = dict(zip(one["steps_s"], one["values"], strict=True))
    if cn:
        pairs = "; ".join(
            f"{_ms(float(s))} ms: {_f(v)} (Euler {_f(euler.get(float(s)))})" for s, v in cn.items()
        )
        study = document.get("crank_nicolson_steps")
        if study is None:
            order = "with fewer than three usable steps it gives no order of its own."
        else:
            zero = study["zero_step"]
            order = (
                f"over its finest three steps the observed order is "
                f"{_f(study['orders'][-1]['order'], 2)}, and single-term Richardson gives "
                f"{_f(zero['extrapolated'])} ± {_f(zero['uncertainty'])} (factor "
                f"{zero['safety_factor']:g}), against Euler's two-term "
                f"{_f(member['extrapolated'])} ± {_f(member['uncertainty'])}."
            )
        low, high = max(cn.values()), min(euler.values())
        z, u = member["extrapolated"], member["uncertainty"]
        overlap = z + u >= low and z - u <= high
        lines.append(
            f"- **Crank–Nicolson 0.9** damps less than Euler at the same step ({pairs}; at 2 ms "
            "the amplitude grows), and its values rise as the step shrinks while Euler's fall: "
            f"if both are monotonic, the zero-step value lies between {low:.4f} (CN's largest) "
            f"and {high:.4f} (Euler's smallest), and Euler's two-term value {z:.4f} ± {u:.4f} "
            + ("overlaps" if overlap else "does NOT overlap")
            + f" that range; {order}"
        )
    uniform = document["mesh_studies"].get("uniform")
    delta = document["boundary_layer_terms"]["stokes_layer_thickness_m"]
    if uniform is not None:
        walls = [m["wall_cell_m"] for m in document["families"]["uniform"].values()]
        lines.append(
            f"- **Uniform meshes converge to the wrong damping.** Their zero-step values "
            f"({' / '.join(_f(v) for v in uniform['mesh']['values'])}, finest first) "
            f"extrapolate in the mesh to {_f(uniform['mesh']['extrapolated'])}, "
            f"{layer / uniform['mesh']['extrapolated']:.1f}× below the boundary-layer theory: "
            f"their wall cells ({1e3 * min(walls):.1f}–{1e3 * max(walls):.1f} mm) are "
            f"{min(walls) / delta:.0f}–{max(walls) / delta:.0f} times the Stokes layer, whose "
            "dissipation they miss; refining them uniformly converges the dissipation of an "
            "unresolved layer."
        )
    what, value, uncertainty, note = reported(document)
    low, high = value - uncertainty, value + uncertainty
    inside = low <= layer <= high
    lines.append(
        f"- **Reported CFD damping of the seed vial: ζ = {value:.4f} ± {uncertainty:.4f}** "
        f"({what}; {note}). The interval {low:.4f}–{high:.4f} "
        + ("contains" if inside else "does not contain")
        + f" the clean-cylinder boundary-layer theory ({layer:.4f}; Case & Parkinson 1957, "
        f"Miles 1958): CFD − theory = {value - layer:+.4f}"
        + (f" ({(value - layer) / uncertainty:+.1f} U)." if uncertainty > 0 else ".")
        + f" The empirical correlations ({theory['sp106']:.4f}–{theory['seed_eq2']:.4f}) lie "
        "above both: they fit experiments with contact-line and surface losses, which this CFD "
        "(σ = 0, no contact-angle model) does not have."
    )
    return lines


def limits(document: dict[str, Any]) -> list[str]:
    """What limits the uncertainty, with the numbers."""
    graded_runs = [r for r in document["runs"] if r["family"].startswith("graded")]
    clean_at_2ms = {
        (r["family"], r["cells_per_radius"])
        for r in graded_runs
        if r["step_s"] == 0.002 and not r["problem"]
    }
    graded_runs = [r for r in graded_runs if (r["family"], r["cells_per_radius"]) in clean_at_2ms]
    smallest = min((r["step_s"] for r in graded_runs if not r["problem"]), default=math.nan)
    noise: dict[float, list[float]] = {}
    for run in graded_runs:
        if math.isfinite(run.get("force_noise_ratio", math.nan)) and not run["failed"]:
            noise.setdefault(run["step_s"], []).append(run["force_noise_ratio"])
    by_step = "; ".join(
        f"{_ms(step)} ms: {min(v):.2f}–{max(v):.2f}"
        for step, v in sorted(noise.items(), reverse=True)
    )
    lines = [
        "**What limits the uncertainty.**",
        "",
        "- **Wall-graded meshes cannot take small steps.** The high-frequency noise of the wall "
        "force (above 15 Hz, relative to the slosh signal) of the graded meshes that run "
        f"cleanly at 2 ms grows as the step shrinks ({by_step}): parasitic currents in the thin "
        "wall cells, as in the wall-stability study above. No graded run below "
        f"{_ms(smallest)} ms is clean, so no graded mesh has the "
        "three steps a step extrapolation of its own needs; each borrows the step-error shape "
        "of the uniform 8/radius mesh (its slope c from two steps, or the mean slope of its "
        "kind from one), and that shape differs between meshes (the uniform meshes' slopes "
        "are "
        + ", ".join(
            f"{_f(m['slope'], 2)} ({c}/radius)"
            for c, m in document["families"]["uniform"].items()
            if "slope" in m
        )
        + ").",
    ]
    for family, members in document["families"].items():
        if not family.startswith("graded"):
            continue
        for cells, m in sorted(members.items(), key=lambda kv: int(kv[0])):
            if "distance" in m:
                lines.append(
                    f"  {family} {cells}/radius: extrapolated over {_f(m['distance'])} "
                    f"(ζ at {_ms(min(m['steps_s']))} ms minus zero step), uncertainty "
                    f"{_f(m['uncertainty'])}."
                )
    for family, members in document["families"].items():
        invalid = {cells: m for cells, m in members.items() if "invalid" in m}
        if not invalid:
            continue
        courant = {
            (str(r["cells_per_radius"]), r["step_s"]): r["max_courant_late"]
            for r in document["runs"]
            if r["family"] == family
        }
        parts = []
        for cells, m in invalid.items():
            values = ", ".join(
                f"{_f(v)} at {_ms(float(k))} ms (late Courant number "
                f"{courant[(cells, float(k))]:.2f})"
                for k, v in sorted(m["values"].items(), key=lambda kv: -float(kv[0]))
            )
            parts.append(f"{cells}/radius: ζ = {values}")
        step = min(float(x) for m in invalid.values() for x in m["values"])
        kept = [
            (int(c), o["values"][str(step)])
            for c, o in members.items()
            if c not in invalid and str(step) in o["values"]
        ]
        line = (
            f"- **The finest meshes break the pattern.** {family}, " + "; ".join(parts) + ": "
            "their damping does not fall as the step shrinks (a mesh run at one step sits "
            "among such meshes), so the step-error shape of the uniform reference does not "
            "transfer to them and they have no zero-step value."
        )
        if kept:
            c, v = max(kept)
            finest = ", ".join(
                f"{_f(m['values'][str(step)])} ({cells}/radius)"
                for cells, m in invalid.items()
                if str(step) in m["values"]
            )
            line += (
                f" At {_ms(step)} ms they damp {finest}, against {_f(v)} on the {c}/radius "
                "mesh: the family is not in the asymptotic range of the mesh, and the "
                "transferred interval rests on the coarser meshes only (session 4, below)."
            )
        lines.append(line)
    study = document["mesh_studies"].get("graded 0.25")
    if study is not None:
        values = study["mesh"]["values"]
        lines.append(
            f"- **Mesh uncertainty** of the graded family: zero-step values "
            f"{' / '.join(_f(v) for v in values)} (finest first), {study['mesh']['behaviour']}, "
            f"mesh GCI {_f(study['mesh']['uncertainty'])} (factor "
            f"{study['mesh']['safety_factor']:g}): the largest part of the reported uncertainty."
        )
    member = document["families"]["uniform"][str(document["reference_cells_per_radius"])]
    parts = member["uncertainty_parts"]
    lines.append(
        f"- **The estimator** on the 8/radius mesh: ζ₀ ranges over "
        f"{_f(2 * member['uncertainty_parts']['estimator_spread'])} between the wall-force "
        "estimators (fit or log decrement, window from 0.3, 0.5 or 0.7 s)"
        + (
            ": the largest part of that mesh's uncertainty."
            if parts["estimator_spread"] >= max(v for v in parts.values() if math.isfinite(v))
            else "."
        )
    )
    return lines
