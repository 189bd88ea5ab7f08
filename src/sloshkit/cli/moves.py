"""Shared CLI option groups for commands that move a container: distance, duration, law,
machine limits and the simulation settings."""

from __future__ import annotations

import math
import typing
from collections.abc import Callable
from dataclasses import dataclass
from typing import Annotated, Any

import typer

from sloshkit.cli.notes import check_bare_length
from sloshkit.cli.options import json_number, with_options
from sloshkit.errors import InputError
from sloshkit.io.units import parse_quantity
from sloshkit.model.modal import SloshModel

if typing.TYPE_CHECKING:  # imported where used: the simulation stack is not start-up's
    from sloshkit.motion.profile import Motion
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


@dataclass(frozen=True)
class MoveRequest:
    """Motion options parsed to SI.

    Attributes
    ----------
    distance_m : float
        Move distance [m].
    duration_s, peak_velocity_m_s : float or None
        Move duration [s] or peak velocity [m/s].
    vmax, amax, jmax : float or None
        Machine limits [m/s], [m/s^2], [m/s^3].
    accel_fraction : float or None
        The trapezoid's acceleration time over the move time.

    Examples
    --------
    >>> request = MoveRequest.parse("200mm", "1.2s", None, None, None, None, None)
    >>> request.distance_m, request.duration_s
    (0.2, 1.2)
    """

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

        distance_m = parse_quantity(distance, "length", "distance")
        check_bare_length(distance, distance_m, "distance")
        return cls(
            distance_m=distance_m,
            duration_s=optional(duration, "time", "duration"),
            peak_velocity_m_s=optional(peak_velocity, "velocity", "peak_velocity"),
            vmax=optional(vmax, "velocity", "vmax"),
            amax=optional(amax, "acceleration", "amax"),
            jmax=optional(jmax, "jerk", "jmax"),
            accel_fraction=accel_fraction,
        )

    def law(self, name: str) -> Motion:
        """The motion law called ``name`` (or ``file:PATH``) for this move."""
        from sloshkit.io.motions import read_motion_file
        from sloshkit.motion.laws import comparison_s_curve_limits, make_law

        if name.startswith("file:"):
            return typing.cast("Motion", read_motion_file(name.removeprefix("file:"), name))
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


def simulate_with_options(
    motion: Motion,
    slosh_model: SloshModel,
    model_kind: str,
    sample_period: str,
    settle_time: str | None,
    settle_tol: str,
) -> SloshResponse:
    """`sloshkit.sim.simulate.simulate` with the simulation options as the user typed them.

    Parameters
    ----------
    motion : Motion
        The container's motion.
    slosh_model : SloshModel
        The equivalent model.
    model_kind : str
        ``--model`` (one of `sloshkit.sim.simulate.MODEL_KINDS`).
    sample_period : str
        ``--sample-period`` (a time, e.g. ``"1ms"``).
    settle_time : str or None
        ``--settle-time`` (a time), or None for the default.
    settle_tol : str
        ``--settle-tol`` (an angle).

    Returns
    -------
    SloshResponse
        The simulated response.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> response = simulate_with_options(
    ...     sk.quintic(0.02, 1.0), model, "linear", "1ms", "0.5s", "0.1deg"
    ... )
    >>> round(float(response.time_s[1] - response.time_s[0]), 6)
    0.001
    >>> simulate_with_options(sk.quintic(0.02, 1.0), model, "cubic", "1ms", None, "0.1deg")
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: model = 'cubic' is invalid: must be one of linear, nonlinear
    """
    from sloshkit.sim.simulate import MODEL_KINDS, simulate

    if model_kind not in MODEL_KINDS:
        raise InputError("model", model_kind, "must be one of " + ", ".join(MODEL_KINDS))
    return simulate(
        slosh_model,
        motion,
        kind=model_kind,  # type: ignore[arg-type]
        sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
        settle_time_s=None
        if settle_time is None
        else parse_quantity(settle_time, "time", "settle_time"),
        settle_tolerance_rad=parse_quantity(settle_tol, "angle", "settle_tol"),
    )


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
#: `simulate_with_options`).
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
