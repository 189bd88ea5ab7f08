"""Session 4 of the CFD damping study: the wall-graded family (grading 0.25) at every step it
ran, and the one-change variants, from the wall force.

Reads docs/cfd-damping-converge.json (the runs) and docs/cfd-damping-estimators.json (every
finished run re-estimated from its wall force: the damped-sine fit from 0.5 s, and the force's
noise ratio above 15 Hz), and writes the text between ``<!-- damping-session4:start -->`` and
``<!-- damping-session4:end -->`` of docs/cfd.md and docs/cfd-damping-session4.json: the
tables show what each mesh and step gave, and the finest three meshes at 1 ms are put through
Richardson/GCI in the mesh (no step extrapolation: below 1 ms the graded meshes are noisy).

Run: PYTHONPATH=src python benchmarks/cfd_damping_session4.py
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from cfd_damping_report import MAX_LATE_COURANT

from sloshkit.cfd.force_signal import NOISE_RATIO_LIMIT as NOISE_LIMIT

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
WORK = "sloshkit-cfd-damping3"
START, END = "<!-- damping-session4:start -->", "<!-- damping-session4:end -->"
STEPS_MS = (4.0, 2.0, 1.0, 0.5)
MESHES = (9, 12, 16, 20, 24, 28)


def load() -> tuple[dict[str, dict[str, Any]], dict[str, dict[str, Any]]]:
    """The runs by key, and their wall-force estimates by key."""
    runs = {r["key"]: r for r in json.loads((DOCS / "cfd-damping-converge.json").read_text())}
    estimates = {
        r["case"]: r
        for r in json.loads((DOCS / "cfd-damping-estimators.json").read_text())
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
        f"above {NOISE_LIMIT} or a late Courant number above {MAX_LATE_COURANT:g}:",
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


def finest_meshes(
    runs: dict[str, dict[str, Any]], estimates: dict[str, dict[str, Any]], step_ms: float
) -> dict[str, Any] | None:
    """Richardson/GCI (`sloshkit.cfd.convergence.richardson`) over the three finest graded
    meshes with a clean run at one step, and the finest one's change from twice that step."""
    from sloshkit.cfd.convergence import richardson

    def clean(key: str) -> bool:
        estimate = estimates.get(key)
        return (
            estimate is not None
            and math.isfinite(estimate["primary"])
            and estimate["force_noise_ratio"] <= NOISE_LIMIT
            and (runs[key].get("max_courant_late") or 0.0) <= MAX_LATE_COURANT
        )

    cells = [n for n in MESHES[::-1] if clean(key_of(n, step_ms))][:3]  # finest first
    if len(cells) < 3:
        return None
    values = [estimates[key_of(n, step_ms)]["primary"] for n in cells]
    study = richardson(values, [cells[0] / cells[1], cells[1] / cells[2]])
    coarse_key = key_of(cells[0], 2 * step_ms)
    return {
        "cells_per_radius": cells,
        "step_ms": step_ms,
        "mesh": study.to_dict(),
        "step_change_finest": (
            values[0] - estimates[coarse_key]["primary"] if clean(coarse_key) else None
        ),
    }


def summary(study: dict[str, Any]) -> str:
    """One finest-meshes estimate as a sentence."""
    mesh = study["mesh"]
    cells = "/".join(str(c) for c in study["cells_per_radius"])
    low, high = (
        mesh["extrapolated"] - mesh["uncertainty"],
        mesh["extrapolated"] + mesh["uncertainty"],
    )
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
        f"**ζ = {mesh['extrapolated']:.4f} ± {mesh['uncertainty']:.4f}** (interval "
        f"{low:.4f}–{high:.4f})."
    )
    change = study["step_change_finest"]
    if change is not None:
        text += (
            f" From {2 * study['step_ms']:g} to {study['step_ms']:g} ms the finest of them changes "
            f"by {change:+.5f}."
        )
    return text


def main() -> None:
    runs, estimates = load()
    studies = [finest_meshes(runs, estimates, step) for step in (2.0, 1.0)]
    studies = [s for s in studies if s is not None]
    section = render(runs, estimates) + "\n\n" + "\n".join(summary(s) for s in studies)
    (DOCS / "cfd-damping-session4.json").write_text(json.dumps(studies, indent=2) + "\n")
    path = DOCS / "cfd.md"
    text = path.read_text()
    if START in text:
        head, rest = text.split(START, 1)
        text = head + START + "\n" + section + "\n" + END + rest.split(END, 1)[1]
        path.write_text(text)
    print(section)


if __name__ == "__main__":
    main()
