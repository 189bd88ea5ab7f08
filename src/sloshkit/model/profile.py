"""Axisymmetric containers given by their inner profile r(z): the `ProfileContainer`, fill
volume <-> fill height through the real profile, and the named primitives (cylinder with a heel
radius, cone, spherical bottom, shoulder and neck) that build one.

The profile is a polyline of inner radius against height, z measured upward from the lowest
inner point (the inside of the bottom). Between its points the wall is a straight frustum, so
the volume, the centroid and the fill height for a volume are exact for the polyline; arcs
(heel, sphere) are polylines of `ARC_SEGMENTS` chords per quarter circle.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from sloshkit.errors import InputError, require_positive
from sloshkit.model.geometry import RADIUS_RANGE_M, UprightCylinder

#: Chords per quarter circle of a heel, spherical bottom or sphere. The chord's sagitta is
#: 1 - cos(pi/(4 n)) = 7.5e-6 of the arc's radius for n = 128, below the frequency tolerance
#: the validation asks for (the half-full sphere converges to 5e-5; docs/validation.md).
ARC_SEGMENTS = 128

#: Relative tolerance on heights (profile points closer than this are the same height).
HEIGHT_TOLERANCE = 1e-9


@dataclass(frozen=True)
class ProfileContainer:
    """An axisymmetric container given by its inner profile r(z) (a polyline).

    Parameters
    ----------
    z_m : tuple of float
        Heights of the profile's points [m], strictly increasing from 0 (the inner bottom).
    r_m : tuple of float
        Inner radius at those heights [m]; the first may be 0 (a vertex or a pole on the axis:
        cone, sphere), then the bottom is that point; a first radius > 0 is a flat bottom of
        that radius. All others must be > 0.
    name : str
        A name for tables and reports.
    source : str
        Where the profile's numbers come from.

    Examples
    --------
    >>> vial = ProfileContainer((0.0, 0.04), (0.01, 0.01), name="tube")
    >>> round(vial.volume_for_fill_height(0.02) * 1e6, 4)  # mL: pi (10 mm)^2 20 mm
    6.2832
    >>> round(vial.fill_height_for_volume(6.2832e-6) * 1e3, 3)  # mm
    20.0
    """

    z_m: tuple[float, ...]
    r_m: tuple[float, ...]
    name: str = "profile"
    source: str = "user"

    def __post_init__(self) -> None:
        z = np.asarray(self.z_m, dtype=float)
        r = np.asarray(self.r_m, dtype=float)
        if z.ndim != 1 or z.shape != r.shape or len(z) < 2:
            raise InputError(
                "points", f"{len(self.z_m)} heights, {len(self.r_m)} radii", "needs >= 2 points"
            )
        if not (np.all(np.isfinite(z)) and np.all(np.isfinite(r))):
            raise InputError("points", "a non-finite value", "must hold finite numbers")
        if z[0] != 0.0:
            raise InputError("points", f"first height {z[0]:.6g} m", "must start at z = 0")
        if np.any(np.diff(z) <= HEIGHT_TOLERANCE * max(float(z[-1]), 1e-12)):
            raise InputError(
                "points",
                "heights " + _short(z),
                "must increase strictly (r must be a function of z)",
            )
        if r[0] < 0.0 or np.any(r[1:] < RADIUS_RANGE_M[0]) or np.any(r > RADIUS_RANGE_M[1]):
            raise InputError(
                "points",
                "radii " + _short(r),
                f"must be >= 0 at the bottom and {RADIUS_RANGE_M[0]:g} .. "
                f"{RADIUS_RANGE_M[1]:g} m above",
            )

    @property
    def wall_height_m(self) -> float:
        """Inner height of the container: the highest profile point [m]."""
        return float(self.z_m[-1])

    @property
    def radius_m(self) -> float:
        """Largest inner radius (the body of a vial) [m]."""
        return float(max(self.r_m))

    @property
    def diameter_m(self) -> float:
        """Largest inner diameter [m]."""
        return 2.0 * self.radius_m

    @property
    def brimful_volume_m3(self) -> float:
        """Volume up to the top of the profile (the brimful capacity) [m^3]."""
        return self.volume_for_fill_height(self.wall_height_m)

    def radius_at(self, height_m: float) -> float:
        """Inner radius r(z) at a height inside the profile [m]."""
        return float(np.interp(height_m, self.z_m, self.r_m))

    def check_fill_height(self, fill_height_m: float) -> float:
        """Return the fill height, or raise `InputError` if it is not > 0 or above the top."""
        height = require_positive("fill_height", fill_height_m, "m")
        if height > self.wall_height_m * (1.0 + HEIGHT_TOLERANCE):
            raise InputError(
                "fill_height",
                f"{height:.6g} m",
                f"must not exceed the container's inner height {self.wall_height_m:.6g} m "
                f"({self.name})",
            )
        return min(height, self.wall_height_m)

    def volume_for_fill_height(self, fill_height_m: float) -> float:
        """Liquid volume below a static fill height, pi integral of r(z)^2 [m^3]."""
        height = self.check_fill_height(fill_height_m)
        z, r = self.wetted(height)
        return float(np.sum(_frustum_volumes(z, r)))

    def fill_height_for_volume(self, volume_m3: float) -> float:
        """Static fill height for a liquid volume (the inverse of `volume_for_fill_height`) [m].

        Exact for the polyline: in the frustum where the volume ends, the height solves
        (r_1 + s t)^3 = r_1^3 + 3 s dV / pi for the slope s = dr/dz.
        """
        volume = require_positive("fill_volume", volume_m3, "m^3")
        z = np.asarray(self.z_m)
        r = np.asarray(self.r_m)
        cumulative = np.concatenate(([0.0], np.cumsum(_frustum_volumes(z, r))))
        if volume > cumulative[-1] * (1.0 + 1e-12):
            raise InputError(
                "fill_volume",
                f"{volume:.6g} m^3",
                f"must not exceed the brimful volume {cumulative[-1]:.6g} m^3 of {self.name}",
            )
        index = max(0, min(int(np.searchsorted(cumulative, volume)) - 1, len(z) - 2))
        rest = volume - cumulative[index]
        dz = z[index + 1] - z[index]
        slope = (r[index + 1] - r[index]) / dz
        r1 = float(r[index])
        if abs(slope) * dz < 1e-9 * max(r1, 1e-12):
            step = rest / (math.pi * r1 * r1)
        else:
            step = (np.cbrt(r1**3 + 3.0 * slope * rest / math.pi) - r1) / slope
        return float(min(z[index] + max(step, 0.0), z[-1]))

    def centroid_height_m(self, fill_height_m: float) -> float:
        """Height of the static liquid's centre of gravity, int z r^2 dz / int r^2 dz [m].

        z r(z)^2 is a cubic on each frustum, so 2-point Gauss-Legendre is exact.
        """
        z, r = self.wetted(self.check_fill_height(fill_height_m))
        nodes = np.array([-1.0, 1.0]) / math.sqrt(3.0)
        middle, half = (z[1:] + z[:-1]) / 2.0, (z[1:] - z[:-1]) / 2.0
        moment = 0.0
        for node in nodes:
            height = middle + half * node
            radius = np.interp(height, z, r)
            moment += float(np.sum(half * height * radius**2))
        return math.pi * moment / float(np.sum(_frustum_volumes(z, r)))

    def wetted(self, fill_height_m: float) -> tuple[np.ndarray, np.ndarray]:
        """The profile's points below the fill height, with the point at the fill height last.

        Parameters
        ----------
        fill_height_m : float
            Static fill height [m].

        Returns
        -------
        tuple of numpy.ndarray
            Heights and radii [m].

        Examples
        --------
        >>> cone = cone_profile(0.01, 0.01)
        >>> [v.round(4).tolist() for v in cone.wetted(0.004)]
        [[0.0, 0.004], [0.0, 0.004]]
        """
        z = np.asarray(self.z_m)
        r = np.asarray(self.r_m)
        below = z < fill_height_m * (1.0 - HEIGHT_TOLERANCE)
        below[0] = True
        return (
            np.append(z[below], fill_height_m),
            np.append(r[below], np.interp(fill_height_m, z, r)),
        )


#: A container the library models: the upright cylinder (closed form) or a profile (FE).
Container = UprightCylinder | ProfileContainer


SegmentKind = Literal["cylinder", "cone", "sphere", "neck"]

SEGMENT_KINDS: tuple[str, ...] = ("cylinder", "cone", "sphere", "neck")


@dataclass(frozen=True)
class ProfileSegment:
    """One named primitive of a profile, stacked on the ones below it (SI units).

    Parameters
    ----------
    kind : str
        ``cylinder`` (radius, height, optional heel_radius at a flat bottom), ``cone`` (from the
        radius below, or from ``bottom_radius`` when first, to ``radius`` over ``height``),
        ``sphere`` (a spherical bottom of ``radius`` from its pole up to ``height`` <= 2 radius;
        first only) or ``neck`` (a straight shoulder over ``shoulder_height`` from the radius
        below to ``radius``, then ``height`` of straight neck).
    radius_m : float
        The segment's radius (top radius of a cone, neck radius) [m].
    height_m : float
        Its height [m].
    heel_radius_m : float
        Corner radius between a first cylinder's flat bottom and its wall [m].
    bottom_radius_m : float
        Bottom radius of a first cone (0: a vertex) [m].
    shoulder_height_m : float
        Height of a neck's shoulder [m].

    Examples
    --------
    >>> body = ProfileSegment("cylinder", 0.007, 0.02)
    >>> neck = ProfileSegment("neck", 0.0035, 0.008, shoulder_height_m=0.005)
    >>> profile = profile_from_segments([body, neck])
    >>> round(profile.wall_height_m * 1e3, 3), round(profile.radius_at(0.033) * 1e3, 3)
    (33.0, 3.5)
    """

    kind: str
    radius_m: float
    height_m: float
    heel_radius_m: float = 0.0
    bottom_radius_m: float = 0.0
    shoulder_height_m: float = 0.0


def profile_from_segments(
    segments: Sequence[ProfileSegment], *, name: str = "profile", source: str = "user"
) -> ProfileContainer:
    """The profile of stacked primitives (`ProfileSegment`), bottom first.

    Parameters
    ----------
    segments : sequence of ProfileSegment
        The primitives, bottom first.
    name : str
        The container's name.
    source : str
        Where its dimensions come from.

    Returns
    -------
    ProfileContainer
        The polyline profile (arcs as `ARC_SEGMENTS` chords per quarter circle).

    Examples
    --------
    A hemisphere: 2/3 pi R^3 (the chords miss 2e-5 of it).

    >>> bowl = profile_from_segments([ProfileSegment("sphere", 0.01, 0.01)])
    >>> round(bowl.brimful_volume_m3 / (2 / 3 * math.pi * 0.01**3), 4)
    1.0
    """
    if not segments:
        raise InputError("profile", "no segments", "needs at least one segment")
    z: list[float] = []
    r: list[float] = []
    for index, segment in enumerate(segments):
        first = index == 0
        kind = segment.kind
        if kind not in SEGMENT_KINDS:
            raise InputError("kind", kind, "must be one of " + ", ".join(SEGMENT_KINDS))
        radius = require_positive("radius", segment.radius_m, "m")
        height = require_positive("height", segment.height_m, "m")
        base = z[-1] if z else 0.0
        if kind == "sphere":
            if not first:
                raise InputError("kind", "sphere", "must be the first (bottom) segment")
            if height > 2.0 * radius * (1.0 + HEIGHT_TOLERANCE):
                raise InputError("height", f"{height:.6g} m", "must not exceed the diameter")
            points = _sphere_points(radius, min(height, 2.0 * radius))
        elif kind == "cylinder":
            heel = segment.heel_radius_m
            if heel < 0.0 or heel >= min(radius, height) or (heel > 0.0 and not first):
                raise InputError(
                    "heel_radius",
                    f"{heel:.6g} m",
                    "must be >= 0, below the radius and the height, on the first segment only",
                )
            points = _cylinder_points(radius, height, heel, first)
        elif kind == "cone":
            start = (segment.bottom_radius_m if first else r[-1], radius)
            points = ([(0.0, start[0])] if first else []) + [(height, start[1])]
        else:
            if first:
                raise InputError("kind", "neck", "needs a segment below it")
            shoulder = require_positive("shoulder_height", segment.shoulder_height_m, "m")
            points = [(shoulder, radius), (shoulder + height, radius)]
        for dz, radius_here in points:
            z.append(base + dz)
            r.append(radius_here)
    # Points of an arc too small to resolve (a heel of a micrometre) would repeat a height.
    keep = [0]
    scale = HEIGHT_TOLERANCE * 10.0 * max(z)
    for index in range(1, len(z)):
        if z[index] - z[keep[-1]] > scale:
            keep.append(index)
    if keep[-1] != len(z) - 1:
        keep[-1] = len(z) - 1
    return ProfileContainer(
        tuple(z[i] for i in keep), tuple(r[i] for i in keep), name=name, source=source
    )


def cylinder_profile(
    radius_m: float, height_m: float, heel_radius_m: float = 0.0, *, name: str = "cylinder"
) -> ProfileContainer:
    """A flat-bottomed cylinder, optionally with a heel (corner) radius, as a profile.

    Parameters
    ----------
    radius_m, height_m : float
        Inner radius and height [m].
    heel_radius_m : float
        Corner radius between the bottom and the wall [m].
    name : str
        The container's name.

    Returns
    -------
    ProfileContainer

    Examples
    --------
    >>> round(cylinder_profile(0.01, 0.05).volume_for_fill_height(0.01) * 1e6, 4)
    3.1416
    """
    segment = ProfileSegment("cylinder", radius_m, height_m, heel_radius_m=heel_radius_m)
    return profile_from_segments([segment], name=name)


def cone_profile(top_radius_m: float, height_m: float, *, name: str = "cone") -> ProfileContainer:
    """A cone standing on its vertex (the 45-degree cone when radius = height).

    Parameters
    ----------
    top_radius_m, height_m : float
        Radius at the top and height [m].
    name : str
        The container's name.

    Returns
    -------
    ProfileContainer

    Examples
    --------
    >>> round(cone_profile(0.01, 0.01).volume_for_fill_height(0.01) / (math.pi * 1e-6 / 3), 9)
    1.0
    """
    return profile_from_segments([ProfileSegment("cone", top_radius_m, height_m)], name=name)


def sphere_profile(radius_m: float, *, name: str = "sphere") -> ProfileContainer:
    """A spherical container (the whole sphere) as a profile.

    Parameters
    ----------
    radius_m : float
        Inner radius [m].
    name : str
        The container's name.

    Returns
    -------
    ProfileContainer

    Examples
    --------
    >>> round(sphere_profile(0.01).radius_at(0.01) * 1e3, 6)
    10.0
    """
    return profile_from_segments([ProfileSegment("sphere", radius_m, 2.0 * radius_m)], name=name)


def _cylinder_points(
    radius: float, height: float, heel: float, first: bool
) -> list[tuple[float, float]]:
    if not first:
        return [(height, radius)]
    if heel == 0.0:
        return [(0.0, radius), (height, radius)]
    angles = np.linspace(0.0, math.pi / 2.0, ARC_SEGMENTS + 1)
    # The heel arc's centre is at (R - rh, rh): from (R - rh, 0) to (R, rh).
    arc = [(heel - heel * math.cos(a), radius - heel + heel * math.sin(a)) for a in angles]
    return [*arc, (height, radius)]


def _sphere_points(radius: float, height: float) -> list[tuple[float, float]]:
    # Polar angle from the bottom pole; chords of equal angle (ARC_SEGMENTS per quarter).
    top = math.acos(max(-1.0, min(1.0, 1.0 - height / radius)))
    count = max(2, math.ceil(ARC_SEGMENTS * top / (math.pi / 2.0) - 1e-9))
    angles = np.linspace(0.0, top, count + 1)
    points = [(radius - radius * math.cos(a), radius * math.sin(a)) for a in angles]
    points[0] = (0.0, 0.0)
    if height >= 2.0 * radius * (1.0 - HEIGHT_TOLERANCE):
        points = points[:-1]  # the top pole (r = 0) is not a wall point
    return points


def _frustum_volumes(z: np.ndarray, r: np.ndarray) -> np.ndarray:
    """pi dz (r1^2 + r1 r2 + r2^2) / 3 per segment [m^3]."""
    return np.asarray(
        math.pi * np.diff(z) * (r[:-1] ** 2 + r[:-1] * r[1:] + r[1:] ** 2) / 3.0, dtype=float
    )


def _short(values: np.ndarray) -> str:
    shown = ", ".join(f"{v:.4g}" for v in values[:6])
    return f"[{shown}{', ...' if len(values) > 6 else ''}] m"
