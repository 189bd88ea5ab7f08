"""The request layer shared by the command line and scenario files: text with units in, checked
SI objects out. Defaults and validation are written once, here; the CLI options and the
scenario tables only name their values. What the command line's model options alone build on
these (the cylinder of ``--radius``, the container of ``--container`` or ``--profile``, the
whole model, the warning for a bare number) is `sloshkit.io.model_options`.
"""

from __future__ import annotations

import math
import typing
from pathlib import Path

from sloshkit.errors import InputError
from sloshkit.io.profiles import read_profile_file
from sloshkit.io.units import parse_bounded, parse_quantity
from sloshkit.model.catalogue import catalogue_container
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import Liquid, get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.model.profile import Container, ProfileContainer
from sloshkit.model.theory import DAMPING_LAWS, DampingLaw

#: Fill height when neither a height nor a volume is given on the command line.
DEFAULT_FILL_HEIGHT = "39mm"

Quantity = str | float


def container_request(radius: Quantity, wall_height: Quantity | None = None) -> UprightCylinder:
    """The container from a radius and an optional wall height (text with units or SI).

    Parameters
    ----------
    radius : str or float
        Inner radius, e.g. ``"20.5mm"``.
    wall_height : str or float, optional
        Inner wall height.

    Returns
    -------
    UprightCylinder
        The container.

    Examples
    --------
    >>> container_request("20.5mm").radius_m
    0.0205
    """
    return UprightCylinder(
        parse_quantity(radius, "length", "radius"),
        None if wall_height is None else parse_quantity(wall_height, "length", "wall_height"),
    )


def profile_request(
    container: str | None,
    profile: str | Path | None,
    *,
    container_parameter: str = "container",
    profile_parameter: str = "profile",
) -> ProfileContainer | None:
    """The container of a catalogue name or a profile file (at most one), or None for neither.

    Parameters
    ----------
    container : str, optional
        A catalogue name, e.g. ``iso8362-2R`` (`sloshkit.model.catalogue`).
    profile : str or Path, optional
        A profile file (`sloshkit.io.profiles`).
    container_parameter, profile_parameter : str
        Their names in error messages.

    Returns
    -------
    ProfileContainer or None

    Examples
    --------
    >>> profile_request("iso8362-2R", None).name
    'iso8362-2R'
    >>> profile_request(None, None) is None
    True
    """
    if container is not None and profile is not None:
        raise InputError(
            profile_parameter,
            str(profile),
            f"give {container_parameter} or {profile_parameter}, not both",
        )
    if container is not None:
        try:
            return catalogue_container(container)
        except InputError as error:
            raise InputError(container_parameter, container, error.valid) from None
    if profile is not None:
        return read_profile_file(profile, profile_parameter)
    return None


def liquid_request(
    preset: str,
    density: Quantity | None = None,
    viscosity: Quantity | None = None,
    surface_tension: Quantity | None = None,
    *,
    surface_tension_parameter: str = "surface_tension",
    note: str = "overridden",
) -> Liquid:
    """A preset liquid, with any of its properties overridden.

    Parameters
    ----------
    preset : str
        Name of the preset (`sloshkit.model.liquids.LIQUIDS`).
    density, viscosity, surface_tension : str or float, optional
        Overrides (text with units or SI).
    surface_tension_parameter : str
        Name of the surface-tension parameter in error messages (``sigma`` on the CLI).
    note : str
        Appended to the preset's source when something is overridden.

    Returns
    -------
    Liquid
        The preset itself when nothing is overridden.

    Examples
    --------
    >>> liquid_request("water-25C", density="1.1 g/mL").density_kg_m3
    1100.0
    """
    base = get_liquid(preset)
    if (density, viscosity, surface_tension) == (None, None, None):
        return base
    return Liquid(
        name=base.name + "*",
        density_kg_m3=base.density_kg_m3
        if density is None
        else parse_quantity(density, "density", "density"),
        viscosity_pa_s=base.viscosity_pa_s
        if viscosity is None
        else parse_quantity(viscosity, "viscosity", "viscosity"),
        surface_tension_n_m=base.surface_tension_n_m
        if surface_tension is None
        else parse_quantity(surface_tension, "surface_tension", surface_tension_parameter),
        source=f"{base.source} ({note})",
    )


def damping_law_request(name: str) -> DampingLaw:
    """The damping-law name, checked.

    Parameters
    ----------
    name : str
        One of `sloshkit.model.theory.DAMPING_LAWS`.

    Returns
    -------
    str
        ``name``.

    Raises
    ------
    InputError
        For an unknown law.

    Examples
    --------
    >>> damping_law_request("seed")
    'seed'
    """
    if name not in DAMPING_LAWS:
        raise InputError("damping_law", name, "must be one of " + ", ".join(DAMPING_LAWS))
    return typing.cast(DampingLaw, name)


