"""The O-grid of an upright cylinder for blockMesh, and the probe columns (pure).

A square core (corners at `CORE_FRACTION` R) and four ring blocks with equal cells; the layers
within +-0.3 R of the free surface are twice as fine vertically. Uniform O-grids keep the
minimum cell determinant near 0.3; strongly wall-graded ones diverged (docs/cfd.md).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sloshkit.cfd.foam import Raw, foam_file, format_number
from sloshkit.cfd.spec import SCALE, CaseSpec

CORE_FRACTION = 0.55  # radius of the O-grid's square core corners, as a fraction of R


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
        "scale": 1,
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


def probe_angles_rad(spec: CaseSpec) -> NDArray[np.float64]:
    """Angles of the probe columns about the axis [rad]: +x and -x (the motion axis of 1-D
    cases), or ``spec.probe_angles`` equally spaced columns starting at +x."""
    count = spec.probe_angles or 2
    return np.asarray(2 * np.pi * np.arange(count) / count, dtype=float)


def probe_columns(spec: CaseSpec) -> tuple[NDArray[np.float64], float]:
    """z of the probes in each column [m] and their spacing dz [m]."""
    count = spec.probes_per_column or max(
        40, round(spec.height_m / (spec.radius_m / (4 * spec.cells_per_radius)))
    )
    dz = spec.height_m / count
    return np.asarray((np.arange(count) + 0.5) * dz, dtype=float), dz
