"""The minimum-time problem transcribed on the controller's export grid (casadi/IPOPT).

The move is a piecewise-constant jerk on the export grid t_k = k Ts: N - 1 full steps and a
last, shorter step of length tau in [0, Ts], so that T = (N - 1) Ts + tau is continuous. The
slosh is what the verification simulates: the exported velocity samples v_k = v(k Ts) (v_N = 0,
the move is over at the last sample) drive the exact first-order-hold discretisation of each
pendulum (Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998)
§6.3.2): z_{k+1} = Phi z_k + Gamma v_k, theta_k = z_k + g1 v_k. The slosh limits are imposed at
exactly the samples the verification checks, so the planned move passes it without tightening
and solving again. Only the last step's kinematics are nonlinear (polynomial in tau); for a fixed
duration the problem is convex (linear constraints, one second-order cone per model).

One NLP is built per shape (steps, pendulums, models, wall limit) and cached; the numbers (the
discretisations, limits, distance, cost weights) are parameters, and the duration, the leading
steps held at rest and the slack are bounds. Holding the first steps at rest shifts the move to
fewer effective steps (the pendulums start from rest, so a delay changes nothing else): one
solver serves every duration up to its shape. Variables are scaled by their limits.

Three uses of the same solver (direct transcription: Betts, *Practical Methods for Optimal
Control*, 2nd ed., SIAM (2010) ch. 4, doi:10.1137/1.9780898718577):

- ``margin``: for a number of steps at tau = Ts, the largest uniform relative margin -s from
  every limit (s <= 0: feasible);
- ``time``: for a number of steps, the shortest last step tau with every limit met;
- ``smooth``: at a given duration, the least integrated squared jerk rate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: Relative margin the time-optimal and smooth moves keep from every limit, so that rounding in
#: the verification (which allows 1e-7) never flags them.
SAFETY_MARGIN = 1e-6

#: Parameters: 8 problem numbers, 3 cost weights, then 12 per pendulum.
_HEAD, _WEIGHTS, _PER = 8, 3, 12

_SOLVERS: dict[tuple[int, int, int, bool], tuple[Any, int]] = {}


@dataclass(frozen=True)
class Pendulum:
    """One mode of one model of the band, discretised on the export grid.

    ``phi`` (2x2), ``gamma`` (2,), ``g1`` (2,) as returned by
    `sloshkit.sim.discretisation.velocity_driven_discretisation`; the pendulums of a problem
    are ordered model-major, and the first of each model is its first mode (angle and residual
    limits).
    """

    phi: FloatArray
    gamma: FloatArray
    g1: FloatArray
    omega_rad_s: float
    damping_ratio: float
    length_m: float
    wall_factor_m: float


@dataclass(frozen=True)
class Limits:
    """Distance, machine and slosh limits of one problem and the sample period (SI)."""

    distance_m: float
    max_velocity_m_s: float
    max_acceleration_m_s2: float
    max_jerk_m_s3: float
    max_angle_rad: float
    max_residual_rad: float
    max_wall_elevation_m: float | None
    sample_period_s: float


@dataclass(frozen=True)
class Solution:
    """One solve: jerk of each effective step [m/s^3], duration T [s], last step [s], slack s
    (the relative margin from the tightest limit is -s), IPOPT's return status and success."""

    jerks_m_s3: FloatArray
    duration_s: float
    last_step_s: float
    slack: float
    status: str
    success: bool


