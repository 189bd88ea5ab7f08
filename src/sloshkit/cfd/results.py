"""Parsing of the function-object output of a sloshkit case into signals (pure functions).

v1912 writes vectors in parentheses; a restarted run writes a new folder named after its start
time, so every time folder of a function object is read and merged in time order (later
folders win where they overlap).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.cfd.case import SCALE
from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


def parse_table(text: str) -> FloatArray:
    """Rows of numbers from a function-object file: '#' lines skipped, parentheses dropped."""
    rows = []
    for line in text.splitlines():
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        rows.append([float(v) for v in stripped.replace("(", " ").replace(")", " ").split()])
    if not rows:
        return np.zeros((0, 0))
    width = min(len(r) for r in rows)
    return np.asarray([r[:width] for r in rows], dtype=float)


def read_function_object(case: Path, name: str, file_name: str) -> FloatArray:
    """All time folders of postProcessing/NAME/*/FILE merged in time order."""
    root = case / "postProcessing" / name
    if not root.is_dir():
        raise InputError("case", str(case), f"has no postProcessing/{name} (has the solver run?)")
    parts = []
    for folder in sorted(
        root.iterdir(), key=lambda p: float(p.name) if _is_number(p.name) else math.inf
    ):
        path = folder / file_name
        if path.is_file():
            table = parse_table(path.read_text(encoding="utf-8", errors="replace"))
            if table.size:
                parts.append(table)
    if not parts:
        raise InputError("case", str(case), f"postProcessing/{name} holds no data")
    merged = parts[0]
    for part in parts[1:]:
        merged = np.vstack((merged[merged[:, 0] < part[0, 0] - 1e-12], part))
    return merged


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


@dataclass(frozen=True)
class CfdSignals:
    """Signals of a run in SI: wall elevations at x = +-0.98 R, mean surface tilt, wall force."""

    time_s: FloatArray
    elevation_plus_m: FloatArray
    elevation_minus_m: FloatArray
    tilt_rad: FloatArray
    force_x_n: FloatArray
    summary: dict[str, object]

    @property
    def elevation_m(self) -> FloatArray:
        """Antisymmetric wall elevation (eta(+x) - eta(-x)) / 2: the first mode's signal [m]."""
        return 0.5 * (self.elevation_plus_m - self.elevation_minus_m)

    def columns(self) -> dict[str, FloatArray]:
        """Named columns for CSV export."""
        return {
            "t_s": self.time_s,
            "elevation_plus_m": self.elevation_plus_m,
            "elevation_minus_m": self.elevation_minus_m,
            "elevation_m": self.elevation_m,
            "tilt_rad": self.tilt_rad,
            "force_x_n": self.force_x_n,
        }


def read_signals(case: Path) -> CfdSignals:
    """Wall elevations, tilt and force of a finished (or partly finished) case."""
    summary = json.loads((case / "sloshkit-case.json").read_text(encoding="utf-8"))
    probes = read_function_object(case, "wallProbes", "alpha.water")
    count = int(summary["probes_per_column"])
    if probes.shape[1] != 1 + 2 * count:
        raise InputError(
            "case", str(case), f"expected {2 * count} probes, found {probes.shape[1] - 1}"
        )
    dz = float(summary["probe_dz_m"])
    fill = float(summary["fill_height_m"])
    alpha = np.clip(probes[:, 1:], 0.0, 1.0)
    plus = alpha[:, :count].sum(axis=1) * dz - fill
    minus = alpha[:, count:].sum(axis=1) * dz - fill
    time = probes[:, 0]
    tilt_table = read_function_object(case, "surfaceTilt", "volFieldValue.dat")
    tilt = np.arctan2(tilt_table[:, 1], -tilt_table[:, 3])
    forces = read_function_object(case, "wallForces", "force.dat")
    force_x = forces[:, 1] / SCALE**4  # mm units: N' = kg mm s^-2 scaled; see case.py
    return CfdSignals(
        time_s=time,
        elevation_plus_m=plus,
        elevation_minus_m=minus,
        tilt_rad=np.interp(time, tilt_table[:, 0], tilt),
        force_x_n=np.interp(time, forces[:, 0], force_x),
        summary=summary,
    )
