"""Why wall-graded O-grids diverge: short, discriminating interFoam runs at rest.

Each experiment writes the seed vial's case (R 20.5 mm, h 39 mm) with a given mesh, changes
one thing (the fluid, the schemes, the solver, the geometry), runs a few fixed steps serially
and records the largest Courant number of every step. A discrete instability shows as
geometric growth from round-off (Courant 1e-17 at the first steps); the growth factor per
step is the slope of log(Courant) over the steps where it lies between 1e-14 and 100.

Results go to the ``instability_diagnosis`` entry of data/cfd-wall-grading.json (the v1
entries there are kept). README.md discusses them.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_wall_stability.py [--only NAME ...]
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
from collections.abc import Callable
from pathlib import Path

import numpy as np

from sloshkit.cfd.case import CaseSpec, FreeDecay
from sloshkit.cfd.mesh import wall_cell_size_m
from sloshkit.cfd.run import openfoam_environment, write_case
from sloshkit.model.liquids import get_liquid

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
QUALITY = {
    "max_aspect_ratio": r"Max aspect ratio = ([0-9.eE+-]+)",
    "min_determinant": r"Cell determinant \(wellposedness\) : minimum: ([0-9.eE+-]+)",
    "max_non_orthogonality_deg": r"Mesh non-orthogonality Max: ([0-9.eE+-]+)",
    "max_skewness": r"Max skewness = ([0-9.eE+-]+)",
    "cells": r"^\s*cells:\s+(\d+)",
}
Edit = Callable[[Path], None]


def replace(path: str, old: str, new: str) -> Edit:
    """An edit of one case file (``old`` must occur in it)."""

    def edit(case: Path) -> None:
        target = case / path
        text = target.read_text()
        if old not in text:
            raise ValueError(f"{old!r} not in {path}")
        target.write_text(text.replace(old, new, 1))

    return edit


ALL_AIR = replace(
    "system/setFieldsDict", "volScalarFieldValue alpha.water 1", "volScalarFieldValue alpha.water 0"
)
ALL_WATER = replace("system/setFieldsDict", "alpha.water 0 )", "alpha.water 1 )")


def zero_viscosity(case: Path) -> None:
    """Both phases inviscid."""
    target = case / "constant" / "transportProperties"
    target.write_text(re.sub(r"(\n\s*nu\s+)[^;]+;", r"\g<1>0;", target.read_text()))


def exact_pressure(case: Path) -> None:
    """p_rgh by PCG to 1e-14, no relative tolerance."""
    target = case / "system" / "fvSolution"
    text = target.read_text().replace("solver          GAMG;", "solver PCG; preconditioner DIC;")
    target.write_text(
        text.replace(
            "tolerance       1e-07;\n        relTol          0.05;", "tolerance 1e-14; relTol 0;"
        )
    )


def flat_box(grading: float) -> Edit:
    """A Cartesian box of the vial's size with the same thin cells at one wall (x = 21 mm)."""

    def edit(case: Path) -> None:
        target = case / "system" / "blockMeshDict"
        head = target.read_text().split("scale")[0]
        target.write_text(
            head + "scale 1;\nvertices\n(\n"
            " (-20 -16 0) (15 -16 0) (21 -16 0) (21 16 0) (15 16 0) (-20 16 0)\n"
            " (-20 -16 70) (15 -16 70) (21 -16 70) (21 16 70) (15 16 70) (-20 16 70)\n);\n"
            "blocks\n(\n hex (0 1 4 5 6 7 10 11) (9 8 40) simpleGrading (1 1 1)\n"
            f" hex (1 2 3 4 7 8 9 10) (12 8 40) simpleGrading ({grading} 1 1)\n);\n"
            "edges ();\nboundary\n(\n"
            " atmosphere { type patch; faces ((6 7 10 11) (7 8 9 10)); }\n);\n"
            "defaultPatch { name walls; type wall; }\n"
        )

    return edit


def chain(*edits: Edit) -> Edit:
    """Several edits in turn."""

    def edit(case: Path) -> None:
        for step in edits:
            step(case)

    return edit