def _build(ca: Any, steps: int, per_model: int, models: int, wall: bool) -> tuple[Any, int]:
    """The NLP of one shape, every number a parameter, built from matrix expressions.

    Returns (solver, number of equality rows, which come first in g).
    """
    n, count = steps, per_model * models
    p = ca.SX.sym("p", _HEAD + _WEIGHTS + _PER * count)
    active = ca.SX.sym("m", n + 1)  # 1 from the node where the move starts, 0 before
    distance, vmax, amax, jmax, theta_max, residual_max, eta_max, ts = (p[i] for i in range(8))
    w_slack, w_time, w_rate = p[8], p[9], p[10]
    q = ca.reshape(p[_HEAD + _WEIGHTS :], _PER, count)  # one column per pendulum

    kin = ca.SX.sym("k", 3, n + 1)  # position / D, velocity / vmax, acceleration / amax
    z = ca.SX.sym("z", 2 * count, n + 1)  # scaled shifted pendulum states at the samples
    jerk = ca.SX.sym("u", n)  # jerk / jmax of each step
    tau = ca.SX.sym("tau")  # last step / Ts
    slack = ca.SX.sym("s")

    # Kinematics: constant jerk over each step, the last one tau Ts long.
    h = ca.horzcat(ca.repmat(ts, 1, n - 1), tau * ts)
    pos, vel, acc = distance * kin[0, :n], vmax * kin[1, :n], amax * kin[2, :n]
    u = jmax * jerk.T
    kinematics = ca.vertcat(
        kin[0, 1:] - (pos + vel * h + acc * h**2 / 2 + u * h**3 / 6) / distance,
        kin[1, 1:] - (vel + acc * h + u * h**2 / 2) / vmax,
        kin[2, 1:] - (acc + u * h) / amax,
    )
    # Pendulums on the export grid: sample k < N is node k; sample N is at rest (v = 0).
    scale = ca.vec(ca.vertcat(q[7, :], q[8, :]))  # (2 count): z0 and z1 scales interleaved
    blocks = [ca.reshape(q[0:4, i], 2, 2).T for i in range(count)]
    phi = ca.diagcat(*blocks)
    gamma = ca.vec(q[4:6, :])
    states = ca.repmat(scale, 1, n + 1) * z
    pendulums = z[:, 1:] - (ca.mtimes(phi, states[:, :n]) + ca.mtimes(gamma, vel)) / ca.repmat(
        scale, 1, n
    )
    equalities = ca.vertcat(ca.vec(kinematics), ca.vec(pendulums))
    samples = ca.horzcat(vel[:, 1:], ca.SX(1, 1))  # v_1 .. v_{N-1}, 0
    angles = states[0::2, 1:] + ca.mtimes(q[6, :].T, samples)  # (count, N): theta_1 .. theta_N

    # Slack only where the move runs: rows of the idle steps would all read s >= -1.
    # Velocity within each step: its Bernstein coefficients v_k, v_k + a_k h / 2, v_{k+1} bound
    # the quadratic, so the midpoint row keeps the whole curve within the limit, not only the
    # samples.
    bernstein = (vel + acc * h / 2) / vmax
    rows = [kin[1, 1:n].T, bernstein.T, kin[2, 1:n].T, jerk]
    bounds = [1 + active[1:n] * slack, 1 + active[:n] * slack]
    bounds += [1 + active[1:n] * slack, 1 + active[:n] * slack]
    firsts = [m * per_model for m in range(models)]
    rows += [angles[i, :].T / theta_max for i in firsts]
    bounds += [1 + active[1:] * slack for _ in firsts]
    bound = 1 + slack
    residuals = []
    for i in firsts:
        omega, zeta = q[9, i], q[10, i]
        end_angle, end_rate = angles[i, n - 1], states[2 * i + 1, n]  # y_N = theta'_N
        # B of `sloshkit.sim.metrics.free_oscillation_components`, the damping a parameter here
        quadrature = (end_rate + zeta * omega * end_angle) / (omega * ca.sqrt(1 - zeta**2))
        residuals.append((end_angle**2 + quadrature**2) / residual_max**2 - bound**2)
    if wall:
        for m in range(models):
            members = range(m * per_model, (m + 1) * per_model)
            # sum f_n theta_n as `sloshkit.sim.metrics.wall_elevation`, whose factors must be
            # numbers; here they are parameters of the solver.
            eta = sum(q[11, i] * angles[i, :] for i in members) / eta_max
            rows.append(eta.T)
            bounds.append(1 + active[1:] * slack)
    values, limits = ca.vertcat(*rows), ca.vertcat(*bounds)
    inequalities = ca.vertcat(values - limits, -values - limits, *residuals)

    rate = ca.sumsqr(jerk[1:] - jerk[:-1])
    objective = w_slack * slack + w_time * tau + (w_rate * rate + 1e-9 * ca.sumsqr(jerk)) / n
    variables = ca.vertcat(ca.vec(kin), ca.vec(z), jerk, tau, slack)
    solver = ca.nlpsol(
        "exact_grid",
        "ipopt",
        {
            "x": variables,
            "p": ca.vertcat(p, active),
            "f": objective,
            "g": ca.vertcat(equalities, inequalities),
        },
        {
            "print_time": False,
            "ipopt": {
                "print_level": 0,
                "sb": "yes",
                "max_iter": 400,
                "tol": 1e-7,
                "constr_viol_tol": 1e-10,
                "bound_relax_factor": 0.0,
                "mu_strategy": "adaptive",
            },
        },
    )
    return solver, int(equalities.shape[0])


