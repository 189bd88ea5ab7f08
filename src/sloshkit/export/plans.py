"""The plans export reads: 1-D slide moves and 3-D container pose streams, and their resampling.

- A 1-D plan is the CSV ``sloshkit plan --out`` writes: ``t_s, position_m, velocity_m_s,
  acceleration_m_s2[, jerk_m_s3]`` on a uniform grid. Between samples it is the quintic Hermite
  polynomial matching position, velocity and acceleration at both ends (exact for the
  polynomial laws, C2 for all), so resampling keeps the samples' own derivatives.
- A pose stream is the container's bottom-centre pose: CSV ``t,x,y,z,qx,qy,qz,qw`` (SI, world
  z up, quaternion container-to-world with the scalar last), optionally preceded by ``# key:
  value`` metadata lines; in memory a `sloshkit.motion.poses.PoseTrajectory` with the
  metadata beside it (`PoseStream`). Resampling interpolates the positions with a quintic
  spline at rest at both ends (as `sloshkit.motion.laws.from_samples`) and the orientations
  with scipy's ``RotationSpline`` (C2 in angular rate).

A 1-D plan becomes a pose stream along ``axis`` (a unit vector of the path frame) with the
container upright.

A plan file written by ``sloshkit plan --out`` starts with a ``# sloshkit-plan: {json}`` line
(`sloshkit.export.headers`), so that ``export`` checks the plan against what it was made for.
An export refuses a plan that does not start and end at rest (`require_rest`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import BPoly, make_interp_spline
from scipy.spatial.transform import Rotation, RotationSpline

from sloshkit.errors import InputError, require_positive
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.sampling import steps_to_reach

FloatArray = NDArray[np.float64]

LINE_COLUMNS = ("t_s", "position_m", "velocity_m_s", "acceleration_m_s2")


@dataclass(frozen=True, eq=False)
class LinePlan:
    """A 1-D move sampled on a uniform grid (SI).

    Attributes
    ----------
    time_s, position_m, velocity_m_s, acceleration_m_s2 : samples [s, m, m/s, m/s^2]
    source : where the plan came from (file name or description)
    metadata : ``key: value`` pairs carried to the exported files

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(3) * 0.5
    >>> plan = LinePlan(t, 0.1 * t, 0.1 + 0 * t, 0 * t, source="demo")
    >>> plan.sample_period_s, plan.duration_s
    (0.5, 1.0)
    """

    time_s: FloatArray
    position_m: FloatArray
    velocity_m_s: FloatArray
    acceleration_m_s2: FloatArray
    source: str = ""
    metadata: dict[str, str] = field(default_factory=dict)

    @property
    def sample_period_s(self) -> float:
        """The sample period [s]."""
        return float(self.time_s[1] - self.time_s[0])

    @property
    def duration_s(self) -> float:
        """Time of the last sample [s]."""
        return float(self.time_s[-1])

    def resample(self, sample_period_s: float) -> LinePlan:
        """The plan at t = k Ts up to the first sample at or after the end (at rest after it),
        interpolated by quintic Hermite polynomials (position, velocity and acceleration of the
        samples at both ends of every interval; scipy ``BPoly.from_derivatives``).

        Parameters
        ----------
        sample_period_s : new sample period [s]

        Returns
        -------
        LinePlan

        References
        ----------
        C. de Boor, *A Practical Guide to Splines*, Springer (2001), ch. II (Hermite
        interpolation).

        Examples
        --------
        >>> t = np.arange(5) * 0.25
        >>> plan = LinePlan(t, t**2, 2 * t, 2 + 0 * t)
        >>> plan.resample(0.1).position_m[:3].round(6)
        array([0.  , 0.01, 0.04])
        """
        period = require_positive("sample_period", sample_period_s, "s")
        count = steps_to_reach(self.duration_s, period)
        times = np.arange(count + 1, dtype=float) * period
        position, velocity, acceleration = self.evaluate(times)
        return LinePlan(times, position, velocity, acceleration, self.source, dict(self.metadata))

    def evaluate(self, time_s: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Position [m], velocity [m/s] and acceleration [m/s^2] at any times (the quintic
        Hermite interpolant of `resample`; after the last sample the last values hold, with
        the position extrapolated by nothing: the plan ends at rest)."""
        derivatives = np.column_stack([self.position_m, self.velocity_m_s, self.acceleration_m_s2])
        curve = BPoly.from_derivatives(self.time_s, derivatives[:, :, None].tolist())
        times = np.asarray(time_s, dtype=float)
        inside = np.clip(times, self.time_s[0], self.duration_s)
        position = np.asarray(curve(inside), dtype=float).ravel()
        velocity = np.asarray(curve.derivative(1)(inside), dtype=float).ravel()
        acceleration = np.asarray(curve.derivative(2)(inside), dtype=float).ravel()
        after = times > self.duration_s
        velocity[after] = self.velocity_m_s[-1]
        acceleration[after] = self.acceleration_m_s2[-1]
        return position, velocity, acceleration


