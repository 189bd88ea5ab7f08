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
#: Inner radius of the wall annulus of graded meshes, as a fraction of R. Its inner and outer
#: edges are concentric arcs, so its cells are orthogonal however strongly they are graded.
ANNULUS_INNER = 0.85


@dataclass(frozen=True)
class MeshLayout:
    """Cell counts of the O-grid: per quarter circumference, across the ring blocks, across
    the wall annulus (0: none), and the z layers.

    Parameters
    ----------
    circumferential : int
        Cells per quarter circumference (and along each edge of the square core).
    radial : int
        Cells across each ring block.
    z_levels_m : tuple of float
        Heights of the block layers [m].
    z_cells : tuple of int
        Cells in each layer.
    annulus : int
        Cells across the graded wall annulus (0: none).

    Returns
    -------
    MeshLayout

    Examples
    --------
    >>> MeshLayout(8, 4, (0.0, 0.03, 0.07), (13, 20)).cells
    6336
    """

    circumferential: int
    radial: int
    z_levels_m: tuple[float, ...]
    z_cells: tuple[int, ...]
    annulus: int = 0

    @property
    def cells_per_layer(self) -> int:
        """Cells in one horizontal layer: the square core plus the ring and annulus blocks."""
        return self.circumferential**2 + 4 * self.circumferential * (self.radial + self.annulus)

    @property
    def cells(self) -> int:
        """Total cell count."""
        return self.cells_per_layer * sum(self.z_cells)


def mesh_layout(spec: CaseSpec) -> MeshLayout:
    """Cell counts for ``spec``: fine vertical cells of R/(sN) within +-0.3 R of the free
    surface (s: ``spec.surface_refinement``, 2 by default), R/N elsewhere.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    MeshLayout

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> mesh_layout(spec).cells
    6336
    """
    n = spec.cells_per_radius
    radius, height, fill = spec.radius_m, spec.height_m, spec.fill_height_m
    fine = radius / (spec.surface_refinement * n)
    band = 0.3 * radius
    levels = [0.0]
    low, high = max(fill - band, 0.0), min(fill + band, height)
    for level in (low, high, height):
        if level - levels[-1] > 1e-9:
            levels.append(level)
    cells = []
    for start, stop in itertools.pairwise(levels):
        in_band = start >= low - 1e-12 and stop <= high + 1e-12
        size = fine if in_band else radius / n
        cells.append(max(1, round((stop - start) / size)))
    uniform = max(2, round(n * (1 - CORE_FRACTION) * 1.1))
    if spec.wall_grading >= 1.0:
        return MeshLayout(n, spec.radial_cells or uniform, tuple(levels), tuple(cells))
    middle = max(2, round(uniform * (ANNULUS_INNER - CORE_FRACTION) / (1 - CORE_FRACTION)))
    annulus = spec.radial_cells or 2 * uniform
    return MeshLayout(n, middle, tuple(levels), tuple(cells), annulus)


def wall_cell_size_m(spec: CaseSpec) -> float:
    """Radial size of the cells at the side wall, on the ring blocks' mid-lines [m]: a
    geometric progression over the annulus (or ring) cells whose last-to-first ratio is the
    grading.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=12,
    ...                 wall_grading=0.1, radial_cells=8)
    >>> round(wall_cell_size_m(spec) * 1e3, 4)
    0.0929
    """
    layout = mesh_layout(spec)
    if layout.annulus:
        length, count = spec.radius_m * (1.0 - ANNULUS_INNER), layout.annulus
    else:
        length, count = spec.radius_m * (1.0 - CORE_FRACTION / math.sqrt(2.0)), layout.radial
    ratio = spec.wall_grading
    if count == 1 or abs(ratio - 1.0) < 1e-12:
        return length / count
    q = ratio ** (1.0 / (count - 1))
    first = length * (q - 1.0) / (q**count - 1.0)
    return float(first * ratio)


