"""Benchmark: the planner's methods, and the optimal method against an independent minimum time.

Part 1, the README's case: the paper's vial (R 20.5 mm, h 39 mm, water, damping ratio 0.03 as in
its Table 3) moving 0.5 m with peak slosh <= 5 deg, residual <= 0.25 deg, v <= 1.5 m/s,
a <= 20 m/s^2, j <= 500 m/s^3, 4 ms controller period: every method's duration, its speed-up
over the best of the paper's laws, its ratio to the time-optimal duration, the sum of the jerk
jumps of its controller samples (how much it chatters), its compute time.

Part 2, the optimal method on six problems (distances 0.1-1 m, peak limits 2-5 deg, five of them
robust over +-10 % of the frequency, 3 modes) against an independent minimum time computed
here: a bisection on the duration T where feasibility is a sparse linear program (scipy's
HiGHS, written here without sloshkit's planner code) over a piecewise-constant jerk on its own
grid (T / n with n = N, the number of export steps, so the grid of the program is not the
controller's), with the slosh of the exported velocity samples from an exact first-order-hold
discretisation written out here (matrix exponential), every limit of the verification, and the
residual circle replaced by a circumscribed polygon (a relaxation: the reference is the minimum
over the program's own class of moves, to the bisection tolerance; that class differs from the
planner's, so a ratio can be just below 1). It prints the ratio of the planner's duration to
that minimum and the planner's compute time (CPU time of this process and wall clock; the
machine is shared, so wall time includes waiting), and the duration and CPU time of the smooth
variant (the planner's default, `SMOOTH_PRICE` above the minimum time).

Run: .venv/bin/python benchmarks/bench_plan.py [--markdown] [--quick]
"""

from __future__ import annotations

import argparse
import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.linalg import expm
from scipy.optimize import linprog

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.errors import ValidityWarning
from sloshkit.model.modal import SloshModel
from sloshkit.motion.sampling import export_samples, steps_to_reach
from sloshkit.plan.line.optimal import SMOOTH_PRICE, plan_optimal
from sloshkit.plan.line.planner import plan
from sloshkit.plan.line.problem import PAPER_LAWS, MachineLimits, PlanProblem, SloshLimits
from sloshkit.plan.line.searches import plan_paper_law, plan_shaped

POLYGON = 64  # sides of the residual polygon


def _vial() -> SloshModel:
    return equivalent_model(
        UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, damping_ratio=0.03
    )


def _problem(distance: float, angle_deg: float, residual_deg: float, band: float) -> PlanProblem:
    return PlanProblem(
        distance,
        MachineLimits(1.5, 20.0, 500.0),
        SloshLimits(math.radians(angle_deg), math.radians(residual_deg), robustness=band),
        _vial(),
        4e-3,
    )


def _hold_matrices(omega: float, zeta: float, length: float, ts: float):
    """(phi, hold, ramp) of theta'' + 2 zeta omega theta' + omega^2 theta = -a / L in the state
    (theta, theta' + v / L) driven by a velocity linear between samples.

    Written independently of sloshkit: A = [[0, 1], [-w^2, -2 z w]], B = [-1/L, 2 z w / L];
    exact first-order hold via the exponential of the augmented matrix
    [[A, B, 0], [0, 0, 1], [0, 0, 0]] * ts; x_{k+1} = phi x_k + (hold - ramp) v_k + ramp v_{k+1}.
    """
    a = np.array([[0.0, 1.0], [-(omega**2), -2 * zeta * omega]])
    b = np.array([-1.0 / length, 2 * zeta * omega / length])
    m = np.zeros((4, 4))
    m[:2, :2], m[:2, 2], m[2, 3] = a, b, 1.0
    e = expm(m * ts)
    return e[:2, :2], e[:2, 2], e[:2, 3] / ts


@dataclass
class Reference:
    """The LP bisection's minimum time and its cost."""

    duration_s: float
    programs: int
    seconds: float


