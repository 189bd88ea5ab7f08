"""The compiled chain against ikpy: forward kinematics of every built-in arm and of a URDF with
a prismatic joint and tilted origins equal to ikpy's own ``Chain.forward_kinematics``, the
geometric Jacobian equal to finite differences of it, and the trajectory IK equal to ikpy's
bounded least squares on each sample."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from ikpy.chain import Chain

from sloshkit.export.chain import CompiledChain
from sloshkit.export.ik import solve_joint_path
from sloshkit.export.kinematics import load_arm, robot_names

MIXED_URDF = """<robot name="mixed">
<link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="tool"/>
<joint name="turn" type="revolute"><parent link="base"/><child link="a"/>
<origin xyz="0.01 -0.02 0.1" rpy="0.3 -0.2 0.5"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" velocity="3"/></joint>
<joint name="slide" type="prismatic"><parent link="a"/><child link="b"/>
<origin xyz="0.2 0 0" rpy="0 1.1 0"/><axis xyz="0.6 0 0.8"/>
<limit lower="-0.5" upper="0.5" velocity="1"/></joint>
<joint name="bend" type="revolute"><parent link="b"/><child link="c"/>
<origin xyz="0 0.15 0" rpy="-0.4 0 1.2"/><axis xyz="0 1 0"/>
<limit lower="-3" upper="3" velocity="3"/></joint>
<joint name="flange" type="fixed"><parent link="c"/><child link="tool"/>
<origin xyz="0 0 0.08" rpy="3.14159 0 0"/></joint>
</robot>"""

ARMS = [*robot_names(), "mixed"]


@pytest.fixture(scope="module")
def arms(tmp_path_factory):
    path = tmp_path_factory.mktemp("urdf") / "mixed.urdf"
    path.write_text(MIXED_URDF)
    loaded = {name: load_arm(name) for name in robot_names()}
    loaded["mixed"] = load_arm(urdf=path, base_link="base", tip_link="tool")
    return loaded


def ikpy_forward(arm, joints: np.ndarray) -> np.ndarray:
    """ikpy's own forward kinematics of the same links (the base class's method)."""
    full = np.zeros(len(arm.chain.links))
    full[np.asarray(arm.chain.active_links_mask, dtype=bool)] = joints
    return np.asarray(Chain.forward_kinematics(arm.chain, full), dtype=float)


def joints_in_range(arm, fractions: list[float]) -> np.ndarray:
    low = np.maximum(arm.lower_rad, -np.pi)
    high = np.minimum(arm.upper_rad, np.pi)
    return low + np.asarray(fractions[: arm.dof]) * (high - low)


def test_every_arm_uses_the_compiled_chain(arms) -> None:
    assert all(isinstance(arm.chain, CompiledChain) for arm in arms.values())


@pytest.mark.parametrize("name", ARMS)
@settings(max_examples=25, deadline=None)
@given(fractions=st.lists(st.floats(0.0, 1.0), min_size=6, max_size=6))
def test_forward_kinematics_equals_ikpys(arms, name: str, fractions: list[float]) -> None:
    arm = arms[name]
    joints = joints_in_range(arm, fractions)
    np.testing.assert_allclose(arm.forward(joints[None])[0], ikpy_forward(arm, joints), atol=1e-12)
    full = np.zeros(len(arm.chain.links))
    full[np.asarray(arm.chain.active_links_mask, dtype=bool)] = joints
    frames = arm.chain.forward_kinematics(full, full_kinematics=True)
    np.testing.assert_allclose(
        np.stack(frames), np.stack(Chain.forward_kinematics(arm.chain, full, True)), atol=1e-12
    )


@pytest.mark.parametrize("name", ARMS)
def test_the_jacobian_is_the_derivative_of_the_forward_kinematics(arms, name: str) -> None:
    arm = arms[name]
    joints = joints_in_range(arm, [0.31, 0.62, 0.47, 0.18, 0.83, 0.55])
    jacobian, tip = arm.jacobian_and_tip(joints)
    np.testing.assert_allclose(tip, ikpy_forward(arm, joints), atol=1e-12)
    step = 1e-6
    for column in range(arm.dof):
        ahead, behind = joints.copy(), joints.copy()
        ahead[column] += step
        behind[column] -= step
        plus, minus = ikpy_forward(arm, ahead), ikpy_forward(arm, behind)
        velocity = (plus[:3, 3] - minus[:3, 3]) / (2 * step)
        spin = (plus[:3, :3] - minus[:3, :3]) / (2 * step) @ tip[:3, :3].T  # [w]x
        omega = np.array([spin[2, 1], spin[0, 2], spin[1, 0]])
        np.testing.assert_allclose(jacobian[:3, column], velocity, atol=1e-8)
        np.testing.assert_allclose(jacobian[3:, column], omega, atol=1e-8)


@pytest.mark.parametrize("name", ["ur5e", "kr6r900", "mixed"])
def test_the_trajectory_ik_equals_ikpys_least_squares(arms, name: str) -> None:
    arm = arms[name]
    start = joints_in_range(arm, [0.45, 0.4, 0.6, 0.55, 0.35, 0.5])
    path = start + np.linspace(0.0, 0.25, 30)[:, None] * np.linspace(1.0, -0.5, arm.dof)
    solved = solve_joint_path(arm, arm.forward(path), np.arange(30) * 0.01, seed_rad=start)
    assert solved.max_tip_error_m < 1e-12
    np.testing.assert_allclose(solved.position_rad, path, atol=1e-9)
    active = np.asarray(arm.chain.active_links_mask, dtype=bool)
    for index in (1, 15, 29):  # ikpy alone, from the previous sample
        seed = np.zeros(len(arm.chain.links))
        seed[active] = path[index - 1]
        theirs = arm.chain.inverse_kinematics_frame(
            arm.forward(path[index][None])[0], initial_position=seed, orientation_mode="all"
        )
        np.testing.assert_allclose(solved.position_rad[index], theirs[active], atol=1e-6)
