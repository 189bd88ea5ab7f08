"""Requests of the command line built from its option values: the model of the model options
or of a model file, a move, the simulation and the grid of a sweep (the slosh limits and the
1-D and 3-D plan problems: `sloshkit.io.plan_requests`; a calibration's record:
`sloshkit.io.calibration_requests`). The options themselves (names, help, defaults) live in
`sloshkit.cli`; what they build is written here, on `sloshkit.io.requests` and
`sloshkit.io.model_options`."""

from __future__ import annotations

import typing
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.io.model_options import check_bare_length, options_model_request
from sloshkit.io.models import read_model_file
from sloshkit.io.plan_requests import (  # still importable from here (docs/migration.md)
    DEFAULT_ANGULAR_ACCELERATION,
    DEFAULT_ANGULAR_VELOCITY,
    path_problem_request,
)
from sloshkit.io.units import parse_quantity, parse_range
from sloshkit.model.modal import SloshModel

FloatArray = NDArray[np.float64]

if typing.TYPE_CHECKING:  # imported where used: the simulation and planning stacks are not
    # start-up's
    from sloshkit.model.profile import Container
    from sloshkit.motion.profile import Motion
    from sloshkit.sim.response import SloshResponse


def model_or_file_request(values: dict[str, Any], defaults: Mapping[str, Any]) -> SloshModel:
    """The model of the model options, or of ``model_file`` when it is given (then every other
    model option must keep its default).

    Parameters
    ----------
    values : dict
        Option name -> value: the arguments of `options_model_request` and ``model_file``.
    defaults : mapping
        Option name -> default, to tell which options were given.

    Returns
    -------
    SloshModel

    Examples
    --------
    >>> defaults = {"radius": "20.5mm", "model_file": None}
    >>> model_or_file_request({"radius": "8mm", "model_file": "vial.toml"}, defaults)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: model_file = 'vial.toml' is invalid: replaces the model ...
    """
    values = dict(values)
    model_file = values.pop("model_file")
    if model_file is not None:
        given = [
            "--" + name.replace("_", "-")
            for name, value in values.items()
            if value != defaults[name]
        ]
        if given:
            raise InputError(
                "model_file",
                str(model_file),
                "replaces the model options; drop " + ", ".join(given) + " or the model file",
            )
        return typing.cast(SloshModel, read_model_file(model_file))
    return options_model_request(**values)


def cylinder_model_or_file_request(
    values: dict[str, Any], defaults: Mapping[str, Any]
) -> SloshModel:
    """`model_or_file_request` for an upright cylinder only (CFD): a ``container`` or
    ``profile`` is refused before any model is built.

    Parameters
    ----------
    values : dict
        Option name -> value, as for `model_or_file_request`.
    defaults : mapping
        Option name -> default.

    Returns
    -------
    SloshModel

    Examples
    --------
    >>> cylinder_model_or_file_request({"container": "iso8362-2R", "profile": None}, {})
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: container = 'iso8362-2R' is invalid: CFD meshes upright ...
    """
    for name in ("container", "profile"):
        if values[name] is not None:
            raise InputError(
                name,
                str(values[name]),
                "CFD meshes upright cylinders only (give --radius and --wall-height); a "
                "container given by its profile is modelled by finite elements, not by CFD",
            )
    return model_or_file_request(values, defaults)


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


def sweep_grid_request(
    container: Container,
    fill_height: str | None,
    fill_volume: str | None,
    duration: str | None,
    peak_acceleration: str | None,
    *,
    real: bool = False,
) -> tuple[FloatArray, FloatArray | None, FloatArray | None]:
    """The grid of ``sloshkit sweep``: fill heights (from a height or a volume range) and move
    durations or peak accelerations, each range ``START:STOP:COUNT`` with both ends included.

    Parameters
    ----------
    container : UprightCylinder or ProfileContainer
        The container (volumes become heights through its profile).
    fill_height, fill_volume : str or None
        ``--fill-height`` or ``--fill-volume`` (default 39 mm; a real container needs one).
    duration, peak_acceleration : str or None
        ``--duration`` (default 0.5 s to 3 s, 200 values) or ``--peak-acceleration``.
    real : bool
        The container was given by ``--container`` or ``--profile``.

    Returns
    -------
    tuple
        Fill heights [m], durations [s] or None, peak accelerations [m/s^2] or None.

    Examples
    --------
    >>> from sloshkit.io.requests import container_request
    >>> heights, durations, accelerations = sweep_grid_request(
    ...     container_request("20mm"), "10mm:60mm:6", None, None, "1m/s^2:2m/s^2:3")
    >>> heights.round(3).tolist(), durations, accelerations.tolist()
    ([0.01, 0.02, 0.03, 0.04, 0.05, 0.06], None, [1.0, 1.5, 2.0])
    """
    from sloshkit.sweep import linspace_inclusive  # the sweep stack: not start-up's

    if real and fill_height is None and fill_volume is None:
        raise InputError("fill_volume", None, "give a --fill-volume or --fill-height range")
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
    return heights, durations, accelerations


__all__ = [
    "DEFAULT_ANGULAR_ACCELERATION",
    "DEFAULT_ANGULAR_VELOCITY",
    "MoveRequest",
    "cylinder_model_or_file_request",
    "model_or_file_request",
    "path_problem_request",
    "simulate_with_options",
    "sweep_grid_request",
]
