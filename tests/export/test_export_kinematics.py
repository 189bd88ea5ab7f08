"""Arms and inverse kinematics for export: the UR5e against Universal Robots' DH table, IK of
reachable paths, and the clear failures (reach, joint limit, singularity, velocity)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from sloshkit.errors import InputError
from sloshkit.export.frames import Mounting, rotation_angle_rad, transform
from sloshkit.export.ik import solve_joint_path
from sloshkit.export.kinematics import load_arm

# Universal Robots, "DH parameters for calculations of kinematics and dynamics", UR5e table.
UR5E_A_M = (0.0, -0.425, -0.3922, 0.0, 0.0, 0.0)
UR5E_D_M = (0.1625, 0.0, 0.0, 0.1333, 0.0997, 0.0996)
UR5E_ALPHA_RAD = (math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0)


def dh_forward(joints: np.ndarray) -> np.ndarray:
    """Closed-form standard DH product T = prod Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    frame = np.eye(4)
    for theta, a, d, alpha in zip(joints, UR5E_A_M, UR5E_D_M, UR5E_ALPHA_RAD, strict=True):
        ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
        frame = frame @ np.array(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0.0, sa, ca, d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
    return frame


@pytest.fixture(scope="module")
def ur5e():
    return load_arm("ur5e")


def smooth_step(count: int) -> np.ndarray:
    s = np.linspace(0.0, 1.0, count)
    return s**3 * (10 - 15 * s + 6 * s**2)


def test_ur5e_forward_kinematics_matches_universal_robots_dh_table(ur5e):
    rng = np.random.default_rng(7)
    joints = rng.uniform(-math.pi, math.pi, size=(20, 6))
    frames = ur5e.forward(joints)
    for row, frame in zip(joints, frames, strict=True):
        np.testing.assert_allclose(frame, dh_forward(row), atol=1e-12)


def test_jacobian_matches_finite_differences(ur5e):
    joints = np.array([0.3, -1.1, 1.4, -1.7, -1.3, 0.6])
    jacobian = ur5e.jacobian(joints)
    step = 1e-7
    base = ur5e.forward(joints[None])[0]
    for column in range(6):
        moved = joints.copy()
        moved[column] += step
        frame = ur5e.forward(moved[None])[0]
        np.testing.assert_allclose(
            (frame[:3, 3] - base[:3, 3]) / step, jacobian[:3, column], atol=1e-6
        )
        rotation = (frame[:3, :3] - base[:3, :3]) / step @ base[:3, :3].T
        omega = np.array([rotation[2, 1], rotation[0, 2], rotation[1, 0]])
        np.testing.assert_allclose(omega, jacobian[3:, column], atol=1e-6)


def test_ik_of_a_reachable_tilting_path_reproduces_the_container_poses(ur5e):
    """A container path with translation and a 10-degree tilt: IK then FK lands on every
    container pose within 1e-6 m and 1e-6 rad."""
    count = 60
    s = smooth_step(count)
    mounting = Mounting(base_xyz_m=(-0.45, -0.15, 0.35))
    container = np.stack(
        [
            mounting.base_to_path
            @ transform((0.15 * v, 0.05 * v, 0.03 * v), (math.radians(10.0) * v, 0.0, 0.2 * v))
            for v in s
        ]
    )
    flange = container @ np.linalg.inv(mounting.flange_to_container)[None]
    time = np.arange(count) * 0.01
    path = solve_joint_path(ur5e, flange, time)
    rebuilt = ur5e.forward(path.position_rad) @ mounting.flange_to_container[None]
    distance = np.linalg.norm(rebuilt[:, :3, 3] - container[:, :3, 3], axis=1)
    assert distance.max() < 1e-6
    assert rotation_angle_rad(rebuilt, container).max() < 1e-6
    assert path.max_tip_error_m < 1e-6
    assert path.max_condition_number < 100.0
    # Velocities: at rest at both ends, close to central differences inside.
    np.testing.assert_allclose(path.velocity_rad_s[[0, -1]], 0.0, atol=1e-12)
    central = (path.position_rad[2:] - path.position_rad[:-2]) / (2 * 0.01)
    scale = np.max(np.abs(central))
    np.testing.assert_allclose(path.velocity_rad_s[1:-1], central, atol=0.02 * scale)


def test_unreachable_pose_names_the_sample(ur5e):
    time = np.arange(5) * 0.01
    far = np.stack([transform((1.5 + 0.001 * k, 0.0, 0.3), (math.pi, 0.0, 0.0)) for k in range(5)])
    with pytest.raises(InputError, match=r"sample 0 \(t = 0\.0000 s\).*cannot reach"):
        solve_joint_path(ur5e, far, time)


def test_joint_limit_violation_names_the_joint(tmp_path: Path, ur5e):
    """The UR5e with the base joint limited to +-0.2 rad: a path that needs 0.5 rad fails
    at the first sample beyond the limit, naming shoulder_pan_joint."""
    source = Path(__file__).parents[2] / "src/sloshkit/export/robots/ur5e.urdf"
    text = source.read_text().replace(
        'lower="-6.283185307179586" upper="6.283185307179586" effort="150"',
        'lower="-0.2" upper="0.2" effort="150"',
        1,
    )
    urdf = tmp_path / "ur5e_limited.urdf"
    urdf.write_text(text)
    arm = load_arm(urdf=urdf, base_link="base", tip_link="tool0", home_rad=ur5e.home_rad)
    count = 30
    joints = ur5e.home_rad + np.outer(smooth_step(count), [0.5, 0, 0, 0, 0, 0])
    with pytest.raises(InputError, match="shoulder_pan_joint at its position limit") as error:
        solve_joint_path(arm, ur5e.forward(joints), np.arange(count) * 0.05)
    index = int(np.argmax(joints[:, 0] > 0.2 + 1e-6))
    assert f"sample {index} " in str(error.value)


def test_singular_path_fails_clearly(ur5e):
    """wrist_2 passing through 0 aligns wrist 1 and wrist 3 (the UR wrist singularity)."""
    count = 21
    joints = np.tile([0.2, -1.4, 1.5, -1.6, 0.0, 0.3], (count, 1))
    joints[:, 4] = np.linspace(-0.3, 0.3, count)  # exactly 0 at sample 10
    with pytest.raises(InputError, match=r"singularity") as error:
        solve_joint_path(ur5e, ur5e.forward(joints), np.arange(count) * 0.05)
    message = str(error.value)
    assert "sample 10 " in message or "sample 9 " in message or "sample 11 " in message
    assert "joint" in message


def test_joint_velocity_limit_names_the_joint(ur5e):
    count = 11
    joints = ur5e.home_rad + np.outer(np.linspace(0.0, 0.1, count), [0, 0, 0, 0, 0, 1.0])
    with pytest.raises(InputError, match=r"wrist_3_joint.*beyond its velocity limit 3\.142"):
        solve_joint_path(ur5e, ur5e.forward(joints), np.arange(count) * 0.002)  # 5 rad/s


def test_load_arm_from_urdf_between_links(ur5e):
    source = Path(__file__).parents[2] / "src/sloshkit/export/robots/ur5e.urdf"
    arm = load_arm(urdf=source, base_link="shoulder_link", tip_link="wrist_3_link")
    assert arm.joint_names == ur5e.joint_names[1:]
    np.testing.assert_allclose(arm.velocity_limit_rad_s, math.pi)
    with pytest.raises(InputError, match="is not below"):
        load_arm(urdf=source, base_link="tool0", tip_link="base")
    with pytest.raises(InputError, match="--base-link and --tip-link"):
        load_arm(urdf=source)
    with pytest.raises(InputError, match="must be one of"):
        load_arm("kuka-unknown")
