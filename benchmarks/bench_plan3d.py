"""Benchmark of the 3-D path planner on the measured series' path geometries.

For the figure-eight (LE), circle (RD) and translation-plus-arc (TRD) paths of the measured
robot series (tests/data/measured-3d, MIT licence, AntiSloshing project): the duration of each
method against the measured run's duration and against uniform time scaling of the measured
timing (the naive fix), and compute times, in two tables:

1. (primary, as issue #13 asks) both slosh limits set to what the measured run reached, and to
   half of it: the peak height limit to the manifest's ``meas_peak_m`` (the largest measured
   height above the baseline) and the residual limit to the **measured residual**, the largest
   measured height above the baseline (``baseline_m``) after the motion's end, i.e. over the
   camera samples with t_meas - tau_s >= ``motion_end_pose_s`` (the free slosh after the
   motion; `measured_residual_m`);
2. (stricter) the height limit as above and half of it, the residual limit fixed at 2 mm.

Then a 20-waypoint path for the compute-time target. Every duration is of a plan verified with
the nonlinear 3-D model.

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


def measured_residual_m(name: str, row: dict[str, str]) -> float:
    """The measured residual slosh height of a series: the largest measured height above the
    baseline after the motion's end (camera time t_meas - tau_s >= motion_end_pose_s) [m]."""
    data = np.loadtxt(DATA / "measured" / f"{name}.csv", delimiter=",", skiprows=1)
    after = data[:, 0] - float(row["tau_s"]) >= float(row["motion_end_pose_s"])
    return float(np.max(data[after, 1]) - float(row["baseline_m"]))


def height_bound_s(problem: PathProblem) -> float:
    """Lower bound on the duration of any timing of the path (container upright on it) that
    keeps the first mode's wall height under the height limit, from the linear pendulum model.

    The first mode is a pendulum of length L and frequency w whose bob, at y, obeys
    y'' = w^2 (q - y) (damping neglected, zeta = 0.0066 here), q the bob's rest point on the
    container's axis (Abramson, NASA SP-106 (1966) ch. 6). A wall height e |phi| <= h keeps
    |y - q| <= d = L h / e, so |y''| <= a = w^2 d and the bob passes within d of every point of
    the path in order: it travels at least l = sum (|q_i+1 - q_i| - 2 d)+ over any ordered
    checkpoints (the largest over several spacings is taken; the last within d too). From rest
    at |acceleration| <= a to a final speed <= v_f = w L r / e (the residual limit r), that
    takes at least (2 sqrt(a l + v_f^2 / 2) - v_f) / a. Horizontal components only; it ignores
    the other modes (which can add to or cancel the first at the wall) and the container's
    tilts (LE tilts it), so it is a bound for the upright RD and TRD moves only.
    """
    mode = problem.model.modes[0]
    omega, length, wall = mode.omega_rad_s, mode.length_m, mode.wall_elevation_factor_m
    reach = length * problem.slosh.max_height_m / wall
    bob_acceleration = omega**2 * reach
    final_speed = omega * length * problem.slosh.max_residual_height_m / wall
    s = np.linspace(0.0, problem.path.length_m, 4001)
    axis = problem.path.orientation(s).apply([0.0, 0.0, 1.0])
    rest = (problem.path.position(s) + mode.bob_height_m * axis)[:, :2]
    travel = 0.0
    for stride in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 4000):
        points = rest[np.unique(np.append(np.arange(0, s.size, stride), s.size - 1))]
        steps = np.linalg.norm(np.diff(points, axis=0), axis=1) - 2.0 * reach
        travel = max(travel, float(np.sum(np.maximum(steps, 0.0))) - reach)
    peak = np.sqrt(bob_acceleration * max(travel, 0.0) + 0.5 * final_speed**2)
    return float((2.0 * peak - final_speed) / bob_acceleration)


