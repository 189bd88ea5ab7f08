"""The nonlinear slosh pendulums along a sampled path, and their linearisation along it.

The path program (`sloshkit.plan.path.optimal`) imposes its slosh limits on the model the
verification simulates: the first lateral mode a damped spherical pendulum of length L_n,
driven by the specific force f at its hinge in the container's non-spinning frame N,
integrated by the classical Runge-Kutta method on the drive's half-step grid
(`sloshkit.sim.spatial`, the equations and their sources;
`sloshkit.sim.spatial_kernels.nonlinear_pendulums`, the integrator), the higher modes the
small-angle pendulums of the same drive (`sloshkit.plan.path.small_angle.linear_track`;
`sloshkit.sim.spatial_kernels.LARGE_ANGLE_MODES`). Here the drive is the sampled one: f at
the export samples, linear between them
(a first-order hold, as the program's finite-difference kinematics give it).

`pendulum_track` integrates the pendulums along the samples with that kernel. `step_jacobians`
differentiates one sample period of the same integrator, x_{k+1} = Phi(x_k, f_k, f_{k+1}) with
x = (u, u') (unit vector along the rod and its rate), by forward differences vectorised over
all samples at once, so that along a track the deviations obey the time-varying linear system

    dx_{k+1} = A_k dx_k + B_k df_k + E_k df_{k+1}

(the linearisation of a discretised trajectory, as in sequential convex programming: Mao, Szmuk
& Acikmese, IEEE CDC (2016), doi:10.1109/CDC.2016.7798816). `slope_jacobian` is the derivative
of the surface slope tan(deflection) = u_lat / (-u_z) that the wall height reads
(`sloshkit.sim.spatial_response.SpatialResponse.mode_slope`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.plan.path.small_angle import kernel_arguments, linear_period, linear_track
from sloshkit.sim.spatial_kernels import LARGE_ANGLE_MODES, STIFFNESS_FLOOR

FloatArray = NDArray[np.float64]

#: Largest omega_n h of one Runge-Kutta step (the rule of `sloshkit.sim.spatial.simulate_spatial`).
MAX_OMEGA_STEP = 0.5
#: Forward-difference steps of the state (u, u') and of the force [m/s^2].
_STATE_STEP, _FORCE_STEP = 1e-6, 1e-5


def rk4_substeps(omegas_rad_s: Sequence[float], sample_period_s: float) -> int:
    """Runge-Kutta steps per sample period: omega_max h <= `MAX_OMEGA_STEP` (accurate, far
    inside the classical method's stability limit 2.8; Hairer, Norsett & Wanner, *Solving
    Ordinary Differential Equations I*, 2nd ed. (1993) §II.1).

    Parameters
    ----------
    omegas_rad_s : sequence of float
        The modes' natural frequencies [rad/s].
    sample_period_s : float
        Sample period [s].

    Returns
    -------
    int
        Steps per sample period (at least 1).

    Examples
    --------
    >>> rk4_substeps([19.2, 41.3], 0.004), rk4_substeps([19.2, 41.3], 0.02)
    (1, 2)
    """
    return max(1, math.ceil(max(omegas_rad_s) * sample_period_s / MAX_OMEGA_STEP))


def _split_by_angle(
    call: Callable[..., tuple[FloatArray, ...]], per_mode: Sequence[Any], large: int
) -> tuple[FloatArray, ...]:
    """``call(*arrays, small_angle)`` with the ``per_mode`` arrays of the first ``large`` modes
    (large-angle) and of the rest (small-angle: the higher modes of the nonlinear model,
    `LARGE_ANGLE_MODES`), each output joined along the mode axis."""
    arrays = [np.asarray(array) for array in per_mode]
    parts = (
        call(*(array[:large] for array in arrays), False),
        call(*(array[large:] for array in arrays), True),
    )
    return tuple(np.concatenate(pieces) for pieces in zip(*parts, strict=True))


def pendulum_track(
    force_m_s2: FloatArray,
    rest_force_m_s2: FloatArray,
    length_m: FloatArray,
    omega_rad_s: FloatArray,
    damping_ratio: FloatArray,
    sample_period_s: float,
    linear: bool = False,
) -> tuple[FloatArray, FloatArray]:
    """The pendulums' unit vectors u and rates u' at the samples, (modes, K, 3) each: the
    first `LARGE_ANGLE_MODES` large-angle, the others small-angle
    (`sloshkit.plan.path.small_angle.linear_track`: u = (theta, -1), u' = (theta', 0)), as the
    verification simulates them; with ``linear`` all small-angle.

    Parameters
    ----------
    force_m_s2 : numpy.ndarray
        Specific force at each mode's hinge in N at the samples, (modes, K, 3) [m/s^2], linear
        between them; or (modes, K, 7) with the lateral angular velocity (p, q) of N [rad/s]
        and its derivative [rad/s^2] after it (the same for every mode).
    rest_force_m_s2 : numpy.ndarray
        The same at rest before the first sample (modes, 3): the pendulums start at rest
        along it.
    length_m, omega_rad_s, damping_ratio : numpy.ndarray
        The modes' L_n, omega_n and zeta_n.
    sample_period_s : float
        Sample period [s].
    linear : bool
        Whether the pendulums are the small-angle ones
        (`sloshkit.plan.path.small_angle.linear_track`).

    Returns
    -------
    tuple of numpy.ndarray
        u and u' [1/s] at the samples.

    Examples
    --------
    A constant lateral force 0.1 g from the first sample: the damped pendulum settles along
    the apparent gravity, atan(0.1) from the axis.

    >>> import numpy as np
    >>> g = 9.81
    >>> force = np.tile([-0.1 * g, 0.0, -g], (1, 3000, 1))
    >>> unit, rate = pendulum_track(force, np.array([[0.0, 0.0, -g]]), np.array([0.01]),
    ...                             np.array([np.sqrt(g / 0.01)]), np.array([0.3]), 1e-3)
    >>> swing = float(np.arctan2(-unit[0, -1, 0], -unit[0, -1, 2]))
    >>> round(swing, 4), round(float(np.arctan(0.1)), 4)
    (0.0997, 0.0997)
    """
    from sloshkit.sim.spatial_kernels import nonlinear_pendulums

    large = force_m_s2.shape[0] if linear else LARGE_ANGLE_MODES
    if 0 < large < force_m_s2.shape[0]:
        unit, rate = _split_by_angle(
            lambda f, rest, length, omega, zeta, small: pendulum_track(
                f, rest, length, omega, zeta, sample_period_s, small
            ),
            (force_m_s2, rest_force_m_s2, length_m, omega_rad_s, damping_ratio),
            large,
        )
        return unit, rate
    if linear:
        return linear_track(
            force_m_s2, rest_force_m_s2, length_m, omega_rad_s, damping_ratio, sample_period_s
        )
    modes, samples, width = force_m_s2.shape
    substeps = rk4_substeps(list(omega_rad_s), sample_period_s)
    fractions = np.arange(2 * substeps) / (2 * substeps)
    start, end = force_m_s2[:, :-1], force_m_s2[:, 1:]
    half = start[:, :, None] + fractions[None, None, :, None] * (end - start)[:, :, None]
    half = np.concatenate((half.reshape(modes, -1, width), force_m_s2[:, -1:]), axis=1)
    unit, rate = nonlinear_pendulums(
        *kernel_arguments(half, rest_force_m_s2, length_m, omega_rad_s, damping_ratio),
        sample_period_s / substeps,
    )
    return unit[:, ::substeps][:, :samples], rate[:, ::substeps][:, :samples]


def at_rest(force_m_s2: FloatArray, linear: bool = False, mode: int = 0) -> FloatArray:
    """The lateral components of u at rest under a constant specific force: along it,
    f_lat / |f|, for the large-angle pendulums, f_lat / (-f_z) for the small-angle ones.

    Parameters
    ----------
    force_m_s2 : numpy.ndarray
        The specific force (..., 3) [m/s^2].
    linear : bool
        Whether the pendulums are the small-angle ones.
    mode : int
        The mode's index: from `LARGE_ANGLE_MODES` on, the modes are small-angle anyway
        (`pendulum_track`).

    Returns
    -------
    numpy.ndarray
        (..., 2).

    Examples
    --------
    >>> import numpy as np
    >>> force = np.array([-0.981, 0.0, -9.81])
    >>> round(float(at_rest(force)[0]), 5), round(float(at_rest(force, True)[0]), 5)
    (-0.0995, -0.1)
    """
    small = linear or mode >= LARGE_ANGLE_MODES
    scale = -force_m_s2[..., 2:3] if small else np.linalg.norm(force_m_s2, axis=-1, keepdims=True)
    return np.asarray(force_m_s2[..., :2] / scale)


def _rhs(
    u: FloatArray, v: FloatArray, f: FloatArray, length: FloatArray, c: FloatArray
) -> FloatArray:
    """u'' of the damped spherical pendulum in N (`sloshkit.sim.spatial_numba.pendulum_rhs`):
    the force across the rod over L, minus the centripetal |u'|^2 u. The drive ``f`` is the
    specific force (3 components) or the specific force, the lateral angular velocity (p, q)
    of N and its derivative (7): F = f - Omega' x rho - Omega x (Omega x rho)
    - 2 Omega x rho' - c rho' with rho = L u, Omega = (p, q, 0) (Goldstein, *Classical
    Mechanics*, 3rd ed. (2002) §4.10)."""
    rod, rod_rate = length[..., None] * u, length[..., None] * v
    force = f[..., :3] - c[..., None] * rod_rate
    if f.shape[-1] == 7:
        zero = np.zeros((*f.shape[:-1], 1))
        spin = np.concatenate((f[..., 3:5], zero), axis=-1)
        spin_rate = np.concatenate((f[..., 5:7], zero), axis=-1)
        force = (
            force
            - np.cross(spin_rate, rod)
            - np.cross(spin, np.cross(spin, rod))
            - 2.0 * np.cross(spin, rod_rate)
        )
    radial = np.sum(u * force, axis=-1, keepdims=True)
    speed2 = np.sum(v * v, axis=-1, keepdims=True)
    return np.asarray((force - radial * u) / length[..., None] - speed2 * u)


def _period(
    u: FloatArray,
    v: FloatArray,
    f0: FloatArray,
    f1: FloatArray,
    length: FloatArray,
    c: FloatArray,
    h: float,
    substeps: int,
) -> tuple[FloatArray, FloatArray]:
    """One sample period of the kernel's integrator: ``substeps`` classical Runge-Kutta steps
    of h with the force linear from f0 to f1, each followed by the kernel's projection back
    onto the sphere (|u| = 1, u' normal to u). Vectorised over leading axes."""
    for sub in range(substeps):
        fa = f0 + (sub / substeps) * (f1 - f0)
        fb = f0 + ((sub + 0.5) / substeps) * (f1 - f0)
        fe = f0 + ((sub + 1.0) / substeps) * (f1 - f0)
        k1v = _rhs(u, v, fa, length, c)
        u2, v2 = u + 0.5 * h * v, v + 0.5 * h * k1v
        k2v = _rhs(u2, v2, fb, length, c)
        u3, v3 = u + 0.5 * h * v2, v + 0.5 * h * k2v
        k3v = _rhs(u3, v3, fb, length, c)
        u4, v4 = u + h * v3, v + h * k3v
        k4v = _rhs(u4, v4, fe, length, c)
        u = u + h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4)
        v = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
        u = u / np.linalg.norm(u, axis=-1, keepdims=True)
        v = v - np.sum(u * v, axis=-1, keepdims=True) * u
    return u, v


