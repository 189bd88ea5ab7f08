"""The minimum-time timing of a 3-D path, verified: rounds of the minimum-time search of the
spline transcription (`sloshkit.plan.path.minimum_time.shortest`;
`sloshkit.plan.path.transcription`, the variables and one program;
`sloshkit.plan.path.program`, the model), each exported and re-simulated.

The programs model what the verification simulates without its smoothing filter; the
verification, which also simulates the export through that filter, can still exceed a slosh
limit by a percent or two. The program's limit is then moved by regula falsi (`_next_limit`)
and the search restarts from the last splines (`plan_optimal`).

The tilted search first runs with the small-angle pendulums (`PathProgram(..., linear=True)`,
`sloshkit.plan.path.small_angle`): the large-angle pendulums' frequency falls with
their amplitude, which makes the residual so nonlinear in the splines that their programs'
trust regions stay small and a tilted search crept towards its duration a few samples at a
time; the small-angle residual is linear in the drive. The large-angle rounds then start
from that plan (docs/planning-3d.md, "The tilted search starts with the small-angle
pendulums").
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.plan.path.joints import joint_map
from sloshkit.plan.path.minimum_time import (
    FIRST_TRUST,
    MAX_DURATIONS,
    knot_count,
    respaced,
    shortest,
)
from sloshkit.plan.path.program import PathProgram, ProgramLimits
from sloshkit.plan.path.samples import export_poses
from sloshkit.plan.path.splines import SplineTiming, fit_timing
from sloshkit.plan.path.transcription import SplineTranscription

#: Searches of `plan_optimal`, each with the program's slosh limits moved towards the values
#: at which the verification meets its limits (`_next_limit`), at most.
TIGHTENINGS = 5
#: A verified plan whose peak or residual is within this fraction of its limit ends them.
LIMIT_TOLERANCE = 0.02
#: The tilt's rate and acceleration limits where the angular ones are lifted [rad/s, rad/s^2]
#: (as `benchmarks/ocp_reference.py`'s tilted problem).
TILT_RATE_RAD_S = math.pi
TILT_ACCELERATION_RAD_S2 = math.radians(1000.0)
#: The least relative distance of two rounds' program limits for `_next_limit` to
#: interpolate between them.
BRACKET = 0.01
#: Where the program's slosh limits aim, as a fraction of the limits: the first round starts
#: there and `_next_limit` moves them towards the verification meeting it.
LIMIT_AIM = 1.0 - 0.5 * LIMIT_TOLERANCE


def capped_start(problem: Any, shaped: bool = False) -> SplineTiming:
    """A first timing: the time-optimal speed profile under the quasi-static acceleration
    that tilts a level surface to the height limit (h = R a / g;
    `sloshkit.plan.path.retime.capped_timing`), as splines on the export grid. ``shaped``:
    box-filtered for the jerk limit and shaped on the first mode for the turning of the path
    (`sloshkit.plan.path.retime.family_member` with `curve_shaper`), a residual that stays
    small when the timing is stretched.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model and export period.
    shaped : bool
        Whether to filter and shape the profile.

    Returns
    -------
    SplineTiming
        On the export grid, upright.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> problem = sk.PathProblem(sk.path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     sk.CartesianLimits(2.0, 10.0, 100.0), sk.SpatialSloshLimits(0.008, 0.001), model)
    >>> start = capped_start(problem)
    >>> start.steps, float(start.coefficients_m[-1])
    (125, 0.1)
    """
    from sloshkit.plan.path.retime import capped_timing, curve_shaper, family_member

    machine, slosh = problem.machine, problem.slosh
    cap = min(
        machine.max_acceleration_m_s2,
        GRAVITY_M_S2 * slosh.max_height_m / float(problem.model.radius_m),
    )
    first = (
        family_member(problem, cap, curve_shaper(problem))
        if shaped
        else capped_timing(problem, cap)
    )
    duration = first.duration_s
    tau = np.linspace(0.0, 1.0, 8 * knot_count(duration) + 1)
    s = np.clip(first.position(tau * duration), 0.0, problem.path.length_m)
    s[-1] = problem.path.length_m
    steps = max(8, math.ceil(duration / problem.sample_period_s))
    return fit_timing(tau, s, knot_count(duration), steps)


def plan_optimal(problem: Any, verifier: Any, log: Any = None, tilt: bool = False) -> Any:
    """The minimum-time timing (and, with ``tilt``, the tilt) of the path, verified.

    Rounds of the minimum-time search (`shortest`; `_Rounds`): the first from
    `capped_start`, each next one from the last one's splines with the program's slosh
    limits moved towards the values at which the verification meets its limits
    (`_next_limit`; at most `TIGHTENINGS`). The rounds end when the verified plan's binding
    slosh is within `LIMIT_TOLERANCE` of its limit, or when a round no longer shortens the
    plan; the shortest verified timing is kept (the 25 Hz smoothing the verification also
    simulates moves the slosh by several percent at a 10 ms period, so a round can miss the
    limits its program met). With ``tilt`` the upright rounds run first; from their shortest
    verified plan (a plan with zero tilt is a tilted plan too) a search with the small-angle
    pendulums runs (`_Rounds.navigated`; module docstring), and the tilted rounds start from
    its plan, or again from the upright plan when their first search meets no limit in
    `FIRST_DURATIONS` durations. The shorter verified plan of the two is returned
    (``detail["tilted"]`` says which), so a tilted plan is never longer than the upright one.
    A limit outside the program is met by a uniform stretch
    (`sloshkit.plan.path.result.verified_candidate`); a verifier that checks an arm's joint
    speeds (`sloshkit.plan.path.result.JointSpeedCheck`) lends the programs the joints along
    the path (`sloshkit.plan.path.joints.joint_map`), and they limit the joint speeds
    themselves.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    verifier : callable
        (problem, poses, tilted) -> Verification.
    log : callable, optional
        Receives one line per duration searched and per verification.
    tilt : bool
        Whether the two tilt angles are variables of the programs (splines zero at both
        ends; limited to ``problem.max_tilt_rad``, the angular velocity and acceleration
        limits, else pi rad/s and 1000 deg/s^2, about ``problem.tilt_centre_height_m``).
        With an arm's joint check the joints enter the tilted programs by their quadratic
        model in the tilt (`sloshkit.plan.path.joints.JointModel`); when the arm cannot reach
        the tilted probes of that model, the plan is upright (``detail["upright"]`` says why).

    Returns
    -------
    PathCandidate
        Method ``optimal``; ``detail`` has the programs solved, each round's limits, verified
        slosh, durations tried and whether it was tilted.

    Examples
    --------
    >>> import sloshkit as sk
    >>> from sloshkit.plan.path.result import verify
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> problem = sk.PathProblem(sk.path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     sk.CartesianLimits(2.0, 10.0, 100.0), sk.SpatialSloshLimits(0.008, 0.001), model,
    ...     sample_period_s=0.01)
    >>> found = plan_optimal(problem, verify)
    >>> rounds = found.detail["rounds"]
    >>> found.feasible, found.duration_s == min(r["duration_s"] for r in rounds
    ...     if r["verified_peak_m"] <= 0.008 and r["verified_residual_m"] <= 0.001)
    (True, True)
    """
    import time

    from sloshkit.plan.path.result import JointSpeedCheck, PathCandidate, verified_candidate

    started = time.perf_counter()
    tilt = tilt and problem.max_tilt_rad > 0.0
    arm = isinstance(verifier, JointSpeedCheck)
    joints = joint_map(problem, verifier, tilt=tilt) if arm else None
    if isinstance(joints, str):
        return PathCandidate("optimal", None, None, time.perf_counter() - started, joints)
    # the joints' model in the tilt needs the IK of the tilted probes: where the arm cannot
    # reach them, plan upright
    upright_for_arm = tilt and joints is not None and joints.tilt_gradient is None
    tilt = tilt and not upright_for_arm
    search = _Rounds(problem, verifier, joints, log)
    search.run(False, None)
    if tilt:
        upright = min(search.verified, key=lambda found: found.steps, default=None)
        search.run(True, upright or search.last)
    if not search.verified:
        # a uniform stretch does not rescue these: the residual turns with the duration
        message = search.failure or (
            "the verification's slosh exceeds the limits after every tightening (closest: "
            f"{min(search.excesses):.3f} times the limit)"
            if search.excesses
            else "no search ran"
        )
        return PathCandidate("optimal", None, None, time.perf_counter() - started, message)
    # the earlier (upright) plan wins a tie
    best = min(search.verified, key=lambda found: found.steps)
    tilted = bool(np.any(best.tilt_rad))
    ts = problem.sample_period_s

    def poses_for(factor: float) -> Any:
        stretched = best if factor == 1.0 else best.on_steps(math.ceil(best.steps * factor))
        return export_poses(problem, stretched.samples(ts))

    detail: dict[str, Any] = {
        "programs": search.programs,
        "rounds": search.rounds,
        "durations": search.durations,
        "knots": best.count,
        "tilted": tilted,
    }
    if upright_for_arm:
        detail["upright"] = "the arm cannot reach the path tilted by the joint model's probes"
    return verified_candidate("optimal", problem, poses_for, 1.0, started, verifier, tilted, detail)


class _Rounds:
    """The rounds of `plan_optimal`: each a minimum-time search at the program's slosh
    limits, verified, the limits moved by `_next_limit` for the next; the record of all
    rounds (upright, then tilted) and their verified timings."""

    def __init__(self, problem: Any, verifier: Any, joints: Any, log: Any) -> None:
        self.problem, self.verifier, self.joints, self.log = problem, verifier, joints, log
        self.rounds: list[dict[str, Any]] = []
        self.verified: list[SplineTiming] = []
        self.excesses: list[float] = []
        self.durations: list[tuple[int, float]] = []
        self.programs = 0
        self.failure = ""
        self.last: SplineTiming | None = None

    def limits(self) -> ProgramLimits:
        """The programs' limits of a first round: the slosh limits at `LIMIT_AIM`."""
        machine, slosh = self.problem.machine, self.problem.slosh
        return ProgramLimits(
            machine.max_velocity_m_s,
            machine.max_acceleration_m_s2,
            machine.max_jerk_m_s3,
            machine.max_angular_velocity_rad_s,
            machine.max_angular_acceleration_rad_s2,
            LIMIT_AIM * slosh.max_height_m,
            LIMIT_AIM * slosh.max_residual_height_m,
            max_tilt_rad=self.problem.max_tilt_rad,
            max_tilt_rate_rad_s=machine.max_angular_velocity_rad_s or TILT_RATE_RAD_S,
            max_tilt_acceleration_rad_s2=(
                machine.max_angular_acceleration_rad_s2 or TILT_ACCELERATION_RAD_S2
            ),
        )

    def transcription(
        self, limits: ProgramLimits, tilt: bool, linear: bool = False
    ) -> SplineTranscription:
        """The programs of one search."""
        problem = self.problem
        program = PathProgram(
            problem.path,
            problem.models(),
            limits,
            problem.sample_period_s,
            tilt=tilt,
            centre_height_m=problem.tilt_centre_height_m,
            joints=self.joints,
            linear=linear,
        )
        return SplineTranscription(program)

    def navigated(self, start: SplineTiming | None) -> SplineTiming | None:
        """The plan of the tilted search with the small-angle pendulums (module docstring)
        from ``start`` (None: `_first_search`), where the tilted rounds start; ``start`` when
        it failed."""
        transcription = self.transcription(self.limits(), True, linear=True)
        timing: SplineTiming | None
        try:
            if start is None:
                timing, _ = _first_search(self.problem, transcription, self.log)
            else:
                timing, _, _ = shortest(transcription, start, self.log, minimise_first=True)
        except RuntimeError:
            timing = start
        self.programs += transcription.programs
        if self.log and timing is not None:
            self.log(f"small-angle search: {timing.steps * self.problem.sample_period_s:.3f} s")
        return timing

    def run(self, tilt: bool, start: SplineTiming | None) -> None:
        """Rounds with the tilt free or not, from ``start`` (None: `_first_search`). Tilted,
        they start from the small-angle search's plan (`navigated`), and from ``start`` when
        those rounds verified no plan (their first search gives up after `FIRST_DURATIONS`
        durations that met no limit)."""
        if tilt:
            navigated = self.navigated(start)
            longest = None if start is None else start.steps - 1
            if navigated is not start and self.rounds_from(
                tilt, navigated, FIRST_DURATIONS, longest
            ):
                return
        self.rounds_from(tilt, start)

    def rounds_from(
        self,
        tilt: bool,
        timing: SplineTiming | None,
        give_up: int = MAX_DURATIONS,
        longest: int | None = None,
    ) -> bool:
        """The rounds from ``timing`` (None: `_first_search`), the first search giving up
        after ``give_up`` durations that met no limit, none trying more than ``longest``
        samples; whether one verified a plan."""
        from dataclasses import replace

        problem, log = self.problem, self.log
        slosh, ts = problem.slosh, problem.sample_period_s
        limits = self.limits()
        rounds: list[dict[str, Any]] = []
        verified: list[SplineTiming] = []
        for _ in range(TIGHTENINGS):
            transcription = self.transcription(limits, tilt)
            try:
                if timing is None:
                    timing, trials = _first_search(problem, transcription, log)
                else:
                    # the first tilted round minimises the ratio at the upright plan's
                    # duration: its slack, not the upright plan's ratio of about 1, sets the
                    # first step of the search
                    first_tilted = tilt and not rounds
                    timing, _, trials = shortest(
                        transcription,
                        timing,
                        log,
                        give_up=MAX_DURATIONS if rounds else give_up,
                        minimise_first=first_tilted,
                        longest=longest,
                    )
            except RuntimeError as error:
                self.failure = str(error)
                self.programs += transcription.programs
                break
            self.programs += transcription.programs
            self.durations += [(trial.steps, trial.excess) for trial in trials]
            self.last = timing
            check = self.verifier(problem, export_poses(problem, timing.samples(ts)), tilt)
            rounds.append(
                {
                    "duration_s": timing.steps * ts,
                    "tilted": tilt,
                    "height_limit_m": limits.max_height_m,
                    "residual_limit_m": limits.max_residual_height_m,
                    "verified_peak_m": check.peak_height_m,
                    "verified_residual_m": check.residual_height_m,
                }
            )
            if log:
                log(
                    f"verified: peak {check.peak_height_m * 1e3:.3g} mm, residual "
                    f"{check.residual_height_m * 1e3:.3g} mm"
                )
            excess = max(
                check.peak_height_m / slosh.max_height_m,
                check.residual_height_m / slosh.max_residual_height_m,
            )
            self.excesses.append(excess)
            if excess <= 1.0:
                verified.append(timing)
                # done when the binding slosh limit is met within the tolerance, or when
                # moving the program's limits towards the limit no longer shortens the plan
                if excess >= 1.0 - LIMIT_TOLERANCE or (
                    len(verified) >= 2 and verified[-1].steps >= verified[-2].steps
                ):
                    break
            limits = replace(
                limits,
                max_height_m=_next_limit(
                    rounds, "height_limit_m", "verified_peak_m", slosh.max_height_m
                ),
                max_residual_height_m=_next_limit(
                    rounds, "residual_limit_m", "verified_residual_m", slosh.max_residual_height_m
                ),
            )
        self.rounds += rounds
        self.verified += verified
        return bool(verified)


