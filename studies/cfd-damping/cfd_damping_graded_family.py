"""The wall-graded family (grading 0.25) of the CFD damping study at every step it ran
(sessions 4 and 5), the one-change variants, and the damping with its mesh and step
uncertainty, from the wall force.

Reads data/cfd-damping-converge.json (the runs) and data/cfd-damping-estimators.json (every
finished run re-estimated from its wall force: the damped-sine fit from 0.5 s, and the force's
noise ratio above 15 Hz), and writes the text between ``<!-- damping-graded-family:start -->``
and ``<!-- damping-graded-family:end -->`` of README.md and
data/cfd-damping-graded-family.json:

- the tables: what each mesh and step gave;
- at each step, Richardson/GCI in the mesh over the three finest meshes with a clean run;
- the damping with both uncertainties (Celik et al. 2008, as in
  `convergence`): first Richardson in the step on each of the three finest meshes
  with three clean steps, then Richardson/GCI in the mesh on their step-free values, the
  uncertainties combined by root-sum-square.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_damping_graded_family.py
"""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path
from typing import Any

from cfd_damping_report import MAX_LATE_COURANT

from sloshkit.cfd.force_signal import NOISE_RATIO_LIMIT as NOISE_LIMIT
from sloshkit.cfd.force_signal import STEP_ALTERNATION_LIMIT as ALTERNATION_LIMIT

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
WORK = "sloshkit-cfd-damping3"
START = "<!-- damping-graded-family:start -->"
END = "<!-- damping-graded-family:end -->"
STEPS_MS = (4.0, 2.0, 1.0, 0.7, 0.5)
#: The step of the mesh study of the reported damping [ms], and the steps of the step studies
#: (finest first): the steps at which the finest meshes run clean.
MESH_STEP_MS = 1.0
EXTRAPOLATION_STEPS_MS = (0.7, 1.0, 2.0)
MESHES = (9, 12, 16, 20, 24, 28)


def load() -> tuple[dict[str, dict[str, Any]], dict[str, dict[str, Any]]]:
    """The runs by key, and their wall-force estimates by key."""
    runs = {r["key"]: r for r in json.loads((DATA / "cfd-damping-converge.json").read_text())}
    estimates = {
        r["case"]: r
        for r in json.loads((DATA / "cfd-damping-estimators.json").read_text())
        if r["work"] == WORK
    }
    return runs, estimates


def cell(key: str, runs: dict[str, dict[str, Any]], estimates: dict[str, dict[str, Any]]) -> str:
    """One run as a table cell: damping, and why it is not clean when it is not."""
    run = runs.get(key)
    if run is None:
        return "not run"
    if run.get("failed"):
        return "failed" if "interFoam stopped" in run["failed"] else "stopped (noise)"
    estimate = estimates.get(key)
    if estimate is None:
        return "-"
    zeta, noise = estimate["primary"], estimate["force_noise_ratio"]
    courant = run.get("max_courant_late") or 0.0
    text = f"{zeta:.4f}" if math.isfinite(zeta) else "no decay"
    notes = []
    if noise > NOISE_LIMIT:
        notes.append(f"noise {noise:.1f}")
    alternation = estimate.get("force_step_alternation", 0.0)
    if noise <= NOISE_LIMIT and alternation > ALTERNATION_LIMIT:
        notes.append(f"alternation {alternation:.3f}")
    if courant > MAX_LATE_COURANT:
        notes.append(f"Courant {courant:.1f}")
    return text + (f" ({', '.join(notes)})" if notes else "")


def key_of(cells: int, step_ms: float, suffix: str = "") -> str:
    """The run key of the graded 0.25 mesh with ``cells`` per radius (annulus cells as run)."""
    radial = {9: 7, 12: 10, 16: 13, 20: 16, 24: 19, 28: 22}[cells]
    return f"n{cells}-dt{step_ms:g}ms-g0.25r{radial}{suffix}"


