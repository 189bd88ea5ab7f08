"""The samples of the 3-D path program: the path parameter and the tilt on the export grid
(`PathSamples`) and the poses they describe (`sample_poses`, `export_poses`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class PathSamples:
    """Path parameter [m] and tilt rotation vector [rad] at uniform samples.

    Parameters
    ----------
    s_m : numpy.ndarray
        Path parameter s_k at the samples, (N + 1,) [m], from 0 to the path's length.
    tilt_rad : numpy.ndarray
        Tilt rotation vector (r_x, r_y) at the samples, (N + 1, 2) [rad].
    period_s : float
        Sample period h [s]: the export's.

    Examples
    --------
    >>> import numpy as np
    >>> PathSamples(np.linspace(0.0, 0.1, 11), np.zeros((11, 2)), 0.004).steps
    10
    """

    s_m: FloatArray
    tilt_rad: FloatArray
    period_s: float

    @property
    def steps(self) -> int:
        """N, the number of sample periods."""
        return int(self.s_m.size - 1)

    def perturbed(
        self, chosen: Any, column: int | None, step: float, length_m: float
    ) -> tuple[PathSamples, FloatArray]:
        """The samples with the ``chosen`` ones moved by ``step`` in s (``column`` None;
        backwards where that would leave [0, ``length_m``]) or in tilt angle ``column``, and
        each sample's signed move (1 where not moved): one colour of a coloured finite
        difference (`sloshkit.plan.path.program.PathProgram.jacobians`).

        Parameters
        ----------
        chosen : array_like of int
            The samples to move.
        column : int or None
            None for s, else the tilt angle (0 or 1).
        step : float
            The move [m or rad].
        length_m : float
            The path's length [m].

        Returns
        -------
        tuple
            The moved samples and the signed moves, (N + 1,).

        Examples
        --------
        >>> import numpy as np
        >>> samples = PathSamples(np.array([0.0, 0.05, 0.1]), np.zeros((3, 2)), 0.01)
        >>> moved, width = samples.perturbed([1, 2], None, 1e-3, 0.1)
        >>> moved.s_m.round(6).tolist(), width.round(6).tolist()
        ([0.0, 0.051, 0.099], [1.0, 0.001, -0.001])
        """
        s_moved = self.s_m.copy()
        tilt_moved = self.tilt_rad.copy()
        width = np.ones(self.s_m.size)
        if column is None:
            forward = s_moved[chosen] + step <= length_m
            s_moved[chosen] = np.where(forward, s_moved[chosen] + step, s_moved[chosen] - step)
            width[chosen] = s_moved[chosen] - self.s_m[chosen]
        else:
            tilt_moved[chosen, column] += step
            width[chosen] = step
        return PathSamples(s_moved, tilt_moved, self.period_s), width


def sample_poses(
    path: Any, samples: PathSamples, centre_height_m: float
) -> tuple[FloatArray, Rotation]:
    """Reference-point positions and container orientations of the samples.

    The tilt rotation R_t = exp([r_x, r_y, 0]) acts on the path's orientation R_p(s) about the
    tilt centre c = (0, 0, h_c) of the container frame: q = R_t R_p, P = p(s) + R_p c - q c
    (the centre stays on the path; `sloshkit.plan.path.tilt_compensation` uses the same
    convention).

    Parameters
    ----------
    path : Path
        The path (`sloshkit.plan.path.geometry.Path`).
    samples : PathSamples
        Path parameter and tilt at the samples.
    centre_height_m : float
        The tilt centre's height h_c above the reference point [m].

    Returns
    -------
    tuple
        Positions (N + 1, 3) [m] and orientations (`scipy.spatial.transform.Rotation`).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> path = path_from_waypoints([[0, 0, 0], [0.1, 0, 0]])
    >>> tilted = PathSamples(np.array([0.0, 0.05]), np.array([[0.0, 0.0], [0.0, 0.2]]), 0.004)
    >>> position, rotation = sample_poses(path, tilted, 0.05)  # tilted about 50 mm up
    >>> (position[1] + rotation[1].apply([0, 0, 0.05])).round(6).tolist()  # the centre: on
    [0.05, 0.0, 0.05]
    """
    base = path.orientation(samples.s_m)
    position = path.position(samples.s_m)
    if not np.any(samples.tilt_rad):
        return position, base
    rotvec = np.column_stack((samples.tilt_rad, np.zeros(samples.s_m.size)))
    rotation = Rotation.from_rotvec(rotvec) * base
    if centre_height_m:
        centre = np.array([0.0, 0.0, centre_height_m])
        position = position + base.apply(centre) - rotation.apply(centre)
    return position, rotation


def export_poses(problem: Any, samples: PathSamples) -> Any:
    """The samples as the export.

    Parameters
    ----------
    problem : PathProblem
        The path, its export period and tilt centre.
    samples : PathSamples
        The timing on the export grid.

    Returns
    -------
    PoseTrajectory
        The container's poses at the samples (`sloshkit.motion.poses.PoseTrajectory`, which
        makes the quaternions sign-continuous).

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.plan.path.geometry import path_from_waypoints
    >>> from sloshkit.plan.path.problem import CartesianLimits, PathProblem, SpatialSloshLimits
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
    >>> problem = PathProblem(path_from_waypoints([[0, 0, 0], [0.1, 0, 0]]),
    ...     CartesianLimits(2.0, 10.0, 100.0), SpatialSloshLimits(0.015, 0.002), model)
    >>> samples = PathSamples(np.linspace(0.0, 0.1, 6), np.zeros((6, 2)), 0.004)
    >>> poses = export_poses(problem, samples)
    >>> float(poses.duration_s), poses.position_m[-1].round(3).tolist()
    (0.02, [0.1, 0.0, 0.0])
    """
    from sloshkit.motion.poses import PoseTrajectory

    position, rotation = sample_poses(problem.path, samples, problem.tilt_centre_height_m)
    time_s = np.arange(samples.s_m.size) * problem.sample_period_s
    return PoseTrajectory(time_s, position, rotation.as_quat())


__all__ = [
    "PathSamples",
    "export_poses",
    "sample_poses",
]
