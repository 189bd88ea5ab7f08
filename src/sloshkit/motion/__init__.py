"""Motion laws (rest-to-rest, 1-D) and input shaping."""

from sloshkit.motion.laws import (
    LAW_NAMES,
    cubic,
    make_law,
    minimum_jerk,
    quintic,
    s_curve,
    septic,
    trapezoidal,
)
from sloshkit.motion.profile import Motion
from sloshkit.motion.recorded import from_samples

__all__ = [
    "LAW_NAMES",
    "Motion",
    "cubic",
    "from_samples",
    "make_law",
    "minimum_jerk",
    "quintic",
    "s_curve",
    "septic",
    "trapezoidal",
]
