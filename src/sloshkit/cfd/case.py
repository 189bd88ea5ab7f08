"""Generation of an interFoam case for a filled upright cylinder (pure: returns file texts).

Choices, and why
----------------
- **Millimetres** (`sloshkit.cfd.spec.SCALE`): g' = 9810, nu' = 1e6 nu, sigma' = 1e9 sigma,
  accelerations x 1000; forces come back x 1e-12.
- **Container frame, body force.** The flow is solved on a static mesh in the container's
  frame with the fictitious forces of its motion, through the fvOption
  ``tabulatedAccelerationSource`` (`sloshkit.cfd.excitation`); the walls are at rest in that
  frame (no-slip).
- **Uniform O-grid** (`sloshkit.cfd.mesh`).
- **Adaptive time step** limited by the Courant and interface-Courant numbers and by a maximum
  step (Euler's numerical damping grows with the step; see the study in docs/cfd.md);
  ``Gauss vanLeer`` for alpha with MULES, laminar flow.
- **Write control**: fields (and ``grad(alpha.water)``) only at write times; the measurements
  below are small files appended every step.
- **Measurements** (function objects): columns of ``alpha.water`` probes at r = 0.98 R (two on
  the x axis, or ``probe_angles`` around the circumference; wall elevation = sum of alpha dz
  minus h), the volume integral of grad(alpha.water) (its x/z ratio is the mean free-surface
  slope, the paper's eq. 13), and the pressure and viscous force on the walls (``forces``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from sloshkit.cfd.excitation import (
    Excitation,
    FreeDecay,
    Harmonic,
    MotionExcitation,
    PoseExcitation,
    frame_motion,
)
from sloshkit.cfd.fields import initial_fields, set_fields_dict, transport_properties
from sloshkit.cfd.foam import Raw, foam_file, format_number
from sloshkit.cfd.mesh import (
    block_mesh_dict,
    mesh_layout,
    probe_angles_rad,
    probe_columns,
    wall_cell_size_m,
)
from sloshkit.cfd.spec import SCALE, CaseSpec
from sloshkit.cfd.system import (
    PROBE_RADIUS_FRACTION,
    control_dict,
    decompose_par_dict,
    fv_schemes,
    fv_solution,
)
from sloshkit.model.theory import GRAVITY_M_S2

__all__ = [
    "SCALE",
    "CaseSpec",
    "Excitation",
    "FreeDecay",
    "Harmonic",
    "MotionExcitation",
    "PoseExcitation",
    "acceleration_table",
    "block_mesh_dict",
    "case_files",
    "control_dict",
    "mesh_layout",
    "probe_columns",
    "set_fields_dict",
    "spec_summary",
]

#: Open MPI options that keep a run on this host: shared memory between the ranks (vader),
#: and loopback for the TCP transport and the out-of-band (runtime) channel; waiting ranks
#: yield their core (no busy polling: the machine may be shared).
MPI_LOCAL_OPTIONS = (
    "--mca",
    "btl",
    "self,vader",
    "--mca",
    "btl_tcp_if_include",
    "lo",
    "--mca",
    "oob_tcp_if_include",
    "lo",
    "--mca",
    "mpi_yield_when_idle",
    "1",
)


def acceleration_table(spec: CaseSpec, sample_period_s: float = 1e-3) -> str:
    """``constant/acceleration.dat``: (t ((ax ay az) (wx wy wz) (dwx dwy dwz))), lengths in mm,
    covering [0, endTime + 0.1 s] (a time outside the table is fatal).

    Parameters
    ----------
    spec : CaseSpec
        The case.
    sample_period_s : float
        Spacing of the table [s].

    Returns
    -------
    str
        The table file.

    References
    ----------
    OpenFOAM v1912 ``tabulatedAccelerationSource`` (the table's format).

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> acceleration_table(spec).splitlines()[2]
    '(0 ((0 0 0) (0 0 0) (0 0 0)))'
    """
    end = spec.end_time_s + 0.1
    t = np.arange(0.0, end + sample_period_s, sample_period_s)
    linear, omega, alpha = frame_motion(spec.excitation, t)
    linear = linear * SCALE

    def vector(v: np.ndarray) -> str:
        return "(" + " ".join(format_number(float(x)) for x in v) + ")"

    rows = "\n".join(
        f"({format_number(round(float(time), 9))} ({vector(a)} {vector(w)} {vector(dw)}))"
        for time, a, w, dw in zip(t, linear, omega, alpha, strict=True)
    )
    return f"{t.size}\n(\n{rows}\n)\n"


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
    # Shared memory between ranks, loopback for the rest; and a private network namespace
    # (loopback only) where the kernel allows it, because Open MPI 4.1's out-of-band listener
    # binds to every interface whatever oob_tcp_if_include says.
    mpi="mpirun --oversubscribe %MCA% -np $np interFoam -parallel"
    if unshare -rn sh -c 'ip link set lo up' > /dev/null 2>&1; then
        unshare -rn sh -c "ip link set lo up && exec $mpi" > log.interFoam 2>&1
    else
        $mpi > log.interFoam 2>&1
    fi
else
    interFoam > log.interFoam 2>&1
fi
"""


def case_files(spec: CaseSpec) -> dict[str, str]:
    """Every file of the case, path relative to the case folder -> text.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    dict of str to str

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> sorted(case_files(spec))[:3]
    ['0/U', '0/alpha.water', '0/p_rgh']
    """
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
                "value": Raw(f"(0 0 {format_number(-GRAVITY_M_S2 * SCALE)})"),
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
        "Allrun": ALLRUN.replace("%NP%", str(spec.processes)).replace(
            "%MCA%", " ".join(MPI_LOCAL_OPTIONS)
        ),
    }
    files.update(initial_fields())
    if isinstance(spec.excitation, PoseExcitation):
        files[POSE_FILE] = pose_table(spec.excitation)
    return files