def render(runs: dict[str, dict[str, Any]], estimates: dict[str, dict[str, Any]]) -> str:
    """The session-4 tables (markdown)."""
    lines = [
        "Damping ratio from the wall force (damped-sine fit from 0.5 s) of the wall-graded "
        "family (grading 0.25), by mesh and step; in parentheses, a wall-force noise ratio "
        f"above {NOISE_LIMIT}, a step alternation above {ALTERNATION_LIMIT:g} or a late Courant "
        f"number above {MAX_LATE_COURANT:g}:",
        "",
        "| cells per radius (cells) | " + " | ".join(f"{s:g} ms" for s in STEPS_MS) + " |",
        "|---|" + "---|" * len(STEPS_MS),
    ]
    for cells in MESHES:
        sample = runs.get(key_of(cells, 2.0), {})
        count = f"{sample['cells']:,}" if sample.get("cells") else "-"
        row = [cell(key_of(cells, s), runs, estimates) for s in STEPS_MS]
        lines.append(f"| {cells} ({count}) | " + " | ".join(row) + " |")
    variants = [
        ("12/radius, 2 ms", key_of(12, 2.0), [
            ("vertical cells near the surface halved (band R/4N)", "-s4"),
            ("tilt 6° instead of 3° (twice the amplitude)", "-tilt6"),
        ]),
        ("16/radius, 2 ms", key_of(16, 2.0), [("band R/4N", "-s4")]),
        ("9/radius, 1 ms", key_of(9, 1.0), [("tilt 6°", "-tilt6")]),
        ("9/radius, 0.5 ms", key_of(9, 0.5), [
            ("tilt 6°", "-tilt6"),
            ("momentum predictor", "-mp"),
        ]),
        ("16/radius, 1 ms", key_of(16, 1.0), [("momentum predictor", "-mp")]),
    ]  # fmt: skip
    lines += [
        "",
        "One change at a time against the family's run:",
        "",
        "| mesh and step | the family's run | change | with the change |",
        "|---|---|---|---|",
    ]
    for label, base, changes in variants:
        for what, suffix in changes:
            changed = base + suffix
            lines.append(
                f"| {label} | {cell(base, runs, estimates)} | {what} | "
                f"{cell(changed, runs, estimates)} |"
            )
    cn = "n16-dt1ms-cn-g0.25r13"
    if cn in runs:
        lines.append(
            f"| 16/radius, 1 ms | {cell(key_of(16, 1.0), runs, estimates)} | Crank–Nicolson 0.9 "
            f"instead of Euler | {cell(cn, runs, estimates)} |"
        )
    return "\n".join(lines)


def clean(key: str, runs: dict[str, dict[str, Any]], estimates: dict[str, dict[str, Any]]) -> bool:
    """Whether a run finished with a decay, a wall force without parasitic noise or
    step-to-step alternation, and a late Courant number within the study's limits."""
    estimate = estimates.get(key)
    return (
        key in runs
        and estimate is not None
        and math.isfinite(estimate["primary"])
        and estimate["force_noise_ratio"] <= NOISE_LIMIT
        and estimate.get("force_step_alternation", math.inf) <= ALTERNATION_LIMIT
        and (runs[key].get("max_courant_late") or 0.0) <= MAX_LATE_COURANT
    )


def finest_meshes(
    runs: dict[str, dict[str, Any]], estimates: dict[str, dict[str, Any]], step_ms: float
) -> dict[str, Any] | None:
    """Richardson/GCI (`convergence.richardson`) over the three finest graded
    meshes with a clean run at one step, and the finest one's change from the next larger
    step of `STEPS_MS` it ran cleanly."""
    from convergence import richardson

    cells = [n for n in MESHES[::-1] if clean(key_of(n, step_ms), runs, estimates)][:3]
    if len(cells) < 3:
        return None
    values = [estimates[key_of(n, step_ms)]["primary"] for n in cells]
    study = richardson(values, [cells[0] / cells[1], cells[1] / cells[2]])
    larger = [s for s in STEPS_MS if s > step_ms and clean(key_of(cells[0], s), runs, estimates)]
    coarse_step = min(larger) if larger else None
    change = (
        values[0] - estimates[key_of(cells[0], coarse_step)]["primary"]
        if coarse_step is not None
        else None
    )
    return {
        "cells_per_radius": cells,
        "step_ms": step_ms,
        "mesh": study.to_dict(),
        "step_change_finest": change,
        "step_change_from_ms": coarse_step,
    }


