"""Design-space sweeps ("slosh maps"): fill height x move duration x law, on the fast path.

Every law in a sweep is time-scaled: a law of shape s_1(tau), tau = t/T, moved in time T. The
polynomial laws and the trapezoid (fixed acceleration fraction) are exactly that family; an
``s-curve`` in a sweep keeps the shape that its --vmax/--amax/--jmax give and is stretched to
each duration. Sweeping by peak acceleration instead of duration uses T = sqrt(a_1 / a_peak),
a_1 being the law's peak acceleration for T = 1 s.

`run_sweep` computes the cases (`sloshkit.sim.batch_kernel.law_metrics`); the result,
`SweepResult` (`sloshkit.sweep.result`), holds them with their CSV, summary and maps.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError, require_positive
from sloshkit.model.modal import SloshModel
from sloshkit.motion.laws import LAW_NAMES, make_law
from sloshkit.motion.scaling import unit_duration_shape
from sloshkit.sim.batch_kernel import kernel_rows_of, law_metrics
from sloshkit.sweep.result import SweepResult

FloatArray = NDArray[np.float64]

#: Every law can be time-scaled (the s-curve keeps the shape its limits give).
SWEEP_LAWS: tuple[str, ...] = LAW_NAMES


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
    rows = kernel_rows_of(models, dt)
    for i, law_shape in enumerate(shapes):
        velocity_pp = law_shape.derivative_pp(1)
        for j, model in enumerate(models):
            metrics = law_metrics(model, velocity_pp, durations[i], dt, chunk_cases, rows[j])
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


def linspace_inclusive(start: float, stop: float, count: int) -> FloatArray:
    """START:STOP:COUNT with both ends included (a single value when COUNT is 1).

    Parameters
    ----------
    start, stop : float
        First and last value.
    count : int
        Number of values.

    Returns
    -------
    numpy.ndarray
        The values.

    Examples
    --------
    >>> linspace_inclusive(1.0, 2.0, 3).tolist(), linspace_inclusive(1.0, 2.0, 1).tolist()
    ([1.0, 1.5, 2.0], [1.0])
    """
    if count == 1:
        return np.array([start])
    return np.linspace(start, stop, count)


def describe_rate(result: SweepResult) -> str:
    """One line: cases, time and rate.

    Parameters
    ----------
    result : SweepResult
        A sweep.

    Returns
    -------
    str
        ``"<cases> cases in <s> s (<rate> cases/s)"``.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> describe_rate(sk.run_sweep(model, ["septic"], 0.1, [1.0, 2.0])).startswith("2 cases in")
    True
    """
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
