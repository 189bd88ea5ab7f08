"""File input and output at the edge: CSV tables, user motions, atomic writes.

Readers are named ``read_*``, writers ``write_*``. Every writer writes a temporary file in the
target folder and renames it, so a failure never leaves a half-written file.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import IO, Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]


@contextlib.contextmanager
def atomic_open(
    path: str | Path, mode: str = "w", encoding: str | None = "utf-8"
) -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path``; rename it onto ``path`` only if the block succeeds."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{target.name}.", dir=target.parent)
    os.close(handle)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(temporary, 0o666 & ~umask)  # mkstemp creates 0600; give the usual permissions
    try:
        with open(temporary, mode, encoding=None if "b" in mode else encoding) as stream:
            yield stream
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)
        raise


def write_columns_csv(
    path: str | Path, columns: Mapping[str, Sequence[float] | FloatArray]
) -> Path:
    """Write equal-length named columns as CSV with a header row (full float precision)."""
    names = list(columns)
    arrays = [np.asarray(columns[name], dtype=float) for name in names]
    with atomic_open(path, "w") as stream:
        stream.write(",".join(names) + "\n")
        np.savetxt(stream, np.column_stack(arrays), delimiter=",", fmt="%.10g")
    return Path(path)


def write_rows_csv(path: str | Path, rows: Sequence[Mapping[str, object]]) -> Path:
    """Write a list of dicts as CSV (columns in the first row's key order)."""
    if not rows:
        raise InputError("rows", 0, "nothing to write")
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    with atomic_open(path, "w") as stream:
        stream.write(buffer.getvalue())
    return Path(path)


def json_safe(payload: Any) -> Any:
    """``payload`` with non-finite floats (an unbounded jerk, say) as None: JSON has no inf."""
    if isinstance(payload, float):
        return payload if np.isfinite(payload) else None
    if isinstance(payload, np.floating):
        return json_safe(float(payload))
    if isinstance(payload, np.integer):
        return int(payload)
    if isinstance(payload, dict):
        return {key: json_safe(value) for key, value in payload.items()}
    if isinstance(payload, list | tuple):
        return [json_safe(value) for value in payload]
    if isinstance(payload, Path):
        return str(payload)
    return payload


def write_json(path: str | Path, payload: object) -> Path:
    """Write ``payload`` as indented, strict JSON (non-finite numbers as null), atomically."""
    with atomic_open(path, "w") as stream:
        json.dump(json_safe(payload), stream, indent=2, allow_nan=False)
        stream.write("\n")
    return Path(path)


def read_table(path: str | Path) -> tuple[list[str], FloatArray]:
    """Read a numeric table: CSV or whitespace-separated, ``#`` comment lines skipped.

    The first non-comment line is a header when it is not numeric; otherwise columns are named
    by their index (``"0"``, ``"1"``, ...). OpenFOAM function-object files (``# Time ...``
    headers, vectors in parentheses) are read too: parentheses are dropped, vector components
    become separate columns, and a last comment line naming the columns is used as the header.
    Raises `InputError` for a missing or empty file or non-numeric cells.
    """
    source = Path(path)
    if not source.is_file():
        raise InputError("file", str(source), "does not exist or is not a file")
    text = source.read_text(encoding="utf-8", errors="replace")
    last_comment = ""
    lines: list[str] = []
    for raw in text.splitlines():
        stripped = raw.strip()
        if not stripped:
            continue
        if stripped.startswith("#"):
            last_comment = stripped.lstrip("#").strip()
            continue
        lines.append(stripped.replace("(", " ").replace(")", " "))
    if not lines:
        raise InputError("file", str(source), "has no data rows")
    delimiter = "," if "," in lines[0] else None
    first = _split(lines[0], delimiter)
    header: list[str] | None = None
    if not _is_numeric(first):
        header = [name.strip() for name in first]
        lines = lines[1:]
    if not lines:
        raise InputError("file", str(source), "has a header but no data rows")
    rows = []
    for number, line in enumerate(lines, start=1):
        cells = _split(line, delimiter)
        try:
            rows.append([float(cell) if cell.strip() else float("nan") for cell in cells])
        except ValueError:
            raise InputError(
                "file", f"{source}:{number}", f"row is not numeric: {line[:60]!r}"
            ) from None
    width = max(len(row) for row in rows)
    if any(len(row) != width for row in rows):
        raise InputError("file", str(source), "rows have different numbers of columns")
    data = np.asarray(rows, dtype=float)
    if header is None and last_comment:
        candidate = last_comment.split()
        header = candidate if len(candidate) == width else None
    if header is None or len(header) != width:
        header = [str(index) for index in range(width)]
    return header, data


def select_column(header: list[str], data: FloatArray, column: str, parameter: str) -> FloatArray:
    """Column by name, or by 0-based index given as text; `InputError` lists the names."""
    if column in header:
        return np.asarray(data[:, header.index(column)], dtype=float)
    if column.lstrip("-").isdigit() and -len(header) <= int(column) < len(header):
        return np.asarray(data[:, int(column)], dtype=float)
    raise InputError(parameter, column, "is not a column; columns are " + ", ".join(header))


def column_name(header: list[str], column: str) -> str:
    """The header name of a column given by name or 0-based index."""
    if column in header:
        return column
    if column.lstrip("-").isdigit() and -len(header) <= int(column) < len(header):
        return header[int(column)]
    return column


def unit_from_name(name: str) -> str | None:
    """A unit written in a column name: ``t [ms]``, ``t(ms)`` or ``t_ms``; None if absent."""
    import re

    match = re.search(r"[\[(]\s*([^\])]+?)\s*[\])]\s*$", name)
    if match:
        return match.group(1)
    match = re.search(r"_(ms|s|us|min)$", name)
    return match.group(1) if match else None


def read_motion_file(path: str | Path, name: str | None = None) -> Any:
    """A user motion from a table with a time column and a position or acceleration column.

    Column names (header) decide: time ``t``, ``t_s`` or ``time``; position ``x``,
    ``position``, ``position_m``; or acceleration ``a``, ``acceleration``,
    ``acceleration_m_s2``. Without a header, column 0 is time and column 1 is position.
    See `sloshkit.motion.laws.from_samples` for the interpolation.
    """
    from sloshkit.motion.laws import from_samples

    header, data = read_table(path)
    lowered = [column.lower() for column in header]
    time_index = next((lowered.index(n) for n in ("t", "t_s", "time", "time_s") if n in lowered), 0)
    for names, keyword in (
        (("x", "position", "position_m", "x_m"), "position_m"),
        (("a", "acceleration", "acceleration_m_s2", "a_m_s2"), "acceleration_m_s2"),
    ):
        found = next((lowered.index(n) for n in names if n in lowered), None)
        if found is not None:
            return from_samples(
                data[:, time_index], name=name or f"file:{path}", **{keyword: data[:, found]}
            )
    if data.shape[1] < 2:
        raise InputError("file", str(path), "needs a time column and a position column")
    return from_samples(data[:, time_index], position_m=data[:, 1], name=name or f"file:{path}")


def _split(line: str, delimiter: str | None) -> list[str]:
    return line.split(delimiter) if delimiter else line.split()


def _is_numeric(cells: list[str]) -> bool:
    try:
        [float(cell) for cell in cells if cell.strip()]
    except ValueError:
        return False
    return True


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
    """Write a model file: TOML for ``.toml``, JSON otherwise; atomically."""
    document = model_to_document(model)
    if Path(path).suffix.lower() == ".toml":
        import tomli_w

        with atomic_open(path, "wb") as stream:
            tomli_w.dump(document, stream)
        return Path(path)
    return write_json(path, document)


def read_model_file(path: str | Path) -> Any:
    """Read a model file written by `write_model_file` (TOML or JSON) into a `SloshModel`.

    Each mode's frequency and damping are taken as written (they may be calibrated); the
    file's ``provenance`` table says where they came from.
    """
    import tomllib

    from sloshkit.geometry import UprightCylinder
    from sloshkit.liquids import Liquid
    from sloshkit.modal import SloshMode, SloshModel

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
