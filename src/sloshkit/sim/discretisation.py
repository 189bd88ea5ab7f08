"""Exact discretisation of the linear pendulum driven by the container's velocity.

The linear equation is rewritten with y = theta' + v/L so that it is driven by the container's
velocity v (continuous for every rest-to-rest law) instead of its acceleration:
theta' = y - v/L, y' = -omega^2 theta - 2 zeta omega (y - v/L). It is discretised exactly for a
velocity that is linear between samples (first-order hold, Franklin, Powell & Workman, *Digital
Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2): exact for the trapezoidal law and
second-order accurate for the others. The resulting recursion is a second-order IIR filter run
by `scipy.signal.lfilter`, vectorised over any number of cases that share a mode.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import expm
from scipy.signal import lfilter, ss2tf

from sloshkit.model.modal import SloshModel

FloatArray = NDArray[np.float64]


@lru_cache(maxsize=4096)
def velocity_driven_discretisation(
    omega_rad_s: float, damping_ratio: float, length_m: float, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(phi, gamma, g1) of the first-order-hold discretisation in the shifted state z.

    With s_k = (theta_k, y_k), y = theta' + v/L, and velocity samples u_k: z_k = s_k - g1 u_k,
    z_{k+1} = phi z_k + gamma u_k, s_k = z_k + g1 u_k, z_0 = 0 for a start from rest.
    """
    w, z, length, h = omega_rad_s, damping_ratio, length_m, sample_period_s
    a_matrix = np.array([[0.0, 1.0], [-(w**2), -2.0 * z * w]])
    b_vector = np.array([-1.0 / length, 2.0 * z * w / length])
    augmented = np.zeros((4, 4))
    augmented[:2, :2] = a_matrix
    augmented[:2, 2] = b_vector
    augmented[2, 3] = 1.0
    exponential = expm(augmented * h)
    phi = exponential[:2, :2]
    gamma_hold = exponential[:2, 2]  # integral of e^{As} B over one step
    gamma_ramp = exponential[:2, 3] / h  # integral of e^{As} B (h - s) / h
    g0 = gamma_hold - gamma_ramp
    g1 = gamma_ramp
    return phi, phi @ g1 + g0, g1


@lru_cache(maxsize=4096)
def velocity_driven_filters(
    omega_rad_s: float, damping_ratio: float, length_m: float, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """IIR coefficients (b_theta, a, b_y, a) of the first-order-hold discretisation.

    ``lfilter(b_theta, a, v)`` gives theta_k and ``lfilter(b_y, a, v)`` gives
    y_k = theta'_k + v_k / L for velocity samples v_k starting from rest (v_0 = 0).
    """
    phi, gamma, g1 = velocity_driven_discretisation(
        omega_rad_s, damping_ratio, length_m, sample_period_s
    )
    b_theta, a_theta = ss2tf(phi, gamma[:, None], np.array([[1.0, 0.0]]), np.array([[g1[0]]]))
    b_y, a_y = ss2tf(phi, gamma[:, None], np.array([[0.0, 1.0]]), np.array([[g1[1]]]))
    return (
        np.asarray(b_theta[0], dtype=float),
        np.asarray(a_theta, dtype=float),
        np.asarray(b_y[0], dtype=float),
        np.asarray(a_y, dtype=float),
    )


def linear_mode_response(
    velocity_m_s: FloatArray,
    sample_period_s: float,
    omega_rad_s: float,
    damping_ratio: float,
    length_m: float,
) -> tuple[FloatArray, FloatArray]:
    """Angle and angular rate of one linear mode for velocity samples (last axis = time).

    The exact first-order-hold discretisation (`velocity_driven_filters`) run as an IIR filter.

    Parameters
    ----------
    velocity_m_s : numpy.ndarray
        Container velocity from rest, sampled at k Ts [m/s]; may be 2-D (cases x samples), all
        cases sharing the mode.
    sample_period_s : float
        Ts [s].
    omega_rad_s : float
        Natural frequency [rad/s].
    damping_ratio : float
        Damping ratio.
    length_m : float
        Pendulum length [m].

    Returns
    -------
    tuple of numpy.ndarray
        (theta [rad], theta' [rad/s]) with the shape of the input.

    References
    ----------
    Franklin, G. F., J. D. Powell, M. Workman, *Digital Control of Dynamic Systems*, 3rd ed.,
    Addison-Wesley (1998) §6.3.2.

    Examples
    --------
    >>> import numpy as np
    >>> theta, rate = linear_mode_response(np.zeros(4), 1e-3, 30.0, 0.03, 0.01)
    >>> theta.tolist()
    [0.0, 0.0, 0.0, 0.0]
    """
    b_theta, a, b_y, _ = velocity_driven_filters(
        float(omega_rad_s), float(damping_ratio), float(length_m), float(sample_period_s)
    )
    theta = lfilter(b_theta, a, velocity_m_s, axis=-1)
    rate = lfilter(b_y, a, velocity_m_s, axis=-1) - velocity_m_s / length_m
    return np.asarray(theta, dtype=float), np.asarray(rate, dtype=float)


def linear_response(
    model: SloshModel, velocity_m_s: FloatArray, sample_period_s: float
) -> tuple[FloatArray, FloatArray]:
    """Angles and rates of every linear mode of ``model`` for velocity samples from rest.

    Parameters
    ----------
    model : SloshModel
        The equivalent model.
    velocity_m_s : numpy.ndarray
        Container velocity sampled at t_k = k Ts from rest, 1-D (samples,) [m/s].
    sample_period_s : float
        Ts [s]; the velocity is taken as linear between samples.

    Returns
    -------
    tuple of numpy.ndarray
        (theta [rad], theta' [rad/s]), each of shape (modes, samples).

    Examples
    --------
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> angle, rate = linear_response(model, np.zeros(5), 1e-3)
    >>> angle.shape, float(abs(angle).max())
    ((3, 5), 0.0)
    """
    angle = np.empty((len(model.modes), np.shape(velocity_m_s)[-1]))
    rate = np.empty_like(angle)
    for row, mode in enumerate(model.modes):
        angle[row], rate[row] = linear_mode_response(
            velocity_m_s, sample_period_s, mode.omega_rad_s, mode.damping_ratio, mode.length_m
        )
    return angle, rate