#: Durations the first search from the unshaped capped timing tries before the search
#: starts again from the shaped one, stretched until it meets the limits.
FIRST_DURATIONS = 4


def _first_search(problem: Any, transcription: SplineTranscription, log: Any) -> Any:
    """The first round's search, from the start that one program brings closer to the limits
    at the same duration (`screened_start`): the unshaped capped timing at its own duration
    (near the optimum on most paths), and when `FIRST_DURATIONS` durations did not meet the
    limits from it, or when the shaped one screened better, from the shaped one stretched
    until it meets them (LE_3D: the unshaped start's programs did not bring its residual
    under the limit)."""
    capped, shaped = capped_start(problem), capped_start(problem, shaped=True)
    if screened_start(transcription, capped, shaped) == 0:
        try:
            timing, _, trials = shortest(transcription, capped, log, give_up=FIRST_DURATIONS)
            return timing, trials
        except RuntimeError:
            pass
    if log:
        log("optimal: from the shaped start, stretched until it meets the limits")
    timing, _, trials = shortest(transcription, shaped, log, stretch=True)
    return timing, trials


def screened_start(
    transcription: SplineTranscription, first: SplineTiming, second: SplineTiming
) -> int:
    """Which of two starts lies in the better basin: both at ``first``'s duration, one
    program each (trust region `FIRST_TRUST`), the index (0 or 1) of the one whose exact
    largest ratio to a limit is then lower (0 on a tie or when both programs fail).

    The search's result depends on the basin its first feasible duration falls into, and
    no start wins everywhere: on the benchmark one program at the capped timing's own
    duration ends TRD_2D at 4.03 times the limits from it and at 70.3 from the shaped one;
    on LE_3D (900 degrees of turning) the capped one's program fails and the shaped one's
    ends at 14.0, and only the shaped start reaches the 3.9 s plan. Compared at their own
    durations instead, the shaped start also wins on RD_2D and pick-and-place, to the same
    plans at three times the compute.

    Parameters
    ----------
    transcription : SplineTranscription
        The program.
    first, second : SplineTiming
        The starts; ``second`` is compared at ``first``'s N and coefficient count.

    Returns
    -------
    int
        0 for ``first``, 1 for ``second``.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.program import PathProgram, ProgramLimits
    >>> from sloshkit.plan.path.splines import fit_timing
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002)
    >>> program = PathProgram(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]), [model], limits,
    ...                       0.01)
    >>> tau = np.linspace(0.0, 1.0, 101)
    >>> smooth = fit_timing(tau, 0.1 * tau**3 * (10 - 15 * tau + 6 * tau**2), 10, 45)
    >>> late = fit_timing(tau, 0.1 * np.clip(3 * tau - 2, 0, 1) ** 3, 10, 45)
    >>> screened_start(SplineTranscription(program), smooth, late)
    0
    """
    ratios = []
    for start in (first, respaced(second.on_steps(first.steps), first.count)):
        step = transcription.step(start, transcription.iterate(start), FIRST_TRUST)
        ratios.append(transcription.iterate(step.timing).excess if step else math.inf)
    return int(ratios[1] < ratios[0])


