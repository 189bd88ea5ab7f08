"""ikpy's kinematic chain with its forward kinematics and geometric Jacobian compiled.

ikpy (P. Manceron, *IKPy*, https://github.com/Phylliade/ikpy) builds each link's transform
from Python lists on every call; in the IK of an exported trajectory (a few forward passes per
sample, thousands of samples) that was most of the time. `CompiledChain` is ikpy's ``Chain``
(its URDF links, bounds and inverse kinematics unchanged) whose ``forward_kinematics``
multiplies the same transforms in a numba loop: per URDF joint, the origin translation, the
origin roll-pitch-yaw rotation (extrinsic x, y, z: Rz(yaw) Ry(pitch) Rx(roll)), then the joint's
rotation about its axis (Rodrigues' formula) or translation along it (ROS URDF XML
specification, http://wiki.ros.org/urdf/XML/joint). ikpy's inverse kinematics calls this
``forward_kinematics``, so it speeds up too. The tests check both against ikpy's own
``Chain.forward_kinematics`` and a finite-difference Jacobian.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from ikpy.chain import Chain
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: Joint kinds in `CompiledChain.kinds`.
FIXED_JOINT, REVOLUTE_JOINT, PRISMATIC_JOINT = 0, 1, 2


def _frames(origins: Any, axes: Any, kinds: Any, joints: Any, out: Any) -> None:
    """Every link's frame in the base frame into ``out`` (L, 4, 4) for one full joint vector:
    F_l = F_(l-1) O_l J_l(q_l), O_l the link's fixed origin transform and J_l the joint's
    rotation about its unit axis (Rodrigues' formula, as ikpy's ``axis_rotation_matrix``) or
    translation along it. Written as scalar loops for numba."""
    parent = np.eye(4)
    local = np.empty((4, 4))
    joint = np.eye(4)
    for link in range(origins.shape[0]):
        for row in range(4):
            for col in range(4):
                joint[row, col] = 1.0 if row == col else 0.0
        kind, value = kinds[link], joints[link]
        x, y, z = axes[link, 0], axes[link, 1], axes[link, 2]
        if kind == 1:
            c, s = math.cos(value), math.sin(value)
            v = 1.0 - c
            joint[0, 0] = x * x + (1.0 - x * x) * c
            joint[0, 1] = x * y * v - z * s
            joint[0, 2] = x * z * v + y * s
            joint[1, 0] = x * y * v + z * s
            joint[1, 1] = y * y + (1.0 - y * y) * c
            joint[1, 2] = y * z * v - x * s
            joint[2, 0] = x * z * v - y * s
            joint[2, 1] = y * z * v + x * s
            joint[2, 2] = z * z + (1.0 - z * z) * c
        elif kind == 2:
            joint[0, 3], joint[1, 3], joint[2, 3] = x * value, y * value, z * value
        for row in range(4):  # local = O_l J_l
            for col in range(4):
                total = 0.0
                for k in range(4):
                    total += origins[link, row, k] * joint[k, col]
                local[row, col] = total
        for row in range(4):  # F_l = F_(l-1) local
            for col in range(4):
                total = 0.0
                for k in range(4):
                    total += parent[row, k] * local[k, col]
                out[link, row, col] = total
        for row in range(4):
            for col in range(4):
                parent[row, col] = out[link, row, col]


def _tips(origins: Any, axes: Any, kinds: Any, joints: Any) -> Any:
    """The last link's frame (N, 4, 4) for full joint vectors (N, L)."""
    links = origins.shape[0]
    scratch = np.empty((links, 4, 4))
    tips = np.empty((joints.shape[0], 4, 4))
    for sample in range(joints.shape[0]):
        _frames_kernel(origins, axes, kinds, joints[sample], scratch)
        tips[sample] = scratch[links - 1]
    return tips


