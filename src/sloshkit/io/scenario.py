"""Scenario files (TOML): a container, liquid, move, limits and the analyses to run.

Values carry units as text (``radius = "20.5mm"``); bare numbers are SI. Unknown tables or keys
are rejected with the list of allowed ones, so a typo never silently falls back to a default.
See ``examples/*.toml``.
"""

from __future__ import annotations

import typing
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sloshkit.errors import InputError
from sloshkit.io import schema
from sloshkit.io.requests import (
    container_request,
    fill_height_request,
    liquid_request,
    model_request,
    profile_request,
)
from sloshkit.io.units import parse_range
from sloshkit.model.modal import SloshModel
from sloshkit.model.profile import Container

ANALYSES: tuple[str, ...] = ("model", "calibrate", "compare", "sweep", "plan", "cfd")
_SCHEMA: dict[str, set[str]] = {
    "": {"name", "description", "analyses", "paper_comparison"},
    "container": {"radius", "wall_height", "name", "profile"},
    "liquid": {"preset", "density", "viscosity", "surface_tension"},
    "fill": {"height", "volume"},
    "model": {"modes", "damping_law", "damping_ratio", "surface_tension_correction"},
    "move": {"distance", "peak_velocity", "duration", "laws", "vmax", "amax", "jmax"},
    "limits": {
        "max_angle",
        "max_residual",
        "max_wall_elevation",
        "vmax",
        "amax",
        "jmax",
        "sample_period",
        "robust",
        "method",
    },
    "sweep": {"fill_height", "duration", "laws"},
    "calibrate": {"data", "time_column", "signal_column", "start", "end", "method", "time_unit"},
    "cfd": {"cells_per_radius", "end_time", "np", "case", "tilt"},
}


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario: SI values, the analyses to run, and the raw tables for the report.

    Attributes
    ----------
    name, description : str
        Title and description of the report.
    model : SloshModel
        The equivalent model of the container, liquid and fill.
    distance_m : float
        Move distance [m].
    peak_velocity_m_s, duration_s : float or None
        The move's peak velocity [m/s] or duration [s] (one of them).
    laws : tuple of str
        The laws compared.
    move_limits : tuple
        Velocity, acceleration and jerk limits of the compared move (None: unlimited).
    plan_limits : dict
        The planner's limits (SI; ``max_angle`` and ``max_residual`` in radians).
    analyses : tuple of str
        model, calibrate, compare, sweep, plan, cfd.
    sweep, calibrate, cfd : dict
        The options of those analyses.
    paper_comparison : bool
        Show the seed paper's printed values beside sloshkit's.
    source : str
        The scenario file ("" when built in).
    raw : dict
        The document as read, for the report.

    Examples
    --------
    >>> scenario = parse_scenario(PAPER_SCENARIO)
    >>> scenario.analyses, round(scenario.plan_limits["sample_period"], 6)
    (('model', 'calibrate', 'compare', 'sweep', 'plan'), 0.004)
    """

    name: str
    model: SloshModel
    distance_m: float
    peak_velocity_m_s: float | None
    duration_s: float | None
    laws: tuple[str, ...]
    move_limits: tuple[float | None, float | None, float | None]
    plan_limits: dict[str, Any]
    analyses: tuple[str, ...]
    sweep: dict[str, Any] = field(default_factory=dict)
    calibrate: dict[str, Any] = field(default_factory=dict)
    cfd: dict[str, Any] = field(default_factory=dict)
    description: str = ""
    paper_comparison: bool = False
    source: str = ""
    raw: dict[str, Any] = field(default_factory=dict)


def _check_keys(table: dict[str, Any], section: str) -> None:
    allowed = _SCHEMA[section]
    for key, value in table.items():
        if section == "" and isinstance(value, dict):
            if key not in _SCHEMA or key == "":
                raise InputError(
                    "scenario",
                    f"[{key}]",
                    "unknown table; allowed: " + ", ".join(f"[{k}]" for k in _SCHEMA if k),
                )
            _check_keys(value, key)
        elif key not in allowed:
            where = f"[{section}] " if section else ""
            raise InputError(
                "scenario", f"{where}{key}", "unknown key; allowed: " + ", ".join(sorted(allowed))
            )


def parse_scenario(
    document: dict[str, Any], source: str = "", base: Path | None = None
) -> Scenario:
    """Build a `Scenario` from a TOML document (already parsed).

    Every key is read with its TOML type checked (`sloshkit.io.schema`); errors name the key
    with its table, e.g. ``[container] radius``.

    Parameters
    ----------
    document : dict
        The TOML document.
    source : str
        Where it came from (file name), for messages and the report.
    base : pathlib.Path, optional
        Folder that relative data paths are read from.

    Returns
    -------
    Scenario

    Examples
    --------
    >>> scenario = parse_scenario({"analyses": ["model", "compare"],
    ...                            "container": {"radius": "20.5mm"}, "fill": {"height": "39mm"},
    ...                            "move": {"distance": "0.2m", "duration": "1s"}})
    >>> round(scenario.model.modes[0].frequency_hz, 2), scenario.distance_m
    (4.72, 0.2)
    >>> parse_scenario({"container": {"radius": "abc"}})
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: [container] radius = ...
    """
    _check_keys(document, "")
    container_table = schema.section(document, "container")
    container = _container(container_table, base)
    liquid_table = schema.section(document, "liquid")
    liquid = liquid_request(
        schema.text(liquid_table, "liquid", "preset", "water-25C") or "",
        schema.quantity(liquid_table, "liquid", "density", "density"),
        schema.quantity(liquid_table, "liquid", "viscosity", "viscosity"),
        schema.quantity(liquid_table, "liquid", "surface_tension", "surface_tension"),
        note="overridden in the scenario",
    )
    fill = schema.section(document, "fill")
    height = fill_height_request(
        container,
        schema.quantity(fill, "fill", "height", "length"),
        schema.quantity(fill, "fill", "volume", "volume"),
        default=None,
        height_parameter="[fill] height",
        volume_parameter="[fill] volume",
    )
    model_table = schema.section(document, "model")
    model = model_request(
        container,
        liquid,
        height,
        modes=schema.integer(model_table, "model", "modes", 3, 1, 50),
        damping_law=schema.text(model_table, "model", "damping_law", "seed") or "",
        damping_ratio=schema.number(model_table, "model", "damping_ratio"),
        surface_tension_correction=None
        if "surface_tension_correction" not in model_table
        else schema.boolean(model_table, "model", "surface_tension_correction"),
    )
    move = schema.section(document, "move")

    def optional(table: dict[str, Any], key: str, kind: str, name: str) -> float | None:
        return typing.cast(float | None, schema.quantity(table, name, key, kind))

    analyses = schema.text_list(document, "", "analyses", ["model", "compare", "plan"])
    for analysis in analyses:
        if analysis not in ANALYSES:
            raise InputError("analyses", analysis, "must be among " + ", ".join(ANALYSES))
    limits = schema.section(document, "limits")
    plan_limits: dict[str, Any] = {}
    if "plan" in analyses or "sweep" in analyses:
        for key, kind in (("max_angle", "angle"), ("max_residual", "angle")):
            if key not in limits:
                raise InputError("scenario", f"[limits] {key}", "is required for plan and sweep")
            plan_limits[key] = schema.quantity(limits, "limits", key, kind)
    if "plan" in analyses:
        for key, kind in (("vmax", "velocity"), ("amax", "acceleration"), ("jmax", "jerk")):
            if key not in limits:
                raise InputError("scenario", f"[limits] {key}", "is required for plan")
            plan_limits[key] = schema.quantity(limits, "limits", key, kind)
        plan_limits["sample_period"] = schema.quantity(
            limits, "limits", "sample_period", "time", "4ms"
        )
        plan_limits["robust"] = schema.quantity(limits, "limits", "robust", "fraction", "0%")
        plan_limits["method"] = schema.text(limits, "limits", "method", "auto")
        plan_limits["max_wall_elevation"] = optional(
            limits, "max_wall_elevation", "length", "limits"
        )
    sweep: dict[str, Any] = {}
    if "sweep" in analyses:
        table = schema.section(document, "sweep")
        default_fill = f"{0.5 * height}:{min(1.5 * height, container.wall_height_m or 1e9)}:21"
        sweep = {
            "fill_height": parse_range(
                schema.text(table, "sweep", "fill_height", default_fill) or "",
                "length",
                "[sweep] fill_height",
            ),
            "duration": parse_range(
                schema.text(table, "sweep", "duration", "0.5s:3s:60") or "",
                "time",
                "[sweep] duration",
            ),
            "laws": schema.text_list(
                table, "sweep", "laws", ["trapezoidal", "cubic", "quintic", "septic"]
            ),
        }
    calibrate: dict[str, Any] = {}
    if "calibrate" in analyses and "calibrate" in document:
        table = schema.section(document, "calibrate")
        if "data" not in table:
            raise InputError("scenario", "[calibrate] data", "is required to calibrate from a file")
        data = Path(schema.text(table, "calibrate", "data") or "")
        if base is not None and not data.is_absolute():
            data = base / data
        calibrate = {
            "data": data,
            "time_column": _column(table, "time_column", "0"),
            "signal_column": _column(table, "signal_column", "1"),
            "start": optional(table, "start", "time", "calibrate"),
            "end": optional(table, "end", "time", "calibrate"),
            "method": schema.text(table, "calibrate", "method", "fit"),
            "time_unit": schema.text(table, "calibrate", "time_unit", "s"),
        }
    return Scenario(
        name=schema.text(document, "", "name", "scenario") or "scenario",
        model=model,
        distance_m=schema.quantity(move, "move", "distance", "length", "0.5m"),
        peak_velocity_m_s=optional(move, "peak_velocity", "velocity", "move"),
        duration_s=optional(move, "duration", "time", "move"),
        laws=schema.text_list(
            move, "move", "laws", ["trapezoidal", "cubic", "quintic", "septic", "s-curve"]
        ),
        move_limits=(
            optional(move, "vmax", "velocity", "move"),
            optional(move, "amax", "acceleration", "move"),
            optional(move, "jmax", "jerk", "move"),
        ),
        plan_limits=plan_limits,
        analyses=analyses,
        sweep=sweep,
        calibrate=calibrate,
        cfd=dict(schema.section(document, "cfd")),
        description=schema.text(document, "", "description", "") or "",
        paper_comparison=schema.boolean(document, "", "paper_comparison"),
        source=source,
        raw=document,
    )


def _container(table: dict[str, Any], base: Path | None) -> Container:
    """[container]: a radius (and wall height), a catalogue ``name`` or a ``profile`` file."""
    given = [key for key in ("radius", "name", "profile") if key in table]
    if len(given) != 1:
        raise InputError(
            "scenario",
            "[container] " + (", ".join(given) or "radius"),
            "give exactly one of radius, name (e.g. iso8362-2R) or profile (a profile file)",
        )
    if given[0] == "radius":
        return container_request(
            schema.quantity(table, "container", "radius", "length"),
            schema.quantity(table, "container", "wall_height", "length"),
        )
    if "wall_height" in table:
        raise InputError("[container] wall_height", table["wall_height"], "comes from the profile")
    profile = schema.text(table, "container", "profile")
    path = None if profile is None else Path(profile)
    if path is not None and base is not None and not path.is_absolute():
        path = base / path
    real = profile_request(
        schema.text(table, "container", "name"),
        path,
        container_parameter="[container] name",
        profile_parameter="[container] profile",
    )
    return typing.cast(Container, real)


def _column(table: dict[str, Any], key: str, default: str) -> str:
    """A column given by name (text) or 0-based index (integer)."""
    value = table.get(key, default)
    if isinstance(value, int) and not isinstance(value, bool):
        return str(value)
    return schema.text(table, "calibrate", key, default) or default


def read_scenario(path: str | Path) -> Scenario:
    r"""Read and check a scenario TOML file (see `sloshkit.io.schema.read_document`).

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file.

    Returns
    -------
    Scenario

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "vial.toml"
    >>> _ = path.write_text('name = "vial"\nanalyses = ["model"]\n[container]\nradius = "20.5mm"\n'
    ...                     '[fill]\nheight = "39mm"\n[move]\ndistance = "0.2m"\n'
    ...                     'duration = "1s"\n')
    >>> scenario = read_scenario(path)
    >>> scenario.name, scenario.source.endswith("vial.toml")
    ('vial', True)
    """
    source = Path(path)
    document = schema.read_document(source, "scenario")
    return parse_scenario(document, str(source), source.parent)


#: The seed paper's case, as `sloshkit reproduce` runs it.
PAPER_SCENARIO: dict[str, Any] = {
    "name": "De Simone et al. (2024): glass vial on a linear slide",
    "description": (
        "R = 20.5 mm, h = 39 mm, water; 0.5 m move at 0.5 m/s peak (trapezoid 1.5 s); damping "
        "ratio 0.03 as in the paper's Table 3; planner limits 5 deg peak, 0.25 deg residual, "
        "1.5 m/s, 20 m/s^2, 500 m/s^3, 4 ms controller period."
    ),
    "paper_comparison": True,
    "analyses": ["model", "calibrate", "compare", "sweep", "plan"],
    "container": {"radius": "20.5mm", "wall_height": "60mm"},
    "liquid": {"preset": "water-25C", "density": "1000 kg/m^3"},
    "fill": {"height": "39mm"},
    # The paper's model has no capillary correction (it would raise f_1 by 2.9 % here).
    "model": {"modes": 3, "damping_ratio": 0.03, "surface_tension_correction": False},
    "move": {"distance": "0.5m", "peak_velocity": "0.5m/s"},
    "limits": {
        "max_angle": "5deg",
        "max_residual": "0.25deg",
        "vmax": "1.5m/s",
        "amax": "20m/s^2",
        "jmax": "500m/s^3",
        "sample_period": "4ms",
    },
    "sweep": {
        "fill_height": "15mm:55mm:21",
        "duration": "0.8s:3s:45",
        "laws": ["trapezoidal", "cubic", "quintic", "septic"],
    },
}
