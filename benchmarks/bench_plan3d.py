"""Benchmark of the 3-D path planner on the measured series' path geometries.

For the figure-eight (LE), circle (RD) and translation-plus-arc (TRD) paths of the measured
robot series (tests/data/measured-3d, MIT licence, AntiSloshing project), with the slosh-height
limit set to what the measured run reached (manifest ``meas_peak_m``) and to half of it, and a
residual limit of 2 mm: the duration of each method against the measured run's duration and
against uniform time scaling of the measured timing (the naive fix), and compute times. Then a
20-waypoint path for the compute-time target. Every duration is of a plan verified with the
nonlinear 3-D model.

Run: ``PYTHONPATH=src python benchmarks/bench_plan3d.py [--transcription] [--out table.md]
[--docs docs/planning-3d.md]`` (minutes on a shared 2-core machine; not a timed test). With
``--docs`` the tables replace the text between the ``<!-- bench_plan3d:start -->`` and
``<!-- bench_plan3d:end -->`` markers of that file, so the docs carry no hand-typed figures.
"""

from __future__ import annotations

import argparse
import csv
import os
import time
import warnings
from pathlib import Path

import numpy as np

from sloshkit.errors import ValidityWarning
from sloshkit.io.poses import read_pose_file
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path import generalised_arc_length, path_from_poses, path_from_waypoints
from sloshkit.plan.path_planner import plan_path
from sloshkit.plan.spatial import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.plan.timing import Timing

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "measured-3d"
SERIES = ("LE_3D_0m_5.3s_900deg", "RD_2D_0.3m_6.5s_720deg", "TRD_2D_0.3m_2.4s_270deg")
LIMITS = CartesianLimits(2.0, 10.0, 100.0)
RESIDUAL_M = 0.002


def reference_timing(
    time_s: np.ndarray, positions: np.ndarray, quaternions: np.ndarray, length_m: float
) -> Timing:
    from scipy.spatial.transform import Rotation

    s = generalised_arc_length(positions, Rotation.from_quat(quaternions))
    start = max(int(np.argmax(s > 1e-9)) - 1, 0)
    moving = np.concatenate(([True], np.diff(s[start:]) > 0.0))
    t = (time_s[start:] - time_s[start])[moving]
    return Timing.from_samples("measured", t, s[start:][moving] / s[-1] * length_m)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--transcription", action="store_true")
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--docs", type=Path, default=None)
    arguments = parser.parse_args()
    warnings.simplefilter("ignore", ValidityWarning)
    model = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )
    with (DATA / "manifest.csv").open() as stream:
        manifest = {row["name"]: row for row in csv.DictReader(stream)}
    rows = [
        "| path | height limit | measured run | uniform scaling | retime | shaped | tilt "
        "| retime vs uniform | tilt vs uniform | compute retime / shaped / tilt |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name in SERIES:
        trajectory = read_pose_file(DATA / "poses" / f"{name}.csv")
        time_s = trajectory.time_s
        positions, quaternions = trajectory.position_m, trajectory.quaternion_xyzw
        path = path_from_poses(positions, quaternions, name=name)
        reference = reference_timing(time_s, positions, quaternions, path.length_m)
        measured = float(manifest[name]["meas_peak_m"])
        for fraction in (1.0, 0.5):
            problem = PathProblem(
                path, LIMITS, SpatialSloshLimits(measured * fraction, RESIDUAL_M), model
            )
            started = time.perf_counter()
            result = plan_path(
                problem,
                "auto",
                reference=reference,
                tilt=True,
                transcription=arguments.transcription,
            )
            found = {c.method: c for c in result.candidates}

            def show(method: str, found: dict = found) -> str:
                candidate = found.get(method)
                if candidate is None or not candidate.feasible:
                    return "infeasible"
                return f"{candidate.duration_s:.2f} s"

            def ratio(method: str, found: dict = found) -> str:
                base, other = found.get("uniform"), found.get(method)
                if base is None or other is None or not (base.feasible and other.feasible):
                    return "-"
                return f"{base.duration_s / other.duration_s:.2f}x"

            compute = " / ".join(
                f"{found[m].compute_time_s:.1f}" if m in found else "-"
                for m in ("retime", "shaped", "tilt")
            )
            rows.append(
                f"| {name.split('_')[0]} | {1e3 * measured * fraction:.1f} mm "
                f"| {float(manifest[name]['motion_duration_s']):.2f} s | {show('uniform')} "
                f"| {show('retime')} | {show('shaped')} | {show('tilt')} | {ratio('retime')} "
                f"| {ratio('tilt')} | {compute} s |"
            )
            print(rows[-1], f"({time.perf_counter() - started:.0f} s)", flush=True)
    # 20 waypoints: a zig-zag in the plane with a rise, 30 mm blends.
    points = np.array([[0.12 * i, 0.1 * (i % 2), 0.01 * i] for i in range(20)])
    problem = PathProblem(
        path_from_waypoints(points, 0.03), LIMITS, SpatialSloshLimits(0.015, RESIDUAL_M), model
    )
    started, cpu = time.perf_counter(), time.process_time()
    result = plan_path(problem, "auto", tilt=True, transcription=arguments.transcription)
    total, cpu = time.perf_counter() - started, time.process_time() - cpu
    rows.append("")
    rows.append(
        f"20 waypoints (zig-zag, {problem.path.length_m:.2f} m, 30 mm blends), 15 mm / 2 mm "
        f"limits; `auto` with tilt took {total:.1f} s wall, {cpu:.1f} s CPU in all:"
    )
    rows.append("")
    rows.append("| method | duration | feasible | compute |")
    rows.append("|---|---|---|---|")
    for candidate in result.candidates:
        rows.append(
            f"| {candidate.method} | {candidate.duration_s:.2f} s | {candidate.feasible} "
            f"| {candidate.compute_time_s:.1f} s |"
        )
    load = os.getloadavg()[0]
    rows.append("")
    rows.append(f"(load average {load:.1f} on {os.cpu_count()} cores when the run ended)")
    text = "\n".join(rows)
    print(text)
    if arguments.out is not None:
        arguments.out.write_text(text + "\n")
    if arguments.docs is not None:
        document = arguments.docs.read_text()
        start, end = "<!-- bench_plan3d:start -->", "<!-- bench_plan3d:end -->"
        head, _, rest = document.partition(start)
        _, _, tail = rest.partition(end)
        arguments.docs.write_text(f"{head}{start}\n{text}\n{end}{tail}")


if __name__ == "__main__":
    main()
