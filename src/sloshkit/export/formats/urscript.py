"""``urscript``: a URScript program that streams joint samples with ``servoj`` every 2 ms.

The file is one ``def ... end`` block (what the controller's primary and secondary interfaces
run when it is sent to them; in a Polyscope Script node, call the function after loading it),
with the metadata as comments inside it. The program moves to the first sample with
``movej`` (slowly), then calls
``servoj(q, a, v, t, lookahead_time, gain)`` once per sample, ``t`` = 0.002 s (the e-Series
controller period; ``servoj`` blocks for ``t``). Between the approach and the stream it waits
``settle_time_s`` (`sloshkit.export.approach.approach_settle_time`: the approach's slosh decays
below the plan's residual limit), and after the last sample it holds the last target for
``hold_time_s`` (one ``servoj`` with that ``t``, marked ``# hold``) before ``stopj``, so the
servo reaches the last target at rest instead of being stopped while its look-ahead still
lags. ``a`` and ``v`` are not used by the controller (written as 0). Signature and ranges
from the URScript manual (Universal Robots, *The URScript Programming Language*,
e-Series SW 5.x, ``servoj``):
``lookahead_time`` in [0.03, 0.2] s, ``gain`` in [100, 2000]
(`sloshkit.export.servoj.LOOKAHEAD_TIME_RANGE_S`, `sloshkit.export.servoj.GAIN_RANGE`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError, require_in_range
from sloshkit.export.formats.common import header_lines, number
from sloshkit.export.ik import JointPath
from sloshkit.export.servoj import GAIN_RANGE, LOOKAHEAD_TIME_RANGE_S
from sloshkit.files import atomic_open

#: The UR e-Series controller period [s] (500 Hz).
UR_SAMPLE_PERIOD_S = 0.002
#: Approach to the first sample: joint acceleration [rad/s^2] and speed [rad/s] of ``movej``.
APPROACH_ACCELERATION_RAD_S2 = 0.5
APPROACH_SPEED_RAD_S = 0.25
#: The last target is held for this many look-ahead times (at least `MIN_HOLD_S`) before
#: ``stopj``: ``servoj`` tracks its targets with a lag of about the look-ahead time.
HOLD_LOOKAHEADS = 4.0
MIN_HOLD_S = 0.2


def hold_time(lookahead_time_s: float) -> float:
    """How long the program holds its last target before ``stopj`` [s].

    Parameters
    ----------
    lookahead_time_s : float
        The ``servoj`` look-ahead [s].

    Returns
    -------
    float

    Examples
    --------
    >>> hold_time(0.05), hold_time(0.1)
    (0.2, 0.4)
    """
    return max(MIN_HOLD_S, HOLD_LOOKAHEADS * float(lookahead_time_s))


_SERVOJ = re.compile(
    r"^\s*servoj\(\[([^\]]*)\],\s*([^,]+),\s*([^,]+),\s*([^,]+),\s*([^,]+),\s*([^)]+)\)"
)


def write_urscript(
    path: str | Path,
    joints: JointPath,
    metadata: Mapping[str, object],
    lookahead_time_s: float = 0.05,
    gain: float = 500.0,
    name: str = "sloshkit_move",
    settle_time_s: float = 0.0,
    hold_time_s: float | None = None,
) -> Path:
    """Write a URScript program that plays ``joints`` with one ``servoj`` per sample.

    Parameters
    ----------
    path : output ``.script`` file
    joints : joint samples on the 2 ms grid (6 joints, base to wrist 3)
    metadata : written as ``#`` comment lines at the top of the function body
    lookahead_time_s : servoj ``lookahead_time`` [s], 0.03..0.2
    gain : servoj ``gain``, 100..2000
    name : the program's function name
    settle_time_s : wait after the approach ``movej`` [s] (`sleep`)
    hold_time_s : time the last target is held before ``stopj`` [s] (default `hold_time`)

    Returns
    -------
    pathlib.Path

    References
    ----------
    Universal Robots, *The URScript Programming Language*, e-Series, ``servoj``, ``movej``,
    ``stopj``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.002
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_urscript(pathlib.Path(tempfile.mkdtemp()) / "m.script", path, {})
    >>> out.read_text().count("servoj(")  # three samples and the hold
    4
    """
    lookahead = require_in_range("lookahead_time", lookahead_time_s, *LOOKAHEAD_TIME_RANGE_S, "s")
    gain = require_in_range("gain", gain, *GAIN_RANGE)
    period = joints.sample_period_s
    if abs(period - UR_SAMPLE_PERIOD_S) > 1e-12 or joints.position_rad.shape[1] != 6:
        raise InputError(
            "joints",
            f"{joints.position_rad.shape[1]} joints every {period:g} s",
            "URScript needs 6 joints sampled every 0.002 s",
        )
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
        raise InputError("name", name, "must be a URScript identifier")

    def q(row: NDArray[np.float64]) -> str:
        return "[" + ", ".join(number(value) for value in row) + "]"

    lines = [
        f"def {name}():\n",
        header_lines(metadata, prefix="  # "),
        f"  # approach the first sample, then stream {joints.time_s.size} samples every "
        f"{number(period)} s\n",
        f"  movej({q(joints.position_rad[0])}, a={number(APPROACH_ACCELERATION_RAD_S2)}, "
        f"v={number(APPROACH_SPEED_RAD_S)})\n",
    ]
    tail = f", 0, 0, {number(period)}, {number(lookahead)}, {number(gain)})\n"
    settle = float(settle_time_s)
    if not (math.isfinite(settle) and settle >= 0.0):
        raise InputError("settle_time", settle_time_s, "must be a finite time >= 0 s")
    hold = hold_time(lookahead) if hold_time_s is None else float(hold_time_s)
    lines += [
        f"  # wait {number(settle)} s for the slosh of the approach to settle\n",
        f"  sleep({number(settle)})\n",
    ]
    lines += [f"  servoj({q(row)}{tail}" for row in joints.position_rad]
    lines += [
        f"  servoj({q(joints.position_rad[-1])}, 0, 0, {number(hold)}, {number(lookahead)}, "
        f"{number(gain)})  # hold the last target\n",
        "  stopj(2.0)\n",
        "end\n",
    ]
    with atomic_open(path) as handle:
        handle.write("".join(lines))
    return Path(path)


def read_urscript(path: str | Path) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Times [s] and joint positions [rad] of the ``servoj`` calls of a program, in order.

    Each ``servoj`` holds its target for its own ``t``; sample k is at the sum of the earlier
    ``t``.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    tuple of numpy.ndarray
        Times [s] and joint positions (samples, 6) [rad].

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.002
    >>> path = JointPath(t, np.zeros((3, 6)), np.zeros((3, 6)), np.zeros((3, 6)), tuple("abcdef"))
    >>> out = write_urscript(pathlib.Path(tempfile.mkdtemp()) / "m.script", path, {})
    >>> read_urscript(out)[0]
    array([0.   , 0.002, 0.004])
    """
    rows, holds = [], []
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        if line.rstrip().endswith("# hold the last target"):
            continue  # at rest on the last sample: not a sample of the move
        match = _SERVOJ.match(line)
        if match:
            rows.append([float(cell) for cell in match.group(1).split(",")])
            holds.append(float(match.group(4)))
    if not rows:
        raise InputError("file", str(path), "has no servoj calls")
    times = np.concatenate([[0.0], np.cumsum(holds[:-1])])
    return times, np.asarray(rows, dtype=float)
