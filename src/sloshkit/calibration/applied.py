"""The motion applied during a record, in the record's clock: a 1-D law, a motion file or a
pose file (``t,x,y,z,qx,qy,qz,qw``), reduced to the displacement along one axis."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sloshkit.errors import InputError
from sloshkit.motion.profile import Motion
from sloshkit.motion.recorded import from_samples

AXES: dict[str, tuple[float, float, float]] = {
    "x": (1.0, 0.0, 0.0),
    "y": (0.0, 1.0, 0.0),
    "z": (0.0, 0.0, 1.0),
}


@dataclass(frozen=True, eq=False)
class AppliedMotion:
    """A rest-to-rest motion that starts at ``start_s`` in the record's clock.

    ``notes`` says how it was read (axis, ignored rotation).

    Attributes
    ----------
    motion : Motion
        The rest-to-rest motion in its own clock.
    start_s : float
        Its start in the record's clock [s].
    notes : tuple of str
        How it was read.

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.motion import quintic
    >>> applied = AppliedMotion(quintic(0.1, 0.5), start_s=2.0)
    >>> applied.end_s, applied.velocity(np.array([1.0, 2.25, 3.0])).round(3).tolist()
    (2.5, [0.0, 0.375, 0.0])
    """

    motion: Motion
    start_s: float = 0.0
    notes: tuple[str, ...] = ()

    @property
    def end_s(self) -> float:
        """End of the motion in the record's clock [s]."""
        return self.start_s + self.motion.duration_s

    def velocity(self, time_s: np.ndarray) -> np.ndarray:
        """Container velocity at record times [m/s] (zero outside the motion)."""
        return np.asarray(self.motion.velocity(np.asarray(time_s) - self.start_s), dtype=float)

    def acceleration(self, time_s: np.ndarray) -> np.ndarray:
        """Container acceleration at record times [m/s^2] (zero outside the motion)."""
        return np.asarray(self.motion.acceleration(np.asarray(time_s) - self.start_s), dtype=float)


def _rotation_angle_deg(quaternions: np.ndarray) -> float:
    """Largest rotation from the first orientation [deg]: 2 acos(|q_0 . q|)."""
    unit = quaternions / np.linalg.norm(quaternions, axis=1, keepdims=True)
    dots = np.clip(np.abs(unit @ unit[0]), 0.0, 1.0)
    return math.degrees(2.0 * float(np.max(np.arccos(dots))))


def applied_from_poses(
    time_s: np.ndarray,
    position_m: np.ndarray,
    quaternion_xyzw: np.ndarray | None = None,
    axis: str | None = None,
    name: str = "poses",
) -> AppliedMotion:
    """A pose trajectory (times, positions (n, 3), optional unit quaternions (n, 4) scalar
    last) as a 1-D motion in its own clock.

    The position is projected on ``axis`` (x, y or z) or, by default, on the principal
    direction of the displacement (largest singular vector, oriented along the travel);
    rotations are not part of the 1-D model and are reported in the notes above 2 deg. The
    motion starts at the first time stamp (``start_s``), so poses and a record written by the
    same controller share one clock.

    Parameters
    ----------
    time_s : numpy.ndarray
        Time stamps [s].
    position_m : numpy.ndarray
        Positions (n, 3) [m].
    quaternion_xyzw : numpy.ndarray, optional
        Orientations (n, 4), scalar last.
    axis : str, optional
        x, y or z (default: the principal direction).
    name : str
        Name of the motion.

    Returns
    -------
    AppliedMotion

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 1, 101)
    >>> x = 0.2 * (10 * t**3 - 15 * t**4 + 6 * t**5)
    >>> positions = np.column_stack((x, 0 * x, 0 * x))
    >>> applied = applied_from_poses(t + 2.0, positions)
    >>> applied.start_s, round(applied.motion.distance_m, 3)
    (2.0, 0.2)
    """
    t = np.asarray(time_s, dtype=float)
    displacement = np.asarray(position_m, dtype=float)
    if displacement.ndim != 2 or displacement.shape != (t.size, 3):
        raise InputError("poses", f"shape {displacement.shape}", f"must be ({t.size}, 3)")
    displacement = displacement - displacement[0]
    if axis is None:
        _, _, vt = np.linalg.svd(displacement - displacement.mean(axis=0), full_matrices=False)
        sense = 1.0 if vt[0] @ (displacement[-1] - displacement[0]) >= 0 else -1.0
        direction = sense * vt[0]
        where = "principal direction (" + ", ".join(f"{c:.3f}" for c in direction) + ")"
    elif axis in AXES:
        direction = np.asarray(AXES[axis])
        where = f"{axis} axis"
    else:
        raise InputError("motion_axis", axis, "must be x, y or z")
    notes = [f"{name}: displacement along the {where}"]
    if quaternion_xyzw is not None:
        rotation = _rotation_angle_deg(np.asarray(quaternion_xyzw, dtype=float))
        if rotation > 2.0:
            notes.append(
                f"the poses rotate the container by up to {rotation:.0f} deg; the 1-D "
                "identification uses the translation only"
            )
    motion = from_samples(t, position_m=displacement @ direction, name=name)
    return AppliedMotion(motion, float(t[0]), tuple(notes))
