"""The URDF reader (issue 30, family 1): a validated tree before any use, bounded walks, names
that can be written into every output; hypothesis mutates a good arm and every mutation is
either a tree or an `InputError`, never another exception."""

from __future__ import annotations

import math
from importlib import resources

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sloshkit.errors import InputError
from sloshkit.export.kinematics import load_arm
from sloshkit.export.urdf import (
    MAX_CHAIN_JOINTS,
    MAX_MOVABLE_JOINTS,
    NAME_PATTERN,
    read_urdf,
    read_urdf_text,
)

JOINT = (
    '<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
    '<origin xyz="0 0 0.1" rpy="{rpy}"/><axis xyz="0 0 1"/>'
    '<limit lower="-3" upper="3" velocity="3"/></joint>'
)


def chain(count: int, kind: str = "revolute") -> str:
    links = ["base", *[f"l{k}" for k in range(1, count)], "tool"]
    joints = "".join(
        JOINT.format(
            name=f"j{k}",
            kind=kind,
            parent=links[k],
            child=links[k + 1],
            rpy="1.5707963 0 0" if k % 2 else "0 0 0",
        )
        for k in range(count)
    )
    return f'<robot name="c">{"".join(f"<link name={link!r}/>" for link in links)}{joints}</robot>'


def test_the_builtin_arm_reads_as_before() -> None:
    source = resources.files("sloshkit.export") / "robots" / "ur5e.urdf"
    with resources.as_file(source) as path:
        tree = read_urdf(path)
    joints = tree.chain_between("base", "tool0")
    assert [joint.name for joint in joints if joint.movable][:2] == [
        "shoulder_pan_joint",
        "shoulder_lift_joint",
    ]
    assert all(joint.velocity == pytest.approx(math.pi) for joint in joints if joint.movable)
    arm = load_arm("ur5e")
    np.testing.assert_allclose(
        arm.forward(np.zeros((1, 6)))[0, :3, 3], [-0.8172, -0.2329, 0.0628], atol=1e-4
    )


def test_a_urdf_arm_matches_its_builtin_twin(tmp_path) -> None:
    """The chain built from the checked tree is the one ikpy built from the file."""
    source = resources.files("sloshkit.export") / "robots" / "ur5e.urdf"
    with resources.as_file(source) as path:
        (tmp_path / "arm.urdf").write_bytes(path.read_bytes())
    own = load_arm(urdf=tmp_path / "arm.urdf", base_link="base", tip_link="tool0")
    builtin = load_arm("ur5e")
    q = builtin.home_rad + np.linspace(-0.3, 0.3, 6)
    np.testing.assert_allclose(own.forward(q[None]), builtin.forward(q[None]), atol=1e-12)
    np.testing.assert_allclose(own.velocity_limit_rad_s, builtin.velocity_limit_rad_s)


def test_chains_up_to_the_bound_are_read_and_longer_ones_refused() -> None:
    tree = read_urdf_text(chain(MAX_MOVABLE_JOINTS), "c.urdf")
    assert len(tree.chain_between("base", "tool")) == MAX_MOVABLE_JOINTS
    with pytest.raises(InputError, match=f"at most {MAX_MOVABLE_JOINTS}"):
        read_urdf_text(chain(MAX_MOVABLE_JOINTS + 1), "c.urdf").chain_between("base", "tool")
    fixed = read_urdf_text(chain(MAX_CHAIN_JOINTS, "fixed"), "c.urdf")
    assert len(fixed.chain_between("base", "tool")) == MAX_CHAIN_JOINTS
    with pytest.raises(InputError, match=f"more than {MAX_CHAIN_JOINTS} joints"):
        read_urdf_text(chain(MAX_CHAIN_JOINTS + 1, "fixed"), "c.urdf").chain_between("base", "tool")


def test_a_joint_cycle_is_named_not_walked_for_ever() -> None:
    text = (
        '<robot name="r"><link name="base"/><link name="a"/><link name="b"/><link name="tool"/>'
        + JOINT.format(name="jt", kind="revolute", parent="b", child="tool", rpy="0 0 0")
        + JOINT.format(name="j1", kind="revolute", parent="a", child="b", rpy="0 0 0")
        + JOINT.format(name="j2", kind="revolute", parent="b", child="a", rpy="0 0 0")
        + "</robot>"
    )
    with pytest.raises(InputError, match="closes a cycle"):
        read_urdf_text(text, "r.urdf").chain_between("base", "tool")


@pytest.mark.parametrize(
    "name", ["j1', 'j2", "a,b", "a b", "a\nb", "a: b", "-a", "", "x" * 129, "caf\u00e9"]
)
def test_names_that_cannot_be_written_safely_are_refused(name: str) -> None:
    from xml.sax.saxutils import quoteattr

    text = chain(2).replace('name="j0"', f"name={quoteattr(name)}")
    with pytest.raises(InputError, match=r"urdf = 'c\.urdf'"):
        read_urdf_text(text, "c.urdf")


@given(st.from_regex(NAME_PATTERN, fullmatch=True))
@settings(max_examples=50, deadline=None)
def test_every_accepted_name_is_safe_in_yaml_csv_and_urscript(name: str) -> None:
    assert not set(name) & set(",'\"\n\r\t :[]{}#&*!|>%@`")
    assert name.isascii() and name.isprintable() and not name.startswith("-")


_PIECES = ['"-3"', '"3"', '"0 0 0.1"', '"0 0 1"', '"revolute"', '"base"', '"tool"', '"j1"']
_VALUES = st.sampled_from(
    ['"nan"', '"inf"', '"1e308"', '"abc"', '""', '"0 0"', '"floating"', '"j0"', '"l1"', '"-1e9"']
)


@given(st.lists(st.tuples(st.sampled_from(_PIECES), _VALUES), min_size=1, max_size=3))
@settings(max_examples=150, deadline=None)
def test_a_mutated_urdf_is_a_tree_or_one_input_error(changes: list[tuple[str, str]]) -> None:
    text = chain(3)
    for old, new in changes:
        text = text.replace(old, new, 1)
    try:
        tree = read_urdf_text(text, "m.urdf")
        joints = tree.chain_between("base", "tool")
    except InputError as error:
        assert error.parameter in ("urdf", "base_link", "tip_link")
        return
    for joint in joints:  # whatever was accepted is finite and ordered
        assert all(math.isfinite(v) for v in (*joint.origin_xyz_m, *joint.origin_rpy_rad))
        assert joint.lower <= joint.upper and joint.velocity > 0
