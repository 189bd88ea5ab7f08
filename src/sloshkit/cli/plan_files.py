"""Plan files on the command line: the ``# sloshkit-plan:`` header that ``plan --out`` writes,
and what ``export`` takes from it (the model and the slosh limits, command-line options
overriding it with a warning when they differ).

A plan file without that header names no model: ``export`` then needs the model options (or
``--no-check``) and refuses the check otherwise (exit code 2), instead of checking the plan
against a default container it was not made for.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from sloshkit.cli.options import MODEL_OPTIONS
from sloshkit.errors import InputError, warn_validity
from sloshkit.io.model_options import options_model_request
from sloshkit.model.modal import SloshModel

#: The slosh-limit options of ``export`` (overriding the plan file's limits).
LIMIT_OPTIONS = ("max_angle", "max_residual")


def given_options(context: Any, names: tuple[str, ...] | list[str]) -> list[str]:
    """The options among ``names`` (Python names) given on the command line or by the
    environment (none without a command context).

    Parameters
    ----------
    context : typer.Context or None
        The running command's context.
    names : sequence of str
        Parameter names, e.g. ``("radius", "damping_ratio")``.

    Returns
    -------
    list of str

    Examples
    --------
    >>> given_options(None, ["radius"])
    []
    """
    if context is None:
        return []
    sources = {name: context.get_parameter_source(name) for name in names}
    return [
        name
        for name, source in sources.items()
        if source is not None and source.name in ("COMMANDLINE", "ENVIRONMENT")
    ]


def _typed_model_options(context: Any) -> dict[str, Any] | None:
    """The running command's model options as typed (None with ``--model-file`` or without a
    context): what a plan file keeps so that an export can change one of them."""
    if context is None or context.params.get("model_file") is not None:
        return None
    return {name: context.params[name] for name in MODEL_OPTIONS if name in context.params}


def plan_file_header(
    context: Any, model: SloshModel, limits: Any, sample_period_s: float
) -> dict[str, Any]:
    """The ``# sloshkit-plan:`` document of the plan the running command writes.

    Parameters
    ----------
    context : typer.Context or None
        The running command's context (its model options go into the header).
    model : SloshModel
        The model planned for.
    limits : SloshLimits or SpatialSloshLimits
        The plan's slosh limits.
    sample_period_s : float
        Its controller period [s].

    Returns
    -------
    dict

    Examples
    --------
    >>> import math
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> from sloshkit.plan.line.problem import SloshLimits
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> plan_file_header(None, model, SloshLimits(0.1, 0.01), 0.004)["model_options"] is None
    True
    """
    from sloshkit.export.headers import plan_header

    return plan_header(model, limits, sample_period_s, _typed_model_options(context))


def model_differences(planned: SloshModel, used: SloshModel) -> list[str]:
    """What differs between the model a plan was made for and the one an export checks, as
    phrases ("first-mode damping ratio 0.03 (the plan's: 0.0057)"); empty when they agree to
    1e-9 relative.

    Parameters
    ----------
    planned, used : SloshModel
        The plan file's model and the export's.

    Returns
    -------
    list of str

    Examples
    --------
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> vial = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> damped = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039,
    ...                           damping_ratio=0.03)
    >>> model_differences(vial, damped)[0].startswith("first-mode damping ratio 0.03")
    True
    >>> model_differences(vial, vial)
    []
    """
    first, other = planned.modes[0], used.modes[0]
    quantities = [
        ("radius", planned.radius_m * 1e3, used.radius_m * 1e3, " mm"),
        ("fill height", planned.fill_height_m * 1e3, used.fill_height_m * 1e3, " mm"),
        ("first-mode frequency", first.frequency_hz, other.frequency_hz, " Hz"),
        ("first-mode damping ratio", first.damping_ratio, other.damping_ratio, ""),
        ("modes", float(len(planned.modes)), float(len(used.modes)), ""),
    ]
    phrases = [
        f"{name} {value:.6g}{unit} (the plan's: {plan_value:.6g}{unit})"
        for name, plan_value, value, unit in quantities
        if not math.isclose(plan_value, value, rel_tol=1e-9, abs_tol=1e-12)
    ]
    if planned.liquid.name != used.liquid.name:
        phrases.append(f"liquid {used.liquid.name} (the plan's: {planned.liquid.name})")
    return phrases


def export_model(
    context: Any,
    header: dict[str, Any] | None,
    command_model: SloshModel,
    check: bool,
    plan_file: Path,
) -> tuple[SloshModel | None, str]:
    """The model an export checks, and where it comes from.

    The plan file's model unless model options are given; given options replace the plan's
    (the others are kept from the plan's typed options when it has them), with a warning
    naming what differs. Without a header and without model options the check is refused.

    Parameters
    ----------
    context : typer.Context or None
        The running command's context (which options were given).
    header : dict or None
        The plan file's ``# sloshkit-plan:`` document.
    command_model : SloshModel
        The model the command's options build.
    check : bool
        Whether the round trip runs (``--check``).
    plan_file : Path
        The plan file (for messages).

    Returns
    -------
    tuple
        (model or None, "plan file", "command line" or "plan file, with --OPTION ...").

    Examples
    --------
    >>> from sloshkit import UprightCylinder, equivalent_model, get_liquid
    >>> vial = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> export_model(None, None, vial, False, Path("old.csv"))
    (None, 'none')
    """
    from sloshkit.model.document import model_from_document

    given = given_options(context, list(MODEL_OPTIONS))
    planned = None
    if header is not None and header.get("model") is not None:
        planned = model_from_document(header["model"], f"{plan_file} (# sloshkit-plan)")
    if not given:
        if planned is not None:
            return planned, "plan file"
        if not check:
            return None, "none"
        raise InputError(
            "plan_file",
            str(plan_file),
            "names no model (no '# sloshkit-plan:' line, which 'sloshkit plan --out' writes): "
            "give the model options (--radius, --fill-height, --liquid, --damping-ratio, ... "
            "or --model-file), or --no-check",
        )
    if planned is None:
        return command_model, "command line"
    typed = header.get("model_options") if header is not None else None
    model = command_model
    if isinstance(typed, dict) and "model_file" not in given:
        params = context.params
        values = {name: params[name] for name in MODEL_OPTIONS if name != "model_file"}
        values.update({name: typed[name] for name in values if name in typed})
        values.update({name: params[name] for name in given})
        model = options_model_request(**values)
    flags = ", ".join("--" + name.replace("_", "-") for name in given)
    differences = model_differences(planned, model)
    if differences:
        warn_validity(
            f"{flags}: the export checks a model other than the plan's: " + "; ".join(differences)
        )
    return model, f"plan file, with {flags} from the command line"


def export_limits(header: dict[str, Any] | None, command_limits: Any) -> Any:
    """The slosh limits an export checks: ``--max-angle``/``--max-residual`` when given (a
    warning when they differ from the plan file's), else the plan file's (1-D or 3-D), else
    None.

    Parameters
    ----------
    header : dict or None
        The plan file's ``# sloshkit-plan:`` document.
    command_limits : SloshLimits or None
        The limits given on the command line.

    Returns
    -------
    SloshLimits, SpatialSloshLimits or None

    Examples
    --------
    >>> from sloshkit.plan.line.problem import SloshLimits
    >>> header = {"limits": {"max_angle_rad": 0.1, "max_residual_rad": 0.01}}
    >>> export_limits(header, None).max_angle_rad
    0.1
    """
    from sloshkit.export.headers import limits_document, limits_from_document

    planned = None
    if header is not None and header.get("limits") is not None:
        planned = limits_from_document(header["limits"])
    if command_limits is None:
        return planned
    if planned is not None:
        mine, theirs = limits_document(command_limits), limits_document(planned)
        if mine.keys() != theirs.keys() or any(
            not math.isclose(mine[key] or 0.0, theirs[key] or 0.0, rel_tol=1e-9) for key in mine
        ):
            warn_validity(
                "--max-angle, --max-residual: the export checks limits other than the plan's "
                f"(the plan's: {_limits_text(theirs)})"
            )
    return command_limits


def _limits_text(document: dict[str, Any]) -> str:
    parts = []
    for key, value in document.items():
        if value is None or key == "robustness":
            continue
        if key.endswith("_rad"):
            parts.append(f"{key[:-4]} {math.degrees(value):.6g} deg")
        else:
            parts.append(f"{key[:-2]} {1e3 * value:.6g} mm")
    return ", ".join(parts)
