"""Shared CLI option groups for commands that move a container: distance, duration, law,
machine limits and the simulation settings."""

from __future__ import annotations

import math
import typing
from collections.abc import Callable
from typing import Annotated, Any

import typer

from sloshkit.cli.options import json_number, with_options
from sloshkit.io.command_requests import MoveRequest

if typing.TYPE_CHECKING:  # imported where used: the simulation stack is not start-up's
    from sloshkit.sim.response import SloshResponse

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


def move_options(peak_velocity: str | None = None) -> dict[str, tuple[Any, Any]]:
    """The move and machine-limit options (one spelling everywhere).

    Parameters
    ----------
    peak_velocity : str, optional
        Default of ``--peak-velocity``.

    Returns
    -------
    dict
        Option name -> (typer annotation, default).

    Examples
    --------
    >>> options = move_options("0.5m/s")
    >>> list(options)[:3], options["peak_velocity"][1]
    (['distance', 'duration', 'peak_velocity'], '0.5m/s')
    """
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
    """The move options, parsed into ``request`` (a `MoveRequest`).

    Parameters
    ----------
    peak_velocity : str, optional
        Default of ``--peak-velocity``.

    Returns
    -------
    callable
        A decorator for a command with a ``request`` parameter.

    Examples
    --------
    >>> @with_move_options()
    ... def command(request: MoveRequest) -> None:
    ...     print(request.distance_m, request.duration_s)
    >>> command(distance="0.3m", duration="2s", peak_velocity=None, vmax=None, amax=None,
    ...         jmax=None, accel_fraction=None)
    0.3 2.0
    """
    return with_options(
        move_options(peak_velocity), "request", lambda values: MoveRequest.parse(**values)
    )


#: The simulation options, passed on as ``simulation`` (keyword arguments of
#: `sloshkit.io.command_requests.simulate_with_options`).
with_simulation_options = with_options(SIMULATION_OPTIONS, "simulation", dict)


def metrics_json(response: SloshResponse) -> dict[str, float | None]:
    """The simulate JSON keys, with infinities as null.

    Parameters
    ----------
    response : SloshResponse
        The simulation.

    Returns
    -------
    dict

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> metrics = metrics_json(sk.simulate(model, sk.trapezoidal(0.1, 0.1)))
    >>> metrics["peak_jerk_m_s3"], metrics["duration_s"] > 0
    (None, True)
    """
    return {key: json_number(value) for key, value in response.metrics().items()}


def _format_metric(key: str, value: float) -> str:
    if not math.isfinite(value):
        return "∞ (impulse)" if "jerk" in key else "∞"
    if key.endswith("_m"):
        return f"{1e3 * value:.3f} mm"
    unit = {"_deg": "°", "_s": " s", "_m_s2": " m/s²", "_m_s3": " m/s³"}
    suffix = next((u for k, u in unit.items() if key.endswith(k)), "")
    return f"{value:.4g}{suffix}"