@dataclass(frozen=True, eq=False)
class PoseStream:
    """A 3-D plan for export: container poses on a uniform grid with the export's metadata.

    The poses are one `sloshkit.motion.poses.PoseTrajectory` (bottom centre [m], orientation
    container -> world, scalar last, validated and sign-continuous); beside it the stream keeps
    what the exported files carry (``source``, ``metadata``) and, for a 1-D plan, the plan and
    its direction (``line``, ``axis``), so that resampling uses the plan's own derivatives.

    Attributes
    ----------
    poses : the sampled poses
    source : where the stream came from
    metadata : ``key: value`` pairs carried to the exported files
    line : the 1-D plan the stream was made from, if any
    axis : unit vector of the 1-D plan's direction in the path frame, if any

    Examples
    --------
    >>> import numpy as np
    >>> from sloshkit.motion.poses import PoseTrajectory
    >>> upright = np.tile([0, 0, 0, 1.0], (3, 1))
    >>> stream = PoseStream(PoseTrajectory(np.arange(3) * 0.5, np.zeros((3, 3)), upright))
    >>> stream.sample_period_s, stream.resample(0.25).time_s.tolist()
    (0.5, [0.0, 0.25, 0.5, 0.75, 1.0])
    """

    poses: PoseTrajectory
    source: str = ""
    metadata: dict[str, str] = field(default_factory=dict)
    line: LinePlan | None = None
    axis: FloatArray | None = None

    @property
    def time_s(self) -> FloatArray:
        """Sample times (N,) [s]."""
        return self.poses.time_s

    @property
    def position_m(self) -> FloatArray:
        """Container bottom centre (N, 3) [m]."""
        return self.poses.position_m

    @property
    def quaternion_xyzw(self) -> FloatArray:
        """Container-to-world rotation (N, 4), scalar last, sign-continuous."""
        return self.poses.quaternion_xyzw

    @property
    def sample_period_s(self) -> float:
        """The sample period [s]."""
        return float(self.time_s[1] - self.time_s[0])

    def resample(self, sample_period_s: float) -> PoseStream:
        """The stream at t = k Ts up to the first sample at or after its end (see the module).

        Parameters
        ----------
        sample_period_s : new sample period [s]

        Returns
        -------
        PoseStream

        References
        ----------
        scipy ``RotationSpline`` (cubic spline in rotation vectors, continuous angular
        acceleration); quintic position spline as `sloshkit.motion.laws.from_samples`.

        Examples
        --------
        >>> from sloshkit.motion.poses import PoseTrajectory
        >>> t = np.arange(8) * 0.1
        >>> upright = np.tile([0.0, 0.0, 0.0, 1.0], (8, 1))
        >>> stream = PoseStream(PoseTrajectory(t, np.zeros((8, 3)), upright))
        >>> stream.resample(0.05).time_s.size
        15
        """
        period = require_positive("sample_period", sample_period_s, "s")
        if self.line is not None and self.axis is not None:
            return line_to_poses(
                self.line.resample(period), self.axis, self.position_m[0], self.metadata
            )
        end = float(self.time_s[-1])
        count = steps_to_reach(end, period)
        times = np.arange(count + 1, dtype=float) * period
        inside = np.minimum(times, end)
        if times.shape == self.time_s.shape and np.allclose(times, self.time_s, atol=1e-12):
            return self
        rest = ([(1, np.zeros(3)), (2, np.zeros(3))], [(1, np.zeros(3)), (2, np.zeros(3))])
        spline = make_interp_spline(self.time_s, self.position_m, k=5, bc_type=rest)
        rotations = RotationSpline(self.time_s, Rotation.from_quat(self.quaternion_xyzw))
        poses = PoseTrajectory(
            times, np.asarray(spline(inside), dtype=float), rotations(inside).as_quat()
        )
        return PoseStream(poses, self.source, dict(self.metadata))


