"""Timings s(t) of a path: the `Timing` object and the two filters of the timing family.

`box_smoothed` averages a timing over a sliding window (a box FIR filter: acceleration jumps
become jerk-limited ramps; Biagiotti & Melchiorri, *Trajectory Planning for Automatic Machines
and Robots*, Springer (2008) ch. 4); `shaped_timing` convolves it with an input shaper's
impulses (Singer & Seering, ASME J. Dyn. Syst. Meas. Control 112 (1990) 76-82,
doi:10.1115/1.2894142). Both change the timing, never the path's geometry. The family built
from them is in `sloshkit.plan.path.retime`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from sloshkit.errors import InputError
from sloshkit.motion.shaping import Shaper

FloatArray = NDArray[np.float64]
#: Resolution of the fine time grid the composed timings are tabulated on [s].
FINE_STEP_S = 5e-4


@dataclass(frozen=True, eq=False)
class Timing:
    """A rest-to-rest timing s(t) [m] of a path on [0, ``duration_s``], tabulated on a fine grid
    and interpolated by a cubic spline (held at 0 before and at ``length_m`` after).

    Parameters
    ----------
    name : str
        Label.
    time_s : ndarray
        Increasing times from 0 [s].
    s_m : ndarray
        Path parameter at those times [m].

    Examples
    --------
    >>> timing = Timing.from_samples("ramp", np.linspace(0, 1, 11), np.linspace(0, 1, 11) ** 2)
    >>> round(float(timing.position(0.5)), 3), timing.duration_s
    (0.25, 1.0)
    """

    name: str
    time_s: FloatArray
    s_m: FloatArray

    @classmethod
    def from_samples(cls, name: str, time_s: ArrayLike, s_m: ArrayLike) -> Timing:
        """A timing through the samples (times increasing from 0)."""
        t = np.asarray(time_s, dtype=float)
        s = np.asarray(s_m, dtype=float)
        if t.ndim != 1 or t.size < 2 or t[0] != 0.0 or np.any(np.diff(t) <= 0):
            raise InputError("timing", t.size, "needs increasing times from 0")
        return cls(name, t, s)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_spline", CubicSpline(self.time_s, self.s_m))

    @property
    def duration_s(self) -> float:
        """Duration T [s]."""
        return float(self.time_s[-1])

    @property
    def length_m(self) -> float:
        """Final s [m]."""
        return float(self.s_m[-1])

    def position(self, time_s: ArrayLike) -> FloatArray:
        """s(t) [m]."""
        spline: CubicSpline = self._spline  # type: ignore[attr-defined]
        t = np.asarray(time_s, dtype=float)
        inside = np.asarray(spline(np.clip(t, 0.0, self.duration_s)), dtype=float)
        return np.where(t <= 0.0, 0.0, np.where(t >= self.duration_s, self.length_m, inside))

    def derivative(self, time_s: ArrayLike, order: int) -> FloatArray:
        """d^k s / dt^k (0 outside the move)."""
        spline: CubicSpline = self._spline  # type: ignore[attr-defined]
        t = np.asarray(time_s, dtype=float)
        inside = (t > 0.0) & (t < self.duration_s)
        return np.where(inside, spline(np.clip(t, 0.0, self.duration_s), order), 0.0)

    def velocity(self, time_s: ArrayLike) -> FloatArray:
        """s' [m/s]."""
        return self.derivative(time_s, 1)

    def acceleration(self, time_s: ArrayLike) -> FloatArray:
        """s'' [m/s^2]."""
        return self.derivative(time_s, 2)

    def jerk(self, time_s: ArrayLike) -> FloatArray:
        """s''' [m/s^3]."""
        return self.derivative(time_s, 3)

    def stretched(self, factor: float) -> Timing:
        """s(t / c): speeds / c, accelerations / c^2, jerks / c^3."""
        return Timing(self.name, self.time_s * factor, self.s_m)


def fine_grid(duration_s: float) -> FloatArray:
    """Equally spaced times on [0, duration] at most `FINE_STEP_S` apart (at least 8 steps): the
    grid on which the timings are filtered and resampled.

    Parameters
    ----------
    duration_s : float
        Length of the grid [s].

    Returns
    -------
    numpy.ndarray
        The times [s], both ends included.

    Examples
    --------
    >>> grid = fine_grid(1.0)
    >>> float(grid[0]), float(grid[-1]), bool(grid[1] - grid[0] <= FINE_STEP_S)
    (0.0, 1.0, True)
    """
    count = max(8, math.ceil(duration_s / FINE_STEP_S))
    return np.linspace(0.0, duration_s, count + 1)


def box_smoothed(timing: Timing, width_s: float) -> Timing:
    """(1/tau) integral_{t-tau}^{t} s(u) du: a jerk-limited timing, tau longer (module step 2).

    Parameters
    ----------
    timing : Timing
        The timing.
    width_s : float
        Window width tau [s] (no smoothing when <= 0).

    Returns
    -------
    Timing

    References
    ----------
    Biagiotti & Melchiorri (2008) ch. 4 (FIR-filter trajectories).

    Examples
    --------
    >>> step = Timing.from_samples("ramp", np.linspace(0, 1, 101), np.linspace(0, 1, 101))
    >>> smooth = box_smoothed(step, 0.2)
    >>> round(smooth.duration_s, 3), round(float(smooth.velocity(0.6)), 3)
    (1.2, 1.0)
    """
    if width_s <= 0.0:
        return timing
    grid = fine_grid(timing.duration_s + width_s)
    step = grid[1] - grid[0]
    values = timing.position(grid)
    integral = np.concatenate(([0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * step)))
    before = np.interp(grid - width_s, grid, integral, left=0.0)
    smoothed = (integral - before) / width_s
    smoothed[-1] = timing.length_m
    return Timing(timing.name, grid, smoothed)


def shaped_timing(timing: Timing, shaper: Shaper) -> Timing:
    """Input shaping of a timing: sum_i A_i s(t - t_i) (duration T + t_N).

    Parameters
    ----------
    timing : Timing
        The timing.
    shaper : Shaper
        Impulse amplitudes and times (`sloshkit.motion.shaping`).

    Returns
    -------
    Timing

    References
    ----------
    Singer & Seering (1990), doi:10.1115/1.2894142.

    Examples
    --------
    >>> from sloshkit.motion.shaping import zv
    >>> ramp = Timing.from_samples("ramp", np.linspace(0, 1, 101), np.linspace(0, 1, 101))
    >>> shaper = zv(2 * np.pi, 0.0)  # 1 Hz: second impulse after 0.5 s
    >>> round(shaped_timing(ramp, shaper).duration_s, 3)
    1.5
    """
    grid = fine_grid(timing.duration_s + float(shaper.times_s[-1]))
    values = sum(
        amplitude * timing.position(grid - delay)
        for amplitude, delay in zip(shaper.amplitudes, shaper.times_s, strict=True)
    )
    values = np.asarray(values, dtype=float)
    values[-1] = timing.length_m
    return Timing(timing.name, grid, values)


__all__ = [
    "FINE_STEP_S",
    "Timing",
    "box_smoothed",
    "shaped_timing",
]
