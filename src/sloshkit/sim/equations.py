"""Equations of motion of the equivalent pendulums: one right-hand side per model family.

Every function here is written with plain arithmetic and the ``sin``/``cos`` it is given, so the
same source serves numpy arrays, Python floats (the integrators) and casadi expressions (the
optimal planner builds its NLP from it).

Convention: x is the container's position along the move [m], theta_n the angle of mode n's
pendulum [rad] (positive when the bob swings towards +x, i.e. it lags the container with
theta < 0 while accelerating forward); omega_n, zeta_n and L_n from the `SloshModel`.

- linear (seed paper eq. 7, per mode; Ibrahim 2005 §6.2):
  theta'' + 2 zeta omega theta' + omega^2 theta = -x''/L;
- nonlinear (large-angle pendulum in the container frame; Ibrahim 2005 §6.2):
  theta'' + 2 zeta omega theta' + omega^2 sin(theta) = -(x''/L) cos(theta).

The paper prints a cos^2(theta) factor on the damper of its eq. 5; the damper here acts on the
pendulum's relative rotation (a rotational damper in the hinge, the paper's Simscape revolute
joint), which reduces to eq. 7 when linearised.

References
----------
R. A. Ibrahim, *Liquid Sloshing Dynamics: Theory and Applications*, Cambridge University Press
(2005), doi:10.1017/CBO9780511536656.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

T = TypeVar("T")


def pendulum_angular_acceleration(
    angle_rad: T,
    rate_rad_s: Any,
    container_acceleration_m_s2: Any,
    omega_rad_s: Any,
    damping_ratio: Any,
    length_m: Any,
    *,
    nonlinear: bool = False,
    sin: Callable[[Any], Any] = np.sin,
    cos: Callable[[Any], Any] = np.cos,
) -> T:
    """theta'' of the pendulum of one mode (or of many, element-wise) driven by x''.

    Parameters
    ----------
    angle_rad : float, array or casadi expression
        Pendulum angle theta [rad].
    rate_rad_s : float, array or casadi expression
        Angular rate theta' [rad/s].
    container_acceleration_m_s2 : float, array or casadi expression
        The container's acceleration x'' [m/s^2].
    omega_rad_s, damping_ratio, length_m : float or array
        The mode's natural frequency [rad/s], damping ratio and pendulum length [m].
    nonlinear : bool
        Large-angle pendulum (sin, cos) instead of the linear equation.
    sin, cos : callable
        The trigonometric functions of the arithmetic used (``np.sin``, ``math.sin``,
        ``casadi.sin``); used only when ``nonlinear``.

    Returns
    -------
    float, array or casadi expression
        theta'' [rad/s^2].

    References
    ----------
    Seed paper eq. 7; R. A. Ibrahim, *Liquid Sloshing Dynamics* (2005) §6.2,
    doi:10.1017/CBO9780511536656.

    Examples
    --------
    At rest and upright, a forward acceleration of 1 m/s^2 swings a 0.1 m pendulum backwards:

    >>> float(pendulum_angular_acceleration(0.0, 0.0, 1.0, 10.0, 0.01, 0.1))
    -10.0
    """
    omega, zeta, length = omega_rad_s, damping_ratio, length_m
    acceleration = container_acceleration_m_s2
    if nonlinear:
        result = (
            -2 * zeta * omega * rate_rad_s
            - omega**2 * sin(angle_rad)
            - acceleration / length * cos(angle_rad)
        )
    else:
        result = -2 * zeta * omega * rate_rad_s - omega**2 * angle_rad - acceleration / length
    return result  # type: ignore[no-any-return]
