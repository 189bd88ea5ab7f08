"""Container profile files: the inner profile r(z) of an axisymmetric container as a CSV of
points (``z [mm], r [mm]``) or a TOML file of points or named primitives.

CSV: two columns, height and inner radius, units in the header (``z [mm]``, ``r [mm]``; bare
names are SI metres); heights from the inner bottom, increasing. TOML::

    name = "my vial"              # optional
    source = "drawing 4711 rev B" # optional
    z_mm = [0, 0.2, 30]           # points: heights and radii with the unit in the key
    r_mm = [6.5, 7, 7]            # (z_m / r_m for metres)

or, bottom first, primitives with units in the values::

    [[segment]]
    kind = "cylinder"             # cylinder, cone, sphere, neck
    radius = "7mm"
    height = "21.4mm"
    heel_radius = "0.5mm"
    [[segment]]
    kind = "neck"
    radius = "3.5mm"
    shoulder_height = "5mm"
    height = "8mm"
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.errors import InputError
from sloshkit.io import schema
from sloshkit.io.checks import naming
from sloshkit.io.tables import column_si, find_column, read_table
from sloshkit.model.profile import (
    SEGMENT_KINDS,
    ProfileContainer,
    ProfileSegment,
    profile_from_segments,
)

#: Keys of a profile TOML file, and of one ``[[segment]]``.
PROFILE_KEYS = {"name", "source", "z_mm", "r_mm", "z_m", "r_m", "segment"}
SEGMENT_KEYS = {"kind", "radius", "height", "heel_radius", "bottom_radius", "shoulder_height"}


def read_profile_file(path: str | Path, parameter: str = "profile") -> ProfileContainer:
    """Read a container profile from a CSV of points or a TOML file (module docstring).

    Parameters
    ----------
    path : str or Path
        The file (``.toml`` or ``.json`` is a document, anything else a table).
    parameter : str
        The option that named it, for error messages (``profile``).

    Returns
    -------
    ProfileContainer
        Named after the file unless the TOML gives a ``name``.

    Raises
    ------
    InputError
        Naming ``parameter``, the file and what is wrong.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> file = pathlib.Path(tempfile.mkdtemp()) / "tube.csv"
    >>> _ = file.write_text("z [mm],r [mm]\\n0,10\\n40,10\\n")
    >>> tube = read_profile_file(file)
    >>> tube.name, round(tube.volume_for_fill_height(0.02) * 1e6, 4)  # mL
    ('tube', 6.2832)
    """
    source = Path(path)
    with naming(parameter, source):
        if source.suffix.lower() in (".toml", ".json"):
            return _profile_document(schema.read_document(source, parameter), source)
        header, data = read_table(source)
        z_index = find_column(header, ("z", "height"))
        r_index = find_column(header, ("r", "radius"))
        if z_index is None or r_index is None:
            if len(header) != 2:
                raise InputError(
                    "file", str(source), "needs the columns z [mm] and r [mm] (or two columns)"
                )
            z_index, r_index = 0, 1
        z = column_si(header, data, z_index, "length")
        r = column_si(header, data, r_index, "length")
        return _profile_points(z, r, source.stem, f"profile file {source.name}")


def _profile_points(z: np.ndarray, r: np.ndarray, name: str, source: str) -> ProfileContainer:
    if not (np.all(np.isfinite(z)) and np.all(np.isfinite(r))):
        raise InputError("file", "an empty or non-finite cell", "must hold numbers in every row")
    # Heights are measured from the inner bottom: a profile drawn from another datum is shifted.
    return ProfileContainer(
        tuple(float(v) for v in z - z[0]), tuple(float(v) for v in r), name=name, source=source
    )


def _profile_document(document: dict[str, Any], source: Path) -> ProfileContainer:
    unknown = sorted(set(document) - PROFILE_KEYS)
    if unknown:
        raise InputError(
            unknown[0],
            document[unknown[0]],
            "is not a profile key: " + ", ".join(sorted(PROFILE_KEYS)),
        )
    name = schema.text(document, "", "name", source.stem) or source.stem
    origin = schema.text(document, "", "source", f"profile file {source.name}") or source.name
    segments = document.get("segment")
    points = {key for key in ("z_mm", "r_mm", "z_m", "r_m") if key in document}
    if (segments is None) == (not points):
        raise InputError(
            "file", str(source), "needs either z_mm and r_mm (points) or [[segment]] tables"
        )
    if segments is None:
        scale = 1e-3 if "z_mm" in points or "r_mm" in points else 1.0
        unit = "mm" if scale == 1e-3 else "m"
        z = schema.number_list(document, "", f"z_{unit}")
        r = schema.number_list(document, "", f"r_{unit}")
        if z is None or r is None or len(z) != len(r):
            raise InputError(f"z_{unit}", z, f"and r_{unit} must be two lists of the same length")
        return _profile_points(np.array(z) * scale, np.array(r) * scale, name, origin)
    if not isinstance(segments, list) or not segments:
        raise InputError("segment", segments, "must be one or more [[segment]] tables")
    parsed = []
    for index, table in enumerate(segments, start=1):
        label = f"segment {index}"
        if not isinstance(table, dict):
            raise InputError(label, table, "must be a table")
        unknown = sorted(set(table) - SEGMENT_KEYS)
        if unknown:
            raise InputError(
                f"[{label}] {unknown[0]}",
                table[unknown[0]],
                "is not a key: " + ", ".join(sorted(SEGMENT_KEYS)),
            )
        kind = schema.text(table, label, "kind")
        if kind not in SEGMENT_KINDS:
            raise InputError(f"[{label}] kind", kind, "must be one of " + ", ".join(SEGMENT_KINDS))
        radius = schema.quantity(table, label, "radius", "length")
        height = schema.quantity(table, label, "height", "length")
        if radius is None or height is None:
            raise InputError(f"[{label}]", kind, "needs a radius and a height")
        parsed.append(
            ProfileSegment(
                kind,
                float(radius),
                float(height),
                heel_radius_m=float(schema.quantity(table, label, "heel_radius", "length", 0.0)),
                bottom_radius_m=float(
                    schema.quantity(table, label, "bottom_radius", "length", 0.0)
                ),
                shoulder_height_m=float(
                    schema.quantity(table, label, "shoulder_height", "length", 0.0)
                ),
            )
        )
    return profile_from_segments(parsed, name=name, source=origin)
