"""CFD pipeline: case from a model, run, signals, calibration, and comparison with the
equivalent pendulum for the same motion (the seed paper's Table 4 and Figs. 5 and 9).

The calibration of a finished case lives in `sloshkit.cfd.analysis` (`analyse`, re-exported
here), the comparison's result object in `sloshkit.cfd.validation`.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from sloshkit.cfd.analysis import (
    CfdAnalysis,
    analyse,
    excitation_end,
    read_finished_signals,
)
from sloshkit.cfd.case import (
    CaseSpec,
    Excitation,
    FreeDecay,
    Harmonic,
    MotionExcitation,
    PoseExcitation,
)
from sloshkit.cfd.run import (
    RunResult,
    check_processes,
    expected_cells,
    interruptible,
    require_openfoam,
    run_case,
    write_case,
)
from sloshkit.cfd.state import check_graded_step
from sloshkit.cfd.summary import read_case_summary
from sloshkit.cfd.validation import model_wall_elevation, validate
from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel

__all__ = [
    "RECOMMENDED",
    "CfdAnalysis",
    "analyse",
    "case_spec",
    "describe",
    "excitation_end",
    "excitation_from_options",
    "model_wall_elevation",
    "read_finished_signals",
    "run",
    "validate",
]

#: Settings recommended by the mesh and time-step study (docs/cfd.md).
RECOMMENDED: dict[str, Any] = {
    "cells_per_radius": 11,
    "delta_t_s": 2e-3,
    "max_courant": 0.5,
    "max_alpha_courant": 0.5,
    "ddt_scheme": "Euler",
    "end_time_s": 3.0,
    "pressure_correctors": 3,
}


def case_spec(
    model: SloshModel,
    excitation: Excitation,
    cells_per_radius: int = RECOMMENDED["cells_per_radius"],
    end_time_s: float = RECOMMENDED["end_time_s"],
    delta_t_s: float = RECOMMENDED["delta_t_s"],
    ddt_scheme: str = RECOMMENDED["ddt_scheme"],
    processes: int = 1,
    surface_tension: bool = False,
    max_courant: float = RECOMMENDED["max_courant"],
    max_alpha_courant: float = RECOMMENDED["max_alpha_courant"],
    adjust_time_step: bool = True,
    probe_angles: int = 0,
    pressure_correctors: int = RECOMMENDED["pressure_correctors"],
    wall_grading: float = 1.0,
    radial_cells: int | None = None,
    momentum_predictor: bool = False,
    surface_refinement: int = 2,
) -> CaseSpec:
    """A case for ``model``'s container, fill and liquid.

    With ``adjust_time_step`` the step follows the Courant limits and never exceeds
    ``delta_t_s``; otherwise it is fixed at ``delta_t_s``.

    Parameters
    ----------
    model : SloshModel
        Container, fill and liquid.
    excitation : Excitation
        The container motion.
    cells_per_radius : int
        Mesh resolution.
    end_time_s, delta_t_s : float
        Simulated time and largest (or fixed) step [s].
    ddt_scheme : str
        Time scheme.
    processes : int
        MPI processes.
    surface_tension : bool
        Include surface tension.
    max_courant, max_alpha_courant : float
        Courant limits of the adaptive step.
    adjust_time_step : bool
        Adaptive (else fixed) step.
    probe_angles : int
        Probe columns around the wall (0: two on the x axis).
    pressure_correctors : int
        PIMPLE pressure correctors.
    wall_grading : float
        Wall refinement (1: uniform; see `CaseSpec`).
    radial_cells : int, optional
        Cells across the ring blocks or the graded wall annulus.
    momentum_predictor : bool
        PIMPLE momentum predictor (see `CaseSpec`).
    surface_refinement : int
        Vertical refinement near the free surface (see `CaseSpec`).

    Returns
    -------
    CaseSpec

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> spec = case_spec(model, FreeDecay(0.05), cells_per_radius=12, wall_grading=0.1,
    ...                  radial_cells=8)
    >>> spec.fill_height_m, spec.wall_grading
    (0.039, 0.1)
    """
    return CaseSpec(
        radius_m=model.radius_m,
        fill_height_m=model.fill_height_m,
        liquid=model.liquid,
        excitation=excitation,
        domain_height_m=model.container.wall_height_m,
        cells_per_radius=cells_per_radius,
        end_time_s=end_time_s,
        delta_t_s=delta_t_s,
        ddt_scheme=ddt_scheme,
        processes=processes,
        surface_tension=surface_tension,
        adjust_time_step=adjust_time_step,
        max_courant=max_courant,
        max_alpha_courant=max_alpha_courant,
        probe_angles=probe_angles,
        pressure_correctors=pressure_correctors,
        wall_grading=wall_grading,
        radial_cells=radial_cells,
        momentum_predictor=momentum_predictor,
        surface_refinement=surface_refinement,
    )


def run(
    spec: CaseSpec, case: Path, resume: bool = False, overwrite: bool = False, progress: Any = None
) -> RunResult:
    """Write (unless resuming) and run a case; record the run in sloshkit-run.json.

    Everything that can be checked before writing is checked first (OpenFOAM and mpirun
    present, a sensible --np), so a refused run leaves no files behind.

    Parameters
    ----------
    spec : CaseSpec
        The case.
    case : Path
        Its folder.
    resume : bool
        Continue an interrupted run.
    overwrite : bool
        Replace an existing sloshkit case.
    progress : callable, optional
        Progress callback (see `sloshkit.cfd.run.run_case`).

    Returns
    -------
    RunResult

    Raises
    ------
    InputError
        Bad --np, or a folder that cannot be written.
    CfdError
        OpenFOAM missing or failing.

    Examples
    --------
    >>> import shutil
    >>> from pathlib import Path
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), processes=64)
    >>> if shutil.which("interFoam"):  # refused before any file is written
    ...     try:
    ...         run(spec, Path("never-written"))
    ...     except InputError as error:
    ...         print(error.parameter)
    ... else:
    ...     print("np")
    np
    """
    require_openfoam(spec.processes)
    with interruptible([], [0.0]):
        _check_and_write(spec, case, resume, overwrite)
        result = run_case(case, spec.processes, resume=resume, progress=progress)
        record = {
            "simulated_s": result.simulated_s,
            "wall_clock_s": result.wall_clock_s,
            "processes": result.processes,
            "cells": result.cells,
            "finished": time.time(),
        }
        staging = case / "sloshkit-run.json.tmp"
        staging.write_text(json.dumps(record, indent=2), encoding="utf-8")
        staging.replace(case / "sloshkit-run.json")
    return result


def _check_and_write(spec: CaseSpec, case: Path, resume: bool, overwrite: bool) -> None:
    if resume:
        if not (case / "sloshkit-case.json").is_file():
            raise InputError("case", str(case), "has no sloshkit case to resume")
        summary = read_case_summary(case)
        check_processes(spec.processes, int(summary["cells"]))
    else:
        check_processes(spec.processes, expected_cells(spec))
        check_graded_step(spec.wall_grading, spec.delta_t_s)
        write_case(spec, case, overwrite=overwrite)


def excitation_from_options(
    kind: str,
    tilt_rad: float,
    amplitude_m: float,
    frequency_hz: float,
    excite_time_s: float,
    motion: Any = None,
    poses: Any = None,
) -> Excitation:
    """Build the excitation named on the command line.

    Parameters
    ----------
    kind : str
        ``free-decay``, ``harmonic``, ``law`` or ``poses``.
    tilt_rad : float
        Initial tilt of a free decay [rad].
    amplitude_m, frequency_hz, excite_time_s : float
        The harmonic excitation.
    motion : Any, optional
        A motion law (``law``).
    poses : PoseTrajectory, optional
        A pose trajectory (``poses``).

    Returns
    -------
    Excitation

    Raises
    ------
    InputError
        An unknown kind, or a missing motion or pose file.

    Examples
    --------
    >>> excitation_from_options("harmonic", 0.05, 0.01, 1.0, 2.0)
    Harmonic(amplitude_m=0.01, frequency_hz=1.0, duration_s=2.0)
    """
    if kind == "poses":
        if poses is None:
            raise InputError("excitation", kind, "needs --pose-file")
        return PoseExcitation(poses)
    if kind == "free-decay":
        return FreeDecay(tilt_rad)
    if kind == "harmonic":
        return Harmonic(amplitude_m, frequency_hz, excite_time_s)
    if kind == "law":
        if motion is None:
            raise InputError("excitation", kind, "needs --law and the move options")
        return MotionExcitation(motion.name, motion.acceleration, motion.duration_s)
    raise InputError("excitation", kind, "must be free-decay, harmonic, law or poses")


def describe(record: dict[str, Any]) -> str:
    """One line about a run's cost.

    Parameters
    ----------
    record : dict
        ``sloshkit-run.json``.

    Returns
    -------
    str
        Empty when the record lacks the numbers.

    Examples
    --------
    >>> describe({"wall_clock_s": 34.4, "simulated_s": 2.0})
    '2 s simulated in 34 s wall clock (17 s per simulated second)'
    """
    wall = record.get("wall_clock_s")
    simulated = record.get("simulated_s")
    if not wall or not simulated:
        return ""
    return f"{simulated:g} s simulated in {wall:.0f} s wall clock ({wall / simulated:.0f} s per simulated second)"
