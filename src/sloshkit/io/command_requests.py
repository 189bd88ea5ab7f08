"""Requests of the command line built from its option values: the model of the model options
or of a model file, a move, the simulation, the limits of a plan, the 1-D and the 3-D plan
problems and the grid of a sweep (a calibration's record: `sloshkit.io.calibration_requests`).
The options themselves (names, help, defaults) live in `sloshkit.cli`; what they build is
written here, on `sloshkit.io.requests`."""

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
from sloshkit.io.requests import angular_rate_request, fraction_request
from sloshkit.io.units import parse_quantity, parse_range
from sloshkit.model.modal import SloshModel

FloatArray = NDArray[np.float64]

#: Default ``--max-angular-velocity`` of a 3-D plan: 180 deg/s, the joint speed limit of the
#: UR5e's wrist joints and of most 5-10 kg collaborative arms (a container turning faster needs
#: at least one joint faster than that).
DEFAULT_ANGULAR_VELOCITY = "180deg/s"
#: Default ``--max-angular-acceleration`` of a 3-D plan: 1000 deg/s^2 (that speed in 0.18 s).
DEFAULT_ANGULAR_ACCELERATION = "1000deg/s^2"

if typing.TYPE_CHECKING:  # imported where used: the simulation and planning stacks are not
    # start-up's
    from sloshkit.model.profile import Container
    from sloshkit.motion.profile import Motion
    from sloshkit.plan.line.problem import PlanProblem, SloshLimits
    from sloshkit.plan.path.geometry import Path
    from sloshkit.plan.path.problem import PathProblem
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


def slosh_limits_request(max_angle: str | None, max_residual: str | None) -> SloshLimits | None:
    """`SloshLimits` from the two options, None when neither is given.

    Parameters
    ----------
    max_angle, max_residual : str or None
        ``--max-angle`` and ``--max-residual`` (angles with units).

    Returns
    -------
    SloshLimits or None

    Examples
    --------
    >>> limits = slosh_limits_request("5deg", "0.5deg")
    >>> round(limits.max_angle_rad, 6), slosh_limits_request(None, None)
    (0.087266, None)
    """
    from sloshkit.plan.line.problem import SloshLimits

    if max_angle is None and max_residual is None:
        return None
    if max_angle is None or max_residual is None:
        raise InputError("max_angle", max_angle, "give both --max-angle and --max-residual")
    return SloshLimits(
        parse_quantity(max_angle, "angle", "max_angle"),
        parse_quantity(max_residual, "angle", "max_residual"),
    )


def line_plan_request(
    slosh_model: SloshModel,
    distance: str,
    vmax: str | None,
    amax: str | None,
    jmax: str | None,
    max_angle: str | None,
    max_residual: str | None,
    max_wall_elevation: str | None,
    robust: str,
    sample_period: str,
    max_duration: str | None,
) -> PlanProblem:
    """The 1-D plan problem of ``sloshkit plan`` (text with units in, SI out).

    Parameters
    ----------
    slosh_model : SloshModel
        The equivalent model.
    distance : str
        ``--distance``.
    vmax, amax, jmax : str or None
        The machine limits (all three required).
    max_angle, max_residual : str or None
        The slosh limits (both required).
    max_wall_elevation : str or None
        An optional limit on the wall elevation.
    robust : str
        The frequency band, e.g. ``"10%"``.
    sample_period : str
        The controller's sample period.
    max_duration : str or None
        The longest acceptable move.

    Returns
    -------
    PlanProblem

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> problem = line_plan_request(model, "0.5m", "1.5m/s", "20m/s^2", "500m/s^3", "5deg",
    ...                             "0.25deg", None, "10%", "4ms", None)
    >>> problem.distance_m, problem.slosh.robustness, problem.sample_period_s
    (0.5, 0.1, 0.004)
    >>> line_plan_request(model, "0.5m", None, None, None, "5deg", None, None, "0%", "4ms", None)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: plan = 'incomplete' is invalid: needs --vmax, --amax, --jmax, ...
    """
    from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits

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
    band = fraction_request(robust, "robust")
    return PlanProblem(
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


def path_problem_request(
    slosh_model: SloshModel,
    path: Path,
    *,
    vmax: str,
    amax: str,
    jmax: str,
    max_angular_velocity: str | None,
    max_angular_acceleration: str | None,
    max_slosh_height: str,
    max_residual_height: str,
    max_surface_angle: str | None,
    band: float,
    sample_period: str,
    max_tilt: str,
    tilt_centre: str,
) -> PathProblem:
    """The 3-D plan problem of ``sloshkit plan --path/--path-from-poses`` (text with units in,
    SI out).

    Parameters
    ----------
    slosh_model : SloshModel
        The equivalent model.
    path : Path
        The geometry (`sloshkit.plan.path.geometry`).
    vmax, amax, jmax : str
        The Cartesian limits.
    max_angular_velocity, max_angular_acceleration : str or None
        The angular limits (`sloshkit.io.requests.angular_rate_request`; None: the defaults
        `DEFAULT_ANGULAR_VELOCITY`, `DEFAULT_ANGULAR_ACCELERATION`; ``none``: no limit).
    max_slosh_height, max_residual_height : str
        The slosh-height limits.
    max_surface_angle : str or None
        An optional limit on the first mode's surface angle.
    band : float
        The frequency band as a fraction.
    sample_period : str
        The controller's sample period.
    max_tilt, tilt_centre : str
        The largest tilt and the height of the tilt's rotation centre.

    Returns
    -------
    PathProblem

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> problem = path_problem_request(None, path, vmax="2m/s", amax="10m/s^2",
    ...     jmax="100m/s^3", max_angular_velocity=None, max_angular_acceleration="none",
    ...     max_slosh_height="15mm", max_residual_height="2mm", max_surface_angle=None,
    ...     band=0.1, sample_period="4ms", max_tilt="30deg", tilt_centre="0mm")
    >>> round(problem.machine.max_angular_velocity_rad_s, 4), problem.slosh.max_height_m
    (3.1416, 0.015)
    """
    from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits

    angular_velocity = (
        DEFAULT_ANGULAR_VELOCITY if max_angular_velocity is None else max_angular_velocity
    )
    angular_acceleration = (
        DEFAULT_ANGULAR_ACCELERATION
        if max_angular_acceleration is None
        else max_angular_acceleration
    )
    return PathProblem(
        path=path,
        machine=CartesianLimits(
            parse_quantity(vmax, "velocity", "vmax"),
            parse_quantity(amax, "acceleration", "amax"),
            parse_quantity(jmax, "jerk", "jmax"),
            angular_rate_request(angular_velocity, 1, "max_angular_velocity"),
            angular_rate_request(angular_acceleration, 2, "max_angular_acceleration"),
        ),
        slosh=SpatialSloshLimits(
            parse_quantity(max_slosh_height, "length", "max_slosh_height"),
            parse_quantity(max_residual_height, "length", "max_residual_height"),
            None
            if max_surface_angle is None
            else parse_quantity(max_surface_angle, "angle", "max_surface_angle"),
            band,
        ),
        model=slosh_model,
        sample_period_s=parse_quantity(sample_period, "time", "sample_period"),
        max_tilt_rad=parse_quantity(max_tilt, "angle", "max_tilt"),
        tilt_centre_height_m=parse_quantity(tilt_centre, "length", "tilt_centre"),
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
