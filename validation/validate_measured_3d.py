"""Validate the 3-D slosh model against the measured robot series (tests/data/measured-3d).

For each series the container's poses are simulated with the container's own parameters
(R 49 mm, h 80 mm, water at 20 C, damping ratio 0.0066 from the free decay; optionally the
first-mode frequency from the free decay, omega_d 19.04 rad/s); nothing is fitted to the
series. Printed per series and model variant: predicted and measured peak slosh height, their
relative error, and the RMS error over the time series from the start of the motion to 2 s
after its end, after the alignment t_pose = t_meas - tau_s (tau_s from the data's manifest)
and subtraction of the measured baseline; per class (LE, RD, TRD, each with and without tilt) the
signed median peak error. Writes docs/figures/validation-3d.png.

The variant "linear, free-decay backbone" takes the first mode's frequency and damping from the
backbone of the container's force-sensor free decay (tests/data/measured-3d/free_decay_force.csv,
`sloshkit.calibration.amplitude`), again nothing fitted to the series. ``--campaign DIR`` adds
the peak errors of every measured series of the same campaign from a checkout of the data's
repository (GiorgioMedico/AntiSloshing, commit 75eb653, MIT licence): 48 series, 42 of them
not among the six (a hold-out; baseline: median of the first 5 s of the camera record; peaks
only, the clocks of those series are not aligned).

Run: PYTHONPATH=src python validation/validate_measured_3d.py [--figure PATH] [--markdown]
     [--campaign PATH/TO/AntiSloshing]
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

from sloshkit.calibration.amplitude import decay_amplitude_dependence
from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.spatial import simulate_spatial
from sloshkit.sim.spatial_amplitude import AmplitudeDependence

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "measured-3d"
FIGURE = ROOT / "docs" / "figures" / "validation-3d.png"
RADIUS_M, FILL_M, ZETA, OMEGA_D = 0.049, 0.080, 0.0066, 19.04
RMS_AFTER_S = 2.0
FREE_DECAY = DATA / "free_decay_force.csv"
#: the free decay starts after the y move of the record (its motion ends near 2.5 s)
FREE_DECAY_START_S = 2.6
CAMPAIGN = Path("Sloshing Models") / "Models Validation" / "Motions_10_10_2024"


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


def free_decay_dependence(model: SloshModel) -> AmplitudeDependence:
    """The first mode's backbone from the container's force-sensor free decay (force_y_n)."""
    record = np.loadtxt(FREE_DECAY, delimiter=",", skiprows=1)
    return decay_amplitude_dependence(
        model, record[:, 0], record[:, 2], FREE_DECAY_START_S, source="free decay (y_noRot)"
    ).dependence


#: name -> (model from free decay?, nonlinear?, height mapping, free-decay backbone?)
VARIANTS: dict[str, tuple[bool, bool, str, bool]] = {
    "linear": (False, False, "modal", False),
    "nonlinear": (False, True, "modal", False),
    "linear, planar": (False, False, "planar", False),
    "nonlinear, planar": (False, True, "planar", False),
    "linear, omega decay": (True, False, "modal", False),
    "linear, free-decay backbone": (False, False, "modal", True),
}


def series_class(name: str, tilt_deg: float) -> str:
    """LE, RD or TRD, prefixed Tilt_ for the tilted moves."""
    base = name.removeprefix("Tilt_").split("_")[0]
    return f"Tilt_{base}" if tilt_deg > 0 else base


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
                    "class": series_class(name, float(row["tilt_deg"])),
                }
            )
    return series


def load_campaign(checkout: Path) -> list[dict[str, Any]]:
    """Every measured series of the campaign in a checkout of the data's repository."""
    from scipy.io import loadmat

    folder = checkout / CAMPAIGN
    series = []
    for path in sorted((folder / "full_slosh").glob("*.mat")):
        name = path.stem
        pose_path = folder / "csv" / f"{name}.csv"
        if not pose_path.exists():
            pose_path = folder / f"{name}.csv"
        data = loadmat(path)
        t_meas = np.asarray(data["slosh_times"], dtype=float).ravel()
        height = 1e-3 * np.asarray(data["slosh_heights"], dtype=float).ravel()
        pose = np.loadtxt(pose_path, delimiter=";")
        quaternion = pose[:, 4:8].copy()
        if name.startswith("Tilt_TRD"):  # the tilt sign of this family (tests/data README)
            quaternion[:, :3] *= -1.0
        baseline = float(np.median(height[t_meas < 5.0]))
        series.append(
            {
                "name": name,
                "poses": PoseTrajectory(pose[:, 0], pose[:, 1:4], quaternion, name),
                "measured_t_s": t_meas,
                "measured_m": height - baseline,
                "peak_m": float(np.max(height) - baseline),
                "start_s": None,
                "end_s": float(pose[-1, 0]),
                "class": series_class(name, 1.0 if name.startswith("Tilt") else 0.0),
            }
        )
    return series


