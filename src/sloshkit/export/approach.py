"""The URScript approach: how long a program waits for the slosh of its ``movej`` to settle.

The approach to the first sample is a joint move whose path depends on where the arm was; what
it leaves in the liquid is bounded from the model and the arm's Jacobian at the first sample
(`approach_settle_time`), and the program waits until that bound has decayed below the plan's
residual limit.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from sloshkit.export.frames import Mounting
from sloshkit.export.kinematics import Arm
from sloshkit.model.modal import SloshModel
from sloshkit.plan.line.problem import SloshLimits
from sloshkit.plan.path.problem import SpatialSloshLimits

FloatArray = NDArray[np.float64]


#: Dynamic amplification of a pendulum's angle by an acceleration step (undamped: twice the
#: quasi-static angle; den Hartog, *Mechanical Vibrations*, 4th ed. (1956) §2.2).
STEP_AMPLIFICATION = 2.0
#: Without a residual limit the approach's slosh is waited for until it decays to this
#: fraction of its bound.
SETTLE_FRACTION = 0.1


def approach_settle_time(
    arm: Arm,
    first_rad: FloatArray,
    mounting: Mounting,
    model: SloshModel | None,
    limits: SloshLimits | SpatialSloshLimits | None,
) -> tuple[float, str]:
    """How long a URScript program waits after its approach ``movej`` [s], and a note.

    The approach (joint acceleration a, speed v: `urscript.APPROACH_ACCELERATION_RAD_S2`,
    `urscript.APPROACH_SPEED_RAD_S`) accelerates the container by at most
    ``|J_c| sqrt(n) (a + v^2)`` (J_c the container's linear Jacobian at the first sample,
    n joints all at a and v: the tangential and centripetal terms); the slosh it leaves is at
    most `STEP_AMPLIFICATION` times the quasi-static angle ``atan(a_c / g)``, and decays as
    ``exp(-zeta_1 omega_1 t)`` (the first mode's free decay). The wait is the time for that
    bound to fall below the plan's residual limit (first-mode angle; for 3-D limits the
    residual height over the first mode's wall factor), or to `SETTLE_FRACTION` of itself
    without limits.

    Parameters
    ----------
    arm : Arm
        The arm.
    first_rad : numpy.ndarray
        Joint positions of the first sample [rad].
    mounting : Mounting
        The container in the flange.
    model : SloshModel or None
        The slosh model (None: no wait, said in the note).
    limits : SloshLimits, SpatialSloshLimits or None
        The plan's limits.

    Returns
    -------
    tuple
        (wait [s], note: "" or why there is no wait).

    Examples
    --------
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.export.kinematics import load_arm
    >>> from sloshkit.plan.line.problem import SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039,
    ...                          damping_ratio=0.03)
    >>> arm = load_arm("ur5e")
    >>> wait, _ = approach_settle_time(arm, arm.home_rad, Mounting(), model,
    ...                                SloshLimits(math.radians(5), math.radians(0.25)))
    >>> 2.0 < wait < 10.0
    True
    """
    from sloshkit.export.formats.urscript import (
        APPROACH_ACCELERATION_RAD_S2,
        APPROACH_SPEED_RAD_S,
    )
    from sloshkit.model.theory import GRAVITY_M_S2

    if model is None:
        return 0.0, "no slosh model: the program does not wait for the approach's slosh to settle"
    jacobian = arm.jacobian(np.asarray(first_rad, dtype=float))
    flange = arm.forward(np.asarray(first_rad, dtype=float)[None])[0]
    lever = flange[:3, :3] @ mounting.flange_to_container[:3, 3]
    linear = jacobian[:3] - _skew(lever) @ jacobian[3:]
    count = math.sqrt(arm.dof)
    acceleration = (
        float(np.linalg.norm(linear, 2))
        * count
        * (APPROACH_ACCELERATION_RAD_S2 + APPROACH_SPEED_RAD_S**2)
    )
    bound = STEP_AMPLIFICATION * math.atan2(acceleration, GRAVITY_M_S2)
    first = model.modes[0]
    if isinstance(limits, SpatialSloshLimits):
        target = limits.max_residual_height_m / abs(first.wall_elevation_factor_m)
    elif limits is not None:
        target = limits.max_residual_rad
    else:
        target = SETTLE_FRACTION * bound
    decay = first.damping_ratio * first.omega_rad_s
    if bound <= target or decay <= 0.0:
        return 0.0, ""
    return math.log(bound / target) / decay, ""


def _skew(vector: FloatArray) -> FloatArray:
    x, y, z = (float(value) for value in vector)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