def line_to_poses(
    line: LinePlan,
    axis: FloatArray,
    start_m: FloatArray | None = None,
    metadata: dict[str, str] | None = None,
) -> PoseStream:
    """The container upright, moving along ``axis`` from ``start_m`` by the 1-D plan.

    Parameters
    ----------
    line : the 1-D plan
    axis : direction of the move in the path frame (normalised here)
    start_m : start position in the path frame [m] (default the origin)
    metadata : metadata of the stream (default the plan's)

    Returns
    -------
    PoseStream

    Examples
    --------
    >>> t = np.arange(5) * 0.25
    >>> line = LinePlan(t, t**2, 2 * t, 2 + 0 * t)
    >>> line_to_poses(line, np.array([0.0, 1.0, 0.0])).position_m[-1]
    array([0., 1., 0.])
    """
    direction = np.asarray(axis, dtype=float)
    norm = float(np.linalg.norm(direction))
    if direction.shape != (3,) or not norm > 0.0:
        raise InputError("axis", direction.tolist(), "must be a non-zero 3-vector")
    direction = direction / norm
    start = np.zeros(3) if start_m is None else np.asarray(start_m, dtype=float)
    count = line.time_s.size
    poses = PoseTrajectory(
        line.time_s,
        start + np.outer(line.position_m - line.position_m[0], direction),
        np.tile([0.0, 0.0, 0.0, 1.0], (count, 1)),
    )
    return PoseStream(
        poses,
        source=line.source,
        metadata=dict(line.metadata if metadata is None else metadata),
        line=line,
        axis=direction,
    )


def read_metadata(path: str | Path) -> dict[str, str]:
    r"""``# key: value`` comment lines at the top of a sloshkit file, as a dict.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    dict of str

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "plan.csv"
    >>> _ = out.write_text("# law: quintic\n# distance_m: 0.2\nt_s,x_m\n0,0\n")
    >>> read_metadata(out)
    {'law': 'quintic', 'distance_m': '0.2'}
    """
    metadata: dict[str, str] = {}
    with Path(path).open(encoding="utf-8", errors="replace") as handle:  # the top lines only
        for raw in handle:
            line = raw.strip()
            if not line:
                continue
            if not line.startswith("#"):
                break
            key, colon, value = line.lstrip("#").partition(":")
            if colon and key.strip() and " " not in key.strip():
                metadata[key.strip()] = value.strip()
    return metadata


def read_plan(path: str | Path) -> LinePlan | PoseStream:
    """A 1-D plan CSV or a pose-stream CSV (see the module), told apart by the header.

    Parameters
    ----------
    path : the CSV file

    Returns
    -------
    LinePlan or PoseStream

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> rows = "\\n".join(f"{0.1 * k},{0.01 * k},0,0,0,0,0,1" for k in range(4))
    >>> _ = (folder / "p.csv").write_text("t,x,y,z,qx,qy,qz,qw\\n" + rows + "\\n")
    >>> type(read_plan(folder / "p.csv")).__name__
    'PoseStream'
    """
    from sloshkit.io.poses import read_plan_file

    # The one reader of pose and plan files (sloshkit.io.poses): its bounds, units and
    # tolerances hold for export as for every other command.
    table = read_plan_file(path, parameter="plan")
    metadata = read_metadata(path)
    if not isinstance(table, dict):
        poses = PoseTrajectory(
            _uniform_time(table.time_s, path), table.position_m, table.quaternion_xyzw, table.name
        )
        return PoseStream(poses, source=str(path), metadata=metadata)
    time = _uniform_time(table["t_s"], path)
    position = table["position_m"]
    if "velocity_m_s" in table and "acceleration_m_s2" in table:
        velocity, acceleration = table["velocity_m_s"], table["acceleration_m_s2"]
    else:
        from sloshkit.motion.laws import from_samples

        motion = from_samples(time, position_m=position)
        velocity, acceleration = motion.velocity(time), motion.acceleration(time)
    return LinePlan(time, position, velocity, acceleration, str(path), metadata)


