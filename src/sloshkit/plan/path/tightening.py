"""The programs' slosh limits, moved round by round towards the values at which the nonlinear
verification meets the problem's limits.

The programs linearise the pendulums around their current track; the verification simulates
the sampled export with the nonlinear model of every band frequency, so the two disagree by a
percent or two. Each round records the program's limit p and the verified value v of every
slosh quantity (peak height, residual height and, when limited, the first mode's surface
angle); v(p) is increasing, so the next round's limit solves v(p) = the limit by regula falsi
(`next_limit`).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from sloshkit.plan.path.program import ProgramLimits

#: A verified plan whose binding slosh quantity is within this fraction of its limit ends the
#: rounds.
LIMIT_TOLERANCE = 0.02
#: The least relative distance of two rounds' program limits for `next_limit` to interpolate.
BRACKET = 0.01
#: Where the program's slosh limits aim, as a fraction of the limits: the first round starts
#: there and `next_limit` moves them towards the verification meeting it.
LIMIT_AIM = 1.0 - 0.5 * LIMIT_TOLERANCE
#: Each slosh quantity: the round's key of the program's limit, of the verified value, the
#: limit's field (the same name in `ProgramLimits` and in
#: `sloshkit.plan.path.problem.SpatialSloshLimits`) and the
#: `sloshkit.plan.path.result.Verification` field.
QUANTITIES = (
    ("height_limit_m", "verified_peak_m", "max_height_m", "peak_height_m"),
    ("residual_limit_m", "verified_residual_m", "max_residual_height_m", "residual_height_m"),
    ("angle_limit_rad", "verified_angle_rad", "max_surface_angle_rad", "peak_slosh_angle_rad"),
)


def aimed(slosh: Any) -> dict[str, float | None]:
    """The first round's program limits: each slosh limit at `LIMIT_AIM` (None: not limited).

    Parameters
    ----------
    slosh : SpatialSloshLimits
        The problem's slosh limits.

    Returns
    -------
    dict
        `ProgramLimits` fields.

    Examples
    --------
    >>> from sloshkit.plan.path.problem import SpatialSloshLimits
    >>> aimed(SpatialSloshLimits(0.015, 0.002))["max_surface_angle_rad"] is None
    True
    """
    found: dict[str, float | None] = {}
    for *_, field, _ in QUANTITIES:
        limit = getattr(slosh, field)
        found[field] = None if limit is None else LIMIT_AIM * limit
    return found


def round_record(limits: ProgramLimits, check: Any) -> dict[str, float]:
    """A round's program limits and verified values (`QUANTITIES`; the angle's only when
    limited).

    Parameters
    ----------
    limits : ProgramLimits
        The round's program limits.
    check : Verification
        The verification of its plan.

    Returns
    -------
    dict

    Examples
    --------
    >>> from sloshkit.plan.path.result import Verification
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.0148, 0.00198)
    >>> sorted(round_record(limits, Verification(0.0149, 0.0019, 0.0, 0.0, ())))
    ['height_limit_m', 'residual_limit_m', 'verified_peak_m', 'verified_residual_m']
    """
    record = {}
    for program_key, verified_key, field, check_field in QUANTITIES:
        if getattr(limits, field) is not None:
            record[program_key] = getattr(limits, field)
            record[verified_key] = getattr(check, check_field)
    return record


def verified_excess(check: Any, slosh: Any) -> float:
    """The largest verified slosh quantity over its limit.

    Parameters
    ----------
    check : Verification
        A plan's verification.
    slosh : SpatialSloshLimits
        The problem's slosh limits.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.plan.path.problem import SpatialSloshLimits
    >>> from sloshkit.plan.path.result import Verification
    >>> check = Verification(0.012, 0.001, 0.0, 0.0, (), peak_slosh_angle_rad=0.3)
    >>> round(verified_excess(check, SpatialSloshLimits(0.015, 0.002, 0.25)), 3)
    1.2
    """
    excess = 0.0
    for *_, field, check_field in QUANTITIES:
        limit = getattr(slosh, field)
        if limit is not None:
            excess = max(excess, getattr(check, check_field) / limit)
    return excess


def tightened(limits: ProgramLimits, rounds: list[dict[str, float]], slosh: Any) -> ProgramLimits:
    """The next round's program limits (`next_limit` of each limited slosh quantity).

    Parameters
    ----------
    limits : ProgramLimits
        The last round's.
    rounds : list of dict
        Every round so far (`round_record`).
    slosh : SpatialSloshLimits
        The problem's slosh limits.

    Returns
    -------
    ProgramLimits

    Examples
    --------
    >>> from sloshkit.plan.path.problem import SpatialSloshLimits
    >>> limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.0148, 0.00198)
    >>> rounds = [{"height_limit_m": 0.0148, "verified_peak_m": 0.0160,
    ...            "residual_limit_m": 0.00198, "verified_residual_m": 0.0018}]
    >>> tightened(limits, rounds, SpatialSloshLimits(0.015, 0.002)).max_height_m < 0.0148
    True
    """
    changes = {}
    for program_key, verified_key, field, _ in QUANTITIES:
        limit = getattr(slosh, field)
        if limit is not None:
            changes[field] = next_limit(rounds, program_key, verified_key, limit)
    return replace(limits, **changes)


def next_limit(
    rounds: list[dict[str, float]], program_key: str, verified_key: str, limit: float
) -> float:
    """The program's next limit: the verification's value is an increasing function v(p) of
    the program's limit p (v = p for a linear verification), up to the few percent by which
    each round's local plan differs; regula falsi for v(p) = limit (slightly below) on the
    rounds that bracket it when their program limits are `BRACKET` apart (closer, the
    difference is the plans' scatter, not v's slope), else p limit / v (at most the limit).

    Parameters
    ----------
    rounds : list of dict
        Every round so far.
    program_key, verified_key : str
        The rounds' keys of the program's limit and of the verified value.
    limit : float
        The problem's limit.

    Returns
    -------
    float

    Examples
    --------
    >>> rounds = [{"p": 0.99, "v": 0.9895}, {"p": 0.9904, "v": 1.063}]
    >>> round(next_limit(rounds, "p", "v", 1.0), 4)  # scatter: scaled, not interpolated
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
    "QUANTITIES",
    "aimed",
    "next_limit",
    "round_record",
    "tightened",
    "verified_excess",
]
