"""How a path program's limited quantities scale with the move's duration: a timing
stretched uniformly in time by a factor lambda, s(t / lambda), has its k-th time derivative
divided by lambda^k (the chain rule), so a speed by lambda, an acceleration by lambda^2,
a jerk by lambda^3, and a slosh height as the acceleration that tilts the quasi-static
surface (h = R a / g; `sloshkit.plan.path.starts.capped_start`) (`EXPONENTS`). The
minimum-time search over the duration (`sloshkit.plan.path.minimum_time.shortest`) guesses
its next number of samples from these laws: the binding quantity (`binding`) and the
exponent measured between two durations (`exponent`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

#: The duration's scaling exponent of each limited quantity's ratio (T^-p).
EXPONENTS = {
    "velocity": 1.0,
    "angular velocity": 1.0,
    "joint speed": 1.0,
    "tilt rate": 1.0,
    "acceleration": 2.0,
    "angular acceleration": 2.0,
    "tilt acceleration": 2.0,
    "peak slosh": 2.0,
    "residual slosh": 2.0,
    "surface angle": 2.0,
    "jerk": 3.0,
    "tilt": 2.0,
}


#: Ratios within this fraction of the largest tie with it (a min-max program leaves its active
#: quantities at one ratio, to the linearisation's accuracy, about 1e-7 relative).
TIE = 1e-5


def binding(ratios: dict[str, float]) -> str:
    """The binding quantity: of those tied at the largest ratio (`TIE`), the one whose ratio
    a uniform time scaling brings to 1 last, the largest r^(1/p) (`EXPONENTS`): for
    r > 1 the one a stretch brings under its limit last, for r < 1 the one a shortening
    brings to it first.

    Parameters
    ----------
    ratios : dict
        Each limited quantity's peak over its limit.

    Returns
    -------
    str

    Examples
    --------
    >>> binding({"jerk": 1.0178, "peak slosh": 1.0178, "joint speed": 1.0178})
    'joint speed'
    >>> binding({"jerk": 0.95, "peak slosh": 0.95, "velocity": 0.7})
    'jerk'
    """
    top = max(ratios.values())
    tied = [name for name, ratio in ratios.items() if ratio >= (1.0 - TIE) * top]
    # then the larger ratio and the name: the same answer whatever the dictionary's order
    return max(
        tied,
        key=lambda name: (ratios[name] ** (1.0 / EXPONENTS.get(name, 2.0)), ratios[name], name),
    )


def exponent(trials: Sequence[Any], default: float) -> float:
    """p in ratio ~ N^-p: the secant through the last two durations' largest ratios when they
    are close (within 5 % of N) and ordered as that law says, within [1, 6]; else
    ``default``, the binding quantity's own order.

    Parameters
    ----------
    trials : sequence
        The durations tried, each with ``steps`` (N) and ``excess`` (its largest ratio);
        the last two count.
    default : float
        The exponent without a usable secant.

    Returns
    -------
    float

    Examples
    --------
    >>> from types import SimpleNamespace as Trial
    >>> trials = [Trial(steps=199, excess=0.934), Trial(steps=192, excess=1.053)]
    >>> round(exponent(trials, 2.0), 2)
    3.35
    """
    if len(trials) >= 2:
        first, second = trials[-2], trials[-1]
        if first.steps != second.steps and abs(first.steps - second.steps) <= 0.05 * first.steps:
            slope = -math.log(second.excess / first.excess) / math.log(second.steps / first.steps)
            if slope > 0.0:
                return min(max(slope, 1.0), 6.0)
    return default


__all__ = ["EXPONENTS", "TIE", "binding", "exponent"]
