"""The plan file's header: what a plan was made for, carried from ``plan --out`` to ``export``.

The first line of a plan file is ``# sloshkit-plan: {json}`` (`PLAN_HEADER`, `plan_header`):
the model (its full serialisation, `sloshkit.model.document`), the model options as typed, the
slosh limits (SI; 1-D or 3-D), the sample period and the slosh check period; a ``# units:``
line follows, then the columns. `read_plan_header` reads it back from the metadata that
`sloshkit.export.plans.read_metadata` returns.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel
from sloshkit.plan.line.problem import SloshLimits

if TYPE_CHECKING:  # the 3-D limits' module imports the path library: only where 3-D is used
    from sloshkit.plan.path.problem import SpatialSloshLimits

FloatArray = NDArray[np.float64]

#: The header line of a plan file (``# sloshkit-plan: {json}``): what the plan was made for.
PLAN_HEADER = "sloshkit-plan"
#: Version of that header's document.
PLAN_HEADER_VERSION = 1
LINE_UNITS = (
    "t_s [s], position_m [m], velocity_m_s [m/s], acceleration_m_s2 [m/s^2], jerk_m_s3 [m/s^3]"
)
POSE_UNITS = "t [s]; x, y, z [m]; qx, qy, qz, qw [-] (container to world, scalar last); z up"


def plan_header(
    model: SloshModel,
    limits: SloshLimits | SpatialSloshLimits | None,
    sample_period_s: float,
    model_options: dict[str, object] | None = None,
) -> dict[str, object]:
    """The document of a plan file's ``# sloshkit-plan:`` line: the model (its full
    serialisation, `sloshkit.model.document.model_to_document`), the model options it was built
    from, the slosh limits (SI), the sample period and the slosh check period.

    Parameters
    ----------
    model : SloshModel
        The model the plan was made for.
    limits : SloshLimits, SpatialSloshLimits or None
        Its slosh limits (1-D: angle, residual, wall elevation; 3-D: slosh heights).
    sample_period_s : float
        The plan's controller period [s].
    model_options : dict, optional
        The command-line model options (``radius``, ``fill_height``, ...) as typed, so that an
        export may change one of them and keep the others.

    Returns
    -------
    dict
        JSON-ready.

    Examples
    --------
    >>> import math
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> header = plan_header(model, SloshLimits(math.radians(5), math.radians(0.25)), 0.004)
    >>> header["kind"], round(header["limits"]["max_angle_rad"], 6), header["slosh_check_period_s"]
    ('line', 0.087266, 0.002)
    """
    from sloshkit.model.document import model_to_document
    from sloshkit.plan.line.verification import slosh_substeps

    document: dict[str, object] = {
        "version": PLAN_HEADER_VERSION,
        "kind": "line" if limits is None or isinstance(limits, SloshLimits) else "poses",
        "sample_period_s": sample_period_s,
        "slosh_check_period_s": sample_period_s / slosh_substeps(sample_period_s),
        "model": model_to_document(model),
        "model_options": None if model_options is None else dict(model_options),
        "limits": None if limits is None else limits_document(limits),
    }
    return document


def limits_document(limits: SloshLimits | SpatialSloshLimits) -> dict[str, float | None]:
    """Slosh limits as a JSON-ready dict (SI, unit-suffixed keys).

    Parameters
    ----------
    limits : SloshLimits or SpatialSloshLimits
        The limits.

    Returns
    -------
    dict

    Examples
    --------
    >>> from sloshkit.plan.path.problem import SpatialSloshLimits
    >>> limits_document(SpatialSloshLimits(0.015, 0.002))["max_slosh_height_m"]
    0.015
    """
    if not isinstance(limits, SloshLimits):
        return {
            "max_slosh_height_m": limits.max_height_m,
            "max_residual_height_m": limits.max_residual_height_m,
            "max_surface_angle_rad": limits.max_surface_angle_rad,
            "robustness": limits.robustness,
        }
    return {
        "max_angle_rad": limits.max_angle_rad,
        "max_residual_rad": limits.max_residual_rad,
        "max_wall_elevation_m": limits.max_wall_elevation_m,
        "robustness": limits.robustness,
    }


def limits_from_document(document: dict[str, Any]) -> SloshLimits | SpatialSloshLimits:
    """The limits of `limits_document` (the inverse).

    Parameters
    ----------
    document : dict
        As written by `limits_document`.

    Returns
    -------
    SloshLimits or SpatialSloshLimits

    Examples
    --------
    >>> limits_from_document(limits_document(SloshLimits(0.1, 0.01))).max_residual_rad
    0.01
    """
    if "max_slosh_height_m" in document:
        from sloshkit.plan.path.problem import SpatialSloshLimits

        return SpatialSloshLimits(
            float(document["max_slosh_height_m"]),
            float(document["max_residual_height_m"]),
            None
            if document.get("max_surface_angle_rad") is None
            else float(document["max_surface_angle_rad"]),
            float(document.get("robustness") or 0.0),
        )
    return SloshLimits(
        float(document["max_angle_rad"]),
        float(document["max_residual_rad"]),
        None
        if document.get("max_wall_elevation_m") is None
        else float(document["max_wall_elevation_m"]),
        float(document.get("robustness") or 0.0),
    )


def read_plan_header(metadata: dict[str, str], source: str = "plan") -> dict[str, Any] | None:
    """The ``# sloshkit-plan:`` document of a plan file's metadata (None without one).

    Parameters
    ----------
    metadata : dict
        The file's ``# key: value`` lines (`read_metadata`).
    source : str
        The file, named in errors.

    Returns
    -------
    dict or None

    Examples
    --------
    >>> read_plan_header({"sloshkit-plan": '{"version": 1, "kind": "line"}'})["kind"]
    'line'
    >>> read_plan_header({}) is None
    True
    """
    import json

    text = metadata.get(PLAN_HEADER)
    if text is None:
        return None
    try:
        document = json.loads(text)
    except json.JSONDecodeError as error:
        raise InputError(
            "plan_file", source, f"its '# {PLAN_HEADER}:' line is not valid JSON ({error.msg})"
        ) from None
    if not isinstance(document, dict) or document.get("version") != PLAN_HEADER_VERSION:
        raise InputError(
            "plan_file", source, f"its '# {PLAN_HEADER}:' line needs version {PLAN_HEADER_VERSION}"
        )
    return document


def write_plan_csv(
    path: str | Path, columns: Mapping[str, FloatArray], header: dict[str, object]
) -> Path:
    r"""Write a plan (1-D columns or pose columns) with its ``# sloshkit-plan:`` line and a
    ``# units:`` line first, atomically.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    columns : mapping
        Column name -> samples (``t_s, position_m, ...`` or ``t,x,y,z,qx,qy,qz,qw``).
    header : dict
        The `plan_header` document.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> t = np.arange(3) * 0.5
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "plan.csv"
    >>> columns = {"t_s": t, "position_m": t, "velocity_m_s": 0 * t, "acceleration_m_s2": 0 * t}
    >>> _ = write_plan_csv(out, columns, {"version": 1, "kind": "line"})
    >>> from sloshkit.export.plans import read_metadata
    >>> read_plan_header(read_metadata(out))["kind"], out.read_text().splitlines()[2][:10]
    ('line', 't_s,positi')
    """
    import json

    from sloshkit.export.formats.common import header_lines, rows_csv
    from sloshkit.files import atomic_open, json_safe

    units = POSE_UNITS if "qw" in columns else LINE_UNITS
    metadata = {PLAN_HEADER: json.dumps(json_safe(header), allow_nan=False), "units": units}
    with atomic_open(path) as handle:
        handle.write(header_lines(metadata) + rows_csv(columns))
    return Path(path)
