"""Time scaling of rest-to-rest laws: a law of shape s_1(tau) on [0, 1] moved in time T."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import PPoly

from sloshkit.motion.profile import Motion

FloatArray = NDArray[np.float64]


def _compile_sampler() -> Any:
    try:
        from numba import njit
    except ImportError:  # pragma: no cover
        return None

    @njit(cache=True, fastmath=True)  # type: ignore[untyped-decorator]
    def sampler(breaks, coefficients, durations, sample_period, steps):  # type: ignore[no-untyped-def]
        cases = durations.size
        pieces = breaks.size - 1
        order = coefficients.shape[0]
        out = np.zeros((steps, cases))
        piece = np.zeros(cases, dtype=np.int64)
        inverse = 1.0 / durations
        for k in range(steps):
            for c in range(cases):
                tau = k * sample_period * inverse[c]
                if tau > breaks[pieces]:
                    continue
                p = piece[c]
                while p < pieces - 1 and tau >= breaks[p + 1]:
                    p += 1
                piece[c] = p
                x = tau - breaks[p]
                value = 0.0
                for j in range(order):
                    value = value * x + coefficients[j, p]
                out[k, c] = value * inverse[c]
        return out

    return sampler


_SAMPLER: Any = None


def scaled_velocity_samples(
    unit_law_velocity: Any, durations_s: FloatArray, sample_period_s: float, steps: int
) -> FloatArray:
    """Velocity samples (steps, cases) of a law time-scaled to each duration.

    A rest-to-rest law of shape s_1(tau) on [0, 1] moved in time T has v_T(t) = v_1(t/T) / T.
    Compiled with numba when available (same values as evaluating the `PPoly`).

    Parameters
    ----------
    unit_law_velocity : scipy.interpolate.PPoly
        v_1 on [0, 1], zero outside it.
    durations_s : numpy.ndarray
        Durations T, one per case [s].
    sample_period_s : float
        Step Ts [s].
    steps : int
        Number of samples.

    Returns
    -------
    numpy.ndarray
        Velocities [m/s], shape (steps, cases).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit import quintic
    >>> unit = unit_duration_shape(quintic(0.1, 2.0)).derivative_pp(1)
    >>> v = scaled_velocity_samples(unit, np.array([1.0, 2.0]), 0.5, 5)
    >>> [round(float(x), 6) for x in v[1]]
    [0.1875, 0.052734]
    """
    global _SAMPLER
    durations = np.asarray(durations_s, dtype=float)
    if _SAMPLER is None:
        _SAMPLER = _compile_sampler() or False
    if _SAMPLER:
        return np.asarray(
            _SAMPLER(
                np.asarray(unit_law_velocity.x, dtype=float),
                np.ascontiguousarray(unit_law_velocity.c, dtype=float),
                durations,
                float(sample_period_s),
                int(steps),
            ),
            dtype=float,
        )
    time = np.arange(steps, dtype=float)[:, None] * sample_period_s
    tau = time / durations[None, :]
    inside = tau <= 1.0
    values = np.zeros((steps, durations.size))
    values[inside] = unit_law_velocity(tau[inside])
    return np.asarray(values / durations[None, :], dtype=float)


def unit_duration_shape(motion: Motion) -> Motion:
    """The same law stretched in time to T = 1 s (same distance): s_1(tau) = s(tau T).

    Parameters
    ----------
    motion : Motion
        A rest-to-rest law.

    Returns
    -------
    Motion
        Its shape on [0, 1] s.

    Examples
    --------
    >>> from sloshkit import septic
    >>> unit_duration_shape(septic(0.1, 3.0)).duration_s
    1.0
    """
    pp = motion.position_pp
    scale = motion.duration_s
    order = pp.c.shape[0] - 1
    powers = scale ** np.arange(order, -1, -1, dtype=float)  # c_i multiplies (t - x)^(order-i)
    return Motion(motion.name, PPoly(pp.c * powers[:, None], pp.x / scale))
