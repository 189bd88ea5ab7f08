"""The JSON files beside a case, read and checked before any use: ``sloshkit-case.json`` (the
case's description, `sloshkit.cfd.case.spec_summary`) and ``sloshkit-run.json`` (the run's
record). A case folder is user input: a file that is not JSON, or whose keys have the wrong
types, is an `InputError` naming the file, never a crash further on."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, TypeGuard

from sloshkit.errors import InputError

CASE_FILE = "sloshkit-case.json"
RUN_FILE = "sloshkit-run.json"

#: Largest JSON file beside a case [bytes] (a case's description is about 2 kB).
MAX_JSON_BYTES = 2**20

#: Keys of ``sloshkit-case.json`` that the readers use, with their checks: a positive
#: number, a non-negative number, a positive integer, a list of numbers, a mapping.
_POSITIVE = ("radius_m", "fill_height_m", "end_time_s", "probe_dz_m")
_NON_NEGATIVE = ("delta_t_s",)
_COUNTS = ("probes_per_column", "cells")
_OPTIONAL_COUNTS = ("processes", "cells_per_radius")


def read_json_file(path: Path, parameter: str = "case") -> Any:
    """A JSON file beside a case, parsed; `InputError` naming it when it is not JSON.

    Parameters
    ----------
    path : Path
        The file.
    parameter : str
        The option that named the case.

    Returns
    -------
    object

    Examples
    --------
    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "a.json"
    >>> _ = path.write_text('{"a": 1}')
    >>> read_json_file(path)
    {'a': 1}
    """
    size = path.stat().st_size
    if size > MAX_JSON_BYTES:
        raise InputError(parameter, str(path), f"is {size} bytes; at most {MAX_JSON_BYTES}")
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except UnicodeDecodeError:
        raise InputError(parameter, str(path), "is not UTF-8 text") from None
    except (ValueError, RecursionError) as error:
        raise InputError(parameter, str(path), f"is not valid JSON ({error})") from None


def _wrong(path: Path, parameter: str, key: str, value: Any, expected: str) -> InputError:
    shown = json.dumps(value)[:60] if not isinstance(value, float) else repr(value)
    return InputError(parameter, str(path), f"key {key!r} is {shown}; it must be {expected}")


def _is_number(value: Any) -> TypeGuard[float]:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def read_case_summary(case: Path, parameter: str = "case") -> dict[str, Any]:
    """``sloshkit-case.json`` of ``case``, checked (the keys sloshkit reads, with their types).

    Parameters
    ----------
    case : Path
        The case folder.
    parameter : str
        The option that named the case.

    Returns
    -------
    dict

    Raises
    ------
    InputError
        No such file (not a sloshkit case), not JSON, or a key missing or of the wrong type;
        the message names the file and the key.

    Examples
    --------
    >>> import tempfile
    >>> from sloshkit.cfd.case import spec_summary
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> case = Path(tempfile.mkdtemp())
    >>> summary = spec_summary(CaseSpec(0.0205, 0.039, get_liquid("water-25C")))
    >>> _ = (case / CASE_FILE).write_text(json.dumps(summary))
    >>> read_case_summary(case)["excitation"]["type"]
    'FreeDecay'
    >>> _ = (case / CASE_FILE).write_text(json.dumps({**summary, "end_time_s": "3 s"}))
    >>> try:
    ...     read_case_summary(case)
    ... except InputError as error:
    ...     print(error.valid)
    key 'end_time_s' is "3 s"; it must be a positive number
    """
    path = case / CASE_FILE
    if not path.is_file():
        raise InputError(parameter, str(case), f"is not a sloshkit CFD case (no {CASE_FILE})")
    summary = read_json_file(path, parameter)
    if not isinstance(summary, dict):
        raise InputError(parameter, str(path), "must hold a JSON object")
    for key in _POSITIVE:
        value = summary.get(key)
        if not (_is_number(value) and value > 0):
            raise _wrong(path, parameter, key, value, "a positive number")
    for key in _NON_NEGATIVE:
        value = summary.get(key, 0.0)
        if not (_is_number(value) and value >= 0):
            raise _wrong(path, parameter, key, value, "a number >= 0")
    for key in _COUNTS:
        value = summary.get(key)
        if not (isinstance(value, int) and not isinstance(value, bool) and value > 0):
            raise _wrong(path, parameter, key, value, "a positive integer")
    for key in _OPTIONAL_COUNTS:
        value = summary.get(key, 1)
        if not (isinstance(value, int) and not isinstance(value, bool) and value > 0):
            raise _wrong(path, parameter, key, value, "a positive integer")
    angles = summary.get("probe_angles_rad", [0.0, math.pi])
    if not (isinstance(angles, list) and angles and all(_is_number(a) for a in angles)):
        raise _wrong(path, parameter, "probe_angles_rad", angles, "a list of numbers")
    excitation = summary.get("excitation")
    if not (isinstance(excitation, dict) and isinstance(excitation.get("type"), str)):
        raise _wrong(path, parameter, "excitation", excitation, 'an object with a "type" name')
    for key in ("duration_s", "tilt_deg", "amplitude_m", "frequency_hz", "cutoff_hz"):
        if key == "cutoff_hz" and excitation.get(key, 0.0) is None:
            continue  # a pose excitation without a filter
        if key in excitation and not _is_number(excitation[key]):
            raise _wrong(path, parameter, f"excitation.{key}", excitation[key], "a number")
    for key in ("name", "pose_file", "liquid"):
        holder = excitation if key != "liquid" else summary
        if key in holder and not isinstance(holder[key], str):
            raise _wrong(path, parameter, key, holder[key], "a string")
    return summary


def read_run_record(case: Path, parameter: str = "case") -> dict[str, Any]:
    """``sloshkit-run.json`` of ``case`` (wall clock, processes), or {} when there is none.

    Parameters
    ----------
    case : Path
        The case folder.
    parameter : str
        The option that named the case.

    Returns
    -------
    dict

    Examples
    --------
    >>> import tempfile
    >>> read_run_record(Path(tempfile.mkdtemp()))
    {}
    """
    path = case / RUN_FILE
    if not path.is_file():
        return {}
    record = read_json_file(path, parameter)
    if not isinstance(record, dict):
        raise InputError(parameter, str(path), "must hold a JSON object")
    for key in ("wall_clock_s", "processes"):
        if key in record and record[key] is not None and not _is_number(record[key]):
            raise _wrong(path, parameter, key, record[key], "a number")
    return record
