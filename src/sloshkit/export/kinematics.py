"""Serial arms from URDF: forward kinematics, Jacobian and inverse kinematics (with ikpy).

The arm's chain is read from a URDF between a base link and a tip link and handed to ikpy
(P. Manceron, *IKPy*, https://github.com/Phylliade/ikpy), whose forward kinematics multiplies
the URDF joint transforms and whose inverse kinematics is a bounded least-squares fit of the
tip frame (scipy ``least_squares``). sloshkit adds what a trajectory needs on top of one IK
call: each sample is seeded with the previous solution (continuity), and the joint path is
checked for reach, joint position limits, jumps, joint velocity limits (URDF ``<limit
velocity=...>``) and singularities (the condition number of the geometric Jacobian).

Built-in arms live in ``sloshkit/export/robots`` (see the README there for their sources).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError

FloatArray = NDArray[np.float64]

#: Built-in arms: URDF file in ``sloshkit/export/robots``, base link, tip link, IK seed [rad].
ROBOTS: dict[str, tuple[str, str, str, tuple[float, ...]]] = {
    # Seed: elbow up, flange pointing down (a usual pick-and-place configuration).
    "ur5e": (
        "ur5e.urdf",
        "base",
        "tool0",
        (0.0, -math.pi / 2, math.pi / 2, -math.pi / 2, -math.pi / 2, 0.0),
    ),
    # Industrial arms (sources in robots/README.md): seeds with the upper arm upright, the
    # forearm level and the flange pointing down.
    "lrmate200id": ("lrmate200id.urdf", "base", "tool0", (0.0, 0.0, 0.0, 0.0, -math.pi / 2, 0.0)),
    "irb120": ("irb120.urdf", "base", "tool0", (0.0, 0.0, 0.0, 0.0, math.pi / 2, 0.0)),
    "kr6r900": (
        "kr6r900.urdf",
        "base",
        "tool0",
        (0.0, -math.pi / 2, math.pi / 2, 0.0, math.pi / 2, 0.0),
    ),
    "tx2_60": ("tx2_60.urdf", "base", "tool0", (0.0, 0.0, math.pi / 2, 0.0, math.pi / 2, 0.0)),
}

#: IK must reproduce the tip frame to this distance [m] and angle [rad].
REACH_TOLERANCE_M = 1e-7
REACH_TOLERANCE_RAD = 1e-7
#: Largest joint step between consecutive samples accepted as continuous [rad].
MAX_JOINT_STEP_RAD = 0.2
#: Largest condition number of the Jacobian (translation rows in m, rotation rows in rad)
#: accepted before the configuration is called singular.
MAX_CONDITION_NUMBER = 1e3


@dataclass(frozen=True, eq=False)
class Arm:
    """A serial arm between two URDF links.

    Attributes
    ----------
    name : the robot's name (URDF ``<robot name>``)
    joint_names : the movable joints from base to tip
    lower_rad, upper_rad : joint position limits [rad] (or [m] for prismatic joints)
    velocity_limit_rad_s : joint velocity limits [rad/s] (inf when the URDF gives none)
    home_rad : the IK seed of the first sample [rad]
    base_link, tip_link : the URDF links the chain runs between
    chain : the ikpy ``Chain`` (an origin link, then one link per URDF joint)

    Examples
    --------
    >>> arm = load_arm("ur5e")
    >>> arm.name, arm.dof, bool((arm.lower_rad < arm.home_rad).all())
    ('ur5e', 6, True)
    """

    name: str
    joint_names: tuple[str, ...]
    lower_rad: FloatArray
    upper_rad: FloatArray
    velocity_limit_rad_s: FloatArray
    home_rad: FloatArray
    base_link: str
    tip_link: str
    chain: Any

    @property
    def dof(self) -> int:
        """Number of movable joints."""
        return len(self.joint_names)

    def _full(self, joints_rad: FloatArray) -> FloatArray:
        full = np.zeros(len(self.chain.links))
        full[self._active] = joints_rad
        return full

    @property
    def _active(self) -> NDArray[np.bool_]:
        return np.asarray(self.chain.active_links_mask, dtype=bool)

    def forward(self, joints_rad: FloatArray) -> FloatArray:
        """Tip frames in the base frame, (N, 4, 4), for joint positions (N, dof) [rad].

        Parameters
        ----------
        joints_rad : joint positions, one row per sample [rad]

        Returns
        -------
        numpy.ndarray
            T_base_tip for every sample.

        References
        ----------
        ikpy ``Chain.forward_kinematics`` (product of the URDF joint transforms).

        Examples
        --------
        >>> arm = load_arm("ur5e")
        >>> arm.forward(np.zeros((1, 6)))[0, :3, 3].round(4)  # stretched out along -x
        array([-0.8172, -0.2329,  0.0628])
        """
        joints = np.atleast_2d(np.asarray(joints_rad, dtype=float))
        return np.stack([self.chain.forward_kinematics(self._full(row)) for row in joints])

    def jacobian(self, joints_rad: FloatArray) -> FloatArray:
        """Geometric Jacobian (6, dof) of the tip in the base frame: rows vx, vy, vz [m/rad],
        then wx, wy, wz [-] (Siciliano et al., *Robotics*, Springer 2009, §3.1.3).

        Parameters
        ----------
        joints_rad : joint positions (dof,) [rad]

        Returns
        -------
        numpy.ndarray
            J with [v; omega] = J q'.

        References
        ----------
        B. Siciliano, L. Sciavicco, L. Villani, G. Oriolo, *Robotics: Modelling, Planning and
        Control*, Springer (2009), eq. 3.30; doi:10.1007/978-1-84628-642-1.

        Examples
        --------
        >>> load_arm("ur5e").jacobian(np.zeros(6)).shape
        (6, 6)
        """
        return self.jacobian_and_tip(joints_rad)[0]

    def jacobian_and_tip(self, joints_rad: FloatArray) -> tuple[FloatArray, FloatArray]:
        """The geometric Jacobian (`jacobian`) and the tip frame (4x4), from one forward pass."""
        frames = self.chain.forward_kinematics(
            self._full(np.asarray(joints_rad, dtype=float)), full_kinematics=True
        )
        tip = frames[-1][:3, 3]
        columns = []
        for index in np.flatnonzero(self._active):
            link = self.chain.links[index]
            rotation = frames[index][:3, :3]
            origin = frames[index][:3, 3]
            if link.joint_type == "prismatic":
                axis = rotation @ np.asarray(link.translation, dtype=float)
                columns.append(np.concatenate([axis, np.zeros(3)]))
            else:
                axis = rotation @ np.asarray(link.rotation, dtype=float)
                columns.append(np.concatenate([np.cross(axis, tip - origin), axis]))
        return np.column_stack(columns), np.asarray(frames[-1], dtype=float)


def robot_names() -> tuple[str, ...]:
    """Names of the built-in arms (``--robot``).

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> "ur5e" in robot_names()
    True
    """
    return tuple(sorted(ROBOTS))


def load_arm(
    robot: str | None = None,
    urdf: str | Path | None = None,
    base_link: str | None = None,
    tip_link: str | None = None,
    home_rad: FloatArray | None = None,
) -> Arm:
    """A built-in arm by name, or the chain of a URDF file between two links.

    Parameters
    ----------
    robot : built-in name (`robot_names`), or None with ``urdf``
    urdf : URDF file (kinematic chain; meshes are not needed)
    base_link, tip_link : the chain's first and last URDF links (built-in arms: their
        controller's base and flange frames)
    home_rad : IK seed for the first sample [rad] (default: the built-in arm's, or the middle
        of each joint range)

    Returns
    -------
    Arm

    References
    ----------
    ROS URDF XML specification (``<joint>``, ``<limit lower upper velocity>``),
    http://wiki.ros.org/urdf/XML/joint.

    Examples
    --------
    >>> load_arm("ur5e").joint_names[:2]
    ('shoulder_pan_joint', 'shoulder_lift_joint')
    """
    if (robot is None) == (urdf is None):
        raise InputError("robot", robot, "give either --robot or --urdf")
    default_home: tuple[float, ...] | None = None
    if robot is not None:
        if robot not in ROBOTS:
            raise InputError("robot", robot, "must be one of " + ", ".join(robot_names()))
        filename, default_base, default_tip, default_home = ROBOTS[robot]
        source = resources.files("sloshkit.export") / "robots" / filename
        with resources.as_file(source) as path:
            return _arm_from_urdf(
                Path(path),
                base_link or default_base,
                tip_link or default_tip,
                home_rad if home_rad is not None else np.asarray(default_home),
            )
    if base_link is None or tip_link is None:
        raise InputError("base_link", base_link, "a URDF needs --base-link and --tip-link")
    return _arm_from_urdf(Path(str(urdf)), base_link, tip_link, home_rad)


def _arm_from_urdf(path: Path, base_link: str, tip_link: str, home_rad: FloatArray | None) -> Arm:
    from ikpy.chain import Chain
    from ikpy.link import OriginLink, URDFLink

    from sloshkit.export.urdf import read_urdf

    tree = read_urdf(path)  # validated before any use (sloshkit.export.urdf)
    joints = tree.chain_between(base_link, tip_link)
    movable = [joint for joint in joints if joint.movable]
    if not movable:
        raise InputError("tip_link", tip_link, f"no movable joint between {base_link} and it")
    links = [
        URDFLink(
            name=joint.name,
            origin_translation=list(joint.origin_xyz_m),
            origin_orientation=list(joint.origin_rpy_rad),
            rotation=list(joint.axis) if joint.kind in ("revolute", "continuous") else None,
            translation=list(joint.axis) if joint.kind == "prismatic" else None,
            bounds=(joint.lower, joint.upper),
            use_symbolic_matrix=False,
            joint_type=joint.kind,
        )
        for joint in joints
    ]
    mask = [False] + [joint.movable for joint in joints]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        chain = Chain([OriginLink(), *links], active_links_mask=mask, name=tree.name)
    low = np.asarray([joint.lower for joint in movable])
    high = np.asarray([joint.upper for joint in movable])
    if home_rad is None:
        home = np.where(np.isfinite(low) & np.isfinite(high), (low + high) / 2.0, 0.0)
    else:
        home = np.asarray(home_rad, dtype=float)
        if home.shape != low.shape:
            raise InputError("seed_joints", home.tolist(), f"needs {low.size} joint values")
    return Arm(
        name=tree.name,
        joint_names=tuple(joint.name for joint in movable),
        lower_rad=low,
        upper_rad=high,
        velocity_limit_rad_s=np.asarray([joint.velocity for joint in movable]),
        home_rad=home,
        base_link=base_link,
        tip_link=tip_link,
        chain=chain,
    )
