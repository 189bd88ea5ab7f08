"""The motion object: a rest-to-rest position profile as an exact piecewise polynomial, with its
derivatives and exact peaks; and the integration of constant-jerk segments into one.

The piecewise polynomial (`PiecewisePolynomial`) is plain numpy with the layout and the
evaluation of `scipy.interpolate.PPoly` (a motion is built and sampled on every plan; importing
scipy.interpolate alone costs more than a whole 1-D plan).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sloshkit.motion.sampling import sample_motion

FloatArray = NDArray[np.float64]


class PiecewisePolynomial:
    """A piecewise polynomial in the layout of `scipy.interpolate.PPoly`: on piece i,
    p(t) = sum_m c[m, i] (t - x[i])^(k - m), k = c.shape[0] - 1, for x[i] <= t < x[i + 1].

    Evaluated as ``PPoly`` evaluates (the piece found as x[i] <= t < x[i + 1], the last piece
    closed on the right, the end pieces extended outside [x[0], x[-1]]; the powers summed from
    the lowest up), so it gives the values of the equivalent ``PPoly`` (Stoer & Bulirsch,
    *Introduction to Numerical Analysis*, 3rd ed., Springer (2002) §2.4: the local power form
    of a piecewise polynomial). Accepts a ``PPoly`` as well (`of`).

    Parameters
    ----------
    c : array_like
        Coefficients, shape (k + 1, pieces), highest power first.
    x : array_like
        Breakpoints, shape (pieces + 1,), non-decreasing.

    Examples
    --------
    >>> p = PiecewisePolynomial([[1.0, -1.0], [0.0, 1.0]], [0.0, 1.0, 2.0])  # t, then 1 - (t-1)
    >>> p(np.array([0.5, 1.5, 2.0])).tolist(), p.derivative()(1.5).item()
    ([0.5, 0.5, 0.0], -1.0)
    """

    __slots__ = ("c", "x")

    def __init__(self, c: ArrayLike, x: ArrayLike) -> None:
        self.c = np.asarray(c, dtype=float)
        self.x = np.asarray(x, dtype=float)
        if self.c.ndim != 2 or self.x.shape != (self.c.shape[1] + 1,):
            raise ValueError("c must be (order + 1, pieces) and x (pieces + 1,)")
        if np.any(np.diff(self.x) < 0.0):
            raise ValueError("x must be non-decreasing")

    @classmethod
    def of(cls, polynomial: PiecewisePolynomial | object) -> PiecewisePolynomial:
        """The polynomial itself, or a copy of any object with ``c`` and ``x`` (a ``PPoly``)."""
        if isinstance(polynomial, cls):
            return polynomial
        return cls(polynomial.c, polynomial.x)  # type: ignore[attr-defined]

    def __call__(self, t: ArrayLike) -> FloatArray:
        """p(t), with the shape of ``t``."""
        points = np.asarray(t, dtype=float)
        flat = points.reshape(-1)
        pieces = self.c.shape[1]
        if pieces == 1:
            piece = np.zeros(flat.size, dtype=np.intp)
        else:
            piece = np.searchsorted(self.x, flat, side="right") - 1
            np.minimum(np.maximum(piece, 0, out=piece), pieces - 1, out=piece)
        local = flat - self.x[piece]
        value = np.zeros_like(flat)
        power = np.ones_like(flat)
        order = self.c.shape[0] - 1
        for m in range(order, -1, -1):
            value = value + self.c[m, piece] * power
            if m > 0:
                power = power * local
        return value.reshape(points.shape)

    def derivative(self, nu: int = 1) -> PiecewisePolynomial:
        """The ``nu``-th derivative (the zero polynomial past the order)."""
        if nu == 0:
            return PiecewisePolynomial(self.c.copy(), self.x)
        kept = self.c[:-nu].copy()
        if kept.shape[0] == 0:
            return PiecewisePolynomial(np.zeros((1, self.c.shape[1])), self.x)
        powers = np.arange(kept.shape[0] + nu - 1, nu - 1, -1)  # power of each row before
        kept *= np.array([math.prod(range(p - nu + 1, p + 1)) for p in powers], dtype=float)[
            :, None
        ]
        return PiecewisePolynomial(kept, self.x)


@dataclass(frozen=True, eq=False)
class Motion:
    """A rest-to-rest motion: position s(t) [m] as a piecewise polynomial on [0, T].

    Build it with a law function (`trapezoidal`, `quintic`, `s_curve`, ...), not directly.

    Parameters
    ----------
    name : str
        The law's name.
    position_pp : PiecewisePolynomial
        Position s(t) [m], t from 0 to T [s] (a `scipy.interpolate.PPoly` is accepted and
        converted).

    Examples
    --------
    >>> from sloshkit import quintic
    >>> law = quintic(0.1, 1.0)
    >>> law.duration_s, round(law.distance_m, 12), round(law.peak_acceleration_m_s2, 4)
    (1.0, 0.1, 0.5774)
    """

    name: str
    position_pp: PiecewisePolynomial

    def __post_init__(self) -> None:
        object.__setattr__(self, "position_pp", PiecewisePolynomial.of(self.position_pp))

    @property
    def duration_s(self) -> float:
        """Move duration T [s]."""
        return float(self.position_pp.x[-1] - self.position_pp.x[0])

    @property
    def distance_m(self) -> float:
        """Travel s(T) - s(0) [m]."""
        return float(self.position_pp(self.position_pp.x[-1]) - self.position_pp(0.0))

    @property
    def breakpoints_s(self) -> FloatArray:
        """Times where the polynomial pieces join [s]."""
        return np.asarray(self.position_pp.x, dtype=float)

    def derivative_pp(self, order: int) -> PiecewisePolynomial:
        """The ``order``-th time derivative (0: position ... 3: jerk)."""
        return self.position_pp if order == 0 else self.position_pp.derivative(order)

    def evaluate(self, time_s: ArrayLike, order: int = 0) -> FloatArray:
        """Position (0), velocity (1), acceleration (2) or jerk (3) at ``time_s`` [SI].

        Outside [0, T] the container is at rest: position is held, derivatives are zero.
        """
        t = np.asarray(time_s, dtype=float)
        end = self.duration_s
        clipped = np.clip(t, 0.0, end)
        values = np.asarray(self.derivative_pp(order)(clipped), dtype=float)
        if order > 0:
            values = np.where((t < 0.0) | (t > end), 0.0, values)
        return values

    def position(self, time_s: ArrayLike) -> FloatArray:
        """Position s(t) [m]."""
        return self.evaluate(time_s, 0)

    def velocity(self, time_s: ArrayLike) -> FloatArray:
        """Velocity s'(t) [m/s]."""
        return self.evaluate(time_s, 1)

    def acceleration(self, time_s: ArrayLike) -> FloatArray:
        """Acceleration s''(t) [m/s^2]."""
        return self.evaluate(time_s, 2)

    def jerk(self, time_s: ArrayLike) -> FloatArray:
        """Jerk s'''(t) [m/s^3] (piecewise; at a jump, the value of the piece on the right)."""
        return self.evaluate(time_s, 3)

    def peak(self, order: int) -> float:
        """Peak |derivative| over the move, exact from the pieces (order 1..3) [SI]."""
        return _peak_abs(self.derivative_pp(order))

    @property
    def peak_velocity_m_s(self) -> float:
        """Peak |velocity| [m/s]."""
        return self.peak(1)

    @property
    def peak_acceleration_m_s2(self) -> float:
        """Peak |acceleration| [m/s^2]."""
        return self.peak(2)

    @property
    def acceleration_jump_m_s2(self) -> float:
        """Largest jump of the acceleration, including from and to rest at 0 and T [m/s^2]."""
        acceleration = self.derivative_pp(2)
        widths = np.diff(acceleration.x)
        starts = acceleration.c[-1, :]  # value at the left end of each piece
        ends = _horner(np.asarray(acceleration.c, dtype=float), widths)
        left = np.concatenate(([0.0], ends))
        right = np.concatenate((starts, [0.0]))
        return float(np.max(np.abs(right - left)))

    @property
    def peak_jerk_m_s3(self) -> float:
        """Peak |jerk| [m/s^3]; ``inf`` when the acceleration jumps (trapezoidal, cubic): the
        jerk is then a Dirac impulse, which is what excites the slosh."""
        scale = max(self.peak_acceleration_m_s2, 1e-300)
        if self.acceleration_jump_m_s2 > 1e-9 * scale:
            return math.inf
        return self.peak(3)

    @property
    def peak_finite_jerk_m_s3(self) -> float:
        """Peak |jerk| between acceleration jumps (ignoring the impulses) [m/s^3]."""
        return self.peak(3)

    def sample(self, sample_period_s: float) -> dict[str, FloatArray]:
        """Samples at t = 0, dt, 2 dt, ..., with the last sample exactly at T.

        Returns arrays ``t_s``, ``position_m``, ``velocity_m_s``, ``acceleration_m_s2``,
        ``jerk_m_s3`` (see `sloshkit.motion.sampling.sample_motion`).
        """
        return sample_motion(self, sample_period_s)


