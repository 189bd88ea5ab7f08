"""The ``sloshkit`` command line (typer + rich): parses units, calls the core, prints results.

Exit codes: 0 success; 1 no feasible result (e.g. a plan that cannot meet the limits);
2 invalid input (one line on stderr naming the parameter, value and valid range).
"""

from __future__ import annotations

import json
import sys
import warnings
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table
from rich.text import Text

from sloshkit.errors import InputError, ValidityWarning
from sloshkit.geometry import UprightCylinder
from sloshkit.liquids import LIQUIDS, Liquid, get_liquid
from sloshkit.modal import DAMPING_LAWS, SloshModel, equivalent_model
from sloshkit.units import parse_quantity

app = typer.Typer(
    name="sloshkit",
    help=(
        "Sloshing of liquids in moving containers: equivalent model, simulation, motion "
        "planning.\n\nExample: sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C"
    ),
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
# Wide, unwrapped output when piped (rich falls back to 80 columns otherwise).
stdout = Console(width=None if sys.stdout.isatty() else 160)


@app.callback()
def _root() -> None:
    """sloshkit: the sloshing toolkit (see the README for a tour)."""


stderr = Console(stderr=True, soft_wrap=True)

# Model options: the same names and meaning in every command.
Radius = Annotated[str, typer.Option("--radius", help="Inner radius, e.g. 20.5mm.")]
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
    bool,
    typer.Option(
        "--surface-tension-correction/--no-surface-tension-correction",
        help="Raise frequencies by the Bond-number capillary correction.",
    ),
]
Json = Annotated[bool, typer.Option("--json", help="Print one JSON object (SI units).")]


def build_model(
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
    surface_tension_correction: bool,
) -> SloshModel:
    """Turn the model options (text with units) into a `SloshModel`."""
    container = UprightCylinder(
        parse_quantity(radius, "length", "radius"),
        None if wall_height is None else parse_quantity(wall_height, "length", "wall_height"),
    )
    if fill_height is not None and fill_volume is not None:
        raise InputError("fill_volume", fill_volume, "give either --fill-height or --fill-volume")
    if fill_volume is not None:
        height = container.fill_height_for_volume(
            parse_quantity(fill_volume, "volume", "fill_volume")
        )
    else:
        height = parse_quantity(fill_height or "39mm", "length", "fill_height")
    base = get_liquid(liquid)
    overridden = Liquid(
        name=base.name if (density, viscosity, sigma) == (None, None, None) else base.name + "*",
        density_kg_m3=base.density_kg_m3
        if density is None
        else parse_quantity(density, "density", "density"),
        viscosity_pa_s=base.viscosity_pa_s
        if viscosity is None
        else parse_quantity(viscosity, "viscosity", "viscosity"),
        surface_tension_n_m=base.surface_tension_n_m
        if sigma is None
        else parse_quantity(sigma, "surface_tension", "sigma"),
        source=base.source,
    )
    if damping_law not in DAMPING_LAWS:
        raise InputError("damping_law", damping_law, "must be one of " + ", ".join(DAMPING_LAWS))
    return equivalent_model(
        container,
        overridden,
        height,
        n_modes=modes,
        damping_law=damping_law,  # type: ignore[arg-type]
        damping_ratio=damping_ratio,
        surface_tension=surface_tension_correction,
    )


def print_json(payload: object) -> None:
    """Print ``payload`` as one JSON object on stdout."""
    sys.stdout.write(json.dumps(payload, indent=2) + "\n")


def model_table(model: SloshModel) -> Table:
    """A rich table of the equivalent model, with units."""
    table = Table(
        title=(
            f"Equivalent sloshing model: R = {1e3 * model.radius_m:.2f} mm, "
            f"h = {1e3 * model.fill_height_m:.2f} mm, {model.liquid.name} "
            f"(m_F = {1e3 * model.liquid_mass_kg:.2f} g, m_0 = {1e3 * model.rigid_mass_kg:.2f} g)"
        )
    )
    columns = [
        ("mode", "n"),
        ("ω [rad/s]", "{:.2f}"),
        ("f [Hz]", "{:.3f}"),
        ("m_n [g]", "{:.3f}"),
        ("L_n [mm]", "{:.3f}"),
        ("pivot [mm]", "{:.2f}"),
        ("bob [mm]", "{:.2f}"),
        ("bob − CG [mm]", "{:.2f}"),
        ("k_n [N/m]", "{:.3f}"),
        ("ζ [-]", "{:.4f}"),
        ("c_n [N·s/m]", "{:.2e}"),
    ]
    for header, _ in columns:
        table.add_column(Text(header), justify="right")
    for mode in model.modes:
        table.add_row(
            str(mode.n),
            f"{mode.omega_rad_s:.2f}",
            f"{mode.frequency_hz:.3f}",
            f"{1e3 * mode.slosh_mass_kg:.3f}",
            f"{1e3 * mode.length_m:.3f}",
            f"{1e3 * mode.pivot_height_m:.2f}",
            f"{1e3 * mode.bob_height_m:.2f}",
            f"{1e3 * (mode.bob_height_m - model.cg_height_m):.2f}",
            f"{mode.stiffness_n_m:.3f}",
            f"{mode.damping_ratio:.4f}",
            f"{mode.damping_coefficient_n_s_m:.2e}",
        )
    table.caption = "Heights from the container bottom; damping: " + model.provenance.get(
        "damping_ratio", model.damping_law
    )
    return table


@app.command()
def model(
    radius: Radius = "20.5mm",
    fill_height: FillHeight = None,
    fill_volume: FillVolume = None,
    wall_height: WallHeight = None,
    liquid: LiquidName = "water-25C",
    density: Density = None,
    viscosity: Viscosity = None,
    sigma: Sigma = None,
    modes: Modes = 3,
    damping_law: DampingLawOpt = "seed",
    damping_ratio: DampingRatio = None,
    surface_tension_correction: SurfaceTension = False,
    json_output: Json = False,
) -> None:
    """Equivalent pendulum model of a filled upright cylinder.

    Defaults are the seed paper's vial (R 20.5 mm, h 39 mm, water at 25 °C).

    Examples:

      sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C

      sloshkit model --radius 8mm --fill-volume 2mL --liquid glycerol-50wt-20C --json
    """
    slosh_model = build_model(
        radius,
        fill_height,
        fill_volume,
        wall_height,
        liquid,
        density,
        viscosity,
        sigma,
        modes,
        damping_law,
        damping_ratio,
        surface_tension_correction,
    )
    if json_output:
        print_json(slosh_model.to_dict())
    else:
        stdout.print(model_table(slosh_model))


def _show_warning(message, category, filename, lineno, file=None, line=None):  # type: ignore[no-untyped-def]
    prefix = "warning" if category is ValidityWarning else category.__name__
    stderr.print(f"[yellow]{prefix}:[/yellow] {message}", highlight=False)


def main() -> None:
    """Entry point: run the app; user mistakes become one line on stderr and exit code 2."""
    warnings.showwarning = _show_warning
    try:
        app()
    except InputError as error:
        stderr.print(f"[red]error:[/red] {error}", highlight=False)
        raise SystemExit(2) from None
