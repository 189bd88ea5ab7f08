"""Markdown and figure of the converged damping study (cfd_damping_converged.py):
every number is taken from the analysis document, none typed by hand."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from cfd_damping_report import (
    MAX_FREQUENCY_ERROR,
    MAX_LATE_COURANT,
    _f,
    _ms,
    conclusions,
    limits,
)


def _mesh_name(family: str, cells: str, member: dict[str, Any]) -> str:
    radial = member.get("radial_cells")
    return f"{family} {cells}/radius" + (f", {radial} annulus cells" if radial else "")


def render_runs(document: dict[str, Any]) -> list[str]:
    """Table of every run: the session-2 estimate (probe elevation, fit from the largest peak)
    next to the wall-force estimate and its scatter."""
    lines = [
        "| mesh | step [ms] | scheme | ζ probe elevation (session 2) | ζ wall force "
        "(fit from 0.5 s) | estimator scatter | f₁ vs theory | left out because |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for run in document["runs"]:
        scheme = "CN 0.9" if run["ddt_scheme"].startswith("Crank") else run["ddt_scheme"]
        error = run["frequency_error"]
        lines.append(
            f"| {run['family']} {run['cells_per_radius']}/radius | {_ms(run['step_s'])} | "
            f"{scheme} | {_f(run['zeta_probe_fit'])} | {_f(run['zeta'])} | "
            f"{_f(run['estimator_scatter'])} | "
            f"{'-' if error is None else f'{100 * error:+.2f} %'} | "
            f"{(run['problem'] or '').split(' (')[0]} |"
        )
    return lines


def render_reference(document: dict[str, Any]) -> list[str]:
    """The step series of the reference mesh: local orders, one-term GCI, two-term fit."""
    one = document["reference_one_term"]
    member = document["families"]["uniform"][str(document["reference_cells_per_radius"])]
    terms, parts = member["two_term"], member["uncertainty_parts"]
    orders = ", ".join(
        f"{_f(o['order'], 2)} ({'/'.join(_ms(s) for s in o['steps_s'])} ms)" for o in one["orders"]
    )
    zero = one["zero_step"]
    a, b = terms["coefficients"]
    lines = [
        f"- **Steps on the uniform {document['reference_cells_per_radius']}/radius mesh** "
        f"({', '.join(_ms(s) for s in one['steps_s'])} ms; ζ = "
        f"{' / '.join(_f(v) for v in one['values'])}): the observed order of each triple of "
        f"halved steps is {orders}. It rises as the step shrinks but stays below 1: Euler's "
        "first order is not reached. Celik's single-term Richardson on the finest triple "
        f"(order {'observed' if zero['order_observed'] else 'below 0.5, so 0.5 assumed with'} "
        f"factor {zero['safety_factor']:g}) gives {_f(zero['extrapolated'])} ± "
        f"{_f(zero['uncertainty'])}.",
        f"- **Two error terms, √Δt and Δt**: ζ(Δt) = ζ₀ + a·√Δt + b·Δt fits all "
        f"{terms['points']} steps with ζ₀ = **{_f(terms['extrapolated'])}**, a = {a:.4f} s^-½, "
        f"b = {b:.3f} s^-1 (rms misfit {terms['residual_rms']:.1e}). A √Δt term makes the "
        "observed order drift from 0 towards ½, as measured.",
    ]
    if "prediction_of_finest" in terms:
        lines.append(
            f"  Test of the form: fitted to the coarser steps only, it predicts "
            f"{_f(terms['prediction_of_finest'])} at {_ms(min(one['steps_s']))} ms, measured "
            f"{_f(terms['finest'])}; ζ₀ of the fits over the finest 3, 4, … steps: "
            f"{' / '.join(_f(v) for v in terms['zero_step_of_finest_subsets'])}."
        )
    estimators = document["reference_zero_step_by_estimator"]
    tilt = document["reference_zero_step_tilt_cross_check"]
    lines.append(
        f"  ζ₀ by estimator (wall force, fit and logdec, windows from 0.3/0.5/0.7 s): "
        f"{_f(min(estimators.values()))}–{_f(max(estimators.values()))}; from the surface tilt "
        f"(cross-check): {_f(min(tilt.values()))}–{_f(max(tilt.values()))}. Uncertainty of ζ₀: "
        f"{document['safety']:g} × root-sum-square of "
        + ", ".join(f"the {k.replace('_', ' ')} ({_f(v)})" for k, v in parts.items())
        + f" = **{_f(document['reference_uncertainty'])}** (the scheme difference: Euler's "
        "two-term value against Crank–Nicolson's Richardson value, below)."
    )
    cn = document["crank_nicolson"]
    if cn:
        lines.append(
            "- **Crank–Nicolson 0.9** (U and alpha; same mesh): "
            + "; ".join(f"{_ms(float(k))} ms: ζ = {_f(v)}" for k, v in cn.items())
            + ". Runs where the wall force gives no free decay (the amplitude grows at 2 ms) "
            "are in the table above."
        )
    return lines


def _how(member: dict[str, Any]) -> str:
    if "invalid" in member:
        return f"no zero-step value: {member['invalid']}"
    if "two_term" in member:
        parts = ", ".join(
            f"{k.replace('_', ' ')} {_f(v)}"
            for k, v in member["uncertainty_parts"].items()
            if math.isfinite(v)
        )
        return f"two-term fit of {member['two_term']['points']} steps ({parts})"
    if member.get("slope_from"):
        ref = member.get("reference", "").replace("|", " ") + "/radius"
        return f"one step, from {ref}; slope {_f(member['slope'], 2)} = {member['slope_from']}"
    ref = member.get("reference", "").replace("|", " ") + "/radius"
    return f"transfer from {ref}, slope c = {_f(member['slope'], 2)}"


def render_meshes(document: dict[str, Any]) -> list[str]:
    """Zero-step value of every mesh and the mesh extrapolation of each family."""
    lines = [
        "| mesh | cells | wall cell | steps [ms] | ζ at the finest step | zero step ± U | "
        "from | transferred from its kind's reference mesh (check) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for family, members in document["families"].items():
        for cells, m in sorted(members.items(), key=lambda kv: int(kv[0])):
            wall = m.get("wall_cell_m")
            finest = m["values"][str(min(m["steps_s"]))] if m["values"] else None
            lines.append(
                f"| {_mesh_name(family, cells, m)} | {m['cells'] or 0:,} | "
                f"{'-' if wall is None else f'{1e3 * wall:.3f} mm'} | "
                f"{', '.join(_ms(s) for s in sorted(m['steps_s'], reverse=True))} | "
                f"{_f(finest)} | **{_f(m.get('extrapolated'))} ± {_f(m.get('uncertainty'))}** | "
                f"{_how(m)} | {_f(m.get('transfer_extrapolated'))} |"
            )
    out = [*lines, ""]
    for family, study in document["mesh_studies"].items():
        if study is None:
            out.append(f"- **{family}**: one mesh only, no extrapolation in the mesh.")
            continue
        mesh = study["mesh"]
        order = (
            f"order {_f(mesh['order'], 2)} ({'observed' if mesh['order_observed'] else 'assumed'})"
            if mesh["behaviour"] != "oscillatory"
            else "oscillatory (no order; factor 3 on half the range)"
        )
        out.append(
            f"- **{family}** ({'/'.join(str(c) for c in study['cells_per_radius'])} cells per "
            f"radius): zero-step values {' / '.join(_f(v) for v in mesh['values'])}; "
            f"{mesh['behaviour']}, {order}, Richardson value {_f(mesh['extrapolated'])}, mesh "
            f"GCI {_f(mesh['uncertainty'])}; with the step uncertainty of the finest mesh "
            f"({_f(study['step_uncertainty_finest'])}): **ζ = {_f(study['finest_zero_step'])} ± "
            f"{_f(study['uncertainty'])}**."
        )
    return out


def render(document: dict[str, Any]) -> str:
    """The Markdown of the damping section."""
    theory = document["theory"]
    layer = document["boundary_layer_terms"]
    out = [
        "Boundary-layer theory of a clean cylinder (Stokes layers on the side wall and the "
        f"bottom, δ = {1e3 * layer['stokes_layer_thickness_m']:.3f} mm, plus the bulk): "
        f"ζ = {layer['side_wall']:.5f} (side wall) + {layer['bottom']:.5f} (bottom) + "
        f"{layer['bulk']:.5f} (bulk) = **{theory['boundary_layer_theory']:.4f}**; the "
        f"correlations give {theory['seed_eq2']:.4f} (seed eq. 2), {theory['sp106']:.4f} "
        f"(NASA SP-106) and {theory['stephens']:.4f} (Stephens et al.).",
        "",
        f"Runs (left out: a run that blew up, a largest Courant number above "
        f"{MAX_LATE_COURANT} late in the run, a frequency more than "
        f"{100 * MAX_FREQUENCY_ERROR:g} % from theory, or no decay in the wall force):",
        "",
        *render_runs(document),
        "",
        *render_reference(document),
        "",
        *render_meshes(document),
        "",
        *conclusions(document),
        "",
        *limits(document),
    ]
    return "\n".join(out)


def figure(document: dict[str, Any], path: Path) -> None:
    """ζ against the step (log axis) for every mesh, the two-term fit of the reference mesh,
    the zero-step values with their uncertainty, and theory."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, (axis, zero_axis) = plt.subplots(
        1, 2, figsize=(10, 4.6), layout="constrained", gridspec_kw={"width_ratios": [3, 1.2]}
    )
    labels = []
    for family, members in document["families"].items():
        for cells, m in sorted(members.items(), key=lambda kv: int(kv[0])):
            steps = sorted(float(s) for s in m["values"])
            (line,) = axis.plot(
                [1e3 * s for s in steps],
                [m["values"][str(s)] for s in steps],
                "o-" if family == "uniform" else "s--",
                markersize=4,
                label=_mesh_name(family, cells, m),
            )
            if "extrapolated" in m:
                labels.append(_mesh_name(family, cells, m))
                zero_axis.errorbar(
                    [len(labels) - 1],
                    [m["extrapolated"]],
                    yerr=[[m["uncertainty"]], [m["uncertainty"]]],
                    fmt="o" if family == "uniform" else "s",
                    color=line.get_color(),
                    capsize=3,
                )
    member = document["families"]["uniform"][str(document["reference_cells_per_radius"])]
    terms = member["two_term"]
    grid = np.geomspace(1e-5, 2.2e-3, 100)
    a, b = terms["coefficients"]
    axis.plot(1e3 * grid, terms["extrapolated"] + a * np.sqrt(grid) + b * grid, "k:", lw=1,
              label="ζ₀ + a√Δt + bΔt (uniform 8/radius)")  # fmt: skip
    cn = document["crank_nicolson"]
    if cn:
        axis.plot([1e3 * float(s) for s in cn], list(cn.values()), "kx", label="CN 0.9, 8/radius")
    theory = document["theory"]
    for ax in (axis, zero_axis):
        ax.axhline(theory["boundary_layer_theory"], color="k", linestyle="--", linewidth=1)
        ax.grid(alpha=0.3)
    axis.set_xscale("log")
    axis.set_xlabel("time step [ms]")
    axis.set_ylabel("damping ratio ζ₁ (wall force) [-]")
    axis.legend(fontsize=6.5, loc="upper left")
    axis.set_title("CFD damping of the seed vial against step and mesh (dashed: theory)")
    zero_axis.set_xticks(range(len(labels)), labels, rotation=70, fontsize=6.5)
    zero_axis.set_title("zero step ± U")
    fig.savefig(path, dpi=110)
