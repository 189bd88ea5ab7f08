"""The ``sloshkit`` command line (typer + rich): parses units, calls the core, prints results.

Exit codes: 0 success; 1 no feasible result (e.g. a plan that cannot meet the limits);
2 invalid input (one line on stderr naming the parameter, value and valid range).
"""

from __future__ import annotations

import functools
import inspect
import json
import math
import sys
import typing
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import typer
from rich.console import Console
from rich.table import Table
from rich.text import Text

from sloshkit.dynamics import MODEL_KINDS, SloshResponse, simulate
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.geometry import UprightCylinder
from sloshkit.liquids import LIQUIDS, Liquid, get_liquid
from sloshkit.modal import DAMPING_LAWS, DampingLaw, SloshModel, equivalent_model
from sloshkit.motion.laws import LAW_NAMES, Motion, comparison_s_curve_limits, make_law
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
ModelFile = Annotated[
    Path | None,
    typer.Option(
        "--model-file",
        help="Model file (TOML/JSON, e.g. from 'sloshkit calibrate'); replaces the other "
        "model options.",
    ),
]
Json = Annotated[bool, typer.Option("--json", help="Print one JSON object (SI units).")]


def build_container(radius: str, wall_height: str | None) -> UprightCylinder:
    """The container from the model options."""
    return UprightCylinder(
        parse_quantity(radius, "length", "radius"),
        None if wall_height is None else parse_quantity(wall_height, "length", "wall_height"),
    )


def build_liquid(
    liquid: str, density: str | None, viscosity: str | None, sigma: str | None
) -> Liquid:
    """A preset liquid, with any of its properties overridden."""
    base = get_liquid(liquid)
    if (density, viscosity, sigma) == (None, None, None):
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
        if sigma is None
        else parse_quantity(sigma, "surface_tension", "sigma"),
        source=base.source + " (overridden)",
    )


def check_damping_law(damping_law: str) -> DampingLaw:
    """The damping-law name, or `InputError`."""
    if damping_law not in DAMPING_LAWS:
        raise InputError("damping_law", damping_law, "must be one of " + ", ".join(DAMPING_LAWS))
    return typing.cast(DampingLaw, damping_law)


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
    container = build_container(radius, wall_height)
    if fill_height is not None and fill_volume is not None:
        raise InputError("fill_volume", fill_volume, "give either --fill-height or --fill-volume")
    if fill_volume is not None:
        height = container.fill_height_for_volume(
            parse_quantity(fill_volume, "volume", "fill_volume")
        )
    else:
        height = parse_quantity(fill_height or "39mm", "length", "fill_height")
    return equivalent_model(
        container,
        build_liquid(liquid, density, viscosity, sigma),
        height,
        n_modes=modes,
        damping_law=check_damping_law(damping_law),
        damping_ratio=damping_ratio,
        surface_tension=surface_tension_correction,
    )


def print_json(payload: object) -> None:
    """Print ``payload`` as one strict JSON object on stdout (non-finite numbers as null)."""
    from sloshkit.io import json_safe

    sys.stdout.write(json.dumps(json_safe(payload), indent=2, allow_nan=False) + "\n")


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


MODEL_OPTIONS: dict[str, tuple[Any, Any]] = {
    "radius": (Radius, "20.5mm"),
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
    "surface_tension_correction": (SurfaceTension, False),
    "model_file": (ModelFile, None),
}