def step_jacobians(
    unit: FloatArray,
    rate: FloatArray,
    force_m_s2: FloatArray,
    length_m: FloatArray,
    omega_rad_s: FloatArray,
    damping_ratio: FloatArray,
    sample_period_s: float,
    linear: bool = False,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A_k, B_k, E_k of every sample period along a track (module docstring): `pendulum_track`'s
    first `LARGE_ANGLE_MODES` large-angle, the others small-angle; with ``linear`` all
    small-angle (`sloshkit.plan.path.small_angle.linear_track`'s).

    Parameters
    ----------
    unit, rate, force_m_s2 : numpy.ndarray
        The track (`pendulum_track`) and its drive, (modes, K, 3) each (the drive (modes, K,
        7) with the tilt rates).
    length_m, omega_rad_s, damping_ratio : numpy.ndarray
        The modes' L_n, omega_n, zeta_n.
    sample_period_s : float
        Sample period [s].
    linear : bool
        Whether the track is `sloshkit.plan.path.small_angle.linear_track`'s.

    Returns
    -------
    tuple of numpy.ndarray
        A (modes, K - 1, 6, 6): d x_{k+1} / d x_k; B and E (modes, K - 1, 6, W): d x_{k+1} /
        d f_k and / d f_{k+1} for a drive of width W; x = (u, u').

    Examples
    --------
    Against a finite difference of two tracks: a small force change at one sample moves the
    states as the linear system predicts.

    >>> import numpy as np
    >>> g, ts = 9.81, 0.004
    >>> t = np.arange(200) * ts
    >>> force = np.zeros((1, 200, 3)); force[0, :, 2] = -g; force[0, :, 0] = -3 * np.sin(6 * t)
    >>> args = (np.array([0.02]), np.array([np.sqrt(g / 0.02)]), np.array([0.01]), ts)
    >>> unit, rate = pendulum_track(force, np.array([[0.0, 0.0, -g]]), *args)
    >>> a, b, e = step_jacobians(unit, rate, force, *args)
    >>> df = np.array([1e-3, 0.0, 0.0])
    >>> moved = force.copy(); moved[0, 100] += df
    >>> unit2, rate2 = pendulum_track(moved, np.array([[0.0, 0.0, -g]]), *args)
    >>> dx = a[0, 100] @ (e[0, 99] @ df) + b[0, 100] @ df
    >>> for k in range(101, 150):
    ...     dx = a[0, k] @ dx
    >>> exact = np.concatenate((unit2[0, 150] - unit[0, 150], rate2[0, 150] - rate[0, 150]))
    >>> bool(np.allclose(dx, exact, rtol=0, atol=1e-3 * np.abs(exact).max()))
    True
    """
    modes, samples, _ = unit.shape
    large = modes if linear else LARGE_ANGLE_MODES
    if 0 < large < modes:
        a_k, b_k, e_k = _split_by_angle(
            lambda u, v, f, length, omega, zeta, small: step_jacobians(
                u, v, f, length, omega, zeta, sample_period_s, small
            ),
            (unit, rate, force_m_s2, length_m, omega_rad_s, damping_ratio),
            large,
        )
        return a_k, b_k, e_k
    substeps = rk4_substeps(list(omega_rad_s), sample_period_s)
    h = sample_period_s / substeps
    length = np.broadcast_to(np.asarray(length_m, dtype=float)[:, None], (modes, samples - 1))
    c = np.broadcast_to(
        (2.0 * np.asarray(damping_ratio) * np.asarray(omega_rad_s))[:, None],
        (modes, samples - 1),
    )
    width = force_m_s2.shape[-1]
    base = (unit[:, :-1], rate[:, :-1], force_m_s2[:, :-1], force_m_s2[:, 1:])
    # the unperturbed period and each input direction (u, u', drive_k, drive_{k+1}) moved
    # forward, all at once along axis 2 (one-sided differences: the programs re-evaluate
    # every step exactly, and their error, ~1e-6 relative, is far below the trust regions')
    sizes = (3, 3, width, width)
    count = sum(sizes)
    inputs = [np.repeat(part[:, :, None], count + 1, axis=2).copy() for part in base]
    steps = np.repeat([_STATE_STEP, _STATE_STEP, _FORCE_STEP, _FORCE_STEP], sizes)
    direction = 0
    for block, size in enumerate(sizes):
        for component in range(size):
            inputs[block][:, :, direction + 1, component] += steps[direction]
            direction += 1
    if linear:
        floor = STIFFNESS_FLOOR * np.asarray(omega_rad_s, dtype=float)[:, None, None] ** 2
        u, v = linear_period(
            inputs[0],
            inputs[1],
            inputs[2],
            inputs[3],
            length[..., None],
            c[..., None],
            floor,
            sample_period_s,
        )
    else:
        u, v = _period(
            inputs[0],
            inputs[1],
            inputs[2],
            inputs[3],
            length[..., None],
            c[..., None],
            h,
            substeps,
        )
    state = np.concatenate((u, v), axis=-1)  # (modes, K - 1, count + 1, 6)
    jac = (state[:, :, 1:] - state[:, :, :1]) / steps[None, None, :, None]
    jac = np.swapaxes(jac, 2, 3)  # (modes, K - 1, 6 outputs, count inputs)
    return jac[..., :6], jac[..., 6 : 6 + width], jac[..., 6 + width :]


def slope_jacobian(unit: FloatArray) -> FloatArray:
    """d (u_lat / (-u_z)) / d u: the derivative of the surface slope tan(deflection) of
    `sloshkit.sim.spatial_response.SpatialResponse.mode_slope` (its cap at 84 deg ignored).

    Parameters
    ----------
    unit : numpy.ndarray
        Pendulum unit vectors u (..., 3), hanging (u_z < 0).

    Returns
    -------
    numpy.ndarray
        (..., 2, 3).

    Examples
    --------
    Against a central difference at 20 deg:

    >>> import numpy as np
    >>> u = np.array([np.sin(0.35), 0.0, -np.cos(0.35)])
    >>> step = np.array([0.0, 0.0, 1e-7])
    >>> numeric = (mode_slope(u + step) - mode_slope(u - step)) / 2e-7
    >>> bool(np.allclose(slope_jacobian(u)[:, 2], numeric))
    True
    """
    axial = -unit[..., 2]
    out = np.zeros((*unit.shape[:-1], 2, 3))
    out[..., 0, 0] = out[..., 1, 1] = 1.0 / axial
    out[..., :, 2] = unit[..., :2] / (axial**2)[..., None]
    return out


def mode_slope(unit: FloatArray) -> FloatArray:
    """The surface slope tan(deflection) = u_lat / (-u_z) of each pendulum, capped at 84 deg
    as `sloshkit.sim.spatial_response.SpatialResponse.mode_slope` caps it.

    Parameters
    ----------
    unit : numpy.ndarray
        Pendulum unit vectors u (..., 3).

    Returns
    -------
    numpy.ndarray
        (..., 2).

    Examples
    --------
    >>> import numpy as np
    >>> slope = mode_slope(np.array([np.sin(0.3), 0.0, -np.cos(0.3)]))
    >>> round(float(slope[0]), 6) == round(float(np.tan(0.3)), 6)
    True
    """
    return np.asarray(unit[..., :2] / np.maximum(-unit[..., 2], 0.1)[..., None], dtype=float)
