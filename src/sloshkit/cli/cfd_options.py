"""Options shared by the ``sloshkit cfd`` commands, and the case they describe."""

from __future__ import annotations

import math
from contextlib import nullcontext
from pathlib import Path
from typing import Annotated, Any

import typer

from sloshkit.cfd.pipeline import RECOMMENDED
from sloshkit.cfd.requests import CaseRequest, require_cylinder, require_processes
from sloshkit.cfd.spec import CaseSpec
from sloshkit.cli.moves import Distance, Duration
from sloshkit.errors import InputError
from sloshkit.io.checks import naming
from sloshkit.io.command_requests import MoveRequest
from sloshkit.io.poses import read_pose_file
from sloshkit.io.units import parse_bounded, parse_quantity
from sloshkit.model.modal import SloshModel

CaseDir = Annotated[Path, typer.Option("--case", help="Case folder.")]


def cfd_options(excitation: str, end_time: str) -> dict[str, tuple[Any, Any]]:
    """The case options shared by the cfd commands (with their command's defaults).

    Parameters
    ----------
    excitation : str
        Default of ``--excitation`` for the command.
    end_time : str
        Default of ``--end-time`` for the command (with its unit).

    Returns
    -------
    dict
        Option name -> (annotated type, default), for `sloshkit.cli.options.with_options`.

    Examples
    --------
    >>> options = cfd_options("harmonic", "4s")
    >>> options["excitation"][1], options["end_time"][1], options["wall_grading"][1]
    ('harmonic', '4s', 1.0)
    """
    return {
        "excitation": (
            Annotated[
                str,
                typer.Option(
                    "--excitation",
                    help="free-decay (tilted surface), harmonic, law, or poses (--pose-file).",
                ),
            ],
            excitation,
        ),
        "tilt": (
            Annotated[str, typer.Option("--tilt", help="Initial tilt for free-decay.")],
            "3deg",
        ),
        "amplitude": (
            Annotated[str, typer.Option("--amplitude", help="Harmonic amplitude.")],
            "10mm",
        ),
        "frequency": (
            Annotated[str, typer.Option("--frequency", help="Harmonic frequency.")],
            "1Hz",
        ),
        "excite_time": (
            Annotated[str, typer.Option("--excite-time", help="Harmonic duration.")],
            "2s",
        ),
        "law": (
            Annotated[str | None, typer.Option("--law", help="Motion law for --excitation law.")],
            None,
        ),
        "distance": (Distance, "0.1m"),
        "duration": (Duration, None),
        "pose_file": (
            Annotated[
                Path | None,
                typer.Option(
                    "--pose-file",
                    help="Pose trajectory for --excitation poses (t, x, y, z and qx, qy, qz, qw "
                    "or roll, pitch, yaw; units in the header).",
                ),
            ],
            None,
        ),
        "probe_angles": (
            Annotated[
                int | None,
                typer.Option(
                    "--probe-angles",
                    help="Probe columns around the wall (default 2 on the x axis; 12 for poses).",
                ),
            ],
            None,
        ),
        "cells_per_radius": (
            Annotated[int, typer.Option("--cells-per-radius", help="Mesh resolution.")],
            RECOMMENDED["cells_per_radius"],
        ),
        "wall_grading": (
            Annotated[
                float,
                typer.Option(
                    "--wall-grading",
                    help="Wall refinement: ratio of the wall cell to the innermost cell of a "
                    "graded wall annulus (1: uniform O-grid; 0.1 with --cells-per-radius 12 "
                    "puts 0.09 mm cells at the wall of the seed vial, docs/cfd.md).",
                ),
            ],
            1.0,
        ),
        "radial_cells": (
            Annotated[
                int | None,
                typer.Option(
                    "--radial-cells",
                    help="Cells across the graded wall annulus (default from the mesh).",
                ),
            ],
            None,
        ),
        "surface_refinement": (
            Annotated[
                int,
                typer.Option(
                    "--surface-refinement",
                    help="Vertical cells within 0.3 R of the free surface are R/(S x N), S this "
                    "value (2: twice as fine as elsewhere). A study option: 4 changed the "
                    "damping of coarse graded meshes, not of fine ones (docs/cfd.md).",
                ),
            ],
            2,
        ),
        "end_time": (Annotated[str, typer.Option("--end-time", help="Simulated time.")], end_time),
        "delta_t": (
            Annotated[
                str,
                typer.Option(
                    "--delta-t", help="Largest time step (the step itself with --fixed-step)."
                ),
            ],
            f"{RECOMMENDED['delta_t_s'] * 1e3:g}ms",
        ),
        "max_courant": (
            Annotated[
                float,
                typer.Option(
                    "--max-courant",
                    help="Courant and interface-Courant limit of the adaptive time step.",
                ),
            ],
            RECOMMENDED["max_courant"],
        ),
        "fixed_step": (
            Annotated[
                bool, typer.Option("--fixed-step", help="A fixed step of --delta-t (no Courant).")
            ],
            False,
        ),
        "ddt": (
            Annotated[str, typer.Option("--ddt", help="Euler, 'CrankNicolson 0.9' or backward.")],
            "Euler",
        ),
        "np_": (
            Annotated[
                int | None,
                typer.Option(
                    "--np",
                    help="MPI processes (default 1, serial; with --resume, the case's own).",
                ),
            ],
            None,
        ),
        "cfd_surface_tension": (
            Annotated[
                bool,
                typer.Option("--cfd-surface-tension", help="Include surface tension in the CFD."),
            ],
            False,
        ),
    }


