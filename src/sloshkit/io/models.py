"""Model files: the document of `sloshkit.model.document` (the one serialisation of a
`SloshModel`) as TOML or JSON, read and written at the file edge."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from sloshkit.errors import InputError
from sloshkit.files import atomic_open, write_json
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
    import tomllib

    source = Path(path)
    if not source.is_file():
        raise InputError("model_file", str(source), "does not exist or is not a file")
    text = source.read_text(encoding="utf-8")
    try:
        document = json.loads(text) if source.suffix.lower() == ".json" else tomllib.loads(text)
    except (ValueError, tomllib.TOMLDecodeError) as error:
        raise InputError("model_file", str(source), f"is not valid TOML/JSON: {error}") from None
    return model_from_document(document, str(source))