def step_and_mesh(
    runs: dict[str, dict[str, Any]],
    estimates: dict[str, dict[str, Any]],
    by_step: dict[float, dict[str, Any]],
) -> dict[str, Any] | None:
    """The damping of the finest mesh with its mesh and step uncertainty (Celik et al. 2008;
    Roache 1998), each direction with the solutions it has.

    - Mesh: Richardson/GCI over the three finest graded meshes with a clean run at
      `MESH_STEP_MS` (`finest_meshes`); the uncertainty taken is the larger of its GCI and
      that of the same study at every other step of `EXTRAPOLATION_STEPS_MS` where three fine
      meshes ran clean (a lucky monotonic triplet must not hide the oscillation the family
      shows at another step).
    - Step, on the finest of them: Richardson over its clean runs at the steps of
      `EXTRAPOLATION_STEPS_MS` (three: observed order, factor 1.25, or 3 × half the range when
      oscillatory; two: Euler's formal order 1 assumed, factor 3).
    - The same step study on every other mesh with three clean steps, as evidence of how the
      step error behaves.

    The reported damping is the finest mesh's solution at `MESH_STEP_MS` (both GCI bands are
    about it), with the root-sum-square (`combined_uncertainty`) of the two uncertainties.
    """
    from convergence import combined_uncertainty, richardson

    mesh_study = by_step.get(MESH_STEP_MS)
    if mesh_study is None:
        return None
    finest = mesh_study["cells_per_radius"][0]

    def step_study(cells: int) -> dict[str, Any] | None:
        steps = [s for s in EXTRAPOLATION_STEPS_MS if clean(key_of(cells, s), runs, estimates)]
        if MESH_STEP_MS not in steps or len(steps) < 2:
            return None
        values = [estimates[key_of(cells, s)]["primary"] for s in steps]
        ratios = [b / a for a, b in itertools.pairwise(steps)]
        order = 1.0 if len(steps) == 2 else None  # Euler's formal order when only two
        return {"steps_ms": steps, **richardson(values, ratios, order).to_dict()}

    on_finest = step_study(finest)
    if on_finest is None:
        return None
    # the step study is about the finest step; the reported solution is at MESH_STEP_MS
    if on_finest["steps_ms"][0] != MESH_STEP_MS:
        return None
    evidence = {
        str(n): study
        for n in MESHES[::-1]
        if n != finest and (study := step_study(n)) is not None and len(study["steps_ms"]) == 3
    }
    value = mesh_study["mesh"]["values"][0]
    others = [by_step.get(s) for s in EXTRAPOLATION_STEPS_MS]
    mesh_uncertainty = max(
        [mesh_study["mesh"]["uncertainty"]]
        + [o["mesh"]["uncertainty"] for o in others if o is not None]
    )
    total = combined_uncertainty(mesh_uncertainty, on_finest["uncertainty"])
    return {
        "cells_per_radius": finest,
        "step_ms": MESH_STEP_MS,
        "mesh": mesh_study,
        "mesh_uncertainty": mesh_uncertainty,
        "step": on_finest,
        "step_on_other_meshes": evidence,
        "damping_ratio": value,
        "uncertainty": total,
        "interval": [value - total, value + total],
    }


