"""The round trip: rebuild the container's motion from an exported file and re-simulate it.

1-D plans: the exported file's container positions (forward kinematics for joint formats,
``T_base_flange T_flange_container``, brought back into the path frame) are projected on the
plan's axis; the position samples become a motion (`sloshkit.motion.laws.from_samples`, a
quintic spline at rest at both ends) and the 1-D model is simulated
(`sloshkit.sim.simulate.simulate`, linear). The plan, interpolated on the export's grid by
its quintic Hermite polynomials (`sloshkit.export.plans.LinePlan.evaluate`), goes through
the same two steps, so the two results differ only by what the export changed. The round
trip also measures how far the rebuilt poses leave the plan's path (position and orientation),
which the 1-D model cannot see.

Pose streams (3-D plans): the rebuilt container poses and the plan, resampled to the same grid,
are both simulated with the nonlinear 3-D model (`sloshkit.sim.spatial.simulate_spatial`,
large-angle spherical pendulums, exact pose derivatives: the model the 3-D planner verifies
with) and compared on peak and residual first-mode angle and slosh height.

The comparison passes when peak and residual first-mode angle and peak and residual wall
elevation agree within `TOLERANCE` (2 %) relative to the plan's value, no slosh limit is
broken (by more than `LIMIT_TOLERANCE`, 0.1 %, the check's own resolution), and the rebuilt
container stays within `PATH_TOLERANCE_M` of the planned path and `ORIENTATION_TOLERANCE_RAD`
of the planned orientation. A residual below `RESIDUAL_FLOOR` of the plan's peak (0.1 %) is
compared against that floor instead: 2 % of a residual that is numerically zero is noise.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import ValidityWarning
from sloshkit.export.frames import invert, rotation_angle_rad
from sloshkit.export.plans import PoseStream
from sloshkit.model.modal import SloshModel
from sloshkit.plan.line.problem import SloshLimits
from sloshkit.plan.path.problem import SpatialSloshLimits
from sloshkit.sim.simulate import simulate

FloatArray = NDArray[np.float64]

#: Largest relative difference of a slosh metric between plan and export.
TOLERANCE = 0.02
#: Largest distance of the rebuilt container from the planned path [m] and largest angle
#: between rebuilt and planned orientations [rad]: far above IK round-off (1e-9), far below
#: what changes the slosh.
PATH_TOLERANCE_M = 1e-4
ORIENTATION_TOLERANCE_RAD = 1e-3
#: Residuals are compared relative to max(plan residual, this fraction of the plan's peak).
RESIDUAL_FLOOR = 1e-3
#: Relative margin over a slosh limit still counted as meeting it. The round trip rebuilds the
#: motion from position samples by a spline, while the planner's verification uses the plan's
#: exact piecewise-constant jerk; the two discretisations move the peak of a move that rides
#: its limit by about (omega * sample_period)^2 / 24 (6e-4 for 4.7 Hz at 4 ms; measured
#: 1.1e-4 on the README's 0.5 m plan). A limit exceeded by less than this is within the
#: check's own resolution, not a broken limit.
LIMIT_TOLERANCE = 1e-3

METRICS = (
    "peak_angle_deg",
    "residual_angle_deg",
    "peak_wall_elevation_m",
    "residual_wall_elevation_m",
)


@dataclass(frozen=True)
class RoundTrip:
    """Plan versus exported file: slosh metrics, their differences, path deviation, verdict.

    Attributes
    ----------
    plan_metrics, export_metrics : the four `METRICS` (degrees and metres, as named)
    relative_differences : |export - plan| / scale per metric [-]
    max_position_error_m : largest distance of a rebuilt container position from the plan's
    max_orientation_error_rad : largest angle between rebuilt and planned container orientations
    violations : broken tolerances and limits, as sentences
    method : how the slosh was simulated (1-D or 3-D model)

    Examples
    --------
    >>> metrics = {"peak_angle_deg": 2.0}
    >>> check = RoundTrip(metrics, metrics, {"peak_angle_deg": 0.0}, 1e-6, 1e-5)
    >>> check.passed, check.to_dict()["max_position_error_m"]
    (True, 1e-06)
    """

    plan_metrics: dict[str, float]
    export_metrics: dict[str, float]
    relative_differences: dict[str, float]
    max_position_error_m: float
    max_orientation_error_rad: float
    violations: tuple[str, ...] = field(default_factory=tuple)
    method: str = "1-D linear model (sloshkit.sim.simulate)"

    @property
    def passed(self) -> bool:
        """True when every metric agrees within the tolerance and no limit is broken."""
        return not self.violations

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, unit-suffixed keys."""
        return {
            "passed": self.passed,
            "method": self.method,
            "relative_tolerance": TOLERANCE,
            "plan": dict(self.plan_metrics),
            "export": dict(self.export_metrics),
            "relative_difference": dict(self.relative_differences),
            "max_position_error_m": self.max_position_error_m,
            "max_orientation_error_deg": math.degrees(self.max_orientation_error_rad),
            "violations": list(self.violations),
        }


