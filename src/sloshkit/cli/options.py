"""Shared CLI option groups: the model options, output options and the decorator that adds an
option group to a command (same names and meaning in every command)."""

from __future__ import annotations

import functools
import inspect
import json
import math
import sys
import typing
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

from sloshkit.files import json_safe
from sloshkit.io.command_requests import cylinder_model_or_file_request, model_or_file_request
from sloshkit.io.model_options import DEFAULT_RADIUS
from sloshkit.model.catalogue import catalogue_names
from sloshkit.model.liquids import LIQUIDS
from sloshkit.model.modal import SloshModel

Radius = Annotated[str, typer.Option("--radius", help="Inner radius, e.g. 20.5mm.")]


ContainerName = Annotated[
    str | None,
    typer.Option(
        "--container",
        help="A real container by name instead of --radius (its inner profile, modes by finite "
        "elements): " + catalogue_names() + ".",
    ),
]


ProfileFile = Annotated[
    Path | None,
    typer.Option(
        "--profile",
        help="Inner profile r(z) of an axisymmetric container instead of --radius: CSV "
        "'z [mm], r [mm]' or TOML (points or primitives; docs/containers.md).",
    ),
]


FillHeight = Annotated[
    str | None, typer.Option("--fill-height", help="Static fill height, e.g. 39mm.")
]


FillVolume = Annotated[
    str | None,
    typer.Option("--fill-volume", help="Liquid volume instead of --fill-height, e.g. 2mL."),
]


WallHeight = Annotated[
    str | None, typer.Option("--wall-height", help="Inner wall height (checks the fill fits).")
]


LiquidName = Annotated[
    str, typer.Option("--liquid", help="Liquid preset: " + ", ".join(sorted(LIQUIDS)) + ".")
]


Density = Annotated[
    str | None, typer.Option("--density", help="Override density, e.g. 1000kg/m^3.")
]


Viscosity = Annotated[
    str | None, typer.Option("--viscosity", help="Override dynamic viscosity, e.g. 1mPa*s.")
]


Sigma = Annotated[
    str | None, typer.Option("--sigma", help="Override surface tension, e.g. 72mN/m.")
]


Modes = Annotated[int, typer.Option("--modes", help="Number of sloshing modes.")]


DampingLawOpt = Annotated[
    str,
    typer.Option("--damping-law", help="First-mode damping correlation: seed, sp106, stephens."),
]


DampingRatio = Annotated[
    float | None,
    typer.Option("--damping-ratio", help="Damping ratio for all modes (overrides the law)."),
]


SurfaceTension = Annotated[
    bool | None,
    typer.Option(
        "--surface-tension-correction/--no-surface-tension-correction",
        help="Raise frequencies by the Bond-number capillary correction (default: where it "
        "raises f₁ by more than 5 %, with a warning).",
        show_default=False,
    ),
]


ModelFile = Annotated[
    Path | None,
    typer.Option(
        "--model-file",
        help="Model file (TOML/JSON, e.g. from 'sloshkit calibrate'); replaces the other "
        "model options.",
    ),
]


Json = Annotated[bool, typer.Option("--json", help="Print one JSON object (SI units).")]


def print_json(payload: object) -> None:
    """Print ``payload`` as one strict JSON object on stdout (non-finite numbers as null),
    with the command's ``warnings`` list.

    Parameters
    ----------
    payload : object
        JSON-ready data.

    Examples
    --------
    >>> print_json({"peak_jerk_m_s3": float("inf")})
    {
      "peak_jerk_m_s3": null,
      "warnings": []
    }
    """

    from sloshkit.cli.notes import with_warnings

    payload = with_warnings(payload)
    sys.stdout.write(json.dumps(json_safe(payload), indent=2, allow_nan=False) + "\n")


MODEL_OPTIONS: dict[str, tuple[Any, Any]] = {
    "radius": (Radius, DEFAULT_RADIUS),
    "fill_height": (FillHeight, None),
    "fill_volume": (FillVolume, None),
    "wall_height": (WallHeight, None),
    "liquid": (LiquidName, "water-25C"),
    "density": (Density, None),
    "viscosity": (Viscosity, None),
    "sigma": (Sigma, None),
    "modes": (Modes, 3),
    "damping_law": (DampingLawOpt, "seed"),
    "damping_ratio": (DampingRatio, None),
    "surface_tension_correction": (SurfaceTension, None),
    "model_file": (ModelFile, None),
    "container": (ContainerName, None),
    "profile": (ProfileFile, None),
}

#: Model option -> its default (an option that differs was given).
MODEL_DEFAULTS: dict[str, Any] = {name: default for name, (_, default) in MODEL_OPTIONS.items()}


