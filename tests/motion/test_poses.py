"""Pose trajectories: validation, constructors, resampling and noise-robust kinematics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sloshkit.errors import InputError
from sloshkit.motion.laws import septic
from sloshkit.motion.pose_builders import (
    concatenate,
    poses_from_law,
    poses_from_path,
    poses_from_rotation,
)
from sloshkit.motion.pose_kinematics import pose_kinematics, savgol_half_width
from sloshkit.motion.poses import PoseTrajectory, poses_from_rpy
from sloshkit.motion.quaternions import quaternion_matrix


def _still(count: int = 3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return np.arange(count, dtype=float), np.zeros((count, 3)), np.tile([0, 0, 0, 1.0], (count, 1))


def test_time_must_increase_strictly() -> None:
    t, p, q = _still()
    t[2] = t[1]
    with pytest.raises(InputError, match="increase strictly"):
        PoseTrajectory(t, p, q)


def test_quaternion_must_be_unit_within_tolerance() -> None:
    t, p, q = _still()
    q[1] = [0, 0, 0, 1.01]
    with pytest.raises(InputError, match="unit quaternion"):
        PoseTrajectory(t, p, q)
    q[1] = [0, 0, 0, 1.0005]
    assert np.allclose(np.linalg.norm(PoseTrajectory(t, p, q).quaternion_xyzw, axis=1), 1.0)


def test_shapes_and_finiteness_are_checked() -> None:
    t, p, q = _still()
    with pytest.raises(InputError):
        PoseTrajectory(t, p[:, :2], q)
    p[1, 0] = np.nan
    with pytest.raises(InputError, match="finite"):
        PoseTrajectory(t, p, q)


def test_sign_continuity() -> None:
    rotation = Rotation.from_euler("z", np.linspace(0, 3 * np.pi, 50)[:, None])
    q = rotation.as_quat()
    q[::2] *= -1.0
    poses = PoseTrajectory(np.arange(50.0), np.zeros((50, 3)), q)
    dots = np.einsum("ij,ij->i", poses.quaternion_xyzw[1:], poses.quaternion_xyzw[:-1])
    assert np.all(dots > 0.0)
    assert np.allclose(poses.rotation.as_matrix(), rotation.as_matrix())


def test_tool_offset_in_the_pose_frame() -> None:
    quarter = Rotation.from_euler("y", 90, degrees=True)
    poses = PoseTrajectory(
        np.array([0.0, 1.0]), np.ones((2, 3)), np.tile(quarter.as_quat(), (2, 1))
    )
    shifted = poses.with_tool_offset([0.0, 0.0, 0.2])
    assert np.allclose(shifted.position_m, [[1.2, 1.0, 1.0]] * 2)
    with pytest.raises(InputError):
        poses.with_tool_offset([1.0, 2.0])


def test_rpy_is_fixed_axis_xyz() -> None:
    poses = poses_from_rpy([0.0, 1.0], np.zeros((2, 3)), [0.1, 0.1], [0.2, 0.2], [0.3, 0.3])
    expected = (
        Rotation.from_euler("z", 0.3)
        * Rotation.from_euler("y", 0.2)
        * Rotation.from_euler("x", 0.1)
    )
    assert np.allclose(poses.rotation[0].as_matrix(), expected.as_matrix())


def test_constructors_hit_their_end_points() -> None:
    law = septic(0.4, 1.0)
    along = poses_from_law(law, (0, 0, 2), sample_period_s=0.01)
    assert np.allclose(along.position_m[-1], [0, 0, 0.4])
    turn = poses_from_rotation(septic(math.pi / 2, 1.0), (0, 0, 1), pivot_m=(0.1, 0, 0))
    assert np.allclose(turn.position_m[-1], [0.1, -0.1, 0.0])
    path = poses_from_path([[0, 0, 0], [0.1, 0.1, 0], [0.2, 0, 0]], law, sample_period_s=0.01)
    assert np.allclose(path.position_m[[0, -1]], [[0, 0, 0], [0.2, 0, 0]])
    both = concatenate([along, turn])
    assert both.time_s.size == along.time_s.size + turn.time_s.size - 1
    assert both.duration_s == pytest.approx(2.0)
    assert np.allclose(both.position_m[-1], [0.1, -0.1, 0.4])


def test_resample_reproduces_a_smooth_trajectory() -> None:
    poses = poses_from_rotation(septic(0.5, 1.0), (1, 0, 0), sample_period_s=0.01)
    fine = poses.resample(0.002)
    exact = Rotation.from_rotvec(np.outer(septic(0.5, 1.0).position(fine.time_s), [1, 0, 0]))
    assert np.max((fine.rotation * exact.inv()).magnitude()) < 1e-5


def test_quaternion_matrix_matches_scipy() -> None:
    rotation = Rotation.random(20, random_state=1)
    assert np.allclose(quaternion_matrix(rotation.as_quat()), rotation.as_matrix())


def test_savgol_cutoff_inversion() -> None:
    # Schafer (2011): f_c / f_N = (N + 1) / (3.2 M - 4.6)
    half = savgol_half_width(25.0, 0.002)
    assert (4 + 1) / (3.2 * half - 4.6) * 250.0 == pytest.approx(25.0, rel=0.05)


def _noisy_orbit(noise: float, seed: int = 3) -> tuple[PoseTrajectory, dict[str, np.ndarray]]:
    """A circle at 1 rev/s, spinning about z and rocking about x, with white noise."""
    dt, rate = 0.002, 2 * np.pi
    t = np.arange(0.0, 3.0 + dt / 2, dt)
    radius, rock = 0.2, 0.2
    position = np.column_stack((radius * np.cos(rate * t), radius * np.sin(rate * t), 0 * t))
    acceleration = -(rate**2) * np.column_stack((position[:, 0], position[:, 1], 0 * t))
    spin = Rotation.from_euler("z", (rate * t)[:, None])
    tilt = Rotation.from_euler("x", (rock * np.sin(rate * t))[:, None])
    rotation = spin * tilt
    # body angular velocity of Rz(a) Rx(b): (b', a' sin b, a' cos b) in the body frame
    b, db, ddb = (
        rock * np.sin(rate * t),
        rock * rate * np.cos(rate * t),
        -rock * rate**2 * np.sin(rate * t),
    )
    omega_body = np.column_stack((db, rate * np.sin(b), rate * np.cos(b)))
    alpha_body = np.column_stack((ddb, rate * np.cos(b) * db, -rate * np.sin(b) * db))
    rng = np.random.default_rng(seed)
    q = rotation.as_quat() + noise * 0.02 * rng.standard_normal((t.size, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    poses = PoseTrajectory(t, position + noise * rng.standard_normal(position.shape), q)
    return poses, {"acceleration": acceleration, "omega": omega_body, "alpha": alpha_body}


def test_kinematics_of_an_exact_orbit() -> None:
    poses, exact = _noisy_orbit(0.0)
    kin = pose_kinematics(poses)
    inner = slice(200, -200)  # away from the (non-rest) ends
    assert np.max(np.abs(kin.acceleration_m_s2 - exact["acceleration"])[inner]) < 0.01 * 7.9
    assert np.max(np.abs(kin.angular_velocity_body_rad_s - exact["omega"])[inner]) < 1e-3 * 6.3
    assert np.max(np.abs(kin.angular_acceleration_body_rad_s2 - exact["alpha"])[inner]) < 0.01 * 8


def test_kinematics_do_not_amplify_noise() -> None:
    """0.1 mm position noise at 500 Hz: finite differences give accelerations off by ~50 m/s^2;
    the 25 Hz Savitzky-Golay differentiator stays within a few % of the 7.9 m/s^2 peak."""
    poses, exact = _noisy_orbit(1e-4)
    kin = pose_kinematics(poses)
    inner = slice(200, -200)
    error = np.abs(kin.acceleration_m_s2 - exact["acceleration"])[inner]
    naive = np.gradient(np.gradient(poses.position_m, 0.002, axis=0), 0.002, axis=0)
    naive_error = np.abs(naive - exact["acceleration"])[inner]
    assert np.sqrt(np.mean(error**2)) < 0.05 * 7.9
    assert np.sqrt(np.mean(naive_error**2)) > 20 * np.sqrt(np.mean(error**2))
    omega_error = np.abs(kin.angular_velocity_body_rad_s - exact["omega"])[inner]
    assert np.sqrt(np.mean(omega_error**2)) < 0.02 * 6.3
    alpha_error = np.abs(kin.angular_acceleration_body_rad_s2 - exact["alpha"])[inner]
    assert np.sqrt(np.mean(alpha_error**2)) < 0.1 * 8


def test_point_acceleration_is_centripetal_for_a_spin() -> None:
    poses = poses_from_rotation(septic(4 * np.pi, 2.0), (0, 0, 1), sample_period_s=0.002)
    kin = pose_kinematics(poses)
    middle = np.argmin(np.abs(kin.time_s - 1.0))
    rate = kin.angular_velocity_world_rad_s[middle, 2]
    arm = kin.to_world(np.array([0.05, 0.0, 0.0]))[middle]
    acceleration = kin.point_acceleration([0.05, 0.0, 0.0])[middle]
    assert acceleration @ arm / 0.05 == pytest.approx(-(rate**2) * 0.05, rel=1e-3)