def evaluate(
    series: list[dict[str, Any]], variants: dict[str, tuple[bool, bool, str, bool]] = VARIANTS
) -> list[dict[str, Any]]:
    """Per series and variant: predicted peak, relative error, RMS error, the series.

    The RMS error needs the clock alignment of `load_series` (``start_s``); it is NaN for
    series without it (`load_campaign`)."""
    rows = []
    models = {flag: container_model(flag) for flag in (False, True)}
    dependence = free_decay_dependence(models[False])
    for item in series:
        for label, (decay, nonlinear, mapping, backbone) in variants.items():
            settle = max(1.0, float(item["measured_t_s"][-1]) - item["poses"].end_s)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                response = simulate_spatial(
                    models[decay],
                    item["poses"],
                    nonlinear=nonlinear,
                    settle_time_s=settle,
                    height_mapping=mapping,  # type: ignore[arg-type]
                    amplitude_dependence=dependence if backbone else None,
                )
            t_meas = item["measured_t_s"]
            rms = math.nan
            if item["start_s"] is not None:
                window = (t_meas >= item["start_s"]) & (t_meas <= item["end_s"] + RMS_AFTER_S)
                predicted = np.interp(t_meas[window], response.time_s, response.slosh_height_m)
                rms = float(np.sqrt(np.mean((predicted - item["measured_m"][window]) ** 2)))
            peak = response.peak_slosh_height_m
            rows.append(
                {
                    "name": item["name"],
                    "class": item["class"],
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


def summary(rows: list[dict[str, Any]]) -> dict[str, tuple[float, float, float, float]]:
    """Per variant: (median |peak error|, 90th percentile |peak error|, median RMS/peak,
    largest |signed median peak error| of a class)."""
    out = {}
    for label in dict.fromkeys(row["variant"] for row in rows):
        errors = np.abs([row["peak_error"] for row in rows if row["variant"] == label])
        rms = [row["rms_relative"] for row in rows if row["variant"] == label]
        biases = class_bias(rows, label).values()
        out[label] = (
            float(np.median(errors)),
            float(np.percentile(errors, 90)),
            float(np.median(rms)),
            max(abs(bias) for bias, _ in biases),
        )
    return out


def class_bias(rows: list[dict[str, Any]], variant: str) -> dict[str, tuple[float, int]]:
    """Per class of ``variant``'s rows: (signed median peak error, number of series)."""
    out = {}
    for cls in sorted({row["class"] for row in rows}):
        errors = [
            row["peak_error"] for row in rows if row["variant"] == variant and row["class"] == cls
        ]
        if errors:
            out[cls] = (float(np.median(errors)), len(errors))
    return out


def class_table(rows: list[dict[str, Any]], markdown: bool = False) -> str:
    """Signed median peak error per class (columns) and variant (rows)."""
    classes = sorted({row["class"] for row in rows})
    lines = []
    if markdown:
        counts = class_bias(rows, rows[0]["variant"])
        lines.append("| variant | " + " | ".join(f"{c} ({counts[c][1]})" for c in classes) + " |")
        lines.append("|---|" + "---:|" * len(classes))
    for label in dict.fromkeys(row["variant"] for row in rows):
        bias = class_bias(rows, label)
        cells = [f"{100 * bias[c][0]:+.1f} %" for c in classes]
        if markdown:
            lines.append(f"| {label} | " + " | ".join(cells) + " |")
        else:
            lines.append(
                f"{label:>28s}: "
                + "  ".join(f"{c} {x:>8s}" for c, x in zip(classes, cells, strict=True))
            )
    return "\n".join(lines)


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
            "| variant | median abs. peak error | 90th percentile | median RMS / measured peak "
            "| largest class bias |"
        )
        lines.append("|---|---:|---:|---:|---:|")
    for label, (median, p90, rms, bias) in summary(rows).items():
        if markdown:
            lines.append(
                f"| {label} | {100 * median:.1f} % | {100 * p90:.1f} % | {100 * rms:.1f} % "
                f"| {100 * bias:.1f} % |"
            )
        else:
            lines.append(
                f"{label:>28s}: median |peak error| {100 * median:5.1f} %, "
                f"90th pct {100 * p90:5.1f} %, median RMS/peak {100 * rms:5.1f} %, "
                f"largest class bias {100 * bias:5.1f} %"
            )
    lines.append("")
    lines.append(class_table(rows, markdown))
    return "\n".join(lines)


def figure(rows: list[dict[str, Any]], series: list[dict[str, Any]], path: Path) -> None:
    """Measured against predicted series (linear and nonlinear), one panel per series."""
    from sloshkit.plotting.response3d import plot_measured_comparison

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
    parser.add_argument("--campaign", type=Path, help="checkout of GiorgioMedico/AntiSloshing")
    args = parser.parse_args()
    started = time.perf_counter()
    series = load_series()
    rows = evaluate(series)
    print(table(rows, markdown=args.markdown))
    figure(rows, series, args.figure)
    if args.campaign is not None:
        campaign = load_campaign(args.campaign)
        if not campaign:
            parser.error(f"--campaign: no measured series under {args.campaign / CAMPAIGN}")
        chosen = {k: VARIANTS[k] for k in ("linear", "linear, free-decay backbone")}
        every = evaluate(campaign, chosen)
        six = {item["name"] for item in series}
        held = [row for row in every if row["name"] not in six]
        count = sum(item["name"] not in six for item in campaign)
        print(f"\ncampaign: {len(campaign)} series ({count} not among the six)")
        for label, subset in (("all", every), ("hold-out", held)):
            for variant, (median, p90, _, bias) in summary(subset).items():
                print(
                    f"  {label:>8s} {variant:>28s}: median |peak error| {100 * median:.1f} %, "
                    f"90th pct {100 * p90:.1f} %, largest class bias {100 * bias:.1f} %"
                )
        print(class_table(every, markdown=args.markdown))
    print(f"\nfigure: {args.figure}  ({time.perf_counter() - started:.1f} s)")


if __name__ == "__main__":
    main()
