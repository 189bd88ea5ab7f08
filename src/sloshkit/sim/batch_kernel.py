"""Fused fast path: time-scaled laws sampled inside the kernel, 64 cases in lock step.

For a rest-to-rest law of shape s_1(tau) moved in time T, the velocity at t_k = k dt is
v_1(k dt / T) / T (`sloshkit.motion.scaling`). The kernel evaluates it where it is needed and
steps the exact first-order-hold discretisation of every mode
(`sloshkit.sim.discretisation.velocity_driven_discretisation`; Franklin, Powell & Workman,
*Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2): no velocity array, no time
history, memory O(cases).

Cases run in blocks of `BLOCK` lanes stepped together; every loop over the lanes is branch-free
(selects, max) so that it compiles to vector instructions. At each step the velocity of all
lanes is one Horner evaluation per law piece present in the block (usually one: the block's
durations are close after sorting), the piece of each lane chosen by a select, so there is
neither a per-lane search nor a gather. The polynomial order is a compile-time constant (the
coefficients are padded with leading zeros to a multiple of 4; one compiled kernel per such
order). Only floating-point contraction (fused multiply-add) is allowed: no reassociation, no
assumption about NaN or infinity.

The metrics are those of `sloshkit.sim.batch.batch_metrics` for the same velocity samples
(peak |theta_1| and peak |wall elevation| over the samples t <= T, residual amplitudes from the
state at the first sample t >= T scaled back to T).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel
from sloshkit.sim.batch import BatchMetrics
from sloshkit.sim.discretisation import velocity_driven_discretisations
from sloshkit.sim.metrics import free_amplitude

FloatArray = NDArray[np.float64]

#: Cases stepped together (lanes): enough independent recursions to hide the latency of the
#: multiply-adds, few enough that the state of every mode stays in the level-1 cache.
BLOCK = 64


def _compile(order: int) -> Any:
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - numba is a dependency
        return None

    lanes = BLOCK

    @njit(cache=True, fastmath={"contract"}, nogil=True)  # type: ignore[untyped-decorator]
    def kernel(breaks, coefficients, durations, sample_period_s, p, out):  # type: ignore[no-untyped-def]
        # p rows per mode: p00 p01 p10 p11 q0 q1 h0 h1 wall_factor 1/L
        modes = p.shape[0]
        pieces = breaks.size - 1
        end_tau = breaks[pieces]
        cases = durations.size
        inverse = np.empty(lanes)
        scale = np.empty(lanes)
        last = np.empty(lanes, dtype=np.int64)
        after = np.empty(lanes, dtype=np.int64)
        tau = np.empty(lanes)
        u = np.empty(lanes)
        z0 = np.zeros((modes, lanes))
        z1 = np.zeros((modes, lanes))
        theta = np.zeros((modes, lanes))
        rate = np.zeros((modes, lanes))
        peak = np.zeros(lanes)
        wall = np.zeros(lanes)
        eta = np.zeros(lanes)
        angle0 = np.zeros(lanes)
        c = np.zeros(order)
        for start in range(0, cases, lanes):
            width = min(lanes, cases - start)
            n = min(lanes, (width + 7) // 8 * 8)  # whole vectors; extra lanes repeat the last case
            for j in range(n):
                duration = durations[start + min(j, width - 1)]
                k = int((duration + 1e-12) / sample_period_s)
                while (k + 1) * sample_period_s <= duration + 1e-12:
                    k += 1
                while k * sample_period_s > duration + 1e-12:
                    k -= 1
                last[j] = k  # last sample with t <= T
                after[j] = k if k * sample_period_s >= duration - 1e-12 else k + 1
                inverse[j] = 1.0 / duration
                scale[j] = sample_period_s * inverse[j]
            steps = after[:n].max() + 1
            k_common = after[:n].min()  # before it, no lane has reached its end
            scale_hi = scale[:n].max()
            scale_lo = scale[:n].min()
            z0[:, :n] = 0.0
            z1[:, :n] = 0.0
            peak[:n] = 0.0
            wall[:n] = 0.0
            p_lo = 0
            p_hi = 0
            for k in range(steps):
                # 1. Velocity of every lane at t = k dt: the pieces p_lo..p_hi are present.
                while p_hi < pieces - 1 and k * scale_hi >= breaks[p_hi + 1]:
                    p_hi += 1
                while p_lo < pieces - 1 and k * scale_lo >= breaks[p_lo + 1]:
                    p_lo += 1
                for j in range(n):
                    tau[j] = k * scale[j]
                    u[j] = 0.0
                for piece in range(p_lo, p_hi + 1):
                    left = breaks[piece]
                    right = breaks[piece + 1] if piece < pieces - 1 else np.inf
                    for i in range(order):
                        c[i] = coefficients[i, piece]
                    for j in range(n):
                        x = tau[j] - left
                        value = c[0]
                        for i in range(1, order):
                            value = value * x + c[i]
                        inside = tau[j] >= left and tau[j] < right
                        u[j] = value if inside else u[j]
                for j in range(n):
                    u[j] = u[j] * inverse[j] if tau[j] <= end_tau else 0.0
                # 2. Step every mode; metrics by max and selects.
                if k < k_common:
                    for j in range(n):
                        eta[j] = 0.0
                    for m in range(modes):
                        p00, p01, p10, p11 = p[m, 0], p[m, 1], p[m, 2], p[m, 3]
                        q0, q1, h0, f = p[m, 4], p[m, 5], p[m, 6], p[m, 8]
                        for j in range(n):
                            a = z0[m, j]
                            b = z1[m, j]
                            angle = a + h0 * u[j]
                            eta[j] += f * angle
                            if m == 0:
                                peak[j] = max(peak[j], abs(angle))
                            z0[m, j] = p00 * a + p01 * b + q0 * u[j]
                            z1[m, j] = p10 * a + p11 * b + q1 * u[j]
                    for j in range(n):
                        wall[j] = max(wall[j], abs(eta[j]))
                else:
                    for j in range(n):
                        eta[j] = 0.0
                        angle0[j] = 0.0
                    for m in range(modes):
                        p00, p01, p10, p11 = p[m, 0], p[m, 1], p[m, 2], p[m, 3]
                        q0, q1, h0, h1, f = p[m, 4], p[m, 5], p[m, 6], p[m, 7], p[m, 8]
                        inverse_length = p[m, 9]
                        first = 1.0 if m == 0 else 0.0
                        for j in range(n):
                            a = z0[m, j]
                            b = z1[m, j]
                            angle = a + h0 * u[j]
                            eta[j] += f * angle
                            angle0[j] += first * angle
                            end_here = k == after[j]
                            theta[m, j] = angle if end_here else theta[m, j]
                            end_rate = b + h1 * u[j] - u[j] * inverse_length
                            rate[m, j] = end_rate if end_here else rate[m, j]
                            z0[m, j] = p00 * a + p01 * b + q0 * u[j]
                            z1[m, j] = p10 * a + p11 * b + q1 * u[j]
                    for j in range(n):
                        during = k <= last[j]
                        peak[j] = max(peak[j], abs(angle0[j]) if during else 0.0)
                        wall[j] = max(wall[j], abs(eta[j]) if during else 0.0)
            for j in range(width):
                case = start + j
                out[case, 0] = peak[j]
                out[case, 1] = wall[j]
                for m in range(modes):
                    out[case, 2 + 2 * m] = theta[m, j]
                    out[case, 3 + 2 * m] = rate[m, j]
                out[case, 2 + 2 * modes] = after[j] * sample_period_s - durations[case]

    return kernel


_KERNELS: dict[int, Any] = {}


def _kernel(order: int) -> Any:
    """The compiled kernel for polynomial pieces of ``order`` coefficients (False without
    numba)."""
    if order not in _KERNELS:
        _KERNELS[order] = _compile(order) or False
    return _KERNELS[order]


def kernel_rows(model: SloshModel, sample_period_s: float) -> FloatArray:
    """Per mode: Phi (4, row-major), Gamma (2), g1 (2), wall factor, 1/L of the
    first-order-hold discretisation in the shifted state
    (`sloshkit.sim.discretisation.velocity_driven_discretisations`, all modes at once).

    Parameters
    ----------
    model : SloshModel
        The modes to discretise.
    sample_period_s : float
        dt [s].

    Returns
    -------
    numpy.ndarray
        Shape (modes, 10).

    References
    ----------
    Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2.

    Examples
    --------
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> kernel_rows(model, 1e-3).shape
    (3, 10)
    """
    return kernel_rows_of([model], sample_period_s)[0]


def kernel_rows_of(models: Sequence[SloshModel], sample_period_s: float) -> list[FloatArray]:
    """`kernel_rows` of many models with one vectorised evaluation of all their exponentials
    (a sweep's fill heights).

    Parameters
    ----------
    models : sequence of SloshModel
        The models.
    sample_period_s : float
        dt [s].

    Returns
    -------
    list of numpy.ndarray
        One (modes, 10) array per model, equal to ``kernel_rows(model, dt)``.

    References
    ----------
    Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2.

    Examples
    --------
    >>> from sloshkit import UprightCylinder, get_liquid
    >>> from sloshkit.model.modal import model_family
    >>> family = model_family(UprightCylinder(0.0205), get_liquid("water-25C"))
    >>> [rows.shape for rows in kernel_rows_of([family(0.02), family(0.04)], 1e-3)]
    [(3, 10), (3, 10)]
    """
    modes = [mode for model in models for mode in model.modes]
    omega = np.array([mode.omega_rad_s for mode in modes])
    zeta = np.array([mode.damping_ratio for mode in modes])
    length = np.array([mode.length_m for mode in modes])
    phi, gamma, ramp = velocity_driven_discretisations(omega, zeta, length, sample_period_s)
    factor = np.array([mode.wall_elevation_factor_m for mode in modes])
    rows = np.column_stack((phi.reshape(-1, 4), gamma, ramp, factor, 1.0 / length))
    bounds = np.cumsum([len(model.modes) for model in models])[:-1]
    return [np.ascontiguousarray(part) for part in np.split(rows, bounds)]


def law_metrics(
    model: SloshModel,
    unit_law_velocity: Any,
    durations_s: FloatArray,
    sample_period_s: float,
    chunk_cases: int = 65536,
    rows: FloatArray | None = None,
) -> BatchMetrics:
    """Linear slosh metrics of one law time-scaled to many durations, sampling fused.

    Parameters
    ----------
    model : SloshModel
        Shared by every case.
    unit_law_velocity : scipy.interpolate.PPoly
        v_1(tau) of the law moved in T = 1 s, on [0, 1] (e.g.
        ``unit_duration_shape(motion).derivative_pp(1)``).
    durations_s : array of float
        Move duration T of each case [s].
    sample_period_s : float
        dt [s].
    chunk_cases : int
        Cases per call of the kernel (bounds the temporary memory).
    rows : numpy.ndarray, optional
        ``kernel_rows(model, sample_period_s)`` when already computed (`kernel_rows_of`).

    Returns
    -------
    BatchMetrics
        Equal to ``batch_metrics(model, scaled_velocity_samples(...), durations, dt)``.

    References
    ----------
    Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.motion import make_law
    >>> from sloshkit.motion.scaling import unit_duration_shape
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> shape = unit_duration_shape(make_law("quintic", 0.5, duration_s=1.0))
    >>> metrics = law_metrics(model, shape.derivative_pp(1), np.array([1.5, 2.0]), 1e-3)
    >>> bool(metrics.peak_angle_rad[0] > metrics.peak_angle_rad[1])
    True
    """
    durations = np.ascontiguousarray(durations_s, dtype=float)
    if durations.ndim != 1 or not np.all((durations > 0) & np.isfinite(durations)):
        raise InputError("durations", durations.shape, "must be positive and finite, one per case")
    given = np.asarray(unit_law_velocity.c, dtype=float)
    order = -(-given.shape[0] // 4) * 4  # leading zeros up to a multiple of 4
    kernel = _kernel(order)
    if not kernel:
        return _through_arrays(model, unit_law_velocity, durations, sample_period_s, chunk_cases)
    modes = len(model.modes)
    if rows is None:
        rows = kernel_rows(model, sample_period_s)
    breaks = np.ascontiguousarray(unit_law_velocity.x, dtype=float)
    coefficients = np.zeros((order, given.shape[1]))
    coefficients[order - given.shape[0] :] = given
    # Sorted by duration, the cases of a block end their moves together (short masked tail).
    order = np.argsort(durations, kind="stable")
    durations = durations[order]
    out = np.empty((durations.size, 3 + 2 * modes))
    for start in range(0, durations.size, chunk_cases):
        stop = min(durations.size, start + chunk_cases)
        kernel(
            breaks,
            coefficients,
            durations[start:stop],
            float(sample_period_s),
            rows,
            out[start:stop],
        )
    unsorted = np.empty_like(out)
    unsorted[order] = out
    out = unsorted
    lag = out[:, 2 + 2 * modes]
    residual = np.zeros((len(model.modes), durations.size))
    for row, mode in enumerate(model.modes):
        amplitude = free_amplitude(
            out[:, 2 + 2 * row], out[:, 3 + 2 * row], mode.omega_rad_s, mode.damping_ratio
        )
        residual[row] = amplitude * np.exp(mode.damping_ratio * mode.omega_rad_s * lag)
    factor = np.array([mode.wall_elevation_factor_m for mode in model.modes])
    return BatchMetrics(
        peak_angle_rad=out[:, 0].copy(),
        residual_angle_rad=residual[0],
        peak_wall_elevation_m=out[:, 1].copy(),
        residual_wall_elevation_m=factor @ residual,
    )


def _through_arrays(
    model: SloshModel,
    unit_law_velocity: Any,
    durations: FloatArray,
    sample_period_s: float,
    chunk_cases: int,
) -> BatchMetrics:
    """The same metrics by sampling into arrays (chunks of cases) and `batch_metrics`."""
    from sloshkit.motion.sampling import steps_for
    from sloshkit.motion.scaling import scaled_velocity_samples
    from sloshkit.sim.batch import batch_metrics

    parts = []
    step = max(1, min(chunk_cases, 4096))
    for start in range(0, durations.size, step):
        block = durations[start : start + step]
        velocity = scaled_velocity_samples(
            unit_law_velocity,
            block,
            sample_period_s,
            steps_for(float(block.max()), sample_period_s),
        )
        parts.append(batch_metrics(model, velocity, block, sample_period_s))
    return BatchMetrics(
        *(
            np.concatenate([getattr(p, name) for p in parts])
            for name in BatchMetrics.__dataclass_fields__
        )
    )
