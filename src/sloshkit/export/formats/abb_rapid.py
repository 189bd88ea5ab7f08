"""``abb-rapid``: an ABB RAPID program module (``.mod``) of timed ``MoveAbsJ`` moves.

The module (ABB, *Technical reference manual - RAPID Instructions, Functions and Data types*,
3HAC050917-001: ``MoveAbsJ``, ``jointtarget``, ``zonedata``, ``speeddata``) holds

- the metadata as ``!`` comment lines;
- ``CONST jointtarget <name>_q{N} := [...]``: every point, ``[[rax_1, ..., rax_6], [9E9, ...]]``
  (robot axes in degrees, 5 decimals; 9E9 = no external axis);
- ``PROC <name>_move()``: ``MoveAbsJ <name>_q{1}\\NoEOffs, v100, fine, tool0;`` (the approach),
  then ``MoveAbsJ <name>_q{i}\\NoEOffs, v1000\\T:=<t>, z0, tool0;`` per point (``\\T``: the
  move takes ``t`` seconds, whatever the speed data say; zone ``z0`` so the robot flies by
  every point) and ``fine`` on the last, so the move stops exactly there.

Timing: the IRC5/OmniCore motion planner interpolates the path every 4 ms (the period EGM
and the path planner run at); the point period is a whole multiple of 4 ms (`CONTROLLER`,
default 4 ms). RAPID ``num`` is a single-precision float: 5 decimals of a degree are about
its resolution. A program pointer that cannot keep ahead of very short segments
stops the robot with "50024 Corner path failure": raise ``--sample-period`` then.

Joints: the robax values are the URDF joint angles in degrees (the built-in ``irb120``
follows ABB's zero positions and directions).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

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

#: Path interpolation every 4 ms; one point per 4 ms by default; at most 5000 points per
#: module (sloshkit's own cap; the controller's limit is its program memory).
CONTROLLER = Controller("abb-rapid", "ABB RAPID", 0.004, 0.004, 5000, ("irb120",))
#: Longest RAPID identifier (``<name>_move`` must fit).
NAME_LIMIT = 27
#: An external axis that is not there.
NO_AXIS = 9e9

_TOKEN = re.compile(
    r"\s*(?:(?P<number>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)|(?P<name>[A-Za-z_]\w*)"
    r"|(?P<string>\"[^\"]*\")|(?P<mark>[\[\],]))"
)


@dataclass(frozen=True)
class MoveAbsJ:
    """One ``MoveAbsJ`` instruction.

    Attributes
    ----------
    target : str or list
        The data name (``p50``, ``path_q{3}``) or a literal ``[[...], [...]]``.
    speed : str
        The speed data (``v1000``).
    time_s : float or None
        ``\\T`` [s], if given.
    zone : str
        The zone data (``fine``, ``z0``, ``z50``).
    tool : str
        The tool data.
    switches : tuple of str
        ``Conc``, ``NoEOffs``, ...

    Examples
    --------
    >>> MoveAbsJ("p50", "v1000", 5.0, "fine", "tool0", ("NoEOffs",)).time_s
    5.0
    """

    target: Any
    speed: str
    time_s: float | None
    zone: str
    tool: str
    switches: tuple[str, ...] = ()


@dataclass(frozen=True)
class RapidModule:
    """A parsed module: name, data declarations and the MoveAbsJ of each routine.

    Attributes
    ----------
    name : str
        ``MODULE`` name.
    data : dict
        Name -> (storage, type, value) for every ``CONST``/``PERS``/``VAR`` declaration.
    routines : dict
        ``PROC`` name -> its MoveAbsJ instructions in order.

    Examples
    --------
    >>> RapidModule("demo").routines
    {}
    """

    name: str
    data: dict[str, tuple[str, str, Any]] = field(default_factory=dict)
    routines: dict[str, list[MoveAbsJ]] = field(default_factory=dict)


def write_abb_rapid(
    path: str | Path, joints: JointPath, metadata: Mapping[str, object], name: str | None = None
) -> Path:
    """Write ``joints`` (one point per sample) as a RAPID module (module docstring).

    Parameters
    ----------
    path : output ``.mod`` file
    joints : joint samples at the point period (6 joints) [rad]
    metadata : written as ``!`` comments at the top of the module
    name : the module name (default: the file's stem)

    Returns
    -------
    pathlib.Path

    References
    ----------
    ABB, *RAPID Instructions, Functions and Data types*, 3HAC050917-001, ``MoveAbsJ``
    (arguments ``ToJointPos [\\NoEOffs] Speed [\\T] Zone Tool``) and ``jointtarget``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.04
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_abb_rapid(pathlib.Path(tempfile.mkdtemp()) / "move.mod", path, {})
    >>> [line.strip() for line in out.read_text().splitlines() if "move_q{3}\\\\" in line][0]
    'MoveAbsJ move_q{3}\\\\NoEOffs, v1000\\\\T:=0.04, fine, tool0;'
    """
    points = program_points(
        CONTROLLER, path, joints, name, NAME_LIMIT, "a RAPID jointtarget holds 6"
    )
    title, count, segments = points.title, points.count, points.segments_s
    externals = ",".join(["9E9"] * 6)
    rows = [
        "    [["
        + ",".join(degrees_text(value, JOINT_DECIMALS) for value in row)
        + f"],[{externals}]]"
        for row in points.degrees
    ]
    lines = [f"MODULE {title}", header_lines(metadata, prefix="  ! ").rstrip("\n")]
    lines += [f"  CONST jointtarget {title}_q{{{count}}} := [", ",\n".join(rows) + "];"]
    lines += [
        f"  PROC {title}_move()",
        f"    ! approach the first point, then {count - 1} timed moves",
        f"    MoveAbsJ {title}_q{{1}}\\NoEOffs, v100, fine, tool0;",
    ]
    for index in range(1, count):
        zone = "fine" if index == count - 1 else "z0"
        lines.append(
            f"    MoveAbsJ {title}_q{{{index + 1}}}\\NoEOffs, v1000\\T:={segments[index - 1]:.6g}, "
            f"{zone}, tool0;"
        )
    lines += ["  ENDPROC", "ENDMODULE"]
    return write_program(points.target, lines)


def parse_rapid(text: str, source: str = "module") -> RapidModule:
    """Parse a RAPID module: ``MODULE ... ENDMODULE``, data declarations
    ``CONST|PERS|VAR type name[{n}] [:= value];``, routines ``PROC name() ... ENDPROC`` whose
    statements are ``MoveAbsJ`` instructions (other instructions are refused: sloshkit reads
    straight-line motion programs). ``!`` starts a comment.

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        Its name, for messages.

    Returns
    -------
    RapidModule

    Examples
    --------
    >>> module = parse_rapid(
    ...     "MODULE m\\n CONST jointtarget p := [[1,2,3,4,5,6],[9E9,9,9,9,9,9]];\\n PROC go()\\n"
    ...     "  MoveAbsJ p\\\\NoEOffs, v1000\\\\T:=5, fine, tool0;\\n ENDPROC\\nENDMODULE\\n"
    ... )
    >>> module.routines["go"][0].time_s, module.data["p"][2][0][:2]
    (5.0, [1.0, 2.0])
    """
    clean = "\n".join(_strip_comment(line) for line in text.splitlines())
    match = re.fullmatch(
        r"\s*MODULE\s+([A-Za-z]\w*)(?:\s*\([^)]*\))?(.*)\bENDMODULE\s*", clean, re.S
    )
    if match is None:
        raise InputError("file", source, "a RAPID module is MODULE <name> ... ENDMODULE")
    module = RapidModule(match.group(1))
    body = match.group(2)
    for routine in re.finditer(r"\bPROC\s+([A-Za-z]\w*)\s*\(\s*\)(.*?)\bENDPROC\b", body, re.S):
        module.routines[routine.group(1)] = [
            _parse_move(statement.strip(), f"{source} PROC {routine.group(1)}")
            for statement in routine.group(2).split(";")
            if statement.strip()
        ]
    declarations = re.sub(r"\bPROC\b.*?\bENDPROC\b", "", body, flags=re.S)
    if re.search(r"\b(PROC|FUNC|TRAP|ENDPROC)\b", declarations):
        raise InputError("file", source, "unbalanced PROC ... ENDPROC (or FUNC/TRAP routines)")
    for statement in declarations.split(";"):
        if statement.strip():
            _parse_declaration(module, statement.strip(), source)
    return module


def _strip_comment(line: str) -> str:
    inside = False
    for index, char in enumerate(line):
        if char == '"':
            inside = not inside
        elif char == "!" and not inside:
            return line[:index]
    return line


def _parse_declaration(module: RapidModule, statement: str, source: str) -> None:
    match = re.fullmatch(
        r"(CONST|PERS|VAR)\s+([A-Za-z]\w*)\s+([A-Za-z]\w*)\s*(?:\{\s*(\d+)\s*\})?\s*"
        r"(?::=\s*(.*))?",
        statement,
        re.S,
    )
    if match is None:
        raise InputError("file", source, f"not a RAPID data declaration: {statement[:50]!r}")
    storage, kind, name, size, value = match.groups()
    if storage == "CONST" and value is None:
        raise InputError("file", source, f"CONST {name} needs a value")
    parsed = None if value is None else _aggregate(value, f"{source} {name}")
    if size is not None and (not isinstance(parsed, list) or len(parsed) != int(size)):
        length = len(parsed) if isinstance(parsed, list) else "no"
        raise InputError("file", source, f"{name}{{{size}}} is given {length} values")
    module.data[name] = (storage, kind, parsed)


def _aggregate(text: str, where: str) -> Any:
    tokens: list[tuple[str, str]] = []
    position = 0
    text = text.strip()
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None or match.end() == position:
            raise InputError("file", where, f"cannot read the value at {text[position:][:20]!r}")
        kind = match.lastgroup or ""
        tokens.append((kind, match.group(kind)))
        position = match.end()
        while position < len(text) and text[position].isspace():
            position += 1

    def value(index: int) -> tuple[Any, int]:
        kind, token = tokens[index]
        if kind == "number":
            return float(token), index + 1
        if kind in ("name", "string"):
            return token, index + 1
        if token != "[":
            raise InputError("file", where, f"unexpected {token!r}")
        items: list[Any] = []
        index += 1
        while tokens[index][1] != "]":
            item, index = value(index)
            items.append(item)
            if tokens[index][1] == ",":
                index += 1
            elif tokens[index][1] != "]":
                raise InputError("file", where, f"expected , or ] not {tokens[index][1]!r}")
        return items, index + 1

    try:
        parsed, end = value(0)
    except IndexError:
        raise InputError("file", where, "unbalanced [ ]") from None
    if end != len(tokens):
        raise InputError("file", where, "text after the value")
    return parsed


def _parse_move(statement: str, where: str) -> MoveAbsJ:
    match = re.fullmatch(r"MoveAbsJ\s+(.*)", statement, re.S)
    if match is None:
        word = statement.split()[0] if statement.split() else statement
        raise InputError("file", where, f"{word}: sloshkit reads MoveAbsJ programs only")
    arguments = _split_arguments(match.group(1))
    switches: list[str] = []
    while arguments and re.fullmatch(r"\\(Conc)", arguments[0]):
        switches.append(arguments.pop(0)[1:])
    if len(arguments) < 4:
        raise InputError(
            "file", where, f"MoveAbsJ needs ToJointPos, Speed, Zone, Tool: {statement!r}"
        )
    target_text, *target_switches = _optionals(arguments[0])
    speed, *speed_options = _optionals(arguments[1])
    zone, *_ = _optionals(arguments[2])
    tool, *_ = _optionals(arguments[3])
    switches += [option.split(":=")[0] for option in target_switches]
    time_s = None
    for option in speed_options:
        key, _, setting = option.partition(":=")
        if key == "T":
            time_s = float(setting)
        elif key != "V":
            raise InputError("file", where, f"\\{key} is not a MoveAbsJ speed option")
    target: Any = (
        _aggregate(target_text, where)
        if target_text.startswith("[")
        else target_text.replace(" ", "")
    )
    if not re.fullmatch(r"v\d+|vmax|[A-Za-z]\w*", speed) or not re.fullmatch(r"[A-Za-z]\w*", zone):
        raise InputError("file", where, f"speed {speed!r} or zone {zone!r} is not a data name")
    return MoveAbsJ(target, speed, time_s, zone, tool, tuple(switches))


def _split_arguments(text: str) -> list[str]:
    parts, depth, current = [], 0, ""
    for char in text:
        depth += char in "[{("
        depth -= char in "]})"
        if char == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += char
    parts.append(current.strip())
    return parts


def _optionals(argument: str) -> list[str]:
    """``name\\opt1\\opt2:=x`` -> [name, opt1, opt2:=x] (``\\`` outside brackets)."""
    depth, pieces, current = 0, [], ""
    for char in argument:
        depth += char in "[{("
        depth -= char in "]})"
        if char == "\\" and depth == 0:
            pieces.append(current.strip())
            current = ""
        else:
            current += char
    pieces.append(current.strip())
    return [piece.replace(" ", "") if index else piece for index, piece in enumerate(pieces)]


def read_abb_rapid(path: str | Path) -> tuple[FloatArray, FloatArray]:
    """Point times [s] and joint angles [rad] of a module written by `write_abb_rapid` (or any
    like it: one routine, an approach ``MoveAbsJ`` then moves with ``\\T``, ending ``fine``).

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.mod`` file.

    Returns
    -------
    tuple of numpy.ndarray
        Times (points,) [s] and joint angles (points, 6) [rad].

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.04
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_abb_rapid(pathlib.Path(tempfile.mkdtemp()) / "move.mod", path, {})
    >>> read_abb_rapid(out)[0]
    array([0.  , 0.04, 0.08])
    """
    module = parse_rapid(Path(path).read_text(encoding="utf-8"), str(path))
    if len(module.routines) != 1:
        raise InputError("file", str(path), f"needs one PROC, has {len(module.routines)}")
    (moves,) = module.routines.values()
    if len(moves) < 3:
        raise InputError("file", str(path), "needs an approach and at least 2 timed moves")
    segments = []
    for index, move in enumerate(moves[1:], start=2):
        if move.time_s is None or not move.time_s > 0.0:
            raise InputError("file", f"{path} MoveAbsJ {index}", "the round trip needs \\T:=t > 0")
        segments.append(move.time_s)
    if moves[-1].zone != "fine":
        raise InputError("file", str(path), "the last MoveAbsJ must end fine (at rest)")
    rows = [_robax(module, move.target, str(path)) for move in moves]
    return times_from_segments(segments), np.radians(np.asarray(rows, dtype=float))


def _robax(module: RapidModule, target: Any, source: str) -> list[float]:
    if isinstance(target, str):
        element = re.fullmatch(r"([A-Za-z]\w*)(?:\{(\d+)\})?", target)
        if element is None or element.group(1) not in module.data:
            raise InputError("file", source, f"MoveAbsJ to {target}, which is not declared")
        value = module.data[element.group(1)][2]
        if element.group(2) is not None:
            index = int(element.group(2))
            if not 1 <= index <= len(value):
                raise InputError("file", source, f"{target} is outside the array")
            value = value[index - 1]
    else:
        value = target
    if (
        not isinstance(value, list)
        or len(value) != 2
        or not isinstance(value[0], list)
        or len(value[0]) != 6
        or not all(isinstance(cell, float) for cell in value[0])
    ):
        raise InputError("file", source, f"{target} is not a jointtarget [[6 axes], [6 external]]")
    return list(value[0])


__all__ = [
    "CONTROLLER",
    "MoveAbsJ",
    "RapidModule",
    "parse_rapid",
    "read_abb_rapid",
    "write_abb_rapid",
]