def _uniform_time(time: FloatArray, path: str | Path) -> FloatArray:
    from sloshkit.errors import require_increasing

    if time.size < 3:
        raise InputError("plan", str(path), "needs at least 3 samples")
    require_increasing("time", time)
    steps = np.diff(time)
    if not np.allclose(steps, steps[0], rtol=1e-6, atol=1e-9):
        raise InputError("plan", str(path), "the time step must be uniform (a controller grid)")
    # Rebuild the grid from the step: printed times carry rounding.
    period = float(np.round((time[-1] - time[0]) / (time.size - 1), 12))
    return np.asarray(time[0] + np.arange(time.size) * period - time[0], dtype=float)


#: A 1-D plan starts and ends at rest when its end speeds are below this fraction of its peak
#: speed (plus 1e-9 m/s) and its end accelerations below this fraction of its peak
#: acceleration (plus 1e-9 m/s^2). sloshkit's plans end exactly at rest; the fraction leaves
#: room for derivatives taken by finite differences in other tools' files (a quintic sampled
#: at 4 ms: 7e-4), and refuses a move cut off while it still moves.
REST_TOLERANCE = 0.01
#: A pose stream (no velocity columns) ends at rest when its speed over the last (first)
#: sample interval is below this fraction of its peak speed over any interval: a rest-to-rest
#: jerk-limited move is far slower over its last interval (below 1 % on the README's moves).
POSE_REST_FRACTION = 0.05


def require_rest(plan: LinePlan | PoseStream, source: str = "plan") -> None:
    """Refuse a plan that does not start and end at rest (`InputError` naming the end speed).

    The export resamples a plan with splines that are at rest at both ends, and a controller
    that receives a move ending at speed must stop it in one sample: neither is what was
    planned.

    Parameters
    ----------
    plan : LinePlan or PoseStream
        The plan.
    source : str
        The plan's file, for the message.

    Raises
    ------
    InputError
        When the start or end speed (or acceleration, 1-D) is not zero (`REST_TOLERANCE`,
        `POSE_REST_FRACTION`).

    Examples
    --------
    >>> t = np.arange(5) * 0.25
    >>> try:
    ...     require_rest(LinePlan(t, t, 1 + 0 * t, 0 * t), "move.csv")
    ... except InputError as error:
    ...     print(str(error).split(": ", 1)[1])
    must start and end at rest (start speed 1 m/s, end speed 1 m/s)
    """
    if isinstance(plan, LinePlan):
        speed = np.abs(plan.velocity_m_s)
        accel = np.abs(plan.acceleration_m_s2)
        ends_v = (float(speed[0]), float(speed[-1]))
        ends_a = (float(accel[0]), float(accel[-1]))
        moving = max(ends_v) > REST_TOLERANCE * float(np.max(speed)) + 1e-9
        accelerating = max(ends_a) > REST_TOLERANCE * float(np.max(accel)) + 1e-9
        if moving or accelerating:
            raise InputError(
                "plan_file",
                source,
                f"must start and end at rest (start speed {ends_v[0]:.4g} m/s, end speed "
                f"{ends_v[1]:.4g} m/s"
                + (
                    f", start acceleration {ends_a[0]:.4g} m/s^2, end acceleration "
                    f"{ends_a[1]:.4g} m/s^2)"
                    if accelerating
                    else ")"
                ),
            )
        return
    steps = np.linalg.norm(np.diff(plan.position_m, axis=0), axis=1) / plan.sample_period_s
    peak = float(np.max(steps)) if steps.size else 0.0
    if peak > 0.0 and max(steps[0], steps[-1]) > POSE_REST_FRACTION * peak:
        raise InputError(
            "plan_file",
            source,
            f"must start and end at rest (speed over the first sample interval "
            f"{steps[0]:.4g} m/s, over the last {steps[-1]:.4g} m/s, peak {peak:.4g} m/s)",
        )
