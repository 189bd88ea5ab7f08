"""What the high-frequency noise of the wall force on wall-graded meshes at small steps is, and
which solver settings change it: short free decays, one change at a time.

The damping study (README.md, *Damping*) found the wall force of every wall-graded O-grid
swamped by noise at a 0.5 ms step (noise ratio 1.7-2.4), and clean at 2 ms. Each experiment
here writes the 9-cells-per-radius graded mesh of that study (grading 0.25, 7 annulus cells,
15,876 cells), 3 deg tilt, fixed 0.5 ms step, 0.6 s of free decay, changes one thing and runs
it serially. It records, for the pressure and the viscous part of the horizontal wall force
separately, the noise ratio (`sloshkit.cfd.force_signal.noise_ratio` above 15 Hz) over
0.1-0.3 s and 0.3-0.6 s, and the frequency of the largest spectral line of the noise (1000 Hz
is the Nyquist frequency of the step: a sign change every step).

Results: data/cfd-parasitic-noise.json; README.md discusses them.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_parasitic_noise.py [--only NAME ...] [--jobs 2]
"""

from __future__ import annotations

import argparse
import json
import math
import re
import shutil
import subprocess
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
from cfd_wall_stability import QUALITY, chain, replace

from sloshkit.cfd.foam import read_scalar_internal_field
from sloshkit.cfd.force_signal import noise_ratio
from sloshkit.cfd.mesh import CORE_FRACTION, mesh_layout
from sloshkit.cfd.results import read_function_object
from sloshkit.cfd.run import openfoam_environment, write_case
from sloshkit.cfd.spec import SCALE, CaseSpec, FreeDecay
from sloshkit.model.liquids import get_liquid

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
Edit = Callable[[Path], None]
CUTOFF_HZ = 15.0  # three times the first-mode frequency, as in the damping study
WINDOWS_S = ((0.1, 0.3), (0.3, 0.6))
SOLUTION, SCHEMES = "system/fvSolution", "system/fvSchemes"
TRANSPORT = "constant/transportProperties"


def scale_property(phase: str, name: str, factor: float) -> Edit:
    """Multiply one property (``nu`` or ``rho``) of one phase in transportProperties."""

    def edit(case: Path) -> None:
        target = case / TRANSPORT
        text = target.read_text()
        pattern = rf"({phase}\s*\{{[^}}]*?\n\s*{name}\s+)([0-9.eE+-]+);"
        match = re.search(pattern, text)
        if match is None:
            raise ValueError(f"{phase}.{name} not in {TRANSPORT}")
        value = float(match.group(2)) * factor
        target.write_text(text[: match.start(2)] + f"{value:.10g}" + text[match.end(2) :])

    return edit


def core_arcs(case: Path) -> None:
    """Bow the edges of the O-grid's square core out to arcs concentric with the wall, so that
    the ring block between the core and the wall annulus is polar (its cell faces radial and
    orthogonal, like the annulus). The core's corners then become flat (non-orthogonality
    up to about 60 degrees, inside the liquid, far from the wall)."""
    spec = spec_for({})
    layout = mesh_layout(spec)
    per_level = 4 + 4 * (2 if layout.annulus else 1)  # core square, then one square per ring
    radius = CORE_FRACTION * spec.radius_m * SCALE
    midpoints = ((radius, 0.0), (0.0, radius), (-radius, 0.0), (0.0, -radius))
    arcs = []
    for level, z in enumerate(layout.z_levels_m):
        for (a, b), (x, y) in zip(((3, 0), (0, 1), (1, 2), (2, 3)), midpoints, strict=True):
            first, second = per_level * level + a, per_level * level + b
            arcs.append(f"    arc {first} {second} ({x:.9g} {y:.9g} {z * SCALE:.9g})")
    target = case / "system" / "blockMeshDict"
    text = target.read_text()
    start = text.index("(", text.index("edges")) + 1
    target.write_text(text[:start] + "\n" + "\n".join(arcs) + text[start:])


