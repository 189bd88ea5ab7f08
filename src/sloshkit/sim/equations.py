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
from numpy.typing import NDArray

T = TypeVar("T")
FloatArray = NDArray[np.float64]


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


def cart_pendulum_accelerations(
    force_n: float,
    angle_rad: FloatArray,
    rate_rad_s: FloatArray,
    *,
    total_mass_kg: float,
    masses_kg: FloatArray,
    lengths_m: FloatArray,
    omegas_rad_s: FloatArray,
    damping_ratios: FloatArray,
) -> FloatArray:
    """(x'', theta_1'', ..., theta_N'') of a cart carrying one pendulum per mode, pushed by F.

    Seed paper eqs. 4-5 (one mode), written for N modes with a hinge damper (Lagrange's
    equations):

    (M_total) x'' + sum m_n L_n (theta_n'' cos theta_n - theta_n'^2 sin theta_n) = F
    L_n cos(theta_n) x'' + L_n^2 theta_n'' + 2 zeta_n omega_n L_n^2 theta_n'
    + omega_n^2 L_n^2 sin(theta_n) = 0,

    with omega_n^2 L_n in place of g so that a calibrated frequency is honoured; the mass matrix
    is solved for the accelerations.

    Parameters
    ----------
    force_n : float
        Force on the cart F [N].
    angle_rad, rate_rad_s : numpy.ndarray
        Pendulum angles theta_n [rad] and rates theta_n' [rad/s], one per mode.
    total_mass_kg : float
        Cart plus liquid mass that moves with the cart plus the pendulum masses [kg].
    masses_kg, lengths_m, omegas_rad_s, damping_ratios : numpy.ndarray
        Per mode: m_n [kg], L_n [m], omega_n [rad/s], zeta_n.

    Returns
    -------
    numpy.ndarray
        [x'' [m/s^2], theta_1'' ... theta_N'' [rad/s^2]].

    References
    ----------
    De Simone, M. C., et al., Appl. Sci. 14 (2024) 4522, eqs. 4-5, doi:10.3390/app14114522;
    Ibrahim, R. A., *Liquid Sloshing Dynamics* (2005) §6.2, doi:10.1017/CBO9780511536656.

    Examples
    --------
    A pushed cart with hanging pendulums at rest accelerates as one rigid body at first:

    >>> import numpy as np
    >>> second = cart_pendulum_accelerations(
    ...     2.0, np.zeros(1), np.zeros(1), total_mass_kg=1.0, masses_kg=np.array([0.0]),
    ...     lengths_m=np.array([0.1]), omegas_rad_s=np.array([10.0]),
    ...     damping_ratios=np.array([0.0]))
    >>> [round(value, 9) for value in second.tolist()]
    [2.0, -20.0]
    """
    theta, theta_dot = angle_rad, rate_rad_s
    masses, lengths, omegas, zetas = masses_kg, lengths_m, omegas_rad_s, damping_ratios
    count = theta.size
    matrix = np.zeros((count + 1, count + 1))
    rhs = np.zeros(count + 1)
    matrix[0, 0] = total_mass_kg
    matrix[0, 1:] = masses * lengths * np.cos(theta)
    rhs[0] = force_n + np.sum(masses * lengths * theta_dot**2 * np.sin(theta))
    matrix[1:, 0] = lengths * np.cos(theta)
    matrix[1:, 1:] = np.diag(lengths**2)
    rhs[1:] = -2 * zetas * omegas * lengths**2 * theta_dot - omegas**2 * lengths**2 * np.sin(theta)
    return np.asarray(np.linalg.solve(matrix, rhs), dtype=float)