def fill_height_request(
    container: Container,
    height: Quantity | None,
    volume: Quantity | None,
    *,
    default: Quantity | None = DEFAULT_FILL_HEIGHT,
    height_parameter: str = "fill_height",
    volume_parameter: str = "fill_volume",
) -> float:
    """The static fill height [m] from a height or a liquid volume (not both).

    Parameters
    ----------
    container : UprightCylinder or ProfileContainer
        The container (for the volume, through its profile, and the wall check).
    height : str or float, optional
        Fill height.
    volume : str or float, optional
        Liquid volume.
    default : str or float, optional
        Fill height when neither is given; None makes one of them required.
    height_parameter, volume_parameter : str
        Names of the two parameters in error messages.

    Returns
    -------
    float
        The fill height [m].

    Examples
    --------
    >>> round(fill_height_request(container_request("20mm"), None, "2 mL"), 6)
    0.001592
    """
    both = f"give exactly one of {height_parameter} or {volume_parameter}"
    if height is not None and volume is not None:
        raise InputError(volume_parameter, volume, both)
    if volume is not None:
        return container.fill_height_for_volume(parse_quantity(volume, "volume", volume_parameter))
    if height is None:
        if default is None:
            raise InputError(height_parameter, None, both)
        height = default
    return parse_quantity(height, "length", height_parameter)


def model_request(
    container: Container,
    liquid: Liquid,
    fill_height_m: float,
    *,
    modes: int = 3,
    damping_law: str = "seed",
    damping_ratio: float | None = None,
    surface_tension_correction: bool | None = None,
) -> SloshModel:
    """The equivalent model of a request (the damping law checked).

    Parameters
    ----------
    container : UprightCylinder or ProfileContainer
        The container (a profile is modelled by finite elements).
    liquid : Liquid
        The liquid.
    fill_height_m : float
        Fill height [m].
    modes : int
        Number of modes.
    damping_law : str
        Damping correlation.
    damping_ratio : float, optional
        Damping ratio overriding the correlation.
    surface_tension_correction : bool, optional
        Apply the Bond-number frequency correction (None: where it matters, see
        `sloshkit.model.modal.equivalent_model`).

    Returns
    -------
    SloshModel
        The model.

    Examples
    --------
    >>> model = model_request(container_request("20.5mm"), liquid_request("water-25C"), 0.039)
    >>> len(model.modes)
    3
    """
    return equivalent_model(
        container,
        liquid,
        fill_height_m,
        n_modes=int(modes),
        damping_law=damping_law_request(damping_law),
        damping_ratio=None if damping_ratio is None else float(damping_ratio),
        surface_tension=None
        if surface_tension_correction is None
        else bool(surface_tension_correction),
    )


def fraction_request(text: str | float, parameter: str) -> float:
    """A fraction given as ``"10%"``, ``"0.1"`` or a number.

    Parameters
    ----------
    text : str or float
        The fraction or percentage.
    parameter : str
        Its name in the error message.

    Returns
    -------
    float
        The fraction.

    Raises
    ------
    InputError
        For text that is not a number or a percentage.

    Examples
    --------
    >>> fraction_request("10%", "robust"), fraction_request(0.05, "robust")
    (0.1, 0.05)
    """
    if isinstance(text, int | float):
        return float(text)
    stripped = text.strip()
    try:
        return float(stripped.rstrip("%")) / (100.0 if stripped.endswith("%") else 1.0)
    except ValueError:
        raise InputError(parameter, text, "must be a fraction or a percentage, e.g. 10%") from None


def angular_rate_request(text: str | None, power: int, parameter: str) -> float | None:
    """An angular speed (``power=1``) or acceleration (``power=2``) limit: ``90deg/s``,
    ``2rad/s``, ``300deg/s^2`` (``s**2``, ``s2`` too) or a bare number in rad/s^power, in the
    strict unit grammar (`sloshkit.io.units`; finite, > 0); None or ``none``: no limit.

    Parameters
    ----------
    text : str or None
        The limit.
    power : int
        1 for rad/s, 2 for rad/s^2.
    parameter : str
        Its name in the error message.

    Returns
    -------
    float or None
        The limit [rad/s or rad/s^2], None for no limit.

    Examples
    --------
    >>> round(angular_rate_request("90deg/s", 1, "w"), 6), angular_rate_request("none", 2, "a")
    (1.570796, None)
    """
    if text is None or text.strip().lower() == "none":
        return None
    kind = "angular_velocity" if power == 1 else "angular_acceleration"
    try:
        return parse_bounded(text, kind, parameter, 0.0, math.inf)
    except InputError as error:
        example = "90deg/s" if power == 1 else "300deg/s^2"
        raise InputError(
            parameter, text, f"must be an angular rate > 0, e.g. {example}", error.valid
        ) from None
