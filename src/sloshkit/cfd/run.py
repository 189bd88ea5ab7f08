"""Running OpenFOAM: the only module of sloshkit that starts processes.

Writes a generated case to disk, then runs blockMesh, checkMesh (poor meshes are refused),
setFields, decomposePar and interFoam (serial, or ``mpirun -np N``), feeding a progress callback
from the solver log. A solver that stops early (exit code 136 is a floating-point exception)
raises `CfdError` with the tail of the log.
"""

from __future__ import annotations

import enum
import json
import math
import os
import re
import shutil
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from sloshkit.cfd.case import CaseSpec, case_files, mesh_layout, spec_summary
from sloshkit.errors import InputError

TIME_LINE = re.compile(r"^Time = ([0-9.eE+-]+)$")
COURANT_LINE = re.compile(r"^Courant Number mean: \S+ max: (\S+)")
#: checkMesh limits beyond which interFoam was seen to diverge here (cfd-notes.md).
MIN_DETERMINANT = 0.05
MAX_NON_ORTHOGONALITY = 65.0


class CfdError(RuntimeError):
    """OpenFOAM is missing, a tool failed, or the solver stopped early."""


class RunStatus(enum.Enum):
    """Outcome of a CFD run."""

    COMPLETED = "completed"
    FAILED = "failed"


@dataclass(frozen=True)
class RunResult:
    """A finished run: the case, how far it got, and how long it took."""

    case: Path
    status: RunStatus
    simulated_s: float
    wall_clock_s: float
    processes: int
    cells: int


Progress = Callable[[float, float, float | None], None]  # (simulated, end, max Courant)


