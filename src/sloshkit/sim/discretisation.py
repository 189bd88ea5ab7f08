"""Exact discretisation of the linear pendulum driven by the container's velocity.

The linear equation is rewritten with y = theta' + v/L so that it is driven by the container's
velocity v (continuous for every rest-to-rest law) instead of its acceleration:
theta' = y - v/L, y' = -omega^2 theta - 2 zeta omega (y - v/L). It is discretised exactly for a
velocity that is linear between samples (first-order hold, Franklin, Powell & Workman, *Digital
Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2): exact for the trapezoidal law and
second-order accurate for the others. The resulting two-state recursion is run in the
eigenbasis of its transition matrix as cumulative sums in numpy (`run_recursion`), vectorised
over any number of cases that share a mode; importing `scipy.signal` for ``lfilter`` would
cost more than a whole plan.
"""

from __future__ import annotations

import math
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


#: Largest growth of the scaled terms of one block of `run_recursion` (|lambda|^-block).
_BLOCK_GROWTH = 1e40
#: Condition number of the eigenvector matrix above which `run_recursion` filters instead.
_WORST_EIGENBASIS = 1e4


def run_recursion(
    phi: FloatArray, gamma: FloatArray, g1: FloatArray, inputs: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Both outputs s_k = z_k + g1 u_k of z_{k+1} = phi z_k + gamma u_k, z_0 = 0.

    Diagonalising phi = V diag(lambda) V^-1 turns the recursion into two first-order ones,
    w_k = sum_{j<k} lambda^(k-1-j) c u_j with c = V^-1 gamma, evaluated as
    lambda^k cumsum(lambda^-(j+1) c u_j) in blocks short enough that lambda^-j stays below
    `_BLOCK_GROWTH` (the scaled terms grow monotonically, so each block's sum keeps full
    relative precision). Near critical damping the eigenbasis is ill-conditioned (a repeated
    eigenvalue has none): the recursion then runs as an IIR filter (`scipy.signal.lfilter`).

    Parameters
    ----------
    phi : numpy.ndarray
        Transition matrix (2, 2).
    gamma, g1 : numpy.ndarray
        Input vectors (2,) of `velocity_driven_discretisation`.
    inputs : numpy.ndarray
        Samples u_k on the last axis (any leading shape).

    Returns
    -------
    tuple of numpy.ndarray
        The two components of s_k, each with the shape of ``inputs``.

    References
    ----------
    Franklin, Powell & Workman (1998) §6.3 (the discrete state equation and its modal form).

    Examples
    --------
    >>> phi = np.array([[0.5, 0.0], [0.0, 0.25]])
    >>> first, second = run_recursion(phi, np.array([1.0, 1.0]), np.zeros(2), np.ones(3))
    >>> first.tolist(), second.tolist()
    ([0.0, 1.0, 1.5], [0.0, 1.0, 1.25])
    """
    u = np.asarray(inputs, dtype=float)
    basis = _eigenbasis(
        np.asarray(phi, dtype=float).tobytes(), np.asarray(gamma, dtype=float).tobytes()
    )
    if basis is None:
        return _filtered(phi, gamma, g1, u)
    eigenvalues, vectors, coefficients = basis
    count = u.shape[-1]
    smallest = float(np.min(np.abs(eigenvalues)))
    decay = -math.log(max(smallest, 1e-300))
    block = count if decay <= 0.0 else max(1, int(math.log(_BLOCK_GROWTH) / decay))
    # A complex pair's second modal coordinate is the conjugate of the first: one suffices.
    pair = abs(eigenvalues[0].imag) > 0.0
    modes = 1 if pair else 2
    modal = np.zeros((modes, *u.shape), dtype=complex)
    carried = np.zeros((modes, *u.shape[:-1]), dtype=complex)
    for start in range(0, count - 1, block):
        stop = min(start + block, count - 1)  # inputs u_start..u_stop-1 give w_start+1..w_stop
        steps = np.arange(1, stop - start + 1)
        for mode in range(modes):
            growth = np.exp(steps * np.log(eigenvalues[mode]))
            terms = u[..., start:stop] * (coefficients[mode] / growth)
            modal[mode, ..., start + 1 : stop + 1] = growth * (
                carried[mode][..., None] + np.cumsum(terms, axis=-1)
            )
            carried[mode] = modal[mode, ..., stop]
    if pair:
        first = 2.0 * (vectors[0, 0] * modal[0]).real
        second = 2.0 * (vectors[1, 0] * modal[0]).real
    else:
        first = (vectors[0, 0] * modal[0] + vectors[0, 1] * modal[1]).real
        second = (vectors[1, 0] * modal[0] + vectors[1, 1] * modal[1]).real
    return first + g1[0] * u, second + g1[1] * u


@lru_cache(maxsize=256)
def _eigenbasis(
    phi_bytes: bytes, gamma_bytes: bytes
) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]] | None:
    """(eigenvalues, eigenvectors V, V^-1 gamma) of a 2x2 transition matrix and its input
    (given as bytes, so that the planner's many recursions of one mode share them), or None
    when V is ill-conditioned (`_WORST_EIGENBASIS`)."""
    phi = np.frombuffer(phi_bytes, dtype=float).reshape(2, 2)
    gamma = np.frombuffer(gamma_bytes, dtype=float)
    eigenvalues, vectors = np.linalg.eig(phi)
    if np.linalg.cond(vectors) > _WORST_EIGENBASIS:
        return None
    return eigenvalues, vectors, np.linalg.solve(vectors, gamma.astype(complex))


def _filtered(
    phi: FloatArray, gamma: FloatArray, g1: FloatArray, u: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """`run_recursion` as an IIR filter (`scipy.signal.lfilter`), for a transition matrix
    whose eigenbasis is ill-conditioned (damping ratio near 1)."""
    from scipy.signal import lfilter, ss2tf  # only here: importing scipy.signal is slow

    outputs = []
    for row in range(2):
        selector = np.zeros((1, 2))
        selector[0, row] = 1.0
        b, a = ss2tf(phi, gamma[:, None], selector, np.array([[g1[row]]]))
        outputs.append(np.asarray(lfilter(b[0], a, u, axis=-1), dtype=float))
    return outputs[0], outputs[1]


def linear_mode_response(
    velocity_m_s: FloatArray,
    sample_period_s: float,
    omega_rad_s: float,
    damping_ratio: float,
    length_m: float,
) -> tuple[FloatArray, FloatArray]:
    """Angle and angular rate of one linear mode for velocity samples (last axis = time).

    The exact first-order-hold discretisation (`velocity_driven_discretisation`) run by
    `run_recursion`.

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
    phi, gamma, g1 = velocity_driven_discretisation(
        float(omega_rad_s), float(damping_ratio), float(length_m), float(sample_period_s)
    )
    theta, y = run_recursion(phi, gamma, g1, velocity_m_s)
    rate = y - np.asarray(velocity_m_s, dtype=float) / length_m
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