def summary(study: dict[str, Any]) -> str:
    """One finest-meshes estimate as a sentence."""
    mesh = study["mesh"]
    cells = "/".join(str(c) for c in study["cells_per_radius"])
    finest = mesh["values"][0]
    low, high = finest - mesh["uncertainty"], finest + mesh["uncertainty"]
    how = (
        f"{mesh['behaviour']}, so Celik's uncertainty is {mesh['safety_factor']:g} × half their "
        "range"
        if mesh["behaviour"] == "oscillatory"
        else f"{mesh['behaviour']}, order {mesh['order']:.2f}"
        + (" (observed)" if mesh["order_observed"] else " (bound, assumed)")
    )
    text = (
        f"- At {study['step_ms']:g} ms the three finest graded meshes with a clean run ({cells} "
        f"cells per radius) give {' / '.join(f'{v:.4f}' for v in mesh['values'])}: {how}: "
        f"**ζ = {finest:.4f} ± {mesh['uncertainty']:.4f}** (interval {low:.4f}–{high:.4f}"
        + (
            f"; Richardson estimate {mesh['extrapolated']:.4f})."
            if mesh["behaviour"] != "oscillatory"
            else ")."
        )
    )
    change = study["step_change_finest"]
    if change is not None:
        text += (
            f" From {study['step_change_from_ms']:g} to {study['step_ms']:g} ms the finest of "
            f"them changes by {change:+.5f}."
        )
    return text


def describe_step_study(study: dict[str, Any]) -> str:
    """One step study as a phrase."""
    steps = "/".join(f"{x:g}" for x in study["steps_ms"])
    values = " / ".join(f"{v:.4f}" for v in study["values"])
    if study["behaviour"] == "oscillatory":
        how = f"oscillatory, {study['safety_factor']:g} × half the range"
    elif study["behaviour"] == "two-level":
        how = f"two steps, order {study['order']:g} assumed, factor {study['safety_factor']:g}"
    else:
        how = f"{study['behaviour']}, order {study['order']:.2f} " + (
            "(observed)" if study["order_observed"] else "(outside 0.5–4: bound, assumed)"
        )
    return (
        f"at {steps} ms {values}: {how}; step-free {study['extrapolated']:.4f}, "
        f"uncertainty ± {study['uncertainty']:.4f}"
    )


def step_and_mesh_summary(result: dict[str, Any]) -> str:
    """The reported damping with both uncertainties, as a list (markdown)."""
    mesh = result["mesh"]["mesh"]
    cells = "/".join(str(c) for c in result["mesh"]["cells_per_radius"])
    low, high = result["interval"]
    lines = [
        f"- **The damping with its mesh and step uncertainty** ({result['cells_per_radius']} "
        f"cells per radius at {result['step_ms']:g} ms):",
        f"  - mesh ({cells}/radius at {result['step_ms']:g} ms): ± {mesh['uncertainty']:.4f}; "
        f"taken as ± {result['mesh_uncertainty']:.4f}, the largest GCI of the finest meshes at "
        "any clean step (the bullets above);",
        f"  - step ({result['cells_per_radius']}/radius) "
        + describe_step_study(result["step"])
        + ";",
    ]
    for cells_per_radius, study in result["step_on_other_meshes"].items():
        lines.append(
            f"  - step on {cells_per_radius}/radius, for comparison: "
            + describe_step_study(study)
            + ";"
        )
    lines.append(
        f"  - **ζ = {result['damping_ratio']:.4f} ± {result['uncertainty']:.4f}** (root-sum-square "
        f"of the two; interval {low:.4f}–{high:.4f})."
    )
    return "\n".join(lines)


def main() -> None:
    runs, estimates = load()
    by_step = {
        step: study
        for step in (2.0, 1.0, 0.7)
        if (study := finest_meshes(runs, estimates, step)) is not None
    }
    studies = list(by_step.values())
    combined = step_and_mesh(runs, estimates, by_step)
    section = render(runs, estimates) + "\n\n" + "\n".join(summary(s) for s in studies)
    if combined is not None:
        section += "\n" + step_and_mesh_summary(combined)
    record = {"finest_meshes_by_step": studies, "step_and_mesh": combined}
    (DATA / "cfd-damping-graded-family.json").write_text(json.dumps(record, indent=2) + "\n")
    path = STUDY / "README.md"
    text = path.read_text()
    if START in text:
        head, rest = text.split(START, 1)
        text = head + START + "\n" + section + "\n" + END + rest.split(END, 1)[1]
        path.write_text(text)
    print(section)


if __name__ == "__main__":
    main()
