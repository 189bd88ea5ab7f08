"""The path program's transcription: the timing (and tilt) as cubic B-splines of normalised
time sampled on the export grid (`sloshkit.plan.path.splines`), and one second-order-cone
program linearised around them.

**Variables.** The path parameter is s(t) = sum_i c_i B_i(t / T), a clamped cubic B-spline
of ``count`` coefficients on uniform knots over the move's duration T = N Ts (N export
samples of period Ts; de Boor, *A Practical Guide to Splines* (1978) ch. IX). Its jerk is
piecewise constant between knots. The first three coefficients are 0 and the last three the
path's length S, so the move starts and ends at rest with zero acceleration; coefficients in
increasing order make s(t) monotone (the B-spline's variation diminishing property, de Boor
ch. XI). With the tilt free, r_x(t) and r_y(t) are two more B-splines of the same basis,
zero with their rate and acceleration at both ends. The samples are the spline at the export
instants k Ts, so what the program constrains is exactly what the export contains.

**Model.** Everything the verification checks is a function of the samples
(`sloshkit.plan.path.program.PathProgram.evaluate`: finite-difference kinematics, the
nonlinear pendulums of every mode and band model, the wall height at every sample,
the residual's semi-major axes, an arm's joint speeds). `SplineTranscription.step`
linearises it around the current splines: the samples' derivatives with respect to the
coefficients are the basis itself; the forces' derivatives come banded from
`PathProgram.jacobians`, with the turn about the axis that a tilt sample leaves on every later
one (`sloshkit.plan.path.axial_turn`; variables after the splines'); the pendulums are the
time-varying linear system of one period along the current track
(`sloshkit.plan.path.pendulums.step_jacobians`). Their states are
condensed into the coefficients within segments of `SEGMENT_SAMPLES` samples and carried
from segment to segment by the state at each segment's start (a variable, tied by equality
rows): a wall-height row then depends on its segment's start state and on the few
coefficients acting inside the segment, so the program stays sparse on long moves
(`sloshkit.plan.path.condensing`).

**Program.** At a fixed N it minimises sigma, the largest ratio of a limited quantity to its
limit (every norm an exact second-order cone: the wall height, the first mode's surface slope
when its angle is limited, Cartesian and angular
velocity, acceleration and jerk, tilt and its rate and acceleration; the residual's
semi-major axis of a 2 x 2 matrix as half the sum of two norms, Horn & Johnson, *Matrix
Analysis*, 2nd ed. (2013) §7.3), within a box trust region on the coefficients (sequential
convex programming: Mao, Szmuk & Acikmese, IEEE CDC (2016), doi:10.1109/CDC.2016.7798816).
Rows that cannot bind are left out and added when the solution violates them (constraint
generation). The cones and the solver call are `sloshkit.plan.path.conic`'s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.plan.path.axial_turn import axial_turn
from sloshkit.plan.path.condensing import condense
from sloshkit.plan.path.conic import ConicProgram, NormRows
from sloshkit.plan.path.pendulums import mode_slope, slope_jacobian, step_jacobians
from sloshkit.plan.path.program import HOLD, PathProgram, ProgramIterate, mode_arrays
from sloshkit.plan.path.samples import PathSamples
from sloshkit.plan.path.splines import SplineTiming

FloatArray = NDArray[np.float64]

#: Spline knots per second of move: one every 25 ms (1/8 of the period of a 40 rad/s mode;
#: a 40 ms spacing lengthened TRD_2D's minimum by 1.3 %, see studies/path-planner-methods).
KNOT_SPACING_S = 0.025
#: Samples per condensed segment of the pendulum states (about 0.4 s at 4 ms: a wall row then
#: depends on about 20 coefficients and one segment's start states).
SEGMENT_SAMPLES = 100
#: Constraint-generation rounds per program, at most.
GENERATION_ROUNDS = 6
#: Relative margin the programs keep from every limit (the export is verified exactly).
PROGRAM_MARGIN = 1e-3


def _carried(use: NDArray[np.bool_], steps: int, new_steps: int, size: int) -> NDArray[np.bool_]:
    """A selection of rows of a program over ``steps`` sample periods, at the same fractions
    of the move over ``new_steps`` (the rows after the move, at rest, to the same rows after
    it), widened by a sample on each side; ``size`` rows."""
    if steps == new_steps and use.size == size:
        return use
    rows = np.flatnonzero(use)
    after = rows > steps
    moved = np.where(after, rows - steps + new_steps, np.rint(rows * new_steps / steps)).astype(int)
    carried = np.zeros(size, dtype=bool)
    for shift in (-1, 0, 1):
        carried[np.clip(moved + shift, 0, size - 1)] = True
    return carried


def _differences(values: FloatArray, order: int, period_s: float) -> FloatArray:
    """Forward differences of order ``order`` of ``values`` held two samples at rest before
    and after (as `PathProgram.forces` measures the kinematics), divided by h^order."""
    padded = np.concatenate((values[:1], values[:1], values, values[-1:], values[-1:]))
    for _ in range(order):
        padded = np.diff(padded, axis=0) / period_s
    return padded


@dataclass(frozen=True, eq=False)
class StepResult:
    """A program's result.

    Parameters
    ----------
    timing : SplineTiming
        The new splines.
    predicted : float
        The largest ratio to a limit the linearised program predicts for them.
    size : float
        The step's largest coefficient change over the trust region's unit (S for the path
        parameter, 2.5 rad for the tilt).

    Examples
    --------
    >>> import numpy as np
    >>> timing = SplineTiming(np.array([0, 0, 0, 1, 1, 1.0]), np.zeros((6, 2)), 10)
    >>> StepResult(timing, 0.9).predicted
    0.9
    """

    timing: SplineTiming
    predicted: float
    size: float = 0.0


class SplineTranscription:
    """The path program's variables as splines (module docstring).

    Parameters
    ----------
    program : PathProgram
        The model (limits, band, tilt, arm).
    knot_spacing_s : float
        The knots' spacing [s] of the splines its search carries to each duration
        (`sloshkit.plan.path.minimum_time.knot_count`).

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
    >>> program = PathProgram(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model], limits,
    ...                       0.01)
    >>> tau = np.linspace(0.0, 1.0, 101)
    >>> from sloshkit.plan.path.splines import fit_timing
    >>> timing = fit_timing(tau, 0.1 * tau**3 * (10 - 15 * tau + 6 * tau**2), 12, 45)
    >>> transcription = SplineTranscription(program)
    >>> current = transcription.iterate(timing)
    >>> step = transcription.step(timing, current, 0.02)
    >>> bool(transcription.iterate(step.timing).excess < current.excess)
    True
    """

    def __init__(self, program: PathProgram, knot_spacing_s: float = KNOT_SPACING_S) -> None:
        self.program = program
        self.knot_spacing_s = knot_spacing_s
        self.length = float(program.path.length_m)
        self.programs = 0
        self.active: tuple[int, list[NDArray[np.bool_]]] | None = None

    def iterate(self, timing: SplineTiming) -> ProgramIterate:
        """The export samples of ``timing`` with their exact evaluation."""
        return self.program.iterate(timing.samples(self.program.ts))

    # ------------------------------------------------------------------ one program
    def step(
        self, timing: SplineTiming, current: ProgramIterate, trust: float
    ) -> StepResult | None:
        """One program around ``timing`` (module docstring): the splines that minimise the
        largest linearised ratio to a limit with every coefficient of s within trust S of
        its value (the tilt's within 2.5 trust rad). None when the solver failed."""
        program, lim = self.program, self.program.limits
        ts, steps, count = program.ts, timing.steps, timing.count
        tilting = program.tilt
        free = count - 6
        nz = free * (3 if tilting else 1)
        tau = np.arange(steps + 1) / steps
        basis = timing.basis(tau)[:, 3 : count - 3]
        samples, ev = current.samples, current.evaluation
        n = steps + 1 + HOLD
        bands = program.jacobians(samples)
        starts = list(range(SEGMENT_SAMPLES, n - 1, SEGMENT_SAMPLES))
        # the variables: the splines, then N's turn about the axis at each segment's start
        # (`sloshkit.plan.path.axial_turn`; zero columns when N does not turn)
        nv = nz + len(starts)
        # each sample's deviation in each variable block, (n, nv)
        blocks = []
        for block in range(3 if tilting else 1):
            dz = np.zeros((n, nv))
            dz[: steps + 1, block * free : (block + 1) * free] = basis
            blocks.append((bands[block], dz))
        turn = axial_turn(blocks, ev.force, ev.drive[0][0, :, 3:], starts, nz)
        if turn is None:
            nv = nz
            blocks = [(band, dz[:, :nz]) for band, dz in blocks]
        keep = 1.0 - PROGRAM_MARGIN
        modes, models = len(program.modes), len(program.models)
        rows: list[NormRows] = []
        position = np.zeros((n, 3, nv))
        for band, dz in blocks:
            position += band.position[:, :, None] * dz[:, None, :]
        for order, values, limit in (
            (1, ev.velocity, lim.max_velocity_m_s),
            (2, ev.acceleration, lim.max_acceleration_m_s2),
            (3, ev.jerk, lim.max_jerk_m_s3),
        ):
            rows.append(NormRows(values, _differences(position, order, ts), limit))
        self._angular_rows(rows, ev, blocks, n, nv)
        if tilting:
            tilt = np.zeros((n, 2))
            tilt[: steps + 1] = samples.tilt_rad
            dtilt = np.stack([blocks[1][1], blocks[2][1]], axis=1)
            for order, limit in (
                (0, lim.max_tilt_rad),
                (1, lim.max_tilt_rate_rad_s),
                (2, lim.max_tilt_acceleration_rad_s2),
            ):
                rows.append(
                    NormRows(
                        _differences(tilt, order, ts) if order else tilt,
                        _differences(dtilt, order, ts) if order else dtilt,
                        limit,
                    )
                )
        if program.joint_model is not None:
            rows.append(self._joint_rows(samples, ev, blocks, steps, nv))
        # the trust region, and the columns' units: the box for the splines, the states' reach
        # within it for the segments' start states
        box = np.full(nz, trust * self.length)
        if tilting:
            box[free:] = 2.5 * trust
        # ----------------------------------------------- pendulums, condensed per segment
        segments = len(starts)
        state_base = nv
        state_width = 6 * modes
        slack = state_base + models * segments * state_width
        residual_base = slack + 1
        columns = residual_base + 2 * modes * models
        scale = np.ones(columns)
        scale[:nz] = box
        cones = ConicProgram()
        turned = [] if turn is None else turn.blocks
        if turn is not None:
            # each segment's turn, within the reach of the box, tied to the splines
            scale[nz:nv] = np.maximum(np.abs(turn.starts[:, :nz]) @ box, 1e-12)
            for used, coefficients in turn.equalities():
                cones.add("zero", np.zeros(used.size, dtype=int), used, coefficients, [0.0])
        for m, model in enumerate(program.models):
            lengths, omegas, zetas = mode_arrays(model)
            # the frame's lateral turning rates (Euler, centrifugal and Coriolis terms) enter
            # only when the container tilts, or may
            width = 7 if tilting or np.any(ev.drive[m][..., 3:]) else 3
            a_k, b_k, e_k = step_jacobians(
                ev.unit[m],
                ev.rate[m],
                ev.drive[m][..., :width],
                lengths,
                omegas,
                zetas,
                ts,
                program.linear,
            )
            kappa = omegas**2 * lengths / model.gravity_m_s2
            states = condense((a_k, b_k, e_k), blocks + turned, kappa, width, starts)
            phi, segment = states.phi, states.segment
            model_base = state_base + m * segments * state_width

            def first_column(seg: NDArray[np.int64], base: int = model_base) -> Any:
                return np.where(seg > 0, base + (seg - 1) * state_width, -1)

            # the segments' start states: x_i = Phi x_{i-1} + Psi z at each start
            for i, start in enumerate(starts, start=1):
                psi_start = states.psi_at(start)
                for q in range(modes):
                    row = np.arange(6)
                    own = model_base + (i - 1) * state_width + 6 * q
                    reach = np.abs(psi_start[q]) @ scale[:nv]
                    if i > 1:
                        before = scale[own - state_width : own - state_width + 6]
                        reach = reach + np.abs(phi[q, start]) @ before
                    scale[own : own + 6] = np.maximum(reach, 1e-12)
                    r_list = [row]
                    c_list = [own + row]
                    v_list = [np.ones(6)]
                    rr, cc = np.nonzero(psi_start[q])
                    r_list.append(rr)
                    c_list.append(cc)
                    v_list.append(-psi_start[q][rr, cc])
                    if i > 1:
                        previous = model_base + (i - 2) * state_width + 6 * q
                        rr, cc = np.nonzero(phi[q, start])
                        r_list.append(rr)
                        c_list.append(previous + cc)
                        v_list.append(-phi[q, start][rr, cc])
                    cones.add(
                        "zero",
                        np.concatenate(r_list),
                        np.concatenate(c_list),
                        np.concatenate(v_list),
                        np.zeros(6),
                    )
            # the wall height: sum_n e_n J_n (Phi_n x_seg,n + Psi_n z)[:3]
            wall_x = np.zeros((n, 2, state_width))
            slopes = np.empty((modes, n, 2, 3))
            for q, mode in enumerate(model.modes):
                slopes[q] = mode.wall_elevation_factor_m * slope_jacobian(ev.unit[m, q])
                wall_x[:, :, 6 * q : 6 * q + 6] = np.einsum(
                    "kac,kcw->kaw", slopes[q], phi[q, :, :3]
                )
            wall_z = states.wall(slopes)
            rows.append(
                NormRows(ev.wall[m], wall_z, lim.max_height_m, wall_x, first_column(segment))
            )
            if lim.max_surface_angle_rad is not None:
                # the first mode's slope alone, within tan of the surface-angle limit
                first = np.zeros_like(slopes)
                first[0] = slopes[0] / model.modes[0].wall_elevation_factor_m
                angle_x = np.zeros_like(wall_x)
                angle_x[:, :, :6] = np.einsum("kac,kcw->kaw", first[0], phi[0, :, :3])
                slope = mode_slope(ev.unit[m, 0])
                tangent = math.tan(lim.max_surface_angle_rad)
                segment_first = first_column(segment)
                rows.append(NormRows(slope, states.wall(first), tangent, angle_x, segment_first))
            # the residual: per mode |e_n [A_n B_n]|_2 as half the sum of two norms
            last = n - 1
            end_column = first_column(segment[last : last + 1])[0]
            psi_last = states.psi_at(last)
            for q, mode in enumerate(model.modes):
                damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
                sig = mode.damping_ratio * mode.omega_rad_s
                back = math.exp(sig * HOLD * ts)
                e = back * mode.wall_elevation_factor_m / lim.max_residual_height_m
                # the lateral deviations (u_x, u_y, u'_x, u'_y) at the end over z and x_seg
                state_z = psi_last[q]
                state_x = np.zeros((6, state_width))
                state_x[:, 6 * q : 6 * q + 6] = phi[q, last]
                combos = []
                for source in (state_z, state_x):
                    a_x, a_y = e * source[0], e * source[1]
                    b_x = e * (source[3] + sig * source[0]) / damped
                    b_y = e * (source[4] + sig * source[1]) / damped
                    combos.append((a_x + b_y, a_y - b_x, a_x - b_y, b_x + a_y))
                av, cv, bv, dv = ev.amplitude[m, q] / lim.max_residual_height_m
                currents = (av + dv, cv - bv, av - dv, bv + cv)
                for cone in range(2):
                    r_list = [np.array([0])]
                    c_list = [np.array([residual_base + 2 * (m * modes + q) + cone])]
                    v_list = [np.array([-1.0])]
                    for component in (1, 2):
                        index = 2 * cone + component - 1
                        through_z = combos[0][index]
                        nonzero = np.flatnonzero(through_z)
                        r_list.append(np.full(nonzero.size, component))
                        c_list.append(nonzero)
                        v_list.append(-through_z[nonzero])
                        if end_column >= 0:
                            through_x = combos[1][index]
                            nonzero = np.flatnonzero(through_x)
                            r_list.append(np.full(nonzero.size, component))
                            c_list.append(end_column + nonzero)
                            v_list.append(-through_x[nonzero])
                    cones.add_soc(
                        np.concatenate(r_list),
                        np.concatenate(c_list),
                        np.concatenate(v_list),
                        [0.0, currents[2 * cone], currents[2 * cone + 1]],
                        [3],
                    )
            # sum of the modes' semi-major axes within keep + sigma
            cones.add(
                "nonneg",
                np.zeros(2 * modes + 1, dtype=int),
                np.concatenate((residual_base + 2 * m * modes + np.arange(2 * modes), [slack])),
                np.concatenate((np.full(2 * modes, 0.5), [-1.0])),
                [keep],
            )
        # ----------------------------------------------- monotone s, trust region, sigma
        coefficients = timing.coefficients_m
        difference = np.arange(free - 1)
        cones.add(
            "nonneg",
            np.repeat(difference, 2),
            np.column_stack((difference + 1, difference)).ravel(),
            np.tile([-1.0, 1.0], free - 1),
            np.diff(coefficients[3 : count - 3]),
        )
        cones.add("nonneg", [0], [0], [-1.0], [coefficients[3]])  # c_3 >= c_2 = 0
        cones.add("nonneg", [0], [free - 1], [1.0], [self.length - coefficients[count - 4]])
        variables = np.arange(nz)
        cones.add("nonneg", variables, variables, np.ones(nz), box)
        cones.add("nonneg", variables, variables, -np.ones(nz), box)
        cones.add("nonneg", [0], [slack], [-1.0], [1.0])  # sigma >= -1
        objective = np.zeros(columns)
        objective[slack] = 1.0
        selected = [group.initial(keep) for group in rows]
        if self.active is not None and len(self.active[1]) == len(selected):
            # the rows the last program needed, at this N's samples: the next one, close by,
            # needs most of them, and each constraint-generation round is a full solve
            last_steps, carried = self.active
            selected = [
                use | _carried(old, last_steps, steps, use.size)
                for use, old in zip(selected, carried, strict=True)
            ]
        x, broken = None, 0.0
        for _ in range(GENERATION_ROUNDS):
            chosen = ConicProgram()
            for group, use in zip(rows, selected, strict=True):
                chosen.add_rows(group, use, slack, keep)
            x = cones.solve(objective, [chosen], scale)
            self.programs += 1
            if x is None:
                return None
            # the largest linearised ratio of a row left out that the solution breaks (after
            # the last round, the step's prediction includes it)
            broken = 0.0
            for group, use in zip(rows, selected, strict=True):
                linearised = group.predicted(x, nv)
                over = (linearised > keep + x[slack] + 1e-6) & ~use
                if over.any():
                    broken = max(broken, float(linearised[over].max() - keep - x[slack]))
                use |= over | np.roll(over, 1) | np.roll(over, -1)
            if not broken:
                break
        assert x is not None
        self.active = (steps, selected)
        new_s = coefficients.copy()
        new_s[3 : count - 3] = np.clip(new_s[3 : count - 3] + x[:free], 0.0, self.length)
        new_s = np.maximum.accumulate(new_s)
        new_tilt = timing.tilt_rad.copy()
        if tilting:
            new_tilt[3 : count - 3, 0] += x[free : 2 * free]
            new_tilt[3 : count - 3, 1] += x[2 * free : 3 * free]
        size = float(np.max(np.abs(x[:free]))) / self.length if free else 0.0
        if tilting:
            size = max(size, float(np.max(np.abs(x[free:nz]))) / 2.5)
        return StepResult(
            SplineTiming(new_s, new_tilt, steps), keep + float(x[slack]) + broken, size
        )

    def _angular_rows(
        self, rows: list[NormRows], ev: Any, blocks: list[Any], n: int, nz: int
    ) -> None:
        """The container's angular velocity and acceleration (when limited): omega_i from the
        samples i - 1 and i (`PathProgram.jacobians`' bands), alpha its difference."""
        lim, ts = self.program.limits, self.program.ts
        if lim.max_angular_velocity_rad_s is None and lim.max_angular_acceleration_rad_s2 is None:
            return
        domega = np.zeros((n + 1, 3, nz))
        for band, dz in blocks:
            index = np.arange(1, n)
            domega[index] += band.omega[1][index][:, :, None] * dz[index][:, None, :]
            domega[index] += band.omega[0][index][:, :, None] * dz[index - 1][:, None, :]
        if lim.max_angular_velocity_rad_s is not None:
            rows.append(NormRows(ev.omega, domega, lim.max_angular_velocity_rad_s))
        if lim.max_angular_acceleration_rad_s2 is not None:
            rows.append(
                NormRows(
                    ev.alpha, np.diff(domega, axis=0) / ts, lim.max_angular_acceleration_rad_s2
                )
            )

    def _joint_rows(
        self, samples: PathSamples, ev: Any, blocks: list[Any], steps: int, nz: int
    ) -> NormRows:
        """Each joint's speed (q_k+1 - q_k) / (h limit) within 1 (a one-dimensional cone per
        joint and period), q linear in the samples' deviations through dq/ds and dq/dr."""
        model = self.program.joint_model
        assert model is not None
        _, dq_ds, dq_dr = model.at(samples.s_m, samples.tilt_rad)
        scaled = self.program.ts * model.joints.limits_rad_s
        dq = dq_ds[:, :, None] * blocks[0][1][: steps + 1, None, :]
        if len(blocks) > 1:
            for c in (0, 1):
                dq = dq + dq_dr[:, :, c, None] * blocks[1 + c][1][: steps + 1, None, :]
        derivative = np.diff(dq, axis=0) / scaled[None, :, None]
        values = ev.joint[:steps]
        dof = values.shape[1]
        return NormRows(values.reshape(-1, 1), derivative.reshape(steps * dof, 1, nz), 1.0)


__all__ = [
    "GENERATION_ROUNDS",
    "KNOT_SPACING_S",
    "PROGRAM_MARGIN",
    "SEGMENT_SAMPLES",
    "SplineTranscription",
    "StepResult",
]
