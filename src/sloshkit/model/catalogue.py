"""A catalogue of real containers by name: the ISO 8362-1 tubular injection vials 2R ... 100R.

Every number comes from one table: the SCHOTT vials brochure (SCHOTT AG, "SCHOTT Vials",
brochure schott-brochure-schott-vials-english-20092017.pdf, ISO 8362-1 format table), as
transcribed in LyoPronto.jl (LyoHUB, github.com/LyoHUB/LyoPronto.jl, ``src/get_vial_dims.jl``,
commit f39d5f545d74a60a3c0f3df8849cccffebaf2eca). Its columns (ISO 8362-1 letters, mm): d1 outer
body diameter, s1 wall thickness, s2 bottom thickness, h1 overall height, h2 height of the
cylindrical body (outside, to the shoulder), h3 height of neck and flange, d4 bore (inner
diameter of the mouth), r2 (taken here as the outer heel radius: the table's other radius, r1,
is the neck's curve as LyoPronto reads the drawing; the transcription names neither in words),
and the brimful (overflow) capacity with its tolerance [mL].

The inner profile built from them (`iso8362_profile`) is an approximation of the drawing,
stated here so it can be checked: inner body radius d1/2 - s1 from the inner bottom (s2 above
the outer bottom) up to h2 - s2; an inner heel radius r2 - s1 (the outer heel offset by the
wall); a straight shoulder from the body to the bore radius d4/2 between h2 and h1 - h3; a neck
of the bore's radius up to the rim. The fills that matter for sloshing stay in the body; the
brimful volumes of the profiles are compared with the table's in the tests and in
docs/validation.md. A vial's bottom push-up is not modelled (r(z) is a function).

ISO 9187-1 ampoules are not in the catalogue: no public source of their dimension tables was
found (ISO 9187-1 itself is not public), and the catalogue holds no number without a source.
"""

from __future__ import annotations

from dataclasses import dataclass

from sloshkit.errors import InputError
from sloshkit.model.profile import ProfileContainer, ProfileSegment, profile_from_segments

#: The source of every number of `ISO8362_VIALS`.
ISO8362_SOURCE = (
    "ISO 8362-1 nominal dimensions from the SCHOTT vials brochure (2017), as transcribed in "
    "LyoPronto.jl src/get_vial_dims.jl (commit f39d5f5)"
)


@dataclass(frozen=True)
class VialDimensions:
    """The nominal dimensions of one ISO 8362-1 tubular vial [mm, mL] (`ISO8362_SOURCE`).

    Attributes
    ----------
    size : str
        The ISO size, e.g. ``2R``.
    brimful_ml : float
        Brimful (overflow) capacity [mL].
    brimful_tolerance_ml : float
        Its tolerance (+/-) [mL].
    d1_mm : float
        Outer body diameter [mm].
    d4_mm : float
        Bore: inner diameter of the mouth [mm].
    h1_mm : float
        Overall height [mm].
    h2_mm : float
        Height of the cylindrical body, outside [mm].
    h3_mm : float
        Height of neck and flange [mm].
    r2_mm : float
        Outer heel radius [mm].
    s1_mm : float
        Wall thickness [mm].
    s2_mm : float
        Bottom thickness [mm].

    Examples
    --------
    >>> vial = ISO8362_VIALS["2R"]
    >>> vial.d1_mm - 2 * vial.s1_mm  # inner body diameter [mm]
    14.0
    """

    size: str
    brimful_ml: float
    brimful_tolerance_ml: float
    d1_mm: float
    d4_mm: float
    h1_mm: float
    h2_mm: float
    h3_mm: float
    r2_mm: float
    s1_mm: float
    s2_mm: float


