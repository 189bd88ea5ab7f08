"""Requests of the command line's planning options, built from their values (text with units
in, SI out): the slosh limits that ``sloshkit export`` may override, the 1-D plan problem of
``sloshkit plan`` and the 3-D plan problem of ``sloshkit plan --path`` or
``--path-from-poses``, with the 3-D plan's default angular limits. The options themselves
(names, help) live in `sloshkit.cli`; what they build is written here, on
`sloshkit.io.requests`. The planning stacks are imported where they are used: they are not the
command line's start-up.
"""

from __future__ import annotations

import typing

from sloshkit.errors import InputError
from sloshkit.io.requests import angular_rate_request, fraction_request
from sloshkit.io.units import parse_quantity

#: Default ``--max-angular-velocity`` of a 3-D plan: 180 deg/s, the joint speed limit of the
#: UR5e's wrist joints and of most 5-10 kg collaborative arms (a container turning faster needs
#: at least one joint faster than that).
DEFAULT_ANGULAR_VELOCITY = "180deg/s"
#: Default ``--max-angular-acceleration`` of a 3-D plan: 1000 deg/s^2 (that speed in 0.18 s).
DEFAULT_ANGULAR_ACCELERATION = "1000deg/s^2"

if typing.TYPE_CHECKING:
    from sloshkit.model.modal import SloshModel
    from sloshkit.plan.line.problem import PlanProblem, SloshLimits
    from sloshkit.plan.path.geometry import Path
    from sloshkit.plan.path.problem import PathProblem


def require_options(options: typing.Sequence[tuple[str, object]]) -> None:
    """Fail with one error naming every option a plan needs that was not given.

    Parameters
    ----------
    options : sequence of (str, object)
        Each option's name on the command line and its value (None: not given).

    Raises
    ------
    InputError
        ``plan = 'incomplete'``, naming the missing options.

    Examples
    --------
    >>> require_options([("--vmax", "1m/s"), ("--amax", None), ("--jmax", None)])
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: plan = 'incomplete' is invalid: needs --amax, --jmax
    """
    missing = [name for name, value in options if value is None]
    if missing:
        raise InputError("plan", "incomplete", "needs " + ", ".join(missing))


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

    require_options(
        [
            ("--vmax", vmax),
            ("--amax", amax),
            ("--jmax", jmax),
            ("--max-angle", max_angle),
            ("--max-residual", max_residual),
        ]
    )
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
