"""Geometric paths for 3-D planning: where the container goes, not when.

A `Path` gives the pose of the container's reference point (its bottom centre, world frame, z
up) as a function of the path parameter ``s`` [m]: a generalised arc length with
ds^2 = |dp|^2 + (rho dtheta)^2, where dtheta is the rotation angle of the container and
``rho`` (`ROTATION_LENGTH_M`) converts rotation into length, so that a pure rotation still
advances the parameter. Positions are a C2 cubic spline of ``s``, orientations a C2
`scipy.spatial.transform.RotationSpline`; the timing s(t) is the planner's business.

Sources of paths:

- `path_from_waypoints`: straight segments joined at each inner waypoint by a symmetric pair of
  clothoids (Euler spirals) whose curvature rises linearly from 0 to 1/r and falls back to 0.
  A circular arc of radius r would make the curvature jump from 0 to 1/r where it meets the
  line, hence an acceleration jump v^2/r and an unbounded Cartesian jerk at any speed; the
  clothoid pair keeps the curvature continuous (jerk bounded) at the price of a blend twice as
  long as the arc (Kanayama & Hartman, "Smooth local path planning for autonomous vehicles",
  IEEE ICRA (1989), doi:10.1109/ROBOT.1989.100215). Optional yaw (rotation about world z) per
  waypoint, interpolated by a clamped cubic spline of ``s``;
- `path_from_poses`: the geometry of an existing pose trajectory (its timing is dropped).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline
from scipy.spatial.transform import Rotation, RotationSpline

from sloshkit.errors import InputError, require_positive

FloatArray = NDArray[np.float64]
#: Length [m] that one radian of container rotation counts for in the path parameter.
ROTATION_LENGTH_M = 0.05
#: Largest knot spacing [m] of the path splines.
KNOT_SPACING_M = 2e-3


@dataclass(frozen=True, eq=False)
class Path:
    """Position [m] and orientation of the container's reference point along ``s`` [m].

    Parameters
    ----------
    name : str
        Label (file name or ``waypoints``).
    knots_m : ndarray
        Increasing path parameter values [m] of the spline knots, from 0 to `length_m`.
    positions_m : ndarray, shape (n, 3)
        Reference-point positions at the knots (world frame) [m].
    rotations : scipy Rotation of length n
        Container-to-world orientations at the knots.

    Examples
    --------
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> round(path.length_m, 6), path.position(0.15).round(6).tolist()
    (0.3, [0.15, 0.0, 0.0])
    """

    name: str
    knots_m: FloatArray
    positions_m: FloatArray
    rotations: Rotation

    def __post_init__(self) -> None:
        object.__setattr__(self, "_position", CubicSpline(self.knots_m, self.positions_m))
        object.__setattr__(self, "_rotation", RotationSpline(self.knots_m, self.rotations))
        turns = (self.rotations[0].inv() * self.rotations).magnitude()
        object.__setattr__(self, "_fixed", bool(np.max(turns) < 1e-12))

    @property
    def length_m(self) -> float:
        """Total path parameter S [m]."""
        return float(self.knots_m[-1])

    def _clip(self, s_m: ArrayLike) -> FloatArray:
        return np.asarray(np.clip(np.asarray(s_m, dtype=float), 0.0, self.length_m), dtype=float)

    def position(self, s_m: ArrayLike, order: int = 0) -> FloatArray:
        """Position p(s) [m] (``order`` 0) or its ``order``-th derivative d^k p / ds^k."""
        spline: CubicSpline = self._position  # type: ignore[attr-defined]
        return np.asarray(spline(self._clip(s_m), order), dtype=float)

    def tangent(self, s_m: ArrayLike) -> FloatArray:
        """Unit tangent p'/|p'| (zero where the position does not move) [-]."""
        first = self.position(s_m, 1)
        norm = np.linalg.norm(first, axis=-1, keepdims=True)
        return np.asarray(np.where(norm > 1e-9, first / np.maximum(norm, 1e-300), 0.0))

    def curvature(self, s_m: ArrayLike) -> FloatArray:
        """Curvature |p' x p''| / |p'|^3 of the position curve [1/m] (0 where p' = 0)."""
        first, second = self.position(s_m, 1), self.position(s_m, 2)
        speed = np.linalg.norm(first, axis=-1)
        cross = np.linalg.norm(np.cross(first, second), axis=-1)
        return np.asarray(np.where(speed > 1e-6, cross / np.maximum(speed, 1e-6) ** 3, 0.0))

    def orientation(self, s_m: ArrayLike) -> Rotation:
        """Container-to-world rotation R(s)."""
        s = self._clip(s_m)
        if self._fixed:  # type: ignore[attr-defined]
            quaternion = self.rotations[0].as_quat()
            return Rotation.from_quat(np.broadcast_to(quaternion, (*s.shape, 4)))
        spline: RotationSpline = self._rotation  # type: ignore[attr-defined]
        return spline(s)

    def distance_to(self, points_m: ArrayLike) -> FloatArray:
        """Distance [m] of each point from the position curve: the nearest of 2e5 dense points,
        refined on the chord between its neighbours (below 1 um for paths up to 20 m)."""
        from scipy.spatial import cKDTree

        cache: dict[str, Any] = self.__dict__.setdefault("_dense", {})
        if not cache:
            cache["points"] = self.position(np.linspace(0.0, self.length_m, 200_001))
            cache["tree"] = cKDTree(cache["points"])
        dense = cache["points"]
        points = np.atleast_2d(np.asarray(points_m, dtype=float))
        _, index = cache["tree"].query(points)
        low = dense[np.maximum(index - 1, 0)]
        chord = dense[np.minimum(index + 1, len(dense) - 1)] - low
        weight = np.clip(
            np.sum((points - low) * chord, axis=1) / np.maximum(np.sum(chord**2, axis=1), 1e-300),
            0.0,
            1.0,
        )
        return np.asarray(np.linalg.norm(points - low - weight[:, None] * chord, axis=1))

    def angular_rate(self, s_m: ArrayLike, order: int = 1) -> FloatArray:
        """d omega / ds (``order`` 1: the angular velocity per unit s [rad/m], world frame;
        ``order`` 2: its derivative [rad/m^2])."""
        s = self._clip(s_m)
        if self._fixed:  # type: ignore[attr-defined]
            return np.zeros((*s.shape, 3))
        spline: RotationSpline = self._rotation  # type: ignore[attr-defined]
        return np.asarray(spline(s, order), dtype=float)


def _resampled(
    name: str, s_m: FloatArray, positions: FloatArray, rotations: Rotation, spacing: float
) -> Path:
    """A `Path` through the subset of the (s, pose) samples at least ``spacing`` apart."""
    keep = [0]
    for index in range(1, s_m.size - 1):
        if s_m[index] - s_m[keep[-1]] >= spacing and s_m[-1] - s_m[index] >= 0.5 * spacing:
            keep.append(index)
    keep.append(s_m.size - 1)
    chosen = np.asarray(keep)
    if chosen.size < 2 or s_m[-1] <= 0.0:
        raise InputError("path", name, "must move (its length is zero)")
    return Path(name, s_m[chosen] - s_m[0], positions[chosen], rotations[chosen])


def generalised_arc_length(
    positions_m: FloatArray, rotations: Rotation, rotation_length_m: float = ROTATION_LENGTH_M
) -> FloatArray:
    """Cumulative path parameter of pose samples: ds^2 = |dp|^2 + (rho dtheta)^2 [m].

    Parameters
    ----------
    positions_m : ndarray, shape (n, 3)
        Positions [m].
    rotations : scipy Rotation of length n
        Orientations.
    rotation_length_m : float
        rho: the length one radian of rotation counts for [m].

    Returns
    -------
    ndarray
        s at each sample, from 0 [m].

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> s = generalised_arc_length(np.array([[0, 0, 0], [0.3, 0, 0], [0.3, 0, 0]]),
    ...                            Rotation.from_euler("z", [[0.0], [0.0], [1.0]]))
    >>> s.round(3).tolist()  # 0.3 m, then 1 rad counts 0.05 m
    [0.0, 0.3, 0.35]
    """
    steps = np.linalg.norm(np.diff(positions_m, axis=0), axis=1)
    turns = (rotations[1:] * rotations[:-1].inv()).magnitude()
    return np.concatenate(([0.0], np.cumsum(np.hypot(steps, rotation_length_m * turns))))


def path_from_poses(
    positions_m: ArrayLike, quaternions_xyzw: ArrayLike, name: str = "poses"
) -> Path:
    """The geometry of a pose trajectory (samples in time order; repeated poses dropped).

    Parameters
    ----------
    positions_m : array (n, 3)
        Reference-point positions [m].
    quaternions_xyzw : array (n, 4)
        Container-to-world unit quaternions, scalar last.
    name : str
        Label.

    Returns
    -------
    Path
        Knots at least `KNOT_SPACING_M` apart taken from the samples themselves.

    References
    ----------
    Pose file format: the measured 3-D series (``tests/data/measured-3d/README.md``).

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 201)
    >>> p = np.c_[0.3 * np.cos(np.pi * t), 0.3 * np.sin(np.pi * t), 0 * t]
    >>> q = np.tile([0.0, 0.0, 0.0, 1.0], (t.size, 1))
    >>> round(path_from_poses(p, q).length_m, 4)  # half circle of radius 0.3 m
    0.9425
    """
    positions = np.asarray(positions_m, dtype=float)
    quaternions = np.asarray(quaternions_xyzw, dtype=float)
    if positions.ndim != 2 or positions.shape[1] != 3 or quaternions.shape != (len(positions), 4):
        raise InputError("poses", positions.shape, "need (n, 3) positions and (n, 4) quaternions")
    rotations = Rotation.from_quat(quaternions)
    s_m = generalised_arc_length(positions, rotations)
    moving = np.concatenate(([True], np.diff(s_m) > 1e-9))
    return _resampled(name, s_m[moving], positions[moving], rotations[moving], KNOT_SPACING_M)


def _clothoid_pair(radius_m: float, deflection_rad: float) -> tuple[FloatArray, FloatArray]:
    """Arc length and planar points (x, y) of a symmetric clothoid pair that starts at the
    origin heading +x and turns left by ``deflection_rad`` with peak curvature 1/r."""
    half = radius_m * deflection_rad  # each clothoid: curvature 0 -> 1/r over this length
    count = max(64, math.ceil(2 * half / (0.25 * KNOT_SPACING_M)))
    sigma = np.linspace(0.0, 2 * half, count + 1)
    heading = np.where(
        sigma <= half,
        sigma**2 / (2 * radius_m * half),
        deflection_rad - (2 * half - sigma) ** 2 / (2 * radius_m * half),
    )
    step = np.diff(sigma)
    # Heading is quadratic per half: Simpson on each step is exact to O(step^5).
    mid = 0.5 * (sigma[1:] + sigma[:-1])
    mid_heading = np.where(
        mid <= half,
        mid**2 / (2 * radius_m * half),
        deflection_rad - (2 * half - mid) ** 2 / (2 * radius_m * half),
    )
    dx = step / 6 * (np.cos(heading[:-1]) + 4 * np.cos(mid_heading) + np.cos(heading[1:]))
    dy = step / 6 * (np.sin(heading[:-1]) + 4 * np.sin(mid_heading) + np.sin(heading[1:]))
    points = np.c_[np.concatenate(([0.0], np.cumsum(dx))), np.concatenate(([0.0], np.cumsum(dy)))]
    return sigma, points


def path_from_waypoints(
    waypoints_m: ArrayLike,
    blend_radius_m: float = 0.05,
    yaw_rad: ArrayLike | None = None,
    name: str = "waypoints",
) -> Path:
    """Straight segments through ``waypoints_m`` with clothoid-pair blends at inner corners.

    Parameters
    ----------
    waypoints_m : array (n, 3)
        Points the path starts at, turns near and ends at [m]; n >= 2.
    blend_radius_m : float
        Smallest radius of curvature of each blend (its peak curvature is 1/r) [m].
    yaw_rad : array (n,), optional
        Rotation about world z at each waypoint [rad]; the container stays upright.
    name : str
        Label.

    Returns
    -------
    Path
        The blends do not pass through the inner waypoints; their ``s`` is the blend's middle.

    References
    ----------
    Kanayama & Hartman (1989), doi:10.1109/ROBOT.1989.100215 (clothoid-pair corners).

    Examples
    --------
    >>> path = path_from_waypoints([[0, 0, 0], [0.4, 0, 0], [0.4, 0.4, 0]], 0.05)
    >>> round(float(path.curvature(path.length_m / 2)))  # about 1/r at the blend's middle
    20
    """
    points = np.asarray(waypoints_m, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3 or len(points) < 2:
        raise InputError("waypoints", points.shape, "need at least 2 points of x, y, z")
    radius = require_positive("blend_radius", blend_radius_m, "m")
    segments = np.diff(points, axis=0)
    lengths = np.linalg.norm(segments, axis=1)
    if np.any(lengths < 1e-9):
        raise InputError("waypoints", int(np.argmin(lengths)) + 1, "repeat the previous point")
    directions = segments / lengths[:, None]
    tangents = np.zeros(len(points))  # distance from each corner to its blend's ends
    blends: list[tuple[FloatArray, FloatArray] | None] = [None] * len(points)
    for corner in range(1, len(points) - 1):
        incoming, outgoing = directions[corner - 1], directions[corner]
        deflection = math.acos(float(np.clip(incoming @ outgoing, -1.0, 1.0)))
        if deflection < 1e-6:
            continue
        if deflection > math.radians(175.0):
            raise InputError("waypoints", corner, "turn back by more than 175 deg")
        sigma, planar = _clothoid_pair(radius, deflection)
        end = planar[-1]
        tangents[corner] = end[0] - end[1] / math.tan(deflection)
        normal = outgoing - (incoming @ outgoing) * incoming
        normal /= np.linalg.norm(normal)
        start = points[corner] - tangents[corner] * incoming
        blends[corner] = (sigma, start + planar[:, :1] * incoming + planar[:, 1:] * normal)
    for index, length in enumerate(lengths):
        if tangents[index] + tangents[index + 1] > length * (1 + 1e-9):
            raise InputError(
                "blend_radius",
                radius,
                f"too large for segment {index + 1} ({length:.4g} m long)",
                "use a smaller radius or fewer, farther waypoints",
            )
    s_parts: list[FloatArray] = []
    p_parts: list[FloatArray] = []
    corner_s = np.zeros(len(points))
    s_now = 0.0
    for index in range(len(points) - 1):
        begin = points[index] + tangents[index] * directions[index]
        straight = lengths[index] - tangents[index] - tangents[index + 1]
        count = max(2, math.ceil(straight / KNOT_SPACING_M) + 1)
        u = np.linspace(0.0, straight, count)
        s_parts.append(s_now + u)
        p_parts.append(begin + u[:, None] * directions[index])
        s_now += straight
        blend = blends[index + 1]
        if blend is not None:
            sigma, curve = blend
            s_parts.append(s_now + sigma[1:])
            p_parts.append(curve[1:])
            corner_s[index + 1] = s_now + 0.5 * sigma[-1]
            s_now += sigma[-1]
        else:
            corner_s[index + 1] = s_now
    s_all = np.concatenate(s_parts)
    p_all = np.concatenate(p_parts)
    keep = np.concatenate(([True], np.diff(s_all) > 1e-12))
    s_all, p_all = s_all[keep], p_all[keep]
    if yaw_rad is None:
        rotations = Rotation.identity(len(s_all))
    else:
        yaw = np.asarray(yaw_rad, dtype=float)
        if yaw.shape != (len(points),):
            raise InputError("yaw", yaw.shape, f"needs one value per waypoint ({len(points)})")
        spline = CubicSpline(corner_s, yaw, bc_type="clamped")
        rotations = Rotation.from_euler("z", spline(s_all)[:, None])
    return _resampled(name, s_all, p_all, rotations, KNOT_SPACING_M)