# size, brimful, tolerance, d1, d4, h1, h2, h3, r2, s1, s2 (ISO8362_SOURCE).
_ISO8362_ROWS = (
    ("2R", 4.0, 0.5, 16.0, 7.0, 35.0, 22.0, 8.0, 1.5, 1.0, 0.6),
    ("4R", 6.0, 0.5, 16.0, 7.0, 45.0, 32.0, 8.0, 1.5, 1.0, 0.6),
    ("6R", 10.0, 0.5, 22.0, 12.6, 40.0, 26.0, 8.5, 2.0, 1.0, 0.7),
    ("8R", 11.5, 0.5, 22.0, 12.6, 45.0, 31.0, 8.5, 2.0, 1.0, 0.7),
    ("10R", 13.5, 1.0, 24.0, 12.6, 45.0, 30.0, 9.0, 2.0, 1.0, 0.7),
    ("15R", 19.0, 1.0, 24.0, 12.6, 60.0, 45.0, 9.0, 2.0, 1.0, 0.7),
    ("20R", 26.0, 1.5, 30.0, 12.6, 55.0, 35.0, 10.0, 2.5, 1.2, 0.7),
    ("25R", 32.5, 1.5, 30.0, 12.6, 65.0, 45.0, 10.0, 2.5, 1.2, 0.7),
    ("30R", 37.5, 1.5, 30.0, 12.6, 75.0, 55.0, 10.0, 2.5, 1.2, 0.7),
    ("50R", 62.0, 4.0, 40.0, 12.6, 73.0, 49.0, 10.0, 4.0, 1.5, 0.9),
    ("100R", 123.0, 7.0, 47.0, 12.6, 100.0, 75.0, 10.0, 4.0, 1.7, 0.9),
)

#: The ISO 8362-1 vials by size.
ISO8362_VIALS: dict[str, VialDimensions] = {row[0]: VialDimensions(*row) for row in _ISO8362_ROWS}

#: Prefix of the catalogue's names (``iso8362-2R``).
ISO8362_PREFIX = "iso8362-"


def iso8362_profile(size: str) -> ProfileContainer:
    """The inner profile of an ISO 8362-1 vial (the construction of the module docstring).

    Parameters
    ----------
    size : str
        ``2R`` ... ``100R``.

    Returns
    -------
    ProfileContainer
        Named ``iso8362-<size>``.

    Examples
    --------
    >>> vial = iso8362_profile("2R")
    >>> round(vial.radius_m * 1e3, 3), round(vial.wall_height_m * 1e3, 3)  # mm
    (7.0, 34.4)
    >>> round(vial.brimful_volume_m3 * 1e6, 2)  # mL; the table: 4.0 +- 0.5
    4.05
    """
    if size not in ISO8362_VIALS:
        raise InputError("container", ISO8362_PREFIX + size, "must be one of " + catalogue_names())
    vial = ISO8362_VIALS[size]
    mm = 1e-3
    radius = (vial.d1_mm / 2.0 - vial.s1_mm) * mm
    heel = max(vial.r2_mm - vial.s1_mm, 0.0) * mm
    body = (vial.h2_mm - vial.s2_mm) * mm
    shoulder = (vial.h1_mm - vial.h3_mm - vial.h2_mm) * mm
    segments = [
        ProfileSegment("cylinder", radius, body, heel_radius_m=heel),
        ProfileSegment("neck", vial.d4_mm / 2.0 * mm, vial.h3_mm * mm, shoulder_height_m=shoulder),
    ]
    return profile_from_segments(segments, name=ISO8362_PREFIX + size, source=ISO8362_SOURCE)


def catalogue_names() -> str:
    """The catalogue's container names, comma-separated (for help texts and errors).

    Returns
    -------
    str

    Examples
    --------
    >>> catalogue_names().split(", ")[:2]
    ['iso8362-2R', 'iso8362-4R']
    """
    return ", ".join(ISO8362_PREFIX + size for size in ISO8362_VIALS)


def catalogue_container(name: str) -> ProfileContainer:
    """A container of the catalogue by name (case-insensitive), e.g. ``iso8362-2R``.

    Parameters
    ----------
    name : str
        The name.

    Returns
    -------
    ProfileContainer

    Raises
    ------
    InputError
        For a name not in the catalogue (the error lists them).

    Examples
    --------
    >>> catalogue_container("ISO8362-10r").name
    'iso8362-10R'
    """
    text = name.strip()
    if text.lower().startswith(ISO8362_PREFIX):
        size = text[len(ISO8362_PREFIX) :].upper()
        if size in ISO8362_VIALS:
            return iso8362_profile(size)
    raise InputError("container", name, "must be one of " + catalogue_names())
