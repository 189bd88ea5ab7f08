"""Benchmark: the planner's methods, and the optimal method against an independent minimum time.

Part 1, the README's case: the paper's vial (R 20.5 mm, h 39 mm, water, damping ratio 0.03 as in
its Table 3) moving 0.5 m with peak slosh <= 5 deg, residual <= 0.25 deg, v <= 1.5 m/s,
a <= 20 m/s^2, j <= 500 m/s^3, 4 ms controller period: every method's duration, its speed-up
over the best of the paper's laws, its ratio to the optimal duration, its compute time.

Part 2, the optimal method on six problems (distances 0.1-1 m, peak limits 2-5 deg, five of them
robust over +-10 % of the frequency, 3 modes) against an independent minimum time computed
here: a bisection on the duration T where feasibility is a linear program (scipy's HiGHS) over
a piecewise-constant jerk on its own grid (T / n with n = N, the number of export steps, so
the grid of the program is not the controller's), with the slosh of the exported velocity
samples from an exact first-order-hold discretisation written out here (matrix exponential),
every limit of the verification, and the residual circle replaced by a circumscribed polygon
(a relaxation: the reference is a lower bound up to the bisection tolerance). It prints the
ratio of the planner's duration to that minimum and the planner's compute time (wall clock and
CPU time of this process; the machine is shared, so wall time includes waiting).

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
from sloshkit.plan.optimal import plan_optimal
from sloshkit.plan.planner import plan
from sloshkit.plan.problem import PAPER_LAWS, MachineLimits, PlanProblem, SloshLimits
from sloshkit.plan.searches import plan_paper_law, plan_shaped

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


def _first_mode_response(omega: float, zeta: float, length: float, ts: float, samples: int):
    """(theta, rate) at samples 0..K-1 per unit velocity sample (K x K lower-triangular maps)
    of theta'' + 2 zeta omega theta' + omega^2 theta = -a / L, velocity linear between samples.

    Written independently of sloshkit: the state (theta, theta' + v / L) driven by v with
    A = [[0, 1], [-w^2, -2 z w]], B = [-1/L, 2 z w / L]; exact first-order hold via the
    exponential of the augmented matrix [[A, B, 0], [0, 0, 1], [0, 0, 0]] * ts.
    """
    a = np.array([[0.0, 1.0], [-(omega**2), -2 * zeta * omega]])
    b = np.array([-1.0 / length, 2 * zeta * omega / length])
    m = np.zeros((4, 4))
    m[:2, :2], m[:2, 2], m[2, 3] = a, b, 1.0
    e = expm(m * ts)
    phi, hold, ramp = e[:2, :2], e[:2, 2], e[:2, 3] / ts
    # x_{k+1} = phi x_k + (hold - ramp) v_k + ramp v_{k+1}
    impulse = np.zeros((samples, 2))  # response at sample k to a unit v at sample 0
    x = hold - ramp
    for k in range(1, samples):
        impulse[k] = x
        x = phi @ x
    impulse_next = np.zeros((samples, 2))  # unit v at sample 1 entering through "ramp"
    x = ramp.copy()
    for k in range(1, samples):
        impulse_next[k] = x
        x = phi @ x
    theta = np.zeros((samples, samples))
    y = np.zeros((samples, samples))
    for j in range(samples):  # column j: unit velocity at sample j
        for part, offset in ((impulse, 0), (impulse_next, -1)):
            start = j + offset
            if start < 0:
                continue
            rows = np.arange(start, samples)
            shifted = part[: samples - start]
            theta[rows, j] += shifted[:, 0]
            y[rows, j] += shifted[:, 1]
    rate = y - np.eye(samples) / length  # theta' = y - v / L
    return theta, rate


@dataclass
class Reference:
    """The LP bisection's minimum time and its cost."""

    duration_s: float
    programs: int
    seconds: float


def _feasible(problem: PlanProblem, duration: float) -> bool:
    ts = problem.sample_period_s
    steps = math.ceil(duration / ts - 1e-9)
    n = steps  # jerk pieces of the program's own grid
    h = duration / n
    t = np.arange(steps + 1) * ts  # export samples
    starts = np.arange(n) * h

    def integral(times: np.ndarray, order: int) -> np.ndarray:
        """Order-th integral (1: acceleration, 2: velocity, 3: position) of unit jerk pieces."""
        x = times[:, None] - starts[None, :]
        inside = np.clip(x, 0.0, h)
        after = np.clip(x - h, 0.0, None)
        if order == 1:
            return inside
        if order == 2:
            return inside**2 / 2 + h * after
        return inside**3 / 6 + h**2 / 2 * after + h * after**2 / 2

    machine, slosh = problem.machine, problem.slosh
    end = np.array([duration])
    equalities = np.vstack((integral(end, 3), integral(end, 2), integral(end, 1)))
    equality_rhs = np.array([problem.distance_m, 0.0, 0.0])
    velocity = integral(t, 2)  # (samples, n)
    acceleration = integral(np.append(starts, duration), 1)
    rows = [velocity, acceleration]
    limits = [machine.max_velocity_m_s, machine.max_acceleration_m_s2]
    polygon = []
    for model in problem.models():
        mode = model.modes[0]
        theta, rate = _first_mode_response(
            mode.omega_rad_s, mode.damping_ratio, mode.length_m, ts, steps + 1
        )
        angle = theta @ velocity
        rows.append(angle)
        limits.append(slosh.max_angle_rad)
        damped = mode.omega_rad_s * math.sqrt(1 - mode.damping_ratio**2)
        quadrature = (rate[-1] @ velocity + mode.damping_ratio * mode.omega_rad_s * angle[-1]) / (
            damped
        )
        for phase in np.linspace(0.0, 2 * math.pi, POLYGON, endpoint=False):
            polygon.append(math.cos(phase) * angle[-1] + math.sin(phase) * quadrature)
    upper = np.vstack([block for pair in rows for block in (pair, -pair)] + polygon)
    bounds_rhs = np.concatenate(
        [np.full(2 * r.shape[0], limit) for r, limit in zip(rows, limits, strict=True)]
        + [np.full(len(polygon), slosh.max_residual_rad)]
    )
    scale = machine.max_jerk_m_s3
    result = linprog(
        np.zeros(n),
        A_ub=sparse.csr_matrix(upper * scale),
        b_ub=bounds_rhs,
        A_eq=equalities * scale,
        b_eq=equality_rhs,
        bounds=(-1.0, 1.0),
        method="highs",
    )
    return bool(result.status == 0)


def reference_minimum(problem: PlanProblem, low: float, high: float) -> Reference:
    """Bisection on T (relative tolerance 2e-5) between an infeasible ``low`` and a feasible
    ``high`` (both checked, widened when wrong)."""
    started = time.perf_counter()
    programs = 2
    while _feasible(problem, low):
        low *= 0.97
        programs += 1
    while not _feasible(problem, high):
        high *= 1.03
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
        lambda: plan_optimal(problem, rows[-1].motion),
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
        "optimal (casadi/IPOPT)",
        "optimal --smooth",
        f"auto (→ {auto.method})",
    ]
    rows.append(auto)
    times.append(auto_time)
    if markdown:
        print("| method | duration | vs best paper law | vs optimal | compute (CPU) |")
        print("|---|---|---|---|---|")
    else:
        print("0.5 m move, |theta| <= 5 deg, residual <= 0.25 deg (README case); CPU seconds")
    for label, row, seconds in zip(labels, rows, times, strict=True):
        feasible = "" if row.feasible else ", infeasible"
        if not row.feasible and row.verification is not None:
            feasible = ", infeasible (" + row.verification.violations[0].split(" ")[0] + ")"
        speed = f"{best_paper / row.duration_s:.2f}×" if row.feasible else ""
        ratio = f"{row.duration_s / optimal.duration_s:.4f}" if row.feasible else ""
        print(
            f"| {label} | {row.duration_s:.4f} s{feasible} | {speed} | {ratio} | {seconds:.3f} s |"
            if markdown
            else f"  {label:<38}{row.duration_s:>9.4f} s{feasible:<24}{speed:>7}{ratio:>9}"
            f"{seconds:>9.3f} s"
        )


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
            "| optimisation (wall / CPU) | repeat (wall / CPU) |"
        )
        print("|---|---|---|---|---|---|---|---|---|")
    else:
        print("optimal method against the LP-bisection minimum time")
    worst = 0.0
    slowest = 0.0
    for distance, angle, residual, band in PROBLEMS[:3] if quick else PROBLEMS:
        problem = _problem(distance, angle, residual, band)
        warm = plan_shaped(problem)
        timings = []
        for _ in range(2):  # the first call builds the solver; the second reuses it
            wall, cpu = time.perf_counter(), time.process_time()
            candidate = plan_optimal(problem, warm.motion)
            timings.append((time.perf_counter() - wall, time.process_time() - cpu))
        assert candidate.feasible, candidate.message
        # The bracket is checked (and widened) by the bisection itself.
        reference = reference_minimum(
            problem, candidate.duration_s / 1.006, 1.0005 * candidate.duration_s
        )
        ratio = candidate.duration_s / reference.duration_s
        worst = max(worst, ratio)
        slowest = max(slowest, timings[1][1])
        cells = [
            f"{distance:g} m",
            f"{angle:g}°",
            f"{residual:g}°",
            f"±{100 * band:g} %",
            f"{reference.duration_s:.4f} s",
            f"{candidate.duration_s:.4f} s",
            f"{ratio:.4f}",
            f"{timings[0][0]:.2f} / {timings[0][1]:.2f} s",
            f"{timings[1][0]:.2f} / {timings[1][1]:.2f} s",
        ]
        print("| " + " | ".join(cells) + " |" if markdown else "  " + "  ".join(cells))
    print(
        f"\nworst ratio {worst:.4f} (target <= 1.005); slowest repeat {slowest:.2f} s CPU "
        "(target < 1 s)"
    )
    return worst <= 1.005


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--markdown", action="store_true", help="print README tables")
    parser.add_argument("--quick", action="store_true", help="three problems only")
    args = parser.parse_args()
    warnings.simplefilter("ignore", ValidityWarning)
    methods_table(args.markdown)
    print()
    optimality_table(args.markdown, args.quick)


if __name__ == "__main__":
    main()
