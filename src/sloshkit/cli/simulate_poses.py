"""``sloshkit simulate --pose-file``: slosh of a container moved along a 3-D pose trajectory."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from sloshkit.cli import display, signals
from sloshkit.cli.app import stdout
from sloshkit.cli.options import json_number, print_json
from sloshkit.errors import InputError, ValidityWarning
from sloshkit.io.checks import naming
from sloshkit.io.poses import parse_tool_offset, read_pose_file
from sloshkit.io.units import parse_quantity
from sloshkit.model.modal import SloshModel
from sloshkit.sim.simulate import MODEL_KINDS
from sloshkit.sim.spatial import simulate_spatial
from sloshkit.sim.spatial_response import HEIGHT_MAPPINGS, SpatialResponse

PoseFile = Annotated[
    Path | None,
    typer.Option(
        "--pose-file",
        help="3-D move: CSV with t,x,y,z,qx,qy,qz,qw (or roll,pitch,yaw) of the container's "
        "bottom centre, world z up; units in headers honoured (t [ms], x [mm]). "
        "Replaces --law and the move options; the simulation step is the file's (when "
        "uniform) unless --sample-period differs from its default.",
    ),
]
ToolOffset = Annotated[
    str | None,
    typer.Option(
        "--tool-offset",
        help="With --pose-file: the container's bottom centre in the frame of the pose "
        "given by the file (e.g. the flange), X,Y,Z, e.g. 0,0,120mm.",
    ),
]
HeightMappingOpt = Annotated[
    str,
    typer.Option(
        "--height-mapping",
        help="With --pose-file: wall height from the simulated modes ('modal', default) or "
        "plus the quasi-static remainder of the others ('planar', exact static tilt).",
    ),
]


def simulate_poses(
    slosh_model: SloshModel,
    pose_file: Path,
    simulation: dict[str, Any],
    *,
    tool_offset: str | None,
    height_mapping: str,
    sample_period_explicit: bool,
) -> tuple[SpatialResponse, list[str]]:
    """Read the poses, simulate, and collect the validity warnings (also shown on stderr).

    Parameters
    ----------
    slosh_model : SloshModel
        The model.
    pose_file : pathlib.Path
        The pose file (``t,x,y,z,qx,qy,qz,qw``).
    simulation : dict
        The simulation options as typed (model_kind, sample_period, settle_time, ...).
    tool_offset : str or None
        ``--tool-offset``.
    height_mapping : str
        modal or planar.
    sample_period_explicit : bool
        ``--sample-period`` was given (else the poses' own period is used).

    Returns
    -------
    tuple
        (`SpatialResponse`, the validity warnings' messages).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> t = np.arange(101) * 0.005
    >>> s = t / t[-1]
    >>> x = 0.05 * s**3 * (10 - 15 * s + 6 * s**2)
    >>> rows = np.column_stack((t, x, 0 * t, 0 * t, 0 * t, 0 * t, 0 * t, 1 + 0 * t))
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "move.csv"
    >>> np.savetxt(path, rows, delimiter=",", header="t,x,y,z,qx,qy,qz,qw", comments="")
    >>> options = {"model_kind": "linear", "sample_period": "1ms", "settle_time": None}
    >>> response, messages = simulate_poses(model, path, options, tool_offset=None,
    ...                                     height_mapping="modal", sample_period_explicit=False)
    >>> round(response.metrics()["duration_s"], 3), messages
    (0.5, [])
    """
    model_kind = simulation["model_kind"]
    if model_kind not in MODEL_KINDS:
        raise InputError("model", model_kind, "must be one of " + ", ".join(MODEL_KINDS))
    if height_mapping not in HEIGHT_MAPPINGS:
        raise InputError("height_mapping", height_mapping, "must be one of modal, planar")
    offset = None if tool_offset is None else parse_tool_offset(tool_offset)
    settle = simulation["settle_time"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ValidityWarning)
        poses = read_pose_file(pose_file, tool_offset_m=offset)
        settle_s = None if settle is None else parse_quantity(settle, "time", "settle_time")
        period_s = (
            parse_quantity(simulation["sample_period"], "time", "sample_period")
            if sample_period_explicit
            else None
        )
        # The compiled kernels must not see a signal's exception in the middle of a call (a
        # SIGTERM there could crash the process): it is recorded and raised after the kernel.
        with (
            signals.deferred(),
            naming("pose_file", pose_file, keep=("settle_time", "sample_period", "model")),
        ):
            response = simulate_spatial(  # the samples' memory estimate names --pose-file
                slosh_model,
                poses,
                nonlinear=model_kind == "nonlinear",
                settle_time_s=settle_s,
                sample_period_s=period_s,
                height_mapping=height_mapping,  # type: ignore[arg-type]
            )
    messages = []
    for item in caught:
        if issubclass(item.category, ValidityWarning):
            messages.append(str(item.message))
        warnings.showwarning(item.message, item.category, item.filename, item.lineno)
    return response, messages


def spatial_json(response: SpatialResponse, messages: list[str]) -> dict[str, Any]:
    """The JSON of ``simulate --pose-file`` (SI, units in the keys).

    Parameters
    ----------
    response : SpatialResponse
        The 3-D simulation.
    messages : list of str
        Its validity warnings.

    Returns
    -------
    dict

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> poses = sk.poses_from_law(sk.quintic(0.05, 0.5), sample_period_s=0.005)
    >>> payload = spatial_json(sk.simulate_spatial(model, poses), ["a note"])
    >>> payload["duration_s"], payload["warnings"]
    (0.5, ['a note'])
    """
    payload: dict[str, Any] = {}
    for key, value in response.metrics().items():
        payload[key] = json_number(value) if isinstance(value, float) else value
    payload["motion"] = response.motion_name
    payload["warnings"] = messages
    return payload


def report_poses(
    response: SpatialResponse,
    messages: list[str],
    *,
    csv: Path | None,
    plot: Path | None,
    json_output: bool,
) -> None:
    """Write the files and print the JSON or a table.

    Parameters
    ----------
    response : SpatialResponse
        The 3-D simulation.
    messages : list of str
        Its validity warnings.
    csv, plot : pathlib.Path or None
        Where to write the time series and the figure.
    json_output : bool
        Print JSON instead of a table.

    Examples
    --------
    >>> import contextlib, io, json, tempfile, pathlib
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> response = sk.simulate_spatial(model, sk.poses_from_law(sk.quintic(0.05, 0.5),
    ...                                                         sample_period_s=0.005))
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "slosh.csv"
    >>> printed = io.StringIO()
    >>> with contextlib.redirect_stdout(printed):
    ...     report_poses(response, [], csv=out, plot=None, json_output=True)
    >>> json.loads(printed.getvalue())["duration_s"], out.read_text().startswith("t_s")
    (0.5, True)
    """
    if csv is not None:
        response.to_csv(csv)
    if plot is not None:
        response.plot(path=plot)
    if json_output:
        print_json(spatial_json(response, messages))
        return
    table = Table(title=f"3-D move {response.motion_name!r}, {response.kind} model")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    for key, value in response.metrics().items():
        text = value if isinstance(value, str) else display.value(key, value)
        table.add_row(Text(display.label(key)), text)
    stdout.print(table)
