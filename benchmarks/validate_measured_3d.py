"""Validate the 3-D slosh model against the measured robot series (tests/data/measured-3d).

For each series the container's poses are simulated with the container's own parameters
(R 49 mm, h 80 mm, water at 20 C, damping ratio 0.0066 from the free decay; optionally the
first-mode frequency from the free decay, omega_d 19.04 rad/s); nothing is fitted to the
series. Printed per series and model variant: predicted and measured peak slosh height, their
relative error, and the RMS error over the time series from the start of the motion to 2 s
after its end, after the alignment t_pose = t_meas - tau_s (tau_s from the data's manifest)
and subtraction of the measured baseline. Writes docs/figures/validation-3d.png.

Run: PYTHONPATH=src python benchmarks/validate_measured_3d.py [--figure PATH] [--markdown]
"""

from __future__ import annotations

import argparse
import csv
import math
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.spatial import simulate_spatial

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "measured-3d"
FIGURE = ROOT / "docs" / "figures" / "validation-3d.png"
RADIUS_M, FILL_M, ZETA, OMEGA_D = 0.049, 0.080, 0.0066, 19.04
RMS_AFTER_S = 2.0


def container_model(from_decay: bool = False) -> SloshModel:
    """The container's model: theory, or omega_1 from the free decay's omega_d."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        model = equivalent_model(
            UprightCylinder(RADIUS_M), get_liquid("water-20C"), FILL_M, 3, damping_ratio=ZETA
        )
    if from_decay:
        omega = OMEGA_D / math.sqrt(1.0 - ZETA**2)
        model = model.with_mode(1, omega_rad_s=omega, source="free decay (README)")
    return model


#: name -> (model from free decay?, nonlinear?, height mapping)
VARIANTS: dict[str, tuple[bool, bool, str]] = {
    "linear": (False, False, "modal"),
    "nonlinear": (False, True, "modal"),
    "linear, planar": (False, False, "planar"),
    "nonlinear, planar": (False, True, "planar"),
    "linear, omega decay": (True, False, "modal"),
}


def load_series(data_dir: Path = DATA) -> list[dict[str, Any]]:
    """Manifest rows with the poses and the measured series."""
    series = []
    with (data_dir / "manifest.csv").open() as stream:
        for row in csv.DictReader(stream):
            name = row["name"]
            pose = np.loadtxt(data_dir / "poses" / f"{name}.csv", delimiter=",", skiprows=1)
            measured = np.loadtxt(data_dir / "measured" / f"{name}.csv", delimiter=",", skiprows=1)
            series.append(
                {
                    "name": name,
                    "poses": PoseTrajectory(pose[:, 0], pose[:, 1:4], pose[:, 4:8], name),
                    "measured_t_s": measured[:, 0] - float(row["tau_s"]),
                    "measured_m": measured[:, 1] - float(row["baseline_m"]),
                    "peak_m": float(row["meas_peak_m"]),
                    "start_s": float(row["motion_start_pose_s"]),
                    "end_s": float(row["motion_end_pose_s"]),
                }
            )
    return series


def evaluate(
    series: list[dict[str, Any]], variants: dict[str, tuple[bool, bool, str]] = VARIANTS
) -> list[dict[str, Any]]:
    """Per series and variant: predicted peak, relative error, RMS error, the series."""
    rows = []
    models = {flag: container_model(flag) for flag in (False, True)}
    for item in series:
        for label, (decay, nonlinear, mapping) in variants.items():
            settle = max(1.0, float(item["measured_t_s"][-1]) - item["poses"].end_s)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                response = simulate_spatial(
                    models[decay],
                    item["poses"],
                    nonlinear=nonlinear,
                    settle_time_s=settle,
                    height_mapping=mapping,  # type: ignore[arg-type]
                )
            t_meas = item["measured_t_s"]
            window = (t_meas >= item["start_s"]) & (t_meas <= item["end_s"] + RMS_AFTER_S)
            predicted = np.interp(t_meas[window], response.time_s, response.slosh_height_m)
            rms = float(np.sqrt(np.mean((predicted - item["measured_m"][window]) ** 2)))
            peak = response.peak_slosh_height_m
            rows.append(
                {
                    "name": item["name"],
                    "variant": label,
                    "measured_peak_m": item["peak_m"],
                    "predicted_peak_m": peak,
                    "peak_error": peak / item["peak_m"] - 1.0,
                    "rms_m": rms,
                    "rms_relative": rms / item["peak_m"],
                    "time_s": response.time_s,
                    "height_m": response.slosh_height_m,
                }
            )
    return rows


def summary(rows: list[dict[str, Any]]) -> dict[str, tuple[float, float, float]]:
    """Per variant: (median |peak error|, 90th percentile |peak error|, median RMS/peak)."""
    out = {}
    for label in dict.fromkeys(row["variant"] for row in rows):
        errors = np.abs([row["peak_error"] for row in rows if row["variant"] == label])
        rms = [row["rms_relative"] for row in rows if row["variant"] == label]
        out[label] = (
            float(np.median(errors)),
            float(np.percentile(errors, 90)),
            float(np.median(rms)),
        )
    return out


def table(rows: list[dict[str, Any]], markdown: bool = False) -> str:
    """The per-series table and the per-variant summary as text (or Markdown)."""
    lines = []
    if markdown:
        lines.append(
            "| series | variant | measured peak [mm] | predicted peak [mm] | peak error "
            "| RMS error [mm] |"
        )
        lines.append("|---|---|---:|---:|---:|---:|")
    for row in rows:
        cells = (
            row["name"],
            row["variant"],
            f"{1e3 * row['measured_peak_m']:.1f}",
            f"{1e3 * row['predicted_peak_m']:.1f}",
            f"{100 * row['peak_error']:+.1f} %",
            f"{1e3 * row['rms_m']:.2f}",
        )
        lines.append(
            "| " + " | ".join(cells) + " |"
            if markdown
            else "  ".join(f"{c:>26s}" if i == 0 else f"{c:>20s}" for i, c in enumerate(cells))
        )
    lines.append("")
    if markdown:
        lines.append(
            "| variant | median abs. peak error | 90th percentile | median RMS / measured peak |"
        )
        lines.append("|---|---:|---:|---:|")
    for label, (median, p90, rms) in summary(rows).items():
        if markdown:
            lines.append(
                f"| {label} | {100 * median:.1f} % | {100 * p90:.1f} % | {100 * rms:.1f} % |"
            )
        else:
            lines.append(
                f"{label:>22s}: median |peak error| {100 * median:5.1f} %, "
                f"90th pct {100 * p90:5.1f} %, median RMS/peak {100 * rms:5.1f} %"
            )
    return "\n".join(lines)


def figure(rows: list[dict[str, Any]], series: list[dict[str, Any]], path: Path) -> None:
    """Measured against predicted series (linear and nonlinear), one panel per series."""
    from sloshkit.plotting.spatial import plot_measured_comparison

    panels = []
    for item in series:
        predicted = [
            (f"{row['variant']} ({100 * row['peak_error']:+.0f} %)", row["time_s"], row["height_m"])
            for row in rows
            if row["name"] == item["name"] and row["variant"] in ("linear", "nonlinear")
        ]
        keep = (item["measured_t_s"] >= -0.5) & (item["measured_t_s"] <= item["end_s"] + 3.0)
        panels.append(
            {
                "name": item["name"],
                "measured_t_s": item["measured_t_s"][keep],
                "measured_m": item["measured_m"][keep],
                "predicted": [
                    (lab, t[t <= item["end_s"] + 3.0], h[t <= item["end_s"] + 3.0])
                    for lab, t, h in predicted
                ],
            }
        )
    path.parent.mkdir(parents=True, exist_ok=True)
    plot_measured_comparison(panels, path)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--figure", type=Path, default=FIGURE)
    parser.add_argument("--markdown", action="store_true")
    args = parser.parse_args()
    started = time.perf_counter()
    series = load_series()
    rows = evaluate(series)
    print(table(rows, markdown=args.markdown))
    figure(rows, series, args.figure)
    print(f"\nfigure: {args.figure}  ({time.perf_counter() - started:.1f} s)")


if __name__ == "__main__":
    main()
