"""Check a ``--scheduler`` address before dask connects to it.

dask's client, pointed at something that is not a dask scheduler, can wait
for a handshake that never comes (an HTTP server waits for a request) or read
another protocol's greeting as a frame length and try to allocate exabytes.
So the address is parsed first, and for TCP a plain socket checks, within a
few seconds, that something listens there and greets as a dask scheduler does:
a scheduler writes its handshake first (``distributed.comm.core.Listener.
on_connection``), a TCP frame whose first 8 bytes are the little-endian byte
count of the message that follows (``distributed.comm.tcp``).
"""
from __future__ import annotations

import socket
import struct

from ..errors import FickcamError, InputError

#: seconds to wait for a connection and for the scheduler's greeting
PROBE_TIMEOUT = 3.0
#: a handshake is a small dict: a first frame header beyond this is not dask's
MAX_HANDSHAKE_BYTES = 1 << 20
EXAMPLE = "tcp://HOST:8786"


def scheduler_address(address: str) -> tuple[str, str, int | None]:
    """(scheme, host, port) of a dask scheduler address.

    Parameters
    ----------
    address : str
        The address, e.g. ``tcp://HOST:8786``.

    Returns
    -------
    scheme : str
        ``tcp``, ``tls``, ``ucx``...
    host : str
        The host (the whole location for a scheme other than tcp and tls).
    port : int or None
        The port (None for a scheme other than tcp and tls).

    Raises
    ------
    fickcam.errors.InputError
        For an http address, an unknown scheme or an address without a valid host.
    """
    # deferred: keeps distributed off the start-up path
    from distributed.comm.addressing import parse_address, parse_host_port

    text = address.strip()
    if text.split("://", 1)[0] in ("http", "https"):
        raise InputError(f"--scheduler {address}: an http address is a web page (the dask "
                         f"dashboard?); the scheduler listens on e.g. {EXAMPLE}")
    # deferred: keeps distributed off the start-up path
    from distributed.comm.registry import backends

    try:
        scheme, location = parse_address(text)
        if scheme not in backends:
            raise ValueError(f"unknown scheme {scheme!r} (known: {', '.join(sorted(backends))})")
        if scheme not in ("tcp", "tls"):
            return scheme, location, None
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise InputError(f"--scheduler {address}: {exc} (expected e.g. {EXAMPLE})") from None
    if not host or any(c.isspace() for c in host):
        raise InputError(f"--scheduler {address}: no valid host (expected e.g. {EXAMPLE})")
    return scheme, host, int(port)


def probe(address: str, timeout: float | None = None) -> None:
    """Raise unless a dask scheduler answers at ``address`` within ``timeout``.

    For TCP a plain socket checks that something listens there and greets as a dask
    scheduler does (a first frame of at most :data:`MAX_HANDSHAKE_BYTES`); other schemes are
    left to dask's own timeout.

    Parameters
    ----------
    address : str
        The scheduler's address.
    timeout : float, optional
        How long to wait for the connection and the greeting [s]; :data:`PROBE_TIMEOUT` by
        default.

    Raises
    ------
    fickcam.errors.InputError
        For a malformed address, an unknown host or another kind of server there (exit 2).
    fickcam.errors.FickcamError
        When nothing answers: refused, unreachable or silent (exit 1).
    """
    timeout = PROBE_TIMEOUT if timeout is None else timeout
    scheme, host, port = scheduler_address(address)
    if scheme != "tcp":  # tls, ucx, ws, inproc: left to dask's own timeout
        return
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except socket.gaierror as exc:
        raise InputError(f"--scheduler {address}: unknown host {host!r} ({exc.strerror})") from None
    except socket.timeout:
        raise FickcamError(f"no dask scheduler at {address}: no answer within {timeout:g} s "
                           f"(is it running?)") from None
    except OSError as exc:
        raise FickcamError(f"no dask scheduler at {address}: {exc.strerror or exc} "
                           f"(is it running?)") from None
    with sock:
        try:
            header = _read(sock, 8)
        except OSError:  # socket.timeout included: a silent server (an HTTP one waits)
            header = b""
    size = struct.unpack("<Q", header)[0] if len(header) == 8 else 0
    if not 0 < size <= MAX_HANDSHAKE_BYTES:
        raise InputError(f"--scheduler {address}: the server there is not a dask scheduler "
                         f"(it does not greet as one within {timeout:g} s); expected e.g. "
                         f"{EXAMPLE}")


def _read(sock, count: int) -> bytes:
    """Up to ``count`` bytes (fewer if the server closes the connection)."""
    data = b""
    while len(data) < count:
        chunk = sock.recv(count - len(data))
        if not chunk:
            break
        data += chunk
    return data
