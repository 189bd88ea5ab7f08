"""Markdown of the wall-stability table for docs/cfd.md, and the run-exclusion limits of the
damping study (the damping section itself: benchmarks/cfd_damping_converged_report.py)."""

from __future__ import annotations

from typing import Any

#: A run whose largest Courant number stays above this after the start-up transient, or whose
#: first-mode frequency departs from linear theory by more than `MAX_FREQUENCY_ERROR` (every
#: clean run is within 0.5 %), carries parasitic currents: excluded from the extrapolation.
MAX_LATE_COURANT = 0.5
MAX_FREQUENCY_ERROR = 0.01


def render_stability(rows: list[dict[str, Any]]) -> str:
    """The table of the wall-stability experiments (benchmarks/cfd_wall_stability.py)."""
    lines = [
        "| experiment (what it tests) | wall cell | min. determinant | max. aspect ratio | "
        "outcome | growth per step | largest Courant at the end |",
        "|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        wall = row["wall_cell_mm"]
        growth = row["growth_per_step"]
        outcome = (
            f"blew up after {row['steps_run']} steps"
            if row["blew_up"]
            else f"ran {row['steps_run']} steps"
        )
        lines.append(
            f"| {row['experiment']} ({row['tests']}) | "
            f"{'-' if wall is None else f'{wall:.3f} mm'} | {row['min_determinant']:.2g} | "
            f"{row['max_aspect_ratio']:.3g} | {outcome} | "
            f"{'-' if growth is None else f'{growth:.3g}'} | {row['courant_last']:.2g} |"
        )
    return "\n".join(lines)
