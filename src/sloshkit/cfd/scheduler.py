"""The Dask scheduler of a CFD campaign, checked before the campaign starts.

`check_scheduler` parses ``--scheduler`` (``[tcp://|tls://]HOST:PORT``), then opens a Dask
connection and asks the scheduler who it is (Dask's ``identity`` operation), all within
`HANDSHAKE_TIMEOUT_S`: a port that accepts and never speaks, or answers with anything but a
Dask scheduler's identity, is refused in seconds, before any case is written. Credentials in
an address (``tcp://user:secret@host``) are never printed (`redact`). `quiet_dask_logging`
keeps Dask's own log lines off stderr.
"""

from __future__ import annotations

import re
from typing import Any

from sloshkit.errors import InputError

#: Longest wait for the scheduler's connection and answer [s].
HANDSHAKE_TIMEOUT_S = 5.0

_ADDRESS = re.compile(
    r"(?:(?P<scheme>[A-Za-z][A-Za-z0-9+.-]*)://)?(?:(?P<credentials>[^@/]*)@)?"
    r"(?P<host>\[[0-9a-fA-F:.]+\]|[A-Za-z0-9._-]+):(?P<port>[0-9]{1,5})"
)


def redact(address: str) -> str:
    """``address`` with any user and password replaced by ``***``.

    Parameters
    ----------
    address : str
        A scheduler address or URL as typed.

    Returns
    -------
    str

    Examples
    --------
    >>> redact("tcp://admin:hunter2@10.0.0.5:8786")
    'tcp://***@10.0.0.5:8786'
    >>> redact("tcp://10.0.0.5:8786")
    'tcp://10.0.0.5:8786'
    """
    return re.sub(r"(?<=://)[^@/\s]*@|^[^@/:\s]*:[^@/\s]*@", "***@", address)


def parse_scheduler(address: str) -> tuple[str, str, int]:
    """(scheme, host, port) of a ``[tcp://|tls://]HOST:PORT`` address; `InputError` otherwise.

    Parameters
    ----------
    address : str
        The ``--scheduler`` option as typed.

    Returns
    -------
    tuple of (str, str, int)

    Examples
    --------
    >>> parse_scheduler("10.0.0.5:8786")
    ('tcp', '10.0.0.5', 8786)
    """
    match = _ADDRESS.fullmatch(address)
    shown = redact(address)
    valid = "must be [tcp://|tls://]HOST:PORT, e.g. tcp://10.0.0.5:8786"
    if match is None:
        raise InputError("scheduler", shown, valid)
    scheme = (match.group("scheme") or "tcp").lower()
    if scheme not in ("tcp", "tls"):
        raise InputError("scheduler", shown, valid)
    if match.group("credentials") is not None:
        raise InputError(
            "scheduler",
            shown,
            "a Dask address carries no user or password (Dask authenticates with TLS "
            "certificates: tls://HOST:PORT and the cluster's security settings)",
        )
    port = int(match.group("port"))
    if not 1 <= port <= 65535:
        raise InputError("scheduler", shown, valid)
    return scheme, match.group("host").strip("[]"), port


def check_scheduler(address: str, timeout_s: float = HANDSHAKE_TIMEOUT_S) -> str:
    """Check that a Dask scheduler answers at ``address``, within ``timeout_s``.

    For ``tcp://`` the scheduler must answer Dask's ``identity`` operation as a scheduler; for
    ``tls://`` (which needs the cluster's certificates) a TCP connection must open.

    Parameters
    ----------
    address : str
        The ``--scheduler`` option as typed.
    timeout_s : float
        Longest wait for the connection and the answer [s].

    Returns
    -------
    str
        The address, unchanged.

    Raises
    ------
    InputError
        Naming ``scheduler`` (its credentials redacted) and what went wrong.

    Examples
    --------
    >>> from sloshkit.errors import InputError
    >>> try:
    ...     check_scheduler("tcp://scheduler:8786 x")
    ... except InputError as error:
    ...     print(error.valid)
    must be [tcp://|tls://]HOST:PORT, e.g. tcp://10.0.0.5:8786
    """
    import socket

    scheme, host, port = parse_scheduler(address)
    hint = "start the scheduler first, or leave --scheduler out for the local cluster"
    try:
        with socket.create_connection((host, port), timeout=timeout_s):
            pass
    except OSError as error:
        raise InputError(
            "scheduler",
            redact(address),
            f"nothing accepts connections there ({error.strerror or error})",
            hint,
        ) from None
    if scheme == "tcp":
        target = f"tcp://[{host}]:{port}" if ":" in host else f"tcp://{host}:{port}"
        answer = _identity(target, timeout_s)
        if not (isinstance(answer, dict) and answer.get("type") == "Scheduler"):
            raise InputError(
                "scheduler",
                redact(address),
                f"did not answer as a Dask scheduler within {timeout_s:g} s ({_describe(answer)})",
                hint,
            )
    return address


def _describe(answer: object) -> str:
    if isinstance(answer, BaseException):
        text = str(answer) or type(answer).__name__
        return text.splitlines()[0][:120] if text.strip() else type(answer).__name__
    if isinstance(answer, dict):
        return f"it says it is a {str(answer.get('type'))[:40]!r}"
    return f"an answer of type {type(answer).__name__}"


def _identity(address: str, timeout_s: float) -> object:
    """The scheduler's answer to ``identity`` (a dict), or the exception that stopped it."""
    import asyncio

    import distributed.comm

    quiet_dask_logging()
    comm_module: Any = distributed.comm  # untyped library

    async def ask() -> object:
        comm = await comm_module.connect(address, timeout=timeout_s)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    try:
        return asyncio.run(asyncio.wait_for(ask(), timeout_s))
    except TimeoutError:
        return TimeoutError(f"no answer within {timeout_s:g} s")
    except Exception as error:  # garbage on the wire: whatever the decoder raised
        return error


def quiet_dask_logging() -> None:
    """Keep Dask's log records off stderr (distributed installs its own stderr handler when
    imported; sloshkit reports a campaign's failures itself, one line each).

    Returns
    -------
    None

    Examples
    --------
    >>> import logging
    >>> quiet_dask_logging()
    >>> logging.getLogger("distributed").propagate
    False
    """
    import logging

    prefixes = ("distributed", "dask", "tornado", "bokeh", "asyncio")
    names = [
        name for name in list(logging.root.manager.loggerDict) if name.split(".")[0] in prefixes
    ]
    for name in {*prefixes, *names}:
        logger = logging.getLogger(name)
        logger.handlers[:] = [logging.NullHandler()]
        logger.propagate = name not in prefixes  # children end at their quiet parent
