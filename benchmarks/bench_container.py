"""Benchmark and validation table of the axisymmetric-container models (issue 27).

Speed: the time to build the `SloshModel` of a new profile and fill (finite elements, cold
cache: `sloshkit.model.axisymmetric._solve` cleared before each run), against the closed-form
cylinder model in the same run (the baseline: what a model costs without the eigenproblem), and
the cached rebuild. Each figure is the best of ``--repeat`` runs after one warm-up run that pays
the imports (scipy, scikit-fem); the import itself is measured once in a fresh interpreter.
The requirement is < 0.2 s per new profile and fill.

Accuracy (the numbers of docs/validation.md): the upright cylinder against its closed form
(Abramson 1966; first three modes: frequency, slosh mass, bob height, wall factor) for four
depths, the 45-degree cone standing on its vertex (exact omega^2 h / g = 1), the half-full
sphere (McIver 1989: omega^2 R / g = 1.5601), each against the radial cells of the mesh; and the
brimful volume of every catalogued ISO 8362-1 vial against the catalogue's.

Run: .venv/bin/python benchmarks/bench_container.py [--markdown] [--repeat 5]
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
import warnings

import numpy as np

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.model import axisymmetric
from sloshkit.model.catalogue import ISO8362_VIALS, catalogue_container
from sloshkit.model.profile import cone_profile, cylinder_profile, sphere_profile
from sloshkit.model.theory import (
    bessel_roots,
    bob_offset_from_cg,
    natural_frequency,
    slosh_mass_ratio,
    wall_elevation_factor,
)

WATER = get_liquid("water-25C")
SPEED_CASES = (
    ("iso8362-2R, 1 mL", "iso8362-2R", 1e-6),
    ("iso8362-10R, 5 mL", "iso8362-10R", 5e-6),
    ("iso8362-50R, 30 mL", "iso8362-50R", 30e-6),
)


def best_time(function, repeat: int) -> float:
    """Best wall-clock time of ``repeat`` calls [s]."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def cold(container, volume):
    """Build the model with an empty cache (a new profile or fill)."""

    def run():
        axisymmetric._solve.cache_clear()
        height = container.fill_height_for_volume(volume)
        return equivalent_model(container, WATER, height, damping_ratio=0.01)

    return run


