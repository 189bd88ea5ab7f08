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
from sloshkit.files import atomic_open
from sloshkit.model.modal import SloshModel
from sloshkit.motion.laws import LAW_NAMES, make_law
from sloshkit.motion.scaling import unit_duration_shape
from sloshkit.results import ResultMixin, require_pandas
from sloshkit.sim.batch_kernel import law_metrics

FloatArray = NDArray[np.float64]

#: Every law can be time-scaled (the s-curve keeps the shape its limits give).
SWEEP_LAWS: tuple[str, ...] = LAW_NAMES


@dataclass(frozen=True, eq=False)
class SweepResult(ResultMixin):
    """Metrics over the grid; arrays indexed [law, fill height, duration] (SI, radians).

    ``durations_s`` and ``peak_acceleration_m_s2`` are (laws, durations): identical rows when the
    sweep is over duration, per-law when it is over peak acceleration. Follows the result protocol
    (`sloshkit.results.ResultMixin`); ``to_csv`` writes one row per case (`rows`).

    Parameters
    ----------
    laws : tuple of str
        The laws swept.
    fill_heights_m : numpy.ndarray
        Fill heights [m].
    durations_s : numpy.ndarray
        Move durations [s], (laws, durations).
    peak_acceleration_m_s2 : numpy.ndarray
        Peak accelerations [m/s^2], (laws, durations).
    omega_1_rad_s : numpy.ndarray
        First-mode frequency per fill height [rad/s].
    peak_angle_rad, residual_angle_rad : numpy.ndarray
        Peak first-mode angle during the move and residual amplitude after it [rad].
    peak_wall_elevation_m, residual_wall_elevation_m : numpy.ndarray
        Peak wall elevation during the move and its residual bound after it [m].
    distance_m : float
        Travel distance [m].
    axis : str
        ``"duration"`` or ``"peak_acceleration"``.
    max_angle_rad, max_residual_rad : float, optional
        The limits that define `safe` [rad].
    elapsed_s : float
        Computing time [s].

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> result = sk.run_sweep(model, ["septic"], 0.1, [1.0, 2.0])
    >>> result.cases, len(result.rows())
    (2, 2)
    """

    laws: tuple[str, ...]
    fill_heights_m: FloatArray
    durations_s: FloatArray
    peak_acceleration_m_s2: FloatArray
    omega_1_rad_s: FloatArray
    peak_angle_rad: FloatArray
    residual_angle_rad: FloatArray
    peak_wall_elevation_m: FloatArray
    residual_wall_elevation_m: FloatArray
    distance_m: float
    axis: str = "duration"
    max_angle_rad: float | None = None
    max_residual_rad: float | None = None
    elapsed_s: float = 0.0

    @property
    def peak_angle_deg(self) -> FloatArray:
        """`peak_angle_rad` in degrees (for tables and figures)."""
        return np.degrees(self.peak_angle_rad)

    @property
    def residual_angle_deg(self) -> FloatArray:
        """`residual_angle_rad` in degrees (for tables and figures)."""
        return np.degrees(self.residual_angle_rad)

    @property
    def max_angle_deg(self) -> float | None:
        """`max_angle_rad` in degrees."""
        return None if self.max_angle_rad is None else math.degrees(self.max_angle_rad)

    @property
    def max_residual_deg(self) -> float | None:
        """`max_residual_rad` in degrees."""
        return None if self.max_residual_rad is None else math.degrees(self.max_residual_rad)

    @property
    def cases(self) -> int:
        """Number of simulated cases."""
        return int(self.peak_angle_rad.size)

    def safe(self) -> NDArray[np.bool_]:
        """Cases that meet the limits (peak angle during, residual amplitude after the move)."""
        mask = np.ones(self.peak_angle_rad.shape, dtype=bool)
        if self.max_angle_rad is not None:
            mask &= self.peak_angle_rad <= self.max_angle_rad
        if self.max_residual_rad is not None:
            mask &= self.residual_angle_rad <= self.max_residual_rad
        return mask

    def rows(self) -> list[dict[str, object]]:
        """One dict per case with the CSV columns (Python floats, bools and strings)."""
        columns = self.columns()
        return [
            dict(zip(columns, values, strict=True))
            for values in zip(*(column.tolist() for column in columns.values()), strict=True)
        ]

    def columns(self) -> dict[str, NDArray[Any]]:
        """The CSV columns as flat arrays, one entry per case (the order of `rows`)."""
        laws, heights, durations = self.peak_angle_deg.shape
        law_index = np.repeat(np.arange(laws), heights * durations)
        height_index = np.tile(np.repeat(np.arange(heights), durations), laws)
        return {
            "law": np.asarray(self.laws, dtype=object)[law_index],
            "fill_height_m": self.fill_heights_m[height_index],
            "duration_s": np.repeat(self.durations_s, heights, axis=0).ravel(),
            "omega_1_rad_s": self.omega_1_rad_s[height_index],
            "peak_angle_deg": self.peak_angle_deg.ravel(),
            "residual_angle_deg": self.residual_angle_deg.ravel(),
            "peak_wall_elevation_m": self.peak_wall_elevation_m.ravel(),
            "residual_wall_elevation_m": self.residual_wall_elevation_m.ravel(),
            "peak_acceleration_m_s2": np.repeat(
                self.peak_acceleration_m_s2, heights, axis=0
            ).ravel(),
            "safe": self.safe().ravel(),
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write the cases as CSV (the columns of `rows`), atomically, from the arrays:
        numbers in their shortest round-trip form (``str`` of each value, as `rows` holds it)."""
        columns = self.columns()
        text = [_as_text(column) for column in columns.values()]
        lines = [",".join(columns), *map(",".join, zip(*text, strict=True))]
        with atomic_open(path, "w") as stream:
            stream.write("\n".join(lines) + "\n")
        return Path(path)

    def to_pandas(self) -> Any:
        """`rows` as a pandas DataFrame (one row per case; pandas is optional)."""
        return require_pandas().DataFrame(self.rows())

    def to_dict(self) -> dict[str, Any]:
        """The `summary` and every case (`rows`)."""
        return {**self.summary(), "rows": self.rows()}

    def shortest_safe(self) -> list[dict[str, object]]:
        """Per fill height, the shortest safe duration over all laws (None if none is safe);
        of laws equally short, the first by name."""
        masked = np.where(self.safe(), self.durations_s[:, None, :], np.inf).min(axis=2)
        best: list[dict[str, object]] = []
        for j, height in enumerate(self.fill_heights_m):
            shortest = float(masked[:, j].min())
            found = math.isfinite(shortest)
            law = min(law for i, law in enumerate(self.laws) if masked[i, j] == shortest)
            best.append(
                {
                    "fill_height_m": float(height),
                    "duration_s": shortest if found else None,
                    "law": law if found else None,
                }
            )
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
    model: SloshModel | Callable[[float], SloshModel],
    laws: Sequence[str],
    distance_m: float,
    durations_s: Sequence[float] | FloatArray | None = None,
    peak_accelerations_m_s2: Sequence[float] | FloatArray | None = None,
    *,
    fill_heights_m: Sequence[float] | FloatArray | None = None,
    s_curve_limits: tuple[float, float, float] | None = None,
    acceleration_fraction: float | None = None,
    sample_period_s: float = 1e-3,
    max_angle_rad: float | None = None,
    max_residual_rad: float | None = None,
    chunk_cases: int = 2048,
    progress: Callable[[int, int], None] | None = None,
) -> SweepResult:
    """Evaluate every (law, fill height, duration) case on the linear fast path.

    Every law is time-scaled: a law of shape s_1(tau), tau = t/T, moved in time T (see the
    module's docstring); the metrics are those of `sloshkit.sim.batch.batch_metrics`, computed by
    `sloshkit.sim.batch_kernel.law_metrics` with the velocity sampled inside the kernel.

    Parameters
    ----------
    model : SloshModel or callable
        The model (a sweep at its own fill height), or a function of the fill height [m]
        returning the model there (e.g. `sloshkit.model.modal.model_family`, or one that
        returns a calibrated model), so calibrated models flow into the maps.
    laws : sequence of str
        Law names (`sloshkit.motion.laws.LAW_NAMES`).
    distance_m : float
        Travel distance [m].
    durations_s : sequence of float, optional
        Move durations [s]; give these or ``peak_accelerations_m_s2``.
    peak_accelerations_m_s2 : sequence of float, optional
        Peak accelerations [m/s^2]: each law gets T = sqrt(a_1 / a_peak).
    fill_heights_m : sequence of float, optional
        Fill heights [m]; required when ``model`` is a function, else the model's own.
    s_curve_limits : tuple of float, optional
        (vmax [m/s], amax [m/s^2], jmax [m/s^3]) that shape an ``s-curve``.
    acceleration_fraction : float, optional
        Acceleration fraction of the trapezoidal law.
    sample_period_s : float
        Sample period of the fast path [s].
    max_angle_rad : float, optional
        Limit on the peak first-mode angle during the move [rad] (for `SweepResult.safe`).
    max_residual_rad : float, optional
        Limit on the residual first-mode amplitude after the move [rad].
    chunk_cases : int
        Cases per call of the kernel.
    progress : callable, optional
        ``progress(done, total)`` after each (law, fill height).

    Returns
    -------
    SweepResult
        Metrics indexed [law, fill height, duration].

    References
    ----------
    M. C. De Simone et al., Appl. Sci. 14 (2024) 4522, doi:10.3390/app14114522 (the laws).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> result = sk.run_sweep(model, ["quintic"], 0.1, [0.8, 1.6], max_angle_rad=0.1)
    >>> # the short move exceeds 0.1 rad, the long one does not:
    >>> result.peak_angle_rad.shape, result.safe().tolist()
    ((1, 1, 2), [[[False, True]]])
    """
    started = time.perf_counter()
    distance = require_positive("distance", distance_m, "m")
    dt = require_positive("sample_period", sample_period_s, "s")
    if isinstance(model, SloshModel):
        if fill_heights_m is not None and not np.allclose(fill_heights_m, model.fill_height_m):
            raise InputError(
                "fill_heights",
                fill_heights_m,
                "give a function of the fill height to sweep other fill heights than the model's",
            )
        fixed = model
        heights = np.array([model.fill_height_m])
        factory: Callable[[float], SloshModel] = lambda _height: fixed  # noqa: E731
    else:
        if fill_heights_m is None:
            raise InputError("fill_heights", None, "needed when the model is a function")
        heights = np.asarray(fill_heights_m, dtype=float)
        factory = model
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
    _check_sweep_size(len(laws), heights.size, durations, dt, chunk_cases)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        models = [factory(float(h)) for h in heights]
    for message in sorted({str(w.message) for w in caught}):
        warnings.warn(message, caught[0].category, stacklevel=2)

    shape = (len(laws), heights.size, grid.size)
    results = {key: np.zeros(shape) for key in ("peak", "residual", "wall", "wall_residual")}
    total = len(laws) * heights.size * grid.size
    done = 0
    for i, law_shape in enumerate(shapes):
        velocity_pp = law_shape.derivative_pp(1)
        for j, model in enumerate(models):
            metrics = law_metrics(model, velocity_pp, durations[i], dt, chunk_cases)
            results["peak"][i, j] = metrics.peak_angle_rad
            results["residual"][i, j] = metrics.residual_angle_rad
            results["wall"][i, j] = metrics.peak_wall_elevation_m
            results["wall_residual"][i, j] = metrics.residual_wall_elevation_m
            done += grid.size
            if progress is not None:
                progress(done, total)
    return SweepResult(
        laws=tuple(laws),
        fill_heights_m=heights,
        durations_s=durations,
        peak_acceleration_m_s2=peak_acceleration,
        omega_1_rad_s=np.array([model.modes[0].omega_rad_s for model in models]),
        peak_angle_rad=results["peak"],
        residual_angle_rad=results["residual"],
        peak_wall_elevation_m=results["wall"],
        residual_wall_elevation_m=results["wall_residual"],
        distance_m=distance,
        axis=axis,
        max_angle_rad=max_angle_rad,
        max_residual_rad=max_residual_rad,
        elapsed_s=time.perf_counter() - started,
    )


def _check_sweep_size(
    laws: int, heights: int, durations: FloatArray, dt: float, chunk_cases: int
) -> None:
    """Refuse a sweep whose result maps or per-chunk velocity block exceed the memory limit."""
    from sloshkit.budget import require_samples

    counts = {"laws": laws, "fill_height": heights, "duration": durations.shape[1]}
    largest = max(counts, key=lambda name: counts[name])
    require_samples(
        largest,
        f"{laws} laws x {heights} fill heights x {durations.shape[1]} durations",
        laws * heights * durations.shape[1],
        8,
        "cases",
    )
    longest = float(durations.max())
    steps = longest / dt + 3.0
    require_samples(
        "sample_period",
        f"{dt:.3g} s for moves up to {longest:.3g} s",
        steps * min(durations.shape[1], chunk_cases),
        3,
        "velocity samples per block",
    )


def _as_text(column: NDArray[Any]) -> list[str]:
    """``str`` of every value of ``column`` (as `SweepResult.rows` holds it), each distinct float
    (bit pattern) formatted once: the fill heights, durations and accelerations repeat."""
    if column.dtype.kind != "f":
        return list(map(str, column.tolist()))
    _, first, inverse = np.unique(column.view(np.int64), return_index=True, return_inverse=True)
    if 2 * first.size > column.size:
        return list(map(str, column.tolist()))
    words = np.array(list(map(str, column[first].tolist())), dtype=object)
    return list(words[inverse.ravel()])


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