#: name -> (what it tests, CaseSpec keywords, edit of the written case)
EXPERIMENTS: dict[str, tuple[str, dict[str, Any], Edit | None]] = {
    "reference": ("the damping study's settings", {}, None),
    "reference at 1 ms": ("the step the study found clean", {"delta_t_s": 1e-3}, None),
    "momentum predictor": (
        "PIMPLE momentumPredictor on",
        {"momentum_predictor": True},
        None,
    ),
    "3 outer correctors": (
        "PIMPLE iterations within the step (nOuterCorrectors 3)",
        {},
        replace(SOLUTION, "nOuterCorrectors 1;", "nOuterCorrectors 3;"),
    ),
    "2 pressure correctors": ("nCorrectors 2 (the study uses 3)", {"pressure_correctors": 2}, None),
    "1 pressure corrector": ("nCorrectors 1", {"pressure_correctors": 1}, None),
    "1 non-orthogonal corrector": (
        "the non-orthogonal part of the pressure equation solved once more",
        {},
        replace(SOLUTION, "nNonOrthogonalCorrectors 0;", "nNonOrthogonalCorrectors 1;"),
    ),
    "limited non-orthogonal correction": (
        "laplacian and snGrad 'limited corrected 0.5'",
        {},
        chain(
            replace(SCHEMES, "Gauss linear corrected;", "Gauss linear limited corrected 0.5;"),
            replace(SCHEMES, "default         corrected;", "default limited corrected 0.5;"),
        ),
    ),
    "no non-orthogonal correction": (
        "laplacian and snGrad 'uncorrected'",
        {},
        chain(
            replace(SCHEMES, "Gauss linear corrected;", "Gauss linear uncorrected;"),
            replace(SCHEMES, "default         corrected;", "default         uncorrected;"),
        ),
    ),
    "Crank-Nicolson 0.9": ("second-order time scheme", {"ddt_scheme": "CrankNicolson 0.9"}, None),
    "water viscosity x4": ("viscous damping in the liquid", {}, scale_property("water", "nu", 4.0)),
    "air viscosity x10": ("viscous damping in the gas", {}, scale_property("air", "nu", 10.0)),
    "air density x10": ("density ratio 84 instead of 840", {}, scale_property("air", "rho", 10.0)),
    "band R/4N": ("vertical cells near the surface halved", {"surface_refinement": 4}, None),
    "polar middle ring": (
        "the core's edges bowed to arcs: every cell between core and wall radial (session 5)",
        {},
        core_arcs,
    ),
}


def slug(name: str) -> str:
    """A folder name for an experiment."""
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")


def spec_for(settings: dict[str, Any]) -> CaseSpec:
    """The experiment's case: the study's graded 9/radius mesh, 3 deg tilt, 0.6 s at 0.5 ms."""
    options: dict[str, Any] = {
        "cells_per_radius": 9,
        "wall_grading": 0.25,
        "radial_cells": 7,
        "end_time_s": 0.6,
        "delta_t_s": 5e-4,
        "write_interval_s": 0.6,
        "adjust_time_step": False,
    }
    options.update(settings)
    return CaseSpec(0.0205, 0.039, get_liquid("water-25C"), FreeDecay(math.radians(3.0)), **options)


def spectral_peak_hz(time_s: np.ndarray, values: np.ndarray, above_hz: float) -> float:
    """Frequency of the largest line of a uniformly sampled signal's spectrum above
    ``above_hz`` [Hz]."""
    spectrum = np.abs(np.fft.rfft(values - values.mean()))
    frequencies = np.fft.rfftfreq(values.size, float(time_s[1] - time_s[0]))
    high = frequencies > above_hz
    return float(frequencies[high][int(np.argmax(spectrum[high]))])


