"""Parsing of the function-object output of a sloshkit case into signals (pure functions).

v1912 writes vectors in parentheses; a restarted run writes a new folder named after its start
time, so every time folder of a function object is read and merged in time order (later
folders win where they overlap).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.cfd.case import SCALE
from sloshkit.cfd.summary import read_case_summary
from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


def parse_table(text: str) -> FloatArray:
    r"""Rows of numbers from a function-object file: '#' lines skipped, parentheses dropped.

    A row that is not all numbers, or shorter than the others (the last line of a run killed
    while writing it), is dropped.

    Parameters
    ----------
    text : str
        The file's text.

    Returns
    -------
    ndarray
        (rows, columns); empty (0, 0) when nothing parses.

    Examples
    --------
    >>> parse_table("# t F\n0.1 (1 2 3)\n0.2 (4 5 6)\n0.3 (7")
    array([[0.1, 1. , 2. , 3. ],
           [0.2, 4. , 5. , 6. ]])
    """
    rows = []
    for line in text.splitlines():
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        try:
            rows.append([float(v) for v in stripped.replace("(", " ").replace(")", " ").split()])
        except ValueError:
            continue
    if not rows:
        return np.zeros((0, 0))
    widths = [len(r) for r in rows]
    width = max(set(widths), key=widths.count)
    return np.asarray([r for r in rows if len(r) == width], dtype=float)


def read_function_object(case: Path, name: str, file_name: str) -> FloatArray:
    r"""All time folders of postProcessing/NAME/*/FILE merged in time order (a restarted run
    starts a new folder; later folders win where they overlap).

    Parameters
    ----------
    case : Path
        The case folder.
    name : str
        The function object's name.
    file_name : str
        Its output file in each time folder.

    Returns
    -------
    ndarray
        The merged table (first column: time).

    Raises
    ------
    InputError
        No output of that function object.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> case = Path(tempfile.mkdtemp())
    >>> for start, rows in (("0", "0 1\n1 2\n2 3\n"), ("1", "1 20\n2 30\n")):
    ...     folder = case / "postProcessing" / "probe" / start
    ...     folder.mkdir(parents=True)
    ...     _ = (folder / "p").write_text(rows)
    >>> read_function_object(case, "probe", "p")[:, 1]
    array([ 1., 20., 30.])
    """
    root = case / "postProcessing" / name
    if not root.is_dir():
        raise InputError("case", str(case), f"has no postProcessing/{name} (has the solver run?)")
    parts = []
    for folder in sorted(
        root.iterdir(), key=lambda p: float(p.name) if _is_number(p.name) else math.inf
    ):
        path = folder / file_name
        if path.is_file():
            table = parse_table(path.read_text(encoding="utf-8", errors="replace"))
            if table.size:
                parts.append(table)
    if not parts:
        raise InputError("case", str(case), f"postProcessing/{name} holds no data")
    merged = parts[0]
    for part in parts[1:]:
        merged = np.vstack((merged[merged[:, 0] < part[0, 0] - 1e-12], part))
    return merged


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


@dataclass(frozen=True)
class CfdSignals:
    """Signals of a run in SI: wall elevations of every probe column (at r = 0.98 R, angles
    ``angles_rad`` about the axis, counted from +x), mean surface tilt, wall force.

    Parameters
    ----------
    time_s : ndarray
        Sample times [s].
    elevations_m : ndarray
        Wall elevation of every probe column, (samples, columns) [m].
    angles_rad : ndarray
        Angles of the columns [rad].
    tilt_rad : ndarray
        Mean free-surface slope angle (the seed paper's eq. 13) [rad].
    force_x_n : ndarray
        Wall force along x [N].
    summary : dict
        The case's ``sloshkit-case.json``.
    notes : tuple of str
        What the signals lack (e.g. no wall-force rows), for the analysis's warnings.

    Returns
    -------
    CfdSignals

    Examples
    --------
    >>> import numpy as np
    >>> t = np.array([0.0, 0.1])
    >>> signals = CfdSignals(t, np.array([[1e-3, -1e-3], [2e-3, -2e-3]]),
    ...                      np.array([0.0, np.pi]), 0 * t, 0 * t, {})
    >>> signals.elevation_m
    array([0.001, 0.002])
    """

    time_s: FloatArray
    elevations_m: FloatArray  # (samples, columns)
    angles_rad: FloatArray
    tilt_rad: FloatArray
    force_x_n: FloatArray
    summary: dict[str, object]
    notes: tuple[str, ...] = ()

    def _column(self, angle: float) -> FloatArray:
        distance = np.abs(np.angle(np.exp(1j * (self.angles_rad - angle))))
        return np.asarray(self.elevations_m[:, int(np.argmin(distance))], dtype=float)

    @property
    def elevation_plus_m(self) -> FloatArray:
        """Wall elevation at +x [m]."""
        return self._column(0.0)

    @property
    def elevation_minus_m(self) -> FloatArray:
        """Wall elevation at -x [m]."""
        return self._column(math.pi)

    @property
    def elevation_m(self) -> FloatArray:
        """Antisymmetric wall elevation (eta(+x) - eta(-x)) / 2: the first mode's signal [m]."""
        return 0.5 * (self.elevation_plus_m - self.elevation_minus_m)

    @property
    def slosh_height_m(self) -> FloatArray:
        """Slosh height: the largest wall elevation above rest over the probe columns [m]."""
        return np.asarray(np.max(self.elevations_m, axis=1), dtype=float)

    def columns(self) -> dict[str, FloatArray]:
        """Named columns for CSV export."""
        columns = {
            "t_s": self.time_s,
            "elevation_plus_m": self.elevation_plus_m,
            "elevation_minus_m": self.elevation_minus_m,
            "elevation_m": self.elevation_m,
            "slosh_height_m": self.slosh_height_m,
            "tilt_rad": self.tilt_rad,
            "force_x_n": self.force_x_n,
        }
        if self.angles_rad.size > 2:
            for k, angle in enumerate(self.angles_rad):
                columns[f"elevation_{math.degrees(angle):.0f}deg_m"] = self.elevations_m[:, k]
        return columns


def _uniform(time: FloatArray, values: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Resample rows logged at adaptive time steps onto a uniform grid (the median step).

    Rows whose time does not advance are dropped first (the last of equal times is kept): a run
    whose adaptive step collapsed to ~1e-70 s logs the same time over and over, and a zero
    median step would ask for an endless grid."""
    advancing = np.concatenate((np.diff(time) > 0.0, [True]))
    time, values = time[advancing], values[advancing]
    if time.size < 3:
        return time, values
    steps = np.diff(time)
    step = float(np.median(steps))
    if np.max(np.abs(steps - step)) <= 1e-6 * step:
        return time, values
    grid = np.arange(time[0], time[-1] + 0.5 * step, step)
    grid = grid[grid <= time[-1] + 1e-12]
    columns = [np.interp(grid, time, values[:, k]) for k in range(values.shape[1])]
    return grid, np.column_stack(columns)


def read_signals(case: Path) -> CfdSignals:
    """Wall elevations, tilt and force of a finished (or partly finished) case, on a uniform
    time grid (runs with an adaptive step are resampled linearly at their median step).

    The wall elevation of a column is the sum of its alpha probes times their spacing, minus
    the fill height.

    Parameters
    ----------
    case : Path
        The case folder.

    Returns
    -------
    CfdSignals

    Raises
    ------
    InputError
        Missing or inconsistent function-object output.

    Examples
    --------
    >>> from pathlib import Path
    >>> read_signals(Path("no-such-case"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: case = 'no-such-case' is invalid: is not a sloshkit CFD case ...
    """
    summary = read_case_summary(case)
    probes = read_function_object(case, "wallProbes", "alpha.water")
    require_finite_table(probes, case, "wallProbes/*/alpha.water")
    count = int(summary["probes_per_column"])
    angles = np.asarray(summary.get("probe_angles_rad", [0.0, math.pi]), dtype=float)
    if probes.shape[1] != 1 + angles.size * count:
        raise InputError(
            "case",
            str(case),
            f"expected {angles.size * count} probes, found {probes.shape[1] - 1}",
        )
    dz = float(summary["probe_dz_m"])
    fill = float(summary["fill_height_m"])
    alpha = np.clip(probes[:, 1:], 0.0, 1.0).reshape(probes.shape[0], angles.size, count)
    elevations = alpha.sum(axis=2) * dz - fill
    tilt_table = read_function_object(case, "surfaceTilt", "volFieldValue.dat")
    require_finite_table(tilt_table, case, "surfaceTilt/*/volFieldValue.dat")
    tilt = np.arctan2(tilt_table[:, 1], -tilt_table[:, 3])
    notes: tuple[str, ...] = ()
    try:
        forces = read_function_object(case, "wallForces", "force.dat")
    except InputError:  # a force.dat with its header only: no wall force, said so
        forces = np.zeros((2, 2))
        forces[1, 0] = 1.0
        notes = (
            "the case has no wall-force rows (postProcessing/wallForces/*/force.dat holds only "
            "its header); frequency and damping are from the probe wall elevation",
        )
    require_finite_table(forces, case, "wallForces/*/force.dat")
    force_x = forces[:, 1] / SCALE**4  # mm units: N' = kg mm s^-2 scaled; see case.py
    raw_time = probes[:, 0]
    stacked = np.column_stack(
        (
            elevations,
            np.interp(raw_time, tilt_table[:, 0], tilt),
            np.interp(raw_time, forces[:, 0], force_x),
        )
    )
    time, stacked = _uniform(raw_time, stacked)
    return CfdSignals(
        time_s=time,
        elevations_m=stacked[:, : angles.size],
        angles_rad=angles,
        tilt_rad=stacked[:, angles.size],
        force_x_n=stacked[:, angles.size + 1],
        summary=summary,
        notes=notes,
    )


def require_finite_table(table: FloatArray, case: Path, name: str) -> None:
    """`InputError` naming the function-object file and time of the first non-finite value:
    a NaN in a signal is a damaged or diverged output, never a reason to switch signals.

    Parameters
    ----------
    table : ndarray
        A merged function-object table (`read_function_object`; first column time).
    case : Path
        The case folder.
    name : str
        The file, relative to postProcessing (for the message).

    Returns
    -------
    None

    Examples
    --------
    >>> require_finite_table(np.array([[0.0, 1.0], [0.1, 2.0]]), Path("c"), "p/0/f")
    """
    bad = ~np.isfinite(table)
    if np.any(bad):
        row = int(np.argmax(bad.any(axis=1)))
        raise InputError(
            "case",
            str(case),
            f"postProcessing/{name} holds {table[row][bad[row]][0]} in data row {row + 1} "
            f"(t = {table[row, 0]:.6g} s): a damaged file or a diverged run",
        )
