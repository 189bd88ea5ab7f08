"""The small-angle slosh pendulums along a sampled path: the path program's linear model.

The 3-D simulation's linear model (`sloshkit.sim.spatial_kernels.linear_pendulums`, the
equations and their sources in `sloshkit.sim.spatial`): each lateral mode a 2-D linear
pendulum theta'' + c theta' + k theta = f_lat / L + (turning terms), k = -f_z / L, in the
container's non-spinning frame, the drive linear between samples and each sample period
discretised exactly (the oscillator's free and forced response over the period: Franklin,
Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998) §6.3). In the form of
`sloshkit.plan.path.pendulums.pendulum_track` (u = (theta, -1), u' = (theta', 0)), so that the
program's rows read it as they read the large-angle pendulums. `linear_period` steps many
states by the same kernel's period, which `sloshkit.plan.path.pendulums.step_jacobians`
differentiates.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
#: The pendulum kernels' arguments before the step (`kernel_arguments`).
KernelArguments = tuple[
    FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray
]


def kernel_arguments(
    force_m_s2: FloatArray,
    rest_force_m_s2: FloatArray,
    length_m: FloatArray,
    omega_rad_s: FloatArray,
    damping_ratio: FloatArray,
) -> KernelArguments:
    """The arguments of the simulation's pendulum kernels before the step
    (`sloshkit.sim.spatial_kernels.linear_pendulums` and ``nonlinear_pendulums``) from a drive
    in `pendulum_track`'s form: the specific force and its rest value, the frame's lateral
    angular velocity and its derivative (zero when the drive has no rates), and the modes'
    L_n, omega_n and zeta_n, each a C-contiguous float array.

    Parameters
    ----------
    force_m_s2 : numpy.ndarray
        (modes, K, 3), or (modes, K, 7) with the lateral angular velocity (p, q) [rad/s] and
        its derivative [rad/s^2] after the force (the same for every mode: the frame's).
    rest_force_m_s2 : numpy.ndarray
        The force at rest before the first sample (modes, 3).
    length_m, omega_rad_s, damping_ratio : numpy.ndarray
        The modes' L_n, omega_n and zeta_n.

    Returns
    -------
    tuple of numpy.ndarray
        force (modes, K, 3), rest force, angular velocity (K, 2), its derivative (K, 2),
        L_n, omega_n, zeta_n.

    Examples
    --------
    >>> import numpy as np
    >>> one = np.ones(2)
    >>> arguments = kernel_arguments(np.zeros((2, 5, 7)), np.zeros((2, 3)), one, one, one)
    >>> [a.shape for a in arguments[:4]]
    [(2, 5, 3), (2, 3), (5, 2), (5, 2)]
    """
    _, samples, width = force_m_s2.shape
    rates = force_m_s2[0, :, 3:] if width == 7 else np.zeros((samples, 4))
    return (
        np.ascontiguousarray(force_m_s2[..., :3]),
        rest_force_m_s2,
        np.ascontiguousarray(rates[:, :2]),
        np.ascontiguousarray(rates[:, 2:]),
        np.asarray(length_m, dtype=float),
        np.asarray(omega_rad_s, dtype=float),
        np.asarray(damping_ratio, dtype=float),
    )


def linear_track(
    force_m_s2: FloatArray,
    rest_force_m_s2: FloatArray,
    length_m: FloatArray,
    omega_rad_s: FloatArray,
    damping_ratio: FloatArray,
    sample_period_s: float,
) -> tuple[FloatArray, FloatArray]:
    """The small-angle pendulums along the samples, in the form of
    `sloshkit.plan.path.pendulums.pendulum_track`: u = (theta_x, theta_y, -1) and
    u' = (theta_x', theta_y', 0), so that the slope u_lat / (-u_z) the wall reads is theta.

    The linear model of the 3-D simulation (`sloshkit.sim.spatial_kernels.linear_pendulums`:
    theta'' + c theta' + k theta = f_lat / L with k = -f_z / L, the frame's turning terms
    linearised, the drive linear between samples, each period discretised exactly). Its
    response is linear in the drive, so the programs' linearisation of it holds over far
    longer steps than that of the large-angle pendulums, whose amplitude-dependent frequency
    turns the residual's phase (`sloshkit.plan.path.optimal` searches with it first).

    Parameters
    ----------
    force_m_s2, rest_force_m_s2, length_m, omega_rad_s, damping_ratio, sample_period_s
        As for `sloshkit.plan.path.pendulums.pendulum_track`.

    Returns
    -------
    tuple of numpy.ndarray
        u and u' at the samples, (modes, K, 3) each.

    Examples
    --------
    A constant lateral force 0.1 g: the pendulum settles at theta = 0.1 (the slope of the
    apparent gravity), as the large-angle one settles at atan(0.1).

    >>> import numpy as np
    >>> g = 9.81
    >>> force = np.tile([-0.1 * g, 0.0, -g], (1, 3000, 1))
    >>> unit, rate = linear_track(force, np.array([[0.0, 0.0, -g]]), np.array([0.01]),
    ...                           np.array([np.sqrt(g / 0.01)]), np.array([0.3]), 1e-3)
    >>> [round(float(x), 4) for x in unit[0, -1]]
    [-0.1, 0.0, -1.0]
    """
    from sloshkit.sim.spatial_kernels import linear_pendulums

    modes, samples, _ = force_m_s2.shape
    angle, angle_rate = linear_pendulums(
        *kernel_arguments(force_m_s2, rest_force_m_s2, length_m, omega_rad_s, damping_ratio),
        sample_period_s,
    )
    unit = np.concatenate((angle, -np.ones((modes, samples, 1))), axis=-1)
    return unit, np.concatenate((angle_rate, np.zeros((modes, samples, 1))), axis=-1)


def linear_period(
    unit: FloatArray,
    rate: FloatArray,
    start: FloatArray,
    end: FloatArray,
    length_m: FloatArray,
    damping: FloatArray,
    floor: FloatArray,
    sample_period_s: float,
) -> tuple[FloatArray, FloatArray]:
    """One sample period of `linear_track` from each of many states at once: the simulation's
    own step (`sloshkit.sim.spatial_numba.linear_step`) over broadcast arrays, which
    `sloshkit.plan.path.pendulums.step_jacobians` differentiates.

    Parameters
    ----------
    unit, rate : numpy.ndarray
        The states in `linear_track`'s form (..., 3).
    start, end : numpy.ndarray
        The drive at the period's start and end (..., 3) or (..., 7) (with the lateral
        angular velocity and its derivative).
    length_m, damping, floor : numpy.ndarray
        L_n [m], 2 zeta_n omega_n [1/s] and the stiffness floor 1e-3 omega_n^2 [1/s^2],
        broadcast to the states' leading axes.
    sample_period_s : float
        Sample period [s].

    Returns
    -------
    tuple of numpy.ndarray
        u and u' at the period's end, in `linear_track`'s form.

    Examples
    --------
    >>> import numpy as np
    >>> g = 9.81
    >>> force = np.tile([-0.1 * g, 0.0, -g], (1, 400, 1))
    >>> args = (np.array([0.01]), np.array([np.sqrt(g / 0.01)]), np.array([0.3]), 1e-3)
    >>> unit, rate = linear_track(force, np.array([[0.0, 0.0, -g]]), *args)
    >>> moved, _ = linear_period(unit[:, 9], rate[:, 9], force[:, 9], force[:, 10],
    ...                          np.array([0.01]), 2 * 0.3 * args[1], 1e-3 * args[1]**2, 1e-3)
    >>> bool(np.allclose(moved, unit[:, 10], rtol=0, atol=1e-15))
    True
    """
    from sloshkit.sim.spatial_kernels import kernels

    shape = unit.shape[:-1]
    width = start.shape[-1]
    drives = []
    for part in (start, end):
        full = np.zeros((*shape, 7))
        full[..., :width] = np.broadcast_to(part, (*shape, width))
        drives.append(full.reshape(-1, 7))
    state = np.concatenate((unit[..., :2], rate[..., :2]), axis=-1).reshape(-1, 4)
    stepped = kernels()["linear_periods"](
        state,
        drives[0],
        drives[1],
        np.broadcast_to(1.0 / np.asarray(length_m, dtype=float), shape).ravel().copy(),
        np.broadcast_to(np.asarray(damping, dtype=float), shape).ravel().copy(),
        np.broadcast_to(np.asarray(floor, dtype=float), shape).ravel().copy(),
        float(sample_period_s),
    ).reshape(*shape, 4)
    angle = np.concatenate((stepped[..., :2], -np.ones((*shape, 1))), axis=-1)
    return angle, np.concatenate((stepped[..., 2:], np.zeros((*shape, 1))), axis=-1)


__all__ = ["kernel_arguments", "linear_period", "linear_track"]
