"""Pose trajectories built from 1-D laws: along a line, along a path, as a rotation about a
fixed axis, and several trajectories chained rigidly.

Each timing law s(t) is a rest-to-rest `Motion`; the poses are sampled on the grid
t_k = k Ts up to the law's end (`sloshkit.motion.sampling`), with the last sample exactly at T.

References
----------
- B. Siciliano et al., *Robotics: Modelling, Planning and Control*, Springer (2009), §4.3
  (paths and timing laws), §2.4 (orientation).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import make_interp_spline
from scipy.spatial.transform import Rotation

from sloshkit.errors import InputError, require_increasing, require_positive
from sloshkit.motion.laws import Motion
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.sampling import sample_times

FloatArray = NDArray[np.float64]


def _unit(vector: ArrayLike, parameter: str) -> FloatArray:
    value = np.asarray(vector, dtype=float).reshape(-1)
    norm = float(np.linalg.norm(value)) if value.shape == (3,) else 0.0
    if norm == 0.0 or not math.isfinite(norm):
        raise InputError(parameter, vector, "must be a non-zero 3-vector")
    return value / norm


def poses_from_law(
    motion: Motion,
    direction: ArrayLike = (1.0, 0.0, 0.0),
    *,
    sample_period_s: float = 1e-3,
    start_m: ArrayLike = (0.0, 0.0, 0.0),
    orientation: Rotation | None = None,
) -> PoseTrajectory:
    """A 1-D law s(t) along a straight line: p(t) = start + s(t) d, constant orientation.

    Parameters
    ----------
    motion : the rest-to-rest 1-D law (`sloshkit.motion.laws`)
    direction : the line's direction in the world frame (normalised) [-]
    sample_period_s : pose sample period [s]; the last sample is exactly at T
    start_m : start position [m]
    orientation : constant container orientation (default upright)

    Returns
    -------
    PoseTrajectory

    Examples
    --------
    >>> from sloshkit.motion.laws import quintic
    >>> poses = poses_from_law(quintic(0.5, 1.0), (0, 1, 0), sample_period_s=0.01)
    >>> poses.position_m[-1].round(9).tolist()
    [0.0, 0.5, 0.0]
    """
    unit = _unit(direction, "direction")
    time = sample_times(motion.duration_s, require_positive("sample_period", sample_period_s, "s"))
    position = (
        np.asarray(start_m, dtype=float).reshape(1, 3) + motion.position(time)[:, None] * unit
    )
    rotation = orientation if orientation is not None else Rotation.identity()
    quaternion = np.tile(rotation.as_quat(), (time.size, 1))
    return PoseTrajectory(time, position, quaternion, motion.name)


def poses_from_path(
    path: Callable[[FloatArray], ArrayLike] | ArrayLike,
    motion: Motion,
    *,
    sample_period_s: float = 1e-3,
    orientation: Callable[[FloatArray], Rotation] | Rotation | None = None,
) -> PoseTrajectory:
    """A path timed by a 1-D law: p(t) = path(u(t)), u = s(t) / s(T) in [0, 1].

    Parameters
    ----------
    path : a vectorised function u -> (M, 3) positions for u in [0, 1], or waypoints (K, 3)
        joined by a cubic spline in chord-length parameter (not exactly arc length)
    motion : the timing law; only its normalised progress s(t)/s(T) is used
    sample_period_s : pose sample period [s]
    orientation : constant `Rotation`, or a function u -> `Rotation` (default upright)

    Returns
    -------
    PoseTrajectory

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.motion.laws import quintic
    >>> circle = lambda u: np.column_stack((0.3 * np.sin(2 * np.pi * u),
    ...                                     0.3 * np.cos(2 * np.pi * u) - 0.3, 0 * u))
    >>> poses = poses_from_path(circle, quintic(1.0, 2.0), sample_period_s=0.01)
    >>> bool(np.allclose(poses.position_m[[0, -1]], 0.0, atol=1e-9))
    True
    """
    time = sample_times(motion.duration_s, require_positive("sample_period", sample_period_s, "s"))
    distance = motion.distance_m
    if distance == 0.0:
        raise InputError("motion", motion.name, "must have a non-zero travel to time a path")
    progress = motion.position(time) / distance
    if callable(path):
        position = np.asarray(path(progress), dtype=float)
    else:
        points = np.asarray(path, dtype=float)
        if points.ndim != 2 or points.shape[1] != 3 or points.shape[0] < 2:
            raise InputError("path", points.shape, "waypoints must have shape (K >= 2, 3)")
        chord = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))))
        require_increasing("path", chord)
        spline = make_interp_spline(chord / chord[-1], points, k=min(3, points.shape[0] - 1))
        position = np.asarray(spline(progress), dtype=float)
    if position.shape != (time.size, 3):
        raise InputError("path", position.shape, f"must return shape ({time.size}, 3)")
    if orientation is None:
        quaternion = np.tile([0.0, 0.0, 0.0, 1.0], (time.size, 1))
    elif isinstance(orientation, Rotation):
        quaternion = np.tile(orientation.as_quat(), (time.size, 1))
    else:
        quaternion = np.asarray(orientation(progress).as_quat(), dtype=float)
    return PoseTrajectory(time, position, quaternion, motion.name)


def poses_from_rotation(
    motion: Motion,
    axis: ArrayLike = (1.0, 0.0, 0.0),
    *,
    sample_period_s: float = 1e-3,
    pivot_m: ArrayLike = (0.0, 0.0, 0.0),
    initial: Rotation | None = None,
) -> PoseTrajectory:
    """Rotation by an angle law psi(t) = s(t) [rad] about a fixed world axis through a pivot.

    A horizontal ``axis`` gives a tilt profile, the vertical axis (0, 0, 1) with the pivot on
    the container axis a spin about the container's own axis. The bottom centre moves on a
    circle about the pivot: p(t) = pivot + Q(t) (p_0 - pivot), q(t) = Q(t) q_0 with
    Q(t) = Rot(axis, psi(t)).

    Parameters
    ----------
    motion : the angle law; its "distance" is the total angle [rad]
    axis : rotation axis in the world frame [-]
    sample_period_s : pose sample period [s]
    pivot_m : a point on the rotation axis, world frame [m]; the bottom centre starts at the
        origin
    initial : the orientation at psi = 0 (default upright)

    Returns
    -------
    PoseTrajectory

    Examples
    --------
    >>> import math
    >>> from sloshkit.motion.laws import septic
    >>> poses = poses_from_rotation(septic(math.radians(20), 1.0), sample_period_s=0.01)
    >>> round(math.degrees(float(poses.tilt_rad[-1])), 6)
    20.0
    """
    unit = _unit(axis, "axis")
    time = sample_times(motion.duration_s, require_positive("sample_period", sample_period_s, "s"))
    angle = motion.position(time)
    turn = Rotation.from_rotvec(angle[:, None] * unit)
    pivot = np.asarray(pivot_m, dtype=float).reshape(3)
    position = pivot + turn.apply(-pivot)
    start = initial if initial is not None else Rotation.identity()
    quaternion = (turn * start).as_quat()
    return PoseTrajectory(time, position, quaternion, motion.name)


def concatenate(parts: Sequence[PoseTrajectory], name: str = "") -> PoseTrajectory:
    """Several trajectories one after the other, chained rigidly.

    Each part is shifted in time to start when the previous one ends, and moved as a rigid
    body (D = R_prev_end R_start^-1, p' = p_prev_end + D (p - p_start), R' = D R) so that its
    first pose coincides with the previous part's last pose; that first sample is dropped.

    Parameters
    ----------
    parts : sequence of PoseTrajectory
        The trajectories, in order.
    name : str
        Name of the result (default: the parts' names joined by +).

    Returns
    -------
    PoseTrajectory

    Examples
    --------
    >>> from sloshkit.motion.laws import septic
    >>> a = poses_from_law(septic(0.1, 1.0), (1, 0, 0), sample_period_s=0.01)
    >>> b = poses_from_law(septic(0.1, 1.0), (0, 1, 0), sample_period_s=0.01)
    >>> concatenate([a, b]).position_m[-1].round(9).tolist()
    [0.1, 0.1, 0.0]
    """
    if not parts:
        raise InputError("parts", 0, "need at least one trajectory")
    first = parts[0]
    times, positions, rotations = [first.time_s], [first.position_m], [first.rotation]
    end_time, end_position, end_rotation = first.end_s, first.position_m[-1], first.rotation[-1]
    for part in parts[1:]:
        shift = end_rotation * part.rotation[0].inv()
        moved = end_position + shift.apply(part.position_m - part.position_m[0])
        turned = shift * part.rotation
        times.append((part.time_s - part.start_s + end_time)[1:])
        positions.append(moved[1:])
        rotations.append(turned[1:])
        end_time, end_position, end_rotation = float(times[-1][-1]), moved[-1], turned[-1]
    quaternion = np.vstack([rotation.as_quat() for rotation in rotations])
    return PoseTrajectory(np.concatenate(times), np.vstack(positions), quaternion, name)
