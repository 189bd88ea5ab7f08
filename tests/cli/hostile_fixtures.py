"""Fixture files of the 3-D and export families of the hostile-input table (issue 16).

Pose files (``p_*.csv``), waypoint files (``w_*``), 1-D plan files (``plan_*.csv``) and URDF
files (``u_*.urdf``) written by `make_spatial_fixtures`; `tests/cli/test_hostile_inputs.py`
calls it next to its own fixtures. A good file of each kind is there so that a case can break
one option at a time.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

POSE_HEADER = "t,x,y,z,qx,qy,qz,qw"


def _quintic(u: np.ndarray) -> np.ndarray:
    return np.asarray(10 * u**3 - 15 * u**4 + 6 * u**5)


def _pose_rows(count: int = 31, duration_s: float = 0.6, distance_m: float = 0.05) -> list[list]:
    """A rest-to-rest quintic move along x, container upright (identity quaternion)."""
    t = np.linspace(0.0, duration_s, count)
    x = distance_m * _quintic(t / duration_s)
    return [
        [f"{a:.6f}", f"{b:.9f}", "0", "0", "0", "0", "0", "1"] for a, b in zip(t, x, strict=True)
    ]


def _csv(header: str, rows: list[list], separator: str = ",") -> str:
    return header + "\n" + "".join(separator.join(row) + "\n" for row in rows)


def _with(rows: list[list], row: int, column: int, value: str) -> list[list]:
    changed = [list(r) for r in rows]
    changed[row][column] = value
    return changed


def _pose_files() -> dict[str, str]:
    rows = _pose_rows()
    rpy_rows = [[*r[:4], "0", "0", "0"] for r in rows]
    backwards = [list(r) for r in rows]
    backwards[10][0], backwards[11][0] = backwards[11][0], backwards[10][0]
    duplicate = [list(r) for r in rows]
    duplicate[12][0] = duplicate[11][0]
    # Two rows 10^7 s apart: a grid at 1 ms would need 10^10 samples.
    long_rows = [rows[0], ["1", *rows[0][1:]], ["10000000", *rows[-1][1:]]]
    tiny = [[f"{k * 1e-12:.3e}", *r[1:]] for k, r in enumerate(rows)]
    hours = [[f"{k * 100}", *r[1:]] for k, r in enumerate(rows)]
    return {
        "p_good.csv": _csv(POSE_HEADER, rows),
        "p_nan_x.csv": _csv(POSE_HEADER, _with(rows, 5, 1, "nan")),
        "p_nan_q.csv": _csv(POSE_HEADER, _with(rows, 5, 7, "NaN")),
        "p_inf_z.csv": _csv(POSE_HEADER, _with(rows, 7, 3, "inf")),
        "p_zero_q.csv": _csv(POSE_HEADER, _with(rows, 9, 7, "0")),
        "p_nonunit_q.csv": _csv(POSE_HEADER, [[*r[:7], "2"] for r in rows]),
        "p_backwards_t.csv": _csv(POSE_HEADER, backwards),
        "p_dup_t.csv": _csv(POSE_HEADER, duplicate),
        "p_one_row.csv": _csv(POSE_HEADER, rows[:1]),
        "p_header_only.csv": POSE_HEADER + "\n",
        "p_no_header.csv": "".join(",".join(r) + "\n" for r in rows),
        "p_t_kg.csv": _csv("t [kg],x,y,z,qx,qy,qz,qw", rows),
        "p_x_s.csv": _csv("t,x [s],y,z,qx,qy,qz,qw", rows),
        "p_roll_m.csv": _csv("t,x,y,z,roll [m],pitch,yaw", rpy_rows),
        "p_unit_markup.csv": _csv("t [[/red]],x,y,z,qx,qy,qz,qw", rows),
        "p_no_orientation.csv": _csv("t,x,y,z", [r[:4] for r in rows]),
        "p_partial_q.csv": _csv("t,x,y,z,qx,qy,qz", [r[:7] for r in rows]),
        "p_no_time.csv": _csv("x,y,z,qx,qy,qz,qw", [r[1:] for r in rows]),
        "p_text.csv": _csv(POSE_HEADER, _with(rows, 4, 2, "abc")),
        "p_ragged.csv": _csv(POSE_HEADER, [*rows[:3], rows[3][:5], *rows[4:]]),
        "p_mixed_separators.csv": "t;x;y;z;qx;qy;qz;qw\n"
        + "".join(",".join(r) + "\n" for r in rows),
        "p_semicolon_bad.csv": _csv("t;x;y;z;qx;qy;qz;qw", _with(rows, 3, 1, "1,2,3"), ";"),
        "p_huge_position.csv": _csv(POSE_HEADER, _with(rows, 15, 1, "1e300")),
        "p_long.csv": _csv(POSE_HEADER, long_rows),
        "p_tiny_step.csv": _csv(POSE_HEADER, tiny),
        "p_hours.csv": _csv("t [h],x,y,z,qx,qy,qz,qw", hours),
        "p_bom_bad.csv": "\ufeff" + _csv(POSE_HEADER, _with(rows, 2, 0, "x")),
        "p_binary.csv": "",
        "p_latin1.csv": "",
    }


def _waypoint_files() -> dict[str, str]:
    good = "x [mm],y [mm],z [mm]\n0,0,0\n100,0,0\n100,100,0\n"
    return {
        # issue 30: millimetres without a unit (300 m), a yaw of 1e9 deg
        "w_mm_as_m.csv": "x,y,z\n0,0,0\n150,0,0\n150,150,0\n",
        "w_mm_as_m.toml": "waypoints = [[0, 0, 0], [150, 0, 0], [150, 150, 0]]\n",
        "w_yaw_huge.csv": "x,y,z,yaw [deg]\n0,0,0,0\n0.1,0,0,1e9\n0.1,0.1,0,0\n",
        "w_yaw_huge.toml": "waypoints = [[0, 0, 0], [0.1, 0, 0]]\nyaw_deg = [0, 1e9]\n",
        "w_yaw_rad_huge.csv": "x,y,z,yaw\n0,0,0,0\n0.1,0,0,100\n",
        "w_yaw_nan.toml": "waypoints = [[0, 0, 0], [0.1, 0, 0]]\nyaw_deg = [0, nan]\n",
        "w_repeat.csv": "x,y,z\n0,0,0\n0.1,0,0\n0.1,0,0\n0.2,0,0\n",
        "w_back.csv": "x,y,z\n0,0,0\n0.1,0,0\n0,0,0\n",
        "w_good.csv": good,
        "w_nan.csv": good.replace("100,0,0", "nan,0,0"),
        "w_inf.csv": good.replace("100,0,0", "inf,0,0"),
        "w_one.csv": "x,y,z\n0,0,0\n",
        "w_same.csv": "x,y,z\n0.1,0,0\n0.1,0,0\n0.1,0,0\n",
        "w_unit_s.csv": good.replace("x [mm]", "x [s]"),
        "w_no_z.csv": "x,y\n0,0\n0.1,0\n",
        "w_huge.csv": "x,y,z\n0,0,0\n1e300,0,0\n",
        "w_text.toml": 'waypoints = "abc"\n',
        "w_short_rows.toml": "waypoints = [[0, 0], [1, 0]]\n",
        "w_mixed.toml": 'waypoints = [[0, 0, 0], [0.1, 0, "a"]]\n',
        "w_nan.toml": "waypoints = [[0, 0, 0], [nan, 0, 0]]\n",
        "w_bool.toml": "waypoints = [[0, 0, 0], [true, 0, 0]]\n",
        "w_yaw_length.toml": "waypoints = [[0, 0, 0], [0.1, 0, 0]]\nyaw_deg = [0, 1, 2]\n",
        "w_yaw_text.toml": 'waypoints = [[0, 0, 0], [0.1, 0, 0]]\nyaw_deg = "abc"\n',
        "w_missing.toml": "path = [[0, 0, 0], [0.1, 0, 0]]\n",
        "w_invalid.toml": "waypoints = [[0, 0, 0\n",
        "w_deep.toml": "waypoints = " + "[" * 5000 + "]" * 5000 + "\n",
        "w_ragged.toml": "waypoints = [[0, 0, 0], [0.1, 0, 0, 0]]\n",
    }


def _plan_files() -> dict[str, str]:
    t = np.arange(0.0, 1.0 + 1e-9, 0.004)
    u = t / 1.0
    x = 0.5 * _quintic(u)
    v = 0.5 * (30 * u**2 - 60 * u**3 + 30 * u**4)
    a = 0.5 * (60 * u - 180 * u**2 + 120 * u**3)
    header = "t_s,position_m,velocity_m_s,acceleration_m_s2"
    rows = [[f"{c:.9g}" for c in row] for row in zip(t, x, v, a, strict=True)]
    backwards = [list(r) for r in rows]
    backwards[50][0] = "0.1"
    big = "".join(",".join(row) + "\n" for row in rows) * 40  # 10,000 rows, ~500 kB
    return {
        "plan_good.csv": _csv(header, rows),
        "plan_good.script": _csv(header, rows),  # a plan named like a URScript program
        "plan_user.csv": _csv(header, rows),
        "plan_user.poses.csv": "my own notes, not written by sloshkit\n",
        "plan_user.script": "def my_program():\n  movej([0, 0, 0, 0, 0, 0])\nend\n",
        "plan_big.csv": header + "\n" + big,
        "plan_huge_position.csv": _csv(header, _with(rows, 30, 1, "1e300")),
        "plan_mm.csv": _csv(
            "t [ms],position [mm],velocity [mm/s],acceleration [mm/s^2]",
            [[f"{1e3 * float(r[0]):.9g}", *(f"{1e3 * float(c):.9g}" for c in r[1:])] for r in rows],
        ),
        "plan_nan.csv": _csv(header, _with(rows, 30, 1, "nan")),
        "plan_one_row.csv": _csv(header, rows[:1]),
        "plan_backwards.csv": _csv(header, backwards),
        "plan_missing_column.csv": _csv("t_s,position_m", [r[:2] for r in rows]),
        "plan_poses_nan.csv": _csv(POSE_HEADER, _with(_pose_rows(), 3, 5, "nan")),
    }


BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lollollollollollollollollollol">
 <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
 <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
 <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
 <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
 <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
 <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<robot name="&lol9;"><link name="base"/></robot>
"""