def _horner(coefficients: FloatArray, t: FloatArray) -> FloatArray:
    """Each piece's polynomial (a column of ``coefficients``, highest power first) at its
    own local time ``t``."""
    value = np.zeros_like(t)
    for row in coefficients:
        value = value * t + row
    return value


def _peak_abs(pp: PiecewisePolynomial) -> float:
    """max |p(t)| over the breakpoints' span, from each piece's ends and interior extrema.

    Pieces up to cubic (every motion built from jerk segments) are done for all pieces at once:
    the extrema are the real roots of the derivative in closed form; higher orders piece by
    piece with `numpy.roots`.
    """
    coefficients = np.asarray(pp.c, dtype=float)  # shape (order + 1, pieces)
    widths = np.diff(pp.x)
    if coefficients.shape[0] > 4:
        return _peak_abs_by_piece(coefficients, widths)
    coefficients = np.vstack((np.zeros((4 - coefficients.shape[0], widths.size)), coefficients))
    c3, c2, c1 = coefficients[0], coefficients[1], coefficients[2]
    candidates = [np.zeros_like(widths), widths]
    # p'(t) = 3 c3 t^2 + 2 c2 t + c1: a quadratic where c3 != 0, linear where only c2 != 0.
    cubic = c3 != 0.0
    a = np.where(cubic, 3.0 * c3, 1.0)
    b = 2.0 * c2
    discriminant = b * b - 4.0 * a * c1
    root = np.sqrt(np.abs(discriminant))
    # numpy.roots' tolerance: a complex pair with |imag| < 1e-12 counts as a double real root.
    real = cubic & ((discriminant >= 0.0) | (root / (2.0 * np.abs(a)) < 1e-12))
    root = np.where(discriminant >= 0.0, root, 0.0)
    candidates += [np.where(real, (-b - root) / (2.0 * a), 0.0)]
    candidates += [np.where(real, (-b + root) / (2.0 * a), 0.0)]
    linear = ~cubic & (c2 != 0.0)
    candidates += [np.where(linear, -c1 / np.where(linear, 2.0 * c2, 1.0), 0.0)]
    best = 0.0
    for t in candidates:
        inside = (t >= 0.0) & (t <= widths)
        values = np.abs(_horner(coefficients, np.where(inside, t, 0.0)))
        if values.size:
            best = max(best, float(np.max(values)))
    return best


