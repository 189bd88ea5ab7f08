"""Compiled (numba) integrators of the 3-D slosh pendulums in the container's non-spinning frame.

Both kernels take the drive of `sloshkit.sim.spatial.spatial_drive` per mode: the specific
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


def _compile() -> dict[str, Any]:
    from sloshkit.sim import _spatial_numba as spatial_numba

    return {
        "linear": spatial_numba.linear,
        "linear_batch": spatial_numba.linear_batch,
        "nonlinear": spatial_numba.nonlinear,
        "step": spatial_numba.oscillator_step,
    }


def kernels() -> dict[str, Any]:
    """The compiled kernels (compiled on first use, cached on disk by numba)."""
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

    The stiffness is floored at 1e-3 omega_n^2 (apparent gravity along the axis reversed or
    nearly zero: the caller warns, the model is not valid there).
    """
    floor = 1e-3 * np.asarray(omega, dtype=float) ** 2
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
    """Spherical pendulums: unit vectors u and u' (modes, steps, 3), drive on the half grid."""
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
