"""The minimum-time timing of a 3-D path, verified: rounds of the minimum-time search of the
spline transcription (`sloshkit.plan.path.minimum_time.shortest`;
`sloshkit.plan.path.transcription`, the variables and one program;
`sloshkit.plan.path.program`, the model), each exported and re-simulated.

The programs model what the verification simulates without its smoothing filter; the
verification, which also simulates the export through that filter, can still exceed a slosh
limit by a percent or two. The program's limit is then moved by regula falsi
(`sloshkit.plan.path.tightening`) and the search restarts from the last splines (`plan_programs`).

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
from dataclasses import replace
from typing import Any

import numpy as np

from sloshkit.plan.path.joints import joint_excess, joint_map
from sloshkit.plan.path.minimum_time import MAX_DURATIONS, shortest
from sloshkit.plan.path.program import PathProgram, ProgramLimits
from sloshkit.plan.path.samples import export_poses
from sloshkit.plan.path.side_by_side import side_by_side
from sloshkit.plan.path.splines import SplineTiming
from sloshkit.plan.path.starts import FIRST_DURATIONS, capped_search, capped_start, first_search
from sloshkit.plan.path.tightening import (
    LIMIT_TOLERANCE,
    aimed,
    round_record,
    tightened,
    verified_excess,
)
from sloshkit.plan.path.transcription import KNOT_SPACING_S, SplineTranscription

#: Searches of `plan_programs`, each with the program's slosh limits moved towards the values
#: at which the verification meets its limits (`sloshkit.plan.path.tightening`), at most.
TIGHTENINGS = 5
#: The tilt's rate and acceleration limits where the angular ones are lifted [rad/s, rad/s^2]
#: (as `benchmarks/ocp_reference.py`'s tilted problem).
TILT_RATE_RAD_S = math.pi
TILT_ACCELERATION_RAD_S2 = math.radians(1000.0)
#: The large-angle tilted rounds' knot spacing [s] without an arm, half the other searches'
#: (`sloshkit.plan.path.transcription.KNOT_SPACING_S`): 0.4-1.2 % shorter plans; upright
#: 0-0.2 %, with an arm (joint speeds binding) none (docs/planning-3d.md, "What the splines cost").
TILTED_KNOT_SPACING_S = 0.0125


def plan_programs(
    problem: Any, verifier: Any, log: Any = None, tilt: bool = False, retime: bool = True
) -> tuple[Any, Any]:
    """The minimum-time timing of the path upright and (with ``tilt``) with the tilt free,
    each verified: the programs of ``retime`` and ``tilt`` (`sloshkit.plan.path.planner`).

    Rounds of the minimum-time search (`shortest`; `_Rounds`): the first from
    `sloshkit.plan.path.starts.first_search`, each next one from the last one's splines with
    the program's slosh limits moved towards the values at which the verification meets
    them (`sloshkit.plan.path.tightening`; at most `TIGHTENINGS`), until the binding slosh is within
    `LIMIT_TOLERANCE` of its limit or a round no longer shortens the plan; the shortest
    verified timing is kept. With ``tilt`` the tilted rounds search by way of the
    small-angle search (module docstring) from the capped timing when that start screens
    better than the shaped one (`sloshkit.plan.path.starts.capped_search`), else, or when
    those rounds verify nothing, from the upright plan (`_tilted_rounds`). With ``retime``
    too the upright rounds run beside them in a second thread
    (`sloshkit.plan.path.side_by_side`); without it only when the tilted search needs
    their plan, else they only look for a plan shorter than the tilted one
    (`_Rounds.upright_below`): their whole search beside the tilted one slowed the
    pick-and-place with the UR5e by a fifth (its verifications, the arm's IK, hold the
    GIL). The tilted candidate is the shortest verified plan of all rounds, upright ones
    included (``detail["tilted"]`` says which): never longer than the upright one. A limit outside
    the program is met by a uniform stretch
    (`sloshkit.plan.path.result.verified_candidate`); with an arm's joint check
    (`sloshkit.plan.path.result.JointSpeedCheck`) the programs limit the joint speeds along
    the path themselves (`sloshkit.plan.path.joints.joint_map`).

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model, sample period.
    verifier : callable
        (problem, poses, tilted) -> Verification.
    log : callable, optional
        Receives one line per duration searched and per verification.
    tilt : bool
        Whether the two tilt angles are variables of the programs too (splines zero at both
        ends; limited to ``problem.max_tilt_rad``, the angular velocity and acceleration
        limits, else pi rad/s and 1000 deg/s^2, about ``problem.tilt_centre_height_m``).
        With an arm's joint check the joints enter the tilted programs by their quadratic
        model in the tilt (`sloshkit.plan.path.joints.JointModel`); when the arm cannot reach
        the tilted probes of that model, the tilted candidate is upright
        (``detail["upright"]`` says why).
    retime : bool
        Whether the upright plan is wanted too (with ``tilt``; above); without it the
        upright candidate is None.

    Returns
    -------
    tuple of PathCandidate
        Upright (method ``retime``; None with ``tilt`` and without ``retime``) and tilted
        (method ``tilt``; None without ``tilt``);
        ``detail`` has the programs solved, each round's limits, verified slosh, durations
        tried and whether the plan is tilted; ``compute_time_s`` of the upright one is its
        own rounds'.

    Examples
    --------
    >>> import sloshkit as sk
    >>> from sloshkit.plan.path.result import verify
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> problem = sk.PathProblem(sk.path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     sk.CartesianLimits(2.0, 10.0, 100.0), sk.SpatialSloshLimits(0.008, 0.001), model,
    ...     sample_period_s=0.01)
    >>> found, _ = plan_programs(problem, verify)
    >>> rounds = found.detail["rounds"]
    >>> found.feasible, found.duration_s == min(r["duration_s"] for r in rounds
    ...     if r["verified_peak_m"] <= 0.008 and r["verified_residual_m"] <= 0.001)
    (True, True)
    """
    import time

    from sloshkit.plan.path.result import JointSpeedCheck, PathCandidate

    started = time.perf_counter()
    tilt = tilt and problem.max_tilt_rad > 0.0
    arm = isinstance(verifier, JointSpeedCheck)
    joints = joint_map(problem, verifier, tilt=tilt) if arm else None
    if isinstance(joints, str):
        failed = PathCandidate("retime", None, None, time.perf_counter() - started, joints)
        return failed, (replace(failed, method="tilt") if tilt else None)
    # the joints' model in the tilt needs the IK of the tilted probes: where the arm cannot
    # reach them, plan upright
    upright_for_arm = tilt and joints is not None and joints.tilt_gradient is None
    upright_search = _Rounds(problem, verifier, joints, log)
    if not tilt or upright_for_arm:
        upright_search.run(False, None)
        upright = upright_search.candidate("retime", started, upright_search.verified)
        if not tilt:
            return upright, None
        reason = "the arm cannot reach the path tilted by the joint model's probes"
        tilted = upright_search.candidate("tilt", started, upright_search.verified)
        tilted = replace(tilted, detail={**tilted.detail, "upright": reason})
        return (upright if retime else None), tilted
    tilted_search = _Rounds(problem, verifier, joints, log)
    upright = None
    if retime:

        def upright_rounds(upright_log: Any) -> Any:
            upright_search.log = upright_log
            upright_search.run(False, None)
            return upright_search.candidate("retime", started, upright_search.verified)

        def tilted_rounds(upright_job: Any) -> None:
            _tilted_rounds(tilted_search, upright_search, upright_job.result)

        # both plans wanted: the upright rounds in a second thread (Clarabel releases the GIL)
        upright = side_by_side(upright_rounds, tilted_rounds, log, "upright: ")
    elif _tilted_rounds(tilted_search, upright_search, lambda: upright_search.run(False, None)):
        upright_search.upright_below(min(found.steps for found in tilted_search.verified) - 1)
    tilted_search.absorb(upright_search)
    # the upright plans first: the earlier plan wins a tie
    plans = upright_search.verified + tilted_search.verified
    return upright, tilted_search.candidate("tilt", started, plans)


def _tilted_rounds(search: _Rounds, upright: _Rounds, upright_rounds: Any) -> bool:
    """The tilted rounds: the small-angle search from the capped timing when that start
    screens better than the shaped one (`sloshkit.plan.path.starts.capped_search`), then the
    large-angle rounds from its plan; when it does not, or those rounds verify nothing, from
    the upright rounds' plan (``upright_rounds()`` runs them or waits for them; `_Rounds.run`).
    Whether the first way verified a plan."""
    direct = search.navigated(None, capped_only=True)
    if direct is not None and search.rounds_from(True, direct, FIRST_DURATIONS):
        return True
    upright_rounds()
    start = min(upright.verified, key=lambda found: found.steps, default=upright.last)
    search.run(True, start)
    return False


class _Rounds:
    """The rounds of `plan_programs`: each a minimum-time search at the program's slosh
    limits, verified, the limits moved by `sloshkit.plan.path.tightening` for the next; the
    record of all rounds (upright, then tilted) and their verified timings."""

    def __init__(self, problem: Any, verifier: Any, joints: Any, log: Any) -> None:
        self.problem, self.verifier, self.joints, self.log = problem, verifier, joints, log
        self.checks: dict[bytes, Any] = {}
        self.rounds: list[dict[str, Any]] = []
        self.verified: list[SplineTiming] = []
        self.excesses: list[float] = []
        self.durations: list[tuple[int, float]] = []
        self.programs = 0
        self.failure = ""
        self.last: SplineTiming | None = None

    def absorb(self, other: _Rounds) -> None:
        """Another search's record before this one's (the upright rounds', so that the tilted
        candidate's detail has every round), and its verifications."""
        self.checks.update(other.checks)
        self.rounds = other.rounds + self.rounds
        self.durations = other.durations + self.durations
        self.excesses = other.excesses + self.excesses
        self.programs += other.programs
        self.failure = self.failure or other.failure

    def candidate(self, method: str, started: float, verified: list[SplineTiming]) -> Any:
        """The shortest of ``verified`` that passes the verifier (the earlier, upright, plan
        wins a tie) as a verified candidate named ``method``, or a failed one naming why no
        round verified a plan (or the shortest's failure when none passes)."""
        import time

        from sloshkit.plan.path.result import PathCandidate

        if not verified:
            # a uniform stretch does not rescue these: the residual turns with the duration
            message = self.failure or (
                "the verification's slosh exceeds the limits after every tightening "
                f"(closest: {min(self.excesses):.3f} times the limit)"
                if self.excesses
                else "no search ran"
            )
            return PathCandidate(method, None, None, time.perf_counter() - started, message)
        # the rounds check the slosh; the candidate's verification also the arm's joints and
        # the tilt, which can fail where the programs' joint model was not the IK (a stretch
        # then rarely saves the slosh): the next round's plan is tried, shortest first, until
        # no remaining one is shorter than the best that passed
        found: Any = None
        for timing in sorted(verified, key=lambda plan: plan.steps):
            if (
                found is not None
                and found.feasible
                and (timing.steps * self.problem.sample_period_s >= found.duration_s)
            ):
                break
            trial = self._verified(method, started, timing)
            shorter = found is None or not found.feasible or trial.duration_s < found.duration_s
            if found is None or (trial.feasible and shorter):
                found = trial
        return found

    def _verified(self, method: str, started: float, best: SplineTiming) -> Any:
        """One round's plan as a verified candidate (`verified_candidate`)."""
        from sloshkit.plan.path.result import verified_candidate

        tilted = bool(np.any(best.tilt_rad))
        problem, ts = self.problem, self.problem.sample_period_s

        def poses_for(factor: float) -> Any:
            stretched = best if factor == 1.0 else best.on_steps(math.ceil(best.steps * factor))
            return export_poses(problem, stretched.samples(ts))

        detail: dict[str, Any] = {
            "source": "program",
            "programs": self.programs,
            "rounds": list(self.rounds),
            "durations": list(self.durations),
            "knots": best.count,
            "tilted": tilted,
        }
        return verified_candidate(
            method, problem, poses_for, 1.0, started, self.check, tilted, detail
        )

    def check(self, problem: Any, poses: Any, tilted: bool) -> Any:
        """The verifier's verification of an export, each export verified once: a round's
        plan is verified again as the returned candidate, and with an arm a verification is
        mostly the export's IK."""
        key = b"".join(
            np.ascontiguousarray(array, dtype=float).tobytes()
            for array in (poses.time_s, poses.position_m, poses.quaternion_xyzw)
        )
        key += bytes([tilted])
        if key not in self.checks:
            self.checks[key] = self.verifier(problem, poses, tilted)
        return self.checks[key]

    def limits(self) -> ProgramLimits:
        """The programs' limits of a first round: the slosh limits at
        `sloshkit.plan.path.tightening.LIMIT_AIM`."""
        machine = self.problem.machine
        return ProgramLimits(
            machine.max_velocity_m_s,
            machine.max_acceleration_m_s2,
            machine.max_jerk_m_s3,
            machine.max_angular_velocity_rad_s,
            machine.max_angular_acceleration_rad_s2,
            **aimed(self.problem.slosh),  # type: ignore[arg-type]
            max_tilt_rad=self.problem.max_tilt_rad,
            max_tilt_rate_rad_s=machine.max_angular_velocity_rad_s or TILT_RATE_RAD_S,
            max_tilt_acceleration_rad_s2=(
                machine.max_angular_acceleration_rad_s2 or TILT_ACCELERATION_RAD_S2
            ),
        )

    def transcription(
        self, limits: ProgramLimits, tilt: bool, linear: bool = False, joint_fraction: float = 1.0
    ) -> SplineTranscription:
        """The programs of one search, the arm's joint speeds limited to ``joint_fraction`` of
        their limits."""
        problem, joints = self.problem, self.joints
        if joints is not None and joint_fraction != 1.0:
            joints = joints.scaled(joint_fraction)
        program = PathProgram(
            problem.path,
            problem.models(),
            limits,
            problem.sample_period_s,
            tilt=tilt,
            centre_height_m=problem.tilt_centre_height_m,
            joints=joints,
            linear=linear,
        )
        fine = tilt and not linear and joints is None
        return SplineTranscription(program, TILTED_KNOT_SPACING_S if fine else KNOT_SPACING_S)

    def navigated(
        self, start: SplineTiming | None, capped_only: bool = False
    ) -> SplineTiming | None:
        """The plan of the tilted search with the small-angle pendulums (module docstring)
        from ``start`` (None: `first_search`; with ``capped_only``
        `sloshkit.plan.path.starts.capped_search`), where the tilted rounds start; ``start``
        when it failed."""
        transcription = self.transcription(self.limits(), True, linear=True)
        timing: SplineTiming | None
        try:
            if start is None and capped_only:
                found = capped_search(self.problem, transcription, self.log)
                timing = None if found is None else found[0]
            elif start is None:
                timing, _ = first_search(self.problem, transcription, self.log)
            else:
                timing, _, _ = shortest(transcription, start, self.log, minimise_first=True)
        except RuntimeError:
            timing = start
        self.programs += transcription.programs
        if self.log and timing is not None:
            self.log(f"small-angle search: {timing.steps * self.problem.sample_period_s:.3f} s")
        return timing

    def run(self, tilt: bool, start: SplineTiming | None) -> None:
        """Rounds with the tilt free or not, from ``start`` (None: `first_search`). Tilted,
        they start from the small-angle search's plan (`navigated`; from ``start`` when that
        search failed), their first search giving up after `FIRST_DURATIONS` durations that
        met no limit or before one no shorter than ``start``: the upright plan then stands.
        (Searching again from ``start`` gained nothing where this happened, on the 20
        waypoints, at 355 s; docs/planning-3d.md.)"""
        if tilt:
            navigated = self.navigated(start)
            if navigated is not start:
                longest = None if start is None else start.steps - 1
                self.rounds_from(tilt, navigated, FIRST_DURATIONS, longest)
                return
        self.rounds_from(tilt, start)

    def upright_below(self, steps: int) -> None:
        """Upright rounds that only look for a plan of at most ``steps`` samples (one less
        than a tilted plan's), from the unshaped capped timing
        (`sloshkit.plan.path.starts.capped_start`) at that duration, giving up when it does
        not meet the limits, so that ``tilt`` asked for alone is never slower than the
        upright programs' plan without their whole search."""
        failure = self.failure
        self.rounds_from(False, capped_start(self.problem).on_steps(steps), 1, steps)
        # a failed search below the tilted plan is that plan's confirmation, not a failure
        self.failure = failure

    def rounds_from(
        self,
        tilt: bool,
        timing: SplineTiming | None,
        give_up: int = MAX_DURATIONS,
        longest: int | None = None,
    ) -> bool:
        """The rounds from ``timing`` (None: `first_search`), the first search giving up
        after ``give_up`` durations that met no limit, none trying more than ``longest``
        samples; whether one verified a plan."""
        problem, log = self.problem, self.log
        slosh, ts = problem.slosh, problem.sample_period_s
        limits = self.limits()
        rounds: list[dict[str, Any]] = []
        verified: list[SplineTiming] = []
        joint_fraction = 1.0
        for _ in range(TIGHTENINGS):
            transcription = self.transcription(limits, tilt, joint_fraction=joint_fraction)
            try:
                if timing is None:
                    timing, trials = first_search(problem, transcription, log)
                else:
                    # the first tilted round minimises the ratio at the upright plan's
                    # duration: its slack, not the upright plan's ratio of about 1, sets the
                    # first step of the search
                    first_tilted = tilt and not rounds and not np.any(timing.tilt_rad)
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
            check = self.check(problem, export_poses(problem, timing.samples(ts)), tilt)
            record = round_record(limits, check)
            rounds.append({"duration_s": timing.steps * ts, "tilted": tilt, **record})
            if log:
                log(
                    f"verified: peak {check.peak_height_m * 1e3:.3g} mm, residual "
                    f"{check.residual_height_m * 1e3:.3g} mm"
                )
            excess = verified_excess(check, slosh)
            self.excesses.append(excess)
            joints_over = joint_excess(check)
            if joints_over > 1.0:
                # the IK's joint speeds exceed what the programs' joint model (quadratic in
                # the tilt) predicted: the next round limits them to the same fraction less
                joint_fraction /= joints_over * (1.0 + 0.5 * LIMIT_TOLERANCE)
                rounds[-1]["joint_speed_fraction"] = joint_fraction
            elif excess <= 1.0:
                verified.append(timing)
                # done when the binding slosh limit is met within the tolerance, or when
                # moving the program's limits towards the limit no longer shortens the plan
                if excess >= 1.0 - LIMIT_TOLERANCE or (
                    len(verified) >= 2 and verified[-1].steps >= verified[-2].steps
                ):
                    break
            limits = tightened(limits, rounds, slosh)
        self.rounds += rounds
        self.verified += verified
        return bool(verified)


__all__ = [
    "TIGHTENINGS",
    "TILTED_KNOT_SPACING_S",
    "TILT_ACCELERATION_RAD_S2",
    "TILT_RATE_RAD_S",
    "plan_programs",
]
