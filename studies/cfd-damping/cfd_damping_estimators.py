"""Is the damping estimator the limit? Every finished case of the damping study, estimated from
three signals, two estimators and several windows.

Signals (`sloshkit.cfd.results.read_signals`): the antisymmetric wall elevation of the probe
columns (alpha summed along a column: on coarse meshes the 1 mm slosh amplitude is about one
cell), the surface tilt (volume integral of grad alpha, an integral over every interface cell)
and the horizontal wall force (an integral over the whole wall). Estimators
(`sloshkit.calibration.calibrate`): the damped-sine least-squares fit and the logarithmic
decrement of the peaks. Windows start after 0.3, 0.5 and 0.7 s (the tilt's higher modes have
decayed) and run to the end; the two halves of the 0.5 s window show amplitude dependence.

The study's value of a run (``primary``) is the fit of the wall force from 0.5 s; its
``scatter`` is the half-range of the force estimates (fit and logdec, three starts; the two
agree within a few per cent on the wall force, not on the probe elevation of coarse meshes).

Each row also carries the wall force's noise ratio above 15 Hz and its step-to-step
alternation (`sloshkit.cfd.force_signal.step_alternation`), both after 0.5 s.

Writes data/cfd-damping-estimators.json (one row per case folder).

Run: PYTHONPATH=src python studies/cfd-damping/cfd_damping_estimators.py [WORK ...]
"""

from __future__ import annotations

import argparse
import json
import math
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.calibration.decrement import estimate_logdec
from sloshkit.calibration.estimators import estimate_fit
from sloshkit.calibration.signals import spectral_peak
from sloshkit.calibration.window import prepare_signal
from sloshkit.cfd.force_signal import noise_ratio, step_alternation
from sloshkit.cfd.results import read_signals
from sloshkit.errors import InputError, ValidityWarning

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
STARTS_S = (0.3, 0.5, 0.7)
PRIMARY = ("force", "fit", 0.5)
NOISE_CUTOFF_HZ = 15.0  # three times the first-mode frequency
WORKS = (Path("/tmp/sloshkit-cfd-damping"), Path("/tmp/sloshkit-cfd-damping3"))


def zeta(time_s: np.ndarray, values: np.ndarray, method: str, start: float, end: float) -> float:
    """Damping ratio by one estimator (`sloshkit.calibration`'s, as `calibrate` runs them)
    over [start, end] (nan when it fails)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            warnings.simplefilter("ignore", RuntimeWarning)
            prepared, _ = prepare_signal(time_s, values, start, end)
            if method == "fit":
                result = estimate_fit(prepared)
            else:
                frequency, _, _ = spectral_peak(prepared.time_s, prepared.values)
                result = estimate_logdec(prepared, 1.0 / frequency)
    except (InputError, ValueError, ZeroDivisionError):
        return math.nan
    value = result.damping_ratio
    return math.nan if value is None else float(value)


def force_noise(time_s: np.ndarray, values: np.ndarray) -> float:
    """The study's noise ratio of the wall force: `sloshkit.cfd.force_signal.noise_ratio`
    above `NOISE_CUTOFF_HZ`, after 0.5 s."""
    return noise_ratio(time_s, values, cutoff_hz=NOISE_CUTOFF_HZ, start_s=0.5)


def summarise(values: dict[str, float]) -> tuple[float, float]:
    """The primary estimate and the scatter (half-range) of the wall-force estimates."""
    pool = [
        v
        for k, v in values.items()
        if k.startswith("force/") and not k.endswith("half") and math.isfinite(v)
    ]
    primary = values["/".join(f"{p:g}" if isinstance(p, float) else p for p in PRIMARY)]
    return primary, 0.5 * (max(pool) - min(pool)) if pool else math.nan


def estimate(case: Path) -> dict[str, Any] | None:
    """Every estimate of one finished free decay (None for a run that did not finish)."""
    try:
        signals = read_signals(case)
    except (InputError, OSError, ValueError):
        return None
    run = case / "sloshkit-run.json"
    summary = json.loads((case / "sloshkit-case.json").read_text())
    t = signals.time_s
    end = float(t[-1])
    if end < 0.98 * float(summary.get("end_time_s", end)) or end < 1.0:
        return None
    series = {
        "elevation": signals.elevation_m,
        "tilt": signals.tilt_rad,
        "force": signals.force_x_n,
    }
    values: dict[str, float] = {}
    for name, y in series.items():
        if not np.all(np.isfinite(y)):
            return None
        for method in ("fit", "logdec"):
            for start in STARTS_S:
                values[f"{name}/{method}/{start:g}"] = zeta(t, y, method, start, end)
        middle = 0.5 * (STARTS_S[1] + end)
        values[f"{name}/fit/first-half"] = zeta(t, y, "fit", STARTS_S[1], middle)
        values[f"{name}/fit/second-half"] = zeta(t, y, "fit", middle, end)
    primary, scatter = summarise(values)
    return {
        "case": case.name,
        "end_time_s": end,
        "record": json.loads(run.read_text()) if run.is_file() else {},
        "primary": primary,
        "scatter": scatter,
        "force_noise_ratio": force_noise(t, signals.force_x_n),
        "force_step_alternation": step_alternation(signals.force_x_n[t > PRIMARY[2]]),
        "estimates": values,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("works", nargs="*", type=Path, default=list(WORKS))
    parser.add_argument("--out", type=Path, default=DATA / "cfd-damping-estimators.json")
    args = parser.parse_args()
    rows = json.loads(args.out.read_text()) if args.out.is_file() else []
    known = {(r["work"], r["case"]) for r in rows}
    for row in rows:  # rows estimated before the noise ratio or the alternation was recorded
        case = Path("/tmp") / row["work"] / row["case"]
        missing = {"force_noise_ratio", "force_step_alternation"} - set(row)
        if missing and case.is_dir():
            signals = read_signals(case)
            t, force = signals.time_s, signals.force_x_n
            row["force_noise_ratio"] = force_noise(t, force)
            row["force_step_alternation"] = step_alternation(force[t > PRIMARY[2]])
    for work in args.works:
        for case in sorted(work.iterdir()) if work.is_dir() else []:
            if (work.name, case.name) in known:
                continue
            row = estimate(case)
            if row is None:
                continue
            row = {"work": work.name, **row}
            row.pop("record")
            rows.append(row)
            print(f"{work.name}/{case.name}: {row['primary']:.5f} ± {row['scatter']:.5f}")
    for row in rows:
        row["primary"], row["scatter"] = summarise(row["estimates"])
    args.out.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
