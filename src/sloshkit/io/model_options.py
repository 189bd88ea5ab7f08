"""The model of the command line's model options (text with units in, a `SloshModel` out): the
container of ``--radius`` and ``--wall-height``, of a catalogue name (``--container``) or of a
profile file (``--profile``), its fill, liquid and modes, built on the request layer that
scenario files share (`sloshkit.io.requests`). A bare number is read in SI, so a length that is
implausible as metres (``--radius 20.5``) warns. A model file instead of these options:
`sloshkit.io.command_requests.model_or_file_request`.
"""

from __future__ import annotations

import warnings
from pathlib import Path

from sloshkit.errors import InputError, ValidityWarning
from sloshkit.io.requests import (
    container_request,
    fill_height_request,
    liquid_request,
    model_request,
    profile_request,
)
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.modal import SloshModel
from sloshkit.model.profile import Container, ProfileContainer

#: Radius when none is given on the command line (the seed paper's vial).
DEFAULT_RADIUS = "20.5mm"

#: Bare numbers are SI; beyond these a length is implausible for a container or a move [m].
PLAUSIBLE_BARE_LENGTH_M: dict[str, float] = {
    "radius": 1.0,
    "fill_height": 2.0,
    "wall_height": 2.0,
    "distance": 10.0,
}


def check_bare_length(text: str | None, value_m: float, parameter: str) -> None:
    """Warn when ``text`` is a bare number (read in metres) that is implausible for
    ``parameter``, e.g. ``--radius 20.5`` (20.5 m): most likely millimetres were meant.

    Parameters
    ----------
    text : str or None
        The option as typed.
    value_m : float
        Its value [m].
    parameter : str
        The option's name (radius, fill_height, wall_height, distance).

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_bare_length("20.5", 20.5, "radius")
    ...     check_bare_length("20.5mm", 0.0205, "radius")
    >>> [str(w.message)[:40] for w in caught]
    ['--radius 20.5 has no unit and is read as']
    """
    if text is None or parameter not in PLAUSIBLE_BARE_LENGTH_M:
        return
    try:
        float(text)
    except ValueError:
        return
    if abs(value_m) > PLAUSIBLE_BARE_LENGTH_M[parameter]:
        warnings.warn(
            f"--{parameter.replace('_', '-')} {text} has no unit and is read as {value_m:g} m "
            f"(a bare number is SI); write the unit, e.g. {text}mm",
            ValidityWarning,
            stacklevel=2,
        )


def cylinder_request(radius: str, wall_height: str | None) -> UprightCylinder:
    """The upright cylinder of the command line's ``--radius`` and ``--wall-height``, with a
    warning for a bare number that is implausible as metres (`check_bare_length`).

    Parameters
    ----------
    radius : str
        ``--radius`` (a length with its unit).
    wall_height : str or None
        ``--wall-height``.

    Returns
    -------
    UprightCylinder

    Examples
    --------
    >>> cylinder_request("20.5mm", "60mm")
    UprightCylinder(radius_m=0.0205, wall_height_m=0.06)
    """
    container = container_request(radius, wall_height)
    check_bare_length(radius, container.radius_m, "radius")
    if wall_height is not None and container.wall_height_m is not None:
        check_bare_length(wall_height, container.wall_height_m, "wall_height")
    return container


def vessel_request(
    radius: str, wall_height: str | None, container: str | None, profile: Path | None
) -> Container:
    """The container of the model options: a catalogue name (``--container``), a profile file
    (``--profile``) or the upright cylinder of ``--radius`` and ``--wall-height``.

    Parameters
    ----------
    radius : str
        ``--radius`` (only its default, `DEFAULT_RADIUS`, with a container or profile).
    wall_height : str or None
        ``--wall-height`` (not with a container or profile).
    container : str or None
        ``--container``.
    profile : Path or None
        ``--profile``.

    Returns
    -------
    UprightCylinder or ProfileContainer

    Examples
    --------
    >>> vessel_request(DEFAULT_RADIUS, None, "iso8362-6R", None).name
    'iso8362-6R'
    >>> vessel_request("8mm", None, None, None).radius_m
    0.008
    """
    real = profile_request(container, profile)
    if real is None:
        return cylinder_request(radius, wall_height)
    if radius != DEFAULT_RADIUS or wall_height is not None:
        given = "--container" if container is not None else "--profile"
        raise InputError(
            "radius" if radius != DEFAULT_RADIUS else "wall_height",
            radius if radius != DEFAULT_RADIUS else wall_height,
            f"is given by {given}; drop it or {given}",
        )
    return real


def options_model_request(
    radius: str,
    fill_height: str | None,
    fill_volume: str | None,
    wall_height: str | None,
    liquid: str,
    density: str | None,
    viscosity: str | None,
    sigma: str | None,
    modes: int,
    damping_law: str,
    damping_ratio: float | None,
    surface_tension_correction: bool | None,
    container: str | None = None,
    profile: Path | None = None,
) -> SloshModel:
    """The `SloshModel` of the command line's model options (text with units).

    Parameters
    ----------
    radius, fill_height, fill_volume, wall_height : str or None
        Lengths and volume with units (``fill_height`` or ``fill_volume``).
    liquid : str
        The preset's name.
    density, viscosity, sigma : str or None
        Overrides of the preset's properties.
    modes : int
        Number of modes.
    damping_law : str
        The damping correlation.
    damping_ratio : float or None
        A damping ratio that replaces the correlation.
    surface_tension_correction : bool or None
        Apply the capillary frequency correction (None: where it matters).
    container : str or None
        ``--container``: a catalogue name replacing the radius and wall height.
    profile : Path or None
        ``--profile``: a profile file replacing the radius and wall height.

    Returns
    -------
    SloshModel

    Examples
    --------
    >>> model = options_model_request("20.5mm", None, "51.5ml", None, "water-25C", None, None,
    ...                               None, 3, "seed", None, False)
    >>> round(model.fill_height_m * 1e3, 1), round(model.modes[0].frequency_hz, 2)
    (39.0, 4.72)
    """
    vessel = vessel_request(radius, wall_height, container, profile)
    if isinstance(vessel, ProfileContainer) and fill_height is None and fill_volume is None:
        given = "--container" if container is not None else "--profile"
        raise InputError("fill_volume", None, f"give --fill-volume or --fill-height with {given}")
    height = fill_height_request(vessel, fill_height, fill_volume)
    if fill_volume is None:
        check_bare_length(fill_height, height, "fill_height")
    return model_request(
        vessel,
        liquid_request(liquid, density, viscosity, sigma, surface_tension_parameter="sigma"),
        height,
        modes=modes,
        damping_law=damping_law,
        damping_ratio=damping_ratio,
        surface_tension_correction=surface_tension_correction,
    )