def openfoam_environment() -> dict[str, str]:
    """The environment the v1912 tools need: WM_PROJECT_DIR set, MPI allowed as root, PWD
    dropped (it triggers a 'PWD is not the cwd()' warning)."""
    environment = {k: v for k, v in os.environ.items() if k != "PWD"}
    environment.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    environment["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    environment["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    environment["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    return environment


def require_openfoam() -> None:
    """Raise `CfdError` unless interFoam and blockMesh are on the PATH."""
    missing = [
        tool for tool in ("blockMesh", "setFields", "interFoam") if shutil.which(tool) is None
    ]
    if missing:
        raise CfdError(
            "OpenFOAM is not installed (missing " + ", ".join(missing) + "): "
            "apt-get install -y openfoam"
        )


def write_case(spec: CaseSpec, case: Path, overwrite: bool = False) -> Path:
    """Write the case files (and sloshkit-case.json) into ``case``."""
    if case.exists() and any(case.iterdir()) and not overwrite:
        raise InputError("case", str(case), "exists and is not empty (use --overwrite or --resume)")
    case.mkdir(parents=True, exist_ok=True)
    for relative, text in case_files(spec).items():
        path = case / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    (case / "Allrun").chmod(0o755)
    (case / "sloshkit-case.json").write_text(
        json.dumps(spec_summary(spec), indent=2), encoding="utf-8"
    )
    return case


def _tool(case: Path, command: list[str], log_name: str) -> str:
    log = case / log_name
    with open(log, "w", encoding="utf-8") as stream:
        completed = subprocess.run(
            command,
            cwd=case,
            env=openfoam_environment(),
            stdout=stream,
            stderr=subprocess.STDOUT,
            check=False,
        )
    text = log.read_text(encoding="utf-8", errors="replace")
    if completed.returncode != 0:
        raise CfdError(f"{command[0]} failed (exit {completed.returncode}):\n" + _tail(text))
    return text


def _tail(text: str, lines: int = 25) -> str:
    return "\n".join(text.splitlines()[-lines:])


def check_mesh_quality(log: str) -> dict[str, float]:
    """Parse checkMesh's cell count, non-orthogonality and skewness; refuse poor meshes."""
    cells = re.search(r"^\s*cells:\s+(\d+)", log, re.M)
    orthogonality = re.search(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)", log)
    skewness = re.search(r"Max skewness = ([0-9.eE+-]+)", log)
    determinant = re.search(r"Cell determinant \(wellposedness\) : minimum: ([0-9.eE+-]+)", log)
    quality = {
        "cells": float(cells.group(1)) if cells else math.nan,
        "max_non_orthogonality_deg": float(orthogonality.group(1)) if orthogonality else math.nan,
        "max_skewness": float(skewness.group(1)) if skewness else math.nan,
    }
    if determinant:
        quality["min_determinant"] = float(determinant.group(1))
        if quality["min_determinant"] < MIN_DETERMINANT:
            raise CfdError(
                f"mesh refused: minimum cell determinant {quality['min_determinant']:.3g} "
                f"< {MIN_DETERMINANT} (interFoam diverges on such meshes here)"
            )
    if "Failed" in log and "mesh checks" in log:
        raise CfdError("checkMesh reports failed mesh checks:\n" + _tail(log))
    if quality["max_non_orthogonality_deg"] > MAX_NON_ORTHOGONALITY:
        raise CfdError(
            f"mesh refused: non-orthogonality {quality['max_non_orthogonality_deg']:.1f} deg"
        )
    return quality


def latest_time(case: Path, processes: int) -> float:
    """The latest written time of a (possibly decomposed) case [s]."""
    folder = case / "processor0" if processes > 1 and (case / "processor0").is_dir() else case
    times = []
    for entry in folder.iterdir():
        try:
            times.append(float(entry.name))
        except ValueError:
            continue
    return max(times, default=0.0)


def run_case(
    case: Path,
    processes: int = 1,
    resume: bool = False,
    progress: Progress | None = None,
) -> RunResult:
    """Mesh, initialise and run the case written in ``case``.

    ``resume`` continues from the latest written time (the mesh and fields are kept).
    """
    require_openfoam()
    summary = json.loads((case / "sloshkit-case.json").read_text(encoding="utf-8"))
    end = float(summary["end_time_s"])
    started = time.perf_counter()
    if not resume or not (case / "constant" / "polyMesh").is_dir():
        _tool(case, ["blockMesh"], "log.blockMesh")
        check_mesh_quality(_tool(case, ["checkMesh", "-allGeometry"], "log.checkMesh"))
        _tool(case, ["setFields"], "log.setFields")
        for processor in case.glob("processor*"):
            shutil.rmtree(processor)
        for folder in (case / "postProcessing",):
            shutil.rmtree(folder, ignore_errors=True)
    if processes > 1 and not (case / "processor0").is_dir():
        _set_subdomains(case, processes)
        _tool(case, ["decomposePar", "-force"], "log.decomposePar")
    command = (
        ["interFoam"]
        if processes == 1
        else [
            "mpirun",
            "--oversubscribe",
            "-np",
            str(processes),
            "interFoam",
            "-parallel",
        ]
    )
    log_path = case / "log.interFoam"
    mode = "a" if resume else "w"
    simulated = latest_time(case, processes) if resume else 0.0
    courant: float | None = None
    with open(log_path, mode, encoding="utf-8") as log:
        process = subprocess.Popen(
            command,
            cwd=case,
            env=openfoam_environment(),
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            bufsize=1,
        )
        assert process.stdout is not None
        for line in process.stdout:
            log.write(line)
            stripped = line.strip()
            match = TIME_LINE.match(stripped)
            if match:
                simulated = float(match.group(1))
                if progress is not None:
                    progress(simulated, end, courant)
                continue
            match = COURANT_LINE.match(stripped)
            if match:
                courant = float(match.group(1))
        code = process.wait()
    wall = time.perf_counter() - started
    reached = simulated >= end - 1e-9
    if code != 0 or not reached:
        text = log_path.read_text(encoding="utf-8", errors="replace")
        reason = (
            "floating-point exception (the solution blew up)"
            if code in (136, -8)
            else f"exit {code}"
        )
        raise CfdError(
            f"interFoam stopped at t = {simulated:.6g} s of {end:g} s ({reason}); log tail:\n"
            + _tail(text)
        )
    return RunResult(case, RunStatus.COMPLETED, simulated, wall, processes, int(summary["cells"]))


def _set_subdomains(case: Path, processes: int) -> None:
    path = case / "system" / "decomposeParDict"
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"numberOfSubdomains\s+\d+;", f"numberOfSubdomains {processes};", text)
    text = re.sub(r"n\s+\(1 1 \d+\);", f"n               (1 1 {processes});", text)
    path.write_text(text, encoding="utf-8")


def expected_cells(spec: CaseSpec) -> int:
    """Cells blockMesh will make for ``spec``."""
    return mesh_layout(spec).cells