def series_table(
    model: object,
    manifest: dict[str, dict[str, str]],
    residual_m: float | None,
    transcription: bool,
    series: tuple[str, ...] = SERIES,
) -> list[str]:
    """Rows of one table over the series and the full and half measured limits: the residual
    limit is ``residual_m`` or, when None, the measured residual (halved with the height)."""
    rows = [
        "| path | height limit | residual limit | measured run | uniform scaling | retime | shaped "
        "| tilt | retime vs uniform | tilt vs uniform | height bound | uniform / bound "
        "| compute retime / shaped / tilt | CPU auto |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name in series:
        trajectory = read_pose_file(DATA / "poses" / f"{name}.csv")
        time_s = trajectory.time_s
        positions, quaternions = trajectory.position_m, trajectory.quaternion_xyzw
        path = path_from_poses(positions, quaternions, name=name)
        reference = reference_timing(time_s, positions, quaternions, path.length_m)
        measured = float(manifest[name]["meas_peak_m"])
        residual = measured_residual_m(name, manifest[name])
        for fraction in (1.0, 0.5):
            limits = SpatialSloshLimits(
                measured * fraction, residual * fraction if residual_m is None else residual_m
            )
            problem = PathProblem(path, LIMITS, limits, model)
            started, cpu = time.perf_counter(), time.process_time()
            result = plan_path(
                problem, "auto", reference=reference, tilt=True, transcription=transcription
            )
            cpu = time.process_time() - cpu
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

            bound = height_bound_s(problem)
            uniform = found.get("uniform")
            uniform_over_bound = (
                f"{uniform.duration_s / bound:.2f}x" if uniform and uniform.feasible else "-"
            )
            compute = " / ".join(
                f"{found[m].compute_time_s:.1f}" if m in found else "-"
                for m in ("retime", "shaped", "tilt")
            )
            rows.append(
                f"| {name.split('_')[0]} | {1e3 * limits.max_height_m:.1f} mm "
                f"| {1e3 * limits.max_residual_height_m:.1f} mm "
                f"| {float(manifest[name]['motion_duration_s']):.2f} s | {show('uniform')} "
                f"| {show('retime')} | {show('shaped')} | {show('tilt')} | {ratio('retime')} "
                f"| {ratio('tilt')} | {bound:.2f} s | {uniform_over_bound} | {compute} s "
                f"| {cpu:.1f} s |"
            )
            print(rows[-1], f"({time.perf_counter() - started:.0f} s)", flush=True)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--transcription", action="store_true")
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--docs", type=Path, default=None)
    parser.add_argument("--series", nargs="*", default=None, help="path classes (LE, RD, TRD)")
    parser.add_argument("--tables", default="primary,strict,waypoints")
    arguments = parser.parse_args()
    warnings.simplefilter("ignore", ValidityWarning)
    model = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )
    with (DATA / "manifest.csv").open() as stream:
        manifest = {row["name"]: row for row in csv.DictReader(stream)}
    series = tuple(
        name for name in SERIES if not arguments.series or name.split("_")[0] in arguments.series
    )
    tables = arguments.tables.split(",")
    rows: list[str] = []
    if "primary" in tables:
        rows += [
            "Primary: both limits from the measured run (peak `meas_peak_m`, residual the "
            "measured residual) and half of both:",
            "",
            *series_table(model, manifest, None, arguments.transcription, series),
            "",
        ]
    if "strict" in tables:
        rows += [
            "Stricter: height limit as above, residual limit fixed at 2 mm:",
            "",
            *series_table(model, manifest, RESIDUAL_M, arguments.transcription, series),
            "",
        ]
    if "waypoints" in tables:
        rows += waypoint_table(model, arguments.transcription)
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


def waypoint_table(model: object, transcription: bool) -> list[str]:
    """The 20-waypoint compute-time case: rows of its table."""
    points = np.array([[0.12 * i, 0.1 * (i % 2), 0.01 * i] for i in range(20)])
    problem = PathProblem(
        path_from_waypoints(points, 0.03), LIMITS, SpatialSloshLimits(0.015, RESIDUAL_M), model
    )
    started, cpu = time.perf_counter(), time.process_time()
    result = plan_path(problem, "auto", tilt=True, transcription=transcription)
    total, cpu = time.perf_counter() - started, time.process_time() - cpu
    rows: list[str] = []
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
    return rows


if __name__ == "__main__":
    main()