class ExactGrid:
    """The cached solver of one shape and the numbers of one problem.

    Parameters
    ----------
    limits : Limits
        Distance, limits and sample period.
    pendulums : list of Pendulum
        The modes kept, model-major: ``per_model`` modes of model 0, then of model 1, ...
    models : int
        Number of models of the robustness band.
    steps : int
        Largest number of steps N the solver can plan (its shape).
    """

    def __init__(self, limits: Limits, pendulums: list[Pendulum], models: int, steps: int) -> None:
        import casadi as ca

        self.limits, self.pendulums, self.models, self.steps = limits, pendulums, models, steps
        wall = limits.max_wall_elevation_m is not None
        key = (steps, len(pendulums) // models, models, wall)
        if key not in _SOLVERS:
            _SOLVERS[key] = _build(ca, *key)
        self.solver, self.equalities = _SOLVERS[key]
        lim = limits
        head = [
            lim.distance_m,
            lim.max_velocity_m_s,
            lim.max_acceleration_m_s2,
            lim.max_jerk_m_s3,
            lim.max_angle_rad,
            lim.max_residual_rad,
            lim.max_wall_elevation_m or 1.0,
            lim.sample_period_s,
        ]
        rows: list[float] = []
        for pend in pendulums:
            rows += [*np.ravel(pend.phi), *pend.gamma, pend.g1[0]]
            rows += [lim.max_angle_rad, lim.max_velocity_m_s / pend.length_m]
            rows += [pend.omega_rad_s, pend.damping_ratio, pend.wall_factor_m]
        self._head, self._rows = head, rows
        self.width = 3 * (steps + 1) + 2 * len(pendulums) * (steps + 1) + steps + 2

    def solve(
        self,
        effective_steps: int,
        mode: str,
        last_step_s: float | None = None,
        slack: float = -SAFETY_MARGIN,
    ) -> Solution:
        """Solve with ``effective_steps`` steps (the first ``steps - effective_steps`` held at
        rest).

        ``mode``: ``margin`` (tau = Ts, minimise the slack), ``time`` (slack fixed, minimise
        tau) or ``smooth`` (slack and ``last_step_s`` fixed, minimise the jerk rate).
        """
        n, count, ts = self.steps, len(self.pendulums), self.limits.sample_period_s
        idle = n - effective_steps
        if not 1 <= effective_steps <= n:
            raise ValueError(f"effective_steps must be in 1..{n}")
        weights = {"margin": [1.0, 0.0, 0.0], "time": [1e4, 1.0, 0.0], "smooth": [0.0, 0.0, 1.0]}
        mask = (np.arange(n + 1) >= idle).astype(float)
        params = np.concatenate((self._head, weights[mode], self._rows, mask))
        low = np.full(self.width, -np.inf)
        high = np.full(self.width, np.inf)
        kin_end = 3 * (n + 1)
        z_end = kin_end + 2 * count * (n + 1)
        kin_low = low[:kin_end].reshape(n + 1, 3)  # column-major vec of (3, n+1)
        kin_high = high[:kin_end].reshape(n + 1, 3)
        kin_low[: idle + 1] = kin_high[: idle + 1] = 0.0  # at rest until the move starts
        kin_low[n] = kin_high[n] = (1.0, 0.0, 0.0)  # at rest on the target
        z_low = low[kin_end:z_end].reshape(n + 1, 2 * count)
        z_high = high[kin_end:z_end].reshape(n + 1, 2 * count)
        z_low[: idle + 1] = z_high[: idle + 1] = 0.0
        jerk_low, jerk_high = low[z_end : z_end + n], high[z_end : z_end + n]
        jerk_low[:idle] = jerk_high[:idle] = 0.0
        tau_index, slack_index = z_end + n, z_end + n + 1
        if mode == "margin":
            low[tau_index] = high[tau_index] = 1.0
            low[slack_index], high[slack_index] = -0.5, 1e3
        elif mode == "time":  # an exact penalty on the slack: positive only when infeasible
            low[tau_index], high[tau_index] = 0.0, 1.0
            low[slack_index], high[slack_index] = slack, 1e3
        else:
            low[slack_index] = high[slack_index] = slack
            if True:
                assert last_step_s is not None
                low[tau_index] = high[tau_index] = last_step_s / ts
        guess = self._guess(effective_steps, low, high, tau_index, slack_index)
        constraints = int(self.solver.size_out("g")[0])
        lbg = np.full(constraints, -np.inf)
        lbg[: self.equalities] = 0.0
        ubg = np.zeros(constraints)
        # The equations of the idle steps hold trivially (every variable fixed at rest): free
        # them, so that IPOPT does not count them as constraints.
        kinematic_rows = 3 * n
        lbg[: 3 * idle] = -np.inf
        ubg[: 3 * idle] = np.inf
        lbg[kinematic_rows : kinematic_rows + 2 * count * idle] = -np.inf
        ubg[kinematic_rows : kinematic_rows + 2 * count * idle] = np.inf
        result = self.solver(x0=guess, p=params, lbx=low, ubx=high, lbg=lbg, ubg=ubg)
        stats = self.solver.stats()
        x = np.asarray(result["x"], dtype=float).ravel()
        tau = float(x[tau_index]) * ts
        jerks = x[z_end + idle : z_end + n] * self.limits.max_jerk_m_s3
        status = str(stats.get("return_status", ""))
        success = bool(stats.get("success", False)) or status == "Solved_To_Acceptable_Level"
        return Solution(
            jerks_m_s3=np.asarray(jerks, dtype=float),
            duration_s=(effective_steps - 1) * ts + tau,
            last_step_s=tau,
            slack=float(x[slack_index]),
            status=status,
            success=success,
        )

    def _guess(
        self, effective: int, low: FloatArray, high: FloatArray, tau_index: int, slack_index: int
    ) -> FloatArray:
        """A start point: a move along a smooth (septic) profile of the effective duration."""
        n, ts = self.steps, self.limits.sample_period_s
        guess = np.zeros(self.width)
        idle = n - effective
        duration = effective * ts
        t = (np.arange(n + 1) - idle).clip(0) * ts / duration
        t = t.clip(0.0, 1.0)
        s = 35 * t**4 - 84 * t**5 + 70 * t**6 - 20 * t**7
        v = (140 * t**3 - 420 * t**4 + 420 * t**5 - 140 * t**6) / duration
        a = (420 * t**2 - 1680 * t**3 + 2100 * t**4 - 840 * t**5) / duration**2
        lim = self.limits
        kin = np.stack(
            (
                s,
                v * lim.distance_m / lim.max_velocity_m_s,
                a * lim.distance_m / lim.max_acceleration_m_s2,
            ),
            axis=1,
        )
        guess[: 3 * (n + 1)] = kin.ravel()
        guess[tau_index] = 1.0
        guess[slack_index] = 0.0
        return np.clip(
            guess, np.where(np.isfinite(low), low, -1e30), np.where(np.isfinite(high), high, 1e30)
        )


def steps_for_duration(duration_s: float, sample_period_s: float) -> tuple[int, float]:
    """(N, tau): the number of steps and the last step of a duration on the grid."""
    steps = max(1, math.ceil(duration_s / sample_period_s - 1e-9))
    return steps, duration_s - (steps - 1) * sample_period_s