def block_mesh_dict(spec: CaseSpec) -> str:
    """blockMeshDict of the O-grid in millimetres; the top is the ``atmosphere`` patch, every
    other face the ``walls`` patch.

    Uniform meshes: a square core and four ring blocks (core edge to wall arc). Wall-graded
    meshes add a wall annulus (arcs at `ANNULUS_INNER` R and R) that alone is graded: grading
    the ring blocks themselves squeezes skewed cells into the O-grid corners, where interFoam
    was seen to lose the hydrostatic balance (docs/cfd.md).

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> block_mesh_dict(spec).count("hex (")
    15
    """
    layout = mesh_layout(spec)
    radius = spec.radius_m * SCALE
    core = CORE_FRACTION * radius / math.sqrt(2.0)
    rings = [ANNULUS_INNER * radius, radius] if layout.annulus else [radius]
    per_level = 4 + 4 * len(rings)
    signs = [(1, 1), (-1, 1), (-1, -1), (1, -1)]  # corners at 45, 135, 225, 315 degrees
    vertices = []
    for z in layout.z_levels_m:
        zz = z * SCALE
        vertices += [(core * sx, core * sy, zz) for sx, sy in signs]
        for ring in rings:
            corner = ring / math.sqrt(2.0)
            vertices += [(corner * sx, corner * sy, zz) for sx, sy in signs]

    def vertex(level: int, ring: int, i: int) -> int:  # ring 0: the core square
        return per_level * level + 4 * ring + i

    n = layout.circumferential
    counts = [layout.radial, layout.annulus]
    gradings = ["1 1 1", f"{format_number(spec.wall_grading)} 1 1"]
    blocks, top_faces = [], []
    for level, count in enumerate(layout.z_cells):
        quads = [([vertex(level, 0, k) for k in (2, 3, 0, 1)], (n, n), "1 1 1")]
        for ring in range(1, len(rings) + 1):
            for a, b in ((3, 0), (0, 1), (1, 2), (2, 3)):
                quad = [
                    vertex(level, ring - 1, a),
                    vertex(level, ring, a),
                    vertex(level, ring, b),
                    vertex(level, ring - 1, b),
                ]
                quads.append((quad, (counts[ring - 1], n), gradings[ring - 1]))
        for bottom, (a, b), grading in quads:
            top = [v + per_level for v in bottom]
            blocks.append(
                f"    hex ({' '.join(map(str, bottom + top))}) ({a} {b} {count}) "
                f"simpleGrading ({grading})"
            )
            if level == len(layout.z_cells) - 1:
                top_faces.append(f"            ({' '.join(map(str, top))})")
    arcs = []
    pairs = [(3, 0), (0, 1), (1, 2), (2, 3)]
    for level, z in enumerate(layout.z_levels_m):
        for ring, ring_radius in enumerate(rings, start=1):
            midpoints = [(ring_radius, 0.0), (0.0, ring_radius), (-ring_radius, 0.0)]
            midpoints.append((0.0, -ring_radius))
            for (a, b), (mx, my) in zip(pairs, midpoints, strict=True):
                arcs.append(
                    f"    arc {vertex(level, ring, a)} {vertex(level, ring, b)} "
                    f"({format_number(round(mx, 9))} {format_number(round(my, 9))} "
                    f"{format_number(z * SCALE)})"
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
    cases), or ``spec.probe_angles`` equally spaced columns starting at +x.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    ndarray

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> probe_angles_rad(spec)
    array([0.        , 3.14159265])
    """
    count = spec.probe_angles or 2
    return np.asarray(2 * np.pi * np.arange(count) / count, dtype=float)


def probe_columns(spec: CaseSpec) -> tuple[NDArray[np.float64], float]:
    """z of the probes in each column [m] and their spacing dz [m].

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    tuple
        (z of the probes [m], spacing dz [m]).

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> z, dz = probe_columns(spec)
    >>> z.size, round(dz * 1e3, 4)
    (109, 0.6399)
    """
    count = spec.probes_per_column or max(
        40, round(spec.height_m / (spec.radius_m / (4 * spec.cells_per_radius)))
    )
    dz = spec.height_m / count
    return np.asarray((np.arange(count) + 0.5) * dz, dtype=float), dz
