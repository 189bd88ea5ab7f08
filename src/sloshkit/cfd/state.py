"""The state of a case on disk, and checks made before running it (no processes started).

- Which time folders are *complete* (every restart field of every processor written to its
  closing line), so that an interrupted run restarts from the latest complete one.
- checkMesh's verdict on the mesh, and the limits on the number of MPI processes.
"""

from __future__ import annotations

import enum
import math
import os
import re
import shutil
import warnings
from dataclasses import dataclass
from pathlib import Path

from sloshkit.errors import InputError, ValidityWarning

#: checkMesh limits beyond which interFoam was seen to diverge here (docs/cfd.md,
#: studies/cfd-damping/data/cfd-wall-grading.json). On the O-grid cylinder, thin wedge-shaped
#: wall cells amplify round-off in every pressure corrector (even in one fluid at rest, with
#: any time step) once the minimum cell determinant falls to 2.3e-4 or below; 9.4e-4 and
#: above stayed stable. (A flat wall with determinant 2e-5 was stable: the limit is one of thin cells on a curved
#: wall.) checkMesh itself flags determinants below 0.001, which stable graded meshes have.
MIN_DETERMINANT = 5e-4
#: In two-phase runs of 2 s the graded O-grids with the largest aspect ratio 29.6 kept parasitic
#: currents at Courant numbers of 1-3 (and the frequency 7 % off); 19 ran cleanly, and one at
#: 19.6 still blew up at a 1 ms step: the limit is marginal, kept at 20 (docs/cfd.md).
MAX_ASPECT_RATIO = 20.0
MAX_NON_ORTHOGONALITY = 65.0
#: Below this minimum determinant (but above `MIN_DETERMINANT`) a mesh runs with a warning:
#: two-phase free decays of 2 s on graded O-grids with 6.5e-4, 9.7e-4 and 1.4e-3 blew up or
#: kept parasitic currents; one with 9.4e-4 ran cleanly (docs/cfd.md).
MARGINAL_DETERMINANT = 2e-3
#: Below this step (fixed, or the largest of an adaptive one) a wall-graded mesh runs with a
#: warning: every graded O-grid of the damping study carried a step-to-step pressure
#: oscillation at 0.5 ms (wall-force noise ratio 0.3-2.4), and none of 13 solver and property
#: changes removed it (studies/cfd-damping/README.md, "The wall force's noise at small steps").
#: The step where it starts depends on the mesh (2 ms at 9 cells per radius, below 0.7 ms at 20), so
#: this is a first warning; `cfd analyse` measures it in the run (force_step_alternation).
MIN_GRADED_STEP_S = 1e-3
#: checkMesh failures covered by `MIN_DETERMINANT` instead of its own 0.001.
TOLERATED_CHECKS = ("small determinant",)
#: Fewest cells per MPI process, and most processes per core, accepted for --np.
MIN_CELLS_PER_PROCESS = 250
MAX_PROCESSES_PER_CORE = 4
#: Fields a time folder needs to restart interFoam from it.
RESTART_FIELDS = ("alpha.water", "U", "p_rgh")
FOAM_FILE_END = b"// ****"


class CfdError(RuntimeError):
    """OpenFOAM is missing, a tool failed, or the solver stopped early.

    Examples
    --------
    >>> raise CfdError("interFoam stopped at t = 0.1 s")
    Traceback (most recent call last):
    ...
    sloshkit.cfd.state.CfdError: interFoam stopped at t = 0.1 s
    """


class CfdInterrupted(Exception):
    """The run was stopped by a signal (the tools are stopped too; ``--resume`` continues).

    Parameters
    ----------
    signum : int
        The signal.
    simulated_s : float
        Simulated time reached [s].

    Examples
    --------
    >>> str(CfdInterrupted(15, 0.25))
    'interrupted by signal 15 at t = 0.25 s'
    """

    def __init__(self, signum: int, simulated_s: float) -> None:
        self.signum = signum
        self.simulated_s = simulated_s
        super().__init__(f"interrupted by signal {signum} at t = {simulated_s:.6g} s")


