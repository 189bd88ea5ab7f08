"""The numba kernels of `sloshkit.sim.spatial_kernels` at module level.

They live in their own module, imported on first use, so that numba's on-disk cache
(``cache=True``) works: kernels defined inside a function and calling each other through its
closure got a new cache key in every process and were compiled again each time (about 15-25 s
per process for the nonlinear kernel); module-level functions calling each other as globals are
cached once. The equations are documented in `sloshkit.sim.spatial_kernels`.
"""

from __future__ import annotations

import numpy as np
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
def linear_periods(state, start, end, inv_l, c, k_floor, h):  # type: ignore[no-untyped-def]
    """`linear_step` of many independent states at once: state (n, 4) (angles, rates), start
    and end (n, 7) the drive at either end of the period (specific force, then the lateral
    angular velocity and its derivative), inv_l, c, k_floor (n,)."""
    out = np.empty_like(state)
    for i in range(state.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = linear_step(
            state[i, 0],
            state[i, 1],
            state[i, 2],
            state[i, 3],
            start[i, :3],
            end[i, :3],
            start[i, 3:5],
            end[i, 3:5],
            start[i, 5:7],
            end[i, 5:7],
            inv_l[i],
            c[i],
            k_floor[i],
            h,
        )
    return out


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
            peak_angle[case] = max(peak_angle[case], np.sqrt(state[0, 0] ** 2 + state[0, 1] ** 2))
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


@njit(cache=True)  # type: ignore[untyped-decorator]
def linear_amplitude(  # type: ignore[no-untyped-def]
    force,
    rest_force,
    tilt_rate,
    tilt_accel,
    length,
    omega,
    zeta,
    k_floor,
    omega_slope,
    zeta_slope,
    amplitude_cap,
    h,
):
    """The linear kernel with each mode's frequency and damping ratio taken from its backbone
    at the wave's current amplitude (`sloshkit.sim.spatial_amplitude`): omega(A) =
    omega_n + omega_slope A^2, zeta(A) = zeta_n + zeta_slope A, A capped at amplitude_cap.
    A^2 = |x|^2 + |x'|^2 / omega(A)^2 with x = theta - u / K the deviation from the
    quasi-static equilibrium at the start of the step (omega(A) of the previous step);
    stiffness and forcing are scaled by (omega(A) / omega_n)^2 over the step (the restoring
    force of the wave, not its equilibrium)."""
    modes, steps, _ = force.shape
    angle = np.zeros((modes, steps, 2))
    rate = np.zeros((modes, steps, 2))
    scaled_a = np.empty(3)
    scaled_b = np.empty(3)
    accel_a = np.empty(2)
    accel_b = np.empty(2)
    for m in range(modes):
        inv_l = 1.0 / length[m]
        k0 = max(-rest_force[m, 2] * inv_l, k_floor[m])
        tx = rest_force[m, 0] * inv_l / k0
        ty = rest_force[m, 1] * inv_l / k0
        vx = 0.0
        vy = 0.0
        ratio = 1.0
        angle[m, 0, 0] = tx
        angle[m, 0, 1] = ty
        for j in range(steps - 1):
            fa = force[m, j]
            fb = force[m, j + 1]
            ka = max(-fa[2] * inv_l, k_floor[m])
            kb = max(-fb[2] * inv_l, k_floor[m])
            # quasi-static equilibrium u / K at both ends of the step, and its rate
            qax = (fa[0] * inv_l + tilt_accel[j, 1]) / ka
            qay = (fa[1] * inv_l - tilt_accel[j, 0]) / ka
            qbx = (fb[0] * inv_l + tilt_accel[j + 1, 1]) / kb
            qby = (fb[1] * inv_l - tilt_accel[j + 1, 0]) / kb
            dx = tx - qax
            dy = ty - qay
            # the rate scaled by the current (previous step's) frequency: A is then constant
            # over a cycle of the free oscillation, however large the shift
            wx = (vx - (qbx - qax) / h) / (omega[m] * ratio)
            wy = (vy - (qby - qay) / h) / (omega[m] * ratio)
            amplitude = min(np.sqrt(dx * dx + dy * dy + wx * wx + wy * wy), amplitude_cap[m])
            ratio = max(1.0 + omega_slope[m] * amplitude * amplitude / omega[m], 0.1)
            scale = ratio * ratio
            damping = max(zeta[m] + zeta_slope[m] * amplitude, 0.0)
            for k in range(3):
                scaled_a[k] = fa[k] * scale
                scaled_b[k] = fb[k] * scale
            for k in range(2):
                accel_a[k] = tilt_accel[j, k] * scale
                accel_b[k] = tilt_accel[j + 1, k] * scale
            tx, ty, vx, vy = linear_step(
                tx,
                ty,
                vx,
                vy,
                scaled_a,
                scaled_b,
                tilt_rate[j],
                tilt_rate[j + 1],
                accel_a,
                accel_b,
                inv_l,
                2.0 * damping * omega[m] * ratio,
                k_floor[m] * scale,
                h,
            )
            angle[m, j + 1, 0] = tx
            angle[m, j + 1, 1] = ty
            rate[m, j + 1, 0] = vx
            rate[m, j + 1, 1] = vy
    return angle, rate
