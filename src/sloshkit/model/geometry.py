"""Container geometry: the upright circular cylinder and fill height <-> liquid volume."""

from __future__ import annotations

import math
from dataclasses import dataclass

from sloshkit.errors import InputError, require_in_range, require_positive

#: Radii the formulas are evaluated for [m]: 10 um to 100 m (outside, the dimensionless numbers
#: under- or overflow double precision; no container of interest is there).
RADIUS_RANGE_M = (1e-5, 100.0)

#: Deepest fill accepted, in radii: beyond about 385 radii sinh(1.84 h/R) overflows, and from a
#: few radii on the modes are those of infinite depth: omega^2 = g xi/R tanh(xi h/R) (Ibrahim,
#: Liquid Sloshing Dynamics, Cambridge UP (2005), ch. 2).
MAX_DEPTH_RATIO = 100.0


@dataclass(frozen=True)
class UprightCylinder:
    """Upright circular cylinder with a flat bottom.

    Parameters
    ----------
    radius_m : float
        Inner radius R [m].
    wall_height_m : float, optional
        Inner height of the wall above the bottom [m]; None means unknown (no check that the
        fill fits).

    Examples
    --------
    >>> from sloshkit import UprightCylinder
    >>> vial = UprightCylinder(0.0205, wall_height_m=0.08)
    >>> round(vial.volume_for_fill_height(0.039) * 1e6, 2)  # ml
    51.49
    """

    radius_m: float
    wall_height_m: float | None = None

    def __post_init__(self) -> None:
        require_in_range("radius", self.radius_m, *RADIUS_RANGE_M, "m")
        if self.wall_height_m is not None:
            require_positive("wall_height", self.wall_height_m, "m")

    @property
    def diameter_m(self) -> float:
        """Inner diameter d = 2R [m]."""
        return 2.0 * self.radius_m

    @property
    def cross_section_m2(self) -> float:
        """Inner cross-section pi R^2 [m^2]."""
        return math.pi * self.radius_m * self.radius_m

    def fill_height_for_volume(self, volume_m3: float) -> float:
        """Static fill height h = V / (pi R^2) [m] for a liquid volume [m^3]."""
        volume = require_positive("fill_volume", volume_m3, "m^3")
        height = float(volume / self.cross_section_m2)
        self.check_fill_height(height)
        return height

    def volume_for_fill_height(self, fill_height_m: float) -> float:
        """Liquid volume V = pi R^2 h [m^3] for a static fill height [m]."""
        return float(self.cross_section_m2 * self.check_fill_height(fill_height_m))

    def check_fill_height(self, fill_height_m: float) -> float:
        """Return the fill height, or raise `InputError` if it is not > 0 or above the wall."""
        height = require_positive("fill_height", fill_height_m, "m")
        if height > MAX_DEPTH_RATIO * self.radius_m:
            raise InputError(
                "fill_height",
                f"{height:.6g} m",
                f"must not exceed {MAX_DEPTH_RATIO:g} radii "
                f"({MAX_DEPTH_RATIO * self.radius_m:.6g} m; deeper fills slosh like that one)",
            )
        if self.wall_height_m is not None and height > self.wall_height_m:
            raise InputError(
                "fill_height",
                f"{height:.6g} m",
                f"must not exceed the wall height {self.wall_height_m:.6g} m",
            )
        return height
