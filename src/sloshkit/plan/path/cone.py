"""One sequential second-order-cone program of the 3-D path planner.

`cone_step` linearises the path program's model (`sloshkit.plan.path.program`) around the
current samples: the force derivatives banded (`PathProgram.jacobians`), the pendulums as the
time-varying linear system of one Runge-Kutta period differentiated along the current track
(`sloshkit.plan.path.pendulums.step_jacobians`), their states variables of banded dynamics rows.
Every norm stays an exact second-order cone (the semi-major axis of a 2 x 2 matrix as half the
sum of two norms). At a fixed period the program maximises the largest common margin sigma of
all limits (value <= limit (1 - margin + sigma)) over the samples within a trust region on their
speed change (sequential convex programming: Mao, Szmuk & Acikmese, IEEE CDC (2016),
doi:10.1109/CDC.2016.7798816; Nocedal & Wright, *Numerical Optimization*, 2nd ed. (2006) §18).
With the period free, h (1 + epsilon) (free final time by time dilation: Szmuk & Acikmese,
AIAA GNC (2018), doi:10.2514/6.2018-0617), it minimises epsilon plus an exact penalty of the
limits still exceeded. Solved by Clarabel (`sloshkit.plan.path.rows.ConeRows.solve`); polyhedral
facets of the 3-D norms let iterates break the jerk limit between facets, so norms stay cones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from sloshkit.plan.path.pendulums import period_jacobian, slope_jacobian, step_jacobians
from sloshkit.plan.path.program import HOLD, FloatArray, PathProgram, mode_arrays
from sloshkit.plan.path.rows import DIFFERENCE_WEIGHTS, ConeRows, tilt_rows, vector_cones
from sloshkit.plan.path.samples import PathSamples

#: Relative margin the programs keep from every limit (the export is then verified exactly).
PROGRAM_MARGIN = 2e-3


#: Weight of the limits' excess sigma against the relative period change while the duration
#: is free (an exact penalty needs more than the multiplier, about 1/2: the duration scales
#: about as the square root of the ratio to a limit).
PENALTY = 10.0


@dataclass(frozen=True, eq=False)
class ConeStep:
    """A cone program's result.

    Parameters
    ----------
    samples : PathSamples
        The new samples (and period).
    sigma : float
        The predicted margin: the largest ratio to a limit is predicted at
        1 - `PROGRAM_MARGIN` + sigma (the largest slack when the period is free).
    residual : float
        The predicted residual over its limit.

    Examples
    --------
    >>> import numpy as np
    >>> step = ConeStep(PathSamples(np.zeros(2), np.zeros((2, 2)), 0.004), -0.1, 0.5)
    >>> step.sigma < 0.0
    True
    """

    samples: PathSamples
    sigma: float
    residual: float


def cone_step(
    program: PathProgram,
    samples: PathSamples,
    evaluation: Any,
    trust: float,
    residual_trust: float = 1.0,
    dilation_trust: float | None = None,
) -> ConeStep | None:
    """One cone program around ``samples`` (module docstring).

    With ``dilation_trust`` the sample period is a variable too, h (1 + epsilon) with
    |epsilon| <= dilation_trust, and the program minimises epsilon + `PENALTY` (sigma_k +
    sigma_w + sigma_r), each sigma >= 0, instead of maximising the margin: an exact penalty of
    the limits it cannot meet yet (Mao, Szmuk & Acikmese (2016)), with one slack for the
    kinematic limits, one for the wall height and one for the residual, so that a limit still
    exceeded does not loosen the others.

    Parameters
    ----------
    program : PathProgram
        The problem's model.
    samples : PathSamples
        The current samples.
    evaluation : object
        Their evaluation (`PathProgram.evaluate`).
    trust : float
        The largest change of a step's speed [m/s] (a sample moves by at most 0.02 s times it).
    residual_trust : float
        The largest change of each free-oscillation entry e_n A, e_n B over the residual limit
        (the residual is the most sensitive quantity: a millimetre's shift of the samples near
        the end moves it by millimetres).
    dilation_trust : float, optional
        The largest relative change of the period; None keeps it fixed.

    Returns
    -------
    ConeStep or None
        The program's samples and predictions, or None when the solver failed.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.program import ProgramLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> path = path_from_waypoints([[0, 0, 0], [0.1, 0, 0]])
    >>> program = PathProgram(path, [model], limits, 0.01)
    >>> t = np.arange(51) / 50  # a quintic rest-to-rest timing of 0.5 s: too fast
    >>> samples = PathSamples(0.1 * t**3 * (10 - 15 * t + 6 * t**2), np.zeros((51, 2)), 0.01)
    >>> iterate = program.iterate(samples)
    >>> step = cone_step(program, iterate.samples, iterate.evaluation, 0.01, 0.05)
    >>> trial = program.iterate(step.samples)
    >>> bool(trial.excess < iterate.excess)
    True
    >>> free = cone_step(program, iterate.samples, iterate.evaluation, 0.01, 1.0, 0.02)
    >>> round(free.samples.period_s, 6)  # too fast: the period grows by the trust region
    0.0102
    >>> bool(abs(program.iterate(free.samples).excess - (1 - PROGRAM_MARGIN + free.sigma)) < 0.01)
    True
    """
    lim, ts = program.limits, samples.period_s
    dilate = dilation_trust is not None
    n = samples.s_m.size
    steps = n - 1
    keep = 1.0 - PROGRAM_MARGIN
    bands = program.jacobians(samples)
    band = bands[0]
    unit = lim.max_jerk_m_s3 * ts**3
    tilting = program.tilt
    sigma = steps
    models, modes = len(program.models), len(program.modes)
    state_base = steps + 1
    last = steps + HOLD  # the pendulums run on through the rest samples after the move
    total = last + 1

    # deviations of the pendulum states x = (u, u') per (model, mode) at samples 1..last
    def state(m: int, k: int, comp: Any, i: Any) -> Any:
        return state_base + ((m * modes + k) * 6 + np.asarray(comp)) * last + (np.asarray(i) - 1)

    t_base = state_base + models * modes * 6 * last
    dilation = t_base + 2 * models * modes  # epsilon's column, when the period is free
    # the tilt deviations (r_x, r_y) of samples 1..N-1 in units of a tilt acceleration's
    # change over one period (the tilt is zero at both ends)
    tilt_base = dilation + (3 if dilate else 0)
    tilt_unit = lim.max_tilt_acceleration_rad_s2 * ts**2
    columns = tilt_base + (2 * (steps - 1) if tilting else 0)
    # the slacks of the wall heights and of the residual: sigma's own column unless dilated
    wall_sigma, residual_sigma = (dilation + 1, dilation + 2) if dilate else (sigma, sigma)
    conic = ConeRows()

    def d(i: Any) -> Any:
        return np.asarray(i) - 1

    # each variable block: its bands, the column of a sample's deviation, which samples have
    # one, and its unit
    blocks: list[tuple[Any, Any, Any, float]] = [(band, d, lambda k: (k >= 1) & (k <= steps), unit)]
    if tilting:
        for c in (0, 1):
            blocks.append(
                (
                    bands[1 + c],
                    lambda k, c=c: tilt_base + (np.asarray(k) - 1) * 2 + c,
                    lambda k: (k >= 1) & (k <= steps - 1),
                    tilt_unit,
                )
            )

    # the end sample is fixed: d_N = (S - s_N) / unit -> an equality
    conic.add("zero", [0], [d(steps)], [1.0], [(program.path.length_m - samples.s_m[-1]) / unit])
    # ------------------------------------------------ pendulum dynamics, linearised
    # dx_{k+1} = A_k dx_k + B_k df_k + E_k df_{k+1}
    # (`sloshkit.plan.path.pendulums.step_jacobians`), the force deviations
    # df_j = sum_o G_o[j] d_{j+o} banded (`PathProgram.jacobians`), x_0 fixed
    period = np.arange(last)
    for m, model in enumerate(program.models):
        lengths, omegas, zetas = mode_arrays(model)
        a_k, b_k, e_k = step_jacobians(
            evaluation.unit[m], evaluation.rate[m], evaluation.drive[m], lengths, omegas, zetas, ts
        )
        kappa = omegas**2 * lengths / model.gravity_m_s2
        if dilate:
            # x_{k+1} moves with the period directly and through the hinge accelerations
            # (proportional to 1 / h^2: d f_n / d epsilon = 2 (R g - f_n), the gravity row
            # unchanged)
            along = period_jacobian(
                evaluation.unit[m],
                evaluation.rate[m],
                evaluation.drive[m],
                lengths,
                omegas,
                zetas,
                ts,
            )
            # the force rows as above, N's angular velocity as 1 / h and its derivative as 1 / h^2
            drive_rates = evaluation.drive[m][0, :, 3:]
            pull = np.concatenate(
                (
                    2.0 * (evaluation.force[-1][None] - evaluation.force[:-1]),
                    np.broadcast_to(
                        np.concatenate((-drive_rates[:, :2], -2.0 * drive_rates[:, 2:]), -1),
                        (modes, *drive_rates.shape[:1], 4),
                    ),
                ),
                axis=-1,
            )
        for q in range(modes):
            r_list = [period * 6 + row for row in range(6)]
            c_list = [state(m, q, row, period + 1) for row in range(6)]
            v_list = [np.ones(last) for _ in range(6)]
            later = period >= 1
            for row in range(6):
                for col in range(6):
                    r_list.append(period[later] * 6 + row)
                    c_list.append(state(m, q, col, period[later]))
                    v_list.append(-a_k[q, later, row, col])
            for shift, matrix in ((0, b_k[q]), (1, e_k[q])):
                force_at = period + shift
                for o in (-1, 0, 1):
                    sample = force_at + o
                    for block, column_of, has, scale in blocks:
                        gain = (
                            block.force[o + 1][q, force_at]
                            + (kappa[q] - 1.0) * block.force[o + 1][-1, force_at]
                        )
                        coefficient = (
                            np.einsum("kac,kc->ka", matrix[..., :3], gain)
                            + np.einsum("kac,kc->ka", matrix[..., 3:], block.rates[o + 1][force_at])
                        ) * scale
                        ok = has(sample)
                        for row in range(6):
                            r_list.append(period[ok] * 6 + row)
                            c_list.append(column_of(sample[ok]))
                            v_list.append(-coefficient[ok, row])
            if dilate:
                total_change = (
                    along[q]
                    + np.einsum("kac,kc->ka", b_k[q], pull[q, :last])
                    + np.einsum("kac,kc->ka", e_k[q], pull[q, 1 : last + 1])
                )
                for row in range(6):
                    r_list.append(period * 6 + row)
                    c_list.append(np.full(last, dilation))
                    v_list.append(-total_change[:, row])
            conic.add(
                "zero",
                np.concatenate(r_list),
                np.concatenate(c_list),
                np.concatenate(v_list),
                np.zeros(6 * last),
            )
    # ------------------------------------------------ wall cones at every sample 1..last
    moved = np.arange(1, total)
    count = moved.size
    for m, model in enumerate(program.models):
        r_list = [np.arange(count) * 3]
        c_list = [np.full(count, wall_sigma)]
        v_list = [-np.ones(count)]
        wall_b = np.zeros((count, 3))
        wall_b[:, 0] = keep
        wall_b[:, 1:] = evaluation.wall[m, 1:] / lim.max_height_m
        for q, mode in enumerate(model.modes):
            slope = slope_jacobian(evaluation.unit[m, q, 1:])  # (count, 2, 3)
            e = mode.wall_elevation_factor_m / lim.max_height_m
            for row in range(2):
                for comp in range(3):
                    r_list.append(np.arange(count) * 3 + 1 + row)
                    c_list.append(state(m, q, comp, moved))
                    v_list.append(-e * slope[:, row, comp])
        conic.add(
            "soc",
            np.concatenate(r_list),
            np.concatenate(c_list),
            np.concatenate(v_list),
            wall_b.ravel(),
            [3] * count,
        )
    # ------------------------------------------------ residual cones and their sum
    for m, model in enumerate(program.models):
        for q, mode in enumerate(model.modes):
            damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
            sig = mode.damping_ratio * mode.omega_rad_s
            back = math.exp(mode.damping_ratio * mode.omega_rad_s * HOLD * ts)
            e = back * mode.wall_elevation_factor_m / lim.max_residual_height_m
            # |e_n [A_n B_n]|_2 (the semi-major axis) of M = [[a, b], [c, d]] = [A B] is
            # (|(a + d, c - b)| + |(a - d, b + c)|) / 2 (a 2 x 2 matrix is a rotation-scaling
            # plus a reflection-scaling whose scales add: Horn & Johnson, *Matrix Analysis*,
            # 2nd ed. (2013) §7.3): two cones t1, t2, linear in the lateral deviations at
            # `last`, A = du, B = (du' + sig du) / damped (`free_oscillation_components`)
            cols = [int(state(m, q, c, last)) for c in (0, 1, 3, 4)]  # du_x, du_y, du'_x, du'_y
            # a, b, c, d as coefficients of (du_x, du_y, du'_x, du'_y)
            a_, c_ = np.array([e, 0.0, 0.0, 0.0]), np.array([0.0, e, 0.0, 0.0])
            b_ = e * np.array([sig / damped, 0.0, 1.0 / damped, 0.0])
            d_ = e * np.array([0.0, sig / damped, 0.0, 1.0 / damped])
            amp = evaluation.amplitude[m, q] / lim.max_residual_height_m  # A_x, A_y, B_x, B_y
            av, cv, bv, dv = amp
            for cone, (first, second, first_b, second_b) in enumerate(
                ((a_ + d_, c_ - b_, av + dv, cv - bv), (a_ - d_, b_ + c_, av - dv, bv + cv))
            ):
                cone_rows = [0] + [1] * 4 + [2] * 4
                cone_columns = [t_base + 2 * (m * modes + q) + cone, *cols, *cols]
                values = np.concatenate(([-1.0], -first, -second))
                conic.add("soc", cone_rows, cone_columns, values, [0.0, first_b, second_b], [3])
            # the residual's own trust region: |change of each entry| <= residual_trust
            for entry in (a_, b_, c_, d_):
                conic.add(
                    "nonneg",
                    [0] * 4 + [1] * 4,
                    cols + cols,
                    np.concatenate((entry, -entry)),
                    [residual_trust, residual_trust],
                )
        # sum (t1 + t2) / 2 <= keep + sigma
        conic.add(
            "nonneg",
            np.zeros(2 * modes + 1, dtype=int),
            np.concatenate((t_base + 2 * m * modes + np.arange(2 * modes), [residual_sigma])),
            np.concatenate((np.full(2 * modes, 0.5), [-1.0])),
            [keep],
        )
    # ------------------------------------------------ kinematic cones
    for order, values, limit in (
        (1, evaluation.velocity, lim.max_velocity_m_s),
        (2, evaluation.acceleration, lim.max_acceleration_m_s2),
        (3, evaluation.jerk, lim.max_jerk_m_s3),
    ):
        rows = values.shape[0]
        r_idx, c_idx, v_idx = [np.arange(rows) * 4], [np.full(rows, sigma)], [np.full(rows, -1.0)]
        for j, weight in enumerate(DIFFERENCE_WEIGHTS[order]):
            k = np.clip(np.arange(rows) + j - 2, 0, total - 1)
            for block, column_of, has, scale in blocks:
                moving = has(k)
                for c in range(3):
                    coefficient = weight / ts**order * block.position[k, c] * scale / limit
                    use = moving & (coefficient != 0.0)
                    r_idx.append(np.flatnonzero(use) * 4 + 1 + c)
                    c_idx.append(column_of(k[use]))
                    v_idx.append(-coefficient[use])
        if dilate:  # a difference of order p scales as h^-p
            for c in range(3):
                r_idx.append(np.arange(rows) * 4 + 1 + c)
                c_idx.append(np.full(rows, dilation))
                v_idx.append(order * values[:, c] / limit)
        vector_cones(conic, r_idx, c_idx, v_idx, values / limit, keep)
    # ------------------------------------------------ angular velocity and acceleration cones
    angular: tuple[tuple[int, FloatArray, float | None], ...] = (
        (1, evaluation.omega, lim.max_angular_velocity_rad_s),
        (2, evaluation.alpha, lim.max_angular_acceleration_rad_s2),
    )
    for order, values, angular_limit in angular:
        if angular_limit is None:
            continue
        rows = values.shape[0]
        r_idx, c_idx, v_idx = [np.arange(rows) * 4], [np.full(rows, sigma)], [np.full(rows, -1.0)]
        # omega row i = samples i-1 (band slot 0) and i (slot 1); alpha row i = (w_{i+1} - w_i) / T
        terms = [(0, 1.0)] if order == 1 else [(1, 1.0 / ts), (0, -1.0 / ts)]
        for shift, weight in terms:
            w_row = np.arange(rows) + shift
            for slot, sample_shift in ((0, -1), (1, 0)):
                k = w_row + sample_shift
                for block, column_of, has, scale in blocks:
                    ok = (w_row >= 1) & (w_row <= total - 1) & has(k)
                    for c in range(3):
                        coefficient = np.zeros(rows)
                        coefficient[ok] = (
                            weight * block.omega[slot][w_row[ok], c] * scale / angular_limit
                        )
                        use = ok & (coefficient != 0.0)
                        r_idx.append(np.flatnonzero(use) * 4 + 1 + c)
                        c_idx.append(column_of(k[use]))
                        v_idx.append(-coefficient[use])
        if dilate:
            for c in range(3):
                r_idx.append(np.arange(rows) * 4 + 1 + c)
                c_idx.append(np.full(rows, dilation))
                v_idx.append(order * values[:, c] / angular_limit)
        vector_cones(conic, r_idx, c_idx, v_idx, values / angular_limit, keep)
    # ------------------------------------------------ the arm's joint speeds
    if program.joint_model is not None:
        # (q_{k+1} - q_k) / (h limit) within keep + sigma on both sides, q_k = q(s_k, r_k)
        # (`sloshkit.plan.path.joints.JointModel`) linear in d_k, d_{k+1} through dq/ds and in
        # the tilts through dq/dr (zero when the arm's map has no tilt data); a free period
        # scales it as 1 / h
        _, dq_ds, dq_dr = program.joint_model.at(samples.s_m, samples.tilt_rad)
        scaled = ts * program.joint_model.joints.limits_rad_s
        slope = dq_ds[:n] / scaled
        tilt_slope = dq_dr[:n] / scaled[:, None]
        joint = evaluation.joint[: n - 1]
        dof = joint.shape[1]
        for sign in (1.0, -1.0):
            rows = np.arange((n - 1) * dof).reshape(n - 1, dof)
            r_idx, c_idx, v_idx = (
                [rows.ravel()],
                [np.full(rows.size, sigma)],
                [np.full(rows.size, -1.0)],
            )
            for shift, weight in ((1, 1.0), (0, -1.0)):
                k = np.arange(n - 1) + shift  # the sample each difference moves with
                ok = (k >= 1) & (k <= steps)
                r_idx.append(rows[ok].ravel())
                c_idx.append(np.repeat(d(k[ok]), dof))
                v_idx.append((sign * weight * slope[k[ok]] * unit).ravel())
                if tilting:  # the tilt of samples 1..N-1 moves the joints too
                    free = (k >= 1) & (k <= steps - 1)
                    for c in (0, 1):
                        r_idx.append(rows[free].ravel())
                        c_idx.append(np.repeat(tilt_base + (k[free] - 1) * 2 + c, dof))
                        v_idx.append(
                            (sign * weight * tilt_slope[k[free], :, c] * tilt_unit).ravel()
                        )
            if dilate:
                r_idx.append(rows.ravel())
                c_idx.append(np.full(rows.size, dilation))
                v_idx.append(-(sign * joint).ravel())
            conic.add(
                "nonneg",
                np.concatenate(r_idx),
                np.concatenate(c_idx),
                np.concatenate(v_idx),
                (keep - sign * joint).ravel(),
            )
    # ------------------------------------------------ the tilt, its rate and acceleration
    if tilting:
        tilt_rows(
            conic,
            samples.tilt_rad,
            samples.period_s,
            lim,
            tilt_base,
            tilt_unit,
            sigma,
            keep,
            trust,
            dilation,
            dilate,
        )
    # ------------------------------------------------ monotone progress and trust region
    s = samples.s_m
    inner = np.arange(1, n - 1)
    pairs = np.column_stack((d(inner + 1), d(inner))).ravel()
    local = np.repeat(np.arange(inner.size), 2)
    ones = np.tile([-1.0, 1.0], inner.size)
    conic.add("nonneg", local, pairs, ones, (s[inner + 1] - s[inner]) / unit)
    step_change = np.full(inner.size, trust * ts / unit)
    conic.add("nonneg", local, pairs, -ones, step_change)
    conic.add("nonneg", local, pairs, ones, step_change)
    shift = min(0.02 * trust, 0.2 * program.path.length_m) / unit
    idx = np.arange(steps)
    conic.add(
        "nonneg",
        idx,
        idx,
        np.ones(steps),
        np.minimum(shift, (program.path.length_m - s[1:]) / unit),
    )
    conic.add("nonneg", idx, idx, -np.ones(steps), np.minimum(shift, s[1:] / unit))
    objective = np.zeros(columns)
    objective[sigma] = 1.0
    if dilate:
        slacks = [sigma, wall_sigma, residual_sigma]
        conic.add("nonneg", [0, 1, 2], slacks, [-1.0] * 3, [0.0] * 3)
        conic.add("nonneg", [0, 1], [dilation, dilation], [1.0, -1.0], [dilation_trust] * 2)
        objective[slacks] = PENALTY
        objective[dilation] = 1.0
    result = conic.solve(objective)
    program.programs += 1
    if result is None:
        return None
    x = np.asarray(result.x)
    new_s = np.concatenate(([0.0], s[1:] + x[:steps] * unit))
    new_s = np.clip(np.maximum.accumulate(new_s), 0.0, program.path.length_m)
    residual = max(
        0.5 * float(np.sum(x[t_base + 2 * m * modes : t_base + 2 * (m + 1) * modes]))
        for m in range(models)
    )
    new_period = ts * (1.0 + float(x[dilation])) if dilate else ts
    margin = max(float(x[sigma]), float(x[wall_sigma]), float(x[residual_sigma]))
    new_tilt = samples.tilt_rad.copy()
    if tilting:
        new_tilt[1:-1] += tilt_unit * x[tilt_base:].reshape(steps - 1, 2)
    return ConeStep(PathSamples(new_s, new_tilt, new_period), margin, residual)


__all__ = [
    "PENALTY",
    "PROGRAM_MARGIN",
    "ConeStep",
    "cone_step",
]
