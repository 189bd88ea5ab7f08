"""The azimuthal content of finished pose-driven CFD cases against the pendulum model.

For each case (run by ``run.sh``): the wall elevation of the probe columns split into
azimuthal orders m = 0..3 (`sloshkit.cfd.pose_validation.azimuthal_orders`), largest during
the move and more than 0.1 s after it; the same for the planner's verification model
(`sloshkit.sim.spatial.simulate_spatial`, nonlinear pendulums, modal height mapping, exact
kinematics) read at the same columns; the largest slosh height (max over the columns) during
and after; the spectral peaks of the columns after the move; and, for a measured series, the
cameras' peak. Prints one block per case and writes ``results.json``.

Usage: ``python azimuthal.py CASES_FOLDER [case ...]`` (a case named after a measured series,
``meas*``, is compared with ``tests/data/measured-3d``).
"""

from __future__ import annotations

import csv
import json
import sys
import warnings
from pathlib import Path

import numpy as np
from scipy.special import jnp_zeros

import sloshkit as sk
from sloshkit.cfd.analysis import read_finished_signals
from sloshkit.cfd.pose_validation import azimuthal_orders
from sloshkit.errors import ValidityWarning
from sloshkit.io.poses import read_pose_file
from sloshkit.model.theory import natural_frequency
from sloshkit.sim.spatial import simulate_spatial

DATA = Path(__file__).resolve().parents[2] / "tests" / "data" / "measured-3d"
MEASURED = "TRD_2D_0.3m_2.4s_270deg"


def spectral_peaks(time: np.ndarray, elevation: np.ndarray, count: int = 3) -> list[float]:
    """The strongest peaks [Hz] of the columns' summed power spectrum (Hann window)."""
    from scipy.signal import find_peaks

    step = float(np.median(np.diff(time)))
    size = 8192
    frequency = np.fft.rfftfreq(size, step)
    power = np.zeros(frequency.size)
    for column in elevation.T:
        power += np.abs(np.fft.rfft((column - column.mean()) * np.hanning(column.size), size)) ** 2
    peaks, _ = find_peaks(power, height=0.05 * power.max())
    strongest = peaks[np.argsort(power[peaks])[::-1][:count]]
    return [round(float(frequency[i]), 2) for i in strongest]


def analyse(case: Path, model: object) -> dict[str, object]:
    """The figures of one finished case (module docstring)."""
    signals = read_finished_signals(case)
    poses = read_pose_file(case / "sloshkit-poses.csv")
    end = poses.duration_s
    time, elevation = signals.time_s, signals.elevations_m
    angles = np.asarray(signals.angles_rad)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(
            model,
            poses,
            nonlinear=True,
            cutoff_hz=None,
            settle_time_s=max(float(time[-1]) - end, 0.0),
            sample_period_s=1e-3,
        )
    model_time = response.time_s - poses.start_s
    modelled = np.column_stack(
        [np.interp(time, model_time, response.wall_elevation_m(a)) for a in angles]
    )
    during, after = time <= end, time > end + 0.1
    cfd_orders = azimuthal_orders(elevation, angles)
    model_orders = azimuthal_orders(modelled, angles)
    assert cfd_orders is not None and model_orders is not None
    cfd = {f"m{m}": values for m, values in enumerate(cfd_orders)}
    pendulum = {f"m{m}": values for m, values in enumerate(model_orders)}
    row: dict[str, object] = {"case": case.name, "move_s": end}
    for name in cfd:
        row[f"{name}_during_mm"] = [
            1e3 * cfd[name][during].max(),
            1e3 * pendulum[name][during].max(),
        ]
        row[f"{name}_after_mm"] = [1e3 * cfd[name][after].max(), 1e3 * pendulum[name][after].max()]
    row["height_during_mm"] = [1e3 * elevation[during].max(), 1e3 * modelled[during].max()]
    row["height_after_mm"] = [1e3 * elevation[after].max(), 1e3 * modelled[after].max()]
    row["peaks_after_hz"] = spectral_peaks(time[after], elevation[after])
    if case.name.startswith("meas"):
        with (DATA / "manifest.csv").open() as stream:
            entry = {r["name"]: r for r in csv.DictReader(stream)}[MEASURED]
        row["measured_peak_mm"] = 1e3 * float(entry["meas_peak_m"])
    return row


def main() -> None:
    root = Path(sys.argv[1])
    names = sys.argv[2:] or sorted(
        p.name for p in root.iterdir() if (p / "sloshkit-poses.csv").is_file()
    )
    model = sk.equivalent_model(
        sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )
    rows = []
    for name in names:
        row = analyse(root / name, model)
        rows.append(row)
        print(
            name,
            {
                k: (np.round(v, 1).tolist() if isinstance(v, list) else v)
                for k, v in row.items()
                if k != "case"
            },
        )
    # the first radial mode of each azimuthal order m: the first root of J_m' in
    # omega = sqrt(g xi / R tanh(xi h / R)) (Abramson, NASA SP-106 (1966) eq. 2.14)
    theory = {
        m: float(natural_frequency(0.049, 0.08, jnp_zeros(m, 1)[0]) / (2 * np.pi)) for m in range(4)
    }
    print(
        "theory, first radial mode of m = 0..3 [Hz]:", {m: round(f, 2) for m, f in theory.items()}
    )
    (root / "results.json").write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
