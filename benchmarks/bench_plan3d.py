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

Last (``reference``), the issue #25 cases (the measured TRD_2D, LE_3D and RD_2D paths, the
20-waypoint path and a pick-and-place: two waypoints 0.3 m apart with a 0.1 m lift and a 90 deg
turn about the vertical) with the issue's settings (R 49 mm, h 80 mm, water-20C, zeta 0.0066;
15 mm peak, 2 mm residual; 2 m/s, 10 m/s^2, 100 m/s^3, 4 ms; no angular limits; tilt up to 30 deg):
each method of ``sloshkit.plan_path`` against the independent minimum time of the same problem
(`ocp_reference`, casadi multiple shooting, upright for ``retime`` and ``shaped``, with free
tilt for ``tilt``), once with the linear slosh model and once with the nonlinear one
that verifies every plan (``slosh_model="nonlinear"``: the optimum of the problem a verified
plan solves), without and with a robot's joint check (``--robot``, default ur5e at the base pose
of docs/planning-3d.md). The reference optima are cached in ``ocp_reference_cache.json`` (keyed
by a hash of the problem, the slosh model and ``ocp_reference.py``; each takes minutes on the
shared machine, and one missing from the cache is computed).

Run: ``PYTHONPATH=src python benchmarks/bench_plan3d.py [--out table.md]
[--docs docs/planning-3d.md] [--tables primary,strict,waypoints,reference,limits]
[--robot ur5e|none] [--quick] [--cached-only]`` (minutes on a shared 2-core machine; not a
timed test; ``--quick``: the reference table's first case only, without the robot;
``--cached-only``: an optimum missing from the cache is shown as "not cached" instead of
computed). With ``--docs`` the tables replace the text between the
``<!-- bench_plan3d:start -->`` and ``<!-- bench_plan3d:end -->`` markers of that file (the
reference table alone, ``--tables reference``, between
``<!-- bench_plan3d-reference:start -->`` and its end marker; the limits table alone between
``<!-- bench_plan3d-limits:start -->`` and its end), so the docs carry no hand-typed figures.

