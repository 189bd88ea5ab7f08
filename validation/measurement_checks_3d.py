"""What the camera heights of the measured robot series are: checks against exact statics.

Three checks of the measured slosh heights (tests/data/measured-3d and, with ``--campaign``,
all 48 series of the data's repository GiorgioMedico/AntiSloshing, commit 75eb653, MIT
licence) that need no slosh dynamics, so that the errors of `validate_measured_3d.py` can be
split into errors of the model and properties of the measurement (docs/validation-3d.md):

1. **Quasi-static humps.** Where the commanded acceleration or tilt changes slowly, the free
   surface is the plane normal to the apparent gravity f: its wall height is exactly
   R |f_lat| / |f_z| (ideal-fluid statics; every mapping of the model reproduces it for a slow
   tilt, `sloshkit.sim.spatial`). A hump of that static height is used when the 3-D model
   (linear, default mapping) stays within 6 % of 0.94 times it, i.e. when no wave rides on it
   (0.94 = sum of 2/(xi_n^2 - 1) over the three simulated modes). The measured series is aligned
   to the model by the clock offset of maximum correlation (-1 to 25 s; for the six series it agrees
   with the manifest's tau_s within 0.02 s) and read within +-0.12 s of the hump's top (maximum
   and median of the camera samples). Printed: measured / static per class and per wall
   direction of the high point in the container frame.
2. **Free slosh after the motion.** The height of the highest point of the wall (the maximum
   over the circumference, what the data's README defines) of a planar wave A cos(omega t)
   oscillates as |A cos(omega t)|: at 2 omega. A reading at one fixed point of the wall
   oscillates at omega. Printed: the power of the measured record in the 2.5-3.5 Hz band
   (omega_1 = 19.15 rad/s = 3.05 Hz) over that in the 5.5-6.7 Hz band, 0.5-6 s after the motion.
3. **Camera geometry** (``--campaign`` only): the two cameras' poses from the authors' ArUco
   calibration (`Experiments/Image Processing/Sloshing Detection/Aruco/Poses/poses_aruco_1.mat`
   for LE and TRD, `poses_aruco_2.mat` for RD), and the height their triangulation of the highest
   image point of each camera (`Sloshing_Detection.m`: highest segmented pixel per camera,
   MATLAB `triangulate`, height = the ArUco frame's y coordinate minus the first frame's) gives
   for a planar surface of known wall height, for several rest levels of the liquid relative to
   the cameras (the ArUco files do not say where the container stands; its axis is taken
   through the point where the two optical axes pass closest).

Run: PYTHONPATH=src python validation/measurement_checks_3d.py [--campaign PATH/TO/AntiSloshing]
"""

from __future__ import annotations

import argparse
import math
import warnings
from collections import defaultdict
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.signal import find_peaks
from validate_measured_3d import container_model, load_campaign, load_series

from sloshkit.errors import ValidityWarning
from sloshkit.model.modal import SloshModel
from sloshkit.sim.spatial import simulate_spatial
from sloshkit.sim.spatial_response import SpatialResponse

FloatArray = NDArray[np.float64]

#: humps lower than this static wall height are left out (camera noise is about +-2 mm) [m]
HUMP_MIN_M = 0.012
#: a hump counts as quasi-static when the model is within this fraction of its static value
QUASI_STATIC_TOLERANCE = 0.06
#: half-width of the window in which the measured series is read around a hump's top [s]
HUMP_WINDOW_S = 0.12
#: clock offsets searched for the alignment of a measured series with the model [s]
ALIGNMENT_SEARCH_S = (-1.0, 25.0, 0.01)
#: bands of the free-slosh spectrum: around omega_1 and around 2 omega_1 [Hz]
OMEGA_BAND_HZ, DOUBLE_BAND_HZ = (2.5, 3.5), (5.5, 6.7)
ARUCO = Path("Experiments") / "Image Processing" / "Sloshing Detection" / "Aruco" / "Poses"