def container_poses_in_path(container_in_base: FloatArray, base_to_path: FloatArray) -> FloatArray:
    """T_path_container = inv(T_base_path) T_base_container for (N, 4, 4) poses.

    Parameters
    ----------
    container_in_base : numpy.ndarray
        Container poses in the robot base frame (N, 4, 4).
    base_to_path : numpy.ndarray
        The path frame in the base frame (4, 4).

    Returns
    -------
    numpy.ndarray
        Container poses in the path frame (N, 4, 4).

    Examples
    --------
    >>> import numpy as np
    >>> path_frame = np.eye(4)
    >>> path_frame[:3, 3] = [0.5, 0.0, 0.2]
    >>> container = np.eye(4)[None].copy()
    >>> container[0, :3, 3] = [0.6, 0.0, 0.2]
    >>> container_poses_in_path(container, path_frame)[0, :3, 3].round(9).tolist()
    [0.1, 0.0, 0.0]
    """
    return np.asarray(invert(base_to_path)[None] @ container_in_base, dtype=float)


def line_metrics(model: SloshModel, time_s: FloatArray, position_m: FloatArray) -> dict[str, float]:
    """Peak and residual slosh of a 1-D position sample stream (linear model), simulated on
    the planner's slosh check grid (the sample period divided by
    `sloshkit.plan.line.verification.slosh_substeps`, at most 2 ms).

    Parameters
    ----------
    model : the slosh model
    time_s : uniform sample times [s]
    position_m : container positions along the move [m]

    Returns
    -------
    dict
        `METRICS` (angles in degrees, wall elevations in metres).

    References
    ----------
    `sloshkit.sim.simulate.simulate` (seed paper eq. 7 per mode, exact discretisation).

    Examples
    --------
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(101) * 0.004
    >>> s = t / t[-1]
    >>> metrics = line_metrics(model, t, 0.2 * s**3 * (10 - 15 * s + 6 * s**2))
    >>> metrics["peak_angle_deg"] > 1.0
    True
    """
    from sloshkit.motion.laws import from_samples
    from sloshkit.plan.line.verification import slosh_substeps

    motion = from_samples(time_s, position_m=position_m, name="export")
    period = float(time_s[1] - time_s[0])
    period /= slosh_substeps(period)  # the planner's slosh check grid
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate(
            motion=motion, model=model, kind="linear", sample_period_s=period, settle_time_s=0.0
        )
    return {
        "peak_angle_deg": math.degrees(response.peak_angle_rad),
        "residual_angle_deg": math.degrees(response.residual_angle_rad),
        "peak_wall_elevation_m": response.peak_wall_elevation_m,
        "residual_wall_elevation_m": response.residual_wall_elevation_m,
    }


def compare_line(
    model: SloshModel,
    plan: PoseStream,
    time_s: FloatArray,
    container_in_path: FloatArray,
    limits: SloshLimits | SpatialSloshLimits | None = None,
) -> RoundTrip:
    """Round trip of a 1-D plan: rebuilt container poses (path frame) against the plan.

    Parameters
    ----------
    model : the slosh model
    plan : the pose stream made from the 1-D plan (``plan.line`` and ``plan.axis`` set)
    time_s : times of the rebuilt poses [s] (uniform)
    container_in_path : (N, 4, 4) rebuilt container poses in the path frame
    limits : slosh limits to check on the export, if known

    Returns
    -------
    RoundTrip

    Examples
    --------
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.export.plans import LinePlan, line_to_poses
    >>> from sloshkit.export.frames import poses_to_matrices
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(101) * 0.004
    >>> s = t / t[-1]
    >>> x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> line = LinePlan(t, x, np.gradient(x, t), np.gradient(np.gradient(x, t), t))
    >>> stream = line_to_poses(line, np.array([1.0, 0.0, 0.0]))
    >>> poses = poses_to_matrices(stream.position_m, stream.quaternion_xyzw)
    >>> compare_line(model, stream, t, poses).passed
    True
    """
    line, axis = plan.line, plan.axis
    if line is None or axis is None:
        raise ValueError("compare_line needs a pose stream made from a 1-D plan")
    start = plan.position_m[0]
    offsets = container_in_path[:, :3, 3] - start
    along = offsets @ axis
    planned = start + np.outer(line.evaluate(time_s)[0] - line.position_m[0], axis)
    position_error = float(np.max(np.linalg.norm(container_in_path[:, :3, 3] - planned, axis=1)))
    upright = np.broadcast_to(np.eye(4), container_in_path.shape)
    turned = float(np.max(rotation_angle_rad(container_in_path, upright)))
    # The plan is simulated on the export's grid (its quintic Hermite interpolant there), so
    # that the comparison sees only what the export changed, not the simulation's step.
    plan_metrics = line_metrics(model, time_s, planned @ axis - start @ axis)
    export_metrics = line_metrics(model, time_s, along)
    return _verdict(plan_metrics, export_metrics, position_error, turned, limits)