``limits`` (not run by default): monotone in the limits (issue #25's target), each method
(``--methods``, default ``retime,tilt``) on the reference cases (``--cases``, default TRD_2D
and pick-and-place) with the height limit 1, 1.01 and 1.02 times 15 mm (`limits_table`).
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import math
import os
import time
import warnings
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from ocp_reference import ReferenceOptimum, reference_optimum

from sloshkit.errors import ValidityWarning
from sloshkit.io.poses import read_pose_file
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.geometry import generalised_arc_length, path_from_poses, path_from_waypoints
from sloshkit.plan.path.planner import AUTO_OPTIMAL_MAX_SAMPLES, plan_path
from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
from sloshkit.plan.path.timing import Timing

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "measured-3d"
SERIES = ("LE_3D_0m_5.3s_900deg", "RD_2D_0.3m_6.5s_720deg", "TRD_2D_0.3m_2.4s_270deg")
LIMITS = CartesianLimits(2.0, 10.0, 100.0)
RESIDUAL_M = 0.002
#: The reference table's cases: measured series, then the built paths.
REFERENCE_SERIES = ("TRD_2D_0.3m_2.4s_270deg", "LE_3D_0m_5.3s_900deg", "RD_2D_0.3m_6.5s_720deg")
REFERENCE_METHODS = ("retime", "shaped", "tilt")
CACHE = Path(__file__).resolve().parent / "ocp_reference_cache.json"
#: Where the arm sits for the robot rows (docs/planning-3d.md: the UR5e reaches the TRD path).
ROBOT_BASE_XYZ_M = (-0.35, -0.6, 0.2)
#: Shooting intervals of the reference [s]: 4 ms upright (halving it moved the TRD optimum by
#: 3e-5 relative), 8 ms tilted (its program is five times costlier per interval; halving it
#: shortened the tilted TRD optimum by 0.2 % and the pick-and-place's by 0.3 %, so the tilted
#: optima are that much long and the `tilt` ratios that much low).
UPRIGHT_INTERVAL_S, TILTED_INTERVAL_S = 4e-3, 8e-3


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
            result = plan_path(problem, "auto", reference=reference, tilt=True)
            cpu = time.process_time() - cpu
            found = {c.method: c for c in result.candidates}

            def show(method: str, found: dict[str, Any] = found) -> str:
                candidate = found.get(method)
                if candidate is None or not candidate.feasible:
                    return "infeasible"
                source = candidate.detail.get("source", "program")
                mark = "" if source == "program" or method in ("uniform", "shaped") else "*"
                return f"{candidate.duration_s:.2f} s{mark}"

            def ratio(method: str, found: dict[str, Any] = found) -> str:
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


def reference_cases(model: object) -> list[tuple[str, PathProblem]]:
    """The issue #25 benchmark problems (module docstring), named."""
    slosh = SpatialSloshLimits(0.015, RESIDUAL_M)
    limits = CartesianLimits(2.0, 10.0, 100.0, None, None)
    paths = []
    for name in REFERENCE_SERIES:
        trajectory = read_pose_file(DATA / "poses" / f"{name}.csv")
        paths.append(
            (
                name.split("_0")[0],
                path_from_poses(trajectory.position_m, trajectory.quaternion_xyzw, name=name),
            )
        )
    zigzag = np.array([[0.12 * i, 0.1 * (i % 2), 0.01 * i] for i in range(20)])
    paths.append(("20 waypoints", path_from_waypoints(zigzag, 0.03)))
    paths.append(
        (
            "pick-and-place",
            path_from_waypoints(
                [[0.0, 0.0, 0.0], [0.3, 0.0, 0.1]], yaw_rad=[0.0, math.pi / 2], name="pick"
            ),
        )
    )
    return [
        (name, PathProblem(path, limits, slosh, model, 4e-3, max_tilt_rad=math.radians(30.0)))
        for name, path in paths
    ]


def problem_key(
    problem: PathProblem, tilt: bool, interval_s: float, slosh_model: str = "linear"
) -> str:
    """SHA-256 of everything the reference depends on: the path's knots and poses, the limits,
    the model band, the tilt settings, the interval, the slosh model (named only when not the
    default, so that the linear keys read as before) and the source of ``ocp_reference.py``."""
    digest = hashlib.sha256()
    path = problem.path
    for array in (path.knots_m, path.positions_m, path.rotations.as_quat()):
        digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    described = [problem.machine, problem.slosh, problem.max_tilt_rad]
    described += [problem.tilt_centre_height_m, tilt, interval_s]
    described += [model.modes for model in problem.models()]
    if slosh_model != "linear":
        described.append(slosh_model)
    digest.update(repr(described).encode())
    digest.update((Path(__file__).resolve().parent / "ocp_reference.py").read_bytes())
    return digest.hexdigest()[:16]


def cached_reference(
    problem: PathProblem, tilt: bool, slosh_model: str = "linear", compute: bool = True
) -> tuple[ReferenceOptimum | None, bool]:
    """The reference optimum from `CACHE` when its key is there, else computed and stored
    (None when not ``compute``); and whether it came from the cache."""
    cache = json.loads(CACHE.read_text()) if CACHE.exists() else {}
    interval = TILTED_INTERVAL_S if tilt else UPRIGHT_INTERVAL_S
    key = problem_key(problem, tilt, interval, slosh_model)
    if key in cache:
        return ReferenceOptimum(**cache[key]), True
    if not compute:
        return None, False
    optimum = reference_optimum(problem, tilt=tilt, interval_s=interval, slosh_model=slosh_model)
    cache = json.loads(CACHE.read_text()) if CACHE.exists() else {}  # another run may add
    cache[key] = optimum.to_dict()
    CACHE.write_text(json.dumps(cache, indent=1, sort_keys=True) + "\n")
    return optimum, False


def _robot(name: str | None) -> Any:
    """``robot_verifier`` of a built-in arm at `ROBOT_BASE_XYZ_M`, or None."""
    if name is None:
        return None
    from sloshkit.export.frames import Mounting
    from sloshkit.export.kinematics import load_arm
    from sloshkit.export.path_robot import robot_verifier

    return robot_verifier(load_arm(name), Mounting(base_xyz_m=ROBOT_BASE_XYZ_M))


def _run_method(problem: PathProblem, method: str, verifier: Any) -> tuple[str, float, float]:
    """(shown duration or failure, verified duration [s] (nan unless feasible), wall [s]); the
    duration is marked with its source when ``retime`` or ``tilt`` returned its floor (a
    family member or the uniform scaling) instead of the programs' plan."""
    started = time.perf_counter()
    try:
        arguments: dict[str, Any] = {} if verifier is None else {"verifier": verifier}
        result = plan_path(problem, method, **arguments)
    except Exception as error:  # a method being rewritten may fail: the table shows it
        return f"error ({type(error).__name__})", math.nan, time.perf_counter() - started
    wall = time.perf_counter() - started
    found = [c for c in result.candidates if c.method == method]
    if not found:
        return "missing", math.nan, wall
    if not found[0].feasible:
        return "infeasible", math.nan, wall
    source = found[0].detail.get("source", "program")
    mark = "" if method == "shaped" or source == "program" else f" ({source})"
    return f"{found[0].duration_s:.3f} s{mark}", found[0].duration_s, wall


def reference_table(
    model: object,
    robot: str | None,
    quick: bool,
    cached_only: bool = False,
    methods: tuple[str, ...] = REFERENCE_METHODS,
    names: tuple[str, ...] = (),
) -> list[str]:
    """Rows of the reference table (module docstring); with ``cached_only`` an optimum not in
    the cache is shown as such instead of computed; ``methods`` and ``names`` (cases) select
    the columns and rows (default: all)."""
    cases = reference_cases(model)[:1] if quick else reference_cases(model)
    if names:
        cases = [(name, problem) for name, problem in cases if name in names]
    robots = [None] if quick or robot is None else [None, robot]
    rows = [
        "Against the independent optimum (`benchmarks/ocp_reference.py`) of the same problem "
        "(15 mm / 2 mm, 2 m/s, 10 m/s^2, 100 m/s^3, 4 ms, no angular limits, tilt up to "
        "30 deg), with the linear slosh model (optimum) and with the nonlinear one that "
        "verifies the plans (nonlinear optimum); `retime` and `shaped` divided by the upright "
        'optimum, `tilt` by the tilted one (a duration marked "family" is the family\'s '
        "verified member, where the programs verified no plan); compute: wall time on the "
        "shared machine:",
        "",
        "| case | robot | optimum upright | optimum tilted | optimum compute "
        "| nonlinear optimum upright | nonlinear optimum tilted | nonlinear optimum compute | "
        + " | ".join(
            f"{m} | {m} / optimum | {m} / nonlinear optimum | {m} compute" for m in methods
        )
        + " |",
        "|---|---|---|---|---|---|---|---|" + "---|---|---|---|" * len(methods),
    ]
    for name, problem in cases:
        compute = not cached_only
        upright, upright_cached = cached_reference(problem, False, compute=compute)
        tilted, tilted_cached = cached_reference(problem, True, compute=compute)
        exact, exact_cached = cached_reference(problem, False, "nonlinear", compute)
        exact_tilted, exact_tilted_cached = cached_reference(problem, True, "nonlinear", compute)

        def optimum(found: ReferenceOptimum | None) -> str:
            if found is None:
                return "not cached"
            flag = "" if found.converged else f" ({found.status})"
            return f"{found.duration_s:.3f} s{flag}"

        def seconds(found: ReferenceOptimum | None) -> str:
            return "-" if found is None else f"{found.compute_time_s:.0f}"

        def compute_of(
            first: ReferenceOptimum | None, second: ReferenceOptimum | None, cached: bool
        ) -> str:
            shown = f"{seconds(first)} / {seconds(second)} s"
            return shown + (" (cached)" if cached else "")

        spent = compute_of(upright, tilted, upright_cached and tilted_cached)
        exact_compute = compute_of(exact, exact_tilted, exact_cached and exact_tilted_cached)
        for arm in robots:
            verifier = _robot(arm)
            cells = []
            for method in methods:
                shown, duration, wall = _run_method(problem, method, verifier)
                tilting = method == "tilt"
                bases = (tilted, exact_tilted) if tilting else (upright, exact)
                ratios = [
                    "-"
                    if base is None or math.isnan(duration)
                    else f"{duration / base.duration_s:.3f}"
                    for base in bases
                ]
                cells.append(f"{shown} | {ratios[0]} | {ratios[1]} | {wall:.1f} s")
            rows.append(
                f"| {name} | {arm or '-'} | {optimum(upright)} | {optimum(tilted)} | {spent} "
                f"| {optimum(exact)} | {optimum(exact_tilted)} | {exact_compute} | "
                + " | ".join(cells)
                + " |"
            )
            print(rows[-1], flush=True)
    return rows


#: The height limit's factors of the limits table: each looser than the one before.
LOOSER_FACTORS = (1.0, 1.01, 1.02)
#: The limits table's methods and cases unless ``--methods`` and ``--cases`` say otherwise.
LIMITS_METHODS = ("retime", "tilt")
LIMITS_CASES = ("TRD_2D", "pick-and-place")


def limits_table(
    model: object,
    methods: tuple[str, ...] = LIMITS_METHODS,
    names: tuple[str, ...] = LIMITS_CASES,
    factors: tuple[float, ...] = LOOSER_FACTORS,
) -> list[str]:
    """Monotone in the limits (issue #25's target) on the reference cases: each method's
    verified duration with the height limit multiplied by each of ``factors`` (the residual
    limit kept), and the largest lengthening of a plan by a looser limit."""
    cases = [(name, problem) for name, problem in reference_cases(model) if name in names]
    slosh = cases[0][1].slosh if cases else SpatialSloshLimits(0.015, RESIDUAL_M)
    rows = [
        f"Monotone in the limits: the reference cases' height limit "
        f"({slosh.max_height_m * 1e3:g} mm) times "
        + ", ".join(f"{f:g}" for f in factors)
        + f" (looser each time; residual {slosh.max_residual_height_m * 1e3:g} mm); each plan "
        "verified; a looser limit that gives a longer plan breaks monotonicity by the "
        "lengthening shown (wall time per plan):",
        "",
        "| case | method | "
        + " | ".join(f"{f:g} × height" for f in factors)
        + " | looser never longer |",
        "|---|---|" + "---|" * len(factors) + "---|",
    ]
    for name, problem in cases:
        for method in methods:
            cells, durations = [], []
            for factor in factors:
                looser = replace(problem.slosh, max_height_m=problem.slosh.max_height_m * factor)
                shown, duration, wall = _run_method(replace(problem, slosh=looser), method, None)
                cells.append(f"{shown} ({wall:.1f} s)")
                durations.append(duration)
            lengthening = max(
                (
                    later / earlier - 1.0
                    for i, earlier in enumerate(durations)
                    for later in durations[i + 1 :]
                    if not (math.isnan(earlier) or math.isnan(later))
                ),
                default=math.nan,
            )
            verdict = (
                "-"
                if math.isnan(lengthening)
                else "yes"
                if lengthening <= 0.0
                else f"no (+{100 * lengthening:.1f} %)"
            )
            rows.append(f"| {name} | {method} | " + " | ".join(cells) + f" | {verdict} |")
            print(rows[-1], flush=True)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--docs", type=Path, default=None)
    parser.add_argument("--series", nargs="*", default=None, help="path classes (LE, RD, TRD)")
    parser.add_argument("--tables", default="primary,strict,waypoints,reference")
    parser.add_argument("--robot", default="ur5e", help="arm of the reference table, or none")
    parser.add_argument("--quick", action="store_true", help="one case of the reference table")
    parser.add_argument(
        "--methods",
        default="",
        help="methods of the reference (default all) or limits table (default retime,tilt), "
        "comma-separated",
    )
    parser.add_argument(
        "--cases",
        default="",
        help="cases of the reference (default all) or limits table (default TRD_2D, "
        "pick-and-place), comma-separated",
    )
    parser.add_argument(
        "--cached-only", action="store_true", help="reference optima from the cache only"
    )
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
    tables = ["reference"] if arguments.quick else arguments.tables.split(",")
    # the reference and limits tables' selections; empty: each table's default
    methods = tuple(name for name in arguments.methods.split(",") if name)
    cases = tuple(name for name in arguments.cases.split(",") if name)
    rows: list[str] = []
    if "primary" in tables:
        rows += [
            "Primary: both limits from the measured run (peak `meas_peak_m`, residual the "
            "measured residual) and half of both (`auto`; * marks a family's verified member: "
            "`auto` runs the programs only where their capped start has at most "
            f"{AUTO_OPTIMAL_MAX_SAMPLES} samples):",
            "",
            *series_table(model, manifest, None, series),
            "",
        ]
    if "strict" in tables:
        rows += [
            "Stricter: height limit as above, residual limit fixed at 2 mm:",
            "",
            *series_table(model, manifest, RESIDUAL_M, series),
            "",
        ]
    if "waypoints" in tables:
        rows += waypoint_table(model)
    if "reference" in tables:
        robot = None if arguments.robot.lower() == "none" else arguments.robot
        rows += [
            "",
            *reference_table(
                model,
                robot,
                arguments.quick,
                arguments.cached_only,
                methods or REFERENCE_METHODS,
                cases,
            ),
        ]
    if "limits" in tables:
        rows += [
            "",
            *limits_table(
                model,
                methods or LIMITS_METHODS,
                cases or LIMITS_CASES,
            ),
        ]
    load = os.getloadavg()[0]
    rows.append("")
    rows.append(f"(load average {load:.1f} on {os.cpu_count()} cores when the run ended)")
    text = "\n".join(rows)
    print(text)
    if arguments.out is not None:
        arguments.out.write_text(text + "\n")
    if arguments.docs is not None:
        document = arguments.docs.read_text()
        # the reference or the limits table alone has its own place in the docs
        marker = (
            f"bench_plan3d-{tables[0]}" if tables in (["reference"], ["limits"]) else "bench_plan3d"
        )
        start, end = f"<!-- {marker}:start -->", f"<!-- {marker}:end -->"
        head, _, rest = document.partition(start)
        _, _, tail = rest.partition(end)
        arguments.docs.write_text(f"{head}{start}\n{text}\n{end}{tail}")


def waypoint_table(model: object) -> list[str]:
    """The 20-waypoint compute-time case: rows of its table."""
    points = np.array([[0.12 * i, 0.1 * (i % 2), 0.01 * i] for i in range(20)])
    problem = PathProblem(
        path_from_waypoints(points, 0.03), LIMITS, SpatialSloshLimits(0.015, RESIDUAL_M), model
    )
    started, cpu = time.perf_counter(), time.process_time()
    result = plan_path(problem, "auto", tilt=True)
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
