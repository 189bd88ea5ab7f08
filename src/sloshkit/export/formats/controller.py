"""What the industrial-robot program formats share: the controller's timing, program size and the
interpolation of its points for the round trip.

An industrial controller does not stream setpoints from a file: it runs a program of timed joint
moves (FANUC TP ``J P[i] 40msec CNT100``, RAPID ``MoveAbsJ ... \\T:=0.04``, KRL ``SPTP`` in a
``TIME_BLOCK``) and interpolates between the points at its own interpolation period (FANUC ITP
8 ms, ABB 4 ms, KUKA IPO 12 ms). sloshkit therefore writes one point per *point period*, a whole
multiple of that interpolation period (a FANUC segment time that is not a multiple of the ITP is
rounded up to one, which stretches the move), and the round trip rebuilds the motion the points
describe: they are joined by the quintic spline at rest at both ends
(`sloshkit.export.ik.joint_derivatives`' interpolation), sampled on a grid that holds every
interpolation instant (the interpolation period subdivided to `ROUND_TRIP_STEP_S`, so that the
re-simulation's own step error stays below the round trip's tolerance), and that motion is
re-simulated against the plan sampled on the same grid. The controllers' own blending between
points (CNT100, zones, spline segments) is proprietary; what the round trip checks is that the
written points, joined smoothly at the controller's rate, keep the planned slosh.
"""

from __future__ import annotations

import re
import typing
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.files import atomic_open
from sloshkit.motion.sampling import steps_to_reach

if typing.TYPE_CHECKING:
    from sloshkit.export.ik import JointPath

FloatArray = NDArray[np.float64]

#: Relative tolerance on "a whole multiple of the interpolation period".
PERIOD_TOLERANCE = 1e-9
#: Longest step of the round trip's re-simulation [s]: the joined points are sampled at the
#: interpolation period divided by the smallest whole number that brings it to this or below
#: (8 ms -> 2 ms), so every interpolation instant is on the grid and the simulation's own
#: discretisation, about (omega dt)^2 / 24 on a peak (`sloshkit.export.roundtrip`), stays below
#: the round trip's limit tolerance (1.5e-4 at 4.7 Hz and 2 ms against 2.4e-3 at 8 ms).
ROUND_TRIP_STEP_S = 0.002


@dataclass(frozen=True)
class Controller:
    """Timing and size rules of one robot-program format.

    Attributes
    ----------
    format : str
        The export format name (``fanuc-ls``).
    language : str
        The controller language, for messages.
    interpolation_period_s : float
        The controller's interpolation period [s]; point periods are whole multiples of it.
    default_period_s : float
        The point period used when ``--sample-period`` is not given [s].
    max_points : int
        Most points written into one program (longer moves are refused).
    robots : tuple of str
        The built-in arms of this vendor (`sloshkit.export.kinematics.robot_names`).

    Examples
    --------
    >>> rule = Controller("demo", "Demo", 0.008, 0.04, 100, ("arm",))
    >>> rule.default_period_s / rule.interpolation_period_s
    5.0
    """

    format: str
    language: str
    interpolation_period_s: float
    default_period_s: float
    max_points: int
    robots: tuple[str, ...]

    @property
    def round_trip_step_s(self) -> float:
        """The round trip's grid [s]: the interpolation period over the smallest whole number
        that brings it to `ROUND_TRIP_STEP_S` or below."""
        return self.interpolation_period_s / steps_to_reach(
            self.interpolation_period_s, ROUND_TRIP_STEP_S
        )

    def point_period(self, requested_s: float | None) -> float:
        """The point period [s]: the default, or ``requested_s`` if it is a whole multiple of
        the interpolation period (`InputError` naming ``--sample-period`` otherwise).

        Parameters
        ----------
        requested_s : float or None
            ``--sample-period`` [s].

        Returns
        -------
        float

        Examples
        --------
        >>> Controller("demo", "Demo", 0.008, 0.04, 100, ()).point_period(0.024)
        0.024
        """
        if requested_s is None:
            return self.default_period_s
        steps = requested_s / self.interpolation_period_s
        whole = round(steps)
        if whole < 1 or abs(steps - whole) > PERIOD_TOLERANCE * max(1.0, steps):
            itp = 1e3 * self.interpolation_period_s
            raise InputError(
                "sample_period",
                f"{1e3 * requested_s:g}ms",
                f"{self.format} points must be a whole multiple of the {self.language} "
                f"interpolation period {itp:g} ms (e.g. {1e3 * self.default_period_s:g}ms)",
            )
        return whole * self.interpolation_period_s

    def check_size(self, points: int, period_s: float) -> None:
        """Refuse a move of more than `max_points` points, naming the shortest point period
        that would fit (`InputError` on ``sample_period``).

        Parameters
        ----------
        points : int
            Points of the move at ``period_s``.
        period_s : float
            The point period [s].

        Examples
        --------
        >>> Controller("demo", "Demo", 0.008, 0.04, 100, ()).check_size(100, 0.04)
        """
        if points <= self.max_points:
            return
        duration = (points - 1) * period_s
        steps = steps_to_reach(duration / (self.max_points - 1), self.interpolation_period_s)
        shortest = steps * self.interpolation_period_s
        raise InputError(
            "sample_period",
            f"{1e3 * period_s:g}ms",
            f"the {duration:.4g} s move needs {points} points, more than the {self.max_points} "
            f"that {self.format} writes into one program",
            f"use --sample-period {1e3 * shortest:g}ms or longer, or split the move into "
            "shorter plans",
        )

    def check_robot(self, robot_name: str, built_in: tuple[str, ...]) -> None:
        """Refuse a built-in arm of another vendor (a URDF arm is accepted: its joints must
        follow the controller's zero positions and directions).

        Parameters
        ----------
        robot_name : str
            The arm's name.
        built_in : tuple of str
            All built-in arm names.

        Examples
        --------
        >>> Controller("demo", "Demo", 0.008, 0.04, 100, ("arm",)).check_robot("arm", ("arm",))
        """
        if robot_name in built_in and robot_name not in self.robots:
            raise InputError(
                "robot",
                robot_name,
                f"{self.format} is a {self.language} program: use "
                + ", ".join(self.robots)
                + " or --urdf with an arm of that vendor",
            )


