"""Moves on the controller's export grid: the problem's numbers, and a move measured again.

`sloshkit.plan.line.export_grid` plans on the grid; this module holds what it works with and the
check it never skips: a solution's end state projected exactly onto rest, and the move
simulated again with the verification's discretisation (Franklin, Powell & Workman, *Digital
Control of Dynamic Systems*, 3rd ed. (1998) §6.3.2) against every limit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Pendulum:
    """One mode of one model of the band, discretised on the export grid.

    Parameters
    ----------
    phi, gamma, g1 : array
        ``phi`` (2x2), ``gamma`` (2,), ``g1`` (2,) as returned by
        `sloshkit.sim.discretisation.velocity_driven_discretisation`.
    omega_rad_s, damping_ratio, length_m, wall_factor_m : float
        The mode's frequency, damping, pendulum length and wall-elevation factor.
    limited : bool
        The angle and residual limits apply (the first mode of each model).
    model : int
        Index of its model in the robustness band.

    Returns
    -------
    Pendulum

    Examples
    --------
    >>> from sloshkit.sim.discretisation import velocity_driven_discretisation
    >>> matrices = velocity_driven_discretisation(29.7, 0.01, 0.011, 4e-3)
    >>> Pendulum(*matrices, 29.7, 0.01, 0.011, 0.02, True, 0).limited
    True
    """

    phi: FloatArray
    gamma: FloatArray
    g1: FloatArray
    omega_rad_s: float
    damping_ratio: float
    length_m: float
    wall_factor_m: float
    limited: bool
    model: int


@dataclass(frozen=True)
class Limits:
    """Distance, machine and slosh limits of one problem and the sample period (SI).

    Parameters
    ----------
    distance_m, max_velocity_m_s, max_acceleration_m_s2, max_jerk_m_s3 : float
        Distance and machine limits.
    max_angle_rad, max_residual_rad : float
        First-mode angle and residual amplitude limits.
    max_wall_elevation_m : float or None
        Wall-elevation limit (every mode), if any.
    sample_period_s : float
        The export grid's step.
    substeps : int
        Sub-samples per step at which the slosh is checked (`sloshkit.plan.line.verification.
        slosh_substeps`): the limits hold on the grid ``sample_period_s / substeps`` too, the
        finest controller period a plan is exported to.

    Returns
    -------
    Limits

    Examples
    --------
    >>> Limits(0.5, 1.5, 20.0, 500.0, 0.087, 0.0044, None, 4e-3, 2).slosh_period_s
    0.002
    """

    distance_m: float
    max_velocity_m_s: float
    max_acceleration_m_s2: float
    max_jerk_m_s3: float
    max_angle_rad: float
    max_residual_rad: float
    max_wall_elevation_m: float | None
    sample_period_s: float
    substeps: int = 1

    @property
    def slosh_period_s(self) -> float:
        """The step of the slosh check grid [s]."""
        return self.sample_period_s / self.substeps


@dataclass(frozen=True)
class Move:
    """A move on the export grid.

    Parameters
    ----------
    jerks_m_s3 : array
        Jerk of each step [m/s^3] (N steps, the last one ``last_step_s`` long).
    duration_s : float
        T = (N - 1) Ts + tau [s].
    last_step_s : float
        tau [s].
    distance_m : float
        Distance it travels [m].
    status : str
        The solver's status.

    Returns
    -------
    Move

    Examples
    --------
    >>> import numpy as np
    >>> Move(np.zeros(3), 0.012, 0.004, 0.0, "optimal").duration_s
    0.012
    """

    jerks_m_s3: FloatArray
    duration_s: float
    last_step_s: float
    distance_m: float
    status: str


def steps_for_duration(duration_s: float, sample_period_s: float) -> tuple[int, float]:
    """(N, tau): the number of steps and the last step of a duration on the grid.

    Parameters
    ----------
    duration_s, sample_period_s : float
        Duration and grid step [s].

    Returns
    -------
    tuple of (int, float)
        N >= 1 and tau in (0, Ts].

    Examples
    --------
    >>> steps_for_duration(0.01, 0.004)
    (3, 0.002)
    """
    from sloshkit.motion.sampling import steps_to_reach

    steps = max(1, steps_to_reach(duration_s, sample_period_s))
    return steps, round(duration_s - (steps - 1) * sample_period_s, 15)


def measure(
    jerks_m_s3: FloatArray, last_step_s: float, limits: Limits, pendulums: list[Pendulum]
) -> tuple[FloatArray, float, float]:
    """Bring a move to rest exactly and measure it against every limit.

    The least-norm correction of the jerks that zeroes the final velocity and acceleration
    (the solver meets its equalities to about 1e-7), then the velocity sampled on the slosh
    check grid (``limits.substeps`` samples per step, at rest from T on) simulated with
    `sloshkit.sim.discretisation.linear_mode_response` (as the verification does) for each
    pendulum; the residual is taken at the first check sample at or after T.

    Parameters
    ----------
    jerks_m_s3 : array
        Jerk of each step; all steps ``limits.sample_period_s`` long but the last.
    last_step_s : float
        Length of the last step [s].
    limits : Limits
        The limits.
    pendulums : list of Pendulum
        The modes to simulate.

    Returns
    -------
    tuple
        (corrected jerks [m/s^3], distance travelled [m], largest ratio of a quantity to its
        limit: velocity within each step, acceleration, jerk, angle, residual, wall).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.sim.discretisation import velocity_driven_discretisation
    >>> matrices = velocity_driven_discretisation(29.66, 0.03, 0.01115, 4e-3)
    >>> pendulum = Pendulum(*matrices, 29.66, 0.03, 0.01115, 0.0, True, 0)
    >>> limits = Limits(0.1, 1.5, 20.0, 500.0, 0.0873, 0.00436, None, 4e-3)
    >>> jerks, distance, ratio = measure(np.array([100.0, -100.0, -100.0, 100.0]), 4e-3,
    ...                                  limits, [pendulum])
    >>> round(distance * 1e6, 3), round(ratio, 3)
    (12.8, 0.26)
    """
    from sloshkit.sim.discretisation import linear_mode_response
    from sloshkit.sim.metrics import free_amplitude

    ts = limits.sample_period_s
    n = jerks_m_s3.size
    h = np.full(n, ts)
    h[-1] = last_step_s
    remaining = np.cumsum(h[::-1])[::-1] - h  # time from the end of each step to the end
    gains = np.vstack((h, h**2 / 2 + h * remaining))  # d(a_N, v_N) / d jerk_k
    u = np.asarray(jerks_m_s3, dtype=float).copy()
    for _ in range(2):
        a = np.concatenate(([0.0], np.cumsum(u * h)))
        v = np.concatenate(([0.0], np.cumsum(a[:-1] * h + u * h**2 / 2)))
        error = np.array([a[-1], v[-1]])
        u -= gains.T @ np.linalg.solve(gains @ gains.T, error)
    a = np.concatenate(([0.0], np.cumsum(u * h)))
    v = np.concatenate(([0.0], np.cumsum(a[:-1] * h + u * h**2 / 2)))
    distance = float(np.sum(v[:-1] * h + a[:-1] * h**2 / 2 + u * h**3 / 6))
    midpoints = v[:-1] + a[:-1] * h / 2
    ratios = [
        float(np.max(np.abs(u))) / limits.max_jerk_m_s3,
        float(np.max(np.abs(a))) / limits.max_acceleration_m_s2,
        max(float(np.max(np.abs(v))), float(np.max(np.abs(midpoints)))) / limits.max_velocity_m_s,
    ]
    samples = check_velocities(u, a, v, last_step_s, limits)
    walls: dict[int, FloatArray] = {}
    for pend in pendulums:
        theta, rate = linear_mode_response(
            samples, limits.slosh_period_s, pend.omega_rad_s, pend.damping_ratio, pend.length_m
        )
        if pend.limited:
            ratios.append(float(np.max(np.abs(theta))) / limits.max_angle_rad)
            residual = free_amplitude(theta[-1], rate[-1], pend.omega_rad_s, pend.damping_ratio)
            ratios.append(float(residual) / limits.max_residual_rad)
        walls[pend.model] = walls.get(pend.model, 0.0) + pend.wall_factor_m * theta
    if limits.max_wall_elevation_m is not None:
        for wall in walls.values():
            ratios.append(float(np.max(np.abs(wall))) / limits.max_wall_elevation_m)
    return u, distance, max(ratios)


def check_velocities(
    jerks_m_s3: FloatArray,
    node_acceleration_m_s2: FloatArray,
    node_velocity_m_s: FloatArray,
    last_step_s: float,
    limits: Limits,
) -> FloatArray:
    """Velocity of a piecewise-constant-jerk move at t_j = j Ts / substeps, from 0 to the
    first sample at or after T (at rest from T on).

    Parameters
    ----------
    jerks_m_s3 : array
        Jerk of each of the N steps [m/s^3].
    node_acceleration_m_s2, node_velocity_m_s : array
        Acceleration and velocity at the N + 1 nodes [m/s^2, m/s].
    last_step_s : float
        Length of the last step [s].
    limits : Limits
        Sample period and substeps.

    Returns
    -------
    numpy.ndarray
        The velocity samples [m/s].

    Examples
    --------
    >>> import numpy as np
    >>> limits = Limits(0.1, 1.5, 20.0, 500.0, 0.0873, 0.00436, None, 4e-3, 2)
    >>> check_velocities(np.array([1.0e3]), np.array([0.0, 4.0]), np.array([0.0, 8e-3]),
    ...                  4e-3, limits).tolist()
    [0.0, 0.002, 0.0]
    """
    from sloshkit.motion.sampling import steps_to_reach

    ts, substeps = limits.sample_period_s, limits.substeps
    n = jerks_m_s3.size
    end = (n - 1) * ts + last_step_s
    index = np.arange(steps_to_reach(end, limits.slosh_period_s) + 1)
    step = np.minimum(index // substeps, n - 1)
    offset = (index - step * substeps) * limits.slosh_period_s
    inside = (step < n - 1) | (offset < last_step_s - 1e-12)
    velocity = (
        node_velocity_m_s[step]
        + node_acceleration_m_s2[step] * offset
        + jerks_m_s3[step] * offset**2 / 2
    )
    return np.where(inside, velocity, 0.0)
