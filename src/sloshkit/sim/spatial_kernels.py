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


def _compile() -> dict[str, Any]:
    from numba import njit

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def transition(k, c, h):  # type: ignore[no-untyped-def]
        """cos- and sin-like terms of x'' + c x' + k x = 0 over one step h."""
        s2 = k - 0.25 * c * c
        if s2 > 1e-12 * k:
            s = np.sqrt(s2)
            return np.cos(s * h), np.sin(s * h) / s
        if s2 < -1e-12 * k:
            s = np.sqrt(-s2)
            return np.cosh(s * h), np.sinh(s * h) / s
        return 1.0, h

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def oscillator_step(x0, v0, u0, u1, k, c, h, cos_term, sin_term, decay):  # type: ignore[no-untyped-def]
        """x'' + c x' + k x = u0 + (u1 - u0) tau / h over one step h (k > 0); the transition
        terms come from `transition`, decay = exp(-c h / 2)."""
        slope = (u1 - u0) / h
        xp0 = u0 / k - c * slope / (k * k)
        xp1 = u1 / k - c * slope / (k * k)
        vp = slope / k
        y0 = x0 - xp0
        w0 = v0 - vp
        y1 = decay * (y0 * (cos_term + 0.5 * c * sin_term) + w0 * sin_term)
        w1 = decay * (w0 * (cos_term - 0.5 * c * sin_term) - y0 * k * sin_term)
        return y1 + xp1, w1 + vp

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def linear_step(tx, ty, vx, vy, fa, fb, ra, rb, aa, ab, inv_l, c, floor, h):  # type: ignore[no-untyped-def]
        """One step of the 2-D linear pendulum: coefficients at the midpoint, forcing FOH."""
        km = 0.5 * (max(-fa[2] * inv_l, floor) + max(-fb[2] * inv_l, floor))
        pm = 0.5 * (ra[0] + rb[0])
        qm = 0.5 * (ra[1] + rb[1])
        spin = np.sqrt(pm * pm + qm * qm)
        if spin > 1e-12:
            e1x = pm / spin
            e1y = qm / spin
        else:
            e1x = 1.0
            e1y = 0.0
        e2x = -e1y
        e2y = e1x
        uax = fa[0] * inv_l + aa[1]
        uay = fa[1] * inv_l - aa[0]
        ubx = fb[0] * inv_l + ab[1]
        uby = fb[1] * inv_l - ab[0]
        decay = np.exp(-0.5 * c * h)
        cos2, sin2 = transition(km, c, h)
        if spin > 1e-12:
            cos1, sin1 = transition(km + spin * spin, c, h)
        else:
            cos1, sin1 = cos2, sin2
        x1, w1 = oscillator_step(
            tx * e1x + ty * e1y,
            vx * e1x + vy * e1y,
            uax * e1x + uay * e1y,
            ubx * e1x + uby * e1y,
            km + spin * spin,
            c,
            h,
            cos1,
            sin1,
            decay,
        )
        x2, w2 = oscillator_step(
            tx * e2x + ty * e2y,
            vx * e2x + vy * e2y,
            uax * e2x + uay * e2y,
            ubx * e2x + uby * e2y,
            km,
            c,
            h,
            cos2,
            sin2,
            decay,
        )
        return (
            x1 * e1x + x2 * e2x,
            x1 * e1y + x2 * e2y,
            w1 * e1x + w2 * e2x,
            w1 * e1y + w2 * e2y,
        )

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def linear(force, rest_force, tilt_rate, tilt_accel, length, omega, zeta, k_floor, h):  # type: ignore[no-untyped-def]
        modes, steps, _ = force.shape
        angle = np.zeros((modes, steps, 2))
        rate = np.zeros((modes, steps, 2))
        for m in range(modes):
            inv_l = 1.0 / length[m]
            c = 2.0 * zeta[m] * omega[m]
            # start from the equilibrium of the container at rest in its first pose
            k0 = max(-rest_force[m, 2] * inv_l, k_floor[m])
            tx = rest_force[m, 0] * inv_l / k0
            ty = rest_force[m, 1] * inv_l / k0
            vx = 0.0
            vy = 0.0
            angle[m, 0, 0] = tx
            angle[m, 0, 1] = ty
            for j in range(steps - 1):
                tx, ty, vx, vy = linear_step(
                    tx,
                    ty,
                    vx,
                    vy,
                    force[m, j],
                    force[m, j + 1],
                    tilt_rate[j],
                    tilt_rate[j + 1],
                    tilt_accel[j],
                    tilt_accel[j + 1],
                    inv_l,
                    c,
                    k_floor[m],
                    h,
                )
                angle[m, j + 1, 0] = tx
                angle[m, j + 1, 1] = ty
                rate[m, j + 1, 0] = vx
                rate[m, j + 1, 1] = vy
        return angle, rate

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def linear_batch(  # type: ignore[no-untyped-def]
        force,
        rest_force,
        tilt_rate,
        tilt_accel,
        length,
        omega,
        zeta,
        k_floor,  # type: ignore[no-untyped-def]
        factor,
        remainder,
        h,
        end_index,
        last_index,
    ):
        """Metrics only: peak slosh height and first-mode angle up to each case's last
        sample, and the state at each case's end index (cases first, time-major inside)."""
        cases = force.shape[0]
        modes = length.size
        peak_height = np.zeros(cases)
        peak_angle = np.zeros(cases)
        end_state = np.zeros((cases, modes, 4))
        state = np.zeros((modes, 4))
        for case in range(cases):
            for m in range(modes):
                inv_l = 1.0 / length[m]
                k0 = max(-rest_force[case, m, 2] * inv_l, k_floor[m])
                state[m, 0] = rest_force[case, m, 0] * inv_l / k0
                state[m, 1] = rest_force[case, m, 1] * inv_l / k0
                state[m, 2] = 0.0
                state[m, 3] = 0.0
            for j in range(last_index[case] + 1):
                quasi = force[case, modes, j]
                axial = max(-quasi[2], 1e-9)
                ex = remainder * quasi[0] / axial
                ey = remainder * quasi[1] / axial
                for m in range(modes):
                    ex += factor[m] * state[m, 0]
                    ey += factor[m] * state[m, 1]
                    if j == end_index[case]:
                        for k in range(4):
                            end_state[case, m, k] = state[m, k]
                peak_height[case] = max(peak_height[case], np.sqrt(ex * ex + ey * ey))
                peak_angle[case] = max(
                    peak_angle[case], np.sqrt(state[0, 0] ** 2 + state[0, 1] ** 2)
                )
                if j == last_index[case]:
                    break
                for m in range(modes):
                    state[m, 0], state[m, 1], state[m, 2], state[m, 3] = linear_step(
                        state[m, 0],
                        state[m, 1],
                        state[m, 2],
                        state[m, 3],
                        force[case, m, j],
                        force[case, m, j + 1],
                        tilt_rate[case, j],
                        tilt_rate[case, j + 1],
                        tilt_accel[case, j],
                        tilt_accel[case, j + 1],
                        1.0 / length[m],
                        2.0 * zeta[m] * omega[m],
                        k_floor[m],
                        h,
                    )
        return peak_height, peak_angle, end_state

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def pendulum_rhs(u, v, f, p, q, dp, dq, length, c):  # type: ignore[no-untyped-def]
        rx = length * u[0]
        ry = length * u[1]
        rz = length * u[2]
        sx = length * v[0]
        sy = length * v[1]
        sz = length * v[2]
        # Omega = (p, q, 0), Omega' = (dp, dq, 0)
        euler_x = dq * rz
        euler_y = -dp * rz
        euler_z = dp * ry - dq * rx
        wr_x = q * rz
        wr_y = -p * rz
        wr_z = p * ry - q * rx
        cen_x = q * wr_z
        cen_y = -p * wr_z
        cen_z = p * wr_y - q * wr_x
        cor_x = q * sz
        cor_y = -p * sz
        cor_z = p * sy - q * sx
        fx = f[0] - euler_x - cen_x - 2.0 * cor_x - c * sx
        fy = f[1] - euler_y - cen_y - 2.0 * cor_y - c * sy
        fz = f[2] - euler_z - cen_z - 2.0 * cor_z - c * sz
        radial = u[0] * fx + u[1] * fy + u[2] * fz
        speed2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
        out = np.empty(3)
        out[0] = (fx - radial * u[0]) / length - speed2 * u[0]
        out[1] = (fy - radial * u[1]) / length - speed2 * u[1]
        out[2] = (fz - radial * u[2]) / length - speed2 * u[2]
        return out

    @njit(cache=True)  # type: ignore[untyped-decorator]
    def nonlinear(force, rest_force, tilt_rate, tilt_accel, length, omega, zeta, h):  # type: ignore[no-untyped-def]
        """Drive on the half-step grid (2 steps + 1 samples); returns u, u' on the full grid."""
        modes, half_samples, _ = force.shape
        steps = (half_samples - 1) // 2 + 1
        unit = np.zeros((modes, steps, 3))
        velocity = np.zeros((modes, steps, 3))
        for m in range(modes):
            ln = length[m]
            c = 2.0 * zeta[m] * omega[m]
            u = rest_force[m].copy()  # hanging along the apparent gravity at rest
            norm = np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
            u /= norm
            v = np.zeros(3)
            unit[m, 0] = u
            for j in range(steps - 1):
                a = 2 * j
                b = a + 1
                e = a + 2
                k1u = v
                k1v = pendulum_rhs(
                    u,
                    v,
                    force[m, a],
                    tilt_rate[a, 0],
                    tilt_rate[a, 1],
                    tilt_accel[a, 0],
                    tilt_accel[a, 1],
                    ln,
                    c,
                )
                u2 = u + 0.5 * h * k1u
                v2 = v + 0.5 * h * k1v
                k2v = pendulum_rhs(
                    u2,
                    v2,
                    force[m, b],
                    tilt_rate[b, 0],
                    tilt_rate[b, 1],
                    tilt_accel[b, 0],
                    tilt_accel[b, 1],
                    ln,
                    c,
                )
                u3 = u + 0.5 * h * v2
                v3 = v + 0.5 * h * k2v
                k3v = pendulum_rhs(
                    u3,
                    v3,
                    force[m, b],
                    tilt_rate[b, 0],
                    tilt_rate[b, 1],
                    tilt_accel[b, 0],
                    tilt_accel[b, 1],
                    ln,
                    c,
                )
                u4 = u + h * v3
                v4 = v + h * k3v
                k4v = pendulum_rhs(
                    u4,
                    v4,
                    force[m, e],
                    tilt_rate[e, 0],
                    tilt_rate[e, 1],
                    tilt_accel[e, 0],
                    tilt_accel[e, 1],
                    ln,
                    c,
                )
                u = u + h / 6.0 * (k1u + 2.0 * v2 + 2.0 * v3 + v4)
                v = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
                norm = np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
                u /= norm
                radial = u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
                v -= radial * u
                unit[m, j + 1] = u
                velocity[m, j + 1] = v
        return unit, velocity

    return {
        "linear": linear,
        "linear_batch": linear_batch,
        "nonlinear": nonlinear,
        "step": oscillator_step,
    }


def kernels() -> dict[str, Any]:
    """The compiled kernels (compiled on first use, cached on disk by numba).

    Returns
    -------
    dict
        linear, linear_batch, nonlinear and step: the numba functions behind
        `linear_pendulums`, `nonlinear_pendulums` and `sloshkit.sim.spatial_batch`.

    Examples
    --------
    >>> sorted(kernels())
    ['linear', 'linear_batch', 'nonlinear', 'step']
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

    The stiffness is floored at 1e-3 omega_n^2 (apparent gravity along the axis reversed or
    nearly zero: the caller warns, the model is not valid there).

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