def program_name(stem: str, limit: int, upper: bool = False) -> str:
    """A program or module name from a file stem: letters, digits and ``_``, starting with a
    letter, at most ``limit`` characters (`InputError` on ``out`` otherwise).

    Parameters
    ----------
    stem : str
        The output file's stem.
    limit : int
        The language's longest name.
    upper : bool
        Upper-case it (FANUC program names are upper case).

    Returns
    -------
    str

    Examples
    --------
    >>> program_name("move_1", 36, upper=True)
    'MOVE_1'
    """
    if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", stem) or len(stem) > limit:
        raise InputError(
            "out",
            stem,
            f"the file name (without suffix) becomes the program name: a letter, then letters, "
            f"digits or _, at most {limit} characters",
        )
    return stem.upper() if upper else stem


@dataclass(frozen=True)
class ProgramPoints:
    """What every robot-program writer starts from (`program_points`).

    Attributes
    ----------
    target : pathlib.Path
        The program file.
    title : str
        The program or module name.
    count : int
        Number of points (the approach point, then one per timed move).
    degrees : numpy.ndarray
        Joint angles (count, 6) in the controller's convention [deg].
    segments_s : numpy.ndarray
        Durations of the count - 1 timed moves [s].

    Examples
    --------
    >>> ProgramPoints(Path("m.ls"), "M", 1, np.zeros((1, 6)), np.zeros(0)).count
    1
    """

    target: Path
    title: str
    count: int
    degrees: FloatArray
    segments_s: FloatArray


def program_points(
    controller: Controller,
    path: str | Path,
    joints: JointPath,
    name: str | None,
    name_limit: int,
    six_joints: str,
    *,
    upper: bool = False,
    to_degrees: Callable[[FloatArray], FloatArray] = np.degrees,
) -> ProgramPoints:
    """The skeleton every vendor writer shares: the program name (``name`` or the file's stem),
    six joints, the controller's size rule (`Controller.check_size`), the angles in degrees
    and the segment times.

    Parameters
    ----------
    controller : Controller
        The format's rules.
    path : str or pathlib.Path
        The program file.
    joints : JointPath
        Joint samples at the point period [rad].
    name : str or None
        The program name (default: from the file's stem, `program_name`).
    name_limit : int
        The language's longest name.
    six_joints : str
        What the error says when ``joints`` has not six joints (the language's own words).
    upper : bool
        Upper-case the name from the stem.
    to_degrees : callable
        Serial joint angles [rad] -> the controller's angles [deg] (FANUC couples J2 and J3).

    Returns
    -------
    ProgramPoints

    Examples
    --------
    >>> from sloshkit.export.ik import JointPath
    >>> rules = Controller("demo", "Demo", 0.004, 0.004, 100, ())
    >>> t = np.arange(3) * 0.004
    >>> zeros = np.zeros((3, 6))
    >>> samples = JointPath(t, zeros, zeros, zeros, tuple("abcdef"))
    >>> points = program_points(rules, "move.mod", samples, None, 20, "needs 6")
    >>> points.title, points.count, points.segments_s.round(6).tolist()
    ('move', 3, [0.004, 0.004])
    """
    target = Path(path)
    title = name or program_name(target.stem, name_limit, upper=upper)
    count = joints.time_s.size
    if joints.position_rad.shape[1] != 6:
        raise InputError("joints", joints.position_rad.shape[1], six_joints)
    controller.check_size(count, joints.sample_period_s)
    return ProgramPoints(
        target, title, count, to_degrees(joints.position_rad), segment_times(joints.time_s)
    )