class RunStatus(enum.Enum):
    """Outcome of a CFD run.

    Parameters
    ----------
    value : str
        ``completed`` or ``failed``.
    names, module, qualname, type, start, boundary : optional
        The arguments of Python's functional `enum.Enum` API (not used here).

    Returns
    -------
    RunStatus

    Examples
    --------
    >>> RunStatus("completed") is RunStatus.COMPLETED
    True
    """

    COMPLETED = "completed"
    FAILED = "failed"


@dataclass(frozen=True)
class RunResult:
    """A finished run: the case, how far it got, and how long it took.

    Parameters
    ----------
    case : Path
        The case folder.
    status : RunStatus
        The outcome.
    simulated_s, wall_clock_s : float
        Simulated time reached and wall clock of the run [s].
    processes, cells : int
        MPI processes and mesh cells.

    Returns
    -------
    RunResult

    Examples
    --------
    >>> from pathlib import Path
    >>> RunResult(Path("c"), RunStatus.COMPLETED, 2.0, 34.4, 2, 15004).status.value
    'completed'
    """

    case: Path
    status: RunStatus
    simulated_s: float
    wall_clock_s: float
    processes: int
    cells: int


def tail(text: str, lines: int = 25) -> str:
    r"""The last ``lines`` lines of a log.

    Parameters
    ----------
    text : str
        A log.
    lines : int
        How many lines.

    Returns
    -------
    str

    Examples
    --------
    >>> tail("a\nb\nc", 2)
    'b\nc'
    """
    return "\n".join(text.splitlines()[-lines:])


