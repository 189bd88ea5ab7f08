"""Model files: the document of `sloshkit.model.document` (the one serialisation of a
`SloshModel`) as TOML or JSON, read and written at the file edge."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from sloshkit.errors import InputError
from sloshkit.files import atomic_open, write_json
from sloshkit.io.schema import read_document
from sloshkit.model.document import model_from_document, model_to_document


def write_model_file(path: str | Path, model: Any) -> Path:
    """Write a model file: TOML for ``.toml``, JSON otherwise; atomically.

    Parameters
    ----------
    path : str or Path
        Target file.
    model : SloshModel
        The model (its `sloshkit.model.document.model_to_document` is written).

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

    source = Path(path)
    document = read_document(source, "model_file")
    _check_model_document(document)
    return model_from_document(document, str(source))


#: Per-mode entries of a model file that must be finite and > 0, and those that must be >= 0.
_POSITIVE_MODE_KEYS = ("bessel_root", "omega_rad_s", "slosh_mass_kg", "length_m")
_FINITE_MODE_KEYS = ("bob_height_m", "wall_elevation_factor_m")


def _check_model_document(document: dict[str, Any]) -> None:
    """Refuse wrong types and non-physical values in a model file, naming the entry."""
    for table, keys in (
        ("container", ("radius_m",)),
        ("liquid", ("density_kg_m3", "viscosity_pa_s", "surface_tension_n_m")),
        ("fill", ("fill_height_m",)),
    ):
        section = document.get(table)
        if not isinstance(section, dict):
            raise InputError("model_file", f"[{table}]", "is missing or not a table")
        for key in keys:
            _require_number(section.get(key), f"[{table}] {key}", positive=key != "viscosity_pa_s")
    modes = document.get("modes")
    if not isinstance(modes, list) or not modes:
        raise InputError("model_file", "[[modes]]", "needs at least one mode table")
    for index, mode in enumerate(modes, start=1):
        name = f"[[modes]] #{index}"
        if not isinstance(mode, dict):
            raise InputError("model_file", name, "must be a table")
        n = mode.get("n")
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise InputError(f"{name} n", n, "must be an integer >= 1")
        for key in _POSITIVE_MODE_KEYS:
            _require_number(mode.get(key), f"{name} {key}", positive=True)
        for key in _FINITE_MODE_KEYS:
            _require_number(mode.get(key), f"{name} {key}", positive=False)
        zeta = _require_number(mode.get("damping_ratio"), f"{name} damping_ratio", positive=False)
        if not 0.0 <= zeta < 1.0:
            raise InputError(f"{name} damping_ratio", zeta, "must be in [0, 1) (underdamped)")
        frequency = mode.get("frequency_hz")
        if frequency is not None:
            _require_number(frequency, f"{name} frequency_hz", positive=True)


def _require_number(value: object, name: str, positive: bool) -> float:
    """``value`` as float: a finite number (> 0 when ``positive``; a viscosity >= 0)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(name, value, "must be a number")
    number = float(value)
    if not math.isfinite(number):
        raise InputError(name, number, "must be finite")
    if positive and number <= 0.0:
        raise InputError(name, number, "must be > 0")
    if name.endswith(("viscosity_pa_s", "damping_ratio")) and number < 0.0:
        raise InputError(name, number, "must be >= 0")
    return number
