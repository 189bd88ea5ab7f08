"""Fast path: slosh metrics of many 3-D pose trajectories at once (linear model).

The 3-D analogue of `sloshkit.sim.batch`: the drive of each trajectory is computed as in
`sloshkit.sim.spatial.simulate_spatial`, the trajectories are padded to a common length (the
container resting in its last pose) and one compiled loop (numba) steps every case and mode
keeping only the metrics, no time histories. The numbers equal those of
``simulate_spatial(model, poses, nonlinear=False, ...)`` with the same options.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError, require_positive
from sloshkit.model.modal import SloshModel
from sloshkit.motion.pose_kinematics import DEFAULT_CUTOFF_HZ, pose_kinematics
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.results import ResultMixin
from sloshkit.sim.metrics import (
    default_settle_time,
    free_oscillation_components,
    wall_elevation_factors,
)
from sloshkit.sim.spatial_drive import spatial_drive
from sloshkit.sim.spatial_kernels import STIFFNESS_FLOOR, kernels
from sloshkit.sim.spatial_response import HEIGHT_MAPPINGS, HeightMapping, ellipse_semi_major

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class SpatialBatchMetrics(ResultMixin):
    """Per-trajectory metrics (SI), arrays of shape (cases,).

    Attributes
    ----------
    peak_slosh_height_m : largest slosh height over the motion and the settling time [m]
    residual_slosh_height_m : bound on the slosh height of the free oscillation left [m]
    peak_angle_rad : largest first-mode deflection [rad]
    residual_angle_rad : first-mode free-oscillation amplitude left at the end [rad]
    duration_s : duration of each pose trajectory [s]

    Examples
    --------
    >>> import numpy as np
    >>> metrics = SpatialBatchMetrics(*np.array([[2e-3], [1e-4], [0.1], [0.005], [1.0]]))
    >>> metrics.to_pandas().loc[0, "peak_slosh_height_m"]
    np.float64(0.002)
    """

    peak_slosh_height_m: FloatArray
    residual_slosh_height_m: FloatArray
    peak_angle_rad: FloatArray
    residual_angle_rad: FloatArray
    duration_s: FloatArray

    def columns(self) -> dict[str, FloatArray]:
        """One row per trajectory."""
        return {
            "duration_s": self.duration_s,
            "peak_slosh_height_m": self.peak_slosh_height_m,
            "residual_slosh_height_m": self.residual_slosh_height_m,
            "peak_angle_rad": self.peak_angle_rad,
            "residual_angle_rad": self.residual_angle_rad,
        }


def spatial_batch_metrics(
    model: SloshModel,
    poses: Sequence[PoseTrajectory],
    *,
    settle_time_s: float | None = None,
    sample_period_s: float | None = None,
    cutoff_hz: float | None = DEFAULT_CUTOFF_HZ,
    height_mapping: HeightMapping = "modal",
) -> SpatialBatchMetrics:
    """Linear 3-D slosh metrics of many pose trajectories sharing ``model``.

    Parameters
    ----------
    model : SloshModel
        The equivalent model.
    poses : sequence of PoseTrajectory
        The trajectories (any lengths; each at rest before its first and after its last pose).
    settle_time_s : float, optional
        Time simulated after each trajectory [s] (default `default_settle_time`).
    sample_period_s : float, optional
        Simulation step [s] (default: the first trajectory's step if uniform, else 1 ms).
    cutoff_hz : float or None
        Cut-off of the pose differentiation (`sloshkit.motion.pose_kinematics`).
    height_mapping : str
        ``"modal"`` or ``"planar"`` (see `sloshkit.sim.spatial`).

    Returns
    -------
    SpatialBatchMetrics

    References
    ----------
    The model and its discretisation: `sloshkit.sim.spatial`, `sloshkit.sim.spatial_kernels`.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.049), sk.get_liquid("water-20C"), 0.08)
    >>> moves = [sk.poses_from_law(sk.septic(d, 1.5)) for d in (0.05, 0.1)]
    >>> metrics = spatial_batch_metrics(model, moves)
    >>> bool(metrics.peak_slosh_height_m[1] > metrics.peak_slosh_height_m[0])
    True
    """
    if not poses:
        raise InputError("poses", 0, "need at least one trajectory")
    if height_mapping not in HEIGHT_MAPPINGS:
        raise InputError("height_mapping", height_mapping, "must be one of modal, planar")
    settle = default_settle_time(model) if settle_time_s is None else float(settle_time_s)
    if not math.isfinite(settle) or settle < 0.0:
        raise InputError("settle_time", settle, "must be >= 0 s")
    first = poses[0]
    if sample_period_s is None:
        dt = first.sample_period_s if first.is_uniform else 1e-3
    else:
        dt = require_positive("sample_period", sample_period_s, "s")
    drives = [
        spatial_drive(model, pose_kinematics(p.extended(settle, dt), dt, cutoff_hz=cutoff_hz))
        for p in poses
    ]
    steps = max(drive.time_s.size for drive in drives)

    def padded(arrays: list[FloatArray], axis: int) -> FloatArray:
        out = []
        for array in arrays:
            extra = steps - array.shape[axis]
            last = np.take(array, [-1], axis=axis)
            out.append(np.concatenate([array, np.repeat(last, extra, axis=axis)], axis=axis))
        return np.ascontiguousarray(np.stack(out))

    force = padded([d.specific_force_m_s2 for d in drives], 1)
    rate = padded([d.tilt_rate_rad_s for d in drives], 0)
    accel = padded([d.tilt_acceleration_rad_s2 for d in drives], 0)
    rest = np.ascontiguousarray(np.stack([d.rest_force_m_s2 for d in drives]))
    modes = model.modes
    length = np.array([m.length_m for m in modes])
    omega = np.array([m.omega_rad_s for m in modes])
    zeta = np.array([m.damping_ratio for m in modes])
    factors = wall_elevation_factors(model)
    remainder = model.radius_m - float(factors.sum()) if height_mapping == "planar" else 0.0
    end_index = np.empty(len(poses), dtype=np.int64)
    lags = np.empty(len(poses))
    for case, (p, drive) in enumerate(zip(poses, drives, strict=True)):
        window = drive.kinematics.window
        settled = (max(window // 2, 4) + 1) * dt
        index = int(np.searchsorted(drive.time_s, p.end_s + settled - 1e-12))
        end_index[case] = min(index, drive.time_s.size - 1)
        lags[case] = float(drive.time_s[end_index[case]]) - p.end_s
    last_index = np.array([drive.time_s.size - 1 for drive in drives], dtype=np.int64)
    peak_height, peak_angle, end_state = kernels()["linear_batch"](
        force,
        rest,
        rate,
        accel,
        length,
        omega,
        zeta,
        STIFFNESS_FLOOR * omega**2,
        factors,
        remainder,
        dt,
        end_index,
        last_index,
    )
    residual = np.empty((len(poses), len(modes)))
    for row, mode in enumerate(modes):
        final = force[np.arange(len(poses)), row, last_index]
        equilibrium = final[:, :2] / np.maximum(-final[:, 2:3], 1e-9)
        offset, quadrature = free_oscillation_components(
            end_state[:, row, :2] - equilibrium,
            end_state[:, row, 2:],
            mode.omega_rad_s,
            mode.damping_ratio,
        )
        semi = ellipse_semi_major(offset, quadrature)
        residual[:, row] = semi * np.exp(mode.damping_ratio * mode.omega_rad_s * lags)
    return SpatialBatchMetrics(
        peak_slosh_height_m=np.asarray(peak_height, dtype=float),
        residual_slosh_height_m=residual @ factors,
        peak_angle_rad=np.asarray(peak_angle, dtype=float),
        residual_angle_rad=residual[:, 0],
        duration_s=np.array([p.duration_s for p in poses]),
    )
