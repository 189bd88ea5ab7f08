"""The signals of one real OpenFOAM free-decay run made by sloshkit, shipped with the package so
the default report can show the paper's Fig. 9 (CFD against the pendulum) without running
OpenFOAM. ``data/cfd-free-decay.json`` records the command, OpenFOAM version and mesh."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.io.tables import column_si, find_column, read_table

#: The shipped wall-elevation signal (CSV, ``t [s]``, ``wall elevation [m]``) and its record.
SIGNALS = Path(__file__).parent / "data" / "cfd-free-decay.csv"
RECORD = SIGNALS.with_suffix(".json")


def shipped_cfd_free_decay() -> tuple[NDArray[np.float64], NDArray[np.float64], dict[str, Any]]:
    """The shipped CFD free decay: time [s], wall elevation [m] and how it was made.

    Returns
    -------
    tuple
        ``(time_s, wall_elevation_m, record)``; ``record`` holds the command, the OpenFOAM
        version, the mesh and the case settings of the run.

    References
    ----------
    M. C. De Simone et al., Appl. Sci. 14 (2024) 4522, doi:10.3390/app14114522, Fig. 9 (the
    comparison this signal reproduces with sloshkit's own CFD).

    Examples
    --------
    >>> time_s, elevation_m, record = shipped_cfd_free_decay()
    >>> time_s.size == elevation_m.size and record["openfoam"].startswith("OpenFOAM")
    True
    """
    header, data = read_table(SIGNALS)
    time_index = find_column(header, ("t", "time"))
    signal_index = find_column(header, ("wall elevation", "elevation"))
    if time_index is None or signal_index is None:
        raise ValueError(f"{SIGNALS} lacks its time or wall-elevation column")
    record = json.loads(RECORD.read_text(encoding="utf-8"))
    return (
        column_si(header, data, time_index, "time"),
        column_si(header, data, signal_index, "length"),
        record,
    )
