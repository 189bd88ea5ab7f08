"""Time scaling of rest-to-rest laws: a law of shape s_1(tau) on [0, 1] moved in time T."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.profile import Motion, PiecewisePolynomial

FloatArray = NDArray[np.float64]


def scaled_velocity_samples(
    unit_law_velocity: Any, durations_s: FloatArray, sample_period_s: float, steps: int
) -> FloatArray:
    """Velocity samples (steps, cases) of a law time-scaled to each duration.

    A rest-to-rest law of shape s_1(tau) on [0, 1] moved in time T has v_T(t) = v_1(t/T) / T,
    zero for tau = t/T beyond the last breakpoint. Each piece is evaluated in Horner form at
    every sample of every case at once (plain numpy: compiling a loop would cost more time to
    load than it saves here).

    Parameters
    ----------
    unit_law_velocity : PiecewisePolynomial or scipy.interpolate.PPoly
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
    breaks = np.asarray(unit_law_velocity.x, dtype=float)
    coefficients = np.asarray(unit_law_velocity.c, dtype=float)
    inverse = 1.0 / np.asarray(durations_s, dtype=float)
    tau = (np.arange(steps, dtype=float) * float(sample_period_s))[:, None] * inverse[None, :]
    pieces = breaks.size - 1
    if pieces == 1:
        local = tau - breaks[0]
        value = np.full_like(tau, coefficients[0, 0])
        for row in coefficients[1:, 0]:
            value = value * local + row
    else:
        piece = np.clip(np.searchsorted(breaks, tau, side="right") - 1, 0, pieces - 1)
        local = tau - breaks[piece]
        value = coefficients[0, piece]
        for row in coefficients[1:]:
            value = value * local + row[piece]
    return np.where(tau <= breaks[-1], value * inverse[None, :], 0.0)


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
    return Motion(motion.name, PiecewisePolynomial(pp.c * powers[:, None], pp.x / scale))
