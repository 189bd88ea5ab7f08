"""Simulation of the equivalent pendulums driven by a container motion.

- `simulate`: every mode of a `SloshModel` driven by a `Motion`, linear (exact discretisation,
  `sloshkit.sim.discretisation`) or nonlinear (large-angle pendulums integrated with DOP853);
  the equations are those of `sloshkit.sim.equations`.
- `simulate_cart_pendulum`: the seed paper's cart-pendulum eqs. 4-5, generalised to all modes,
  driven by a force on the cart (see its docstring).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError, require_positive, warn_validity
from sloshkit.model.modal import SloshModel
from sloshkit.motion.profile import Motion
from sloshkit.sim.discretisation import linear_response
from sloshkit.sim.equations import cart_pendulum_accelerations, pendulum_angular_acceleration
from sloshkit.sim.metrics import (
    DEFAULT_SETTLE_TOLERANCE_RAD,
    default_settle_time,
    residual_from_state,
    simulation_grid,
)
from sloshkit.sim.response import CartPendulumResponse, SloshResponse

FloatArray = NDArray[np.float64]


ModelKind = Literal["linear", "nonlinear"]


MODEL_KINDS: tuple[str, ...] = ("linear", "nonlinear")


def simulate(
    model: SloshModel,
    motion: Motion,
    *,
    kind: ModelKind = "linear",
    sample_period_s: float = 1e-3,
    settle_time_s: float | None = None,
    settle_tolerance_rad: float = DEFAULT_SETTLE_TOLERANCE_RAD,
) -> SloshResponse:
    """Slosh response of every mode of ``model`` to the container ``motion``.

    Parameters
    ----------
    model : SloshModel
        Equivalent pendulum model (`sloshkit.equivalent_model`).
    motion : Motion
        The container's rest-to-rest motion (`sloshkit.motion`).
    kind : {"linear", "nonlinear"}
        ``"linear"``: exact first-order-hold discretisation (fast); ``"nonlinear"``: large-angle
        pendulums integrated with DOP853 piece by piece between the motion's breakpoints.
    sample_period_s : float
        Output sample period [s].
    settle_time_s : float, optional
        Time simulated after the move [s] (default `sloshkit.sim.metrics.default_settle_time`).
    settle_tolerance_rad : float
        Tolerance on abs(theta_1) for the settling time [rad].

    Returns
    -------
    SloshResponse
        Time histories and metrics (`SloshResponse.metrics`).

    References
    ----------
    Seed paper eq. 7; R. A. Ibrahim, *Liquid Sloshing Dynamics* (2005) §6.2,
    doi:10.1017/CBO9780511536656; G. F. Franklin, J. D. Powell, M. Workman, *Digital Control of
    Dynamic Systems*, 3rd ed. (1998) §6.3.2.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> response = sk.simulate(model, sk.quintic(0.2, 1.0), sample_period_s=2e-3)
    >>> round(response.metrics()["peak_angle_deg"], 2)
    8.95
    """
    if isinstance(model, Motion) and isinstance(motion, SloshModel):
        raise TypeError("simulate takes (model, motion, *, ...): the model comes first")
    if kind not in MODEL_KINDS:
        raise InputError("model", kind, "must be one of " + ", ".join(MODEL_KINDS))
    dt = require_positive("sample_period", sample_period_s, "s")
    settle = default_settle_time(model) if settle_time_s is None else float(settle_time_s)
    if settle < 0.0:
        raise InputError("settle_time", settle, "must be >= 0 s")
    time = simulation_grid(motion.duration_s, dt, settle)
    velocity = motion.velocity(time)
    acceleration = motion.acceleration(time)
    if kind == "linear":
        angle, rate = linear_response(model, velocity, dt)
    else:
        angle, rate = _nonlinear_modes(motion, model, time)
    residual = residual_from_state(time, angle, rate, motion.duration_s, model)
    response = SloshResponse(
        time_s=time,
        position_m=motion.position(time),
        velocity_m_s=velocity,
        acceleration_m_s2=acceleration,
        angle_rad=angle,
        rate_rad_s=rate,
        move_duration_s=motion.duration_s,
        model=model,
        kind=kind,
        residual_amplitude_rad=residual,
        motion_name=motion.name,
        peak_jerk_m_s3=motion.peak_jerk_m_s3,
        settle_tolerance_rad=settle_tolerance_rad,
    )
    _warn_beyond_validity(response)
    return response


#: Above this first-mode angle the small-amplitude theory behind the model is doubtful [deg].
LARGE_ANGLE_DEG = 15.0


def _warn_beyond_validity(response: SloshResponse) -> None:
    peak = math.degrees(float(np.max(np.abs(response.angle_rad[0]))))
    if peak > LARGE_ANGLE_DEG:
        warn_validity(
            f"slosh angle reaches {peak:.1f} deg (> {LARGE_ANGLE_DEG:g} deg): beyond "
            "small-amplitude theory; swirl, wave breaking and bubbles are not modelled"
        )
    wall = response.model.container.wall_height_m
    if wall is not None:
        highest = response.model.fill_height_m + float(np.max(np.abs(response.wall_elevation_m)))
        if highest > wall:
            warn_validity(
                f"free surface reaches {1e3 * highest:.1f} mm at the wall, above the "
                f"{1e3 * wall:.1f} mm wall: the liquid may spill"
            )


def _segment_edges(motion: Motion, end_time: float) -> list[float]:
    edges = sorted({0.0, *(float(b) for b in motion.breakpoints_s if 0.0 < b < end_time), end_time})
    if motion.duration_s < end_time:
        edges = sorted({*edges, motion.duration_s})
    return edges


def _nonlinear_modes(
    motion: Motion, model: SloshModel, time: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Large-angle pendulums, one per mode, integrated between breakpoints (DOP853)."""
    angle = np.zeros((len(model.modes), time.size))
    rate = np.zeros_like(angle)
    edges = _segment_edges(motion, float(time[-1]))
    acceleration_pp = motion.derivative_pp(2)
    end_of_move = motion.duration_s
    for row, mode in enumerate(model.modes):
        w, z, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
        state = np.zeros(2)
        for start, stop in itertools.pairwise(edges):
            # Evaluate the acceleration of this piece only: jumps sit on the edges.
            last = float(np.nextafter(stop, start))

            def rhs(
                t: float,
                y: FloatArray,
                start: float = start,
                last: float = last,
                w: float = w,
                z: float = z,
                length: float = length,
            ) -> list[float]:
                moment = min(max(t, start), last)
                accel = float(acceleration_pp(moment)) if moment < end_of_move else 0.0
                second = pendulum_angular_acceleration(
                    y[0], y[1], accel, w, z, length, nonlinear=True, sin=math.sin, cos=math.cos
                )
                return [y[1], second]

            inside = (time >= start) & (time <= stop)
            t_eval = np.union1d(time[inside], [stop])
            from scipy.integrate import solve_ivp  # lazily: keeps start-up short

            solution = solve_ivp(
                rhs, (start, stop), state, method="DOP853", rtol=1e-10, atol=1e-12, t_eval=t_eval
            )
            if not solution.success:  # pragma: no cover - DOP853 does not fail on smooth input
                raise RuntimeError(f"nonlinear integration failed: {solution.message}")
            keep = np.isin(t_eval, time[inside])
            angle[row, inside] = solution.y[0, keep]
            rate[row, inside] = solution.y[1, keep]
            state = solution.y[:, -1]
    return angle, rate


