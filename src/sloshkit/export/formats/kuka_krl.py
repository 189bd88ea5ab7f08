"""``kuka-krl``: a KUKA KRL program (``.src`` with its ``.dat``) of one timed PTP spline block.

Written for KUKA System Software 8.3 or later on a KR C4 (spline motions ``SPTP`` and
``TIME_BLOCK``; KUKA, *KUKA System Software 8.3, Operating and Programming Instructions for
System Integrators*, "Spline block", "TIME_BLOCK", "SPTP"):

- ``<name>.dat``: ``DEFDAT <name>`` with one ``DECL E6AXIS XPi={A1 ..., A6 ..., E1 0, ...}``
  per point (axis angles in degrees, 5 decimals: about the resolution of KRLs single-precision
  ``REAL``), ``ENDDAT``;
- ``<name>.src``: ``DEF <name>( )``, the metadata as ``;`` comments, the approach (``$VEL_AXIS``
  and ``$ACC_AXIS`` at 10 %, ``SPTP XP1``: an exact stop there), then ``PTP_SPLINE`` with
  ``TIME_BLOCK START``, one ``SPTP XPi`` and ``TIME_BLOCK PART = <share in %>`` per segment,
  ``TIME_BLOCK END = <total time in s>`` and ``ENDSPLINE`` (the block ends at rest), ``END``.

Timing: the KR C4 interpolates every 12 ms (the IPO cycle); the point period is a whole
multiple of 12 ms (`CONTROLLER`, default 12 ms). ``TIME_BLOCK`` gives the block's total time
and each segment's share of it; if the axes cannot keep it (speed, acceleration, jerk), the
controller moves slower and says so. One spline block is computed before it starts, so the
whole move is one block and longer moves are refused (`CONTROLLER.max_points`).

Joints: the A1..A6 values are the URDF joint angles in degrees (the built-in ``kr6r900``
follows KUKA's zero positions and directions, A1 positive clockwise seen from above).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.export.formats.common import header_lines
from sloshkit.export.formats.controller import (
    Controller,
    degrees_text,
    program_points,
    times_from_segments,
    write_program,
)
from sloshkit.export.ik import JointPath

FloatArray = NDArray[np.float64]

#: Decimals of the joint angles [deg] written.
JOINT_DECIMALS = 5

#: IPO cycle 12 ms; one point per IPO cycle by default; at most 1000 segments in the one spline
#: block (sloshkit's own cap: the block is planned before the robot starts).
CONTROLLER = Controller("kuka-krl", "KUKA KRL", 0.012, 0.012, 1001, ("kr6r900",))
#: Longest KRL name (24 characters).
NAME_LIMIT = 24
#: Axis speed and acceleration of the approach [% of the maximum].
APPROACH_PERCENT = 10
AXES = ("A1", "A2", "A3", "A4", "A5", "A6")

_AGGREGATE = re.compile(r"\{([^}]*)\}")


@dataclass(frozen=True)
class KrlProgram:
    """A parsed ``.src`` with its ``.dat``.

    Attributes
    ----------
    name : str
        The ``DEF`` name (equal to the ``DEFDAT`` name).
    points : dict
        Point name -> A1..A6 [deg] from the ``.dat`` (``E6AXIS`` or ``AXIS``).
    motions : list of tuple
        (point name or ``"{...}"`` literal, A1..A6 [deg], in a block?, TIME_BLOCK part or None).
    block_time_s : float or None
        ``TIME_BLOCK END`` [s].
    system : dict
        ``$VEL_AXIS[i]`` and ``$ACC_AXIS[i]`` assignments.

    Examples
    --------
    >>> KrlProgram("demo").block_time_s is None
    True
    """

    name: str
    points: dict[str, list[float]] = field(default_factory=dict)
    motions: list[tuple[str, list[float], bool, float | None]] = field(default_factory=list)
    block_time_s: float | None = None
    system: dict[str, float] = field(default_factory=dict)


def dat_path(src: str | Path) -> Path:
    """The ``.dat`` that belongs to a ``.src``.

    Parameters
    ----------
    src : str or pathlib.Path
        The ``.src`` file.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> dat_path("runs/move.src").as_posix()
    'runs/move.dat'
    """
    return Path(src).with_suffix(".dat")


def write_kuka_krl(
    path: str | Path, joints: JointPath, metadata: Mapping[str, object], name: str | None = None
) -> Path:
    """Write ``joints`` (one point per sample) as ``<name>.src`` and ``<name>.dat`` (module
    docstring); returns the ``.src``.

    Parameters
    ----------
    path : output ``.src`` file (the ``.dat`` goes beside it)
    joints : joint samples at the point period (6 joints) [rad]
    metadata : written as ``;`` comments at the top of the ``.src``
    name : the program name (default: the file's stem)

    Returns
    -------
    pathlib.Path

    References
    ----------
    KUKA System Software 8.3, Operating and Programming Instructions for System Integrators:
    spline block ``PTP_SPLINE ... ENDSPLINE``, ``SPTP``, ``TIME_BLOCK START/PART/END``,
    ``E6AXIS``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.048
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_kuka_krl(pathlib.Path(tempfile.mkdtemp()) / "move.src", path, {})
    >>> [line.strip() for line in out.read_text().splitlines() if "END =" in line]
    ['TIME_BLOCK END = 0.096']
    """
    target = Path(path)
    if target.suffix.lower() != ".src":
        raise InputError("out", str(target), "a KRL program is a .src file (its .dat beside it)")
    points = program_points(
        CONTROLLER, target, joints, name, NAME_LIMIT, "a KRL E6AXIS holds 6 axes"
    )
    title, count, segments = points.title, points.count, points.segments_s
    total = float(np.sum(segments))
    externals = ",".join(f"E{axis} 0.0" for axis in range(1, 7))
    data = ["&ACCESS RVP", "&REL 1", f"DEFDAT {title}"]
    for index, row in enumerate(points.degrees, start=1):
        cells = ",".join(
            f"{axis} {degrees_text(value, JOINT_DECIMALS)}"
            for axis, value in zip(AXES, row, strict=True)
        )
        data.append(f"DECL E6AXIS XP{index}={{{cells},{externals}}}")
    data.append("ENDDAT")
    program = [
        "&ACCESS RVP",
        "&REL 1",
        f"DEF {title}( )",
        header_lines(metadata, prefix=";").rstrip("\n"),
        f";approach the first point at {APPROACH_PERCENT} % axis speed, exact stop",
        *[f"$VEL_AXIS[{axis}]={APPROACH_PERCENT}" for axis in range(1, 7)],
        *[f"$ACC_AXIS[{axis}]={APPROACH_PERCENT}" for axis in range(1, 7)],
        "SPTP XP1",
        f";{count - 1} segments timed by TIME_BLOCK, ending at rest",
        "PTP_SPLINE",
        "  TIME_BLOCK START",
    ]
    for index in range(1, count):
        program += [
            f"  SPTP XP{index + 1}",
            f"  TIME_BLOCK PART = {100.0 * segments[index - 1] / total:.9g}",
        ]
    program += [f"  TIME_BLOCK END = {total:.9g}", "ENDSPLINE", "END"]
    write_program(dat_path(target), data)
    return write_program(target, program)


def parse_krl(src_text: str, dat_text: str, source: str = "program") -> KrlProgram:
    """Parse a ``.src``/``.dat`` pair: ``DEF name( ) ... END`` with ``$VEL_AXIS[i]=`` /
    ``$ACC_AXIS[i]=`` assignments, ``SPTP <point or {A1 ..}>``, ``PTP_SPLINE``/``SPLINE`` ...
    ``ENDSPLINE`` blocks holding ``SPTP`` segments and ``TIME_BLOCK START``/``PART = x``/
    ``END = t``; ``DEFDAT name ... ENDDAT`` with ``DECL [GLOBAL] E6AXIS|AXIS name={A1 x, ...}``.
    ``;`` starts a comment, ``&`` lines are editor attributes.

    Parameters
    ----------
    src_text, dat_text : str
        The two files' texts.
    source : str
        The program's name, for messages.

    Returns
    -------
    KrlProgram

    Examples
    --------
    >>> dat = "DEFDAT demo\\nDECL E6AXIS XP1={A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\\nENDDAT\\n"
    >>> src = "DEF demo( )\\nSPTP XP1\\nEND\\n"
    >>> parse_krl(src, dat).motions[0][1]
    [0.0, -90.0, 90.0, 0.0, 0.0, 0.0]
    """
    program = KrlProgram(_module_name(dat_text, "DEFDAT", "ENDDAT", source))
    for line in _code_lines(dat_text)[1:-1]:
        match = re.fullmatch(
            r"DECL\s+(?:GLOBAL\s+)?(E6AXIS|AXIS)\s+([A-Za-z_]\w*)\s*=\s*(\{.*\})", line
        )
        if match:
            program.points[match.group(2)] = _axes(match.group(3), f"{source}.dat {match.group(2)}")
        elif not re.match(r"DECL\s", line):
            raise InputError("file", f"{source}.dat", f"not a declaration: {line[:50]!r}")
    name = _module_name(src_text, "DEF", "END", source)
    if name != program.name:
        raise InputError("file", source, f"DEF {name} but DEFDAT {program.name}")
    in_block, timed, block_time = False, False, None
    motions = program.motions
    for line in _code_lines(src_text)[1:-1]:
        upper = line.upper()
        system = re.fullmatch(r"(\$(?:VEL|ACC)_AXIS\[[1-6]\])\s*=\s*([-+\d.eE]+)", line)
        if system:
            program.system[system.group(1)] = float(system.group(2))
        elif upper in ("PTP_SPLINE", "SPLINE"):
            if in_block:
                raise InputError("file", source, "spline blocks do not nest")
            in_block = True
        elif upper == "ENDSPLINE":
            if not in_block or timed:
                raise InputError("file", source, "ENDSPLINE without its block (or TIME_BLOCK open)")
            in_block = False
        elif upper == "TIME_BLOCK START":
            if not in_block or timed or block_time is not None:
                raise InputError("file", source, "TIME_BLOCK START outside a block or twice")
            timed = True
        elif part := re.fullmatch(r"TIME_BLOCK\s+PART\s*=\s*([-+\d.eE]+)", line, re.I):
            if not timed or not motions or motions[-1][3] is not None or not motions[-1][2]:
                raise InputError("file", source, "TIME_BLOCK PART must follow a timed segment")
            motions[-1] = (*motions[-1][:3], float(part.group(1)))
        elif end := re.fullmatch(r"TIME_BLOCK\s+END\s*=\s*([-+\d.eE]+)", line, re.I):
            if not timed:
                raise InputError("file", source, "TIME_BLOCK END without START")
            timed, block_time = False, float(end.group(1))
        elif move := re.fullmatch(r"SPTP\s+(\{[^}]*\}|[A-Za-z_]\w*)(?:\s+C_SPL)?", line, re.I):
            target = move.group(1)
            if target.startswith("{"):
                axes = _axes(target, source)
            elif target in program.points:
                axes = program.points[target]
            else:
                raise InputError("file", source, f"SPTP {target}, which the .dat does not declare")
            motions.append((target, axes, in_block, None))
        else:
            raise InputError(
                "file", source, f"sloshkit reads SPTP spline programs, not {line[:40]!r}"
            )
    if in_block or timed:
        raise InputError("file", source, "a spline block or TIME_BLOCK is not closed")
    return KrlProgram(program.name, program.points, motions, block_time, program.system)


def _code_lines(text: str) -> list[str]:
    lines = []
    for raw in text.splitlines():
        line = raw.split(";", 1)[0].strip()
        if line and not line.startswith("&"):
            lines.append(line)
    return lines


def _module_name(text: str, opening: str, closing: str, source: str) -> str:
    lines = _code_lines(text)
    pattern = rf"{opening}\s+([A-Za-z_]\w*)" + (
        r"\s*\(\s*\)" if opening == "DEF" else r"(\s+PUBLIC)?"
    )
    match = re.fullmatch(pattern, lines[0], re.I) if lines else None
    if match is None or lines[-1].upper() != closing:
        raise InputError("file", source, f"a KRL {opening} file is {opening} <name> ... {closing}")
    return match.group(1)


def _axes(aggregate: str, where: str) -> list[float]:
    body = _AGGREGATE.fullmatch(aggregate.strip())
    if body is None:
        raise InputError("file", where, f"not an axis aggregate: {aggregate[:40]!r}")
    cells = {}
    for cell in body.group(1).split(","):
        key, _, value = cell.strip().partition(" ")
        try:
            cells[key.upper()] = float(value)
        except ValueError:
            raise InputError("file", where, f"{cell.strip()!r} is not 'A1 <number>'") from None
    missing = [axis for axis in AXES if axis not in cells]
    if missing:
        raise InputError("file", where, "the aggregate lacks " + ", ".join(missing))
    return [cells[axis] for axis in AXES]


def read_kuka_krl(path: str | Path) -> tuple[FloatArray, FloatArray]:
    """Point times [s] and joint angles [rad] of a program written by `write_kuka_krl` (or any
    like it): one approach ``SPTP`` outside a block (t = 0), then one timed spline block.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.src`` file (its ``.dat`` beside it).

    Returns
    -------
    tuple of numpy.ndarray
        Times (points,) [s] and joint angles (points, 6) [rad].

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.048
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_kuka_krl(pathlib.Path(tempfile.mkdtemp()) / "move.src", path, {})
    >>> read_kuka_krl(out)[0].round(9)
    array([0.   , 0.048, 0.096])
    """
    source = Path(path)
    dat = dat_path(source)
    if not dat.is_file():
        raise InputError("file", str(source), f"needs its data list {dat.name} beside it")
    program = parse_krl(
        source.read_text(encoding="utf-8"), dat.read_text(encoding="utf-8"), str(source)
    )
    motions = program.motions
    if len(motions) < 3 or motions[0][2] or not all(motion[2] for motion in motions[1:]):
        raise InputError("file", str(source), "needs an approach SPTP, then one spline block")
    parts = [motion[3] for motion in motions[1:]]
    if program.block_time_s is None or any(part is None or not part > 0.0 for part in parts):
        raise InputError("file", str(source), "every segment needs a TIME_BLOCK PART > 0 and END")
    shares = np.asarray(parts, dtype=float)
    segments = (program.block_time_s * shares / shares.sum()).tolist()
    rows = [motion[1] for motion in motions]
    return times_from_segments(segments), np.radians(np.asarray(rows, dtype=float))


__all__ = ["CONTROLLER", "KrlProgram", "dat_path", "parse_krl", "read_kuka_krl", "write_kuka_krl"]
