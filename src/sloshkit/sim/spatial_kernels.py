"""Compiled (numba) integrators of the 3-D slosh pendulums in the container's non-spinning frame.

Both kernels take the drive of `sloshkit.sim.spatial_drive.spatial_drive` per mode: the specific
force f (3 components, non-spinning frame N), and the lateral angular velocity Omega = (p, q)
of N and its derivative.

Linear kernel
-------------
theta'' + 2 zeta omega theta' + K theta = u, with K = (-f_z / L) I + Omega Omega^T and
u = f_lat / L + (q', -p'). Over each step the coefficients are frozen at the step's midpoint
and u is linear in time (first-order hold); K is symmetric with eigenvectors along Omega and
perpendicular to it, so the step is two scalar damped oscillators solved in closed form
(homogeneous solution plus the exact particular solution of a ramp). This is the exact
discretisation for constant coefficients (Franklin, Powell & Workman, *Digital Control of
Dynamic Systems*, 3rd ed., §6.3) and second-order accurate for the parametric variation.

Nonlinear kernel
----------------
The spherical pendulum as a unit vector u (hinge to bob) with the constraint force
eliminated: u'' = (F - (u.F) u) / L - |u'|^2 u, F = f - Omega' x rho - Omega x (Omega x rho)
- 2 Omega x rho' - c rho', rho = L u (relative motion in a non-inertial frame: Goldstein,
*Classical Mechanics*, 3rd ed. §4.10; constrained form: Hairer, Lubich & Wanner, *Geometric
Numerical Integration* §VII.1). Classical fourth-order Runge-Kutta with the drive given on a
half-step grid; u is renormalised and u' made tangent after every step.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

_KERNELS: dict[str, Any] = {}
#: The linear pendulums' stiffness -f_z / L is floored at this fraction of omega_n^2 (apparent
#: gravity along the axis reversed or nearly zero: the caller warns, the model is not valid
#: there).
STIFFNESS_FLOOR = 1e-3
#: The modes that the nonlinear model simulates as large-angle spherical pendulums: the first.
#: The large-angle pendulum models the fundamental mode's finite-amplitude (softening, rotary)
#: slosh; the higher modes of the equivalent model are linear oscillators (their pendulum
#: parameters come from linear theory, and the multimodal theory carries them at a higher order
#: of the amplitude: Faltinsen & Timokha, *Sloshing*, Cambridge University Press (2009) ch. 8-9).
#: Their short pendulums (L_2 = 9 mm, L_3 = 6 mm for R = 49 mm) swing past 50 deg under the
#: optimal plans' jerks, where tan(deflection) would read a wall height that jumps with the
#: timing (studies/path-planner-methods, "The higher modes").
LARGE_ANGLE_MODES = 1


def _compile() -> dict[str, Any]:
    from sloshkit.sim import spatial_numba

    return {
        "linear": spatial_numba.linear,
        "linear_batch": spatial_numba.linear_batch,
        "linear_periods": spatial_numba.linear_periods,
        "linear_amplitude": spatial_numba.linear_amplitude,
        "nonlinear": spatial_numba.nonlinear,
        "step": spatial_numba.oscillator_step,
    }


def kernels() -> dict[str, Any]:
    """The compiled kernels (compiled on first use, cached on disk by numba).

    Returns
    -------
    dict
        linear, linear_batch, linear_amplitude, linear_periods, nonlinear and step: the
        numba functions behind `linear_pendulums`, `nonlinear_pendulums`,
        `sloshkit.sim.spatial_batch`, `sloshkit.sim.spatial_amplitude` and
        `sloshkit.plan.path.small_angle.linear_period`.

    Examples
    --------
    >>> sorted(kernels())
    ['linear', 'linear_amplitude', 'linear_batch', 'linear_periods', 'nonlinear', 'step']
    """
    if not _KERNELS:
        _KERNELS.update(_compile())
    return _KERNELS


def linear_pendulums(
    force: FloatArray,
    rest_force: FloatArray,
    tilt_rate: FloatArray,
    tilt_accel: FloatArray,
    length: FloatArray,
    omega: FloatArray,
    zeta: FloatArray,
    sample_period_s: float,
) -> tuple[FloatArray, FloatArray]:
    """Linear 2-D pendulum angles and rates (modes, steps, 2) in the non-spinning frame.

    ``rest_force`` (modes, 3): the specific force of the container at rest in its first pose;
    the pendulums start in its equilibrium (the container rests before the first pose).

    The stiffness is floored at `STIFFNESS_FLOOR` omega_n^2 (apparent gravity along the axis
    reversed or nearly zero: the caller warns, the model is not valid there).

    Parameters
    ----------
    force : numpy.ndarray
        Specific force at each mode's hinge (modes, steps, 3) in the non-spinning frame
        [m/s^2] (`sloshkit.sim.spatial_drive.SpatialDrive`).
    rest_force : numpy.ndarray
        The same at rest in the first pose (modes, 3).
    tilt_rate, tilt_accel : numpy.ndarray
        Lateral angular velocity (steps, 2) [rad/s] and its derivative [rad/s^2].
    length, omega, zeta : numpy.ndarray
        The modes' L_n [m], omega_n [rad/s] and damping ratios.
    sample_period_s : float
        Step [s].

    Returns
    -------
    tuple of numpy.ndarray
        Angles [rad] and rates [rad/s].

    References
    ----------
    The equations: `sloshkit.sim.spatial`; the exact discretisation of the linear oscillator:
    `sloshkit.sim.discretisation`.

    Examples
    --------
    A constant lateral acceleration a = 0.1 g tilts the pendulum to theta = -a/g:

    >>> import numpy as np
    >>> steps, g = 1000, 9.81
    >>> force = np.tile([-0.1 * g, 0.0, -g], (1, steps, 1))
    >>> still = np.zeros((steps, 2))
    >>> angle, rate = linear_pendulums(force, np.array([[0.0, 0.0, -g]]), still, still,
    ...                                np.array([0.01]), np.array([np.sqrt(g / 0.01)]),
    ...                                np.array([0.3]), 1e-3)
    >>> angle[0, -1].round(4).tolist()
    [-0.1, 0.0]
    """
    floor = STIFFNESS_FLOOR * np.asarray(omega, dtype=float) ** 2
    angle, rate = kernels()["linear"](
        np.ascontiguousarray(force),
        np.ascontiguousarray(rest_force),
        np.ascontiguousarray(tilt_rate),
        np.ascontiguousarray(tilt_accel),
        np.asarray(length, dtype=float),
        np.asarray(omega, dtype=float),
        np.asarray(zeta, dtype=float),
        floor,
        float(sample_period_s),
    )
    return np.asarray(angle, dtype=float), np.asarray(rate, dtype=float)


def nonlinear_pendulums(
    force_half: FloatArray,
    rest_force: FloatArray,
    tilt_rate_half: FloatArray,
    tilt_accel_half: FloatArray,
    length: FloatArray,
    omega: FloatArray,
    zeta: FloatArray,
    sample_period_s: float,
) -> tuple[FloatArray, FloatArray]:
    """Spherical pendulums: unit vectors u and u' (modes, steps, 3), drive on the half grid.

    Parameters
    ----------
    force_half : numpy.ndarray
        Specific force at each mode's hinge on the half-step grid (modes, 2 steps - 1, 3)
        [m/s^2].
    rest_force : numpy.ndarray
        The same at rest in the first pose (modes, 3).
    tilt_rate_half, tilt_accel_half : numpy.ndarray
        Lateral angular velocity (2 steps - 1, 2) [rad/s] and its derivative, half-step grid.
    length, omega, zeta : numpy.ndarray
        The modes' L_n [m], omega_n [rad/s] and damping ratios.
    sample_period_s : float
        Step [s] (classical Runge-Kutta).

    Returns
    -------
    tuple of numpy.ndarray
        Unit vectors along the pendulums and their rates [1/s].

    References
    ----------
    The equations: `sloshkit.sim.spatial`.

    Examples
    --------
    A constant lateral acceleration 0.1 g: the large-angle pendulum hangs along the apparent
    gravity, at atan(0.1) from the axis.

    >>> import numpy as np
    >>> steps, g = 1000, 9.81
    >>> force = np.tile([-0.1 * g, 0.0, -g], (1, 2 * steps - 1, 1))
    >>> still = np.zeros((2 * steps - 1, 2))
    >>> unit, rate = nonlinear_pendulums(force, np.array([[0.0, 0.0, -g]]), still, still,
    ...                                  np.array([0.01]), np.array([np.sqrt(g / 0.01)]),
    ...                                  np.array([0.3]), 1e-3)
    >>> swing = float(np.arctan2(-unit[0, -1, 0], -unit[0, -1, 2]))
    >>> round(swing, 4), round(float(np.arctan(0.1)), 4)
    (0.0997, 0.0997)
    """
    unit, velocity = kernels()["nonlinear"](
        np.ascontiguousarray(force_half),
        np.ascontiguousarray(rest_force),
        np.ascontiguousarray(tilt_rate_half),
        np.ascontiguousarray(tilt_accel_half),
        np.asarray(length, dtype=float),
        np.asarray(omega, dtype=float),
        np.asarray(zeta, dtype=float),
        float(sample_period_s),
    )
    return np.asarray(unit, dtype=float), np.asarray(velocity, dtype=float)