def simulate_cart_pendulum(
    model: SloshModel,
    force_n: Callable[[float], float],
    *,
    cart_mass_kg: float,
    duration_s: float,
    sample_period_s: float = 1e-3,
    include_rigid_liquid: bool = True,
) -> CartPendulumResponse:
    """Cart of mass M (plus the rigid liquid m_0) carrying one pendulum per mode, driven by F(t).

    The equations are `sloshkit.sim.equations.cart_pendulum_accelerations` (seed paper eqs. 4-5
    for N modes), integrated with DOP853.

    Parameters
    ----------
    model : SloshModel
        The equivalent model (its pendulums and rigid mass).
    force_n : callable
        Force on the cart F(t) [N].
    cart_mass_kg : float
        Cart mass M [kg].
    duration_s : float
        Simulated time [s].
    sample_period_s : float
        Output sample period [s].
    include_rigid_liquid : bool
        Add the non-sloshing liquid mass m_0 to the cart.

    Returns
    -------
    CartPendulumResponse
        The cart's motion and the pendulums' angles.

    References
    ----------
    De Simone, M. C., et al., Appl. Sci. 14 (2024) 4522, eqs. 4-5, doi:10.3390/app14114522.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> cart = simulate_cart_pendulum(model, lambda t: 0.0, cart_mass_kg=1.0, duration_s=0.1)
    >>> float(abs(cart.angle_rad).max())
    0.0
    """
    mass_cart = require_positive("cart_mass", cart_mass_kg, "kg")
    end = require_positive("duration", duration_s, "s")
    dt = require_positive("sample_period", sample_period_s, "s")
    modes = model.modes
    count = len(modes)
    masses = np.array([mode.slosh_mass_kg for mode in modes])
    lengths = np.array([mode.length_m for mode in modes])
    omegas = np.array([mode.omega_rad_s for mode in modes])
    zetas = np.array([mode.damping_ratio for mode in modes])
    total = mass_cart + masses.sum() + (model.rigid_mass_kg if include_rigid_liquid else 0.0)

    def accelerations(t: float, state: FloatArray) -> FloatArray:
        return cart_pendulum_accelerations(
            force_n(t),
            state[2 : 2 + count],
            state[2 + count :],
            total_mass_kg=total,
            masses_kg=masses,
            lengths_m=lengths,
            omegas_rad_s=omegas,
            damping_ratios=zetas,
        )

    def rhs_function(t: float, state: FloatArray) -> FloatArray:
        second = accelerations(t, state)
        return np.concatenate(([state[1]], [second[0]], state[2 + count :], second[1:]))

    time = np.arange(math.floor(end / dt + 1e-9) + 1, dtype=float) * dt
    from scipy.integrate import solve_ivp  # lazily: keeps start-up short

    solution = solve_ivp(
        rhs_function,
        (0.0, float(time[-1])),
        np.zeros(2 + 2 * count),
        method="DOP853",
        rtol=1e-10,
        atol=1e-12,
        t_eval=time,
        max_step=dt * 10,
    )
    states = solution.y
    cart_acceleration = np.array(
        [accelerations(t, states[:, k])[0] for k, t in enumerate(solution.t)]
    )
    return CartPendulumResponse(
        time_s=solution.t,
        position_m=states[0],
        velocity_m_s=states[1],
        angle_rad=states[2 : 2 + count],
        rate_rad_s=states[2 + count :],
        acceleration_m_s2=cart_acceleration,
    )
