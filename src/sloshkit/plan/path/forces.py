"""The drive of the path program's pendulums: the specific force at each mode's hinge in the
container's non-spinning frame N, with the kinematics the limits see, for a batch of sample
sets at once (`specific_forces`; `sloshkit.plan.path.program.PathProgram.forces` is one set,
its `jacobians` the perturbed sets of one program).

Batched because the program's banded derivatives evaluate ten perturbed copies of the same
samples per program (`PathProgram.jacobians`), and at a few hundred samples each evaluation
is dominated by the fixed cost of the rotation calls, not by the samples.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.motion.quaternions import (
    conjugate,
    hamilton_product,
    rotate_inverse,
    rotated_z_axis,
    rotation_vector,
)
from sloshkit.plan.path.samples import PathSamples, sample_poses

FloatArray = NDArray[np.float64]


def held(values: FloatArray, pad: int, axis: int = 0) -> FloatArray:
    """``values`` with ``pad`` copies of the first and last samples along ``axis`` (at rest
    before and after the move, as the export's kinematics are differenced).

    Parameters
    ----------
    values : numpy.ndarray
        Samples along ``axis``.
    pad : int
        Copies at each end.
    axis : int
        The samples' axis (1 for a batch of sample sets).

    Returns
    -------
    numpy.ndarray

    Examples
    --------
    >>> import numpy as np
    >>> held(np.array([1.0, 2.0, 3.0]), 2).tolist()
    [1.0, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0]
    """
    first = np.take(values, [0], axis=axis)
    last = np.take(values, [-1], axis=axis)
    return np.concatenate((first,) * pad + (values,) + (last,) * pad, axis=axis)


def spin_angles(quaternion_xyzw: FloatArray) -> FloatArray:
    """The container's spin about its own axis at sampled poses: the sum of the body-frame
    rotation increments' axial components from the first sample (`non_spinning_frame`).

    Parameters
    ----------
    quaternion_xyzw : numpy.ndarray
        Container-to-world unit quaternions at the samples, (..., N + 1, 4), scalar last.

    Returns
    -------
    numpy.ndarray
        The spin at each sample, (..., N + 1) [rad], zero at the first.

    Examples
    --------
    >>> import numpy as np
    >>> yaw = np.linspace(0.0, np.pi / 2, 5)  # a turn about the container's own axis
    >>> q = np.stack([0 * yaw, 0 * yaw, np.sin(yaw / 2), np.cos(yaw / 2)], axis=-1)
    >>> spin_angles(q).round(6).tolist()
    [0.0, 0.392699, 0.785398, 1.178097, 1.570796]
    """
    quaternion = np.asarray(quaternion_xyzw, dtype=float)
    body = rotation_vector(
        hamilton_product(conjugate(quaternion[..., :-1, :]), quaternion[..., 1:, :])
    )
    start = np.zeros((*quaternion.shape[:-2], 1))
    return np.concatenate((start, np.cumsum(body[..., 2], axis=-1)), axis=-1)


def turned_about_axis(force: FloatArray, rates: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The derivatives of the forces and N's lateral rates (`specific_forces`) in N when N
    turns about its own axis: a turn by d turns every vector in N by -d, so d f / d spin =
    e_z x f, and the rates' pairs (p, q) the same way.

    Parameters
    ----------
    force : numpy.ndarray
        Forces (..., 3) in N [m/s^2].
    rates : numpy.ndarray
        N's lateral angular velocity and its derivative (..., 4).

    Returns
    -------
    tuple of numpy.ndarray
        d force / d spin and d rates / d spin, shaped as the inputs.

    Examples
    --------
    >>> import numpy as np
    >>> f, r = turned_about_axis(np.array([1.0, 0.0, -9.81]), np.array([0.0, 2.0, 1.0, 0.0]))
    >>> f.tolist(), r.tolist()
    ([-0.0, 1.0, 0.0], [-2.0, 0.0, -0.0, 1.0])
    """
    turned_force = np.zeros(force.shape)
    turned_force[..., 0], turned_force[..., 1] = -force[..., 1], force[..., 0]
    turned_rates = np.zeros(rates.shape)
    turned_rates[..., 0], turned_rates[..., 1] = -rates[..., 1], rates[..., 0]
    turned_rates[..., 2], turned_rates[..., 3] = -rates[..., 3], rates[..., 2]
    return turned_force, turned_rates


def non_spinning_frame(
    quaternion_xyzw: FloatArray, spin_rad: FloatArray | None = None
) -> FloatArray:
    """The container's non-spinning frame N at sampled poses: the container frame turned back
    about its own axis by its spin, the sum of the body-frame rotation increments' axial
    components from the first sample (N's convention: `sloshkit.sim.spatial_drive`, there
    integrated from the continuous body rate).

    Parameters
    ----------
    quaternion_xyzw : numpy.ndarray
        Container-to-world unit quaternions at the samples, (..., N + 1, 4), scalar last.
    spin_rad : numpy.ndarray, optional
        Their spin (`spin_angles`), when already computed.

    Returns
    -------
    numpy.ndarray
        N-to-world unit quaternions, (..., N + 1, 4).

    Examples
    --------
    >>> import numpy as np
    >>> yaw = np.linspace(0.0, np.pi / 2, 5)  # a pure turn about the vertical axis
    >>> q = np.stack([0 * yaw, 0 * yaw, np.sin(yaw / 2), np.cos(yaw / 2)], axis=-1)
    >>> np.abs(non_spinning_frame(q)).round(12).tolist()[-1]  # N does not turn
    [0.0, 0.0, 0.0, 1.0]
    """
    quaternion = np.asarray(quaternion_xyzw, dtype=float)
    spin = spin_angles(quaternion) if spin_rad is None else spin_rad
    unspin = np.zeros(quaternion.shape)
    unspin[..., 2], unspin[..., 3] = -np.sin(0.5 * spin), np.cos(0.5 * spin)
    return hamilton_product(quaternion, unspin)


def specific_forces(
    path: Any,
    modes: Any,
    gravity: FloatArray,
    s_m: FloatArray,
    tilt_rad: FloatArray,
    period_s: float,
    centre_height_m: float,
) -> tuple[FloatArray, dict[str, FloatArray]]:
    """Specific force g - a_hinge at each mode's hinge in N, and g itself in N, for a batch of
    sample sets, with the kinematics by finite differences of the samples held at rest before
    and after (as `sloshkit.plan.path.limits.kinematics` measures them).

    N is the container frame with its spin about its own axis removed (the spin integrated
    from the body-frame increments), as `sloshkit.sim.spatial_drive` defines it; the hinge
    of mode n sits ``pivot_height_m`` up the container's axis from the reference point
    (Dodge, SwRI (2000) ch. 3: the pendulum analogy).

    Parameters
    ----------
    path : Path
        The geometry.
    modes : sequence of SloshMode
        One band model's modes (their hinge heights).
    gravity : numpy.ndarray
        Gravity (3,) [m/s^2].
    s_m : numpy.ndarray
        Path parameter of each set, (batch, N + 1) [m].
    tilt_rad : numpy.ndarray
        Tilt rotation vectors, (batch, N + 1, 2) [rad].
    period_s : float
        Sample period [s].
    centre_height_m : float
        The tilt centre's height above the reference point [m].

    Returns
    -------
    tuple
        The forces (batch, modes + 1, N + 1, 3) [m/s^2] (gravity last) and the kinematics:
        ``tilt_rates`` (batch, N + 1, 4: N's lateral angular velocity and its derivative),
        ``velocity``, ``acceleration``, ``jerk`` (batch, N + 4, N + 3, N + 2 rows, 3),
        ``omega`` (batch, N + 2, 3), ``alpha`` (batch, N + 1, 3), ``position``
        (batch, N + 1, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> path = path_from_waypoints([[0, 0, 0], [0.1, 0, 0]])
    >>> s = np.array([[0.0, 0.0, 0.0, 0.0]])  # at rest: the force is gravity
    >>> force, _ = specific_forces(path, model.modes, np.array([0, 0, -9.81]), s,
    ...                            np.zeros((1, 4, 2)), 0.01, 0.0)
    >>> force.shape, force[0, 0, 0].round(6).tolist()
    ((1, 4, 4, 3), [0.0, 0.0, -9.81])
    """
    batch, count = s_m.shape
    flat = PathSamples(s_m.reshape(-1), tilt_rad.reshape(-1, 2), period_s)
    position_flat, rotation_flat = sample_poses(path, flat, centre_height_m)
    position = position_flat.reshape(batch, count, 3)
    quaternion = rotation_flat.as_quat().reshape(batch, count, 4)
    padded = held(position, 2, axis=1)
    velocity = np.diff(padded, axis=1) / period_s
    acceleration = np.diff(velocity, axis=1) / period_s
    jerk = np.diff(acceleration, axis=1) / period_s
    later, earlier = quaternion[:, 1:], quaternion[:, :-1]
    rest = np.zeros((batch, 1, 3))
    increments = rotation_vector(hamilton_product(later, conjugate(earlier)))
    omega = np.concatenate((rest, increments / period_s, rest), axis=1)
    alpha = np.diff(omega, axis=1) / period_s
    spin = spin_angles(quaternion)
    frame_quaternion = non_spinning_frame(quaternion, spin)
    axis = rotated_z_axis(quaternion)
    force = np.empty((batch, len(modes) + 1, count, 3))
    for index, mode in enumerate(modes):
        point = held(position + mode.pivot_height_m * axis, 1, axis=1)
        hinge = (point[:, 2:] - 2.0 * point[:, 1:-1] + point[:, :-2]) / period_s**2
        force[:, index] = rotate_inverse(frame_quaternion, gravity - hinge)
    force[:, -1] = rotate_inverse(frame_quaternion, np.broadcast_to(gravity, (batch, count, 3)))
    # the lateral angular velocity (p, q) of N in N and its derivative at the samples: the
    # increments of N over each period (zero before and after: at rest), averaged and
    # differenced about each sample
    turn = rotation_vector(
        hamilton_product(conjugate(frame_quaternion[:, :-1]), frame_quaternion[:, 1:])
    )
    turn = turn[:, :, :2] / period_s
    still = np.zeros((batch, 1, 2))
    turn = np.concatenate((still, turn, still), axis=1)
    kinematic_rates = np.concatenate(
        (0.5 * (turn[:, 1:] + turn[:, :-1]), np.diff(turn, axis=1) / period_s), axis=2
    )
    kinematic = {
        "tilt_rates": kinematic_rates,
        "velocity": velocity,
        "acceleration": acceleration,
        "jerk": jerk,
        "omega": omega,
        "alpha": alpha,
        "position": position,
        "spin": spin,
    }
    return force, kinematic


__all__ = ["held", "non_spinning_frame", "specific_forces", "spin_angles", "turned_about_axis"]