def import_time() -> float:
    """Import of scipy.sparse.linalg + scikit-fem in a fresh interpreter [s]."""
    code = (
        "import time; t = time.perf_counter(); import scipy.linalg, scipy.sparse.linalg, skfem, "
        "threadpoolctl; print(time.perf_counter() - t)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip())


def cylinder_errors(depth_ratio: float, cells: int | None) -> np.ndarray:
    """Max relative error over the first three modes of (frequency, mass, bob, wall)."""
    radius = 0.0205
    height = depth_ratio * radius
    modes = axisymmetric.axisymmetric_modes(
        cylinder_profile(radius, 5 * height), height, 3, radial_cells=cells
    )
    xi = bessel_roots(3)
    exact = (
        np.sqrt(natural_frequency(radius, height, xi, 1.0) ** 2),
        slosh_mass_ratio(radius, height, xi) * math.pi * radius**2 * height,
        height / 2 + bob_offset_from_cg(radius, height, xi),
        wall_elevation_factor(radius, xi),
    )
    found = (
        np.sqrt(modes.eigenvalues_1_m),
        np.array(modes.mass_per_density_m3),
        np.array(modes.bob_height_m),
        np.array(modes.wall_elevation_factor_m),
    )
    return np.array([np.max(np.abs(f / e - 1.0)) for f, e in zip(found, exact, strict=True)])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--markdown", action="store_true", help="print Markdown tables")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    rule = "|" if args.markdown else ""

    print(f"import of scipy.linalg/sparse + scikit-fem (fresh process): {import_time():.3f} s")
    cylinder = UprightCylinder(0.007)
    cold(catalogue_container("iso8362-2R"), 1e-6)()  # warm-up: imports, first assembly
    baseline = best_time(lambda: equivalent_model(cylinder, WATER, 0.0065), args.repeat)
    print(f"closed-form cylinder model (baseline): {1e3 * baseline:.3f} ms")
    print()
    print(f"{rule} case {rule} new profile/fill [ms] {rule} cached [ms] {rule} / baseline {rule}")
    if args.markdown:
        print("|---|---:|---:|---:|")
    for label, name, volume in SPEED_CASES:
        container = catalogue_container(name)
        new = best_time(cold(container, volume), args.repeat)
        height = container.fill_height_for_volume(volume)
        equivalent_model(container, WATER, height, damping_ratio=0.01)
        cached = best_time(
            lambda c=container, h=height: equivalent_model(c, WATER, h, damping_ratio=0.01),
            args.repeat,
        )
        print(
            f"{rule} {label} {rule} {1e3 * new:.1f} {rule} {1e3 * cached:.3f} {rule} "
            f"{new / baseline:.0f} {rule}"
        )
    print()
    print("cylinder R = 20.5 mm against the closed form, modes 1-3 (max relative error):")
    print(
        f"{rule} h/R {rule} cells {rule} frequency {rule} slosh mass {rule} bob height "
        f"{rule} wall factor {rule}"
    )
    if args.markdown:
        print("|---:|---:|---:|---:|---:|---:|")
    for depth in (0.3, 1.0, 1.9024, 4.0):
        for cells in (8, 16, None, 32):
            errors = cylinder_errors(depth, cells)
            shown = axisymmetric.DEFAULT_RADIAL_CELLS if cells is None else cells
            default = " (default)" if cells is None else ""
            print(
                f"{rule} {depth:g} {rule} {shown}{default} {rule} "
                + f" {rule} ".join(f"{e:.1e}" for e in errors)
                + f" {rule}"
            )
    print()
    print("exact and published values (first mode):")
    print(f"{rule} case {rule} reference {rule} cells {rule} computed {rule} rel. error {rule}")
    if args.markdown:
        print("|---|---:|---:|---:|---:|")
    for cells in (4, 8, 16, 24, 32):
        modes = axisymmetric.axisymmetric_modes(
            cone_profile(0.03, 0.03), 0.012, 1, radial_cells=cells
        )
        value = modes.eigenvalues_1_m[0] * 0.012
        print(
            f"{rule} 45-degree cone, omega^2 h/g {rule} 1 (exact) {rule} {cells} {rule} "
            f"{value:.10f} {rule} {abs(value - 1):.1e} {rule}"
        )
    for cells in (8, 16, 24, 32, 48):
        modes = axisymmetric.axisymmetric_modes(sphere_profile(0.01), 0.01, 1, radial_cells=cells)
        value = modes.eigenvalues_1_m[0] * 0.01
        print(
            f"{rule} half-full sphere, omega^2 R/g {rule} 1.5601 (McIver 1989) {rule} {cells} "
            f"{rule} {value:.5f} {rule} {abs(value / 1.5601 - 1):.1e} {rule}"
        )
    print()
    print("iso8362-2R at 1 mL (heel): first mode against the mesh (self-convergence):")
    print(
        f"{rule} cells {rule} unknowns {rule} omega^2 R_s/g {rule} m_1 [g] {rule} bob [mm] "
        f"{rule} wall factor [mm] {rule}"
    )
    if args.markdown:
        print("|---:|---:|---:|---:|---:|---:|")
    vial = catalogue_container("iso8362-2R")
    height = vial.fill_height_for_volume(1e-6)
    for cells in (8, 16, 24, 32, 48, 64):
        modes = axisymmetric.axisymmetric_modes(vial, height, 1, radial_cells=cells)
        print(
            f"{rule} {cells} {rule} {modes.unknowns} {rule} "
            f"{modes.eigenvalues_1_m[0] * modes.surface_radius_m:.6f} {rule} "
            f"{1e3 * WATER.density_kg_m3 * modes.mass_per_density_m3[0]:.5f} {rule} "
            f"{1e3 * modes.bob_height_m[0]:.5f} {rule} "
            f"{1e3 * modes.wall_elevation_factor_m[0]:.5f} {rule}"
        )
    print()
    print("ISO 8362-1 vials: brimful volume of the profile against the catalogue:")
    print(
        f"{rule} size {rule} catalogue [mL] {rule} profile [mL] {rule} difference {rule} "
        f"within tolerance {rule}"
    )
    if args.markdown:
        print("|---|---:|---:|---:|---|")
    for size, vial in ISO8362_VIALS.items():
        volume = catalogue_container("iso8362-" + size).brimful_volume_m3 * 1e6
        inside = abs(volume - vial.brimful_ml) <= vial.brimful_tolerance_ml
        print(
            f"{rule} {size} {rule} {vial.brimful_ml:g} +- {vial.brimful_tolerance_ml:g} {rule} "
            f"{volume:.2f} {rule} {100 * (volume / vial.brimful_ml - 1):+.1f} % {rule} "
            f"{'yes' if inside else 'no'} {rule}"
        )


if __name__ == "__main__":
    main()