POSE_FILE = "sloshkit-poses.csv"


def pose_table(excitation: PoseExcitation) -> str:
    """The pose trajectory that drives the case, as a pose file (`sloshkit.io.poses`), so the
    case can be compared with the 3-D model later without the original file.

    Parameters
    ----------
    excitation : PoseExcitation
        The pose-driven excitation.

    Returns
    -------
    str
        CSV text with ``t [s], x [m], y [m], z [m], qx, qy, qz, qw``.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> t = np.linspace(0.0, 1.0, 3)
    >>> poses = PoseTrajectory(t, np.zeros((3, 3)), np.tile([0.0, 0.0, 0.0, 1.0], (3, 1)))
    >>> pose_table(PoseExcitation(poses)).splitlines()[1]
    '0.0,0.0,0.0,0.0,0.0,0.0,0.0,1.0'
    """
    poses = excitation.poses
    rows = ["t [s],x [m],y [m],z [m],qx,qy,qz,qw"]
    for time, position, quaternion in zip(
        poses.time_s, poses.position_m, poses.quaternion_xyzw, strict=True
    ):
        values = [time, *position, *quaternion]
        rows.append(",".join(repr(float(v)) for v in values))
    return "\n".join(rows) + "\n"


def spec_summary(spec: CaseSpec) -> dict[str, Any]:
    """JSON-ready description of a case (SI), written beside it as sloshkit-case.json.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    dict

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> summary = spec_summary(spec)
    >>> summary["cells"], summary["excitation"]["type"]
    (6336, 'FreeDecay')
    """
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
    elif isinstance(excitation, PoseExcitation):
        description.update(
            name=excitation.name,
            duration_s=excitation.duration_s,
            pose_file=POSE_FILE,
            cutoff_hz=excitation.cutoff_hz,
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
        "adjust_time_step": spec.adjust_time_step,
        "max_courant": spec.max_courant,
        "max_alpha_courant": spec.max_alpha_courant,
        "write_interval_s": spec.write_interval_s,
        "ddt_scheme": spec.ddt_scheme,
        "pressure_correctors": spec.pressure_correctors,
        "momentum_predictor": spec.momentum_predictor,
        "surface_refinement": spec.surface_refinement,
        "wall_grading": spec.wall_grading,
        "radial_cells": mesh_layout(spec).radial,
        "wall_cell_m": wall_cell_size_m(spec),
        "processes": spec.processes,
        "probe_dz_m": dz,
        "probes_per_column": int(z.size),
        "probe_x_m": PROBE_RADIUS_FRACTION * spec.radius_m,
        "probe_radius_m": PROBE_RADIUS_FRACTION * spec.radius_m,
        "probe_angles_rad": [float(a) for a in probe_angles_rad(spec)],
        "excitation": description,
        "units_in_case": "mm (lengths x1000, g 9810, nu x1e6, sigma x1e9)",
    }
