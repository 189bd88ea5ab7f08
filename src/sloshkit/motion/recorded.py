"""Motions from recorded samples (position or acceleration), interpolated by splines."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from sloshkit.errors import InputError, require_increasing
from sloshkit.motion.profile import Motion, PiecewisePolynomial


def from_samples(
    time_s: ArrayLike,
    position_m: ArrayLike | None = None,
    acceleration_m_s2: ArrayLike | None = None,
    name: str = "user",
) -> Motion:
    """A user motion from samples of position or of acceleration (times strictly increasing).

    - position: interpolating quintic spline with zero velocity and acceleration at both ends (the
      move is rest to rest), differentiated analytically; give smooth, well-sampled data, since
      differentiation amplifies noise.
    - acceleration: interpolating cubic spline (not-a-knot), integrated analytically from rest;
      the distance is what the integral gives.

    Time is shifted to start at 0.

    Parameters
    ----------
    time_s : array_like
        Sample times [s], strictly increasing.
    position_m : array_like, optional
        Position samples [m] (give these or ``acceleration_m_s2``).
    acceleration_m_s2 : array_like, optional
        Acceleration samples [m/s^2].
    name : str
        Name of the motion.

    Returns
    -------
    Motion
        The interpolated motion.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit import from_samples, quintic
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> law = from_samples(t, position_m=quintic(0.1, 1.0).position(t))
    >>> round(law.distance_m, 9)
    0.1
    """
    from scipy.interpolate import CubicSpline, PPoly, make_interp_spline  # slow: only here

    t = np.asarray(time_s, dtype=float)
    if (position_m is None) == (acceleration_m_s2 is None):
        raise InputError("motion samples", "both/none", "give either position or acceleration")
    values = np.asarray(position_m if position_m is not None else acceleration_m_s2, dtype=float)
    if t.ndim != 1 or values.shape != t.shape:
        raise InputError("motion samples", f"{t.shape} vs {values.shape}", "need equal 1-D lengths")
    minimum = 6 if position_m is not None else 4
    if t.size < minimum:
        raise InputError("motion samples", t.size, f"need at least {minimum} samples")
    bad = ~np.isfinite(t) | ~np.isfinite(values)
    if bad.any():
        row = int(np.argmax(bad))
        raise InputError("motion samples", f"row {row}", "time and values must be finite (NaN?)")
    require_increasing("time", t)
    t = t - t[0]
    if position_m is not None:
        spline = make_interp_spline(
            t, values - values[0], k=5, bc_type=([(1, 0.0), (2, 0.0)], [(1, 0.0), (2, 0.0)])
        )
        pp = PPoly.from_spline(spline)
    else:
        pp = CubicSpline(t, values).antiderivative(2)
    # Trim the spline's padding pieces to [0, T].
    return Motion(name, PiecewisePolynomial(pp.c, pp.x))
