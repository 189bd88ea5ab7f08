"""The serialisation of a `SloshModel`: one versioned, nested document (SI, unit-suffixed
keys), written to and read from model files by `sloshkit.io.models`.

`SloshModel.to_dict` is a different thing: the flat summary printed by ``sloshkit model --json``
(with derived quantities), not meant to be read back.
"""

from __future__ import annotations

from typing import Any

from sloshkit.errors import InputError
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import Liquid
from sloshkit.model.modal import SloshMode, SloshModel
from sloshkit.model.profile import Container, ProfileContainer
from sloshkit.model.theory import GRAVITY_M_S2

#: Version of the model document (``sloshkit_model_version``).
MODEL_FILE_VERSION = 1


def model_to_document(model: SloshModel) -> dict[str, Any]:
    """A `SloshModel` as a versioned, nested document (SI, unit-suffixed keys).

    Parameters
    ----------
    model : SloshModel
        The model.

    Returns
    -------
    dict
        The document (``sloshkit_model_version``, container, liquid, fill, settings, modes,
        provenance).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> model_to_document(model)["sloshkit_model_version"]
    1
    """
    container = model.container
    document: dict[str, Any] = {
        "sloshkit_model_version": MODEL_FILE_VERSION,
        "container": {"radius_m": container.radius_m},
        "liquid": {
            "name": model.liquid.name,
            "density_kg_m3": model.liquid.density_kg_m3,
            "viscosity_pa_s": model.liquid.viscosity_pa_s,
            "surface_tension_n_m": model.liquid.surface_tension_n_m,
            "source": model.liquid.source,
        },
        "fill": {"fill_height_m": model.fill_height_m},
        "settings": {
            "gravity_m_s2": model.gravity_m_s2,
            "damping_law": model.damping_law,
            "surface_tension_correction": model.surface_tension_correction,
        },
        "modes": [
            {
                "n": mode.n,
                "bessel_root": mode.bessel_root,
                "omega_rad_s": mode.omega_rad_s,
                "frequency_hz": mode.frequency_hz,
                "damping_ratio": mode.damping_ratio,
                "slosh_mass_kg": mode.slosh_mass_kg,
                "length_m": mode.length_m,
                "bob_height_m": mode.bob_height_m,
                "wall_elevation_factor_m": mode.wall_elevation_factor_m,
            }
            for mode in model.modes
        ],
        "provenance": dict(model.provenance),
    }
    if container.wall_height_m is not None:
        document["container"]["wall_height_m"] = container.wall_height_m
    if isinstance(container, ProfileContainer):
        # The profile itself, so the model file names the container it was computed for.
        document["container"]["profile"] = {
            "name": container.name,
            "source": container.source,
            "z_m": list(container.z_m),
            "r_m": list(container.r_m),
        }
    return document


def _container_from_table(table: dict[str, Any]) -> Container:
    profile = table.get("profile")
    if profile is None:
        return UprightCylinder(float(table["radius_m"]), table.get("wall_height_m"))
    return ProfileContainer(
        tuple(float(z) for z in profile["z_m"]),
        tuple(float(r) for r in profile["r_m"]),
        name=str(profile.get("name", "profile")),
        source=str(profile.get("source", "model file")),
    )


def model_from_document(document: dict[str, Any], source: str = "document") -> SloshModel:
    """The `SloshModel` of a document written by `model_to_document`.

    Each mode's frequency and damping are taken as written (they may be calibrated); the
    document's ``provenance`` says where they came from.

    Parameters
    ----------
    document : dict
        The nested document.
    source : str
        Where it comes from (named in errors).

    Returns
    -------
    SloshModel
        The model.

    Raises
    ------
    InputError
        When an entry is missing or invalid, or there are no modes.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> model_from_document(model_to_document(model)) == model
    True
    """
    try:
        container = _container_from_table(document["container"])
        liquid_table = document["liquid"]
        liquid = Liquid(
            name=str(liquid_table["name"]),
            density_kg_m3=float(liquid_table["density_kg_m3"]),
            viscosity_pa_s=float(liquid_table["viscosity_pa_s"]),
            surface_tension_n_m=float(liquid_table["surface_tension_n_m"]),
            source=str(liquid_table.get("source", "model file")),
        )
        modes = tuple(
            SloshMode(
                n=int(mode["n"]),
                bessel_root=float(mode["bessel_root"]),
                omega_rad_s=float(mode["omega_rad_s"]),
                slosh_mass_kg=float(mode["slosh_mass_kg"]),
                length_m=float(mode["length_m"]),
                bob_height_m=float(mode["bob_height_m"]),
                damping_ratio=float(mode["damping_ratio"]),
                wall_elevation_factor_m=float(mode["wall_elevation_factor_m"]),
            )
            for mode in document["modes"]
        )
        settings = document.get("settings", {})
        model = SloshModel(
            container=container,
            liquid=liquid,
            fill_height_m=container.check_fill_height(float(document["fill"]["fill_height_m"])),
            modes=modes,
            gravity_m_s2=float(settings.get("gravity_m_s2", GRAVITY_M_S2)),
            damping_law=str(settings.get("damping_law", "user")),
            surface_tension_correction=bool(settings.get("surface_tension_correction", False)),
            provenance={str(k): str(v) for k, v in document.get("provenance", {}).items()},
        )
    except (KeyError, TypeError, ValueError) as error:
        if isinstance(error, InputError):
            raise
        raise InputError("model_file", source, f"missing or invalid entry: {error}") from None
    if not modes:
        raise InputError("model_file", source, "has no modes")
    return model
