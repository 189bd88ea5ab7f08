"""Design-space sweeps ("slosh maps"): fill height x move duration x law, on the fast path.

Every law in a sweep is time-scaled: a law of shape s_1(tau), tau = t/T, moved in time T. The
polynomial laws and the trapezoid (fixed acceleration fraction) are exactly that family; an
``s-curve`` in a sweep keeps the shape that its --vmax/--amax/--jmax give and is stretched to
each duration. Sweeping by peak acceleration instead of duration uses T = sqrt(a_1 / a_peak),
a_1 being the law's peak acceleration for T = 1 s.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError, require_positive
from sloshkit.files import write_rows_csv
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import Liquid
from sloshkit.model.modal import DampingLaw, equivalent_model
from sloshkit.motion.laws import LAW_NAMES, make_law
from sloshkit.motion.sampling import steps_for
from sloshkit.motion.scaling import scaled_velocity_samples, unit_duration_shape
from sloshkit.results import ResultMixin, require_pandas
from sloshkit.sim.batch import batch_metrics

FloatArray = NDArray[np.float64]

#: Every law can be time-scaled (the s-curve keeps the shape its limits give).
SWEEP_LAWS: tuple[str, ...] = LAW_NAMES


@dataclass(frozen=True, eq=False)
class SweepResult(ResultMixin):
    """Metrics over the grid; arrays indexed [law, fill height, duration].

    ``durations_s`` and ``peak_acceleration_m_s2`` are (laws, durations): identical rows when
    the sweep is over duration, per-law when it is over peak acceleration.
    """

    laws: tuple[str, ...]
    fill_heights_m: FloatArray
    durations_s: FloatArray
    peak_acceleration_m_s2: FloatArray
    omega_1_rad_s: FloatArray
    peak_angle_deg: FloatArray
    residual_angle_deg: FloatArray
    peak_wall_elevation_m: FloatArray
    residual_wall_elevation_m: FloatArray
    distance_m: float
    axis: str = "duration"
    max_angle_deg: float | None = None
    max_residual_deg: float | None = None
    elapsed_s: float = 0.0

    @property
    def cases(self) -> int:
        """Number of simulated cases."""
        return int(self.peak_angle_deg.size)

    def safe(self) -> NDArray[np.bool_]:
        """Cases that meet the limits (peak angle during, residual amplitude after the move)."""
        mask = np.ones(self.peak_angle_deg.shape, dtype=bool)
        if self.max_angle_deg is not None:
            mask &= self.peak_angle_deg <= self.max_angle_deg
        if self.max_residual_deg is not None:
            mask &= self.residual_angle_deg <= self.max_residual_deg
        return mask

    def rows(self) -> list[dict[str, object]]:
        """One dict per case with the CSV columns."""
        safe = self.safe()
        rows: list[dict[str, object]] = []
        for i, law in enumerate(self.laws):
            for j, height in enumerate(self.fill_heights_m):
                for k in range(self.durations_s.shape[1]):
                    rows.append(
                        {
                            "law": law,
                            "fill_height_m": float(height),
                            "duration_s": float(self.durations_s[i, k]),
                            "omega_1_rad_s": float(self.omega_1_rad_s[j]),
                            "peak_angle_deg": float(self.peak_angle_deg[i, j, k]),
                            "residual_angle_deg": float(self.residual_angle_deg[i, j, k]),
                            "peak_wall_elevation_m": float(self.peak_wall_elevation_m[i, j, k]),
                            "residual_wall_elevation_m": float(
                                self.residual_wall_elevation_m[i, j, k]
                            ),
                            "peak_acceleration_m_s2": float(self.peak_acceleration_m_s2[i, k]),
                            "safe": bool(safe[i, j, k]),
                        }
                    )
        return rows

    def to_csv(self, path: str | Path) -> Path:
        """Write `rows` as CSV, atomically."""
        return write_rows_csv(path, self.rows())

    def to_pandas(self) -> Any:
        """`rows` as a pandas DataFrame (one row per case; pandas is optional)."""
        return require_pandas().DataFrame(self.rows())

    def to_dict(self) -> dict[str, Any]:
        """The `summary` and every case (`rows`)."""
        return {**self.summary(), "rows": self.rows()}

    def shortest_safe(self) -> list[dict[str, object]]:
        """Per fill height, the shortest safe duration over all laws (None if none is safe)."""
        safe = self.safe()
        best: list[dict[str, object]] = []
        for j, height in enumerate(self.fill_heights_m):
            candidates = [
                (float(self.durations_s[i, k]), law)
                for i, law in enumerate(self.laws)
                for k in range(self.durations_s.shape[1])
                if safe[i, j, k]
            ]
            duration, law = min(candidates) if candidates else (None, None)
            best.append({"fill_height_m": float(height), "duration_s": duration, "law": law})
        return best

    def summary(self) -> dict[str, object]:
        """JSON-ready summary: counts, limits and the shortest safe duration per fill height."""
        safe = self.safe()
        by_law = {}
        for i, law in enumerate(self.laws):
            durations = []
            for j in range(self.fill_heights_m.size):
                ok = np.nonzero(safe[i, j])[0]
                durations.append(float(self.durations_s[i, ok].min()) if ok.size else None)
            by_law[law] = durations
        return {
            "cases": self.cases,
            "safe_cases": int(safe.sum()),
            "laws": list(self.laws),
            "axis": self.axis,
            "distance_m": self.distance_m,
            "max_angle_deg": self.max_angle_deg,
            "max_residual_deg": self.max_residual_deg,
            "shortest_safe": self.shortest_safe(),
            "shortest_safe_by_law_s": by_law,
            "elapsed_s": self.elapsed_s,
            "cases_per_s": self.cases / self.elapsed_s if self.elapsed_s > 0 else None,
        }

    def plot_maps(self, folder: str | Path) -> list[Path]:
        """Heat maps of peak and residual slosh angle, one panel per law (PNG)."""

        target = Path(folder)
        paths = [target / "peak_angle_map.png", target / "residual_angle_map.png"]
        self.plot(path=paths[0], quantity="peak_angle_deg")
        self.plot(path=paths[1], quantity="residual_angle_deg")
        return paths


def run_sweep(
    container: UprightCylinder,
    liquid: Liquid,
    fill_heights_m: Sequence[float] | FloatArray,
    laws: Sequence[str],
    distance_m: float,
    durations_s: Sequence[float] | FloatArray | None = None,
    peak_accelerations_m_s2: Sequence[float] | FloatArray | None = None,
    *,
    n_modes: int = 3,
    damping_law: DampingLaw = "seed",
    damping_ratio: float | None = None,
    surface_tension: bool = False,
    s_curve_limits: tuple[float, float, float] | None = None,
    acceleration_fraction: float | None = None,
    sample_period_s: float = 1e-3,
    max_angle_deg: float | None = None,
    max_residual_deg: float | None = None,
    chunk_cases: int = 2048,
    progress: Callable[[int, int], None] | None = None,
) -> SweepResult:
    """Evaluate every (law, fill height, duration) case on the linear fast path.

    Give either ``durations_s`` or ``peak_accelerations_m_s2``. ``progress(done, total)`` is called
    after each block of cases. Memory is bounded by ``chunk_cases`` velocity histories.
    """
    started = time.perf_counter()
    distance = require_positive("distance", distance_m, "m")
    dt = require_positive("sample_period", sample_period_s, "s")
    heights = np.asarray(fill_heights_m, dtype=float)
    if heights.size == 0 or not laws:
        raise InputError("sweep", "empty", "needs at least one fill height and one law")
    if (durations_s is None) == (peak_accelerations_m_s2 is None):
        raise InputError("duration", None, "give either durations or peak accelerations")
    shapes = []
    for name in laws:
        if name not in SWEEP_LAWS:
            raise InputError("laws", name, "must be among " + ", ".join(SWEEP_LAWS))
        if name == "s-curve" and s_curve_limits is None:
            raise InputError("laws", name, "an s-curve in a sweep needs --vmax, --amax and --jmax")
        vmax, amax, jmax = s_curve_limits or (None, None, None)
        motion = make_law(
            name,
            distance,
            duration_s=1.0,
            max_velocity_m_s=vmax,
            max_acceleration_m_s2=amax,
            max_jerk_m_s3=jmax,
            acceleration_fraction=acceleration_fraction,
        )
        shapes.append(unit_duration_shape(motion))
    if durations_s is not None:
        grid = np.asarray(durations_s, dtype=float)
        for value in grid:
            require_positive("duration", value, "s")
        durations = np.tile(grid, (len(laws), 1))
        axis = "duration"
    else:
        grid = np.asarray(peak_accelerations_m_s2, dtype=float)
        for value in grid:
            require_positive("peak_acceleration", value, "m/s^2")
        unit_peaks = np.array([shape.peak_acceleration_m_s2 for shape in shapes])
        durations = np.sqrt(unit_peaks[:, None] / grid[None, :])
        axis = "peak_acceleration"
    unit_peaks = np.array([shape.peak_acceleration_m_s2 for shape in shapes])
    peak_acceleration = unit_peaks[:, None] / durations**2

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        models = [
            equivalent_model(
                container,
                liquid,
                float(h),
                n_modes=n_modes,
                damping_law=damping_law,
                damping_ratio=damping_ratio,
                surface_tension=surface_tension,
            )
            for h in heights
        ]
    for message in sorted({str(w.message) for w in caught}):
        warnings.warn(message, caught[0].category, stacklevel=2)

    shape = (len(laws), heights.size, grid.size)
    results = {key: np.zeros(shape) for key in ("peak", "residual", "wall", "wall_residual")}
    per_chunk = max(1, min(grid.size, chunk_cases))
    total = len(laws) * heights.size * grid.size
    done = 0
    for i, law_shape in enumerate(shapes):
        velocity_pp = law_shape.derivative_pp(1)
        for start in range(0, grid.size, per_chunk):
            block = durations[i, start : start + per_chunk]
            steps = steps_for(float(block.max()), dt)
            velocity = scaled_velocity_samples(velocity_pp, block, dt, steps)
            for j, model in enumerate(models):
                metrics = batch_metrics(model, velocity, block, dt)
                stop = start + block.size
                results["peak"][i, j, start:stop] = metrics.peak_angle_rad
                results["residual"][i, j, start:stop] = metrics.residual_angle_rad
                results["wall"][i, j, start:stop] = metrics.peak_wall_elevation_m
                results["wall_residual"][i, j, start:stop] = metrics.residual_wall_elevation_m
                done += block.size
                if progress is not None:
                    progress(done, total)
    return SweepResult(
        laws=tuple(laws),
        fill_heights_m=heights,
        durations_s=durations,
        peak_acceleration_m_s2=peak_acceleration,
        omega_1_rad_s=np.array([model.modes[0].omega_rad_s for model in models]),
        peak_angle_deg=np.degrees(results["peak"]),
        residual_angle_deg=np.degrees(results["residual"]),
        peak_wall_elevation_m=results["wall"],
        residual_wall_elevation_m=results["wall_residual"],
        distance_m=distance,
        axis=axis,
        max_angle_deg=max_angle_deg,
        max_residual_deg=max_residual_deg,
        elapsed_s=time.perf_counter() - started,
    )


def linspace_inclusive(start: float, stop: float, count: int) -> FloatArray:
    """START:STOP:COUNT with both ends included (a single value when COUNT is 1)."""
    if count == 1:
        return np.array([start])
    return np.linspace(start, stop, count)


def describe_rate(result: SweepResult) -> str:
    """One line: cases, time and rate."""
    rate = result.cases / result.elapsed_s if result.elapsed_s > 0 else math.inf
    return f"{result.cases} cases in {result.elapsed_s:.2f} s ({rate:,.0f} cases/s)"


__all__ = [
    "SWEEP_LAWS",
    "SweepResult",
    "describe_rate",
    "linspace_inclusive",
    "run_sweep",
    "unit_duration_shape",
]