SPATIAL_METRICS = (
    "peak_angle_deg",
    "residual_angle_deg",
    "peak_slosh_height_m",
    "residual_slosh_height_m",
)


def spatial_metrics(
    model: SloshModel, time_s: FloatArray, poses_in_world: FloatArray
) -> dict[str, float]:
    """Peak and residual slosh of container poses (world z up) with the 3-D model (nonlinear
    spherical pendulums, as the 3-D planner verifies its plans).

    Parameters
    ----------
    model : the slosh model
    time_s : uniform sample times [s]
    poses_in_world : (N, 4, 4) container bottom-centre poses in a frame with z up

    Returns
    -------
    dict
        `SPATIAL_METRICS` (angles in degrees, heights in metres).

    References
    ----------
    `sloshkit.sim.spatial.simulate_spatial` (large-angle spherical pendulums in the container
    frame, RK4), on exact (unsmoothed) pose derivatives.

    Examples
    --------
    The 3-D model agrees with the (linear) 1-D one on a straight, upright, small move:

    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.export.frames import poses_to_matrices
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(251) * 0.004
    >>> s = t / t[-1]
    >>> x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> position = np.column_stack((x, 0 * x, 0 * x))
    >>> poses = poses_to_matrices(position, np.tile([0, 0, 0, 1.0], (t.size, 1)))
    >>> spatial = spatial_metrics(model, t, poses)["peak_angle_deg"]
    >>> planar = line_metrics(model, t, x)["peak_angle_deg"]
    >>> bool(abs(spatial - planar) < 0.02 * planar)
    True
    """
    from sloshkit.export.frames import matrices_to_poses
    from sloshkit.motion.poses import PoseTrajectory
    from sloshkit.sim.spatial import simulate_spatial

    position, quaternion = matrices_to_poses(poses_in_world)
    poses = PoseTrajectory(np.asarray(time_s, dtype=float), position, quaternion, "export")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        response = simulate_spatial(model, poses, nonlinear=True, cutoff_hz=None)
    return {
        "peak_angle_deg": math.degrees(response.peak_angle_rad),
        "residual_angle_deg": math.degrees(response.residual_angle_rad),
        "peak_slosh_height_m": response.peak_slosh_height_m,
        "residual_slosh_height_m": response.residual_slosh_height_m,
    }


def compare_spatial(
    model: SloshModel,
    plan: PoseStream,
    time_s: FloatArray,
    container_in_path: FloatArray,
    limits: SloshLimits | SpatialSloshLimits | None = None,
) -> RoundTrip:
    """Round trip of a 3-D pose stream: rebuilt container poses (path frame, z up) against
    the plan resampled on the same grid, both simulated with the 3-D model.

    Parameters
    ----------
    model : the slosh model
    plan : the planned pose stream (path frame)
    time_s : times of the rebuilt poses [s] (uniform)
    container_in_path : (N, 4, 4) rebuilt container poses in the path frame
    limits : slosh limits to check on the export, if known

    Returns
    -------
    RoundTrip

    Examples
    --------
    Poses rebuilt exactly pass the round trip:

    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.export.frames import poses_to_matrices
    >>> from sloshkit.export.plans import PoseStream
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> t = np.arange(101) * 0.004
    >>> s = t / t[-1]
    >>> x = 0.2 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> upright = np.tile([0, 0, 0, 1.0], (101, 1))
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> plan = PoseStream(PoseTrajectory(t, np.column_stack((x, 0 * x, 0 * x)), upright))
    >>> check = compare_spatial(model, plan, t, poses_to_matrices(plan.position_m, upright))
    >>> check.passed, check.max_position_error_m
    (True, 0.0)
    """
    from sloshkit.export.frames import poses_to_matrices

    period = float(time_s[1] - time_s[0])
    planned = plan.resample(period)
    count = min(planned.time_s.size, time_s.size)
    reference = poses_to_matrices(planned.position_m, planned.quaternion_xyzw)[:count]
    rebuilt = container_in_path[:count]
    position_error = float(np.max(np.linalg.norm(rebuilt[:, :3, 3] - reference[:, :3, 3], axis=1)))
    turned = float(np.max(rotation_angle_rad(rebuilt, reference)))
    plan_metrics = spatial_metrics(model, time_s[:count], reference)
    export_metrics = spatial_metrics(model, time_s[:count], rebuilt)
    return _verdict(
        plan_metrics,
        export_metrics,
        position_error,
        turned,
        limits,
        "3-D nonlinear model (sloshkit.sim.spatial.simulate_spatial)",
    )


