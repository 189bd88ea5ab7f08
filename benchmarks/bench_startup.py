"""Benchmark: start-up of the command line against ``python -c "import numpy"``, side by side.

Each command runs in a fresh interpreter (``python -m sloshkit ...``), alternating with the
numpy reference, ``--repeat`` times; the table gives the best and the median wall time, the
best CPU time (user + system of the child: on a shared machine the wall clock includes waiting
for a core) and the ratios of the best times to the reference's. The last row is the
40,000-case sweep of the README with its CSV and both maps (target: under 3 s), before it the
README's 1-D plan of the paper's vial (target: under 1 s); ``--breakdown`` adds where the
sweep's time goes, measured phase by phase in one fresh interpreter that runs the same steps as
the command.

Run: .venv/bin/python benchmarks/bench_startup.py [--markdown] [--repeat 5] [--breakdown]
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

SWEEP = (
    "sweep --distance 0.5m --fill-height 10mm:60mm:50 --duration 0.5s:3s:200 "
    "--laws trapezoidal,cubic,quintic,septic --max-angle 10deg --max-residual 1deg --out {out}"
)

#: The README's 1-D plan (the paper's vial; target: under 1 s wall on an idle machine).
PLAN = (
    "plan --distance 0.5m --max-angle 5deg --max-residual 0.25deg --vmax 1.5m/s "
    "--amax 20m/s^2 --jmax 500m/s^3 --json"
)

PHASES = """
import sys, tempfile, time
clock = [(time.perf_counter(), time.process_time())]
marks = []
def mark(name):
    clock.append((time.perf_counter(), time.process_time()))
    marks.append(name)
import numpy as np
mark("numpy")
import sloshkit.cli.app, sloshkit.cli.options, sloshkit.cli.moves
mark("typer, rich, the CLI's options")
import sloshkit.cli.sweep
mark("the sweep command")
import numba
from sloshkit import UprightCylinder, get_liquid
from sloshkit.model.modal import model_family
from sloshkit.motion import make_law
from sloshkit.motion.scaling import unit_duration_shape
from sloshkit.sim.batch_kernel import law_metrics
from sloshkit.sweep import run_sweep
family = model_family(UprightCylinder(0.0205), get_liquid("water-25C"))
for law in ("trapezoidal", "septic"):  # the two compiled kernels of the sweep, from the cache
    unit = unit_duration_shape(make_law(law, 0.5, duration_s=1.0)).derivative_pp(1)
    law_metrics(family(0.039), unit, np.array([1.0]), 1e-3)
mark("numba and its cached kernels")
result = run_sweep(family, ["trapezoidal", "cubic", "quintic", "septic"], 0.5,
                   np.linspace(0.5, 3.0, 200), fill_heights_m=np.linspace(0.01, 0.06, 50),
                   max_angle_rad=np.radians(10), max_residual_rad=np.radians(1))
mark("40,000 cases")
folder = tempfile.mkdtemp()
result.to_csv(folder + "/sweep.csv")
mark("sweep.csv")
import matplotlib.figure, sloshkit.plotting.sweep
mark("matplotlib")
result.plot_maps(folder)
mark("two maps")
for name, (a, b) in zip(marks, zip(clock, clock[1:])):
    print(f"{name}\t{b[0] - a[0]:.3f}\t{b[1] - a[1]:.3f}")
"""


def breakdown(repeat: int, markdown: bool) -> None:
    """Best wall and CPU time of each phase of the sweep over ``repeat`` fresh interpreters."""
    best: dict[str, tuple[float, float]] = {}
    for _ in range(repeat):
        out = subprocess.run(
            [sys.executable, "-c", PHASES], check=True, capture_output=True, text=True
        ).stdout
        for line in out.strip().splitlines():
            name, wall, cpu = line.split("\t")
            old = best.get(name, (float("inf"), float("inf")))
            best[name] = (min(old[0], float(wall)), min(old[1], float(cpu)))
    total = (sum(w for w, _ in best.values()), sum(c for _, c in best.values()))
    if markdown:
        print("\n| sweep phase | wall | CPU |\n|---|---|---|")
        for name, (wall, cpu) in [*best.items(), ("sum", total)]:
            print(f"| {name} | {wall:.2f} s | {cpu:.2f} s |")
    else:
        print(f"\nsweep, phase by phase (best of {repeat}; interpreter start not included)")
        for name, (wall, cpu) in [*best.items(), ("sum", total)]:
            print(f"{name:<52}{wall:>8.3f}{cpu:>8.3f}")


def run(arguments: list[str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of one child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    subprocess.run(arguments, check=True, capture_output=True)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument(
        "--markdown", action="store_true", help="print the docs/performance.md table"
    )
    parser.add_argument("--breakdown", action="store_true", help="the sweep's phases too")
    args = parser.parse_args()
    out = tempfile.mkdtemp(prefix="sloshkit-bench-")
    python = [sys.executable]
    commands = {
        'python -c "import numpy"': [*python, "-c", "import numpy"],
        "sloshkit --help": [*python, "-m", "sloshkit", "--help"],
        "sloshkit model": [*python, "-m", "sloshkit", "model"],
        "sloshkit plan (the paper's 1-D problem, --json)": [
            *python,
            "-m",
            "sloshkit",
            *PLAN.split(),
        ],
        "sloshkit sweep (40,000 cases, CSV and maps)": [
            *python,
            "-m",
            "sloshkit",
            *SWEEP.format(out=out).split(),
        ],
    }
    env_note = os.environ.get("PYTHONPATH", "")
    best = {name: (float("inf"), float("inf")) for name in commands}
    walls: dict[str, list[float]] = {name: [] for name in commands}
    run(commands["sloshkit sweep (40,000 cases, CSV and maps)"])  # numba cache, disk cache
    run(commands["sloshkit plan (the paper's 1-D problem, --json)"])
    for _ in range(args.repeat):
        for name, command in commands.items():
            wall, cpu = run(command)
            best[name] = (min(best[name][0], wall), min(best[name][1], cpu))
            walls[name].append(wall)
    reference_wall, reference_cpu = best['python -c "import numpy"']
    if args.markdown:
        print("| command | wall (best) | wall (median) | CPU | wall / numpy | CPU / numpy |")
        print("|---|---|---|---|---|---|")
    else:
        print(
            f"best and median of {args.repeat}, fresh interpreters (PYTHONPATH={env_note or '-'})"
        )
        print(
            f"{'command':<46}{'wall [s]':>10}{'median':>9}{'CPU [s]':>10}{'wall x':>9}{'CPU x':>8}"
        )
    for name, (wall, cpu) in best.items():
        ratios = (wall / reference_wall, cpu / reference_cpu)
        median = statistics.median(walls[name])
        if args.markdown:
            print(
                f"| `{name}` | {wall:.2f} s | {median:.2f} s | {cpu:.2f} s | {ratios[0]:.1f}× "
                f"| {ratios[1]:.1f}× |"
            )
        else:
            print(
                f"{name:<46}{wall:>10.3f}{median:>9.3f}{cpu:>10.3f}{ratios[0]:>9.1f}"
                f"{ratios[1]:>8.1f}"
            )

    if args.breakdown:
        breakdown(args.repeat, args.markdown)


if __name__ == "__main__":
    main()