def with_options(
    options: dict[str, tuple[Any, Any]], target: str, build: Callable[[dict[str, Any]], Any]
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """Add a shared group of ``options`` to a command; it receives ``build(values)`` as its
    parameter ``target``.

    The options are added to the command's signature (which typer reads), so every command
    spells and documents them identically.

    Parameters
    ----------
    options : dict
        Option name -> (typer annotation, default).
    target : str
        The command's parameter that receives the built value.
    build : callable
        Option values -> the value passed as ``target``.

    Returns
    -------
    callable
        The decorator.

    Examples
    --------
    >>> import inspect
    >>> from typing import Annotated
    >>> import typer
    >>> Scale = Annotated[float, typer.Option("--scale")]
    >>> @with_options({"scale": (Scale, 2.0)}, "factor", lambda values: 10 * values["scale"])
    ... def command(factor: float) -> None:
    ...     print(factor)
    >>> list(inspect.signature(command).parameters)
    ['scale']
    >>> command(scale=3.0)
    30.0
    """

    def decorate(command: Callable[..., None]) -> Callable[..., None]:
        signature = inspect.signature(command, eval_str=True)
        own = [p for p in signature.parameters.values() if p.name != target]
        added = [
            inspect.Parameter(
                name, inspect.Parameter.KEYWORD_ONLY, default=default, annotation=hint
            )
            for name, (hint, default) in options.items()
        ]
        own_hints = typing.get_type_hints(command, include_extras=True)

        @functools.wraps(command)
        def wrapper(**kwargs: Any) -> None:
            kwargs[target] = build({name: kwargs.pop(name) for name in options})
            command(**kwargs)

        ordered = sorted(own + added, key=lambda p: p.default is not inspect.Parameter.empty)
        wrapper.__signature__ = signature.replace(  # type: ignore[attr-defined]
            parameters=[p.replace(kind=inspect.Parameter.KEYWORD_ONLY) for p in ordered]
        )
        wrapper.__annotations__ = {
            **{name: own_hints[name] for name in own_hints if name not in (target, "return")},
            **{name: hint for name, (hint, _) in options.items()},
        }
        return wrapper

    return decorate


def with_model_options(command: Callable[..., None]) -> Callable[..., None]:
    """Give a command the shared model options; it receives the built ``slosh_model``.

    Parameters
    ----------
    command : callable
        A command with a ``slosh_model`` parameter.

    Returns
    -------
    callable
        The command with the model options (`MODEL_OPTIONS`) in its signature.

    Examples
    --------
    >>> @with_model_options
    ... def command(slosh_model: SloshModel) -> None:
    ...     print(round(slosh_model.modes[0].frequency_hz, 2))
    >>> options = {name: default for name, (_, default) in MODEL_OPTIONS.items()}
    >>> command(**{**options, "fill_height": "39mm"})
    4.72
    """
    return with_options(MODEL_OPTIONS, "slosh_model", _model_from_options)(command)


def _model_from_options(values: dict[str, Any]) -> SloshModel:
    return model_or_file_request(values, MODEL_DEFAULTS)


def with_cylinder_model_options(command: Callable[..., None]) -> Callable[..., None]:
    """The shared model options for a command that needs an upright cylinder (CFD): a
    ``--container`` or ``--profile`` is refused before any model is built.

    Parameters
    ----------
    command : callable
        A command with a ``slosh_model`` parameter.

    Returns
    -------
    callable
        The command with the model options (`MODEL_OPTIONS`) in its signature.

    Examples
    --------
    >>> @with_cylinder_model_options
    ... def command(slosh_model: SloshModel) -> None:
    ...     print(slosh_model.radius_m)
    >>> options = {name: default for name, (_, default) in MODEL_OPTIONS.items()}
    >>> command(**{**options, "container": "iso8362-2R"})
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: container = 'iso8362-2R' is invalid: CFD meshes upright ...
    """
    return with_options(MODEL_OPTIONS, "slosh_model", _cylinder_model_from_options)(command)


def _cylinder_model_from_options(values: dict[str, Any]) -> SloshModel:
    return cylinder_model_or_file_request(values, MODEL_DEFAULTS)


def json_number(value: float) -> float | None:
    """JSON has no infinity: an unbounded value (a jerk impulse) is written as null.

    Parameters
    ----------
    value : float
        The number.

    Returns
    -------
    float or None

    Examples
    --------
    >>> json_number(2.5), json_number(float("inf"))
    (2.5, None)
    """
    return value if math.isfinite(value) else None