def limit_checks(
    limits: SloshLimits | SpatialSloshLimits | None, metrics: dict[str, float]
) -> list[tuple[str, float]]:
    """(metric, limit) pairs of the slosh limits a round trip checks, in the metrics' units
    (degrees, metres): 1-D limits on the first-mode angle, residual and wall elevation (the
    slosh height of a 3-D round trip); 3-D limits on the peak and residual slosh height and the
    surface angle.

    Parameters
    ----------
    limits : SloshLimits, SpatialSloshLimits or None
        The limits (None: nothing to check).
    metrics : dict
        The round trip's metrics (`METRICS` or `SPATIAL_METRICS`).

    Returns
    -------
    list of tuple

    Examples
    --------
    >>> from sloshkit.plan.path.problem import SpatialSloshLimits
    >>> limit_checks(SpatialSloshLimits(0.015, 0.002), {"peak_slosh_height_m": 0.0})
    [('peak_slosh_height_m', 0.015), ('residual_slosh_height_m', 0.002)]
    """
    if limits is None:
        return []
    if isinstance(limits, SpatialSloshLimits):
        checks = [
            ("peak_slosh_height_m", limits.max_height_m),
            ("residual_slosh_height_m", limits.max_residual_height_m),
        ]
        if limits.max_surface_angle_rad is not None:
            checks.append(("peak_angle_deg", math.degrees(limits.max_surface_angle_rad)))
        return checks
    checks = [
        ("peak_angle_deg", math.degrees(limits.max_angle_rad)),
        ("residual_angle_deg", math.degrees(limits.max_residual_rad)),
    ]
    if limits.max_wall_elevation_m is not None:
        height = "peak_wall_elevation_m" if "peak_wall_elevation_m" in metrics else None
        checks.append((height or "peak_slosh_height_m", limits.max_wall_elevation_m))
    return checks


def _verdict(
    plan_metrics: dict[str, float],
    export_metrics: dict[str, float],
    position_error: float,
    turned: float,
    limits: SloshLimits | SpatialSloshLimits | None,
    method: str = "1-D linear model (sloshkit.sim.simulate)",
) -> RoundTrip:
    differences: dict[str, float] = {}
    violations: list[str] = []
    for key in plan_metrics:
        planned, exported = plan_metrics[key], export_metrics[key]
        scale = abs(planned)
        if key.startswith("residual"):
            peak = plan_metrics[key.replace("residual", "peak")]
            scale = max(scale, RESIDUAL_FLOOR * abs(peak))
        difference = abs(exported - planned) / scale if scale > 0.0 else abs(exported - planned)
        differences[key] = difference
        if difference > TOLERANCE:
            violations.append(
                f"{key}: export {exported:.6g} vs plan {planned:.6g} "
                f"({100 * difference:.2f} % > {100 * TOLERANCE:g} %)"
            )
    if position_error > PATH_TOLERANCE_M:
        violations.append(
            f"the rebuilt container leaves the planned path by {1e3 * position_error:.3g} mm "
            f"(> {1e3 * PATH_TOLERANCE_M:g} mm)"
        )
    if turned > ORIENTATION_TOLERANCE_RAD:
        violations.append(
            f"the rebuilt container turns {math.degrees(turned):.3g} deg from the planned "
            f"orientation (> {math.degrees(ORIENTATION_TOLERANCE_RAD):.3g} deg)"
        )
    for key, limit in limit_checks(limits, export_metrics):
        if export_metrics[key] > limit * (1.0 + LIMIT_TOLERANCE):
            violations.append(f"{key}: export {export_metrics[key]:.6g} > limit {limit:.6g}")
    return RoundTrip(
        plan_metrics, export_metrics, differences, position_error, turned, tuple(violations), method
    )