def _next_limit(
    rounds: list[dict[str, float]], program_key: str, verified_key: str, limit: float
) -> float:
    """The program's next limit: the verification's value is an increasing function v(p) of
    the program's limit p (v = p for a linear verification), up to the few percent by which
    each round's local plan differs; regula falsi for v(p) = limit (slightly below) on the
    rounds that bracket it when their program limits are `BRACKET` apart (closer, the
    difference is the plans' scatter, not v's slope), else p limit / v (at most the limit).

    Examples
    --------
    >>> rounds = [{"p": 0.99, "v": 0.9895}, {"p": 0.9904, "v": 1.063}]
    >>> round(_next_limit(rounds, "p", "v", 1.0), 4)  # scatter: scaled, not interpolated
    0.9224
    """
    aim = LIMIT_AIM * limit
    points = sorted((r[program_key], r[verified_key]) for r in rounds)
    below = [p for p in points if p[1] <= aim]
    above = [p for p in points if p[1] > aim]
    if below and above:
        (p1, v1), (p2, v2) = below[-1], above[0]
        if v2 > v1 and p2 > (1.0 + BRACKET) * p1:
            return p1 + (aim - v1) * (p2 - p1) / (v2 - v1)
    p, v = rounds[-1][program_key], rounds[-1][verified_key]
    return min(limit, p * aim / max(v, 1e-12))


__all__ = [
    "BRACKET",
    "LIMIT_AIM",
    "LIMIT_TOLERANCE",
    "TIGHTENINGS",
    "TILT_ACCELERATION_RAD_S2",
    "TILT_RATE_RAD_S",
    "capped_start",
    "plan_optimal",
]
