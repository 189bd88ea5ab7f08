"""Rigid-body pose trajectories of a container: time, position and orientation.

A `PoseTrajectory` holds sampled poses of the container's **bottom centre** in a world frame
with z up (gravity along -z): positions [m] and unit quaternions rotating container
coordinates into world coordinates, scalar last (the ``x, y, z, w`` order of
`scipy.spatial.transform.Rotation.from_quat`). The container axis is its local z axis.

The container is assumed at rest before the first and after the last pose (rest-to-rest, as
for every 1-D law). Kinematics (velocity, accelerations, angular velocity and acceleration)
come from `PoseTrajectory.kinematics`, see `sloshkit.motion.pose_kinematics`.

`PoseTrajectory` is the one type of sampled poses: pose files read into it
(`sloshkit.io.poses`), the 3-D simulation takes it (`sloshkit.sim.spatial`), the 3-D planner
exports it (`sloshkit.plan.path.problem.sample_path`), and the export's 3-D plan
(`sloshkit.export.plans.PoseStream`) holds one with the exported files' metadata beside it.
`sloshkit.motion.pose_kinematics.PoseKinematics` is not a second container of the poses but
their time derivatives on a uniform grid, computed from a `PoseTrajectory`.

References
----------
- J. Diebel, "Representing attitude: Euler angles, unit quaternions, and rotation vectors",
  Stanford University (2006), §5-6 (quaternion conventions and kinematics).
- B. Siciliano et al., *Robotics: Modelling, Planning and Control*, Springer (2009), §2.4
  (roll-pitch-yaw angles), §3.6 (tool frames).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import make_interp_spline
from scipy.spatial.transform import Rotation, RotationSpline

from sloshkit.budget import require_samples
from sloshkit.errors import InputError, require_increasing, require_positive
from sloshkit.motion.pose_kinematics import DEFAULT_CUTOFF_HZ, PoseKinematics, pose_kinematics
from sloshkit.motion.quaternions import sign_continuous
from sloshkit.motion.sampling import steps_to_reach

FloatArray = NDArray[np.float64]

#: Quaternions whose norm differs from 1 by more than this are rejected (not renormalised).
QUATERNION_NORM_TOLERANCE = 1e-3
#: The columns of a pose file, in order: time [s], bottom centre [m], quaternion (scalar last).
POSE_COLUMNS: tuple[str, ...] = ("t", "x", "y", "z", "qx", "qy", "qz", "qw")


@dataclass(frozen=True, eq=False)
class PoseTrajectory:
    """Sampled poses of a container's bottom centre (world frame, z up).

    Parameters
    ----------
    time_s : sample times, shape (N,), strictly increasing [s]
    position_m : bottom-centre positions in the world frame, shape (N, 3) [m]
    quaternion_xyzw : orientation, container -> world, scalar last, shape (N, 4). Normalised
        on construction (norms must be within 1e-3 of 1) and made sign-continuous
        (q and -q are the same rotation; neighbours are flipped so that q_k . q_{k+1} >= 0).
    name : a label for reports

    Examples
    --------
    >>> import numpy as np
    >>> poses = PoseTrajectory(np.array([0.0, 1.0]), np.zeros((2, 3)),
    ...                        np.array([[0, 0, 0, 1.0], [0, 0, 0, -1.0]]))
    >>> poses.quaternion_xyzw[1].tolist()
    [-0.0, -0.0, -0.0, 1.0]
    """

    time_s: FloatArray
    position_m: FloatArray
    quaternion_xyzw: FloatArray
    name: str = ""

    def __post_init__(self) -> None:
        time = np.asarray(self.time_s, dtype=float).reshape(-1)
        position = np.asarray(self.position_m, dtype=float)
        quaternion = np.asarray(self.quaternion_xyzw, dtype=float)
        count = time.size
        if count < 2:
            raise InputError("poses", count, "need at least 2 samples")
        if position.shape != (count, 3):
            raise InputError("position", position.shape, f"must have shape ({count}, 3)")
        if quaternion.shape != (count, 4):
            raise InputError("quaternion", quaternion.shape, f"must have shape ({count}, 4)")
        for label, values in (("time", time), ("position", position), ("quaternion", quaternion)):
            if not np.all(np.isfinite(values)):
                row = int(np.argmax((~np.isfinite(values.reshape(count, -1))).any(axis=1)))
                raise InputError(label, f"non-finite value at sample {row}", "must be finite")
        require_increasing("time", time)
        norm = np.linalg.norm(quaternion, axis=1)
        bad = np.abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE
        if np.any(bad):
            row = int(np.argmax(bad))
            raise InputError(
                "quaternion",
                f"norm {norm[row]:.6g} at sample {row}",
                f"must be a unit quaternion (|q| within {QUATERNION_NORM_TOLERANCE:g} of 1)",
            )
        quaternion = sign_continuous(quaternion / norm[:, None])
        object.__setattr__(self, "time_s", time)
        object.__setattr__(self, "position_m", position)
        object.__setattr__(self, "quaternion_xyzw", quaternion)

    # -- basic properties -------------------------------------------------------------------

    @property
    def start_s(self) -> float:
        """Time of the first pose [s]."""
        return float(self.time_s[0])

    @property
    def end_s(self) -> float:
        """Time of the last pose [s]."""
        return float(self.time_s[-1])

    @property
    def duration_s(self) -> float:
        """Time from the first to the last pose [s]."""
        return self.end_s - self.start_s

    @cached_property
    def sample_period_s(self) -> float:
        """Median step between poses [s]."""
        return float(np.median(np.diff(self.time_s)))

    @cached_property
    def is_uniform(self) -> bool:
        """True when every step equals the median step within 1e-6 relative."""
        steps = np.diff(self.time_s)
        return bool(np.all(np.abs(steps - self.sample_period_s) <= 1e-6 * self.sample_period_s))

    @property
    def rotation(self) -> Rotation:
        """Orientations as one `scipy.spatial.transform.Rotation` (container -> world)."""
        return Rotation.from_quat(self.quaternion_xyzw)

    def columns(self) -> dict[str, FloatArray]:
        """The `POSE_COLUMNS` of a pose file, ``t,x,y,z,qx,qy,qz,qw`` (SI; `sloshkit.io.poses`).

        Examples
        --------
        >>> import numpy as np
        >>> upright = np.tile([0, 0, 0, 1.0], (2, 1))
        >>> poses = PoseTrajectory(np.array([0.0, 0.1]), np.zeros((2, 3)), upright)
        >>> list(poses.columns()), poses.columns()["qw"].tolist()
        (['t', 'x', 'y', 'z', 'qx', 'qy', 'qz', 'qw'], [1.0, 1.0])
        """
        position = dict(zip(POSE_COLUMNS[1:4], self.position_m.T, strict=True))
        quaternion = dict(zip(POSE_COLUMNS[4:], self.quaternion_xyzw.T, strict=True))
        return {POSE_COLUMNS[0]: self.time_s, **position, **quaternion}

    @property
    def axis_world(self) -> FloatArray:
        """Container axis (local z) in world coordinates, shape (N, 3)."""
        return np.asarray(self.rotation.apply([0.0, 0.0, 1.0]), dtype=float)

    @property
    def tilt_rad(self) -> FloatArray:
        """Angle between the container axis and the world vertical, shape (N,) [rad]."""
        x, y = self.quaternion_xyzw[:, 0], self.quaternion_xyzw[:, 1]
        return np.arccos(np.clip(1.0 - 2.0 * (x * x + y * y), -1.0, 1.0))  # R_zz

    # -- transformations --------------------------------------------------------------------

    def with_tool_offset(self, offset_m: ArrayLike) -> PoseTrajectory:
        """Poses of the point at ``offset_m`` in the pose's own frame (same orientation).

        Use it when a file gives the flange or another tool point: ``offset_m`` is the
        container's bottom centre in that frame, so p_bottom = p + R(q) offset (Siciliano et
        al. 2009 §3.6). The container axis must be the frame's z axis.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> q = Rotation.from_euler("x", 90, degrees=True).as_quat()
        >>> poses = PoseTrajectory(np.array([0.0, 1.0]), np.zeros((2, 3)), np.tile(q, (2, 1)))
        >>> np.round(poses.with_tool_offset([0, 0, 0.1]).position_m[0], 6).tolist()
        [0.0, -0.1, 0.0]
        """
        offset = np.asarray(offset_m, dtype=float).reshape(-1)
        if offset.shape != (3,) or not np.all(np.isfinite(offset)):
            raise InputError("tool_offset", offset_m, "must be three finite numbers X,Y,Z [m]")
        position = self.position_m + self.rotation.apply(offset)
        return PoseTrajectory(self.time_s, position, self.quaternion_xyzw, self.name)

    def in_world_frame(self, rotation: Rotation, translation_m: ArrayLike = (0.0, 0.0, 0.0)) -> Any:
        """The same motion written in another world frame: p' = Q p + t, q' = Q q.

        ``rotation`` must keep z up (a rotation about the vertical) for the physics to be the
        same; used to check frame invariance.
        """
        shift = np.asarray(translation_m, dtype=float).reshape(3)
        position = rotation.apply(self.position_m) + shift
        quaternion = (rotation * self.rotation).as_quat()
        return PoseTrajectory(self.time_s, position, quaternion, self.name)

    def resample(self, sample_period_s: float, end_s: float | None = None) -> PoseTrajectory:
        """Poses on the uniform grid t_0 + k dt, up to ``end_s`` (default: the last pose).

        Positions by a cubic interpolating spline (not-a-knot), orientations by
        `scipy.spatial.transform.RotationSpline` (C2 cubic in rotation vectors; Diebel 2006
        §6). Beyond the last pose the final pose is held (rest).

        Examples
        --------
        >>> from sloshkit.motion.laws import quintic
        >>> from sloshkit.motion.pose_builders import poses_from_law
        >>> poses = poses_from_law(quintic(0.2, 1.0), sample_period_s=0.01)
        >>> poses.resample(0.05).time_s.size
        21
        """
        dt = require_positive("sample_period", sample_period_s, "s")
        stop = self.end_s if end_s is None else float(end_s)
        samples = (stop - self.start_s) / dt + 1.0
        require_samples("poses", f"{stop - self.start_s:.4g} s at {dt:.3g} s steps", samples, 16)
        count = math.floor(samples - 1.0 + 1e-9) + 1
        times = self.start_s + np.arange(count, dtype=float) * dt
        return PoseTrajectory(times, *self.sample(times), name=self.name)

    def sample(self, time_s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Interpolated (position (M, 3), quaternion (M, 4)) at ``time_s``; held outside."""
        times = np.asarray(time_s, dtype=float).reshape(-1)
        clipped = np.clip(times, self.start_s, self.end_s)
        if self.time_s.size >= 4:
            spline = make_interp_spline(self.time_s, self.position_m, k=3, axis=0)
            position = np.asarray(spline(clipped), dtype=float)
        else:
            position = np.column_stack(
                [np.interp(clipped, self.time_s, self.position_m[:, i]) for i in range(3)]
            )
        rotation_spline = RotationSpline(self.time_s, self.rotation)
        quaternion = np.asarray(rotation_spline(clipped).as_quat(), dtype=float)
        return position, sign_continuous(quaternion)

    def extended(self, settle_time_s: float, sample_period_s: float | None = None) -> Any:
        """Copy with the final pose held for ``settle_time_s`` more (the container rests)."""
        settle = float(settle_time_s)
        if settle <= 0.0:
            return self
        dt = self.sample_period_s if sample_period_s is None else float(sample_period_s)
        extra = self.end_s + np.arange(1, steps_to_reach(settle, dt) + 1) * dt
        times = np.concatenate((self.time_s, extra))
        position = np.vstack((self.position_m, np.repeat(self.position_m[-1:], extra.size, 0)))
        quaternion = np.vstack(
            (self.quaternion_xyzw, np.repeat(self.quaternion_xyzw[-1:], extra.size, 0))
        )
        return PoseTrajectory(times, position, quaternion, self.name)

    def kinematics(
        self,
        sample_period_s: float | None = None,
        *,
        cutoff_hz: float | None = DEFAULT_CUTOFF_HZ,
    ) -> PoseKinematics:
        """Velocity, accelerations, angular velocity and acceleration on a uniform grid.

        See `sloshkit.motion.pose_kinematics.pose_kinematics`: Savitzky-Golay differentiation
        with the stated cut-off [Hz], or an interpolating spline with ``cutoff_hz=None``.
        """
        return pose_kinematics(self, sample_period_s, cutoff_hz=cutoff_hz)