def spec_from_options(slosh_model: SloshModel, options: dict[str, Any]) -> CaseSpec:
    """The case described by the values of `cfd_options`: units and files parsed here, the
    case checked and built by `sloshkit.cfd.requests.CaseRequest`.

    Parameters
    ----------
    slosh_model : SloshModel
        The container, fill and liquid.
    options : dict
        The values of the options of `cfd_options`, by name.

    Returns
    -------
    CaseSpec

    Raises
    ------
    InputError
        A bad value or a missing file for the chosen excitation.

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> values = {name: default for name, (_, default) in cfd_options("free-decay", "2s").items()}
    >>> spec = spec_from_options(model, values)
    >>> spec.end_time_s, spec.cells_per_radius, spec.wall_grading
    (2.0, 11, 1.0)
    """

    require_cylinder(slosh_model)  # before any file is read
    motion = poses = None
    if options["excitation"] == "poses":
        if options["pose_file"] is None:
            raise InputError("pose-file", None, "is needed with --excitation poses")
        poses = read_pose_file(options["pose_file"])
    if options["excitation"] == "law":
        request = MoveRequest.parse(
            options["distance"], options["duration"], None, None, None, None, None
        )
        motion = request.law(options["law"] or "quintic")
    require_processes(options["np_"])  # before the units are parsed (the request checks again)
    # ranges that keep a case meaningful: a tilt below 45 deg, an amplitude below 10 m
    case = CaseRequest(
        excitation=options["excitation"],
        tilt_rad=parse_bounded(options["tilt"], "angle", "tilt", 0.0, math.radians(45.0)),
        amplitude_m=parse_bounded(options["amplitude"], "length", "amplitude", 0.0, 10.0),
        frequency_hz=parse_bounded(options["frequency"], "frequency", "frequency", 0.0, 1e3),
        excite_time_s=parse_bounded(options["excite_time"], "time", "excite_time", 0.0, 1e5),
        motion=motion,
        poses=poses,
        end_time_s=parse_quantity(options["end_time"], "time", "end_time"),
        delta_t_s=parse_quantity(options["delta_t"], "time", "delta_t"),
        cells_per_radius=options["cells_per_radius"],
        ddt_scheme=options["ddt"],
        processes=options["np_"],
        surface_tension=options["cfd_surface_tension"],
        max_courant=options["max_courant"],
        fixed_step=options["fixed_step"],
        probe_angles=options["probe_angles"],
        wall_grading=options.get("wall_grading", 1.0),
        radial_cells=options.get("radial_cells"),
        surface_refinement=options.get("surface_refinement", 2),
    )
    # the excitation and the grid of a pose file (too short, too long) name --pose-file
    with (
        naming("pose_file", options["pose_file"], keep=("np",))
        if poses is not None
        else nullcontext()
    ):
        return case.spec(slosh_model)