def _feasible(problem: PlanProblem, duration: float) -> bool:
    """Is there a move of ``duration`` within every limit? One sparse linear program.

    Variables (scaled by their limits): the jerk of n = ceil(T / Ts) equal pieces of T / n
    (the program's own grid, not the controller's), acceleration, velocity and position at
    the pieces' ends, and per model of the band the first mode's state at every export sample
    t_k = k Ts (k = 0..N; at rest from T on). The velocity at a sample is the polynomial of the
    piece it falls in; limits: velocity at the samples, acceleration at the nodes, jerk per
    piece, the angle at every sample, the residual circle relaxed to a circumscribed polygon.
    The slosh rows share a slack s that the program minimises; the move exists when s <= 0.
    """
    ts = problem.sample_period_s
    machine, slosh = problem.machine, problem.slosh
    jmax, amax, vmax = (
        machine.max_jerk_m_s3,
        machine.max_acceleration_m_s2,
        machine.max_velocity_m_s,
    )
    steps = steps_to_reach(duration, ts)
    n = steps
    h = duration / n
    models = problem.models()
    # columns: u 0..n-1, a 1..n, v 1..n, p 1..n, then per model x_k (2 each), k = 0..N
    iu, ia, iv, ip = (np.arange(n) + i * n for i in range(4))
    base = 4 * n
    width = base + len(models) * 2 * (steps + 1)
    eq_rows, eq_cols, eq_vals, eq_rhs = [], [], [], []
    row = 0

    def eq(entries, rhs=0.0):
        nonlocal row
        for col, val in entries:
            eq_rows.append(row)
            eq_cols.append(col)
            eq_vals.append(val)
        eq_rhs.append(rhs)
        row += 1

    for j in range(n):  # node j -> j + 1; node 0 at rest
        prev_a = [(ia[j - 1], -1.0)] if j else []
        eq([(ia[j], 1.0), (iu[j], -jmax * h / amax), *prev_a])
        prev = [(iv[j - 1], -1.0), (ia[j - 1], -amax * h / vmax)] if j else []
        eq([(iv[j], 1.0), (iu[j], -jmax * h**2 / 2 / vmax), *prev])
        prev = (
            [
                (ip[j - 1], -1.0),
                (iv[j - 1], -vmax * h / problem.distance_m),
                (ia[j - 1], -amax * h**2 / 2 / problem.distance_m),
            ]
            if j
            else []
        )
        eq([(ip[j], 1.0), (iu[j], -jmax * h**3 / 6 / problem.distance_m), *prev])
    eq([(ip[n - 1], 1.0)], 1.0)  # at the target, at rest
    eq([(iv[n - 1], 1.0)])
    eq([(ia[n - 1], 1.0)])

    def velocity(k):
        """v(k Ts) as (column, coefficient in m/s per unit) entries."""
        t = k * ts
        if t >= duration - 1e-12:
            return []
        j = min(int(t // h), n - 1)
        d = t - j * h
        entries = [(iu[j], jmax * d**2 / 2)]
        if j:
            entries += [(iv[j - 1], vmax), (ia[j - 1], amax * d)]
        return entries

    samples = [velocity(k) for k in range(steps + 1)]
    ub_rows, ub_cols, ub_vals = [], [], []
    ub = 0
    for k in range(1, steps):  # |v(t_k)| <= vmax
        for sign in (1.0, -1.0):
            for col, val in samples[k]:
                ub_rows.append(ub)
                ub_cols.append(col)
                ub_vals.append(sign * val / vmax)
            ub += 1
    ub_rhs = [1.0] * ub
    x_bounds = []
    polygon_rows: list[int] = []
    for index, model in enumerate(models):
        mode = model.modes[0]
        phi, hold, ramp = _hold_matrices(mode.omega_rad_s, mode.damping_ratio, mode.length_m, ts)
        scale = np.array([slosh.max_angle_rad, vmax / mode.length_m])
        first = base + index * 2 * (steps + 1)
        for c in range(2):
            eq([(first + c, 1.0)])  # at rest at sample 0
        for k in range(steps):
            for c in range(2):
                entries = [(first + 2 * (k + 1) + c, scale[c])]
                entries += [(first + 2 * k + d, -phi[c, d] * scale[d]) for d in range(2)]
                entries += [(col, -(hold[c] - ramp[c]) * val) for col, val in samples[k]]
                entries += [(col, -ramp[c] * val) for col, val in samples[k + 1]]
                eq(entries)
        x_bounds.append((first, steps))
        # residual: B = (theta' + zeta w theta) / w_d with theta' = y (at rest after T)
        damped = mode.omega_rad_s * math.sqrt(1 - mode.damping_ratio**2)
        last = first + 2 * steps
        for phase in np.linspace(0.0, 2 * math.pi, POLYGON, endpoint=False):
            c, s_ = math.cos(phase), math.sin(phase)
            coef_theta = (c + s_ * mode.damping_ratio * mode.omega_rad_s / damped) * scale[0]
            for col, val in ((last, coef_theta), (last + 1, s_ * scale[1] / damped)):
                ub_rows.append(ub)
                ub_cols.append(col)
                ub_vals.append(val / slosh.max_residual_rad)
            polygon_rows.append(ub)
            ub_rhs.append(1.0)
            ub += 1
    # The slosh rows get a common slack s (minimised): the program is then always feasible
    # when the machine limits are, and the move exists when s <= 0. (A plain feasibility
    # program stalls HiGHS near the boundary.)
    slack = width
    for first, count in x_bounds:  # |theta_k| / theta_max - s <= 1
        for k in range(count + 1):
            for sign in (1.0, -1.0):
                ub_rows.extend((ub, ub))
                ub_cols.extend((first + 2 * k, slack))
                ub_vals.extend((sign, -1.0))
                ub_rhs.append(1.0)
                ub += 1
    for r in polygon_rows:  # facet - s <= 1
        ub_rows.append(r)
        ub_cols.append(slack)
        ub_vals.append(-1.0)
    bounds = [(-1.0, 1.0)] * (3 * n) + [(None, None)] * (width - 3 * n) + [(-0.5, None)]
    cost = np.zeros(width + 1)
    cost[slack] = 1.0
    result = linprog(
        cost,
        A_ub=sparse.csr_matrix((ub_vals, (ub_rows, ub_cols)), shape=(ub, width + 1)),
        b_ub=np.array(ub_rhs),
        A_eq=sparse.csr_matrix((eq_vals, (eq_rows, eq_cols)), shape=(row, width + 1)),
        b_eq=np.array(eq_rhs),
        bounds=bounds,
        method="highs",
    )
    return bool(result.status == 0 and result.x[slack] <= 0.0)


def reference_minimum(problem: PlanProblem, low: float, high: float) -> Reference:
    """Bisection on T (relative tolerance 2e-5) between an infeasible ``low`` and a feasible
    ``high`` (both checked, widened when wrong)."""
    started = time.perf_counter()
    programs = 2
    while _feasible(problem, low):
        low *= 0.99
        programs += 1
    while not _feasible(problem, high):
        high *= 1.01
        programs += 1
    while high - low > 2e-5 * high:
        middle = 0.5 * (low + high)
        programs += 1
        if _feasible(problem, middle):
            high = middle
        else:
            low = middle
    return Reference(high, programs, time.perf_counter() - started)


def _cpu(function, *args, **kwargs):
    """(result, CPU seconds of this process): the machine is shared, wall time waits."""
    started = time.process_time()
    result = function(*args, **kwargs)
    return result, time.process_time() - started


def methods_table(markdown: bool) -> None:
    problem = _problem(0.5, 5.0, 0.25, 0.0)
    rows, times = [], []
    for law in PAPER_LAWS:
        row, seconds = _cpu(plan_paper_law, law, problem)
        rows.append(row)
        times.append(seconds)
    plan_shaped(problem, ("zv",))  # warm-up: numba kernels
    fast_times = []
    for _ in range(5):
        fast, seconds = _cpu(plan_shaped, problem, ("zv",))
        fast_times.append(seconds)
    rows.append(fast)
    times.append(min(fast_times))
    for call in (
        lambda: plan_shaped(problem),
        lambda: plan_optimal(problem, rows[-1].motion, smooth=False),
        lambda: plan_optimal(problem, rows[-2].motion, smooth=True),
    ):
        row, seconds = _cpu(call)
        rows.append(row)
        times.append(seconds)
    result, auto_time = _cpu(plan, problem)
    auto = result.chosen
    assert auto is not None
    optimal = rows[-2]
    best_paper = min(r.duration_s for r in rows[: len(PAPER_LAWS)] if r.feasible)
    labels = [
        *PAPER_LAWS,
        "fast (ZV-shaped S-curve)",
        "shaped (best of ZV, ZVD, EI, 2-mode)",
        "optimal --time-optimal (LP on the export grid)",
        f"optimal (default: smooth, +{100 * SMOOTH_PRICE:g} %)",
        f"auto (→ {auto.method})",
    ]
    rows.append(auto)
    times.append(auto_time)
    if markdown:
        print(
            "| method | duration | vs best paper law | vs time-optimal | jerk jumps "
            "| compute (CPU) |"
        )
        print("|---|---|---|---|---|---|")
    else:
        print("0.5 m move, |theta| <= 5 deg, residual <= 0.25 deg (README case); CPU seconds")
    for label, row, seconds in zip(labels, rows, times, strict=True):
        feasible = "" if row.feasible else ", infeasible"
        if not row.feasible and row.verification is not None:
            feasible = ", infeasible (" + row.verification.violations[0].split(" ")[0] + ")"
        speed = f"{best_paper / row.duration_s:.2f}×" if row.feasible else ""
        ratio = f"{row.duration_s / optimal.duration_s:.4f}" if row.feasible else ""
        jumps = f"{jerk_jumps(row.motion, problem.sample_period_s):,.0f} m/s³" if row.motion else ""
        print(
            f"| {label} | {row.duration_s:.4f} s{feasible} | {speed} | {ratio} | {jumps} "
            f"| {seconds:.3f} s |"
            if markdown
            else f"  {label:<46}{row.duration_s:>9.4f} s{feasible:<24}{speed:>7}{ratio:>9}"
            f"{jumps:>16}{seconds:>9.3f} s"
        )


def jerk_jumps(motion, sample_period_s: float) -> float:
    """Sum of |jerk jumps| [m/s^3] of the controller samples (jerk zero before and after)."""
    acceleration = export_samples(motion, sample_period_s)["acceleration_m_s2"]
    jerk = np.diff(acceleration) / sample_period_s
    return float(np.abs(np.diff(np.concatenate(([0.0], jerk, [0.0])))).sum())


PROBLEMS = [
    (0.5, 5.0, 0.25, 0.0),
    (0.1, 2.0, 0.1, 0.1),
    (0.25, 3.0, 0.15, 0.1),
    (0.5, 5.0, 0.25, 0.1),
    (0.75, 2.0, 0.25, 0.1),
    (1.0, 4.0, 0.2, 0.1),
]


def optimality_table(markdown: bool, quick: bool) -> bool:
    if markdown:
        print(
            "| distance | peak limit | residual limit | band | LP minimum | optimal | ratio "
            f"| optimisation (CPU / wall) | programs | smooth (+{100 * SMOOTH_PRICE:g} %) "
            "| smooth (CPU) |"
        )
        print("|---|---|---|---|---|---|---|---|---|---|---|")
    else:
        print("optimal method against the LP-bisection minimum time")
    worst = 0.0
    slowest = 0.0
    for distance, angle, residual, band in PROBLEMS[:3] if quick else PROBLEMS:
        problem = _problem(distance, angle, residual, band)
        warm = plan_shaped(problem)
        wall, cpu = time.perf_counter(), time.process_time()
        candidate = plan_optimal(problem, warm.motion, smooth=False)
        timing = (time.process_time() - cpu, time.perf_counter() - wall)
        assert candidate.feasible, candidate.message
        smooth, smooth_cpu = _cpu(plan_optimal, problem, warm.motion, smooth=True)
        # The bracket is checked (and widened) by the bisection itself.
        reference = reference_minimum(
            problem, candidate.duration_s / 1.002, 1.0003 * candidate.duration_s
        )
        ratio = candidate.duration_s / reference.duration_s
        worst = max(worst, ratio)
        slowest = max(slowest, timing[0])
        cells = [
            f"{distance:g} m",
            f"{angle:g}°",
            f"{residual:g}°",
            f"±{100 * band:g} %",
            f"{reference.duration_s:.4f} s",
            f"{candidate.duration_s:.4f} s",
            f"{ratio:.4f}",
            f"{timing[0]:.2f} / {timing[1]:.2f} s",
            str(candidate.detail["programs"]),
            f"{smooth.duration_s:.4f} s"
            + ("" if smooth.detail.get("variant") == "smooth" else " (time-optimal)"),
            f"{smooth_cpu:.2f} s",
        ]
        print("| " + " | ".join(cells) + " |" if markdown else "  " + "  ".join(cells))
    print(
        f"\nworst ratio {worst:.4f} (target <= 1.005); slowest optimisation {slowest:.2f} s CPU "
        "(target < 1 s)"
    )
    return worst <= 1.005


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--markdown", action="store_true", help="print the docs/performance.md tables"
    )
    parser.add_argument("--quick", action="store_true", help="three problems only")
    args = parser.parse_args()
    warnings.simplefilter("ignore", ValidityWarning)
    methods_table(args.markdown)
    print()
    optimality_table(args.markdown, args.quick)


if __name__ == "__main__":
    main()