def _peak_abs_by_piece(coefficients: FloatArray, widths: FloatArray) -> float:
    best = 0.0
    for piece in range(coefficients.shape[1]):
        poly = np.poly1d(coefficients[:, piece])
        candidates = [0.0, float(widths[piece])]
        if poly.order >= 2:
            for root in np.roots(np.polyder(poly.coeffs)):
                if abs(root.imag) < 1e-12 and 0.0 < root.real < widths[piece]:
                    candidates.append(float(root.real))
        best = max(best, float(np.max(np.abs(poly(np.asarray(candidates))))))
    return best


def piecewise_constant_jerk(
    name: str,
    durations: list[float],
    jerks: list[float],
    start_accelerations: list[float] | None = None,
) -> Motion:
    """A motion of segments of constant jerk, integrated exactly from rest at 0.

    Position, velocity and acceleration are continuous from segment to segment (the
    acceleration may jump at a segment's start when ``start_accelerations`` is given); the
    result is an exact cubic `PiecewisePolynomial`. Segments of zero or negative length
    are skipped.

    Parameters
    ----------
    name : str
        Name of the motion.
    durations : list of float
        Length of each segment [s].
    jerks : list of float
        Jerk of each segment [m/s^3].
    start_accelerations : list of float, optional
        Acceleration at the start of each segment [m/s^2], replacing the one carried over.

    Returns
    -------
    Motion
        The motion, from t = 0 to the sum of the durations.

    Examples
    --------
    Jerk +J for tau, then -J for tau: the acceleration rises to J tau and falls back to 0, and
    the distance is J tau^3:

    >>> motion = piecewise_constant_jerk("bump", [0.5, 0.5], [8.0, -8.0])
    >>> motion.duration_s, round(float(motion.position(1.0)), 12)
    (1.0, 1.0)
    """
    position = velocity = 0.0
    acceleration = 0.0
    breaks = [0.0]
    columns = []
    for index, (width, jerk) in enumerate(zip(durations, jerks, strict=True)):
        if start_accelerations is not None:
            acceleration = start_accelerations[index]
        if width <= 0.0:
            continue
        columns.append([jerk / 6.0, acceleration / 2.0, velocity, position])
        position += velocity * width + acceleration * width**2 / 2.0 + jerk * width**3 / 6.0
        velocity += acceleration * width + jerk * width**2 / 2.0
        acceleration += jerk * width
        breaks.append(breaks[-1] + width)
    return Motion(name, PiecewisePolynomial(np.asarray(columns, dtype=float).T, breaks))
