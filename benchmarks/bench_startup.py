"""Benchmark: start-up of the command line against ``python -c "import numpy"``, side by side.

Each command runs in a fresh interpreter (``python -m sloshkit ...``), alternating with the
numpy reference, ``--repeat`` times; the table gives the best wall time and the best CPU time
(user + system of the child: on a shared machine the wall clock includes waiting for a core)
and their ratios to the reference. The last row is the 40,000-case sweep of the README with
its CSV and both maps (target: under 3 s).

Run: .venv/bin/python benchmarks/bench_startup.py [--markdown] [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

SWEEP = (
    "sweep --distance 0.5m --fill-height 10mm:60mm:50 --duration 0.5s:3s:200 "
    "--laws trapezoidal,cubic,quintic,septic --max-angle 10deg --max-residual 1deg --out {out}"
)


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
    parser.add_argument("--markdown", action="store_true", help="print the README table")
    args = parser.parse_args()
    out = tempfile.mkdtemp(prefix="sloshkit-bench-")
    python = [sys.executable]
    commands = {
        'python -c "import numpy"': [*python, "-c", "import numpy"],
        "sloshkit --help": [*python, "-m", "sloshkit", "--help"],
        "sloshkit model": [*python, "-m", "sloshkit", "model"],
        "sloshkit sweep (40,000 cases, CSV and maps)": [
            *python,
            "-m",
            "sloshkit",
            *SWEEP.format(out=out).split(),
        ],
    }
    env_note = os.environ.get("PYTHONPATH", "")
    best = {name: (float("inf"), float("inf")) for name in commands}
    run(commands["sloshkit sweep (40,000 cases, CSV and maps)"])  # numba cache, disk cache
    for _ in range(args.repeat):
        for name, command in commands.items():
            wall, cpu = run(command)
            best[name] = (min(best[name][0], wall), min(best[name][1], cpu))
    reference_wall, reference_cpu = best['python -c "import numpy"']
    if args.markdown:
        print("| command | wall | CPU | wall / numpy | CPU / numpy |")
        print("|---|---|---|---|---|")
    else:
        print(f"best of {args.repeat}, fresh interpreters (PYTHONPATH={env_note or '-'})")
        print(f"{'command':<46}{'wall [s]':>10}{'CPU [s]':>10}{'wall x':>9}{'CPU x':>8}")
    for name, (wall, cpu) in best.items():
        ratios = (wall / reference_wall, cpu / reference_cpu)
        if args.markdown:
            print(
                f"| `{name}` | {wall:.2f} s | {cpu:.2f} s | {ratios[0]:.1f}× | {ratios[1]:.1f}× |"
            )
        else:
            print(f"{name:<46}{wall:>10.3f}{cpu:>10.3f}{ratios[0]:>9.1f}{ratios[1]:>8.1f}")


if __name__ == "__main__":
    main()