def static_wall_height_m(response: SpatialResponse) -> FloatArray:
    """R |f_lat| / |f_z|: the wall height of the plane normal to the apparent gravity (M,) [m].

    Exact ideal-fluid statics for a slow tilt or acceleration (the surface of a liquid at rest
    relative to its container is normal to the specific force)."""
    slope = response.quasi_static_slope
    return np.asarray(response.model.radius_m * np.hypot(slope[:, 0], slope[:, 1]), dtype=float)


def static_direction_rad(response: SpatialResponse) -> FloatArray:
    """Wall direction of the static surface's high point in the container frame (M,) [rad]."""
    slope = response.quasi_static_slope
    return np.asarray(
        np.arctan2(slope[:, 1], slope[:, 0]) - response.drive.spin_angle_rad, dtype=float
    )


def clock_offset_s(
    t_meas: FloatArray, h_meas: FloatArray, t_model: FloatArray, h_model: FloatArray
) -> float:
    """The offset tau (t_model = t_meas - tau) of maximum correlation of the two series [s]."""
    offsets = np.arange(*ALIGNMENT_SEARCH_S)
    scores = [
        float(np.dot(np.interp(t_meas - tau, t_model, h_model, left=0.0, right=0.0), h_meas))
        for tau in offsets
    ]
    return float(offsets[int(np.argmax(scores))])


def quasi_static_humps(item: dict[str, Any], response: SpatialResponse) -> list[dict[str, Any]]:
    """The quasi-static humps of one series with the measured height read at their tops."""
    t, model_h = response.time_s, response.slosh_height_m
    static = static_wall_height_m(response)
    direction = static_direction_rad(response)
    factor = float(np.sum([m.wall_elevation_factor_m for m in response.model.modes]))
    modal_static = factor / response.model.radius_m
    step = float(t[1] - t[0])
    t_meas, h_meas = item["measured_t_s"], item["measured_m"]
    tau = clock_offset_s(t_meas, h_meas, t, model_h)
    tops, _ = find_peaks(static, height=HUMP_MIN_M, prominence=0.004, distance=int(0.25 / step))
    humps = []
    half = int(HUMP_WINDOW_S / step)
    for i in tops:
        model_top = float(model_h[max(0, i - half) : i + half].max())
        if abs(model_top / (modal_static * static[i]) - 1.0) > QUASI_STATIC_TOLERANCE:
            continue
        near = np.abs(t_meas - tau - t[i]) <= HUMP_WINDOW_S
        if not near.any():
            continue
        humps.append(
            {
                "name": item["name"],
                "class": item["class"],
                "time_s": float(t[i]),
                "static_m": float(static[i]),
                "model_m": model_top,
                "measured_max_m": float(h_meas[near].max()),
                "measured_median_m": float(np.median(h_meas[near])),
                "direction_deg": math.degrees(math.remainder(float(direction[i]), 2 * math.pi)),
                "clock_offset_s": tau,
            }
        )
    return humps


def model_humps(item: dict[str, Any], response: SpatialResponse) -> list[dict[str, Any]]:
    """The humps of the predicted slosh height during the motion (at least `HUMP_MIN_M`), with
    their overshoot over the model's own static value and the measured maximum near them."""
    t, model_h = response.time_s, response.slosh_height_m
    static = static_wall_height_m(response)
    vector = response.elevation_vector_m
    direction = np.arctan2(vector[:, 1], vector[:, 0]) - response.drive.spin_angle_rad
    modal_static = sum(m.wall_elevation_factor_m for m in response.model.modes) / (
        response.model.radius_m
    )
    step = float(t[1] - t[0])
    t_meas, h_meas = item["measured_t_s"], item["measured_m"]
    tau = clock_offset_s(t_meas, h_meas, t, model_h)
    tops, _ = find_peaks(model_h, height=HUMP_MIN_M, prominence=0.004, distance=int(0.15 / step))
    humps = []
    for i in tops:
        near = np.abs(t_meas - tau - t[i]) <= HUMP_WINDOW_S
        if t[i] > item["end_s"] + 0.3 or not near.any():
            continue
        humps.append(
            {
                "class": item["class"],
                "model_m": float(model_h[i]),
                "overshoot": float(model_h[i] / (modal_static * static[i]) - 1.0),
                "measured_max_m": float(h_meas[near].max()),
                "direction_deg": math.degrees(math.remainder(float(direction[i]), 2 * math.pi)),
            }
        )
    return humps