def check_processes(processes: int, cells: int, cores: int | None = None) -> None:
    """Refuse absurd MPI process counts, warn about oversubscription.

    More than `MAX_PROCESSES_PER_CORE` processes per core, or fewer than
    `MIN_CELLS_PER_PROCESS` cells per process, only slow a run down (communication dominates);
    more processes than cores runs, with a `ValidityWarning`.

    Parameters
    ----------
    processes : int
        Requested MPI processes.
    cells : int
        Cells of the mesh.
    cores : int, optional
        Cores of the machine (default: ``os.cpu_count()``).

    Returns
    -------
    None

    Raises
    ------
    InputError
        Too many processes for the cores or the mesh.

    Examples
    --------
    >>> check_processes(2, 15004, cores=2)
    >>> check_processes(64, 15004, cores=2)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: np = 64 is invalid: must be between 1 and 8 here ...
    """
    cores = cores or os.cpu_count() or 1
    limit = max(1, min(MAX_PROCESSES_PER_CORE * cores, cells // MIN_CELLS_PER_PROCESS))
    if processes > limit:
        raise InputError(
            "np",
            processes,
            f"must be between 1 and {limit} here ({cores} cores, {cells} cells: at most "
            f"{MAX_PROCESSES_PER_CORE} per core and at least {MIN_CELLS_PER_PROCESS} cells each)",
        )
    if processes > cores:
        warnings.warn(
            f"--np {processes} is more than the {cores} cores of this machine: "
            "the ranks will share cores and the run will be slower than with --np "
            f"{cores}",
            ValidityWarning,
            stacklevel=2,
        )


def check_graded_step(wall_grading: float, delta_t_s: float) -> None:
    """Warn (`ValidityWarning`) when a wall-graded mesh is to run at steps below
    `MIN_GRADED_STEP_S`.

    Parameters
    ----------
    wall_grading : float
        The case's wall grading (1: a uniform O-grid, never warned about).
    delta_t_s : float
        Its fixed step, or the largest step of an adaptive one [s].

    Returns
    -------
    None
        It only warns.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_graded_step(0.25, 5e-4)
    ...     check_graded_step(1.0, 5e-4)
    ...     check_graded_step(0.25, 2e-3)
    >>> len(caught), caught[0].category.__name__
    (1, 'ValidityWarning')
    """
    if wall_grading < 1.0 and delta_t_s < MIN_GRADED_STEP_S * (1.0 - 1e-9):
        warnings.warn(
            f"a wall-graded mesh at a step of {1e3 * delta_t_s:g} ms: below "
            f"{1e3 * MIN_GRADED_STEP_S:g} ms interFoam v1912 puts a step-to-step pressure "
            "oscillation into wall-graded meshes and the damping is not trustworthy (docs/cfd.md, "
            "damping; the step where it starts falls as the mesh is refined: 2 ms at 9 cells per "
            "radius, below 0.7 ms at 20); use --delta-t 1ms or more, or a uniform mesh, and check "
            "force_step_alternation in cfd analyse",
            ValidityWarning,
            stacklevel=2,
        )


def check_mesh_quality(log: str) -> dict[str, float]:
    r"""Parse checkMesh's cell count, non-orthogonality, skewness, aspect ratio and cell
    determinant; refuse meshes on which interFoam diverges.

    Parameters
    ----------
    log : str
        Output of ``checkMesh -allGeometry``.

    Returns
    -------
    dict of str to float
        ``cells``, ``max_non_orthogonality_deg``, ``max_skewness``, and where reported
        ``max_aspect_ratio`` and ``min_determinant``.

    Raises
    ------
    CfdError
        A cell determinant below `MIN_DETERMINANT`, an aspect ratio above `MAX_ASPECT_RATIO`,
        non-orthogonality above
        `MAX_NON_ORTHOGONALITY`, or a failed check other than `TOLERATED_CHECKS`.

    Examples
    --------
    >>> log = "    cells:            100\nMesh non-orthogonality Max: 20 average: 5\n"
    >>> log += "Cell determinant (wellposedness) : minimum: 0.002 average: 0.5\n"
    >>> check_mesh_quality(log)["min_determinant"]
    0.002
    """
    cells = re.search(r"^\s*cells:\s+(\d+)", log, re.M)
    orthogonality = re.search(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)", log)
    skewness = re.search(r"Max skewness = ([0-9.eE+-]+)", log)
    determinant = re.search(r"Cell determinant \(wellposedness\) : minimum: ([0-9.eE+-]+)", log)
    aspect = re.search(r"Max aspect ratio = ([0-9.eE+-]+)", log)
    quality = {
        "cells": float(cells.group(1)) if cells else math.nan,
        "max_non_orthogonality_deg": float(orthogonality.group(1)) if orthogonality else math.nan,
        "max_skewness": float(skewness.group(1)) if skewness else math.nan,
    }
    if aspect:
        quality["max_aspect_ratio"] = float(aspect.group(1))
        if quality["max_aspect_ratio"] > MAX_ASPECT_RATIO:
            raise CfdError(
                f"mesh refused: maximum cell aspect ratio {quality['max_aspect_ratio']:.3g} > "
                f"{MAX_ASPECT_RATIO:g} (parasitic currents in thin wall cells: use more "
                "cells around (--cells-per-radius) or more annulus cells (--radial-cells))"
            )
    if determinant:
        quality["min_determinant"] = float(determinant.group(1))
        if quality["min_determinant"] < MIN_DETERMINANT:
            raise CfdError(
                f"mesh refused: minimum cell determinant {quality['min_determinant']:.3g} "
                f"< {MIN_DETERMINANT:g} (thin cells on the curved wall make interFoam diverge "
                "here: use more cells around (--cells-per-radius) or a milder --wall-grading)"
            )
    if MIN_DETERMINANT <= quality.get("min_determinant", 1.0) < MARGINAL_DETERMINANT:
        warnings.warn(
            f"mesh is marginal: minimum cell determinant {quality['min_determinant']:.3g} "
            f"< {MARGINAL_DETERMINANT:g}; two-phase runs on such wall-graded meshes blew up or "
            "kept parasitic currents (check the Courant numbers in log.interFoam)",
            ValidityWarning,
            stacklevel=2,
        )
    failures = [
        line
        for line in log.splitlines()
        if line.strip().startswith("***") and not any(c in line for c in TOLERATED_CHECKS)
    ]
    if failures:
        raise CfdError("checkMesh reports failed mesh checks:\n" + tail(log))
    if quality["max_non_orthogonality_deg"] > MAX_NON_ORTHOGONALITY:
        raise CfdError(
            f"mesh refused: non-orthogonality {quality['max_non_orthogonality_deg']:.1f} deg"
        )
    return quality


def time_folders(folder: Path) -> dict[float, Path]:
    """The time folders in ``folder`` (names that are numbers).

    Parameters
    ----------
    folder : Path
        A case, processor or function-object folder.

    Returns
    -------
    dict of float to Path

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> case = Path(tempfile.mkdtemp())
    >>> for name in ("0", "0.5", "system"):
    ...     (case / name).mkdir()
    >>> sorted(time_folders(case))
    [0.0, 0.5]
    """
    times = {}
    if folder.is_dir():
        for entry in folder.iterdir():
            try:
                value = float(entry.name)
            except ValueError:
                continue
            if entry.is_dir():
                times[value] = entry
    return times


def _complete(folder: Path) -> bool:
    """Every restart field present and written to its closing line."""
    for name in RESTART_FIELDS:
        path = folder / name
        try:
            with open(path, "rb") as stream:
                stream.seek(max(0, path.stat().st_size - 200))
                if FOAM_FILE_END not in stream.read():
                    return False
        except OSError:
            return False
    return True


def _roots(case: Path, processes: int) -> list[Path]:
    if processes > 1:
        return [case / f"processor{k}" for k in range(processes)]
    return [case]


def latest_time(case: Path, processes: int) -> float:
    """The latest time folder, complete or not, of a (possibly decomposed) case [s].

    Parameters
    ----------
    case : Path
        The case folder.
    processes : int
        Its MPI processes (1: not decomposed).

    Returns
    -------
    float

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> case = Path(tempfile.mkdtemp())
    >>> for name in ("0", "0.5", "1"):
    ...     (case / name).mkdir()
    >>> latest_time(case, 1)
    1.0
    """
    return max(time_folders(_roots(case, processes)[0]), default=0.0)


def latest_complete_time(case: Path, processes: int) -> float | None:
    """The latest time whose fields are complete in every processor folder [s], or None.

    Parameters
    ----------
    case : Path
        The case folder.
    processes : int
        Its MPI processes (1: not decomposed).

    Returns
    -------
    float or None

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> case = Path(tempfile.mkdtemp())
    >>> for name in ("0", "0.5", "1"):
    ...     (case / name).mkdir()
    >>> latest_complete_time(case, 1) is None  # no fields written
    True
    """
    roots = _roots(case, processes)
    candidates = sorted(time_folders(roots[0]), reverse=True)
    for value in candidates:
        folders = [time_folders(root).get(value) for root in roots]
        if all(folder is not None and _complete(folder) for folder in folders):
            return value
    return None


def discard_after(case: Path, processes: int, start: float) -> None:
    """Remove time folders after ``start`` (half-written or stale) and the function-object
    output that begins at or after it (interFoam writes it again from ``start``).

    Parameters
    ----------
    case : Path
        The case folder.
    processes : int
        Its MPI processes (1: not decomposed).
    start : float
        The time the run restarts from [s].

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> case = Path(tempfile.mkdtemp())
    >>> for name in ("0", "0.5", "1"):
    ...     (case / name).mkdir()
    >>> discard_after(case, 1, 0.5)
    >>> sorted(time_folders(case))
    [0.0, 0.5]
    """
    for root in _roots(case, processes):
        for value, folder in time_folders(root).items():
            if value > start + 1e-12:
                shutil.rmtree(folder)
    post = case / "postProcessing"
    if post.is_dir():
        for function in post.iterdir():
            for value, folder in time_folders(function).items():
                if value >= start - 1e-12:
                    shutil.rmtree(folder)
