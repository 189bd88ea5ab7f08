"""Generation of an interFoam case for a filled upright cylinder (pure: returns file texts).

Choices, and why
----------------
- **Millimetres.** interFoam on O-grid cylinders in metres diverged within a few steps on this
  version, the same mesh scaled by 1000 ran stably (docs/cfd.md, "units"). Lengths are in mm,
  so g' = 9810, nu' = 1e6 nu, sigma' = 1e9 sigma, accelerations x 1000; forces come back x 1e-12.
- **Container frame, body force.** The vial translates rigidly, so the flow is solved on a
  static mesh in the container's frame with the fictitious force -rho a(t), through the fvOption
  ``tabulatedAccelerationSource`` (g_eff = g - a). Exact for rigid translation, cheaper and
  more robust than a moving mesh; the walls are at rest in that frame (no-slip). The table is
  the container's acceleration sampled every millisecond over [0, endTime] and beyond.
- **Uniform O-grid** (square core and four ring blocks, equal cells): strong wall grading
  diverged here; the layers within +-0.3 R of the free surface are twice as fine vertically.
- **Low numerical damping.** Fixed time step (the damping of Euler grows with it, see the
  time-step study in docs/cfd.md), ``Gauss vanLeer`` for alpha with MULES, laminar flow.
- **Measurements** (function objects): two columns of ``alpha.water`` probes at x = +-0.98 R
  on the motion axis (wall elevation = sum of alpha dz minus h), the volume integral of
  grad(alpha.water) (its x/z ratio is the mean free-surface slope, the paper's eq. 13), and the
  pressure and viscous force on the walls (``forces``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.cfd.foam import Raw, foam_file, format_number
from sloshkit.errors import InputError, require_in_range, require_positive
from sloshkit.model.liquids import Liquid

SCALE = 1000.0  # metres -> millimetres
#: Air at 25 degC, 1 atm: the seed paper's Table 1.
AIR_DENSITY_KG_M3 = 1.185
AIR_VISCOSITY_PA_S = 1.831e-5
CORE_FRACTION = 0.55  # radius of the O-grid's square core corners, as a fraction of R


@dataclass(frozen=True)
class FreeDecay:
    """Initial free surface tilted by ``tilt_rad`` about the y axis (rising towards +x)."""

    tilt_rad: float = math.radians(3.0)

    def acceleration(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """No container motion [m/s^2]."""
        return np.zeros_like(t)


@dataclass(frozen=True)
class Harmonic:
    """The seed paper's excitation: x(t) = A sin(2 pi f t) for ``duration_s``, then at rest
    (acceleration -A (2 pi f)^2 sin(2 pi f t), zero at both ends for whole cycles)."""

    amplitude_m: float = 0.01
    frequency_hz: float = 1.0
    duration_s: float = 2.0

    def acceleration(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """Container acceleration [m/s^2]."""
        omega = 2 * math.pi * self.frequency_hz
        values = -self.amplitude_m * omega**2 * np.sin(omega * t)
        return np.where((t >= 0) & (t <= self.duration_s), values, 0.0)


@dataclass(frozen=True)
class MotionExcitation:
    """Any container motion given by its acceleration function of time [m/s^2] (zero after
    ``duration_s``, e.g. a sloshkit motion law)."""

    name: str
    acceleration_function: Callable[[NDArray[np.float64]], NDArray[np.float64]]
    duration_s: float = 0.0

    def acceleration(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """Container acceleration [m/s^2]."""
        return np.asarray(self.acceleration_function(t), dtype=float)


Excitation = FreeDecay | Harmonic | MotionExcitation


@dataclass(frozen=True)
class CaseSpec:
    """Everything that defines a case (SI units; the case itself is written in mm)."""

    radius_m: float
    fill_height_m: float
    liquid: Liquid
    excitation: Excitation = field(default_factory=FreeDecay)
    domain_height_m: float | None = None
    cells_per_radius: int = 10
    end_time_s: float = 3.0
    delta_t_s: float = 5e-4
    ddt_scheme: str = "Euler"
    write_interval_s: float = 0.5
    surface_tension: bool = False
    probes_per_column: int | None = None
    processes: int = 1

    def __post_init__(self) -> None:
        require_positive("radius", self.radius_m, "m")
        require_positive("fill_height", self.fill_height_m, "m")
        require_in_range("cells_per_radius", self.cells_per_radius, 3, 60)
        require_positive("end_time", self.end_time_s, "s")
        require_in_range("delta_t", self.delta_t_s, 1e-6, 0.05, "s")
        require_in_range("np", self.processes, 1, 256)
        if self.height_m <= self.fill_height_m:
            raise InputError("domain_height", self.height_m, "must exceed the fill height")
        if self.ddt_scheme not in ("Euler", "CrankNicolson 0.9", "backward"):
            raise InputError(
                "ddt_scheme", self.ddt_scheme, "must be Euler, CrankNicolson 0.9 or backward"
            )

    @property
    def height_m(self) -> float:
        """Domain height: the given wall height, else the fill plus 1.5 R of headspace [m]."""
        if self.domain_height_m is not None:
            return self.domain_height_m
        return self.fill_height_m + 1.5 * self.radius_m


@dataclass(frozen=True)
class MeshLayout:
    """Cell counts of the O-grid: per quarter circumference, radial ring, and the z layers."""

    circumferential: int
    radial: int
    z_levels_m: tuple[float, ...]
    z_cells: tuple[int, ...]

    @property
    def cells_per_layer(self) -> int:
        """Cells in one horizontal layer: the square core plus four ring blocks."""
        return self.circumferential**2 + 4 * self.circumferential * self.radial

    @property
    def cells(self) -> int:
        """Total cell count."""
        return self.cells_per_layer * sum(self.z_cells)


def mesh_layout(spec: CaseSpec) -> MeshLayout:
    """Cell counts for ``spec``: fine vertical cells of R/(2N) within +-0.3 R of the free
    surface, twice that elsewhere."""
    n = spec.cells_per_radius
    radius, height, fill = spec.radius_m, spec.height_m, spec.fill_height_m
    fine = radius / (2 * n)
    band = 0.3 * radius
    levels = [0.0]
    low, high = max(fill - band, 0.0), min(fill + band, height)
    for level in (low, high, height):
        if level - levels[-1] > 1e-9:
            levels.append(level)
    cells = []
    for start, stop in itertools.pairwise(levels):
        in_band = start >= low - 1e-12 and stop <= high + 1e-12
        size = fine if in_band else 2 * fine
        cells.append(max(1, round((stop - start) / size)))
    return MeshLayout(n, max(2, round(n * (1 - CORE_FRACTION) * 1.1)), tuple(levels), tuple(cells))


def block_mesh_dict(spec: CaseSpec) -> str:
    """blockMeshDict of the O-grid in millimetres; the top is the ``atmosphere`` patch, every
    other face the ``walls`` patch."""
    layout = mesh_layout(spec)
    radius = spec.radius_m * SCALE
    corner = radius / math.sqrt(2.0)
    core = CORE_FRACTION * radius / math.sqrt(2.0)
    signs = [(1, 1), (-1, 1), (-1, -1), (1, -1)]  # corners at 45, 135, 225, 315 degrees
    vertices = []
    for z in layout.z_levels_m:
        zz = z * SCALE
        vertices += [(core * sx, core * sy, zz) for sx, sy in signs]
        vertices += [(corner * sx, corner * sy, zz) for sx, sy in signs]

    def inner(level: int, i: int) -> int:
        return 8 * level + i

    def outer(level: int, i: int) -> int:
        return 8 * level + 4 + i

    n, m = layout.circumferential, layout.radial
    blocks, top_faces = [], []
    for level, count in enumerate(layout.z_cells):
        rings = [
            ([inner(level, 2), inner(level, 3), inner(level, 0), inner(level, 1)], (n, n)),
            ([inner(level, 3), outer(level, 3), outer(level, 0), inner(level, 0)], (m, n)),
            ([inner(level, 0), outer(level, 0), outer(level, 1), inner(level, 1)], (m, n)),
            ([inner(level, 1), outer(level, 1), outer(level, 2), inner(level, 2)], (m, n)),
            ([inner(level, 2), outer(level, 2), outer(level, 3), inner(level, 3)], (m, n)),
        ]
        for bottom, (a, b) in rings:
            top = [v + 8 for v in bottom]
            blocks.append(
                f"    hex ({' '.join(map(str, bottom + top))}) ({a} {b} {count}) simpleGrading (1 1 1)"
            )
            if level == len(layout.z_cells) - 1:
                top_faces.append(f"            ({' '.join(map(str, top))})")
    arcs = []
    midpoints = [(radius, 0.0), (0.0, radius), (-radius, 0.0), (0.0, -radius)]
    pairs = [(3, 0), (0, 1), (1, 2), (2, 3)]
    for level, z in enumerate(layout.z_levels_m):
        for (a, b), (mx, my) in zip(pairs, midpoints, strict=True):
            arcs.append(
                f"    arc {outer(level, a)} {outer(level, b)} "
                f"({format_number(mx)} {format_number(my)} {format_number(z * SCALE)})"
            )
    vertex_text = "\n".join(
        f"    ({format_number(round(x, 9))} {format_number(round(y, 9))} {format_number(round(z, 9))})"
        for x, y, z in vertices
    )
    entries = {
        "convertToMeters": 1,
        "vertices": Raw("\n(\n" + vertex_text + "\n)"),
        "blocks": Raw("\n(\n" + "\n".join(blocks) + "\n)"),
        "edges": Raw("\n(\n" + "\n".join(arcs) + "\n)"),
        "boundary": Raw(
            "\n(\n    atmosphere\n    {\n        type patch;\n        faces\n        (\n"
            + "\n".join(top_faces)
            + "\n        );\n    }\n)"
        ),
        "defaultPatch": {"name": "walls", "type": "wall"},
    }
    return foam_file("dictionary", "blockMeshDict", entries, "system")


def acceleration_table(spec: CaseSpec, step_s: float = 1e-3) -> str:
    """``constant/acceleration.dat``: (t ((ax ay az) (wx wy wz) (dwx dwy dwz))) in mm/s^2,
    covering [0, endTime + 0.1 s] (a time outside the table is fatal)."""
    end = spec.end_time_s + 0.1
    t = np.arange(0.0, end + step_s, step_s)
    ax = spec.excitation.acceleration(t) * SCALE
    rows = "\n".join(
        f"({format_number(round(float(time), 9))} (({format_number(float(a))} 0 0) (0 0 0) (0 0 0)))"
        for time, a in zip(t, ax, strict=True)
    )
    return f"{t.size}\n(\n{rows}\n)\n"


def probe_columns(spec: CaseSpec) -> tuple[NDArray[np.float64], float]:
    """z of the probes in each column [m] and their spacing dz [m]."""
    count = spec.probes_per_column or max(
        40, round(spec.height_m / (spec.radius_m / (4 * spec.cells_per_radius)))
    )
    dz = spec.height_m / count
    return np.asarray((np.arange(count) + 0.5) * dz, dtype=float), dz


def control_dict(spec: CaseSpec) -> str:
    """controlDict with the function objects the calibration needs."""
    z, _ = probe_columns(spec)
    x = 0.98 * spec.radius_m * SCALE
    points = [
        f"({format_number(sx * x)} 0 {format_number(round(zz * SCALE, 9))})"
        for sx in (1, -1)
        for zz in z
    ]
    entries: dict[str, Any] = {
        "application": "interFoam",
        "startFrom": "latestTime",
        "startTime": 0,
        "stopAt": "endTime",
        "endTime": spec.end_time_s,
        "deltaT": spec.delta_t_s,
        "writeControl": "adjustableRunTime",
        "writeInterval": spec.write_interval_s,
        "purgeWrite": 0,
        "writeFormat": "ascii",
        "writePrecision": 8,
        "writeCompression": "off",
        "timeFormat": "general",
        "timePrecision": 8,
        "runTimeModifiable": "no",
        "adjustTimeStep": "no",
        "maxCo": 1,
        "maxAlphaCo": 1,
        "maxDeltaT": spec.delta_t_s,
        "libs": Raw(
            '("libfvOptions.so" "libforces.so" "libsampling.so" "libfieldFunctionObjects.so")'
        ),
        "functions": {
            "wallProbes": {
                "type": "probes",
                "libs": Raw('("libsampling.so")'),
                "writeControl": "timeStep",
                "writeInterval": 1,
                "fields": Raw("(alpha.water)"),
                "probeLocations": Raw(
                    "\n        (\n            " + "\n            ".join(points) + "\n        )"
                ),
            },
            "gradAlpha": {
                "type": "grad",
                "libs": Raw('("libfieldFunctionObjects.so")'),
                "field": "alpha.water",
                "writeControl": "timeStep",
                "writeInterval": 1,
                "log": "false",
            },
            "surfaceTilt": {
                "type": "volFieldValue",
                "libs": Raw('("libfieldFunctionObjects.so")'),
                "writeControl": "timeStep",
                "writeInterval": 1,
                "writeFields": "false",
                "log": "false",
                "regionType": "all",
                "operation": "volIntegrate",
                "fields": Raw("(grad(alpha.water))"),
            },
            "wallForces": {
                "type": "forces",
                "libs": Raw('("libforces.so")'),
                "writeControl": "timeStep",
                "writeInterval": 1,
                "patches": Raw("(walls)"),
                "rho": "rho",
                "rhoInf": 1,
                "CofR": Raw("(0 0 0)"),
                "log": "false",
            },
        },
    }
    return foam_file("dictionary", "controlDict", entries, "system")


def fv_schemes(spec: CaseSpec) -> str:
    """Schemes: bounded second-order convection, the chosen time scheme."""
    entries = {
        "ddtSchemes": {"default": spec.ddt_scheme},
        "gradSchemes": {"default": "Gauss linear"},
        "divSchemes": {
            "div(rhoPhi,U)": "Gauss linearUpwind grad(U)",
            "div(phi,alpha)": "Gauss vanLeer",
            "div(phirb,alpha)": "Gauss linear",
            "div(((rho*nuEff)*dev2(T(grad(U)))))": "Gauss linear",
        },
        "laplacianSchemes": {"default": "Gauss linear corrected"},
        "interpolationSchemes": {"default": "linear"},
        "snGradSchemes": {"default": "corrected"},
    }
    return foam_file("dictionary", "fvSchemes", entries, "system")


def fv_solution(spec: CaseSpec) -> str:
    """Solvers and PIMPLE settings (MULES for alpha, GAMG for p_rgh)."""
    entries = {
        "solvers": {
            '"alpha.water.*"': {
                "nAlphaCorr": 2,
                "nAlphaSubCycles": 1,
                "cAlpha": 1,
                "MULESCorr": "yes",
                "nLimiterIter": 5,
                "solver": "smoothSolver",
                "smoother": "symGaussSeidel",
                "tolerance": 1e-8,
                "relTol": 0,
            },
            '"pcorr.*"': {"solver": "PCG", "preconditioner": "DIC", "tolerance": 1e-7, "relTol": 0},
            "p_rgh": {"solver": "GAMG", "smoother": "DIC", "tolerance": 1e-7, "relTol": 0.05},
            "p_rghFinal": {"$p_rgh": "", "relTol": 0},
            '"U.*"': {
                "solver": "smoothSolver",
                "smoother": "symGaussSeidel",
                "tolerance": 1e-7,
                "relTol": 0,
            },
        },
        "PIMPLE": {
            "momentumPredictor": "no",
            "nOuterCorrectors": 1,
            "nCorrectors": 3,
            "nNonOrthogonalCorrectors": 0,
        },
        "relaxationFactors": {"equations": {'".*"': 1}},
    }
    text = foam_file("dictionary", "fvSolution", entries, "system")
    return text.replace("$p_rgh          ;", "$p_rgh;")


def decompose_par_dict(spec: CaseSpec) -> str:
    """Decomposition along z (hierarchical: scotch and metis are dummies in this package)."""
    entries = {
        "numberOfSubdomains": spec.processes,
        "method": "hierarchical",
        "coeffs": {"n": Raw(f"(1 1 {spec.processes})"), "order": "xyz"},
    }
    return foam_file("dictionary", "decomposeParDict", entries, "system")


def set_fields_dict(spec: CaseSpec) -> str:
    """setFieldsDict: water below the (possibly tilted) static free surface."""
    radius, height, fill = spec.radius_m * SCALE, spec.height_m * SCALE, spec.fill_height_m * SCALE
    tilt = spec.excitation.tilt_rad if isinstance(spec.excitation, FreeDecay) else 0.0
    if tilt == 0.0:
        region = f"""    boxToCell
    {{
        box (-{2 * radius} -{2 * radius} -1) ({2 * radius} {2 * radius} {format_number(fill)});
        fieldValues ( volScalarFieldValue alpha.water 1 );
    }}"""
    else:
        c, s = math.cos(tilt), math.sin(tilt)
        depth = 2 * height
        span = 4 * radius
        # Top face of the box lies on the plane z = fill + x tan(tilt) (through the axis, so
        # the liquid volume is unchanged); the box reaches `depth` below it.
        p0 = (-2 * radius * c, -2 * radius, fill - 2 * radius * s)
        origin = (p0[0] + depth * s, p0[1], p0[2] - depth * c)
        region = f"""    rotatedBoxToCell
    {{
        origin ({" ".join(format_number(round(v, 9)) for v in origin)});
        i ({format_number(round(span * c, 9))} 0 {format_number(round(span * s, 9))});
        j (0 {format_number(span)} 0);
        k ({format_number(round(-depth * s, 9))} 0 {format_number(round(depth * c, 9))});
        fieldValues ( volScalarFieldValue alpha.water 1 );
    }}"""
    entries = {
        "defaultFieldValues": Raw("( volScalarFieldValue alpha.water 0 )"),
        "regions": Raw("\n(\n" + region + "\n)"),
    }
    return foam_file("dictionary", "setFieldsDict", entries, "system")


def transport_properties(spec: CaseSpec) -> str:
    """Water and air (the paper's Table 1 for air), in mm units."""
    liquid = spec.liquid
    sigma = liquid.surface_tension_n_m * SCALE**3 if spec.surface_tension else 0.0
    entries = {
        "phases": Raw("(water air)"),
        "water": {
            "transportModel": "Newtonian",
            "nu": liquid.kinematic_viscosity_m2_s * SCALE**2,
            "rho": liquid.density_kg_m3,
        },
        "air": {
            "transportModel": "Newtonian",
            "nu": AIR_VISCOSITY_PA_S / AIR_DENSITY_KG_M3 * SCALE**2,
            "rho": AIR_DENSITY_KG_M3,
        },
        "sigma": sigma,
    }
    return foam_file("dictionary", "transportProperties", entries, "constant")


def initial_fields() -> dict[str, str]:
    """0/alpha.water, 0/U, 0/p_rgh: no-slip walls, an open top (atmosphere)."""
    alpha = foam_file(
        "volScalarField",
        "alpha.water",
        {
            "dimensions": Raw("[0 0 0 0 0 0 0]"),
            "internalField": Raw("uniform 0"),
            "boundaryField": {
                "walls": {"type": "zeroGradient"},
                "atmosphere": {
                    "type": "inletOutlet",
                    "inletValue": Raw("uniform 0"),
                    "value": Raw("uniform 0"),
                },
            },
        },
        "0",
    )
    velocity = foam_file(
        "volVectorField",
        "U",
        {
            "dimensions": Raw("[0 1 -1 0 0 0 0]"),
            "internalField": Raw("uniform (0 0 0)"),
            "boundaryField": {
                "walls": {"type": "noSlip"},
                "atmosphere": {
                    "type": "pressureInletOutletVelocity",
                    "value": Raw("uniform (0 0 0)"),
                },
            },
        },
        "0",
    )
    pressure = foam_file(
        "volScalarField",
        "p_rgh",
        {
            "dimensions": Raw("[1 -1 -2 0 0 0 0]"),
            "internalField": Raw("uniform 0"),
            "boundaryField": {
                "walls": {"type": "fixedFluxPressure", "value": Raw("uniform 0")},
                "atmosphere": {
                    "type": "totalPressure",
                    "p0": Raw("uniform 0"),
                    "value": Raw("uniform 0"),
                },
            },
        },
        "0",
    )
    return {"0/alpha.water": alpha, "0/U": velocity, "0/p_rgh": pressure}


ALLRUN = """#!/bin/sh
# Run this case without sloshkit (OpenFOAM v1912, Debian package `openfoam`).
# Usage: ./Allrun [number of processes]
cd "${0%/*}" || exit 1
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
np="${1:-%NP%}"
set -e
[ -d constant/polyMesh ] || blockMesh > log.blockMesh 2>&1
checkMesh > log.checkMesh 2>&1
[ -f 0/alpha.water.orig ] || cp 0/alpha.water 0/alpha.water.orig
[ -f log.setFields ] || setFields > log.setFields 2>&1
if [ "$np" -gt 1 ]; then
    foamDictionary -entry numberOfSubdomains -set "$np" system/decomposeParDict > /dev/null
    foamDictionary -entry coeffs.n -set "(1 1 $np)" system/decomposeParDict > /dev/null
    [ -d processor0 ] || decomposePar -force > log.decomposePar 2>&1
    mpirun --oversubscribe -np "$np" interFoam -parallel > log.interFoam 2>&1
else
    interFoam > log.interFoam 2>&1
fi
"""


def case_files(spec: CaseSpec) -> dict[str, str]:
    """Every file of the case, path relative to the case folder -> text."""
    files = {
        "system/blockMeshDict": block_mesh_dict(spec),
        "system/controlDict": control_dict(spec),
        "system/fvSchemes": fv_schemes(spec),
        "system/fvSolution": fv_solution(spec),
        "system/setFieldsDict": set_fields_dict(spec),
        "system/decomposeParDict": decompose_par_dict(spec),
        "constant/transportProperties": transport_properties(spec),
        "constant/turbulenceProperties": foam_file(
            "dictionary", "turbulenceProperties", {"simulationType": "laminar"}, "constant"
        ),
        "constant/g": foam_file(
            "uniformDimensionedVectorField",
            "g",
            {
                "dimensions": Raw("[0 1 -2 0 0 0 0]"),
                "value": Raw(f"(0 0 {format_number(-9.81 * SCALE)})"),
            },
            "constant",
        ),
        "constant/fvOptions": foam_file(
            "dictionary",
            "fvOptions",
            {
                "containerMotion": {
                    "type": "tabulatedAccelerationSource",
                    "active": "yes",
                    "timeDataFileName": '"constant/acceleration.dat"',
                    "tabulatedAccelerationSourceCoeffs": {
                        "timeDataFileName": '"constant/acceleration.dat"'
                    },
                },
            },
            "constant",
        ),
        "constant/acceleration.dat": acceleration_table(spec),
        "Allrun": ALLRUN.replace("%NP%", str(spec.processes)),
    }
    files.update(initial_fields())
    return files


def spec_summary(spec: CaseSpec) -> dict[str, Any]:
    """JSON-ready description of a case (SI), written beside it as sloshkit-case.json."""
    layout = mesh_layout(spec)
    z, dz = probe_columns(spec)
    excitation = spec.excitation
    description: dict[str, Any] = {"type": type(excitation).__name__}
    if isinstance(excitation, FreeDecay):
        description["tilt_deg"] = math.degrees(excitation.tilt_rad)
    elif isinstance(excitation, Harmonic):
        description.update(
            amplitude_m=excitation.amplitude_m,
            frequency_hz=excitation.frequency_hz,
            duration_s=excitation.duration_s,
        )
    else:
        description.update(name=excitation.name, duration_s=excitation.duration_s)
    return {
        "radius_m": spec.radius_m,
        "fill_height_m": spec.fill_height_m,
        "domain_height_m": spec.height_m,
        "liquid": spec.liquid.name,
        "density_kg_m3": spec.liquid.density_kg_m3,
        "viscosity_pa_s": spec.liquid.viscosity_pa_s,
        "surface_tension": spec.surface_tension,
        "cells_per_radius": spec.cells_per_radius,
        "cells": layout.cells,
        "end_time_s": spec.end_time_s,
        "delta_t_s": spec.delta_t_s,
        "ddt_scheme": spec.ddt_scheme,
        "processes": spec.processes,
        "probe_dz_m": dz,
        "probes_per_column": int(z.size),
        "probe_x_m": 0.98 * spec.radius_m,
        "excitation": description,
        "units_in_case": "mm (lengths x1000, g 9810, nu x1e6, sigma x1e9)",
    }
