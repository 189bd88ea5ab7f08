"""Fast path: slosh metrics of very many linear cases at once.

Cases that share one `SloshModel` (one container, liquid and fill height) and one sample period
are run together. Each case is a sampled container velocity (time-major array, one column per
case) and a move duration. The first-order-hold discretisation of `sloshkit.sim.discretisation` is
stepped for every mode and case in one compiled loop (numba) that keeps only the metrics: no
time history is stored, and the loop over cases is innermost so that it vectorises. Without
numba the same recursion runs through `scipy.signal.lfilter` (slower, same numbers to
rounding). Only floating-point contraction (fused multiply-add) is allowed to the compiler.

The metrics equal those of `sloshkit.sim.simulate.simulate(..., kind="linear")` for the same motion
and sample period: peak |theta_1| and peak |wall elevation| over the samples t <= T, residual
amplitudes from the state at the first sample t >= T, scaled back to T.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel
from sloshkit.sim.discretisation import linear_mode_response, velocity_driven_discretisation
from sloshkit.sim.metrics import free_amplitude

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class BatchMetrics:
    """Per-case slosh metrics (SI): arrays of shape (cases,).

    Parameters
    ----------
    peak_angle_rad : numpy.ndarray
        Peak |theta_1| over the samples t <= T [rad].
    residual_angle_rad : numpy.ndarray
        Residual first-mode amplitude after the move, at T [rad].
    peak_wall_elevation_m : numpy.ndarray
        Peak |wall elevation| (all modes) over the samples t <= T [m].
    residual_wall_elevation_m : numpy.ndarray
        Sum over the modes of their residual wall amplitudes [m].

    Examples
    --------
    >>> import numpy as np
    >>> metrics = BatchMetrics(*(np.zeros(2) for _ in range(4)))
    >>> metrics.peak_angle_rad.shape
    (2,)
    """

    peak_angle_rad: FloatArray
    residual_angle_rad: FloatArray
    peak_wall_elevation_m: FloatArray
    residual_wall_elevation_m: FloatArray


def _compile_kernel() -> Any:
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - numba is a dependency, but optional at run time
        return None

    @njit(cache=True, fastmath={"contract"})  # type: ignore[untyped-decorator]
    def kernel(velocity, last_move, first_after, phi, gamma, g1, factor):  # type: ignore[no-untyped-def]
        steps, cases = velocity.shape
        modes = phi.shape[0]
        z0 = np.zeros((modes, cases))
        z1 = np.zeros((modes, cases))
        eta = np.zeros(cases)
        peak_angle = np.zeros(cases)
        peak_wall = np.zeros(cases)
        end_state = np.zeros((modes, 2, cases))
        for k in range(steps):
            for c in range(cases):
                eta[c] = 0.0
            for m in range(modes):
                p00, p01, p10, p11 = phi[m, 0, 0], phi[m, 0, 1], phi[m, 1, 0], phi[m, 1, 1]
                q0, q1, h0, h1, f = gamma[m, 0], gamma[m, 1], g1[m, 0], g1[m, 1], factor[m]
                for c in range(cases):
                    u = velocity[k, c]
                    a = z0[m, c]
                    b = z1[m, c]
                    theta = a + h0 * u
                    eta[c] += f * theta
                    if m == 0 and k <= last_move[c]:
                        peak_angle[c] = max(peak_angle[c], abs(theta))
                    if k == first_after[c]:
                        end_state[m, 0, c] = theta
                        end_state[m, 1, c] = b + h1 * u
                    z0[m, c] = p00 * a + p01 * b + q0 * u
                    z1[m, c] = p10 * a + p11 * b + q1 * u
            for c in range(cases):
                if k <= last_move[c]:
                    peak_wall[c] = max(peak_wall[c], abs(eta[c]))
        return peak_angle, peak_wall, end_state

    return kernel


_KERNEL: Any = None


def _kernel() -> Any:
    global _KERNEL
    if _KERNEL is None:
        _KERNEL = _compile_kernel() or False
    return _KERNEL


def move_indices(
    move_durations_s: FloatArray, sample_period_s: float, steps: int
) -> tuple[IntArray, IntArray]:
    """(last sample with t <= T, first sample with t >= T) per case on the grid k dt, with
    the tolerances of `sloshkit.sim.simulate.simulate` (1e-12 s).

    Parameters
    ----------
    move_durations_s : numpy.ndarray
        Move duration T of each case [s].
    sample_period_s : float
        dt [s].
    steps : int
        Samples of the grid (the first sample after T is clipped to the last one).

    Returns
    -------
    tuple of numpy.ndarray
        (last_move, first_after), integer sample indices per case.

    Examples
    --------
    >>> import numpy as np
    >>> [a.tolist() for a in move_indices(np.array([0.5, 0.35]), 0.1, 10)]
    [[5, 3], [5, 4]]
    """
    time = np.arange(steps, dtype=float) * sample_period_s
    last_move = np.searchsorted(time, move_durations_s + 1e-12, side="right") - 1
    first_after = np.minimum(np.searchsorted(time, move_durations_s - 1e-12), steps - 1)
    return last_move.astype(np.int64), first_after.astype(np.int64)


def batch_metrics(
    model: SloshModel,
    velocity_m_s: FloatArray,
    move_durations_s: FloatArray,
    sample_period_s: float,
    use_numba: bool = True,
) -> BatchMetrics:
    """Linear slosh metrics for many cases sharing ``model``.

    Parameters
    ----------
    model : SloshModel
        Shared by every case.
    velocity_m_s : numpy.ndarray
        Container velocity, shape (samples, cases), time-major, sampled at t_k = k dt from
        rest; zero after each case's move. Must cover the first sample t >= T of the longest
        move.
    move_durations_s : numpy.ndarray
        Move duration T of each case [s], shape (cases,).
    sample_period_s : float
        dt [s].
    use_numba : bool
        Use the compiled kernel when numba is installed (else `scipy.signal.lfilter`).

    Returns
    -------
    BatchMetrics
        The metrics of every case, equal to those of ``simulate(..., kind="linear")``.

    References
    ----------
    Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(0.0, 1.201, 1e-3)
    >>> velocity = np.where(t <= 1.0, 0.3 * np.sin(np.pi * t) ** 2, 0.0)[:, None]
    >>> metrics = batch_metrics(model, velocity, np.array([1.0]), 1e-3)
    >>> bool(0.0 < metrics.residual_angle_rad[0] < metrics.peak_angle_rad[0])
    True
    """
    velocity = np.ascontiguousarray(velocity_m_s, dtype=float)
    durations = np.asarray(move_durations_s, dtype=float)
    if velocity.ndim != 2 or durations.shape != (velocity.shape[1],):
        raise InputError(
            "velocity", velocity.shape, "must be (samples, cases) with one duration per case"
        )
    steps = velocity.shape[0]
    if durations.size and durations.max() > (steps - 1) * sample_period_s + 1e-12:
        raise InputError("velocity", steps, "too few samples to reach the end of every move")
    last_move, first_after = move_indices(durations, sample_period_s, steps)
    modes = model.modes
    factor = np.array([mode.wall_elevation_factor_m for mode in modes])
    kernel = _kernel() if use_numba else None
    if kernel:
        discretisations = [
            velocity_driven_discretisation(
                mode.omega_rad_s, mode.damping_ratio, mode.length_m, sample_period_s
            )
            for mode in modes
        ]
        phi = np.array([d[0] for d in discretisations])
        gamma = np.array([d[1] for d in discretisations])
        g1 = np.array([d[2] for d in discretisations])
        peak_angle, peak_wall, end_state = kernel(
            velocity, last_move, first_after, phi, gamma, g1, factor
        )
        end_angle, end_rate = end_state[:, 0, :], end_state[:, 1, :]
        end_velocity = velocity[first_after, np.arange(durations.size)]
        end_rate = end_rate - end_velocity[None, :] / np.array([m.length_m for m in modes])[:, None]
    else:
        peak_angle, peak_wall, end_angle, end_rate = _lfilter_metrics(
            model, velocity, last_move, first_after, factor, sample_period_s
        )
    lag = first_after * sample_period_s - durations
    residual = np.empty((len(modes), durations.size))
    for row, mode in enumerate(modes):
        amplitude = free_amplitude(
            end_angle[row], end_rate[row], mode.omega_rad_s, mode.damping_ratio
        )
        residual[row] = amplitude * np.exp(mode.damping_ratio * mode.omega_rad_s * lag)
    return BatchMetrics(
        peak_angle_rad=np.asarray(peak_angle, dtype=float),
        residual_angle_rad=residual[0],
        peak_wall_elevation_m=np.asarray(peak_wall, dtype=float),
        residual_wall_elevation_m=factor @ residual,
    )


def _lfilter_metrics(
    model: SloshModel,
    velocity: FloatArray,
    last_move: IntArray,
    first_after: IntArray,
    factor: FloatArray,
    sample_period_s: float,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    cases_first = velocity.T
    steps = velocity.shape[0]
    during = np.arange(steps)[None, :] <= last_move[:, None]
    columns = np.arange(cases_first.shape[0])
    wall = np.zeros_like(cases_first)
    end_angle = np.empty((len(model.modes), columns.size))
    end_rate = np.empty_like(end_angle)
    peak_angle = np.zeros(columns.size)
    for row, mode in enumerate(model.modes):
        theta, rate = linear_mode_response(
            cases_first, sample_period_s, mode.omega_rad_s, mode.damping_ratio, mode.length_m
        )
        if row == 0:
            peak_angle = np.max(np.where(during, np.abs(theta), 0.0), axis=1)
        wall += factor[row] * theta
        end_angle[row] = theta[columns, first_after]
        end_rate[row] = rate[columns, first_after]
    peak_wall = np.max(np.where(during, np.abs(wall), 0.0), axis=1)
    return peak_angle, peak_wall, end_angle, end_rate
