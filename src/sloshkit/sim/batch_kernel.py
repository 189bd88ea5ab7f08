"""Fused fast path: time-scaled laws sampled inside the kernel, one case at a time.

For a rest-to-rest law of shape s_1(tau) moved in time T, the velocity at t_k = k dt is
v_1(k dt / T) / T (`sloshkit.motion.scaling`). The kernel evaluates it where it is needed and
steps the exact first-order-hold discretisation of every mode
(`sloshkit.sim.discretisation.velocity_driven_discretisation`; Franklin, Powell & Workman,
*Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2) with the state of each mode in
registers: no velocity array, no time history, memory O(cases). The loop over samples has no
data-dependent branch: it runs to the first sample at or after T, the last of which is peeled.

The metrics are those of `sloshkit.sim.batch.batch_metrics` for the same velocity samples
(peak |theta_1| and peak |wall elevation| over the samples t <= T, residual amplitudes from the
state at the first sample t >= T scaled back to T).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel
from sloshkit.sim.batch import BatchMetrics
from sloshkit.sim.discretisation import velocity_driven_discretisations
from sloshkit.sim.metrics import free_amplitude

FloatArray = NDArray[np.float64]

#: Cases stepped together: their states stay in a few vector registers and the velocity
#: samples of a block fit in the level-2 cache.
BLOCK = 64


def _compile() -> Any:
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - numba is a dependency
        return None

    block = BLOCK

    @njit(cache=True, fastmath=True, nogil=True)  # type: ignore[untyped-decorator]
    def kernel(breaks, coefficients, durations, sample_period_s, p, out):  # type: ignore[no-untyped-def]
        # p rows per mode: p00 p01 p10 p11 q0 q1 h0 h1 wall_factor 1/L
        modes = p.shape[0]
        pieces = breaks.size - 1
        order = coefficients.shape[0]
        cases = durations.size
        last_move = np.empty(cases, dtype=np.int64)
        first_after = np.empty(cases, dtype=np.int64)
        for c in range(cases):
            duration = durations[c]
            k = int((duration + 1e-12) / sample_period_s)
            while (k + 1) * sample_period_s <= duration + 1e-12:
                k += 1
            while k * sample_period_s > duration + 1e-12:
                k -= 1
            last_move[c] = k
            first_after[c] = k if k * sample_period_s >= duration - 1e-12 else k + 1
        steps = int(first_after.max()) + 1 if cases else 0
        velocity = np.zeros((steps, block))
        z0 = np.zeros((modes, block))
        z1 = np.zeros((modes, block))
        theta = np.zeros((modes, block))
        rate = np.zeros((modes, block))
        last = np.zeros(block, dtype=np.int64)
        after = np.zeros(block, dtype=np.int64)
        peak = np.zeros(block)
        wall = np.zeros(block)
        eta = np.zeros(block)
        angle0 = np.zeros(block)
        for start in range(0, cases, block):
            width = min(block, cases - start)
            # 1. Sample the block's velocities, piece by piece (vectorised over samples).
            velocity[:, :] = 0.0
            for j in range(width):
                c = start + j
                inverse = 1.0 / durations[c]
                scale = sample_period_s * inverse
                k_stop = first_after[c] + 1
                k = 0
                for piece in range(pieces):
                    upper = breaks[piece + 1]
                    # samples with tau < the next break (the last piece includes tau = 1)
                    end = min(k_stop, max(k, int(upper / scale) - 1))
                    while end < k_stop and (
                        end * scale < upper or (piece == pieces - 1 and end * scale <= upper)
                    ):
                        end += 1
                    left = breaks[piece]
                    for kk in range(k, end):
                        x = kk * scale - left
                        value = 0.0
                        for i in range(order):
                            value = value * x + coefficients[i, piece]
                        velocity[kk, j] = value * inverse
                    k = end
            # 2. Step every mode of the block's cases together (branch-free selects).
            z0[:, :] = 0.0
            z1[:, :] = 0.0
            peak[:] = 0.0
            wall[:] = 0.0
            block_steps = int(first_after[start : start + width].max()) + 1
            last[:] = -1
            after[:] = -1
            last[:width] = last_move[start : start + width]
            after[:width] = first_after[start : start + width]
            # Before the first end of the block's moves every case is moving: no selects.
            k_common = int(first_after[start : start + width].min())
            for k in range(k_common):
                p00, p01, p10, p11 = p[0, 0], p[0, 1], p[0, 2], p[0, 3]
                q0, q1, h0, f = p[0, 4], p[0, 5], p[0, 6], p[0, 8]
                for j in range(block):
                    u = velocity[k, j]
                    a = z0[0, j]
                    b = z1[0, j]
                    angle = a + h0 * u
                    eta[j] = f * angle
                    peak[j] = max(peak[j], abs(angle))
                    z0[0, j] = p00 * a + p01 * b + q0 * u
                    z1[0, j] = p10 * a + p11 * b + q1 * u
                for m in range(1, modes):
                    p00, p01, p10, p11 = p[m, 0], p[m, 1], p[m, 2], p[m, 3]
                    q0, q1, h0, f = p[m, 4], p[m, 5], p[m, 6], p[m, 8]
                    for j in range(block):
                        u = velocity[k, j]
                        a = z0[m, j]
                        b = z1[m, j]
                        eta[j] += f * (a + h0 * u)
                        z0[m, j] = p00 * a + p01 * b + q0 * u
                        z1[m, j] = p10 * a + p11 * b + q1 * u
                for j in range(block):
                    wall[j] = max(wall[j], abs(eta[j]))
            for k in range(k_common, block_steps):
                for j in range(block):
                    eta[j] = 0.0
                    angle0[j] = 0.0
                for m in range(modes):
                    p00, p01, p10, p11 = p[m, 0], p[m, 1], p[m, 2], p[m, 3]
                    q0, q1, h0, h1, f = p[m, 4], p[m, 5], p[m, 6], p[m, 7], p[m, 8]
                    inverse_length = p[m, 9]
                    first = 1.0 if m == 0 else 0.0
                    for j in range(block):
                        u = velocity[k, j]
                        a = z0[m, j]
                        b = z1[m, j]
                        angle = a + h0 * u
                        eta[j] += f * angle
                        angle0[j] += first * angle
                        end_here = k == after[j]
                        theta[m, j] = angle if end_here else theta[m, j]
                        rate[m, j] = b + h1 * u - u * inverse_length if end_here else rate[m, j]
                        z0[m, j] = p00 * a + p01 * b + q0 * u
                        z1[m, j] = p10 * a + p11 * b + q1 * u
                for j in range(block):
                    during = k <= last[j]
                    peak[j] = max(peak[j], abs(angle0[j]) if during else 0.0)
                    wall[j] = max(wall[j], abs(eta[j]) if during else 0.0)
            for j in range(width):
                c = start + j
                out[c, 0] = peak[j]
                out[c, 1] = wall[j]
                for m in range(modes):
                    out[c, 2 + 2 * m] = theta[m, j]
                    out[c, 3 + 2 * m] = rate[m, j]
                out[c, 2 + 2 * modes] = first_after[c] * sample_period_s - durations[c]

    return kernel


_KERNEL: Any = None


def _kernel() -> Any:
    global _KERNEL
    if _KERNEL is None:
        _KERNEL = _compile() or False
    return _KERNEL


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
    omega = np.array([mode.omega_rad_s for mode in model.modes])
    zeta = np.array([mode.damping_ratio for mode in model.modes])
    length = np.array([mode.length_m for mode in model.modes])
    phi, gamma, ramp = velocity_driven_discretisations(omega, zeta, length, sample_period_s)
    factor = np.array([mode.wall_elevation_factor_m for mode in model.modes])
    return np.column_stack((phi.reshape(-1, 4), gamma, ramp, factor, 1.0 / length))


def law_metrics(
    model: SloshModel,
    unit_law_velocity: Any,
    durations_s: FloatArray,
    sample_period_s: float,
    chunk_cases: int = 65536,
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
    if durations.ndim != 1 or not np.all(durations > 0):
        raise InputError("durations", durations.shape, "must be positive, one per case")
    kernel = _kernel()
    if not kernel:
        return _through_arrays(model, unit_law_velocity, durations, sample_period_s, chunk_cases)
    modes = len(model.modes)
    rows = kernel_rows(model, sample_period_s)
    breaks = np.ascontiguousarray(unit_law_velocity.x, dtype=float)
    coefficients = np.ascontiguousarray(unit_law_velocity.c, dtype=float)
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
