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

from sloshkit.model.modal import SloshModel

FloatArray = NDArray[np.float64]


@lru_cache(maxsize=4096)
def velocity_driven_discretisation(
    omega_rad_s: float, damping_ratio: float, length_m: float, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(phi, gamma, g1) of the first-order-hold discretisation in the shifted state z.

    With s_k = (theta_k, y_k), y = theta' + v/L, and velocity samples u_k: z_k = s_k - g1 u_k,
    z_{k+1} = phi z_k + gamma u_k, s_k = z_k + g1 u_k, z_0 = 0 for a start from rest.
    One mode of `velocity_driven_discretisations`.
    """
    phi, gamma, g1 = velocity_driven_discretisations(
        np.array([omega_rad_s]), np.array([damping_ratio]), np.array([length_m]), sample_period_s
    )
    return phi[0], gamma[0], g1[0]


def velocity_driven_discretisations(
    omega_rad_s: FloatArray, damping_ratio: FloatArray, length_m: FloatArray, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(phi, gamma, g1) of many modes at once: shapes (modes, 2, 2), (modes, 2), (modes, 2).

    The exponential of the augmented matrix [[A, B, 0], [0, 0, 1], [0, 0, 0]] h (A, B of the
    velocity-driven pendulum) gives phi = e^{Ah}, the hold integral and the ramp integral
    (Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2);
    the exponentials of all modes are one vectorised scaling-and-squaring Taylor evaluation in
    numpy (`_expm_stack`): no call per mode.

    Parameters
    ----------
    omega_rad_s, damping_ratio, length_m : array of float
        Natural frequency [rad/s], damping ratio and pendulum length [m] of each mode.
    sample_period_s : float
        Step h [s].

    Returns
    -------
    tuple of arrays
        (phi, gamma, g1) per mode, as in `velocity_driven_discretisation`.

    References
    ----------
    Franklin, Powell & Workman (1998) §6.3.2; Moler & Van Loan, SIAM Review 45 (2003) 3,
    doi:10.1137/S00361445024180 (method 3, scaling and squaring).

    Examples
    --------
    >>> phi, gamma, g1 = velocity_driven_discretisations(
    ...     np.array([30.0, 50.0]), np.array([0.01, 0.01]), np.array([0.01, 0.004]), 1e-3)
    >>> phi.shape, gamma.shape, g1.shape
    ((2, 2, 2), (2, 2), (2, 2))
    """
    w = np.asarray(omega_rad_s, dtype=float)
    z = np.asarray(damping_ratio, dtype=float)
    length = np.asarray(length_m, dtype=float)
    h = float(sample_period_s)
    augmented = np.zeros((w.size, 4, 4))
    augmented[:, 0, 1] = 1.0
    augmented[:, 1, 0] = -(w**2)
    augmented[:, 1, 1] = -2.0 * z * w
    augmented[:, 0, 2] = -1.0 / length
    augmented[:, 1, 2] = 2.0 * z * w / length
    augmented[:, 2, 3] = 1.0
    exponential = _expm_stack(augmented * h)
    phi = exponential[:, :2, :2]
    gamma_hold = exponential[:, :2, 2]  # integral of e^{As} B over one step
    gamma_ramp = exponential[:, :2, 3] / h  # integral of e^{As} B (h - s) / h
    g0 = gamma_hold - gamma_ramp
    g1 = gamma_ramp
    return phi, np.einsum("nij,nj->ni", phi, g1) + g0, g1


def _expm_stack(matrices: FloatArray) -> FloatArray:
    """Exponentials of a stack of small matrices: scaling and squaring with a degree-20 Taylor
    polynomial (scaled norm <= 1/2: truncation below 1e-25), plain numpy (no BLAS call per
    matrix)."""
    norm = np.abs(matrices).sum(axis=-1).max(axis=-1)
    squarings = np.maximum(0, np.ceil(np.log2(np.maximum(norm, 1e-300) / 0.5))).astype(int)
    scaled = matrices / (2.0**squarings)[:, None, None]
    identity = np.broadcast_to(np.eye(matrices.shape[-1]), matrices.shape)
    result = identity.copy()
    term = identity.copy()
    for order in range(1, 21):
        term = np.einsum("nij,njk->nik", term, scaled) / order
        result = result + term
    for level in range(int(squarings.max(initial=0))):
        square = np.einsum("nij,njk->nik", result, result)
        result = np.where((squarings > level)[:, None, None], square, result)
    return np.asarray(result, dtype=float)


@lru_cache(maxsize=4096)
def velocity_driven_filters(
    omega_rad_s: float, damping_ratio: float, length_m: float, sample_period_s: float
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """IIR coefficients (b_theta, a, b_y, a) of the first-order-hold discretisation.

    ``lfilter(b_theta, a, v)`` gives theta_k and ``lfilter(b_y, a, v)`` gives
    y_k = theta'_k + v_k / L for velocity samples v_k starting from rest (v_0 = 0).
    """
    from scipy.signal import ss2tf  # lazily: keeps start-up short

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
    from scipy.signal import lfilter  # lazily: keeps start-up short

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
