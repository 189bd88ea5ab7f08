"""The linear slosh screen of a sampled 3-D export, used by the searches of the path planner.

Linear screen (Abramson, NASA SP-106 (1966) ch. 6; Dodge (2000) ch. 3): each mode n is a
spherical pendulum of length L_n whose small deflection phi_n (2-vector, relative to the
container axis) obeys phi'' + 2 zeta w phi' + w^2 phi = f_lat / L_n, with f = g - a_B the
specific force at the container-fixed point B_n where the bob rests (its acceleration includes
the Euler and centripetal terms of the container's rotation), taken in the container's frame
with its spin about the own axis removed (an ideal liquid does not spin with the container).
A static tilt psi gives phi = sin(psi): the surface stays level. Wall height: |sum_n e_n phi_n|,
e_n = 2R/(xi_n^2 - 1) (the model's ``wall_elevation_factor_m``). Rotations are handled as
quaternion arrays (scalar last) in numpy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.quaternions import rotate_inverse, rotated_z_axis
from sloshkit.plan.path.forces import non_spinning_frame
from sloshkit.plan.path.problem import GRAVITY, SEARCH_MARGIN, PathProblem, second_difference

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class ScreenResult:
    """Linear-screen metrics, the worst over the band.

    Parameters
    ----------
    peak_height_m : float
        Peak slosh height at the wall [m].
    residual_height_m : float
        Bound of the residual slosh height [m].
    peak_angle_rad : float
        Peak first-mode surface angle [rad].

    Examples
    --------
    >>> ScreenResult(0.01, 0.001, 0.05).residual_height_m
    0.001
    """

    peak_height_m: float
    residual_height_m: float
    peak_angle_rad: float


def linear_screen(models: list[Any], poses: PoseTrajectory) -> ScreenResult:
    """Slosh of the sampled ``poses`` by the linear spherical-pendulum model (module docstring).

    The liquid starts in equilibrium with the first pose; the residual height is the bound
    sum_n e_n sqrt(|A_n|^2 + |B_n|^2) of the free oscillation about the last pose's equilibrium
    (A_n, B_n: the cosine and sine amplitude vectors of mode n).

    Parameters
    ----------
    models : list of SloshModel
        The models of the band (`PathProblem.models`).
    poses : PoseTrajectory
        The export.

    Returns
    -------
    ScreenResult
        The worst over the models.

    References
    ----------
    Abramson, NASA SP-106 (1966) ch. 6; Dodge, *The New "Dynamic Behavior of Liquids in
    Moving Containers"*, SwRI (2000) ch. 3.

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import (CartesianLimits, PathProblem,
    ...                                         SpatialSloshLimits, sample_path)
    >>> from sloshkit.motion.laws import s_curve
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> path = path_from_waypoints([[0, 0, 0], [0.5, 0, 0]])
    >>> poses = sample_path(path, s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> round(linear_screen([model], poses).peak_height_m * 1e3)  # [mm]
    24
    """
    peak = residual = angle = 0.0
    for wall, bound, first, _ in screen_outputs(models, poses):
        peak = max(peak, float(np.max(wall)))
        residual = max(residual, bound)
        angle = max(angle, first)
    return ScreenResult(peak, residual, angle)


def screen_outputs(
    models: list[Any], poses: PoseTrajectory
) -> list[tuple[FloatArray, float, float, FloatArray]]:
    """The linear screen's outputs per model of the band (`linear_screen` takes their worst).

    Parameters
    ----------
    models : list of SloshModel
        The models of the band (`PathProblem.models`).
    poses : PoseTrajectory
        The export.

    Returns
    -------
    list of tuple
        Per model: the wall height |sum_n e_n phi_n| at every sample [m], the residual bound
        sum_n e_n sqrt(|A_n|^2 + |B_n|^2) [m], the peak first-mode angle [rad] and the rows
        e_n (A_n, B_n) of every mode n [m] (the cosine and sine amplitude vectors of its free
        oscillation after the move, whose norms add up to the residual bound).

    References
    ----------
    Abramson, NASA SP-106 (1966) ch. 6; Dodge (2000) ch. 3 (module docstring).

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import sample_path
    >>> from sloshkit.motion.laws import s_curve
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> poses = sample_path(path_from_waypoints([[0, 0, 0], [0.5, 0, 0]]),
    ...                     s_curve(0.5, 1.0, 2.0, 20.0), 4e-3)
    >>> (wall, residual, angle, amplitudes), = screen_outputs([model], poses)
    >>> wall.shape == poses.time_s.shape, round(float(wall.max()) * 1e3), amplitudes.shape
    (True, 24, (3, 4))
    """
    from sloshkit.sim.discretisation import linear_mode_response

    ts = float(poses.time_s[1] - poses.time_s[0])
    quaternion = poses.quaternion_xyzw
    frame = non_spinning_frame(quaternion)
    axis = rotated_z_axis(quaternion)
    outputs: list[tuple[FloatArray, float, float, FloatArray]] = []
    for model in models:
        wall = np.zeros((poses.time_s.size, 2))
        bound = angle = 0.0
        amplitudes = np.zeros((len(model.modes), 4))
        for index, mode in enumerate(model.modes):
            point = poses.position_m + mode.bob_height_m * axis
            force = rotate_inverse(frame, GRAVITY - second_difference(point, ts))[:, :2]
            rest = force / (mode.length_m * mode.omega_rad_s**2)
            # Equivalent velocity w with w' = -(f - f_0): linear_mode_response solves
            # theta'' + 2 zeta w theta' + w^2 theta = -w'/L.
            excess = force - force[0]
            equivalent = -np.concatenate(
                (np.zeros((1, 2)), np.cumsum(0.5 * (excess[1:] + excess[:-1]) * ts, axis=0))
            )
            theta, rate = linear_mode_response(
                equivalent.T, ts, mode.omega_rad_s, mode.damping_ratio, mode.length_m
            )
            phi = theta.T + rest[0]
            wall += mode.wall_elevation_factor_m * phi
            if index == 0:
                angle = float(np.max(np.linalg.norm(phi, axis=1)))
            damped = mode.omega_rad_s * math.sqrt(1.0 - mode.damping_ratio**2)
            cosine = phi[-1] - rest[-1]
            sine = (rate.T[-1] + mode.damping_ratio * mode.omega_rad_s * cosine) / damped
            amplitudes[index] = mode.wall_elevation_factor_m * np.concatenate((cosine, sine))
            bound += float(np.linalg.norm(amplitudes[index]))
        outputs.append((np.linalg.norm(wall, axis=1), bound, angle, amplitudes))
    return outputs


def screen_ok(problem: PathProblem, result: ScreenResult, margin: float = SEARCH_MARGIN) -> bool:
    """True when the screen meets every slosh limit with the relative ``margin``.

    Parameters
    ----------
    problem : PathProblem
        The limits.
    result : ScreenResult
        The screen of an export.
    margin : float
        Relative margin kept from each limit.

    Returns
    -------
    bool

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import (CartesianLimits, PathProblem,
    ...                                         SpatialSloshLimits, sample_path)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> [screen_ok(problem, ScreenResult(peak, 0.001, 0.0)) for peak in (0.0099, 0.009)]
    [False, True]
    """
    slosh = problem.slosh
    keep = 1.0 - margin
    ok = result.peak_height_m <= slosh.max_height_m * keep
    ok &= result.residual_height_m <= slosh.max_residual_height_m * keep
    if slosh.max_surface_angle_rad is not None:
        ok &= result.peak_angle_rad <= slosh.max_surface_angle_rad * keep
    return bool(ok)


def binding_slosh(problem: PathProblem, result: ScreenResult) -> str:
    """The slosh limit that the screen comes closest to or exceeds most (the largest ratio to
    its limit), with its value and the limit, as failure messages name it.

    Parameters
    ----------
    problem : PathProblem
        The limits.
    result : ScreenResult
        The screen of an export.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.3, 0, 0]]),
    ...                       CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.01, 0.002),
    ...                       None)
    >>> binding_slosh(problem, ScreenResult(0.004, 0.003, 0.0))
    'residual slosh height 3 mm against its 2 mm limit'
    """
    slosh = problem.slosh
    ratios = [
        ("peak slosh height", result.peak_height_m, slosh.max_height_m, 1e3, "mm"),
        ("residual slosh height", result.residual_height_m, slosh.max_residual_height_m, 1e3, "mm"),
    ]
    if slosh.max_surface_angle_rad is not None:
        angle = (result.peak_angle_rad, slosh.max_surface_angle_rad)
        ratios.append(("peak surface angle", *angle, 180.0 / math.pi, "deg"))
    name, value, limit, scale, unit = max(ratios, key=lambda r: r[1] / r[2])
    return f"{name} {value * scale:.3g} {unit} against its {limit * scale:.3g} {unit} limit"