def measure(case: Path) -> dict[str, Any]:
    """Noise ratios (`sloshkit.cfd.force_signal.noise_ratio` above `CUTOFF_HZ`) of the
    pressure and viscous wall force in each window, and the noise's largest spectral line."""
    table = read_function_object(case, "wallForces", "force.dat")
    t = table[:, 0]
    step = float(np.median(np.diff(t)))
    uniform = np.arange(t[0], t[-1] + 0.5 * step, step)
    out: dict[str, Any] = {"simulated_s": float(t[-1])}
    for part, column in (("pressure", 4), ("viscous", 7)):
        values = np.interp(uniform, t, table[:, column])
        for start, stop in WINDOWS_S:
            ratio = noise_ratio(uniform, values, cutoff_hz=CUTOFF_HZ, start_s=start, stop_s=stop)
            out[f"noise_{part}_{start:g}_{stop:g}s"] = None if math.isnan(ratio) else ratio
        if part == "pressure":
            late = uniform > WINDOWS_S[0][0]
            out["noise_peak_hz"] = spectral_peak_hz(uniform[late], values[late], CUTOFF_HZ)
    return out


def experiment(name: str, work: Path) -> dict[str, Any]:
    """Run one experiment of `EXPERIMENTS`; its settings and measurements."""
    purpose, settings, edit = EXPERIMENTS[name]
    spec = spec_for(settings)
    case = write_case(spec, work / slug(name), overwrite=True)
    if edit is not None:
        edit(case)
    env = openfoam_environment()
    for command in ("blockMesh", "setFields"):
        subprocess.run([command], cwd=case, env=env, capture_output=True, check=True)
    quality = subprocess.run(["checkMesh"], cwd=case, env=env, capture_output=True, text=True)
    found = re.search(QUALITY["max_non_orthogonality_deg"], quality.stdout)
    done = subprocess.run(["interFoam"], cwd=case, env=env, capture_output=True, text=True)
    (case / "log.interFoam").write_text(done.stdout + done.stderr)
    times = re.findall(r"^Time = ([0-9.eE+-]+)$", done.stdout, re.M)
    row: dict[str, Any] = {
        "experiment": name,
        "tests": purpose,
        "step_s": spec.delta_t_s,
        "blew_up": done.returncode != 0,
        "reached_s": float(times[-1]) if times else 0.0,
        "max_non_orthogonality_deg": float(found.group(1)) if found else None,
    }
    try:
        row.update(measure(case))
    except (ValueError, IndexError, OSError) as error:  # no usable force output
        row["measure_error"] = str(error)
    return row


def read_field(path: Path) -> np.ndarray:
    """A scalar field's internal values (`sloshkit.cfd.foam.read_scalar_internal_field`)."""
    return read_scalar_internal_field(path.read_text())