# ---------------------------------------------------------------------------------------------
# Constructors
# ---------------------------------------------------------------------------------------------


def poses_from_rpy(
    time_s: ArrayLike,
    position_m: ArrayLike,
    roll_rad: ArrayLike,
    pitch_rad: ArrayLike,
    yaw_rad: ArrayLike,
    name: str = "",
) -> PoseTrajectory:
    """Poses from roll, pitch and yaw angles: R = Rz(yaw) Ry(pitch) Rx(roll).

    Fixed-axis (extrinsic x, then y, then z) roll-pitch-yaw as in Siciliano et al. (2009)
    §2.4.4; scipy's ``Rotation.from_euler("xyz", ...)`` with lower-case (extrinsic) axes.

    Parameters
    ----------
    time_s : array_like
        Time stamps (M,) [s].
    position_m : array_like
        Bottom-centre positions (M, 3) [m].
    roll_rad, pitch_rad, yaw_rad : array_like
        Angles (M,) [rad].
    name : str
        Name of the trajectory.

    Returns
    -------
    PoseTrajectory

    Examples
    --------
    >>> import numpy as np
    >>> poses = poses_from_rpy([0.0, 1.0], np.zeros((2, 3)), [0.0, 0.1], [0.0, 0.0], [0.0, 0.0])
    >>> round(float(poses.tilt_rad[1]), 6)
    0.1
    """
    angles = np.column_stack(
        [np.asarray(a, dtype=float).reshape(-1) for a in (roll_rad, pitch_rad, yaw_rad)]
    )
    quaternion = Rotation.from_euler("xyz", angles).as_quat()
    return PoseTrajectory(np.asarray(time_s, dtype=float), np.asarray(position_m), quaternion, name)