def with_options(
    options: dict[str, tuple[Any, Any]], target: str, build: Callable[[dict[str, Any]], Any]
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """Add a shared group of ``options`` to a command; it receives ``build(values)`` as its
    parameter ``target``.

    The options are added to the command's signature (which typer reads), so every command
    spells and documents them identically.
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


def _model_from_options(values: dict[str, Any]) -> SloshModel:
    model_file = values.pop("model_file")
    if model_file is not None:
        from sloshkit.io import read_model_file

        return typing.cast(SloshModel, read_model_file(model_file))
    return build_model(**values)


#: Give a command the shared model options; it receives the built ``slosh_model``.
with_model_options = with_options(MODEL_OPTIONS, "slosh_model", _model_from_options)


@app.command()
@with_model_options
def model(slosh_model: SloshModel, json_output: Json = False) -> None:
    """Equivalent pendulum model of a filled upright cylinder.

    Defaults are the seed paper's vial (R 20.5 mm, h 39 mm, water at 25 °C).

    Examples:

      sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C

      sloshkit model --radius 8mm --fill-volume 2mL --liquid glycerol-50wt-20C --json
    """
    if json_output:
        print_json(slosh_model.to_dict())
    else:
        stdout.print(model_table(slosh_model))


# Motion and machine-limit options: the same names in every command that moves a container.
Distance = Annotated[str, typer.Option("--distance", help="Travel distance, e.g. 0.5m.")]
Duration = Annotated[str | None, typer.Option("--duration", help="Move duration, e.g. 1.5s.")]
PeakVelocity = Annotated[
    str | None,
    typer.Option(
        "--peak-velocity",
        help="Trapezoid peak velocity; sets the duration (T = 1.5 D / V by default).",
    ),
]
Vmax = Annotated[str | None, typer.Option("--vmax", help="Machine velocity limit, e.g. 1m/s.")]
Amax = Annotated[
    str | None, typer.Option("--amax", help="Machine acceleration limit, e.g. 5m/s^2.")
]
Jmax = Annotated[str | None, typer.Option("--jmax", help="Machine jerk limit, e.g. 50m/s^3.")]
AccelFraction = Annotated[
    float | None,
    typer.Option("--accel-fraction", help="Trapezoid: acceleration time / duration (1/3)."),
]
ModelKindOpt = Annotated[
    str, typer.Option("--model", help="Slosh model: linear or nonlinear (large angles).")
]
SamplePeriod = Annotated[str, typer.Option("--sample-period", help="Simulation step, e.g. 1ms.")]
SettleTime = Annotated[
    str | None, typer.Option("--settle-time", help="Time simulated after the move.")
]
SettleTolerance = Annotated[
    str, typer.Option("--settle-tol", help="Settling tolerance on the first-mode angle.")
]


@dataclass(frozen=True)
class MoveRequest:
    """Motion options parsed to SI."""

    distance_m: float
    duration_s: float | None
    peak_velocity_m_s: float | None
    vmax: float | None
    amax: float | None
    jmax: float | None
    accel_fraction: float | None

    @classmethod
    def parse(
        cls,
        distance: str,
        duration: str | None,
        peak_velocity: str | None,
        vmax: str | None,
        amax: str | None,
        jmax: str | None,
        accel_fraction: float | None,
    ) -> MoveRequest:
        def optional(text: str | None, kind: str, name: str) -> float | None:
            return None if text is None else parse_quantity(text, kind, name)

        return cls(
            distance_m=parse_quantity(distance, "length", "distance"),
            duration_s=optional(duration, "time", "duration"),
            peak_velocity_m_s=optional(peak_velocity, "velocity", "peak_velocity"),
            vmax=optional(vmax, "velocity", "vmax"),
            amax=optional(amax, "acceleration", "amax"),
            jmax=optional(jmax, "jerk", "jmax"),
            accel_fraction=accel_fraction,
        )

    def law(self, name: str) -> Motion:
        """The motion law called ``name`` (or ``file:PATH``) for this move."""
        if name.startswith("file:"):
            from sloshkit.io import read_motion_file

            return typing.cast(Motion, read_motion_file(name.removeprefix("file:"), name))
        vmax, amax, jmax = self.vmax, self.amax, self.jmax
        if name == "s-curve" and self.peak_velocity_m_s is not None:
            vmax, amax, jmax = comparison_s_curve_limits(
                self.distance_m, self.peak_velocity_m_s, vmax, amax, jmax, self.accel_fraction
            )
        return make_law(
            name,
            self.distance_m,
            duration_s=self.duration_s,
            peak_velocity_m_s=self.peak_velocity_m_s,
            max_velocity_m_s=vmax,
            max_acceleration_m_s2=amax,
            max_jerk_m_s3=jmax,
            acceleration_fraction=self.accel_fraction,
        )


def _simulate(
    motion: Motion,
    slosh_model: SloshModel,
    model_kind: str,
    sample_period: str,
    settle_time: str | None,
    settle_tol: str,
) -> SloshResponse:
    if model_kind not in MODEL_KINDS:
        raise InputError("model", model_kind, "must be one of " + ", ".join(MODEL_KINDS))
    return simulate(
        motion,
        slosh_model,
        kind=model_kind,  # type: ignore[arg-type]
        sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
        settle_time_s=None
        if settle_time is None
        else parse_quantity(settle_time, "time", "settle_time"),
        settle_tolerance_rad=parse_quantity(settle_tol, "angle", "settle_tol"),
    )


def move_options(peak_velocity: str | None = None) -> dict[str, tuple[Any, Any]]:
    """The move and machine-limit options (one spelling everywhere)."""
    return {
        "distance": (Distance, "0.5m"),
        "duration": (Duration, None),
        "peak_velocity": (PeakVelocity, peak_velocity),
        "vmax": (Vmax, None),
        "amax": (Amax, None),
        "jmax": (Jmax, None),
        "accel_fraction": (AccelFraction, None),
    }


SIMULATION_OPTIONS: dict[str, tuple[Any, Any]] = {
    "model_kind": (ModelKindOpt, "linear"),
    "sample_period": (SamplePeriod, "1ms"),
    "settle_time": (SettleTime, None),
    "settle_tol": (SettleTolerance, "0.1deg"),
}


def with_move_options(
    peak_velocity: str | None = None,
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """The move options, parsed into ``request`` (a `MoveRequest`)."""
    return with_options(
        move_options(peak_velocity), "request", lambda values: MoveRequest.parse(**values)
    )


#: The simulation options, passed on as ``simulation`` (keyword arguments of `_simulate`).
with_simulation_options = with_options(SIMULATION_OPTIONS, "simulation", dict)


def json_number(value: float) -> float | None:
    """JSON has no infinity: an unbounded value (a jerk impulse) is written as null."""
    return value if math.isfinite(value) else None


def metrics_json(response: SloshResponse) -> dict[str, float | None]:
    """The simulate JSON keys, with infinities as null."""
    return {key: json_number(value) for key, value in response.metrics().items()}


def _format_metric(key: str, value: float) -> str:
    if not math.isfinite(value):
        return "∞ (impulse)" if "jerk" in key else "∞"
    if key.endswith("_m"):
        return f"{1e3 * value:.3f} mm"
    unit = {"_deg": "°", "_s": " s", "_m_s2": " m/s²", "_m_s3": " m/s³"}
    suffix = next((u for k, u in unit.items() if key.endswith(k)), "")
    return f"{value:.4g}{suffix}"


@app.command("simulate")
@with_model_options
@with_move_options()
@with_simulation_options
def simulate_command(
    slosh_model: SloshModel,
    request: MoveRequest,
    simulation: dict[str, Any],
    law: Annotated[
        str, typer.Option("--law", help="Law: " + ", ".join(LAW_NAMES) + ", file:PATH.")
    ] = "quintic",
    csv: Annotated[Path | None, typer.Option("--csv", help="Write the time series as CSV.")] = None,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="Write a figure (PNG/SVG/PDF).")
    ] = None,
    json_output: Json = False,
) -> None:
    """Slosh response of the container to one motion law.

    Examples:

      sloshkit simulate --law quintic --distance 0.5m --duration 1.5s --json

      sloshkit simulate --law s-curve --distance 0.5m --vmax 1m/s --amax 5m/s^2 --jmax 50m/s^3

      sloshkit simulate --law file:move.csv --model nonlinear --plot slosh.png
    """
    motion = request.law(law)
    response = _simulate(motion, slosh_model, **simulation)
    model_kind = simulation["model_kind"]
    if csv is not None:
        response.to_csv(csv)
    if plot is not None:
        response.plot(plot)
    if json_output:
        print_json({"law": motion.name, "model": model_kind, **metrics_json(response)})
        return
    table = Table(
        title=f"{motion.name} move of {1e3 * motion.distance_m:.1f} mm, {model_kind} model"
    )
    table.add_column("metric")
    table.add_column("value", justify="right")
    for key, value in response.metrics().items():
        table.add_row(key, _format_metric(key, value))
    stdout.print(table)


COMPARE_LAWS = "trapezoidal,cubic,quintic,septic,s-curve"


@app.command("compare")
@with_model_options
@with_move_options("0.5m/s")
@with_simulation_options
def compare_command(
    slosh_model: SloshModel,
    request: MoveRequest,
    simulation: dict[str, Any],
    laws: Annotated[str, typer.Option("--laws", help="Comma-separated law names.")] = COMPARE_LAWS,
    out: Annotated[
        Path | None, typer.Option("--out", help="Folder for compare.csv, compare.json, figures.")
    ] = None,
    json_output: Json = False,
) -> None:
    """All laws on the same move, side by side (the seed paper's Figs. 7-9).

    Polynomial laws take the trapezoid's duration (same peak velocity for the trapezoid); the
    s-curve takes the trapezoid's peak velocity and acceleration and a 0.1 s jerk time unless
    --vmax/--amax/--jmax are given.

    Example:

      sloshkit compare --distance 0.5m --peak-velocity 0.5m/s --out compare/
    """
    names = [name.strip() for name in laws.split(",") if name.strip()]
    if not names:
        raise InputError("laws", laws, "give at least one law name")
    motions = [request.law(name) for name in names]
    responses = [_simulate(motion, slosh_model, **simulation) for motion in motions]
    model_kind = simulation["model_kind"]
    rows = [
        {"law": motion.name, **metrics_json(response)}
        for motion, response in zip(motions, responses, strict=True)
    ]
    if out is not None:
        from sloshkit.io import write_json, write_rows_csv
        from sloshkit.plotting import plot_law_comparison, plot_slosh_comparison

        write_rows_csv(out / "compare.csv", rows)
        write_json(out / "compare.json", rows)
        plot_law_comparison(motions, out / "fig7_laws.png")
        plot_slosh_comparison(responses, out / "fig8_slosh.png")
    if json_output:
        print_json(rows)
        return
    table = Table(
        title=f"Motion laws compared: {1e3 * request.distance_m:.0f} mm move, {model_kind} model"
    )
    headers = [
        ("law", None),
        ("duration", "duration_s"),
        ("peak acc.", "peak_acceleration_m_s2"),
        ("peak jerk", "peak_jerk_m_s3"),
        ("peak θ₁", "peak_angle_deg"),
        ("residual θ₁", "residual_angle_deg"),
        ("peak wall η", "peak_wall_elevation_m"),
        ("settling", "settling_time_s"),
    ]
    for header, _ in headers:
        table.add_column(Text(header), justify="right")
    for motion, response in zip(motions, responses, strict=True):
        metrics = response.metrics()
        table.add_row(motion.name, *(_format_metric(k, metrics[k]) for _, k in headers[1:] if k))
    stdout.print(table)
    if out is not None:
        stdout.print(f"wrote {out}/compare.csv, compare.json, fig7_laws.png, fig8_slosh.png")


MaxAngle = Annotated[
    str | None, typer.Option("--max-angle", help="Limit on the peak slosh angle, e.g. 5deg.")
]
MaxResidual = Annotated[
    str | None,
    typer.Option("--max-residual", help="Limit on the residual slosh amplitude, e.g. 0.25deg."),
]


@app.command("sweep")
def sweep_command(
    distance: Distance = "0.5m",
    fill_height: Annotated[
        str | None, typer.Option("--fill-height", help="Range START:STOP:COUNT, e.g. 10mm:60mm:50.")
    ] = None,
    fill_volume: Annotated[
        str | None,
        typer.Option("--fill-volume", help="Range of volumes instead, e.g. 5mL:50mL:10."),
    ] = None,
    duration: Annotated[
        str | None, typer.Option("--duration", help="Range START:STOP:COUNT, e.g. 0.5s:3s:200.")
    ] = None,
    peak_acceleration: Annotated[
        str | None,
        typer.Option(
            "--peak-acceleration", help="Range of peak accelerations instead of durations."
        ),
    ] = None,
    laws: Annotated[str, typer.Option("--laws", help="Comma-separated law names.")] = (
        "trapezoidal,cubic,quintic,septic"
    ),
    max_angle: MaxAngle = None,
    max_residual: MaxResidual = None,
    vmax: Vmax = None,
    amax: Amax = None,
    jmax: Jmax = None,
    accel_fraction: AccelFraction = None,
    sample_period: SamplePeriod = "1ms",
    radius: Radius = "20.5mm",
    wall_height: WallHeight = None,
    liquid: LiquidName = "water-25C",
    density: Density = None,
    viscosity: Viscosity = None,
    sigma: Sigma = None,
    modes: Modes = 3,
    damping_law: DampingLawOpt = "seed",
    damping_ratio: DampingRatio = None,
    surface_tension_correction: SurfaceTension = False,
    out: Annotated[
        Path | None, typer.Option("--out", help="Folder for sweep.csv and maps.")
    ] = None,
    json_output: Json = False,
) -> None:
    """Slosh maps over fill height x move duration x law (linear fast path).

    A range is START:STOP:COUNT with both ends included. Writes sweep.csv (one row a case),
    peak_angle_map.png and residual_angle_map.png into --out, marking the region that meets
    --max-angle and --max-residual.

    Example:

      sloshkit sweep --distance 0.5m --fill-height 10mm:60mm:50 --duration 0.5s:3s:200
      --laws trapezoidal,cubic,quintic,septic --max-angle 10deg --max-residual 1deg --out maps/
    """
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    from sloshkit.sweep import describe_rate, linspace_inclusive, run_sweep
    from sloshkit.units import parse_range

    container = build_container(radius, wall_height)
    if fill_height is not None and fill_volume is not None:
        raise InputError("fill_volume", fill_volume, "give either --fill-height or --fill-volume")
    if fill_volume is not None:
        volumes = linspace_inclusive(*parse_range(fill_volume, "volume", "fill_volume"))
        heights = np.array([container.fill_height_for_volume(v) for v in volumes])
    else:
        heights = linspace_inclusive(*parse_range(fill_height or "39mm", "length", "fill_height"))
    if duration is not None and peak_acceleration is not None:
        raise InputError("peak_acceleration", peak_acceleration, "give either --duration or it")
    durations = accelerations = None
    if peak_acceleration is not None:
        accelerations = linspace_inclusive(
            *parse_range(peak_acceleration, "acceleration", "peak_acceleration")
        )
    else:
        durations = linspace_inclusive(*parse_range(duration or "0.5s:3s:200", "time", "duration"))
    request = MoveRequest.parse(distance, None, None, vmax, amax, jmax, accel_fraction)
    limits = None
    if request.vmax is not None and request.amax is not None and request.jmax is not None:
        limits = (request.vmax, request.amax, request.jmax)
    names = [name.strip() for name in laws.split(",") if name.strip()]
    with Progress(
        TextColumn("sweep"),
        BarColumn(),
        TextColumn("{task.completed:,}/{task.total:,} cases"),
        TimeRemainingColumn(),
        console=stderr,
        transient=True,
    ) as bar:
        task = bar.add_task("sweep", total=1)

        def advance(done: int, total: int) -> None:
            bar.update(task, completed=done, total=total)

        result = run_sweep(
            container,
            build_liquid(liquid, density, viscosity, sigma),
            heights,
            names,
            request.distance_m,
            durations,
            accelerations,
            n_modes=modes,
            damping_law=check_damping_law(damping_law),
            damping_ratio=damping_ratio,
            surface_tension=surface_tension_correction,
            s_curve_limits=limits,
            acceleration_fraction=accel_fraction,
            sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
            max_angle_deg=None
            if max_angle is None
            else math.degrees(parse_quantity(max_angle, "angle", "max_angle")),
            max_residual_deg=None
            if max_residual is None
            else math.degrees(parse_quantity(max_residual, "angle", "max_residual")),
            progress=advance,
        )
    summary = result.summary()
    if out is not None:
        csv_path = result.to_csv(out / "sweep.csv")
        maps = result.plot_maps(out)
        summary["csv"] = str(csv_path)
        summary["maps"] = [str(path) for path in maps]
    if json_output:
        print_json(summary)
        return
    stderr.print(describe_rate(result))
    table = Table(
        title=f"Shortest safe move per fill height ({summary['safe_cases']:,} of "
        f"{summary['cases']:,} cases safe)"
    )
    table.add_column("fill height", justify="right")
    table.add_column("ω₁ [rad/s]", justify="right")
    table.add_column("shortest safe duration", justify="right")
    table.add_column("law")
    for row, omega in zip(result.shortest_safe(), result.omega_1_rad_s, strict=True):
        shortest = row["duration_s"]
        table.add_row(
            f"{1e3 * float(typing.cast(float, row['fill_height_m'])):.1f} mm",
            f"{omega:.2f}",
            "none" if shortest is None else f"{float(typing.cast(float, shortest)):.3f} s",
            str(row["law"] or "-"),
        )
    stdout.print(table)
    if out is not None:
        stdout.print(
            f"wrote {summary['csv']} and {', '.join(typing.cast(list[str], summary['maps']))}"
        )


@app.command("calibrate")
@with_model_options
def calibrate_command(
    slosh_model: SloshModel,
    data: Annotated[Path, typer.Argument(help="CSV or whitespace table; '#' lines skipped.")],
    time_column: Annotated[str, typer.Option("--time-column", help="Name or 0-based index.")] = "0",
    signal_column: Annotated[
        str, typer.Option("--signal-column", help="Name or 0-based index.")
    ] = "1",
    time_unit: Annotated[
        str | None,
        typer.Option(
            "--time-unit", help="Unit of the time column (default: from its header, else s)."
        ),
    ] = None,
    start: Annotated[
        str | None, typer.Option("--start", help="Window start (default: largest peak).")
    ] = None,
    end: Annotated[
        str | None, typer.Option("--end", help="Window end (default: last sample).")
    ] = None,
    method: Annotated[
        str, typer.Option("--method", help="Reported estimator: fit, logdec, fft.")
    ] = "fit",
    detrend: Annotated[str, typer.Option("--detrend", help="mean, linear or none.")] = "linear",
    lowpass: Annotated[
        str | None, typer.Option("--lowpass", help="Zero-phase low-pass cut-off, e.g. 20Hz.")
    ] = None,
    model_file_out: Annotated[
        Path | None,
        typer.Option("--model-file-out", help="Write the calibrated model (TOML/JSON)."),
    ] = None,
    plot: Annotated[
        Path | None, typer.Option("--plot", help="Figure like the paper's Fig. 5b.")
    ] = None,
    json_output: Json = False,
) -> None:
    """Natural frequency and damping from a free-decay record (camera, sensor, CFD probe).

    The model options describe the container, for the comparison with theory and for the
    calibrated model file.

    Examples:

      sloshkit calibrate decay.csv --time-column t --signal-column eta --start 4s --plot fig.png

      sloshkit calibrate probes.dat --signal-column 2 --method logdec --model-file-out vial.toml
    """
    from sloshkit.calibration import METHODS, calibrate
    from sloshkit.io import column_name, read_table, select_column, unit_from_name, write_model_file

    if method not in METHODS:
        raise InputError("method", method, "must be one of " + ", ".join(METHODS))
    if detrend not in ("mean", "linear", "none"):
        raise InputError("detrend", detrend, "must be mean, linear or none")
    header, table = read_table(data)
    if time_unit is None:
        time_unit = unit_from_name(column_name(header, time_column)) or "s"
    time_scale = parse_quantity(f"1 {time_unit}", "time", "time_unit")
    time = select_column(header, table, time_column, "time_column") * time_scale
    values = select_column(header, table, signal_column, "signal_column")
    result = calibrate(
        time,
        values,
        method=typing.cast(typing.Any, method),
        start_s=None if start is None else parse_quantity(start, "time", "start"),
        end_s=None if end is None else parse_quantity(end, "time", "end"),
        detrend=typing.cast(typing.Any, detrend),
        lowpass_hz=None if lowpass is None else parse_quantity(lowpass, "frequency", "lowpass"),
        source=str(data),
    )
    payload = result.to_dict()
    theory = slosh_model.modes[0]
    payload["theory"] = {
        "omega_n_rad_s": theory.omega_rad_s,
        "frequency_hz": theory.frequency_hz,
        "damping_ratio": theory.damping_ratio,
        "damping_source": slosh_model.provenance.get("damping_ratio", ""),
    }
    if model_file_out is not None:
        write_model_file(model_file_out, result.calibrated_model(slosh_model))
        payload["model_file"] = str(model_file_out)
    if plot is not None:
        result.plot(plot)
    if json_output:
        print_json(payload)
        return
    table_out = Table(
        title=f"Calibration of {data} ({method}), window "
        f"{payload['window_s'][0]:.3f}-{payload['window_s'][1]:.3f} s"
    )
    table_out.add_column("estimator")
    for header_text in ("ω_n [rad/s]", "f_n [Hz]", "ζ [-]", "δ [-]"):
        table_out.add_column(Text(header_text), justify="right")

    def cell(value: float | None, fmt: str) -> str:
        return "n/a" if value is None else format(value, fmt)

    for name, estimate in result.estimates.items():
        omega = estimate.omega_n_rad_s
        table_out.add_row(
            name + (" (reported)" if name == method else ""),
            cell(omega, ".3f"),
            cell(None if omega is None else omega / (2 * math.pi), ".4f"),
            cell(estimate.damping_ratio, ".4f"),
            cell(estimate.log_decrement, ".4f"),
        )
    table_out.add_row(
        "theory (model)",
        f"{theory.omega_rad_s:.3f}",
        f"{theory.frequency_hz:.4f}",
        f"{theory.damping_ratio:.4f}",
        "",
    )
    stdout.print(table_out)
    fit = result.estimates["fit"]
    if fit.omega_n_interval and fit.damping_ratio_interval:
        stdout.print(
            f"fit 95 % intervals: ω_n {fit.omega_n_interval[0]:.3f}…{fit.omega_n_interval[1]:.3f} "
            f"rad/s, ζ {fit.damping_ratio_interval[0]:.4f}…{fit.damping_ratio_interval[1]:.4f}; "
            f"residual RMS {fit.residual_rms:.3g}"
        )
    for note in payload["notes"]:
        stdout.print(f"note: {note}")
    if model_file_out is not None:
        stdout.print(f"wrote {model_file_out}")


@app.command("plan")
@with_model_options
def plan_command(
    slosh_model: SloshModel,
    distance: Distance = "0.5m",
    max_angle: MaxAngle = None,
    max_residual: MaxResidual = None,
    max_wall_elevation: Annotated[
        str | None, typer.Option("--max-wall-elevation", help="Limit on the wall elevation.")
    ] = None,
    vmax: Vmax = None,
    amax: Amax = None,
    jmax: Jmax = None,
    method: Annotated[
        str,
        typer.Option(
            "--method",
            help="auto, paper, trapezoidal, cubic, quintic, septic, fast, shaped, optimal.",
        ),
    ] = "auto",
    robust: Annotated[
        str,
        typer.Option("--robust", help="Frequency band the limits must hold over, e.g. 10%."),
    ] = "0%",
    sample_period: Annotated[
        str, typer.Option("--sample-period", help="Controller sample period, e.g. 4ms.")
    ] = "4ms",
    nonlinear_optimal: Annotated[
        bool,
        typer.Option("--nonlinear-optimal", help="Optimal control with nonlinear pendulums."),
    ] = False,
    max_duration: Annotated[
        str | None, typer.Option("--max-duration", help="Longest acceptable move, e.g. 2s.")
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Trajectory CSV at the sample period.")
    ] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Figure of the candidates.")] = None,
    json_output: Json = False,
) -> None:
    """The fastest move that keeps the slosh within limits, verified by simulation.

    Every candidate is re-simulated from its sampled export. Exit code 1 when no method meets
    the limits.

    Example:

      sloshkit plan --distance 0.5m --max-angle 5deg --max-residual 0.25deg --vmax 1.5m/s
      --amax 20m/s^2 --jmax 500m/s^3 --damping-ratio 0.03 --out traj.csv --plot plan.png
    """
    from sloshkit.planning import MachineLimits, PlanProblem, SloshLimits, plan

    missing = [
        name
        for name, value in (
            ("--vmax", vmax),
            ("--amax", amax),
            ("--jmax", jmax),
            ("--max-angle", max_angle),
            ("--max-residual", max_residual),
        )
        if value is None
    ]
    if missing:
        raise InputError("plan", "incomplete", "needs " + ", ".join(missing))
    band_text = robust.strip()
    try:
        band = float(band_text.rstrip("%")) / (100.0 if band_text.endswith("%") else 1.0)
    except ValueError:
        raise InputError("robust", robust, "must be a fraction or a percentage, e.g. 10%") from None
    problem = PlanProblem(
        distance_m=parse_quantity(distance, "length", "distance"),
        machine=MachineLimits(
            parse_quantity(typing.cast(str, vmax), "velocity", "vmax"),
            parse_quantity(typing.cast(str, amax), "acceleration", "amax"),
            parse_quantity(typing.cast(str, jmax), "jerk", "jmax"),
        ),
        slosh=SloshLimits(
            parse_quantity(typing.cast(str, max_angle), "angle", "max_angle"),
            parse_quantity(typing.cast(str, max_residual), "angle", "max_residual"),
            None
            if max_wall_elevation is None
            else parse_quantity(max_wall_elevation, "length", "max_wall_elevation"),
            band,
        ),
        model=slosh_model,
        sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
        max_duration_s=None
        if max_duration is None
        else parse_quantity(max_duration, "time", "max_duration"),
    )
    with stderr.status("planning") as status:
        result = plan(problem, method, nonlinear_optimal, progress=lambda text: status.update(text))
    if result.feasible:
        if out is not None:
            result.to_csv(out)
        if plot is not None:
            result.plot(plot)
    payload = result.to_dict()
    if json_output:
        print_json(payload)
    else:
        table = Table(title=f"Plans for a {1e3 * problem.distance_m:.0f} mm move")
        for header_text in (
            "method",
            "duration",
            "peak θ₁",
            "residual θ₁",
            "peak v",
            "peak a",
            "peak j",
            "feasible",
            "compute",
        ):
            table.add_column(Text(header_text), justify="right")
        for candidate in payload["candidates"]:

            def show(value: float | None, fmt: str) -> str:
                return "-" if value is None else format(value, fmt)

            table.add_row(
                candidate["method"],
                show(candidate["duration_s"], ".4f") + " s",
                show(candidate["peak_angle_deg"], ".3f") + "°",
                show(candidate["residual_angle_deg"], ".3f") + "°",
                show(candidate["peak_velocity_m_s"], ".3f"),
                show(candidate["peak_acceleration_m_s2"], ".3f"),
                "∞"
                if candidate["peak_jerk_m_s3"] is None and candidate["duration_s"]
                else show(candidate["peak_jerk_m_s3"], ".1f"),
                "yes" if candidate["feasible"] else "no",
                f"{candidate['compute_time_s']:.3f} s",
            )
        stdout.print(table)
        if result.feasible:
            stdout.print(
                f"chosen: {payload['method']}, {payload['duration_s']:.4f} s"
                + (
                    f", {payload['speed_up_over_best_paper_law']:.2f}x faster than the best "
                    "paper law"
                    if payload["speed_up_over_best_paper_law"]
                    else ""
                )
                + (f"; wrote {out}" if out is not None else "")
            )
    if not result.feasible:
        messages = "; ".join(f"{c.method}: {c.message}" for c in result.candidates)
        stderr.print(f"[red]error:[/red] no method meets the limits ({messages})", highlight=False)
        raise typer.Exit(1)


def _run_report(
    scenario: Any, out: Path, cfd_calibration: Any = None, json_output: bool = False
) -> None:
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    from sloshkit.report import build_report

    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TimeElapsedColumn(),
        console=stderr,
        transient=True,
    ) as bar:
        task = bar.add_task("starting", total=None)
        path = build_report(
            scenario,
            out,
            progress=lambda text: bar.update(task, description=text),
            cfd_calibration=cfd_calibration,
            command="sloshkit " + " ".join(sys.argv[1:]),
        )
    if json_output:
        print_json(
            {
                "report": str(path),
                "figures": sorted(str(p) for p in (out / "figures").glob("*")),
                "tables": sorted(str(p) for p in (out / "tables").glob("*")),
            }
        )
    else:
        stdout.print(f"report: {path.resolve()}")


@app.command("reproduce")
def reproduce_command(
    out: Annotated[
        Path, typer.Option("--out", help="Folder for report.html, figures/, tables/.")
    ] = Path("sloshkit-report"),
    cfd: Annotated[
        bool,
        typer.Option(
            "--cfd",
            help="Also run the OpenFOAM free-decay calibration "
            "(case in OUT/../sloshkit-cfd-free-decay).",
        ),
    ] = False,
    cfd_case: Annotated[
        Path | None,
        typer.Option("--cfd-case", help="Reuse a finished OpenFOAM case for the calibration."),
    ] = None,
    json_output: Json = False,
) -> None:
    """Rebuild the seed paper end to end on the analytic model and write a report.

    Model (Table 3), calibration (Table 4, Fig. 5b), motion laws (Figs. 7-9), slosh maps and the
    planner's fastest safe move, with every difference from the paper explained.

    Example:

      sloshkit reproduce --out report/
    """
    from sloshkit.report import paper_scenario

    scenario = paper_scenario()
    calibration = None
    if cfd or cfd_case is not None:
        calibration = _cfd_free_decay(
            scenario.model, cfd_case or out.parent / "sloshkit-cfd-free-decay"
        )
    _run_report(scenario, out, calibration, json_output)


def _cfd_free_decay(slosh_model: SloshModel, case: Path) -> Any:
    """Calibration from a free-decay CFD case: reused when it has results, else run with the
    recommended settings on 2 MPI ranks (a few minutes), with a progress bar."""
    from sloshkit.cfd.case import FreeDecay
    from sloshkit.cfd.pipeline import analyse, case_spec

    if not (case / "postProcessing").is_dir():
        stderr.print(f"running the OpenFOAM free decay in {case} (a few minutes)")
        _run_with_progress(case_spec(slosh_model, FreeDecay(), processes=2), case, False, True)
    return analyse(case).calibration


@app.command("run")
def run_command(
    scenario_file: Annotated[Path, typer.Argument(help="Scenario TOML (see examples/).")],
    out: Annotated[
        Path | None, typer.Option("--out", help="Report folder (default: beside the file).")
    ] = None,
    json_output: Json = False,
) -> None:
    """Run a scenario file's analyses (model, calibrate, compare, sweep, plan) into a report.

    Example:

      sloshkit run examples/vial-2ml.toml --out vial-2ml-report/
    """
    from sloshkit.scenario import read_scenario

    scenario = read_scenario(scenario_file)
    calibration = None
    if "cfd" in scenario.analyses:
        case = scenario.cfd.get("case")
        calibration = _cfd_free_decay(
            scenario.model,
            scenario_file.parent / str(case or scenario_file.stem + "-cfd-free-decay"),
        )
    _run_report(scenario, out or scenario_file.with_suffix(""), calibration, json_output)


cfd_app = typer.Typer(
    help="The volume-of-fluid step with OpenFOAM (interFoam): generate, run, analyse, validate.",
    no_args_is_help=True,
)
app.add_typer(cfd_app, name="cfd")

CaseDir = Annotated[Path, typer.Option("--case", help="Case folder.")]


def cfd_options(excitation: str, end_time: str) -> dict[str, tuple[Any, Any]]:
    """The case options shared by the cfd commands (with their command's defaults)."""
    return {
        "excitation": (
            Annotated[
                str,
                typer.Option("--excitation", help="free-decay (tilted surface), harmonic or law."),
            ],
            excitation,
        ),
        "tilt": (
            Annotated[str, typer.Option("--tilt", help="Initial tilt for free-decay.")],
            "3deg",
        ),
        "amplitude": (
            Annotated[str, typer.Option("--amplitude", help="Harmonic amplitude.")],
            "10mm",
        ),
        "frequency": (
            Annotated[str, typer.Option("--frequency", help="Harmonic frequency.")],
            "1Hz",
        ),
        "excite_time": (
            Annotated[str, typer.Option("--excite-time", help="Harmonic duration.")],
            "2s",
        ),
        "law": (
            Annotated[str | None, typer.Option("--law", help="Motion law for --excitation law.")],
            None,
        ),
        "distance": (Distance, "0.1m"),
        "duration": (Duration, None),
        "cells_per_radius": (
            Annotated[int, typer.Option("--cells-per-radius", help="Mesh resolution.")],
            10,
        ),
        "end_time": (Annotated[str, typer.Option("--end-time", help="Simulated time.")], end_time),
        "delta_t": (Annotated[str, typer.Option("--delta-t", help="Fixed time step.")], "0.5ms"),
        "ddt": (
            Annotated[str, typer.Option("--ddt", help="Euler, 'CrankNicolson 0.9' or backward.")],
            "Euler",
        ),
        "np_": (Annotated[int, typer.Option("--np", help="MPI processes (1: serial).")], 1),
        "cfd_surface_tension": (
            Annotated[
                bool,
                typer.Option("--cfd-surface-tension", help="Include surface tension in the CFD."),
            ],
            False,
        ),
    }


def _cfd_spec(slosh_model: SloshModel, options: dict[str, Any]) -> Any:
    from sloshkit.cfd.pipeline import case_spec, excitation_from_options

    motion = None
    if options["excitation"] == "law":
        request = MoveRequest.parse(
            options["distance"], options["duration"], None, None, None, None, None
        )
        motion = request.law(options["law"] or "quintic")
    chosen = excitation_from_options(
        options["excitation"],
        parse_quantity(options["tilt"], "angle", "tilt"),
        parse_quantity(options["amplitude"], "length", "amplitude"),
        parse_quantity(options["frequency"], "frequency", "frequency"),
        parse_quantity(options["excite_time"], "time", "excite_time"),
        motion,
    )
    return case_spec(
        slosh_model,
        chosen,
        cells_per_radius=options["cells_per_radius"],
        end_time_s=parse_quantity(options["end_time"], "time", "end_time"),
        delta_t_s=parse_quantity(options["delta_t"], "time", "delta_t"),
        ddt_scheme=options["ddt"],
        processes=options["np_"],
        surface_tension=options["cfd_surface_tension"],
    )


def _run_with_progress(spec: Any, case: Path, resume: bool, overwrite: bool) -> Any:
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from sloshkit.cfd.pipeline import run as run_cfd
    from sloshkit.cfd.run import CfdError

    with Progress(
        TextColumn("interFoam"),
        BarColumn(),
        TextColumn("t = {task.completed:.3f}/{task.total:g} s"),
        TextColumn("Co {task.fields[courant]}"),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=stderr,
        transient=True,
    ) as bar:
        task = bar.add_task("run", total=spec.end_time_s, courant="-")

        def advance(simulated: float, end: float, courant: float | None) -> None:
            bar.update(
                task,
                completed=simulated,
                total=end,
                courant="-" if courant is None else f"{courant:.2f}",
            )

        try:
            return run_cfd(spec, case, resume=resume, overwrite=overwrite, progress=advance)
        except CfdError as error:
            stderr.print(f"[red]error:[/red] {error}", highlight=False)
            raise typer.Exit(1) from None


def _print_analysis(
    analysis: Any,
    json_output: bool,
    model_file_out: Path | None,
    plot: Path | None,
    slosh_model: SloshModel | None,
) -> None:
    from sloshkit.cfd.pipeline import describe

    payload = analysis.to_dict()
    if slosh_model is not None:
        payload["theory"] = {
            "omega_n_rad_s": slosh_model.modes[0].omega_rad_s,
            "frequency_hz": slosh_model.modes[0].frequency_hz,
        }
        if model_file_out is not None:
            from sloshkit.io import write_model_file

            write_model_file(model_file_out, analysis.calibration.calibrated_model(slosh_model))
            payload["model_file"] = str(model_file_out)
    if plot is not None:
        analysis.calibration.plot(plot)
    if json_output:
        print_json(payload)
        return
    table = Table(title=f"CFD calibration: {analysis.case} ({payload['cells']} cells)")
    for header_text in ("estimator", "ω_n [rad/s]", "f_n [Hz]", "ζ [-]"):
        table.add_column(Text(header_text), justify="right")
    for name, estimate in payload["estimates"].items():
        table.add_row(
            name,
            *(
                ("-" if estimate[k] is None else f"{estimate[k]:.4g}")
                for k in ("omega_n_rad_s", "frequency_hz", "damping_ratio")
            ),
        )
    if "theory" in payload:
        table.add_row(
            "linear theory",
            f"{payload['theory']['omega_n_rad_s']:.4g}",
            f"{payload['theory']['frequency_hz']:.4g}",
            "",
        )
    stdout.print(table)
    line = describe(analysis.run_record)
    if line:
        stdout.print(line)


@cfd_app.command("run")
@with_model_options
@with_options(cfd_options("free-decay", "3s"), "case_options", dict)
def cfd_run_command(
    slosh_model: SloshModel,
    case_options: dict[str, Any],
    case: CaseDir,
    resume: Annotated[
        bool, typer.Option("--resume", help="Continue from the last written time.")
    ] = False,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace an existing case.")
    ] = False,
    model_file_out: Annotated[
        Path | None, typer.Option("--model-file-out", help="Write the calibrated model.")
    ] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Calibration figure.")] = None,
    json_output: Json = False,
) -> None:
    """Generate and run an interFoam case of the container, then calibrate from it.

    Example:

      sloshkit cfd run --case vial-decay --excitation free-decay --cells-per-radius 10 --np 2
    """
    from sloshkit.cfd.pipeline import analyse

    spec = _cfd_spec(slosh_model, case_options)
    _run_with_progress(spec, case, resume, overwrite)
    _print_analysis(analyse(case), json_output, model_file_out, plot, slosh_model)


@cfd_app.command("analyse")
def cfd_analyse_command(
    case: Annotated[Path, typer.Argument(help="A case run by sloshkit cfd run.")],
    method: Annotated[str, typer.Option("--method", help="fit, logdec or fft.")] = "fit",
    start: Annotated[str | None, typer.Option("--start", help="Window start.")] = None,
    plot: Annotated[Path | None, typer.Option("--plot", help="Calibration figure.")] = None,
    csv: Annotated[Path | None, typer.Option("--csv", help="Write the CFD signals as CSV.")] = None,
    json_output: Json = False,
) -> None:
    """Frequency and damping from a finished case's wall elevation (calibrate's JSON keys plus
    cells, simulated_s, wall_clock_s).

    Example:

      sloshkit cfd analyse vial-decay --json
    """
    from sloshkit.cfd.pipeline import analyse

    if not (case / "sloshkit-case.json").is_file():
        raise InputError("case", str(case), "is not a sloshkit CFD case")
    analysis = analyse(
        case, method, None if start is None else parse_quantity(start, "time", "start")
    )
    if csv is not None:
        from sloshkit.io import write_columns_csv

        write_columns_csv(csv, analysis.signals.columns())
    _print_analysis(analysis, json_output, None, plot, None)


@cfd_app.command("validate")
@with_model_options
@with_options(cfd_options("harmonic", "4s"), "case_options", dict)
def cfd_validate_command(
    slosh_model: SloshModel,
    case_options: dict[str, Any],
    case: CaseDir,
    reuse: Annotated[
        bool, typer.Option("--reuse", help="Use the case's existing results.")
    ] = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="CFD vs pendulum (Fig. 9).")] = None,
    json_output: Json = False,
) -> None:
    """Run the CFD and the pendulum model on the same motion and report how far apart they
    are (frequency, damping, peak and residual wall elevation).

    Example:

      sloshkit cfd validate --case vial-harmonic --excitation harmonic --np 2 --plot fig9.png
    """
    from sloshkit.cfd.pipeline import validate

    if not reuse:
        spec = _cfd_spec(slosh_model, case_options)
        _run_with_progress(spec, case, False, True)
    result = validate(case, slosh_model)
    if plot is not None:
        from sloshkit.plotting import plot_cfd_validation

        plot_cfd_validation(result, plot)
    summary = {
        k: v
        for k, v in result.items()
        if k not in ("time_s", "cfd_elevation_m", "model_elevation_m")
    }
    if json_output:
        print_json(summary)
        return
    table = Table(title=f"CFD against the pendulum model: {case}")
    for header_text in ("quantity", "CFD", "model", "difference"):
        table.add_column(Text(header_text), justify="right")
    for key, row in summary["comparison"].items():
        table.add_row(
            key,
            *("-" if row[k] is None else f"{row[k]:.4g}" for k in ("cfd", "model")),
            "-"
            if row["relative_difference"] is None
            else f"{100 * row['relative_difference']:+.1f} %",
        )
    stdout.print(table)
    stdout.print(f"correlation of the wall-elevation signals: {summary['correlation']:.4f}")


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