#: the camera calibration of each family of moves (data repository's Aruco/README.md)
CAMERA_SETS = (("LE, TRD", ("LE", "TRD")), ("RD", ("RD",)))


def direction_bins(
    humps: list[dict[str, Any]],
) -> list[tuple[str, int, list[dict[str, Any]]]]:
    """(camera set, lower edge [deg], humps) per camera set and 90-degree bin of the
    direction of the high point in the container frame."""
    out = []
    for label, family in CAMERA_SETS:
        rows = [r for r in humps if r["class"].removeprefix("Tilt_") in family]
        for lo in range(-180, 180, 90):
            out.append((label, lo, [r for r in rows if lo <= r["direction_deg"] < lo + 90]))
    return out


def overshoot_table(humps: list[dict[str, Any]]) -> str:
    """Measured - predicted at the model's humps [mm], quasi-static (overshoot within
    `QUASI_STATIC_TOLERANCE`) against humps with a predicted overshoot above 15 %, per set of
    camera poses and direction of the high point (bins with at least 3 humps)."""
    lines = [
        "| cameras | high point at [deg] | humps: quasi-static, overshoot > 15 % "
        "| measured - predicted [mm], quasi-static | overshoot > 15 % "
        "| overshoot > 15 %: measured - static of the model [mm] |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for label, lo, in_bin in direction_bins(humps):
        calm = [r for r in in_bin if abs(r["overshoot"]) <= QUASI_STATIC_TOLERANCE]
        wave = [r for r in in_bin if r["overshoot"] > 0.15]

        def cell(sel: list[dict[str, Any]]) -> str:
            if len(sel) < 3:
                return "-"
            d = 1e3 * np.array([r["measured_max_m"] - r["model_m"] for r in sel])
            low, high = np.percentile(d, 10), np.percentile(d, 90)
            return f"{np.median(d):+.1f} ({low:+.1f} to {high:+.1f})"

        if len(calm) < 3 and len(wave) < 3:
            continue
        over = "-"
        if len(wave) >= 3:
            above = 1e3 * np.array(
                [r["measured_max_m"] - r["model_m"] / (1.0 + r["overshoot"]) for r in wave]
            )
            over = f"{np.median(above):+.1f}"
        lines.append(
            f"| {label} | {lo} to {lo + 90} | {len(calm)}, {len(wave)} | {cell(calm)} "
            f"| {cell(wave)} | {over} |"
        )
    return "\n".join(lines)


def omega_band_ratio(
    time_s: FloatArray, height_m: FloatArray, start_s: float, stop_s: float
) -> float:
    """Power of ``height_m`` in `OMEGA_BAND_HZ` over that in `DOUBLE_BAND_HZ`, between
    ``start_s`` and ``stop_s`` (resampled at 60 Hz, mean removed, Hann window).

    Large for a reading at a fixed point of the wall (A cos omega t), small for the maximum
    over the circumference of a standing wave (|A cos omega t|, whose lines are even multiples
    of omega)."""
    keep = (time_s >= start_s) & (time_s <= stop_s)
    t_k, h_k = time_s[keep], height_m[keep]
    grid = np.arange(t_k[0], t_k[-1], 1.0 / 60.0)
    values = np.interp(grid, t_k, h_k)
    values = (values - values.mean()) * np.hanning(values.size)
    power = np.abs(np.fft.rfft(values, 8 * values.size)) ** 2
    freq = np.fft.rfftfreq(8 * values.size, 1.0 / 60.0)

    def band(lo_hi: tuple[float, float]) -> float:
        return float(power[(freq >= lo_hi[0]) & (freq <= lo_hi[1])].sum())

    return band(OMEGA_BAND_HZ) / band(DOUBLE_BAND_HZ)


def band_power_ratio(item: dict[str, Any], response: SpatialResponse) -> tuple[float, float]:
    """`omega_band_ratio` of the measured and the predicted series, 0.5-6 s after the motion."""
    start, stop = item["end_s"] + 0.5, item["end_s"] + 6.0
    tau = clock_offset_s(
        item["measured_t_s"], item["measured_m"], response.time_s, response.slosh_height_m
    )
    measured = omega_band_ratio(item["measured_t_s"] - tau, item["measured_m"], start, stop)
    return measured, omega_band_ratio(response.time_s, response.slosh_height_m, start, stop)


def simulate(model: SloshModel, item: dict[str, Any]) -> SpatialResponse:
    """The default 3-D model along the series' poses, 6.5 s past the end of the motion."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return simulate_spatial(model, item["poses"], settle_time_s=6.5)


def hump_table(humps: list[dict[str, Any]]) -> str:
    """Per class: humps, series, median measured / static (top maximum, top median), model."""
    by_class: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for hump in humps:
        by_class[hump["class"]].append(hump)
    lines = [
        "| class | humps (series) | static height [mm] | measured max / static "
        "| measured median / static | model / static |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for cls, rows in sorted(by_class.items()):
        static = np.array([r["static_m"] for r in rows])
        top = np.array([r["measured_max_m"] for r in rows]) / static
        median = np.array([r["measured_median_m"] for r in rows]) / static
        model = np.array([r["model_m"] for r in rows]) / static
        lines.append(
            f"| {cls} | {len(rows)} ({len({r['name'] for r in rows})}) "
            f"| {1e3 * static.min():.0f}-{1e3 * static.max():.0f} "
            f"| {np.median(top):.2f} ({np.percentile(top, 10):.2f}-{np.percentile(top, 90):.2f}) "
            f"| {np.median(median):.2f} | {np.median(model):.2f} |"
        )
    everything = np.array([r["measured_max_m"] / r["static_m"] for r in humps])
    lines.append(
        f"| all | {len(humps)} ({len({r['name'] for r in humps})}) | | "
        f"{np.median(everything):.2f} ({np.percentile(everything, 10):.2f}-"
        f"{np.percentile(everything, 90):.2f}) | | |"
    )
    return "\n".join(lines)


def peak_difference_table(rows: list[tuple[str, str, float, float, float]]) -> str:
    """Per class of (name, class, predicted peak, measured peak, largest static wall height)
    rows: predicted - measured peak [mm] and measured peak / largest static height."""
    by_class: dict[str, list[tuple[float, float]]] = defaultdict(list)
    for _, cls, predicted, measured, static in rows:
        by_class[cls].append((1e3 * (predicted - measured), measured / static))
    lines = [
        "| class | series | predicted - measured peak [mm]: median (range) "
        "| measured peak / largest static height: median (range) |",
        "|---|---:|---:|---:|",
    ]
    for cls, pairs in sorted(by_class.items()):
        diff, ratio = [p[0] for p in pairs], [p[1] for p in pairs]
        lines.append(
            f"| {cls} | {len(pairs)} | {np.median(diff):+.1f} ({min(diff):+.1f} to "
            f"{max(diff):+.1f}) | {np.median(ratio):.2f} ({min(ratio):.2f}-{max(ratio):.2f}) |"
        )
    return "\n".join(lines)


def direction_table(humps: list[dict[str, Any]]) -> str:
    """Measured max - static [mm] by direction of the high point (container frame), per set
    of camera poses (LE and TRD: poses_aruco_1; RD: poses_aruco_2)."""
    lines = [
        "| cameras | high point at [deg] | humps | measured max - static [mm], median (10-90 %) |",
        "|---|---|---:|---:|",
    ]
    for label, lo, sel in direction_bins(humps):
        if not sel:
            continue
        diff = 1e3 * np.array([r["measured_max_m"] - r["static_m"] for r in sel])
        lines.append(
            f"| {label} | {lo} to {lo + 90} | {len(sel)} | {np.median(diff):+.1f} "
            f"({np.percentile(diff, 10):+.1f} to {np.percentile(diff, 90):+.1f}) |"
        )
    return "\n".join(lines)


# --- camera geometry -------------------------------------------------------------------------


def aruco_camera_poses(path: Path) -> list[tuple[FloatArray, FloatArray]]:
    """(R, t) of each camera (x_camera = R x_aruco + t, mm) from a MATLAB ArUco pose file.

    The files hold MATLAB `rigidtform3d` objects, which scipy reads only as an opaque
    workspace; the matrices are found as 9 consecutive doubles forming a proper rotation
    (orthonormal to 1e-9, determinant +1, not the identity), the translation as the next 3
    consecutive doubles of ordinary magnitude (1e-3 to 1e4)."""
    from scipy.io import loadmat

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        raw = loadmat(path)["__function_workspace__"].tobytes()
    values = np.frombuffer(raw[: len(raw) // 8 * 8], dtype="<f8")
    poses = []
    i = 0
    while i + 9 <= values.size:
        block = values[i : i + 9]
        rotation = block.reshape(3, 3, order="F")
        if (
            np.all(np.isfinite(block))
            and np.all(np.abs(block) <= 1.0 + 1e-9)
            and np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-9)
            and abs(np.linalg.det(rotation) - 1.0) < 1e-9
            and not np.allclose(rotation, np.eye(3))
        ):
            tail = values[i + 9 : i + 40]
            ordinary = (np.abs(tail) > 1e-3) & (np.abs(tail) < 1e4)
            for j in range(tail.size - 2):
                if ordinary[j : j + 3].all():
                    poses.append((rotation.copy(), tail[j : j + 3].copy()))
                    break
            i += 9
        else:
            i += 1
    if len(poses) != 2:
        raise ValueError(f"{path}: expected two camera poses, found {len(poses)}")
    return poses


def _closest_points(
    c1: FloatArray, d1: FloatArray, c2: FloatArray, d2: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The points of closest approach of the lines c1 + s d1 and c2 + u d2."""
    w = c1 - c2
    a, b, c, d, e = d1 @ d1, d1 @ d2, d2 @ d2, d1 @ w, d2 @ w
    den = a * c - b * b
    return c1 + (b * e - c * d) / den * d1, c2 + (a * e - b * d) / den * d2


def triangulated_height_mm(
    poses: list[tuple[FloatArray, FloatArray]],
    wall_height_mm: float,
    direction_rad: float,
    rest_offset_mm: float,
    radius_mm: float = 49.0,
) -> float:
    """Height (ArUco y) the two cameras triangulate from their highest image points for a
    planar surface of ``wall_height_mm`` towards ``direction_rad`` [mm], the rest surface
    ``rest_offset_mm`` above the point where the optical axes pass closest; minus the same for
    the flat surface (the first frame)."""
    (r1, t1), (r2, t2) = poses
    c1, c2 = -r1.T @ t1, -r2.T @ t2
    p1, p2 = _closest_points(c1, r1[2], c2, r2[2])
    centre = 0.5 * (p1 + p2)

    def reading(height: float) -> float:
        r = np.linspace(0.0, radius_mm, 50)[:, None]
        angle = np.linspace(0.0, 2 * np.pi, 360, endpoint=False)[None, :]
        z = height * (r / radius_mm) * np.cos(angle - direction_rad)
        points = np.stack(
            [
                (centre[0] + r * np.cos(angle)).ravel(),
                (centre[1] + rest_offset_mm + z).ravel(),
                (centre[2] + r * np.sin(angle)).ravel(),
            ]
        )
        rays = []
        for rotation, translation in poses:
            camera = rotation @ points + translation[:, None]
            row = camera[1] / camera[2]  # image rows grow downwards: highest = smallest
            k = int(np.argmin(row))
            direction = rotation.T @ np.array([camera[0, k] / camera[2, k], row[k], 1.0])
            rays.append((-rotation.T @ translation, direction / np.linalg.norm(direction)))
        q1, q2 = _closest_points(rays[0][0], rays[0][1], rays[1][0], rays[1][1])
        return float(0.5 * (q1[1] + q2[1]))

    return reading(wall_height_mm) - reading(0.0)


def camera_table(checkout: Path) -> str:
    """Camera geometry and the planar-surface triangulation factor per ArUco pose file."""
    lines = [
        "| poses | cameras from the axis [mm] | angle between them [deg] | pitch [deg] "
        "| rest level [mm] | measured / true at 10, 20, 30, 40 mm (range over directions) |",
        "|---|---|---:|---|---:|---|",
    ]
    for name in ("poses_aruco_1.mat", "poses_aruco_2.mat"):
        poses = aruco_camera_poses(checkout / ARUCO / name)
        (r1, t1), (r2, t2) = poses
        c1, c2 = -r1.T @ t1, -r2.T @ t2
        p1, p2 = _closest_points(c1, r1[2], c2, r2[2])
        centre = 0.5 * (p1 + p2)
        arms = [np.array([c[0] - centre[0], c[2] - centre[2]]) for c in (c1, c2)]
        between = math.degrees(
            math.acos(float(arms[0] @ arms[1] / np.linalg.norm(arms[0]) / np.linalg.norm(arms[1])))
        )
        pitch = [math.degrees(math.asin(float(r[2][1]))) for r, _ in poses]
        for offset in (-20.0, -10.0, 0.0, 10.0):
            cells = []
            for height in (10.0, 20.0, 30.0, 40.0):
                factors = [
                    triangulated_height_mm(poses, height, math.radians(a), offset) / height
                    for a in range(0, 360, 15)
                ]
                cells.append(f"{min(factors):.2f}-{max(factors):.2f}")
            lines.append(
                f"| {name} | {np.linalg.norm(arms[0]):.0f}, {np.linalg.norm(arms[1]):.0f} "
                f"| {between:.0f} | {pitch[0]:.1f}, {pitch[1]:.1f} | {offset:+.0f} | "
                + ", ".join(cells)
                + " |"
            )
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaign", type=Path, help="checkout of GiorgioMedico/AntiSloshing")
    args = parser.parse_args()
    model = container_model()
    series = load_series()
    if args.campaign is not None:
        series = load_campaign(args.campaign)
        if not series:
            parser.error(f"--campaign: no measured series under {args.campaign}")
    humps: list[dict[str, Any]] = []
    predicted_humps: list[dict[str, Any]] = []
    peaks: list[tuple[str, str, float, float, float]] = []
    lines = ["| series | omega_1 / 2 omega_1 band power, measured | model |", "|---|---:|---:|"]
    for item in series:
        response = simulate(model, item)
        humps += quasi_static_humps(item, response)
        predicted_humps += model_humps(item, response)
        peaks.append(
            (
                item["name"],
                item["class"],
                response.peak_slosh_height_m,
                float(item["peak_m"]),
                float(static_wall_height_m(response).max()),
            )
        )
        measured, predicted = band_power_ratio(item, response)
        lines.append(f"| {item['name']} | {measured:.2f} | {predicted:.3f} |")
    print(f"{len(series)} series\n")
    print(hump_table(humps))
    print()
    print(direction_table(humps))
    print()
    print(peak_difference_table(peaks))
    print()
    print(overshoot_table(predicted_humps))
    print()
    print("\n".join(lines))
    if args.campaign is not None:
        print()
        print(camera_table(args.campaign))


if __name__ == "__main__":
    main()
