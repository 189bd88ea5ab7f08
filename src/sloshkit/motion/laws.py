"""Rest-to-rest 1-D motion laws as exact piecewise polynomials.

Every law is a `Motion`: position s(t) on [0, T] held as a `PiecewisePolynomial`, so
position, velocity, acceleration and jerk are exact derivatives of one object, vectorised over
time, and peak values are found from the polynomial pieces (not from samples). Outside [0, T]
the container rests at its start or end.

Laws and sources
----------------
- ``trapezoidal``: trapezoidal velocity, MATLAB ``trapveltraj`` semantics (acceleration time a
  third of the move by default); Biagiotti & Melchiorri, *Trajectory Planning for Automatic
  Machines and Robots*, Springer (2008) §3.2.
- ``cubic``: s = D (3 tau^2 - 2 tau^3), MATLAB ``cubicpolytraj`` with zero end velocities.
- ``quintic``: s = D (10 tau^3 - 15 tau^4 + 6 tau^5), ``quinticpolytraj`` with zero end velocity
  and acceleration.
- ``septic``: s = D (35 tau^4 - 84 tau^5 + 70 tau^6 - 20 tau^7), zero end velocity,
  acceleration and jerk: the "jerk-optimised", jerk-continuous polynomial of the seed paper
  (Biagiotti & Melchiorri 2008 §2.1.6).
- ``minimum-jerk``: the trajectory minimising the integral of squared jerk between rest states
  (Flash & Hogan, J. Neurosci. 5 (1985) 1688). For rest-to-rest with zero end accelerations it
  is the same polynomial as ``quintic``; it is kept as a name because users look for it.
- ``s-curve``: time-optimal jerk-limited (7-segment) profile from velocity, acceleration and
  jerk limits, computed by ruckig (Berscheid & Kröger, RSS 2021).
- `from_samples`: a user's sampled position (quintic interpolating spline, differentiated
  analytically) or acceleration (cubic spline, integrated analytically).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sloshkit.errors import InputError, require_in_range, require_positive
from sloshkit.motion.profile import Motion as Motion  # re-exported (v1 path)
from sloshkit.motion.profile import PiecewisePolynomial, piecewise_constant_jerk
from sloshkit.motion.recorded import from_samples as from_samples  # re-exported (v1 path)

#: Move durations the laws accept [s]: 1 us to about 30 years (a polynomial law divides the
#: distance by T^7, which underflows to 0 for shorter moves).
DURATION_RANGE_S = (1e-6, 1e9)

LAW_NAMES: tuple[str, ...] = (
    "trapezoidal",
    "cubic",
    "quintic",
    "septic",
    "minimum-jerk",
    "s-curve",
)


def _normalised_polynomial(
    name: str, distance_m: float, duration_s: float, coefficients: list[float]
) -> Motion:
    """s(t) = D * sum_k c_k (t/T)^k as a one-piece polynomial (c_k in ascending powers)."""
    distance = require_positive("distance", distance_m, "m")
    duration = require_in_range("duration", duration_s, *DURATION_RANGE_S, "s")
    # The pieces hold descending powers of (t - 0): c_k D / T^k.
    scaled = [distance * c / duration**k for k, c in enumerate(coefficients)]
    return Motion(
        name, PiecewisePolynomial(np.asarray(scaled[::-1], dtype=float)[:, None], [0.0, duration])
    )


def cubic(distance_m: float, duration_s: float) -> Motion:
    """Cubic polynomial, zero end velocities (``cubicpolytraj``): s = D (3 tau^2 - 2 tau^3).

    Parameters
    ----------
    distance_m : float
        Travel distance D [m].
    duration_s : float
        Move duration T [s].

    Returns
    -------
    Motion
        The law as an exact piecewise polynomial.

    References
    ----------
    Biagiotti, L., C. Melchiorri, *Trajectory Planning for Automatic Machines and Robots*,
    Springer (2008), §2.1, doi:10.1007/978-3-540-85629-0.

    Examples
    --------
    >>> from sloshkit import cubic
    >>> law = cubic(0.1, 1.0)
    >>> round(law.peak_velocity_m_s, 4)
    0.15
    """
    return _normalised_polynomial("cubic", distance_m, duration_s, [0, 0, 3, -2])


def quintic(distance_m: float, duration_s: float) -> Motion:
    """Quintic, zero end velocity and acceleration: s = D (10 tau^3 - 15 tau^4 + 6 tau^5).

    Parameters
    ----------
    distance_m : float
        Travel distance D [m].
    duration_s : float
        Move duration T [s].

    Returns
    -------
    Motion
        The law as an exact piecewise polynomial.

    References
    ----------
    Biagiotti, L., C. Melchiorri, *Trajectory Planning for Automatic Machines and Robots*,
    Springer (2008), §2.1, doi:10.1007/978-3-540-85629-0.

    Examples
    --------
    >>> from sloshkit import quintic
    >>> law = quintic(0.1, 1.0)
    >>> round(law.peak_velocity_m_s, 4)
    0.1875
    """
    return _normalised_polynomial("quintic", distance_m, duration_s, [0, 0, 0, 10, -15, 6])


def septic(distance_m: float, duration_s: float) -> Motion:
    """Jerk-continuous 7th-degree polynomial, zero end velocity, acceleration and jerk:
    s = D (35 tau^4 - 84 tau^5 + 70 tau^6 - 20 tau^7).

    Parameters
    ----------
    distance_m : float
        Travel distance D [m].
    duration_s : float
        Move duration T [s].

    Returns
    -------
    Motion
        The law as an exact piecewise polynomial.

    References
    ----------
    Biagiotti, L., C. Melchiorri, *Trajectory Planning for Automatic Machines and Robots*,
    Springer (2008), §2.1.6, doi:10.1007/978-3-540-85629-0.

    Examples
    --------
    >>> from sloshkit import septic
    >>> law = septic(0.1, 1.0)
    >>> round(law.peak_velocity_m_s, 4)
    0.2188
    """
    return _normalised_polynomial("septic", distance_m, duration_s, [0, 0, 0, 0, 35, -84, 70, -20])


def minimum_jerk(distance_m: float, duration_s: float) -> Motion:
    """Minimum integral of squared jerk between rest states; equal to the quintic polynomial.

    Parameters
    ----------
    distance_m : float
        Travel distance D [m].
    duration_s : float
        Move duration T [s].

    Returns
    -------
    Motion
        The law as an exact piecewise polynomial.

    References
    ----------
    Flash, T., N. Hogan, The coordination of arm movements, J. Neurosci. 5 (1985) 1688-1703,
    doi:10.1523/JNEUROSCI.05-07-01688.1985.

    Examples
    --------
    >>> from sloshkit import minimum_jerk
    >>> law = minimum_jerk(0.1, 1.0)
    >>> round(law.peak_velocity_m_s, 4)
    0.1875
    """
    return _normalised_polynomial("minimum-jerk", distance_m, duration_s, [0, 0, 0, 10, -15, 6])


def trapezoidal(
    distance_m: float,
    peak_velocity_m_s: float | None = None,
    duration_s: float | None = None,
    acceleration_fraction: float | None = None,
) -> Motion:
    """Trapezoidal velocity profile with MATLAB ``trapveltraj`` semantics.

    Give the peak velocity V, the duration T, or both. With one of them the acceleration (and
    deceleration) phase lasts ``acceleration_fraction`` of T (default 1/3, as ``trapveltraj``), so
    D = V T (1 - f): e.g. D = 0.5 m, V = 0.5 m/s gives T = 1.5 s and a = 1 m/s^2. With both, the
    acceleration time is T - D/V and must lie in (0, T/2].

    Parameters
    ----------
    distance_m : float
        Travel distance D [m].
    peak_velocity_m_s : float, optional
        Peak (cruise) velocity V [m/s].
    duration_s : float, optional
        Move duration T [s].
    acceleration_fraction : float, optional
        Fraction of T spent accelerating, in (0, 0.5].

    Returns
    -------
    Motion
        The law (a cubic piecewise polynomial with acceleration jumps).

    References
    ----------
    Biagiotti, L., C. Melchiorri, *Trajectory Planning for Automatic Machines and Robots*,
    Springer (2008), §3.2, doi:10.1007/978-3-540-85629-0; M. C. De Simone et al., Appl. Sci. 14
    (2024) 4522, doi:10.3390/app14114522.

    Examples
    --------
    >>> from sloshkit import trapezoidal
    >>> law = trapezoidal(0.5, peak_velocity_m_s=0.5)
    >>> round(law.duration_s, 9), round(law.peak_acceleration_m_s2, 6)
    (1.5, 1.0)
    """
    distance = require_positive("distance", distance_m, "m")
    if peak_velocity_m_s is None and duration_s is None:
        raise InputError("peak_velocity", None, "give a peak velocity, a duration, or both")
    if peak_velocity_m_s is not None and duration_s is not None:
        if acceleration_fraction is not None:
            raise InputError(
                "acceleration_fraction",
                acceleration_fraction,
                "cannot be set together with both peak velocity and duration",
            )
        velocity = require_positive("peak_velocity", peak_velocity_m_s, "m/s")
        duration = require_in_range("duration", duration_s, *DURATION_RANGE_S, "s")
        accel_time = duration - distance / velocity
        if not 0.0 < accel_time <= duration / 2.0 * (1 + 1e-12):
            raise InputError(
                "peak_velocity",
                f"{velocity:.6g} m/s",
                f"must lie in ({distance / duration:.6g}, {2 * distance / duration:.6g}] m/s "
                f"for a {distance:.6g} m move in {duration:.6g} s",
            )
        accel_time = min(accel_time, duration / 2.0)
    else:
        fraction = (
            1.0 / 3.0
            if acceleration_fraction is None
            else require_in_range("acceleration_fraction", acceleration_fraction, 1e-6, 0.5)
        )
        if duration_s is not None:
            duration = require_in_range("duration", duration_s, *DURATION_RANGE_S, "s")
            velocity = distance / (duration * (1.0 - fraction))
        else:
            velocity = require_positive("peak_velocity", peak_velocity_m_s, "m/s")  # type: ignore[arg-type]
            duration = distance / (velocity * (1.0 - fraction))
        accel_time = fraction * duration
    acceleration = velocity / accel_time
    cruise = duration - 2.0 * accel_time
    return piecewise_constant_jerk(
        "trapezoidal",
        durations=[accel_time, cruise, accel_time],
        jerks=[0.0, 0.0, 0.0],
        start_accelerations=[acceleration, 0.0, -acceleration],
    )


def s_curve(
    distance_m: float, max_velocity_m_s: float, max_acceleration_m_s2: float, max_jerk_m_s3: float
) -> Motion:
    """Time-optimal jerk-limited rest-to-rest profile (up to 7 constant-jerk segments), by ruckig.

    The segment durations and jerks ruckig returns are integrated exactly, so the law is a cubic
    piecewise polynomial that matches ruckig's trajectory to rounding.

    Parameters
    ----------
    distance_m : float
        Travel distance [m].
    max_velocity_m_s : float
        Velocity limit [m/s].
    max_acceleration_m_s2 : float
        Acceleration limit [m/s^2].
    max_jerk_m_s3 : float
        Jerk limit [m/s^3].

    Returns
    -------
    Motion
        The shortest move within the limits.

    References
    ----------
    Berscheid, L., T. Kröger, Jerk-limited real-time trajectory generation with arbitrary target
    states, Robotics: Science and Systems XVII (2021), doi:10.15607/RSS.2021.XVII.015.

    Examples
    --------
    >>> from sloshkit import s_curve
    >>> law = s_curve(0.1, 1.0, 2.0, 50.0)
    >>> round(law.peak_acceleration_m_s2, 6), round(law.peak_jerk_m_s3, 6)
    (2.0, 50.0)
    """
    from ruckig import InputParameter, Result, Ruckig, Trajectory

    distance = require_positive("distance", distance_m, "m")
    limits = (
        require_positive("vmax", max_velocity_m_s, "m/s"),
        require_positive("amax", max_acceleration_m_s2, "m/s^2"),
        require_positive("jmax", max_jerk_m_s3, "m/s^3"),
    )
    parameters = InputParameter(1)
    parameters.current_position = [0.0]
    parameters.target_position = [distance]
    parameters.max_velocity = [limits[0]]
    parameters.max_acceleration = [limits[1]]
    parameters.max_jerk = [limits[2]]
    trajectory = Trajectory(1)
    result = Ruckig(1).calculate(parameters, trajectory)
    if result != Result.Working:
        raise InputError("s-curve limits", limits, f"ruckig could not plan the move ({result})")
    profile = trajectory.profiles[0][0]
    motion = piecewise_constant_jerk("s-curve", list(profile.t), list(profile.j))
    return Motion("s-curve", motion.position_pp)


def comparison_s_curve_limits(
    distance_m: float,
    peak_velocity_m_s: float,
    max_velocity_m_s: float | None = None,
    max_acceleration_m_s2: float | None = None,
    max_jerk_m_s3: float | None = None,
    acceleration_fraction: float | None = None,
) -> tuple[float, float, float]:
    """S-curve limits for comparing laws at one peak velocity: the given limits, else the
    trapezoid's peak velocity and acceleration and a jerk time of 0.1 s (j = 10 a per second).

    Parameters
    ----------
    distance_m : float
        Move distance [m].
    peak_velocity_m_s : float
        The peak velocity the laws share [m/s].
    max_velocity_m_s, max_acceleration_m_s2, max_jerk_m_s3 : float, optional
        Given limits [m/s], [m/s^2], [m/s^3].
    acceleration_fraction : float, optional
        The trapezoid's acceleration time over the move time (`trapezoidal`).

    Returns
    -------
    tuple of float
        (velocity [m/s], acceleration [m/s^2], jerk [m/s^3]).

    Examples
    --------
    >>> v, a, j = comparison_s_curve_limits(0.2, 0.5)
    >>> v, round(j / a, 9)
    (0.5, 10.0)
    """
    reference = trapezoidal(distance_m, peak_velocity_m_s, None, acceleration_fraction)
    velocity = max_velocity_m_s if max_velocity_m_s is not None else peak_velocity_m_s
    acceleration = (
        max_acceleration_m_s2
        if max_acceleration_m_s2 is not None
        else reference.peak_acceleration_m_s2
    )
    jerk = max_jerk_m_s3 if max_jerk_m_s3 is not None else 10.0 * acceleration
    return velocity, acceleration, jerk


def make_law(
    name: str,
    distance_m: float,
    *,
    duration_s: float | None = None,
    peak_velocity_m_s: float | None = None,
    max_velocity_m_s: float | None = None,
    max_acceleration_m_s2: float | None = None,
    max_jerk_m_s3: float | None = None,
    acceleration_fraction: float | None = None,
) -> Motion:
    """Build a law by its command-line name (`LAW_NAMES`).

    Polynomial laws need a duration, or a peak velocity from which the duration is that of the
    trapezoidal law with the same peak velocity (the seed paper's comparison at equal time).
    ``s-curve`` needs the three machine limits; its duration follows from them.

    Parameters
    ----------
    name : str
        One of `LAW_NAMES`.
    distance_m : float
        Travel distance [m].
    duration_s : float, optional
        Move duration [s].
    peak_velocity_m_s : float, optional
        Peak velocity [m/s] (sets the duration through the trapezoidal law).
    max_velocity_m_s, max_acceleration_m_s2, max_jerk_m_s3 : float, optional
        Limits of an ``s-curve`` [m/s, m/s^2, m/s^3].
    acceleration_fraction : float, optional
        Acceleration fraction of the trapezoidal law.

    Returns
    -------
    Motion
        The law.

    References
    ----------
    M. C. De Simone et al., Appl. Sci. 14 (2024) 4522, doi:10.3390/app14114522.

    Examples
    --------
    >>> from sloshkit import make_law
    >>> make_law("septic", 0.1, duration_s=2.0).duration_s
    2.0
    """
    if name == "s-curve":
        missing = [
            option
            for option, value in (
                ("vmax", max_velocity_m_s),
                ("amax", max_acceleration_m_s2),
                ("jmax", max_jerk_m_s3),
            )
            if value is None
        ]
        if missing:
            raise InputError("law", name, "needs the machine limits " + ", ".join(missing))
        return s_curve(distance_m, max_velocity_m_s, max_acceleration_m_s2, max_jerk_m_s3)  # type: ignore[arg-type]
    if name == "trapezoidal":
        return trapezoidal(distance_m, peak_velocity_m_s, duration_s, acceleration_fraction)
    builders: dict[str, Callable[[float, float], Motion]] = {
        "cubic": cubic,
        "quintic": quintic,
        "septic": septic,
        "minimum-jerk": minimum_jerk,
    }
    if name not in builders:
        raise InputError("law", name, "must be one of " + ", ".join(LAW_NAMES) + " or file:PATH")
    if duration_s is None:
        if peak_velocity_m_s is None:
            raise InputError(
                "duration", None, f"the {name} law needs a duration or a peak velocity"
            )
        duration_s = trapezoidal(
            distance_m, peak_velocity_m_s, None, acceleration_fraction
        ).duration_s
    return builders[name](distance_m, duration_s)
