"""Size estimation before allocation: refuse work whose arrays would not fit, before it starts.

Every place that allocates an array whose size the user controls (time grids from a duration and
a sample period, sweep grids from counts, tables from files) asks `require_memory` first. The
limit is ``SLOSHKIT_MAX_MEMORY`` (bytes, or text like ``512MiB``/``8GB``; the CLI's
``--max-memory`` sets it), else half of the physical memory. A refusal is an `InputError`
naming the parameter, the estimated bytes and the limit, raised in microseconds instead of a
MemoryError after minutes of swapping.
"""

from __future__ import annotations

import math
import os
import re

from sloshkit.errors import InputError

#: Environment variable holding the memory limit.
ENVIRONMENT_VARIABLE = "SLOSHKIT_MAX_MEMORY"

#: Bytes of one float64 sample.
FLOAT_BYTES = 8

_FACTORS = {
    "": 1,
    "b": 1,
    "kb": 10**3,
    "mb": 10**6,
    "gb": 10**9,
    "tb": 10**12,
    "kib": 2**10,
    "mib": 2**20,
    "gib": 2**30,
    "tib": 2**40,
    "k": 2**10,
    "m": 2**20,
    "g": 2**30,
    "t": 2**40,
}


def parse_bytes(text: str, parameter: str = "max_memory") -> int:
    """Bytes from text like ``"4GiB"``, ``"500 MB"``, ``"2e9"``.

    Parameters
    ----------
    text : str
        A positive number with an optional unit (B, kB, MB, GB, TB, KiB, MiB, GiB, TiB).
    parameter : str
        The option name for the error message.

    Returns
    -------
    int
        The number of bytes (> 0).

    References
    ----------
    IEC 80000-13:2008, binary prefixes (KiB, MiB, GiB).

    Examples
    --------
    >>> parse_bytes("4GiB"), parse_bytes("500MB")
    (4294967296, 500000000)
    """
    match = re.fullmatch(r"\s*(\d+(?:\.\d*)?(?:[eE][+-]?\d+)?)\s*([A-Za-z]{0,3})\s*", str(text))
    if match is None or match.group(2).lower() not in _FACTORS:
        raise InputError(parameter, text, "must be a size like 4GiB, 512MiB or 2e9 (bytes)")
    value = float(match.group(1)) * _FACTORS[match.group(2).lower()]
    if not math.isfinite(value) or value < 1.0:
        raise InputError(parameter, text, "must be a finite size of at least 1 byte")
    return int(value)


def physical_memory() -> int | None:
    """Installed memory in bytes, or None where the platform does not say.

    Returns
    -------
    int or None

    Examples
    --------
    >>> (physical_memory() or 1) > 0
    True
    """
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):
        return None


def memory_limit() -> int:
    """The current limit in bytes: ``SLOSHKIT_MAX_MEMORY`` or half the physical memory.

    Returns
    -------
    int
        Bytes any single request may allocate.

    Examples
    --------
    >>> memory_limit() > 0
    True
    """
    text = os.environ.get(ENVIRONMENT_VARIABLE)
    if text:
        return parse_bytes(text, ENVIRONMENT_VARIABLE)
    installed = physical_memory()
    return installed // 2 if installed else 4 * 2**30


def format_bytes(count: float) -> str:
    """``count`` bytes in binary units, e.g. ``'64.0 GiB'``.

    Parameters
    ----------
    count : float
        A number of bytes.

    Returns
    -------
    str

    Examples
    --------
    >>> format_bytes(3 * 2**30)
    '3.0 GiB'
    """
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if count >= size:
            return f"{count / size:.1f} {unit}"
    return f"{count:.0f} B"


def require_memory(parameter: str, value: object, estimated_bytes: float, what: str) -> None:
    """Raise `InputError` when ``estimated_bytes`` exceed `memory_limit`.

    Parameters
    ----------
    parameter : str
        The option that makes the request large (named in the message).
    value : object
        Its value, as given.
    estimated_bytes : float
        The estimate of the memory the request needs.
    what : str
        What would be allocated (e.g. ``"3e9 time samples x 12 columns"``).

    Returns
    -------
    None

    Examples
    --------
    >>> require_memory("sample_period", "1ms", 1e6, "1000 samples")
    """
    limit = memory_limit()
    if not estimated_bytes <= limit:
        raise InputError(
            parameter,
            value,
            f"needs about {format_bytes(estimated_bytes)} ({what}), above the memory limit "
            f"{format_bytes(limit)}",
            f"raise it with --max-memory or {ENVIRONMENT_VARIABLE} if the machine has the memory",
        )


def require_samples(
    parameter: str, value: object, samples: float, columns: int = 1, what: str = "time samples"
) -> int:
    """Check that ``samples`` x ``columns`` float64 values fit; return ``samples`` as int.

    Parameters
    ----------
    parameter, value :
        The option responsible and its value (for the message).
    samples : float
        Number of samples (may be inf or NaN from a bad division: refused).
    columns : int
        Arrays of that length allocated together.
    what : str
        Name of the samples in the message.

    Returns
    -------
    int
        ``samples`` as an integer.

    Examples
    --------
    >>> require_samples("sample_period", "1ms", 1501, 5)
    1501
    """
    if not math.isfinite(samples):
        raise InputError(parameter, value, f"gives an unbounded number of {what}")
    require_memory(
        parameter,
        value,
        samples * columns * FLOAT_BYTES,
        f"{samples:.3g} {what} x {columns} column{'s' if columns != 1 else ''}",
    )
    return int(samples)