def _jacobian_tip(origins: Any, axes: Any, kinds: Any, active: Any, joints: Any) -> Any:
    """The geometric Jacobian (6, active) of the last frame's origin and that frame (4, 4):
    a revolute joint's column is [a x (p_tip - p_joint); a], a prismatic one's [a; 0], a the
    joint's axis in the base frame (Siciliano et al., *Robotics*, Springer 2009, eq. 3.30)."""
    links = origins.shape[0]
    frames = np.empty((links, 4, 4))
    _frames_kernel(origins, axes, kinds, joints, frames)
    last = links - 1
    jacobian = np.zeros((6, active.size))
    for column in range(active.size):
        link = active[column]
        axis = np.zeros(3)
        for row in range(3):
            for k in range(3):
                axis[row] += frames[link, row, k] * axes[link, k]
        if kinds[link] == 2:
            jacobian[0, column], jacobian[1, column], jacobian[2, column] = axis
        else:
            rx = frames[last, 0, 3] - frames[link, 0, 3]
            ry = frames[last, 1, 3] - frames[link, 1, 3]
            rz = frames[last, 2, 3] - frames[link, 2, 3]
            jacobian[0, column] = axis[1] * rz - axis[2] * ry
            jacobian[1, column] = axis[2] * rx - axis[0] * rz
            jacobian[2, column] = axis[0] * ry - axis[1] * rx
            jacobian[3, column], jacobian[4, column], jacobian[5, column] = axis
    return jacobian, frames[last].copy()


def _compiled(function: Callable[..., Any]) -> Callable[..., Any]:
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - numba is a dependency
        return function
    compiled: Callable[..., Any] = njit(cache=True)(function)
    return compiled


_frames_kernel = _compiled(_frames)
_tips_kernel = _compiled(_tips)
_jacobian_tip_kernel = _compiled(_jacobian_tip)


