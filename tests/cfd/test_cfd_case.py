"""CFD case generation and result parsing (pure: no OpenFOAM needed)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from sloshkit.cfd.case import (
    CaseSpec,
    FreeDecay,
    Harmonic,
    block_mesh_dict,
    case_files,
    mesh_layout,
    probe_columns,
    set_fields_dict,
)
from sloshkit.cfd.foam import Raw, foam_file, format_value, read_scalar_internal_field
from sloshkit.cfd.results import parse_table, read_function_object, read_signals
from sloshkit.cfd.run import write_case
from sloshkit.errors import InputError
from sloshkit.model.liquids import get_liquid

WATER = get_liquid("water-25C")


def spec(**kwargs) -> CaseSpec:
    settings = dict(
        radius_m=0.0205, fill_height_m=0.039, liquid=WATER, cells_per_radius=6, end_time_s=0.5
    )
    settings.update(kwargs)
    return CaseSpec(**settings)


def test_foam_writer_syntax():
    text = foam_file(
        "dictionary",
        "demo",
        {"a": 1, "b": 2.5, "c": {"d": "word", "e": [1, 2, 3]}, "f": Raw("(x y)")},
    )
    assert "FoamFile" in text and "object          demo;" in text
    assert re.search(r"a\s+1;", text) and re.search(r"b\s+2.5;", text)
    assert re.search(r"c\n\{\n    d\s+word;\n    e\s+\(1 2 3\);\n\}", text)
    assert format_value(True) == "true" and format_value(3.0) == "3"


def test_read_scalar_fields():
    assert np.all(read_scalar_internal_field("internalField uniform 0.5;", cells=3) == 0.5)
    field = "internalField   nonuniform List<scalar> 3\n(\n0\n0.25\n1\n)\n;"
    np.testing.assert_allclose(read_scalar_internal_field(field), [0, 0.25, 1])


def test_mesh_layout_counts_and_surface_refinement():
    layout = mesh_layout(spec(cells_per_radius=10))
    assert layout.cells_per_layer == 10 * 10 + 4 * 10 * layout.radial
    levels = np.array(layout.z_levels_m)
    sizes = np.diff(levels) / np.array(layout.z_cells)
    band = np.argmin(sizes)
    assert levels[band] < 0.039 < levels[band + 1]  # the fine layer holds the free surface
    assert sizes.max() / sizes.min() == pytest.approx(2.0, rel=0.2)
    assert layout.cells == layout.cells_per_layer * sum(layout.z_cells)


@pytest.mark.parametrize("refinement", [1, 3, 4])
def test_surface_refinement_sets_the_band_cells_only(refinement):
    base, fine = (
        mesh_layout(spec(cells_per_radius=10)),
        mesh_layout(spec(cells_per_radius=10, surface_refinement=refinement)),
    )
    sizes = np.diff(fine.z_levels_m) / np.array(fine.z_cells)
    band = np.argmin(sizes)
    assert sizes[band] == pytest.approx(0.0205 / (refinement * 10), rel=0.1)
    assert fine.z_levels_m == base.z_levels_m  # the band itself does not move
    others = [k for k in range(len(sizes)) if k != band]
    assert fine.z_cells[others[0]] == base.z_cells[others[0]]


def test_momentum_predictor_reaches_fv_solution():
    from sloshkit.cfd.system import fv_solution

    assert "momentumPredictor no;" in fv_solution(spec())
    assert "momentumPredictor yes;" in fv_solution(spec(momentum_predictor=True))


def test_block_mesh_dict_geometry():
    case = spec()
    text = block_mesh_dict(case)
    layout = mesh_layout(case)
    vertices = re.search(r"vertices\s*\n\(\n(.*?)\n\);", text, re.S).group(1).splitlines()
    assert len(vertices) == 8 * len(layout.z_levels_m)
    assert text.count("hex (") == 5 * len(layout.z_cells)
    assert text.count("arc ") == 4 * len(layout.z_levels_m)
    points = np.array([[float(v) for v in line.strip(" ()").split()] for line in vertices])
    radii = np.hypot(points[:, 0], points[:, 1])
    assert radii.max() == pytest.approx(20.5, rel=1e-9)  # millimetres
    assert points[:, 2].max() == pytest.approx(1000 * case.height_m)


def _inside_rotated_box(text: str, point: np.ndarray) -> bool:
    def vector(name):
        return np.array(
            [float(v) for v in re.search(rf"{name} \(([^)]*)\)", text).group(1).split()]
        )

    origin, i, j, k = (vector(n) for n in ("origin", "i", "j", "k"))
    coefficients = np.linalg.solve(np.column_stack([i, j, k]), point - origin)
    return bool(np.all((coefficients >= 0) & (coefficients <= 1)))


def test_tilted_fill_is_a_plane_through_the_axis():
    tilt = math.radians(5.0)
    text = set_fields_dict(spec(excitation=FreeDecay(tilt)))
    for x in (-15.0, 0.0, 15.0):
        surface = 39.0 + x * math.tan(tilt)
        assert _inside_rotated_box(text, np.array([x, 3.0, surface - 0.2]))
        assert not _inside_rotated_box(text, np.array([x, 3.0, surface + 0.2]))
    flat = set_fields_dict(spec(excitation=FreeDecay(0.0)))
    assert "boxToCell" in flat and "39" in flat


def test_acceleration_table_covers_the_run_and_matches_the_excitation():
    case = spec(excitation=Harmonic(0.01, 1.0, 0.4), end_time_s=0.5)
    table = case_files(case)["constant/acceleration.dat"]
    rows = [
        line
        for line in table.splitlines()
        if line.startswith("((") is False and line.startswith("(") and "((" in line
    ]
    times = np.array([float(r[1:].split()[0]) for r in rows])
    values = np.array([float(r.split("((")[1].split()[0]) for r in rows])
    assert times[0] == 0.0 and times[-1] >= 0.5
    expected = -0.01 * (2 * math.pi) ** 2 * np.sin(2 * math.pi * times) * 1000
    expected[times > 0.4] = 0.0
    np.testing.assert_allclose(values, expected, atol=1e-9)


def test_case_files_and_allrun(tmp_path):
    case = spec(processes=2)
    files = case_files(case)
    for name in (
        "system/blockMeshDict",
        "system/controlDict",
        "system/fvSchemes",
        "system/fvSolution",
        "system/setFieldsDict",
        "system/decomposeParDict",
        "constant/transportProperties",
        "constant/g",
        "constant/fvOptions",
        "0/alpha.water",
        "0/U",
        "0/p_rgh",
        "Allrun",
    ):
        assert name in files
    control = files["system/controlDict"]
    for function in ("wallProbes", "surfaceTilt", "wallForces", "gradAlpha"):
        assert function in control
    z, _ = probe_columns(case)
    assert control.count("(20.09 0 ") == z.size and control.count("(-20.09 0 ") == z.size
    assert "(0 0 -9810)" in files["constant/g"]
    assert "nu              0.89257" in files["constant/transportProperties"]  # mm^2/s
    written = write_case(case, tmp_path / "case")
    assert (written / "Allrun").stat().st_mode & 0o111
    with pytest.raises(InputError, match="not empty"):
        write_case(case, tmp_path / "case")


@pytest.mark.parametrize(
    ("kwargs", "parameter"),
    [
        ({"cells_per_radius": 1}, "cells_per_radius"),
        ({"delta_t_s": 1.0}, "delta_t"),
        ({"domain_height_m": 0.03}, "domain_height"),
        ({"ddt_scheme": "RK4"}, "ddt_scheme"),
        ({"radius_m": -1.0}, "radius"),
        ({"surface_refinement": 0}, "surface_refinement"),
        ({"surface_refinement": 9}, "surface_refinement"),
    ],
)
def test_bad_case_specs(kwargs, parameter):
    with pytest.raises(InputError) as info:
        spec(**kwargs)
    assert info.value.parameter == parameter


def test_parse_v1912_tables_and_restarts(tmp_path):
    text = (
        "# Time (total_x total_y total_z) (pressure_x pressure_y pressure_z)\n"
        "0.1\t(1 2 3)\t(4 5 6)\n0.2\t(7 8 9)\t(1 1 1)\n"
    )
    np.testing.assert_allclose(
        parse_table(text), [[0.1, 1, 2, 3, 4, 5, 6], [0.2, 7, 8, 9, 1, 1, 1]]
    )
    root = tmp_path / "postProcessing" / "fo"
    (root / "0").mkdir(parents=True)
    (root / "0.2").mkdir()
    (root / "0" / "f.dat").write_text("0.1 1\n0.2 2\n0.3 3\n")
    (root / "0.2" / "f.dat").write_text("0.2 20\n0.3 30\n0.4 40\n")
    merged = read_function_object(tmp_path, "fo", "f.dat")
    np.testing.assert_allclose(merged, [[0.1, 1], [0.2, 20], [0.3, 30], [0.4, 40]])


def test_read_signals_from_synthetic_output(tmp_path):
    case = spec(end_time_s=0.2)
    folder = write_case(case, tmp_path / "case")
    z, dz = probe_columns(case)
    t = np.array([0.0, 0.1, 0.2])
    elevation = np.array([0.001, -0.0005, 0.0])
    rows = []
    for time, eta in zip(t, elevation, strict=True):
        plus = np.clip((0.039 + eta - (z - dz / 2)) / dz, 0, 1)
        minus = np.clip((0.039 - eta - (z - dz / 2)) / dz, 0, 1)
        rows.append(" ".join(f"{v:.9f}" for v in [time, *plus, *minus]))
    probes = folder / "postProcessing" / "wallProbes" / "0"
    probes.mkdir(parents=True)
    (probes / "alpha.water").write_text("# Probe 0 (20 0 1)\n# Time values\n" + "\n".join(rows))
    tilt = folder / "postProcessing" / "surfaceTilt" / "0"
    tilt.mkdir(parents=True)
    (tilt / "volFieldValue.dat").write_text(
        "# Time volIntegrate\n0 (10 0 -1000)\n0.2 (0 0 -1000)\n"
    )
    forces = folder / "postProcessing" / "wallForces" / "0"
    forces.mkdir(parents=True)
    (forces / "force.dat").write_text(
        "# Time\n0 (1e12 0 -5e11) (0 0 0) (0 0 0)\n0.2 (2e12 0 -5e11) (0 0 0) (0 0 0)\n"
    )
    signals = read_signals(folder)
    np.testing.assert_allclose(signals.elevation_plus_m, elevation, atol=1e-12)
    np.testing.assert_allclose(signals.elevation_m, elevation, atol=1e-12)
    assert signals.tilt_rad[0] == pytest.approx(math.atan(0.01))
    np.testing.assert_allclose(signals.force_x_n, [1.0, 1.5, 2.0])


def test_a_row_cut_by_a_killed_run_is_dropped():
    text = "# Time alpha\n0.001 0.5 0.25\n0.002 0.5 0.25\n0.003 0.5"
    assert parse_table(text).shape == (2, 3)
    assert parse_table(text + " 5e-\n").shape == (2, 3)
