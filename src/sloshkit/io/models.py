"""The model file: one serialisation of `SloshModel` (TOML, versioned), read and written at the
file edge."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from sloshkit.errors import InputError
from sloshkit.files import atomic_open, write_json
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import Liquid
from sloshkit.model.modal import SloshMode, SloshModel

MODEL_FILE_VERSION = 1


def model_to_document(model: Any) -> dict[str, Any]:
    """A `SloshModel` as a nested dict for a model file (SI, unit-suffixed keys)."""
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
    return document


def write_model_file(path: str | Path, model: Any) -> Path:
    """Write a model file: TOML for ``.toml``, JSON otherwise; atomically.

    Parameters
    ----------
    path : str or Path
        Target file.
    model : SloshModel
        The model (`SloshModel.to_dict` is what is written).

    Returns
    -------
    Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> path = sk.write_model_file(pathlib.Path(tempfile.mkdtemp()) / "vial.toml", model)
    >>> sk.read_model_file(path).modes[0].omega_rad_s == model.modes[0].omega_rad_s
    True
    """
    document = model_to_document(model)
    if Path(path).suffix.lower() == ".toml":
        import tomli_w

        with atomic_open(path, "wb") as stream:
            tomli_w.dump(document, stream)
        return Path(path)
    return write_json(path, document)


def read_model_file(path: str | Path) -> Any:
    """Read a model file written by `write_model_file` (TOML or JSON) into a `SloshModel`.

    Each mode's frequency and damping are taken as written (they may be calibrated); the file's
    ``provenance`` table says where they came from.

    Parameters
    ----------
    path : str or Path
        The model file.

    Returns
    -------
    SloshModel
        The model.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> path = sk.write_model_file(pathlib.Path(tempfile.mkdtemp()) / "vial.json", model)
    >>> sk.read_model_file(path).fill_height_m
    0.039
    """
    import tomllib

    source = Path(path)
    if not source.is_file():
        raise InputError("model_file", str(source), "does not exist or is not a file")
    text = source.read_text(encoding="utf-8")
    try:
        document = json.loads(text) if source.suffix.lower() == ".json" else tomllib.loads(text)
    except (ValueError, tomllib.TOMLDecodeError) as error:
        raise InputError("model_file", str(source), f"is not valid TOML/JSON: {error}") from None
    try:
        container = UprightCylinder(
            float(document["container"]["radius_m"]),
            document["container"].get("wall_height_m"),
        )
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
            gravity_m_s2=float(settings.get("gravity_m_s2", 9.81)),
            damping_law=str(settings.get("damping_law", "user")),
            surface_tension_correction=bool(settings.get("surface_tension_correction", False)),
            provenance={str(k): str(v) for k, v in document.get("provenance", {}).items()},
        )
    except (KeyError, TypeError, ValueError) as error:
        if isinstance(error, InputError):
            raise
        raise InputError("model_file", str(source), f"missing or invalid entry: {error}") from None
    if not modes:
        raise InputError("model_file", str(source), "has no modes")
    return model
