"""CFD campaigns on Dask: many cases (fills, liquids, meshes, excitations) run as tasks of a
``dask.distributed`` cluster, gathered into one table and a calibration-versus-fill model.

- Each case is an ordinary sloshkit case folder (with its ``Allrun``) under the campaign
  folder; a task runs it (`sloshkit.cfd.run.run_case`) and calibrates it, then writes
  ``sloshkit-result.json`` beside it (atomically). A campaign started again skips every case
  with a result and resumes half-run cases from their latest complete time folder.
- The default cluster is in-process (``LocalCluster(processes=False)``: threads talking over
  Dask's ``inproc://`` transport; its HTTP servers bound to 127.0.0.1); the OpenFOAM work
  happens in the tasks' subprocesses. ``scheduler`` connects to an existing cluster instead, e.g. one made by
  ``dask-jobqueue`` on SLURM or PBS (docs/cfd.md): the campaign folder must then be on a file
  system every worker sees, and sloshkit and OpenFOAM installed on the workers.
- The calibration-versus-fill model is a least-squares line of the CFD/theory frequency ratio
  and of the damping ratio against h/R (per liquid and mesh), over the fills run.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.cfd.pipeline import analyse
from sloshkit.cfd.prepare import check_case_path
from sloshkit.cfd.run import run_case, write_case
from sloshkit.cfd.scheduler import HANDSHAKE_TIMEOUT_S, quiet_dask_logging, redact
from sloshkit.cfd.spec import CaseSpec
from sloshkit.cfd.summary import read_case_summary, read_json_file
from sloshkit.errors import InputError
from sloshkit.files import write_json, write_rows_csv

RESULT_FILE = "sloshkit-result.json"
COLUMNS = (
    "case",
    "status",
    "liquid",
    "fill_height_m",
    "radius_m",
    "cells",
    "cells_per_radius",
    "frequency_hz",
    "theory_frequency_hz",
    "frequency_ratio",
    "damping_ratio",
    "simulated_s",
    "wall_clock_s",
    "error",
)


@dataclass(frozen=True)
class CampaignCase:
    """One case of a campaign: its folder name, its spec and the linear-theory frequency.

    Parameters
    ----------
    name : str
        Folder name of the case in the campaign.
    spec : CaseSpec
        The case.
    theory_frequency_hz : float
        First-mode frequency of linear theory [Hz], for the frequency ratio.

    Returns
    -------
    CampaignCase

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> CampaignCase("fill-39mm", spec, 4.72).name
    'fill-39mm'
    """

    name: str
    spec: CaseSpec
    theory_frequency_hz: float


def run_one(folder: str, processes: int, theory_frequency_hz: float) -> dict[str, Any]:
    """Task: run (or resume) the case in ``folder``, calibrate it, record the result.

    Failures become a row with status ``failed`` (and are not recorded, so a later campaign
    tries the case again).

    Parameters
    ----------
    folder : str
        The case folder (written by `run_campaign`).
    processes : int
        MPI processes of the run.
    theory_frequency_hz : float
        Linear-theory frequency [Hz].

    Returns
    -------
    dict
        One row with the keys of `COLUMNS`.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from sloshkit.cfd.run import write_case
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=4)
    >>> case = write_case(spec, Path(tempfile.mkdtemp()) / "c")
    >>> row = run_one(str(case), 64, 4.72)  # an impossible process count: a failed row
    >>> row["status"], row["cells"]
    ('failed', 768)
    """
    case = Path(folder)
    summary = read_case_summary(case)
    row: dict[str, Any] = {name: None for name in COLUMNS}
    row.update(
        case=case.name,
        liquid=summary["liquid"],
        fill_height_m=summary["fill_height_m"],
        radius_m=summary["radius_m"],
        cells=summary["cells"],
        cells_per_radius=summary["cells_per_radius"],
        theory_frequency_hz=theory_frequency_hz,
    )
    started = time.perf_counter()
    try:
        resume = (case / ".sloshkit-fill-done").is_file()
        result = run_case(case, processes, resume=resume)
        calibration = analyse(case).calibration
    except Exception as error:  # one failed case must not stop the campaign
        row.update(status="failed", error=str(error).splitlines()[0])
        return row
    frequency = float(calibration.omega_n_rad_s) / (2 * math.pi)
    row.update(
        status="completed",
        frequency_hz=frequency,
        frequency_ratio=frequency / theory_frequency_hz,
        damping_ratio=calibration.damping_ratio,
        simulated_s=result.simulated_s,
        wall_clock_s=time.perf_counter() - started,
    )
    write_json(case / RESULT_FILE, row)
    return row


def fill_model(rows: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """Least-squares lines of the frequency ratio and damping ratio against h/R, per liquid
    and mesh (needs two fills or more; otherwise the single values).

    Parameters
    ----------
    rows : sequence of dict
        Campaign rows (`run_one`).

    Returns
    -------
    dict
        ``form`` and one entry per (liquid, mesh) in ``groups``.

    Examples
    --------
    >>> rows = [{"status": "completed", "liquid": "water", "cells_per_radius": 8,
    ...          "fill_height_m": h, "radius_m": 0.02, "frequency_ratio": 1.0 + h,
    ...          "damping_ratio": 0.01} for h in (0.02, 0.04)]
    >>> round(fill_model(rows)["groups"][0]["frequency_ratio"]["slope_per_fill_over_radius"], 3)
    0.02
    """
    groups: dict[tuple[str, int], list[dict[str, Any]]] = {}
    for row in rows:
        if row["status"] == "completed":
            groups.setdefault((row["liquid"], row["cells_per_radius"]), []).append(row)
    models = []
    for (liquid, cells), members in sorted(groups.items()):
        ratio = np.array([m["fill_height_m"] / m["radius_m"] for m in members])
        entry: dict[str, Any] = {
            "liquid": liquid,
            "cells_per_radius": cells,
            "fill_over_radius_range": [float(ratio.min()), float(ratio.max())],
            "cases": len(members),
        }
        for key in ("frequency_ratio", "damping_ratio"):
            values = np.array([np.nan if m[key] is None else m[key] for m in members], float)
            ok = np.isfinite(values)
            if np.unique(ratio[ok]).size >= 2:
                slope, intercept = np.polyfit(ratio[ok], values[ok], 1)
                fitted = intercept + slope * ratio[ok]
                entry[key] = {
                    "intercept": float(intercept),
                    "slope_per_fill_over_radius": float(slope),
                    "rms_residual": float(np.sqrt(np.mean((values[ok] - fitted) ** 2))),
                }
            elif ok.any():
                entry[key] = {"mean": float(values[ok].mean())}
        models.append(entry)
    return {"form": "value = intercept + slope * h/R (least squares)", "groups": models}


Progress = Callable[[int, int, float | None], None]  # (done, total, eta [s])


def run_campaign(
    cases: Sequence[CampaignCase],
    folder: Path,
    *,
    workers: int = 1,
    processes: int = 1,
    scheduler: str | None = None,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Run every case of a campaign on Dask and gather the results.

    Parameters
    ----------
    cases : the cases (names must be unique)
    folder : campaign folder; each case in ``folder/name``; ``results.csv`` and
        ``results.json`` written at the end
    workers : concurrent cases on the default local cluster
    processes : MPI processes per case
    scheduler : address of an existing Dask scheduler (default: an in-process local cluster)
    progress : called with (cases done, total, estimated seconds left)

    Returns
    -------
    dict
        ``rows`` (one per case, `COLUMNS`), ``model`` (`fill_model`), ``skipped`` (cases
        finished by an earlier campaign), and the paths written.

    References
    ----------
    Dask Development Team, *Dask: Library for dynamic task scheduling* (2016),
    https://dask.org; De Simone et al. (2024) (the calibration from CFD, Table 4).

    Examples
    --------
    >>> run_campaign([], Path("campaign"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: cases = 0 is invalid: a campaign needs at least one case
    """
    if not cases:
        raise InputError("cases", 0, "a campaign needs at least one case")
    names = [c.name for c in cases]
    if len(set(names)) != len(names):
        raise InputError("cases", len(names), "case names must be unique")
    check_case_path(folder, "folder")  # before anything is written
    import dask.distributed

    distributed: Any = dask.distributed  # untyped library
    quiet_dask_logging()

    rows: dict[str, dict[str, Any]] = {}
    pending = []
    for item in cases:
        result = folder / item.name / RESULT_FILE
        if result.is_file():
            rows[item.name] = read_json_file(result, "out")
            continue
        pending.append(item)
    skipped = len(rows)
    total = len(cases)
    if pending:
        # The cluster first: a scheduler that does not answer leaves nothing written.
        if scheduler is None:
            # Threads in this process (inproc:// transport); the scheduler's and the
            # worker's HTTP (dashboard, metrics) servers on loopback only.
            cluster: Any = distributed.LocalCluster(
                processes=False,
                n_workers=1,
                threads_per_worker=max(1, workers),
                dashboard_address="127.0.0.1:0",
                worker_dashboard_address="127.0.0.1:0",
            )
            client = distributed.Client(cluster)
        else:
            cluster = None
            try:
                client = distributed.Client(scheduler, timeout=HANDSHAKE_TIMEOUT_S)
            except Exception as error:  # Dask raises OSError, TimeoutError or its own
                raise InputError(
                    "scheduler",
                    redact(scheduler),
                    f"no Dask scheduler answered within {HANDSHAKE_TIMEOUT_S:g} s "
                    f"({str(error).splitlines()[0][:120] if str(error) else type(error).__name__})",
                ) from None
        quiet_dask_logging()
        try:
            for item in pending:
                if not (folder / item.name / "sloshkit-case.json").is_file():
                    write_case(item.spec, folder / item.name, overwrite=False)
            started = time.perf_counter()
            futures = [
                client.submit(
                    run_one,
                    str(folder / item.name),
                    processes,
                    item.theory_frequency_hz,
                    key=f"sloshkit-cfd-{item.name}",
                    pure=False,
                )
                for item in pending
            ]
            for done_here, future in enumerate(distributed.as_completed(futures), start=1):
                row = future.result()
                rows[row["case"]] = row
                if progress is not None:
                    rate = (time.perf_counter() - started) / done_here
                    progress(skipped + done_here, total, rate * (len(pending) - done_here))
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    ordered = [rows[name] for name in names]
    model = fill_model(ordered)
    write_rows_csv(folder / "results.csv", [{k: row.get(k) for k in COLUMNS} for row in ordered])
    payload = {"rows": ordered, "model": model, "skipped": skipped}
    write_json(folder / "results.json", payload)
    return {**payload, "csv": str(folder / "results.csv"), "json": str(folder / "results.json")}