def locate(work: Path, steps: int = 6) -> dict[str, Any]:
    """Where the step-to-step pressure oscillation of the reference experiment lives.

    Copies the reference case (run first if missing) from its end time, continues it for
    ``steps`` steps writing every step, and takes each cell's alternating part of p_rgh as the
    mean of |p[n+1] - 2 p[n] + p[n-1]| / 4 (the amplitude of a sign change every step). Reports
    it by phase, by distance from the side wall, and around the wall cells of each layer, as
    multiples of the median over all liquid cells.
    """
    source = work / slug("reference")
    if not (source / "0.6").is_dir():
        experiment("reference", work)
    case = work / "reference-every-step"
    if case.exists():
        shutil.rmtree(case)
    shutil.copytree(source, case, ignore=shutil.ignore_patterns("postProcessing", "log.*"))
    spec = spec_for({})
    start = spec.end_time_s
    control = case / "system" / "controlDict"
    text = re.sub(
        r"(?m)^endTime .*$", f"endTime {start + steps * spec.delta_t_s:.9g};", control.read_text()
    )
    text = re.sub(r"(?m)^writeInterval .*$", f"writeInterval {spec.delta_t_s:.9g};", text)
    control.write_text(text)
    env = openfoam_environment()
    subprocess.run(["interFoam"], cwd=case, env=env, capture_output=True, check=True)
    subprocess.run(
        ["postProcess", "-func", "writeCellCentres", "-time", f"{start:g}"],
        cwd=case, env=env, capture_output=True, check=True,
    )  # fmt: skip
    times = sorted(
        (d for d in case.iterdir() if re.fullmatch(r"[0-9.]+", d.name)), key=lambda d: float(d.name)
    )
    times = [d for d in times if float(d.name) >= start - 1e-12]
    pressure = np.array([read_field(d / "p_rgh") for d in times])
    alternating = np.abs(pressure[2:] - 2 * pressure[1:-1] + pressure[:-2]).mean(axis=0) / 4
    centres = np.column_stack([read_field(times[0] / f"C{axis}") for axis in "xyz"])
    alpha = read_field(times[0] / "alpha.water")
    radius = np.hypot(centres[:, 0], centres[:, 1])
    azimuth = np.degrees(np.arctan2(centres[:, 1], centres[:, 0]))
    liquid = alpha >= 0.99
    scale = float(np.median(alternating[liquid]))
    wall = radius > radius.max() - 1e-6
    phases = {"liquid": liquid, "interface": (alpha > 0.01) & (alpha < 0.99), "gas": alpha <= 0.01}
    bands_mm = ((0.0, 0.3), (0.3, 1.0), (1.0, 2.0), (2.0, 5.0), (5.0, 30.0))
    distance = (radius.max() - radius) / SCALE * 1e3  # mm from the wall cells' centres
    around: dict[str, float] = {}
    for angle in sorted({round(a) for a in azimuth[wall & liquid]}):
        chosen = wall & liquid & (np.abs(azimuth - angle) < 0.5)
        around[str(angle)] = float(alternating[chosen].mean() / scale)
    return {
        "steps": steps,
        "from_s": start,
        "unit": "mean |p[n+1] - 2 p[n] + p[n-1]| / 4 of p_rgh over the median of the liquid cells",
        "by_phase": {name: float(alternating[m].mean() / scale) for name, m in phases.items()},
        "by_wall_distance_mm": {
            f"{lo:g}-{hi:g}": float(alternating[(distance >= lo) & (distance < hi)].mean() / scale)
            for lo, hi in bands_mm
        },
        "wall_liquid_cells_by_azimuth_deg": around,
        "wall_cell_volume_spread_within_layers": volume_spread(case, start, wall, centres[:, 2]),
    }


def volume_spread(case: Path, time_s: float, chosen: np.ndarray, height: np.ndarray) -> float:
    """Largest relative spread (max - min over mean) of the chosen cells' volumes within one
    layer of equal height: 0 when the cells around the wall are identical."""
    volumes, heights = read_cell_volumes(case, time_s, chosen), np.round(height[chosen], 6)
    spreads = [np.ptp(volumes[heights == z]) / volumes[heights == z].mean() for z in set(heights)]
    return float(max(spreads))


def read_cell_volumes(case: Path, time_s: float, chosen: np.ndarray) -> np.ndarray:
    """Volumes of the chosen cells [mm^3] (``postProcess -func writeCellVolumes``)."""
    subprocess.run(
        ["postProcess", "-func", "writeCellVolumes", "-time", f"{time_s:g}"],
        cwd=case, env=openfoam_environment(), capture_output=True, check=True,
    )  # fmt: skip
    return read_field(case / f"{time_s:g}" / "V")[chosen]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", default=None, help="experiment names")
    parser.add_argument("--jobs", type=int, default=2, help="experiments run at once")
    parser.add_argument("--work", type=Path, default=Path("/tmp/sloshkit-cfd-noise"))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-parasitic-noise.json")
    parser.add_argument(
        "--locate", action="store_true", help="where the oscillation lives (reference case)"
    )
    args = parser.parse_args()
    if args.locate:
        where = locate(args.work)
        target = args.out.with_name("cfd-parasitic-noise-where.json")
        target.write_text(json.dumps(where, indent=2) + "\n", encoding="utf-8")
        print(json.dumps(where, indent=2))
        return
    stored = json.loads(args.out.read_text()) if args.out.is_file() else []
    rows = {r["experiment"]: r for r in stored}
    names = args.only or list(EXPERIMENTS)
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for row in pool.map(lambda n: experiment(n, args.work), names):
            rows[row["experiment"]] = row
            print(json.dumps(row), flush=True)
            ordered = [rows[k] for k in EXPERIMENTS if k in rows]
            args.out.write_text(json.dumps(ordered, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