def write_program(target: str | Path, lines: Iterable[str]) -> Path:
    r"""Write a program's lines (empty ones left out), all or nothing (`atomic_open`).

    Parameters
    ----------
    target : str or pathlib.Path
        The file.
    lines : iterable of str
        Its lines, without newlines.

    Returns
    -------
    pathlib.Path
        ``target``.

    Examples
    --------
    >>> import tempfile
    >>> out = write_program(Path(tempfile.mkdtemp()) / "m.mod", ["MODULE m", "", "ENDMODULE"])
    >>> out.read_text()
    'MODULE m\nENDMODULE\n'
    """
    with atomic_open(target) as handle:
        handle.write("\n".join(line for line in lines if line) + "\n")
    return Path(target)


def segment_times(time_s: FloatArray) -> FloatArray:
    """Durations of the segments between consecutive points [s].

    Parameters
    ----------
    time_s : numpy.ndarray
        Point times [s].

    Returns
    -------
    numpy.ndarray

    Examples
    --------
    >>> segment_times(np.array([0.0, 0.04, 0.08]))
    array([0.04, 0.04])
    """
    return np.diff(np.asarray(time_s, dtype=float))


def times_from_segments(segments_s: list[float]) -> FloatArray:
    """Point times [s] from the segment durations that lead to points 2..N (point 1 at 0).

    Parameters
    ----------
    segments_s : list of float
        Segment durations [s].

    Returns
    -------
    numpy.ndarray

    Examples
    --------
    >>> times_from_segments([0.04, 0.04])
    array([0.  , 0.04, 0.08])
    """
    return np.concatenate([[0.0], np.cumsum(np.asarray(segments_s, dtype=float))])


def interpolate_points(
    time_s: FloatArray, position_rad: FloatArray, period_s: float
) -> tuple[FloatArray, FloatArray]:
    """Joint points joined by the quintic spline at rest at both ends, sampled every
    ``period_s`` (the controller's interpolation period) from the first point to the last.

    Parameters
    ----------
    time_s : numpy.ndarray
        Point times [s] (increasing; their span a whole multiple of ``period_s``).
    position_rad : numpy.ndarray
        (points, joints) joint positions [rad].
    period_s : float
        Interpolation period [s].

    Returns
    -------
    tuple of numpy.ndarray
        Times (uniform, step ``period_s``) [s] and joint positions [rad].

    References
    ----------
    C. de Boor, *A Practical Guide to Splines*, Springer (2001), ch. XIII; scipy
    ``make_interp_spline`` with zero first and second derivatives at both ends (the
    interpolation of `sloshkit.export.ik.joint_derivatives`).

    Examples
    --------
    >>> t = np.arange(5) * 0.04
    >>> s = t / t[-1]
    >>> q = (s**3 * (10 - 15 * s + 6 * s**2))[:, None]
    >>> grid, joints = interpolate_points(t, q, 0.008)
    >>> grid.size, bool(np.allclose(joints[::5], q))
    (21, True)
    """
    from scipy.interpolate import make_interp_spline

    times = np.asarray(time_s, dtype=float)
    position = np.asarray(position_rad, dtype=float)
    if times.size < 3 or np.any(np.diff(times) <= 0.0):
        raise InputError(
            "file", f"{times.size} points", "needs at least 3 points, increasing in time"
        )
    count = round(float(times[-1] - times[0]) / period_s)
    grid = times[0] + np.arange(count + 1, dtype=float) * period_s
    rest = np.zeros(position.shape[1:])
    spline = make_interp_spline(
        times, position, k=5, bc_type=([(1, rest), (2, rest)], [(1, rest), (2, rest)])
    )
    return grid, np.asarray(spline(np.clip(grid, times[0], times[-1])), dtype=float)


def degrees_text(value: float, decimals: int) -> str:
    """A joint angle [deg] with ``decimals`` decimals, never ``-0.00...``.

    Parameters
    ----------
    value : float
        The angle [deg].
    decimals : int
        Decimals written.

    Returns
    -------
    str

    Examples
    --------
    >>> degrees_text(-1e-9, 5), degrees_text(-12.345678, 5)
    ('0.00000', '-12.34568')
    """
    text = f"{value:.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def comment_chunks(metadata: dict[str, object], width: int) -> list[str]:
    """``key: value`` metadata as text pieces of at most ``width`` characters (for languages
    whose comment lines are short, e.g. FANUC TP remarks).

    Parameters
    ----------
    metadata : dict
        Keys and values.
    width : int
        Longest piece.

    Returns
    -------
    list of str

    Examples
    --------
    >>> comment_chunks({"robot": "lrmate200id", "note": "a b"}, 12)
    ['robot:', 'lrmate200id', 'note: a b']
    """
    pieces: list[str] = []
    for key, value in metadata.items():
        words = f"{key}: {' '.join(str(value).split())}".split(" ")
        line = ""
        for word in words:
            while len(word) > width:
                if line:
                    pieces.append(line)
                    line = ""
                pieces.append(word[:width])
                word = word[width:]
            candidate = f"{line} {word}" if line else word
            if len(candidate) > width:
                pieces.append(line)
                line = word
            else:
                line = candidate
        if line:
            pieces.append(line)
    return pieces