class CompiledChain(Chain):  # type: ignore[misc]
    """ikpy's ``Chain`` whose forward kinematics runs compiled (see the module).

    Parameters
    ----------
    links : list
        ikpy links (``OriginLink``, then ``URDFLink`` per URDF joint).
    *args, **kwargs
        The rest of ikpy's ``Chain`` arguments (``active_links_mask``, ``name``).

    Attributes
    ----------
    origins : (L, 4, 4) each link's fixed origin transform (ikpy's translation, then rpy)
    axes : (L, 3) each joint's axis in its own frame (zeros for a fixed one)
    kinds : (L,) `FIXED_JOINT`, `REVOLUTE_JOINT` or `PRISMATIC_JOINT`

    Examples
    --------
    >>> from ikpy.link import OriginLink, URDFLink
    >>> link = URDFLink("j", origin_translation=[0.0, 0.0, 0.1], origin_orientation=[0, 0, 0],
    ...     rotation=[0, 0, 1], use_symbolic_matrix=False)
    >>> tool = URDFLink("t", origin_translation=[0.2, 0.0, 0.0], origin_orientation=[0, 0, 0],
    ...     joint_type="fixed", use_symbolic_matrix=False)
    >>> chain = CompiledChain([OriginLink(), link, tool], active_links_mask=[False, True, False])
    >>> chain.forward_kinematics([0.0, np.pi / 2, 0.0])[:3, 3].round(6)  # the tool turned to +y
    array([0. , 0.2, 0.1])
    """

    def __init__(self, links: list[Any], *args: Any, **kwargs: Any) -> None:
        super().__init__(links, *args, **kwargs)
        count = len(self.links)
        self.origins = np.tile(np.eye(4), (count, 1, 1))
        self.axes = np.zeros((count, 3))
        self.kinds = np.zeros(count, dtype=np.int64)
        for index, link in enumerate(self.links):
            if link.joint_type == "fixed" and not hasattr(link, "origin_translation"):
                continue  # ikpy's OriginLink: the identity
            self.origins[index] = _origin(link.origin_translation, link.origin_orientation)
            if link.joint_type in ("revolute", "continuous"):
                self.kinds[index] = REVOLUTE_JOINT
                self.axes[index] = np.asarray(link.rotation, dtype=float)
            elif link.joint_type == "prismatic":
                self.kinds[index] = PRISMATIC_JOINT
                self.axes[index] = np.asarray(link.translation, dtype=float)

    def forward_kinematics(
        self, joints: Any, full_kinematics: bool = False, backend: str = "numpy"
    ) -> Any:
        """ikpy's ``Chain.forward_kinematics`` (the tip frame, or every link's with
        ``full_kinematics``), compiled; ``backend`` other than numpy goes to ikpy's."""
        if backend != "numpy":
            return super().forward_kinematics(joints, full_kinematics, backend)
        full = np.asarray(joints, dtype=float)
        if full.shape != (len(self.links),):
            raise ValueError(
                f"Your joints vector length is {full.size} but you have {len(self.links)} links"
            )
        frames = np.empty((full.size, 4, 4))
        _frames_kernel(self.origins, self.axes, self.kinds, full, frames)
        return list(frames) if full_kinematics else frames[-1]

    def tip_frames(self, joints: FloatArray) -> FloatArray:
        """The tip frames (N, 4, 4) of full joint vectors (N, L), one compiled loop.

        Parameters
        ----------
        joints : (N, L) joint values of every link (inactive ones included) [rad, m]

        Returns
        -------
        numpy.ndarray
            T_base_tip of each row.

        Examples
        --------
        >>> from sloshkit.export.kinematics import load_arm
        >>> chain = load_arm("ur5e").chain
        >>> chain.tip_frames(np.zeros((2, len(chain.links))))[:, :3, 3].round(4)
        array([[-0.8172, -0.2329,  0.0628],
               [-0.8172, -0.2329,  0.0628]])
        """
        full = np.ascontiguousarray(np.atleast_2d(joints), dtype=float)
        result: FloatArray = _tips_kernel(self.origins, self.axes, self.kinds, full)
        return result

    def jacobian_and_tip(self, joints: FloatArray) -> tuple[FloatArray, FloatArray]:
        """The geometric Jacobian (6, active joints) of the tip and the tip frame (4, 4) of a
        full joint vector: rows vx, vy, vz [m/rad], wx, wy, wz [-] (Siciliano et al.,
        *Robotics*, Springer 2009, eq. 3.30; doi:10.1007/978-1-84628-642-1).

        Parameters
        ----------
        joints : (L,) joint values of every link [rad, m]

        Returns
        -------
        tuple
            J with [v; omega] = J q' over the active joints, and T_base_tip.

        Examples
        --------
        >>> from sloshkit.export.kinematics import load_arm
        >>> chain = load_arm("ur5e").chain
        >>> jacobian, tip = chain.jacobian_and_tip(np.zeros(len(chain.links)))
        >>> jacobian.shape, jacobian[3:, 0].round(6).tolist()  # the base joint turns about z
        ((6, 6), [0.0, 0.0, 1.0])
        """
        active = np.flatnonzero(np.asarray(self.active_links_mask, dtype=bool))
        full = np.ascontiguousarray(joints, dtype=float)
        jacobian, tip = _jacobian_tip_kernel(self.origins, self.axes, self.kinds, active, full)
        return jacobian, tip


def _origin(translation: Any, orientation: Any) -> FloatArray:
    """A URDF joint's origin transform: translation xyz, then the rotation of roll, pitch, yaw
    about the fixed x, y, z axes, Rz(yaw) Ry(pitch) Rx(roll) (ROS URDF specification)."""
    roll, pitch, yaw = (float(value) for value in orientation)
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    frame = np.eye(4)
    frame[:3, :3] = np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )
    frame[:3, 3] = np.asarray(translation, dtype=float)
    return frame


__all__ = ["FIXED_JOINT", "PRISMATIC_JOINT", "REVOLUTE_JOINT", "CompiledChain"]
