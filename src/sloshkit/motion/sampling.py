"""Sampling of motions on a controller grid t_k = k Ts (the one place of the grid rule).

Every sampled grid in sloshkit starts at t = 0 with a uniform step and uses the same count of
steps to reach a duration T: ``ceil(T / Ts - 1e-9)`` (the 1e-9 keeps T = k Ts from adding a
sample to floating-point rounding).
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sloshkit.errors import require_positive

FloatArray = NDArray[np.float64]


class _Law(Protocol):
    """What sampling reads of a motion (`sloshkit.motion.profile.Motion` is one): its duration
    and its derivatives at given times. Written as a protocol so that this module, which
    `Motion.sample` uses, does not import the motion's module back."""

    @property
    def duration_s(self) -> float: ...

    def position(self, time_s: ArrayLike) -> FloatArray: ...

    def velocity(self, time_s: ArrayLike) -> FloatArray: ...

    def acceleration(self, time_s: ArrayLike) -> FloatArray: ...

    def jerk(self, time_s: ArrayLike) -> FloatArray: ...


def steps_to_reach(duration_s: float, sample_period_s: float) -> int:
    """Number of steps k such that k Ts is the first grid time at or after ``duration_s``.

    Parameters
    ----------
    duration_s : float
        Duration T to reach [s].
    sample_period_s : float
        Grid step Ts [s].

    Returns
    -------
    int
        ``ceil(T / Ts - 1e-9)``.

    Examples
    --------
    >>> steps_to_reach(1.0, 0.1), steps_to_reach(1.05, 0.1)
    (10, 11)
    """
    return math.ceil(duration_s / sample_period_s - 1e-9)


def sample_times(duration_s: float, sample_period_s: float) -> FloatArray:
    """0, Ts, 2 Ts, ... up to and including ``duration_s`` (the last step may be shorter).

    Parameters
    ----------
    duration_s : float
        Duration T [s].
    sample_period_s : float
        Step Ts [s].

    Returns
    -------
    numpy.ndarray
        The times [s], the last exactly T.

    Examples
    --------
    >>> sample_times(0.25, 0.1).tolist()
    [0.0, 0.1, 0.2, 0.25]
    """
    count = _checked_steps(duration_s, sample_period_s)
    t = np.arange(count + 1, dtype=float) * sample_period_s
    t[-1] = duration_s
    return t


def _checked_steps(duration_s: float, sample_period_s: float) -> int:
    """`steps_to_reach`, after checking that the five sampled columns fit in memory."""
    from sloshkit.budget import require_samples

    samples = duration_s / sample_period_s if sample_period_s > 0.0 else math.inf
    require_samples(
        "sample_period", f"{sample_period_s:.3g} s for {duration_s:.3g} s", samples + 1.0, 5
    )
    return steps_to_reach(duration_s, sample_period_s)


def sample_motion(motion: _Law, sample_period_s: float) -> dict[str, FloatArray]:
    """Samples of a motion at t = 0, Ts, 2 Ts, ..., with the last sample exactly at T.

    Parameters
    ----------
    motion : Motion
        The motion.
    sample_period_s : float
        Step Ts [s].

    Returns
    -------
    dict of numpy.ndarray
        ``t_s``, ``position_m``, ``velocity_m_s``, ``acceleration_m_s2``, ``jerk_m_s3``.

    Examples
    --------
    >>> from sloshkit import quintic
    >>> samples = sample_motion(quintic(0.1, 1.0), 0.25)
    >>> [round(float(x), 6) for x in samples["position_m"]]
    [0.0, 0.010352, 0.05, 0.089648, 0.1]
    """
    dt = require_positive("sample_period", sample_period_s, "s")
    t = sample_times(motion.duration_s, dt)
    return {
        "t_s": t,
        "position_m": motion.position(t),
        "velocity_m_s": motion.velocity(t),
        "acceleration_m_s2": motion.acceleration(t),
        "jerk_m_s3": motion.jerk(t),
    }


def export_samples(motion: _Law, sample_period_s: float) -> dict[str, FloatArray]:
    """Controller samples: t = k Ts from 0 until the first sample at or after T, at rest on the
    target from T on.

    Parameters
    ----------
    motion : Motion
        The motion.
    sample_period_s : float
        Controller period Ts [s].

    Returns
    -------
    dict of numpy.ndarray
        ``t_s``, ``position_m``, ``velocity_m_s``, ``acceleration_m_s2``, ``jerk_m_s3``.

    Examples
    --------
    >>> from sloshkit import quintic
    >>> export_samples(quintic(0.1, 1.0), 0.3)["t_s"].tolist()
    [0.0, 0.3, 0.6, 0.8999999999999999, 1.2]
    """
    count = _checked_steps(motion.duration_s, sample_period_s)
    t = np.arange(count + 1, dtype=float) * sample_period_s
    jerk = motion.jerk(t)
    jerk[t >= motion.duration_s - 1e-12] = 0.0
    return {
        "t_s": t,
        "position_m": motion.position(t),
        "velocity_m_s": motion.velocity(t),
        "acceleration_m_s2": motion.acceleration(t),
        "jerk_m_s3": jerk,
    }


def steps_for(max_duration_s: float, sample_period_s: float) -> int:
    """Samples on the grid k Ts that reach the first sample t >= T of the longest move.

    Parameters
    ----------
    max_duration_s : float
        Longest move duration [s].
    sample_period_s : float
        Step Ts [s].

    Returns
    -------
    int
        `steps_to_reach` + 2.

    Examples
    --------
    >>> steps_for(1.0, 0.1)
    12
    """
    return steps_to_reach(max_duration_s, sample_period_s) + 2
