"""Kinematic limits of a sampled 3-D export: peaks by finite differences, the limits they
break, the uniform slow-down that meets them, and the distance from the path.
"""

from __future__ import annotations

import math

import numpy as np

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.quaternions import conjugate, hamilton_product, rotated_z_axis, rotation_vector
from sloshkit.plan.path.geometry import Path
from sloshkit.plan.path.problem import PathProblem


def kinematics(poses: PoseTrajectory) -> dict[str, float]:
    """Peaks of the sampled export by finite differences (the ends held at rest).

    Parameters
    ----------
    poses : PoseTrajectory
        The export.

    Returns
    -------
    dict
        ``velocity`` [m/s], ``acceleration`` [m/s^2], ``jerk`` [m/s^3], ``angular_velocity``
        [rad/s], ``angular_acceleration`` [rad/s^2], ``tilt`` (from vertical) [rad].

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import (CartesianLimits, PathProblem,
    ...                                         SpatialSloshLimits, sample_path)
    >>> from sloshkit.motion.laws import s_curve
    >>> poses = sample_path(path_from_waypoints([[0, 0, 0], [0.5, 0, 0]]),
    ...                     s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> round(kinematics(poses)["acceleration"], 1), kinematics(poses)["tilt"]
    (2.0, 0.0)
    """
    ts = float(poses.time_s[1] - poses.time_s[0])
    rest = np.concatenate(
        (poses.position_m[:1],) * 2 + (poses.position_m,) + (poses.position_m[-1:],) * 2
    )
    velocity = np.diff(rest, axis=0) / ts
    acceleration = np.diff(velocity, axis=0) / ts
    jerk = np.diff(acceleration, axis=0) / ts
    quaternion = poses.quaternion_xyzw
    omega = rotation_vector(hamilton_product(quaternion[1:], conjugate(quaternion[:-1]))) / ts
    omega = np.concatenate((np.zeros((1, 3)), omega, np.zeros((1, 3))))
    alpha = np.diff(omega, axis=0) / ts
    axis = rotated_z_axis(quaternion)
    return {
        "velocity": float(np.max(np.linalg.norm(velocity, axis=1))),
        "acceleration": float(np.max(np.linalg.norm(acceleration, axis=1))),
        "jerk": float(np.max(np.linalg.norm(jerk, axis=1))),
        "angular_velocity": float(np.max(np.linalg.norm(omega, axis=1))),
        "angular_acceleration": float(np.max(np.linalg.norm(alpha, axis=1))),
        "tilt": float(np.max(np.arccos(np.clip(axis[:, 2], -1.0, 1.0)))),
    }


def machine_violations(problem: PathProblem, poses: PoseTrajectory, tilted: bool) -> list[str]:
    """Names and values of the Cartesian, angular and tilt limits the export breaks.

    Parameters
    ----------
    problem : PathProblem
        The limits.
    poses : PoseTrajectory
        The export.
    tilted : bool
        Whether the tilt limit applies.

    Returns
    -------
    list of str
        One sentence per limit broken (empty when all hold).

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import (CartesianLimits, PathProblem,
    ...                                         SpatialSloshLimits, sample_path)
    >>> from sloshkit.motion.laws import s_curve
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(2.0, 1.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), None)
    >>> machine_violations(problem, sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3), False)
    ['acceleration 2 > 1 m/s^2']
    """
    peaks = kinematics(poses)
    machine = problem.machine
    checks = [
        ("velocity", peaks["velocity"], machine.max_velocity_m_s, "m/s"),
        ("acceleration", peaks["acceleration"], machine.max_acceleration_m_s2, "m/s^2"),
        ("jerk", peaks["jerk"], machine.max_jerk_m_s3, "m/s^3"),
    ]
    if machine.max_angular_velocity_rad_s is not None:
        checks.append(
            (
                "angular velocity",
                peaks["angular_velocity"],
                machine.max_angular_velocity_rad_s,
                "rad/s",
            )
        )
    if machine.max_angular_acceleration_rad_s2 is not None:
        checks.append(
            (
                "angular acceleration",
                peaks["angular_acceleration"],
                machine.max_angular_acceleration_rad_s2,
                "rad/s^2",
            )
        )
    if tilted:
        checks.append(("tilt", peaks["tilt"], problem.max_tilt_rad, "rad"))
    return [
        f"{name} {value:.4g} > {limit:.4g} {unit}"
        for name, value, limit, unit in checks
        if value > limit * (1.0 + 1e-6)
    ]


def machine_stretch(problem: PathProblem, poses: PoseTrajectory) -> float:
    """Smallest uniform stretch in time c >= 1 after which the export meets the Cartesian and
    angular limits (speeds scale as 1/c, accelerations 1/c^2, jerks 1/c^3).

    Parameters
    ----------
    problem : PathProblem
        The limits.
    poses : PoseTrajectory
        The export.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import (CartesianLimits, PathProblem,
    ...                                         SpatialSloshLimits, sample_path)
    >>> from sloshkit.motion.laws import s_curve
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> problem = PathProblem(path, CartesianLimits(0.5, 10.0, 100.0),
    ...                       SpatialSloshLimits(0.01, 0.002), None)
    >>> poses = sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> speed = kinematics(poses)["velocity"]  # 0.9 m/s against 0.5 m/s
    >>> bool(np.isclose(machine_stretch(problem, poses), speed / 0.5))
    True
    """
    peaks = kinematics(poses)
    machine = problem.machine
    needs = [
        peaks["velocity"] / machine.max_velocity_m_s,
        math.sqrt(peaks["acceleration"] / machine.max_acceleration_m_s2),
        (peaks["jerk"] / machine.max_jerk_m_s3) ** (1.0 / 3.0),
    ]
    if machine.max_angular_velocity_rad_s is not None:
        needs.append(peaks["angular_velocity"] / machine.max_angular_velocity_rad_s)
    if machine.max_angular_acceleration_rad_s2 is not None:
        needs.append(
            math.sqrt(peaks["angular_acceleration"] / machine.max_angular_acceleration_rad_s2)
        )
    return float(max(1.0, *needs))


def path_deviation(path: Path, poses: PoseTrajectory) -> float:
    """Largest distance [m] of the exported positions from the path (`Path.distance_to`).

    Parameters
    ----------
    path : Path
        The geometry.
    poses : PoseTrajectory
        The export.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import (CartesianLimits, PathProblem,
    ...                                         SpatialSloshLimits, sample_path)
    >>> path = path_from_waypoints([[0, 0, 0], [0.3, 0, 0]])
    >>> poses = PoseTrajectory(np.arange(2) * 0.1, np.array([[0.1, 0.002, 0], [0.3, 0, 0]]),
    ...                        np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)))
    >>> round(path_deviation(path, poses), 6)
    0.002
    """
    return float(np.max(path.distance_to(poses.position_m)))