GRADED = {"radial_cells": 12, "wall_grading": 0.05}  # wall cells 0.038 mm, 8 cells per quarter
#: name -> (what it tests, mesh/case keywords, edit)
EXPERIMENTS: dict[str, tuple[str, dict[str, object], Edit | None]] = {
    "two-phase, graded 0.038 mm": ("the failure as seen (water and air at rest)", GRADED, None),
    "two-phase, graded 0.038 mm, surface tension on": (
        "capillary time-step limit (the row above has sigma = 0, sloshkit's default)",
        {**GRADED, "surface_tension": True},
        None,
    ),
    "all water": ("no interface at all (one fluid)", GRADED, ALL_WATER),
    "all air": ("no interface, the light fluid only", GRADED, ALL_AIR),
    "all water, inviscid": ("no viscous term", GRADED, chain(ALL_WATER, zero_viscosity)),
    "all water, step 0.1 ms": ("time step 10x smaller", {**GRADED, "step": 1e-4}, ALL_WATER),
    "all water, step 10 ms": ("time step 10x larger", {**GRADED, "step": 1e-2}, ALL_WATER),
    "all air, 1 pressure corrector": (
        "growth per pressure corrector?",
        GRADED,
        chain(ALL_AIR, replace("system/fvSolution", "nCorrectors     3", "nCorrectors     1")),
    ),
    "all air, p_rgh solved to 1e-14": (
        "solver residual as the source",
        GRADED,
        chain(ALL_AIR, exact_pressure),
    ),
    "all air, zeroGradient p_rgh at walls": (
        "fixedFluxPressure wall condition",
        GRADED,
        chain(ALL_AIR, replace("0/p_rgh", "fixedFluxPressure", "zeroGradient")),
    ),
    "all air, momentum predictor": (
        "momentum predictor on",
        GRADED,
        chain(
            ALL_AIR, replace("system/fvSolution", "momentumPredictor no;", "momentumPredictor yes;")
        ),
    ),
    "all air, 2 non-orthogonal correctors": (
        "non-orthogonal correction",
        GRADED,
        chain(
            ALL_AIR,
            replace(
                "system/fvSolution", "nNonOrthogonalCorrectors 0", "nNonOrthogonalCorrectors 2"
            ),
        ),
    ),
    "all air, flat wall, same thin cells": (
        "curvature: a Cartesian box with the same 0.04 mm graded wall cells",
        GRADED,
        chain(ALL_AIR, flat_box(0.05)),
    ),
    "all air, uniform O-grid": ("reference", {"radial_cells": None, "wall_grading": 1.0}, ALL_AIR),
    "all air, graded 0.26 mm": ("mild grading", {"radial_cells": 6, "wall_grading": 0.3}, ALL_AIR),
    "all air, graded 0.093 mm": (
        "8 cells per quarter",
        {"radial_cells": 8, "wall_grading": 0.1},
        ALL_AIR,
    ),
    "all air, graded 0.093 mm, 12 per quarter": (
        "more cells around",
        {"cells_per_radius": 12, "radial_cells": 8, "wall_grading": 0.1},
        ALL_AIR,
    ),
    "all air, graded 0.038 mm, 16 per quarter": (
        "more cells around, thinner wall cells",
        {"cells_per_radius": 16, "radial_cells": 12, "wall_grading": 0.05},
        ALL_AIR,
    ),
    "all air, graded 0.121 mm, 9 per quarter": (
        "coarse level of the graded family",
        {"cells_per_radius": 9, "radial_cells": 6, "wall_grading": 0.1},
        ALL_AIR,
    ),
    "all air, graded 0.069 mm, 16 per quarter": (
        "fine level of the graded family",
        {"cells_per_radius": 16, "radial_cells": 11, "wall_grading": 0.1},
        ALL_AIR,
    ),
    "two-phase, graded 0.093 mm, 8 per quarter": (
        "the unstable mesh with the interface",
        {"radial_cells": 8, "wall_grading": 0.1, "steps": 40},
        None,
    ),
    "two-phase, graded 0.105 mm, 10 per quarter, tilted 3 deg": (
        "the graded mesh that blew up at a 1 ms step in the damping study",
        {"cells_per_radius": 10, "radial_cells": 7, "wall_grading": 0.1, "tilt": 3.0, "steps": 150},
        None,
    ),
    "same, no interface compression (cAlpha 0)": (
        "the interface-compression flux at the thin wall cells",
        {"cells_per_radius": 10, "radial_cells": 7, "wall_grading": 0.1, "tilt": 3.0, "steps": 150},
        replace("system/fvSolution", "cAlpha          1;", "cAlpha          0;"),
    ),
    "same, 90 deg contact angle on the wall": (
        "the wall condition of alpha (contact-angle normal instead of zeroGradient)",
        {"cells_per_radius": 10, "radial_cells": 7, "wall_grading": 0.1, "tilt": 3.0, "steps": 150},
        replace(
            "0/alpha.water",
            "type            zeroGradient;",
            "type constantAlphaContactAngle; theta0 90; limit gradient; value uniform 0;",
        ),
    ),
    "two-phase, graded 0.093 mm, 12 per quarter, tilted 3 deg": (
        "the graded mesh of the damping study, as it runs",
        {"cells_per_radius": 12, "radial_cells": 8, "wall_grading": 0.1, "tilt": 3.0, "steps": 60},
        None,
    ),
}