EXTERNAL_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<robot name="r"><link name="&secret;"/></robot>
"""


_REVOLUTE = (
    '<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
    '<origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>'
    '<limit lower="-3" upper="3" velocity="3"/></joint>'
)


def _arm(joints: list[str], links: tuple[str, ...] = ("base", "a", "tool")) -> str:
    return (
        '<?xml version="1.0"?>\n<robot name="r">'
        + "".join(f'<link name="{link}"/>' for link in links)
        + "".join(joints)
        + "</robot>\n"
    )


def _broken(old: str, new: str) -> str:
    """The two-joint arm with one piece of its first joint replaced."""
    joint = _REVOLUTE.format(name="j1", parent="base", child="a")
    assert old in joint, old
    return _arm([joint.replace(old, new, 1), _REVOLUTE.format(name="j2", parent="a", child="tool")])


def _chain(count: int) -> str:
    links = ("base", *[f"l{k}" for k in range(1, count)], "tool")
    return _arm(
        [_REVOLUTE.format(name=f"j{k}", parent=links[k], child=links[k + 1]) for k in range(count)],
        links,
    )


def _urdf_files() -> dict[str, str]:
    cycle = _arm(
        [
            _REVOLUTE.format(name="jt", parent="b", child="tool"),
            _REVOLUTE.format(name="j1", parent="a", child="b"),
            _REVOLUTE.format(name="j2", parent="b", child="a"),
        ],
        ("base", "a", "b", "tool"),
    )
    two_parents = _arm(
        [
            _REVOLUTE.format(name="j1", parent="base", child="a"),
            _REVOLUTE.format(name="j2", parent="a", child="tool"),
            _REVOLUTE.format(name="j3", parent="base", child="tool"),
        ]
    )
    return {
        "u_laughs.urdf": BILLION_LAUGHS,
        "u_external.urdf": EXTERNAL_ENTITY,
        "u_not_xml.urdf": "this is not XML <robot\n",
        "u_no_joints.urdf": '<?xml version="1.0"?>\n<robot name="r"><link name="a"/></robot>\n',
        "u_good.urdf": _broken('type="revolute"', 'type="revolute"'),
        # issue 30, family 1: each exited 3 (or hung) before the URDF was checked
        "u_cycle.urdf": cycle,
        "u_no_child.urdf": _broken('<child link="a"/>', ""),
        "u_no_joint_name.urdf": _broken('name="j1" ', ""),
        "u_no_link_name.urdf": _arm(
            [_REVOLUTE.format(name="j1", parent="base", child="tool")], ("base", "tool")
        ).replace('<link name="tool"/>', '<link name="tool"/><link/>'),
        "u_no_type.urdf": _broken(' type="revolute"', ""),
        "u_lower_abc.urdf": _broken('lower="-3"', 'lower="abc"'),
        "u_floating.urdf": _broken('type="revolute"', 'type="floating"'),
        "u_origin_nan.urdf": _broken('xyz="0 0 0.1"', 'xyz="nan 0 0.1"'),
        "u_origin_huge.urdf": _broken('xyz="0 0 0.1"', 'xyz="1e308 0 0.1"'),
        "u_velocity_nan.urdf": _broken('velocity="3"', 'velocity="nan"'),
        "u_chain50.urdf": _chain(50),
        "u_name_quote.urdf": _broken('name="j1"', "name=\"j1', 'j0\""),
        "u_name_comma.urdf": _broken('name="j1"', 'name="j1,x"'),
        # new instances of the family
        "u_two_parents.urdf": two_parents,
        "u_duplicate_joint.urdf": _arm(
            [
                _REVOLUTE.format(name="j1", parent="base", child="a"),
                _REVOLUTE.format(name="j1", parent="a", child="tool"),
            ]
        ),
        "u_duplicate_link.urdf": _broken('type="revolute"', 'type="revolute"').replace(
            '<link name="a"/>', '<link name="a"/><link name="a"/>'
        ),
        "u_planar.urdf": _broken('type="revolute"', 'type="planar"'),
        "u_unknown_parent.urdf": _broken('<parent link="base"/>', '<parent link="ghost"/>'),
        "u_no_parent.urdf": _broken('<parent link="base"/>', ""),
        "u_origin_inf.urdf": _broken('rpy="0 0 0"', 'rpy="0 inf 0"'),
        "u_origin_text.urdf": _broken('xyz="0 0 0.1"', 'xyz="0 0"'),
        "u_axis_zero.urdf": _broken('<axis xyz="0 0 1"/>', '<axis xyz="0 0 0"/>'),
        "u_axis_text.urdf": _broken('<axis xyz="0 0 1"/>', '<axis xyz="z"/>'),
        "u_lower_above_upper.urdf": _broken('lower="-3"', 'lower="4"'),
        "u_upper_inf.urdf": _broken('upper="3"', 'upper="inf"'),
        "u_velocity_negative.urdf": _broken('velocity="3"', 'velocity="-1"'),
        "u_velocity_zero.urdf": _broken('velocity="3"', 'velocity="0"'),
        "u_name_newline.urdf": _broken('name="j1"', 'name="j1&#10;x"'),
        "u_name_unicode.urdf": _broken('name="j1"', 'name="gelenk_\u00e4"'),
        "u_name_space.urdf": _broken('name="j1"', 'name="joint 1"'),
        "u_name_yaml.urdf": _broken('name="j1"', 'name="j1: [x]"'),
        "u_self_loop.urdf": _broken('<child link="a"/>', '<child link="base"/>'),
        "u_chain12.urdf": _chain(12),
        "u_root_tag.urdf": '<?xml version="1.0"?>\n<sdf><link name="base"/></sdf>\n',
        "u_big.urdf": "<robot name='r'>" + "<!-- padding -->" * 600_000 + "</robot>",
    }


def make_spatial_fixtures(folder: Path) -> None:
    """Write the pose, waypoint, plan and URDF fixture files into ``folder``.

    Parameters
    ----------
    folder : Path
        The table's working folder.

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> make_spatial_fixtures(folder)
    >>> (folder / "p_good.csv").read_text().splitlines()[0]
    't,x,y,z,qx,qy,qz,qw'
    """
    for files in (_pose_files(), _waypoint_files(), _plan_files(), _urdf_files()):
        for name, text in files.items():
            (folder / name).write_text(text, encoding="utf-8")
    many = _pose_rows(count=12_400, duration_s=12.4)  # ~600 kB: above --max-memory 1MiB / 8
    (folder / "p_big.csv").write_text(_csv(POSE_HEADER, many), encoding="utf-8")
    (folder / "p_binary.csv").write_bytes(b"t,x,y,z,qx,qy,qz,qw\n" + bytes(range(256)) * 8)
    (folder / "p_latin1.csv").write_bytes(
        ("t [\u00b5s],x,y,z,qx,qy,qz,qw\n" + "0,0,0,0,0,0,0,1\n1,0,0,0,0,0,0,1\n").encode("latin-1")
    )
