"""``fanuc-ls``: a FANUC TP program in ASCII (``.ls``) of timed joint moves.

The program (FANUC, *R-30iB/R-30iB Plus Controller Operator's Manual (Basic Operation)*,
B-83284EN, "Program structure" and "Motion instructions"; the ``.ls`` layout is the one the
controller prints when it saves a program as ASCII) has

- ``/PROG <NAME>`` and the ``/ATTR`` header (owner, comment, sizes, ``LINE_COUNT``,
  ``PROTECT``, the task attributes ``TCD``, ``DEFAULT_GROUP = 1,*,*,*,*``, ``CONTROL_CODE``);
- ``/MN``: remark lines (``!text``, the metadata in pieces of at most `REMARK_WIDTH`
  characters), then ``J P[1] 10% FINE`` (the approach to the start, at 10 % of the joint
  speed), then one ``J P[i] <t>msec CNT100`` per point (joint motion, time-based speed: the
  segment ends ``t`` after the previous point) and ``FINE`` on the last point, so the move stops
  exactly there;
- ``/POS``: every ``P[i]`` in joint representation (``GP1: UF : 0, UT : 1,`` then ``J1=`` to
  ``J6=`` in degrees with 5 decimals: about the single-precision resolution the controller
  stores, while the pendant shows 3; 3 decimals would add a 1.7e-5 rad joint noise that the
  round trip sees as a 7 % change of the residual slosh at 8 ms points) and ``/END``.

Timing: the controller interpolates every ITP, 8 ms on the R-30iA/R-30iB families; a segment
time that is not a whole multiple of the ITP is rounded up to one (about 4 ms per 100 ms point
measured on a 600-point path, which stretches the move), so the point period is a multiple of
8 ms (`CONTROLLER`, default 8 ms: one point per ITP).

Joints: FANUC's J3 is measured from the horizontal, not from the upper arm (the J2/J3
interaction of FANUC arms with a parallel J3 drive), so ``J3 = joint_3 - joint_2`` for the
serial URDF angles (``joint_3 = J3 + J2`` back: the ROS-Industrial ``fanuc_driver``'s
``J23_factor`` = 1). Every other joint is written as it is, in degrees.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.formats.controller import (
    Controller,
    comment_chunks,
    degrees_text,
    program_points,
    times_from_segments,
    write_program,
)
from sloshkit.export.ik import JointPath

FloatArray = NDArray[np.float64]

#: Decimals of the joint angles [deg] written.
JOINT_DECIMALS = 5
JOINT_WIDTH = 12

#: ITP 8 ms; one point per ITP by default (docs/export.md: the measured effect of coarser
#: points); at most 2000 points in one program (sloshkit's
#: own cap, well inside TP memory; the controller's limit is its free TPP memory,
#: STATUS > Memory).
CONTROLLER = Controller("fanuc-ls", "FANUC TP", 0.008, 0.008, 2000, ("lrmate200id",))
#: Longest remark written per line (short enough for the remark field of any TP editor).
REMARK_WIDTH = 32
#: Longest program name (R-30iB; older controllers take 8).
NAME_LIMIT = 36
#: Approach to the first point: joint speed in % of the maximum.
APPROACH_PERCENT = 10

_MOTION = re.compile(
    r"^\s*(\d+):\s*([JLCA])\s+P\[(\d+)(?::[^\]]*)?\]\s+"
    r"(\d+(?:\.\d*)?)\s*(%|msec|sec|mm/sec|cm/min|inch/min|deg/sec)\s+"
    r"(FINE|CNT\d{1,3})\b[^;]*;\s*$"
)
_MOTION_START = re.compile(r"^\s*\d+:\s*[JLCA]\s+P\[")
_REMARK = re.compile(r"^\s*(\d+):\s*!([^;]*);\s*$")
_OTHER = re.compile(r"^\s*(\d+):\s*[^;]*;\s*$")
_ATTR = re.compile(r"^\s*([A-Z_]+)\s*=\s*(.*?);?\s*$")
_JOINT = re.compile(r"J(\d)\s*=\s*(-?\d+(?:\.\d*)?)\s*deg")


@dataclass(frozen=True)
class Motion:
    """One TP motion instruction: ``J P[3] 40msec CNT100``.

    Attributes
    ----------
    line : int
        The /MN line number.
    kind : str
        ``J`` (joint), ``L`` (linear), ``C`` (circular), ``A`` (circle arc).
    position : int
        The position number (``P[position]``).
    speed : float
        Its value.
    unit : str
        ``%``, ``msec``, ``sec``, ``mm/sec``, ``cm/min``, ``inch/min`` or ``deg/sec``.
    termination : str
        ``FINE`` or ``CNTn`` (n in 0..100).

    Examples
    --------
    >>> Motion(3, "J", 3, 40.0, "msec", "CNT100").termination
    'CNT100'
    """

    line: int
    kind: str
    position: int
    speed: float
    unit: str
    termination: str


@dataclass(frozen=True)
class TpProgram:
    """A parsed ``.ls`` program: name, attributes, instructions and joint positions.

    Attributes
    ----------
    name : str
        ``/PROG`` name.
    attributes : dict
        ``/ATTR`` keys and raw values.
    motions : list of Motion
        The motion instructions in order.
    remarks : list of str
        The ``!`` remark texts.
    positions : dict
        Position number -> J1..Jn [deg].

    Examples
    --------
    >>> TpProgram("MOVE", {"LINE_COUNT": "0"}).positions
    {}
    """

    name: str
    attributes: dict[str, str]
    motions: list[Motion] = field(default_factory=list)
    remarks: list[str] = field(default_factory=list)
    positions: dict[int, list[float]] = field(default_factory=dict)


def to_controller_deg(position_rad: FloatArray) -> FloatArray:
    """FANUC joint values [deg] from serial URDF joint angles [rad] (``J3 = q3 - q2``).

    Parameters
    ----------
    position_rad : numpy.ndarray
        (samples, 6) [rad].

    Returns
    -------
    numpy.ndarray
        (samples, 6) [deg].

    Examples
    --------
    >>> to_controller_deg(np.radians([[0, 30, 40, 0, -90, 0]])).round(6).tolist()
    [[0.0, 30.0, 10.0, 0.0, -90.0, 0.0]]
    """
    degrees: FloatArray = np.degrees(np.asarray(position_rad, dtype=float))
    degrees[:, 2] = degrees[:, 2] - degrees[:, 1]
    return degrees


def from_controller_deg(joints_deg: FloatArray) -> FloatArray:
    """Serial URDF joint angles [rad] from FANUC joint values [deg] (``q3 = J3 + J2``).

    Parameters
    ----------
    joints_deg : numpy.ndarray
        (samples, 6) [deg].

    Returns
    -------
    numpy.ndarray
        (samples, 6) [rad].

    Examples
    --------
    >>> np.degrees(from_controller_deg(np.array([[0, 30, 10, 0, -90, 0.0]]))).round(6).tolist()
    [[0.0, 30.0, 40.0, 0.0, -90.0, 0.0]]
    """
    serial = np.array(joints_deg, dtype=float)
    serial[:, 2] = serial[:, 2] + serial[:, 1]
    radians: FloatArray = np.radians(serial)
    return radians


def write_fanuc_ls(
    path: str | Path, joints: JointPath, metadata: Mapping[str, object], name: str | None = None
) -> Path:
    """Write ``joints`` (one point per sample) as a FANUC TP program (module docstring).

    Parameters
    ----------
    path : output ``.ls`` file
    joints : joint samples at the point period (6 joints, serial URDF angles)
    metadata : written as remarks at the top of /MN
    name : the program name (default: the file's stem, upper case)

    Returns
    -------
    pathlib.Path

    References
    ----------
    FANUC, *R-30iB Controller Operator's Manual (Basic Operation)*, B-83284EN, motion
    instructions (``J``, speed in ``msec``, ``FINE``/``CNT``) and position data.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.04
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_fanuc_ls(pathlib.Path(tempfile.mkdtemp()) / "move.ls", path, {})
    >>> [line for line in out.read_text().splitlines() if "P[3]" in line][0]
    '   3:J P[3] 40msec FINE    ;'
    """
    points = program_points(
        CONTROLLER,
        path,
        joints,
        name,
        NAME_LIMIT,
        "a FANUC TP program needs 6",
        upper=True,
        to_degrees=to_controller_deg,
    )
    title, count = points.title, points.count
    milliseconds = np.rint(1e3 * points.segments_s).astype(int)
    # A remark ends at ";" and holds no quotes on older controllers: ";" -> ",", '"' -> "'".
    pieces = comment_chunks(dict(metadata), REMARK_WIDTH)
    remarks = [piece.replace(";", ",").replace('"', "'") for piece in pieces]
    # As the controller prints a program: remarks "  !text ;", motions "J P[i] ...    ;".
    body = [f"  !{text} ;" for text in remarks]
    body.append(f"J P[1] {APPROACH_PERCENT}% FINE    ;")
    for index in range(1, count):
        end = "FINE" if index == count - 1 else "CNT100"
        body.append(f"J P[{index + 1}] {milliseconds[index - 1]}msec {end}    ;")
    main = [f"{number:4d}:{text}" for number, text in enumerate(body, start=1)]
    now = datetime.now(UTC)
    stamp = f"DATE {now:%y-%m-%d}  TIME {now:%H:%M:%S}"
    lines = [
        f"/PROG  {title}",
        "/ATTR",
        "OWNER\t\t= MNEDITOR;",
        'COMMENT\t\t= "sloshkit";',
        "PROG_SIZE\t= 0;",
        f"CREATE\t\t= {stamp};",
        f"MODIFIED\t= {stamp};",
        "FILE_NAME\t= ;",
        "VERSION\t\t= 0;",
        f"LINE_COUNT\t= {len(main)};",
        "MEMORY_SIZE\t= 0;",
        "PROTECT\t\t= READ_WRITE;",
        "TCD:  STACK_SIZE\t= 0,",
        "      TASK_PRIORITY\t= 50,",
        "      TIME_SLICE\t= 0,",
        "      BUSY_LAMP_OFF\t= 0,",
        "      ABORT_REQUEST\t= 0,",
        "      PAUSE_REQUEST\t= 0;",
        "DEFAULT_GROUP\t= 1,*,*,*,*;",
        "CONTROL_CODE\t= 00000000 00000000;",
        "/MN",
        *main,
        "/POS",
    ]
    for index, row in enumerate(points.degrees, start=1):
        cells = [
            f"J{axis}={degrees_text(value, JOINT_DECIMALS):>{JOINT_WIDTH}} deg"
            for axis, value in enumerate(row, start=1)
        ]
        lines += [
            f"P[{index}]{{",
            "   GP1:",
            "\tUF : 0, UT : 1,\t",
            "\t" + ",\t".join(cells[:3]) + ",",
            "\t" + ",\t".join(cells[3:]),
            "};",
        ]
    lines.append("/END")
    return write_program(points.target, lines)


def parse_tp(text: str, source: str = "program") -> TpProgram:
    """Parse an ASCII TP program (module docstring; the grammar of the manual's program
    listing: sections /PROG, /ATTR, /MN, /POS, /END, numbered instruction lines ending in
    ``;``, positions ``P[n]{ GP1: UF : u, UT : t, J1= x deg, ... };``).

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        Its name, for messages.

    Returns
    -------
    TpProgram

    Raises
    ------
    InputError
        For a section out of order, a malformed line, a line-number gap, a LINE_COUNT that
        does not match, or a motion to a position that /POS does not define.

    Examples
    --------
    >>> program = parse_tp(
    ...     "/PROG  A\\n/ATTR\\nLINE_COUNT = 1;\\n/MN\\n   1:J P[1] 100% FINE    ;\\n"
    ...     "/POS\\nP[1]{\\n   GP1:\\n\\tUF : 0, UT : 1,\\n\\tJ1= 1.000 deg, J2= 0.000 deg\\n"
    ...     "};\\n/END\\n"
    ... )
    >>> program.name, program.motions[0].termination, program.positions[1]
    ('A', 'FINE', [1.0, 0.0])
    """
    lines = text.splitlines()
    if not lines or not lines[0].startswith("/PROG"):
        raise InputError("file", source, "a TP program starts with /PROG")
    name = lines[0].split()[1] if len(lines[0].split()) > 1 else ""
    if not re.fullmatch(r"[A-Z][A-Z0-9_]*", name):
        raise InputError("file", source, f"/PROG name {name!r} is not a TP program name")
    program = TpProgram(name, {})
    section, expected_line = "", 1
    position_text: list[str] = []
    ended = False
    for number, line in enumerate(lines[1:], start=2):
        stripped = line.strip()
        if stripped.startswith("/"):
            order = ("/ATTR", "/APPL", "/MN", "/POS", "/END")
            word = stripped.split()[0]
            if word not in order or (section and order.index(word) <= order.index(section)):
                raise InputError("file", f"{source} line {number}", f"section {word} out of order")
            section = word
            ended = word == "/END"
            continue
        if not stripped or section in ("/APPL",):
            continue
        if ended:
            raise InputError("file", f"{source} line {number}", "text after /END")
        if section == "/ATTR":
            match = _ATTR.match(line)
            if match:
                program.attributes[match.group(1)] = match.group(2).strip()
        elif section == "/MN":
            expected_line = _parse_instruction(program, line, expected_line, f"{source} {number}")
        elif section == "/POS":
            position_text.append(line)
        else:
            raise InputError("file", f"{source} line {number}", "text outside a section")
    if not ended:
        raise InputError("file", source, "a TP program ends with /END")
    _parse_positions(program, "\n".join(position_text), source)
    count = program.attributes.get("LINE_COUNT")
    if count is not None and int(count) != expected_line - 1:
        raise InputError("file", source, f"LINE_COUNT {count} but {expected_line - 1} lines")
    missing = sorted({m.position for m in program.motions} - set(program.positions))
    if missing:
        raise InputError("file", source, f"motion to P[{missing[0]}], which /POS does not define")
    return program


def _parse_instruction(program: TpProgram, line: str, expected: int, where: str) -> int:
    for pattern in (_MOTION, _REMARK, _OTHER):
        match = pattern.match(line)
        if match:
            break
    if match is None or (pattern is _OTHER and _MOTION_START.match(line)):
        raise InputError("file", where, f"not a TP instruction line: {line.strip()!r}")
    if int(match.group(1)) != expected:
        raise InputError("file", where, f"line number {match.group(1)}, expected {expected}")
    if pattern is _MOTION:
        termination = match.group(6)
        if termination.startswith("CNT") and int(termination[3:]) > 100:
            raise InputError("file", where, f"{termination}: CNT takes 0..100")
        program.motions.append(
            Motion(
                expected,
                match.group(2),
                int(match.group(3)),
                float(match.group(4)),
                match.group(5),
                termination,
            )
        )
    elif pattern is _REMARK:
        program.remarks.append(match.group(2))
    return expected + 1


def _parse_positions(program: TpProgram, text: str, source: str) -> None:
    blocks = re.findall(r"P\[(\d+)(?::\"[^\"]*\")?\]\s*\{(.*?)\};", text, flags=re.S)
    leftover = re.sub(r"P\[\d+(?::\"[^\"]*\")?\]\s*\{.*?\};", "", text, flags=re.S).strip()
    if leftover:
        raise InputError(
            "file", source, f"/POS holds text outside P[...]{{...}}: {leftover[:40]!r}"
        )
    for index, body in blocks:
        if "GP1" not in body:
            raise InputError("file", source, f"P[{index}] has no group GP1")
        if re.search(r"\b[XYZWPR]\s*=", body):
            raise InputError(
                "file", source, f"P[{index}] is Cartesian; sloshkit reads joint values"
            )
        joints = _JOINT.findall(body)
        axes = [int(axis) for axis, _ in joints]
        if axes != list(range(1, len(axes) + 1)) or not axes:
            raise InputError("file", source, f"P[{index}] needs J1, J2, ... in order (deg)")
        program.positions[int(index)] = [float(value) for _, value in joints]


def read_fanuc_ls(path: str | Path) -> tuple[FloatArray, FloatArray]:
    """Point times [s] and serial joint angles [rad] of a program written by `write_fanuc_ls`
    (or any like it): P[1] at t = 0 (the approach), then each timed joint move.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.ls`` file.

    Returns
    -------
    tuple of numpy.ndarray
        Times (points,) [s] and joint angles (points, 6) [rad].

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.04
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_fanuc_ls(pathlib.Path(tempfile.mkdtemp()) / "move.ls", path, {})
    >>> read_fanuc_ls(out)[0]
    array([0.  , 0.04, 0.08])
    """
    program = parse_tp(Path(path).read_text(encoding="utf-8"), str(path))
    motions = program.motions
    if len(motions) < 3:
        raise InputError("file", str(path), "needs an approach and at least 2 timed moves")
    segments = []
    for motion in motions[1:]:
        if motion.kind != "J" or motion.unit not in ("msec", "sec"):
            raise InputError(
                "file",
                f"{path} line {motion.line}",
                f"{motion.kind} P[{motion.position}] {motion.speed:g}{motion.unit}: the round "
                "trip needs joint moves with a time (msec or sec)",
            )
        segments.append(motion.speed * (1e-3 if motion.unit == "msec" else 1.0))
    if motions[-1].termination != "FINE":
        raise InputError("file", str(path), "the last move must end FINE (at rest)")
    rows = [program.positions[motion.position] for motion in motions]
    if any(len(row) != 6 for row in rows):
        raise InputError("file", str(path), "every position needs J1..J6")
    return times_from_segments(segments), from_controller_deg(np.asarray(rows, dtype=float))


__all__ = [
    "CONTROLLER",
    "Motion",
    "TpProgram",
    "from_controller_deg",
    "parse_tp",
    "read_fanuc_ls",
    "to_controller_deg",
    "write_fanuc_ls",
]
