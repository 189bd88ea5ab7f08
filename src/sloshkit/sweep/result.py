"""The result of a sweep: metrics over law x fill height x duration, its CSV, summary and maps."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.files import atomic_open
from sloshkit.results import ResultMixin, require_pandas

FloatArray = NDArray[np.float64]


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
        masked = self._shortest_by_law()
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
        by_law = {
            law: [value if math.isfinite(value) else None for value in row.tolist()]
            for law, row in zip(self.laws, self._shortest_by_law(), strict=True)
        }
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

    def _shortest_by_law(self) -> FloatArray:
        """Shortest safe duration [s] per (law, fill height); inf where none is safe."""
        return np.asarray(np.where(self.safe(), self.durations_s[:, None, :], np.inf).min(axis=2))

    def plot_maps(self, folder: str | Path) -> list[Path]:
        """Heat maps of peak and residual slosh angle, one panel per law (PNG)."""
        target = Path(folder)
        paths = [target / "peak_angle_map.png", target / "residual_angle_map.png"]
        self.plot(path=paths[0], quantity="peak_angle_deg")
        self.plot(path=paths[1], quantity="residual_angle_deg")
        return paths


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
