"""URDF files read into a validated kinematic tree before any use.

A URDF is parsed once (`read_urdf`) into `UrdfJoint` records whose every field has been
checked: names that can be written into any output (`NAME_PATTERN`: YAML, CSV headers,
URScript), a joint type sloshkit can drive, a parent and a child that are links of the file,
finite origins within `MAX_ORIGIN_M` and `MAX_ORIGIN_RAD`, a non-zero axis, numeric limits
with lower <= upper and a finite positive velocity. Every link has at most one parent joint,
so the joints form a tree; `chain_between` walks it from the tip up to the base with a bound
(`MAX_CHAIN_JOINTS`, `MAX_MOVABLE_JOINTS`), so a joint cycle or an endless chain is an error,
not a hang. Every error is an `InputError` naming ``--urdf`` (``urdf``), the element and the
problem.

References
----------
ROS URDF XML specification, http://wiki.ros.org/urdf/XML/joint and
http://wiki.ros.org/urdf/XML/link (types, origin, axis, limit and their defaults).
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from sloshkit.errors import InputError

#: Joint types sloshkit drives (``floating`` and ``planar`` have no single joint coordinate).
JOINT_TYPES: tuple[str, ...] = ("revolute", "continuous", "prismatic", "fixed")

#: Names a link or joint may have: they are written unquoted into CSV headers, YAML lists and
#: robot programs, so only letters, digits and ``_ . - /`` (not first), at most 128 characters.
NAME_PATTERN = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_./-]{0,127}")

#: Largest URDF file read [bytes] (a 7-axis arm with meshes referenced is ~20 kB).
MAX_URDF_BYTES = 8 * 2**20
#: Most joints in one file, and most joints (fixed included) between base and tip link.
MAX_FILE_JOINTS = 1000
MAX_CHAIN_JOINTS = 32
#: Most movable joints between base and tip link (industrial arms have 6 or 7, 8 on a rail):
#: the inverse kinematics of every sample grows with their number.
MAX_MOVABLE_JOINTS = 10
#: Largest origin offset [m] and angle [rad] of a joint (beyond them the file is surely wrong).
MAX_ORIGIN_M = 100.0
MAX_ORIGIN_RAD = 4 * math.pi


@dataclass(frozen=True)
class UrdfJoint:
    """One checked URDF joint (SI: metres, radians; prismatic limits in metres).

    Attributes
    ----------
    name : str
        The joint's name (matches `NAME_PATTERN`).
    kind : str
        One of `JOINT_TYPES`.
    parent, child : str
        The links it connects.
    origin_xyz_m : tuple of 3 floats
        Translation of the joint frame in the parent link's frame [m].
    origin_rpy_rad : tuple of 3 floats
        Fixed-axis roll, pitch, yaw of the joint frame [rad].
    axis : tuple of 3 floats
        Unit axis in the joint frame (``(1, 0, 0)`` when the file gives none).
    lower, upper : float
        Position limits [rad or m] (infinite for continuous joints or without ``<limit>``).
    velocity : float
        Velocity limit [rad/s or m/s] (infinite without one).

    Examples
    --------
    >>> joint = UrdfJoint("j1", "revolute", "a", "b", (0.0, 0.0, 0.1), (0.0, 0.0, 0.0),
    ...                   (0.0, 0.0, 1.0), -1.0, 1.0, 2.0)
    >>> joint.movable, joint.child
    (True, 'b')
    """

    name: str
    kind: str
    parent: str
    child: str
    origin_xyz_m: tuple[float, float, float]
    origin_rpy_rad: tuple[float, float, float]
    axis: tuple[float, float, float]
    lower: float
    upper: float
    velocity: float

    @property
    def movable(self) -> bool:
        """Whether the joint has a coordinate (every type but ``fixed``)."""
        return self.kind != "fixed"


@dataclass(frozen=True)
class UrdfTree:
    """A checked URDF: its name, its links and its joints (a tree: one parent per link).

    Attributes
    ----------
    name : str
        ``<robot name>``.
    links : tuple of str
        The link names.
    joints : tuple of UrdfJoint
        The joints, in file order.
    source : str
        The file (for messages).

    Examples
    --------
    >>> tree = read_urdf_text('<robot name="r"><link name="a"/><link name="b"/>'
    ...     '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
    ...     '<limit lower="-1" upper="1" velocity="2"/></joint></robot>', "r.urdf")
    >>> [joint.name for joint in tree.chain_between("a", "b")]
    ['j']
    """

    name: str
    links: tuple[str, ...]
    joints: tuple[UrdfJoint, ...]
    source: str

    def chain_between(self, base_link: str, tip_link: str) -> tuple[UrdfJoint, ...]:
        """The joints from ``base_link`` down to ``tip_link``, checked for length.

        Parameters
        ----------
        base_link, tip_link : str
            Links of the tree (``--base-link``, ``--tip-link``).

        Returns
        -------
        tuple of UrdfJoint
            Base to tip.

        Examples
        --------
        >>> tree = read_urdf_text('<robot name="r"><link name="a"/><link name="b"/>'
        ...     '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
        ...     '</robot>', "r.urdf")
        >>> len(tree.chain_between("a", "b")), tree.chain_between("a", "a")
        (1, ())
        """
        for parameter, value in (("base_link", base_link), ("tip_link", tip_link)):
            if value not in self.links:
                shown = ", ".join(sorted(self.links)[:20])
                raise InputError(parameter, value, f"is not a link of {self.source}: {shown}")
        parent_joint = {joint.child: joint for joint in self.joints}
        path: list[UrdfJoint] = []
        current = tip_link
        visited = {tip_link}
        while current != base_link:
            joint = parent_joint.get(current)
            if joint is None:
                raise InputError("tip_link", tip_link, f"is not below {base_link} in {self.source}")
            if len(path) >= MAX_CHAIN_JOINTS:
                raise InputError(
                    "urdf",
                    self.source,
                    f"the chain from {tip_link} up towards {base_link} passes more than "
                    f"{MAX_CHAIN_JOINTS} joints (a joint cycle, or not a serial arm)",
                )
            path.append(joint)
            current = joint.parent
            if current in visited:
                raise InputError(
                    "urdf",
                    self.source,
                    f"joint {joint.name!r} closes a cycle: its parent {current!r} is its own "
                    "descendant",
                )
            visited.add(current)
        movable = sum(joint.movable for joint in path)
        if movable > MAX_MOVABLE_JOINTS:
            raise InputError(
                "urdf",
                self.source,
                f"{movable} movable joints between {base_link} and {tip_link}; at most "
                f"{MAX_MOVABLE_JOINTS} (the inverse kinematics of every sample grows with them)",
            )
        return tuple(path[::-1])


def read_urdf(path: str | Path) -> UrdfTree:
    """Read and check a URDF file (see the module for the checks).

    Parameters
    ----------
    path : str or Path
        The file (``--urdf``).

    Returns
    -------
    UrdfTree

    Raises
    ------
    InputError
        Naming ``urdf``, the element and the problem.

    Examples
    --------
    >>> from importlib import resources
    >>> source = resources.files("sloshkit.export") / "robots" / "ur5e.urdf"
    >>> with resources.as_file(source) as file:
    ...     tree = read_urdf(file)
    >>> tree.name, sum(joint.movable for joint in tree.joints)
    ('ur5e', 6)
    """
    source = Path(path)
    if not source.is_file():
        raise InputError("urdf", str(path), "does not exist or is not a file")
    size = source.stat().st_size
    if size > MAX_URDF_BYTES:
        raise InputError(
            "urdf", str(path), f"is {size} bytes; a URDF of at most {MAX_URDF_BYTES} is read"
        )
    return read_urdf_text(source.read_bytes(), str(path))


def read_urdf_text(text: str | bytes, source: str) -> UrdfTree:
    """Check a URDF document given as text (the parser of `read_urdf`).

    Parameters
    ----------
    text : str or bytes
        The XML.
    source : str
        Where it came from (named in messages).

    Returns
    -------
    UrdfTree

    Examples
    --------
    >>> read_urdf_text('<robot name="r"><link name="a"/></robot>', "r.urdf").links
    ('a',)
    """
    try:
        root = ET.fromstring(text)
    except ET.ParseError as error:
        raise InputError("urdf", source, f"is not valid XML ({error})") from None
    if root.tag != "robot":
        raise InputError("urdf", source, f"the root element is <{root.tag}>, not <robot>")
    links: list[str] = []
    for element in root.findall("link"):
        name = _name(element, "link", source)
        if name in links:
            raise InputError("urdf", source, f"link {name!r} is defined twice")
        links.append(name)
    elements = root.findall("joint")
    if len(elements) > MAX_FILE_JOINTS:
        raise InputError(
            "urdf", source, f"has {len(elements)} joints; at most {MAX_FILE_JOINTS} are read"
        )
    joints: list[UrdfJoint] = []
    names: set[str] = set()
    children: dict[str, str] = {}
    known = set(links)
    for element in elements:
        joint = _joint(element, known, source)
        if joint.name in names:
            raise InputError("urdf", source, f"joint {joint.name!r} is defined twice")
        if joint.child in children:
            raise InputError(
                "urdf",
                source,
                f"link {joint.child!r} is the child of joints {children[joint.child]!r} and "
                f"{joint.name!r} (a URDF is a tree: one parent per link)",
            )
        if joint.child == joint.parent:
            raise InputError(
                "urdf", source, f"joint {joint.name!r} connects {joint.child} to itself"
            )
        names.add(joint.name)
        children[joint.child] = joint.name
        joints.append(joint)
    robot = root.get("name", Path(source).stem)
    return UrdfTree(robot, tuple(links), tuple(joints), source)


def _name(element: ET.Element, what: str, source: str) -> str:
    name = element.get("name")
    if name is None:
        raise InputError("urdf", source, f"a <{what}> element has no name")
    if not NAME_PATTERN.fullmatch(name):
        raise InputError(
            "urdf",
            source,
            f"{what} name {name!r} cannot be written safely into the outputs; names must be "
            "letters, digits and _ . - / (not first), at most 128 characters",
        )
    return name


def _link_of(element: ET.Element, tag: str, joint: str, known: set[str], source: str) -> str:
    found = element.find(tag)
    link = None if found is None else found.get("link")
    if link is None:
        raise InputError("urdf", source, f"joint {joint!r} has no <{tag} link=...>")
    if link not in known:
        raise InputError("urdf", source, f"joint {joint!r}: {tag} {link!r} is not a link")
    return link


def _numbers(text: str | None, default: tuple[float, ...], what: str, source: str) -> list[float]:
    if text is None:
        return list(default)
    parts = text.split()
    try:
        values = [float(part) for part in parts]
    except ValueError:
        values = []
    if len(values) != len(default) or not all(math.isfinite(v) for v in values):
        raise InputError("urdf", source, f"{what} = {text!r} must be {len(default)} finite numbers")
    return values


def _number(element: ET.Element, key: str, default: float, what: str, source: str) -> float:
    text = element.get(key)
    if text is None:
        return default
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise InputError("urdf", source, f"{what} {key} = {text!r} must be a finite number")
    return value


def _joint(element: ET.Element, known: set[str], source: str) -> UrdfJoint:
    name = _name(element, "joint", source)
    kind = element.get("type")
    if kind is None:
        raise InputError("urdf", source, f"joint {name!r} has no type")
    if kind not in JOINT_TYPES:
        raise InputError(
            "urdf",
            source,
            f"joint {name!r} has type {kind!r}; sloshkit drives " + ", ".join(JOINT_TYPES),
        )
    parent = _link_of(element, "parent", name, known, source)
    child = _link_of(element, "child", name, known, source)
    origin = element.find("origin")
    xyz = _numbers(
        None if origin is None else origin.get("xyz"),
        (0.0,) * 3,
        f"joint {name!r} origin xyz",
        source,
    )
    rpy = _numbers(
        None if origin is None else origin.get("rpy"),
        (0.0,) * 3,
        f"joint {name!r} origin rpy",
        source,
    )
    if max(abs(v) for v in xyz) > MAX_ORIGIN_M or max(abs(v) for v in rpy) > MAX_ORIGIN_RAD:
        raise InputError(
            "urdf",
            source,
            f"joint {name!r} origin xyz {xyz} m, rpy {rpy} rad: at most {MAX_ORIGIN_M:g} m "
            f"and {MAX_ORIGIN_RAD:.4g} rad",
        )
    axis_element = element.find("axis")
    axis = _numbers(
        None if axis_element is None else axis_element.get("xyz", "1 0 0"),
        (1.0, 0.0, 0.0),
        f"joint {name!r} axis xyz",
        source,
    )
    norm = math.sqrt(sum(v * v for v in axis))
    if kind != "fixed" and not norm > 1e-9:
        raise InputError("urdf", source, f"joint {name!r} axis xyz is zero")
    unit = tuple(v / norm for v in axis) if norm > 1e-9 else (1.0, 0.0, 0.0)
    lower, upper, velocity = -math.inf, math.inf, math.inf
    limit = element.find("limit")
    if limit is not None:
        what = f"joint {name!r} <limit>"
        if kind in ("revolute", "prismatic"):
            lower = _number(limit, "lower", 0.0, what, source)
            upper = _number(limit, "upper", 0.0, what, source)
            if lower > upper:
                raise InputError("urdf", source, f"{what} lower {lower:g} > upper {upper:g}")
        velocity = _number(limit, "velocity", math.inf, what, source)
        if not velocity > 0.0:
            raise InputError("urdf", source, f"{what} velocity {velocity:g} must be > 0")
    return UrdfJoint(
        name,
        kind,
        parent,
        child,
        (xyz[0], xyz[1], xyz[2]),
        (rpy[0], rpy[1], rpy[2]),
        (unit[0], unit[1], unit[2]),
        lower,
        upper,
        velocity,
    )