def tool(case: Path, *command: str) -> tuple[str, int]:
    """Run an OpenFOAM tool in ``case``; its output and exit code."""
    done = subprocess.run(
        command, cwd=case, env=openfoam_environment(), capture_output=True, text=True
    )
    return done.stdout + done.stderr, done.returncode


def growth_per_step(courant: list[float]) -> float | None:
    """Geometric growth factor per step of the largest Courant number: least squares on its
    logarithm from the first step above 1e-19 (round-off) to the first step above 1 (or the
    end; a record that starts above 0.1, after a tilted start, is fitted whole); below 1 it
    decays. None with fewer than two such steps."""
    start = next((k for k, c in enumerate(courant) if c > 1e-19), None)
    if start is None:
        return None
    stop = len(courant) - 1
    if courant[start] < 0.1:  # from round-off or spurious currents: up to order one
        stop = next((k for k, c in enumerate(courant) if k > start and c > 1.0), stop)
    window = [math.log(c) for c in courant[start : stop + 1] if c > 0.0]
    if len(window) < 2:
        return None
    return float(math.exp(np.polyfit(np.arange(len(window)), window, 1)[0]))


def experiment(name: str, work: Path) -> dict[str, object]:
    """Run one experiment of `EXPERIMENTS`; its settings and outcome."""
    purpose, settings, edit = EXPERIMENTS[name]
    options = dict(settings)
    steps = int(options.pop("steps", 25))  # type: ignore[call-overload]
    step = float(options.pop("step", 1e-3))  # type: ignore[arg-type]
    tilt = float(options.pop("tilt", 0.0))  # type: ignore[arg-type]
    spec = CaseSpec(
        0.0205,
        0.039,
        get_liquid("water-25C"),
        FreeDecay(math.radians(tilt)),
        cells_per_radius=int(options.pop("cells_per_radius", 8)),  # type: ignore[call-overload]
        end_time_s=steps * step,
        write_interval_s=steps * step,
        delta_t_s=step,
        adjust_time_step=False,
        **options,  # type: ignore[arg-type]
    )
    case = write_case(spec, work / re.sub(r"[^a-z0-9]+", "-", name.lower()), overwrite=True)
    if edit is not None:
        edit(case)
    tool(case, "blockMesh")
    quality_log, _ = tool(case, "checkMesh", "-allGeometry")
    tool(case, "setFields")
    log, code = tool(case, "interFoam")
    courant = [float(c) for c in re.findall(r"^Courant Number mean: \S+ max: (\S+)", log, re.M)]
    times = re.findall(r"^Time = ([0-9.eE+-]+)$", log, re.M)
    row: dict[str, object] = {
        "experiment": name,
        "tests": purpose,
        "wall_cell_mm": None if "flat wall" in name else 1e3 * wall_cell_size_m(spec),
        "cells_per_quarter": spec.cells_per_radius,
        "step_s": step,
        "steps_asked": steps,
        "steps_run": len(times),
        "blew_up": code != 0 or len(times) < steps,
        "courant_first": courant[2] if len(courant) > 2 else None,
        "courant_last": courant[-1] if courant else None,
        "growth_per_step": growth_per_step(courant),
        "max_courant_per_step": [float(f"{c:.3g}") for c in courant[:30]],
    }
    for key, pattern in QUALITY.items():
        match = re.search(pattern, quality_log, re.M)
        row[key] = float(match.group(1)) if match else None
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", default=None, help="experiment names")
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-stability"))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-wall-grading.json")
    parser.add_argument(
        "--regrow", action="store_true", help="only recompute the growth from the stored series"
    )
    args = parser.parse_args()
    document = json.loads(args.out.read_text()) if args.out.is_file() else {}
    rows = {row["experiment"]: row for row in document.get("instability_diagnosis", [])}
    if args.regrow:
        for row in rows.values():
            row["growth_per_step"] = growth_per_step(row["max_courant_per_step"])
        args.out.write_text(json.dumps(document, indent=2) + "\n", encoding="utf-8")
        return
    for name in args.only or list(EXPERIMENTS):
        rows[name] = experiment(name, args.work)
        print(json.dumps(rows[name]), flush=True)
        document["instability_diagnosis"] = [rows[k] for k in EXPERIMENTS if k in rows]
        args.out.write_text(json.dumps(document, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
