"""The journal of a sweep: one append-only file to which each finished case is added
as it arrives, so that what is done stays done through any interruption (Ctrl-C,
``kill -9``, a lost machine).

Each entry is ``MAGIC | payload length | CRC-32 of the payload | payload`` (one
``write``), the payload the case's record (status, message, values, wall time) as
JSON followed by its result's arrays as raw bytes (numbers and times; text as
JSON). Opening the journal reads the entries in order and cuts the file back to
the last whole one: an entry torn by a kill fails its length or checksum and is
dropped (its case runs again), the ones before it are kept. No per-case netCDF
file is written and no combine pass reads them back: the result is built from the
journal in memory and written once.
"""
from __future__ import annotations

import json
import os
import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import WriteError
from ..messages import warn
from ..results.store import byte_size
import xarray as xr


MAGIC = b"FKJ1"
HEAD = struct.Struct("<4sQI")  # magic, payload length, CRC-32 of the payload
LENGTH = struct.Struct("<I")   # bytes of the JSON header at the start of a payload


def _plain(value):
    """JSON for numpy scalars and arrays in attributes."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"cannot store {type(value).__name__} in a sweep journal")


def encode_case(record: dict, dataset=None) -> bytes:
    """A case's journal payload: its record and (ok cases) every variable of its result.

    The payload is the JSON header's length, the header (the record and each variable's
    name, dims, attributes and place) and the numbers' raw bytes; text goes into the header.

    Parameters
    ----------
    record : dict
        The case's record (status, message, values, wall time [s]).
    dataset : xarray.Dataset, optional
        The result of an ok case; None for a failed one.

    Returns
    -------
    bytes
        The payload.

    Raises
    ------
    TypeError
        For an attribute JSON cannot hold (other than numpy scalars and arrays).
    """
    variables, blobs, offset = [], [], 0
    for name, variable in ({} if dataset is None else dataset.variables).items():
        data = np.asarray(variable.values)
        entry = {"name": name, "dims": list(variable.dims), "attrs": dict(variable.attrs),
                 "coord": name in dataset.coords, "shape": list(data.shape)}
        if data.dtype.kind in "OUS":
            entry["text"] = [str(v) for v in data.ravel()]
        else:
            data = np.ascontiguousarray(data)
            entry.update(dtype=data.dtype.str, offset=offset, nbytes=data.nbytes)
            blobs.append(data.tobytes())
            offset += data.nbytes
        variables.append(entry)
    head = json.dumps({"record": record, "variables": variables}, default=_plain).encode()
    return LENGTH.pack(len(head)) + head + b"".join(blobs)


def _header(payload: bytes) -> tuple[dict, int]:
    (size,) = LENGTH.unpack_from(payload)
    return json.loads(payload[LENGTH.size:LENGTH.size + size]), LENGTH.size + size


def decode_record(payload: bytes) -> dict:
    """The record stored in a journal payload.

    Parameters
    ----------
    payload : bytes
        A payload of :func:`encode_case`.

    Returns
    -------
    dict
        The case's record.
    """
    return _header(payload)[0]["record"]


@dataclass(frozen=True)
class CaseArrays:
    """A case's result as plain arrays, without the cost of an xarray.Dataset per case.

    (20 ms for the demo cam's 133 variables.)

    Parameters
    ----------
    data : dict
        Data variable name -> (dims, values, attrs).
    coords : dict
        Coordinate name -> (dims, values, attrs).
    """

    data: dict
    coords: dict

    @classmethod
    def of(cls, dataset) -> "CaseArrays":
        def plain(variables):
            return {name: (tuple(v.dims), v.values, dict(v.attrs)) for name, v in variables.items()}
        return cls(plain(dataset.data_vars), plain(dataset.coords))

    def to_dataset(self):
        return xr.Dataset({name: xr.Variable(*v) for name, v in self.data.items()},
                          coords={name: xr.Variable(*v) for name, v in self.coords.items()})


def decode_arrays(payload: bytes) -> CaseArrays | None:
    """The result of an ok case's payload as arrays (None for a failed case).

    Parameters
    ----------
    payload : bytes
        What :func:`encode_case` wrote for the case (an ok case's holds its arrays).

    Returns
    -------
    CaseArrays or None
        The arrays (numbers are read-only views of ``payload``).
    """
    header, start = _header(payload)
    if not header["variables"]:
        return None
    data_vars, coords = {}, {}
    for entry in header["variables"]:
        if "text" in entry:
            values = np.array(entry["text"], dtype=object).reshape(entry["shape"])
        else:
            first = start + entry["offset"]
            values = np.frombuffer(payload[first:first + entry["nbytes"]],
                                   dtype=np.dtype(entry["dtype"])).reshape(entry["shape"])
        (coords if entry["coord"] else data_vars)[entry["name"]] = (
            tuple(entry["dims"]), values, entry["attrs"])
    return CaseArrays(data_vars, coords)


def decode_dataset(payload: bytes):
    """The result Dataset of an ok case's payload (None for a failed case).

    Parameters
    ----------
    payload : bytes
        As for :func:`decode_arrays`.

    Returns
    -------
    xarray.Dataset or None
        The case's result.
    """
    arrays = decode_arrays(payload)
    return None if arrays is None else arrays.to_dataset()


@dataclass(frozen=True)
class Entry:
    """Where a case's payload lies in the journal, and its record.

    Parameters
    ----------
    record : dict
        The case's record.
    offset : int
        The payload's first byte in the file [byte].
    size : int
        The payload's length [byte].
    """

    record: dict
    offset: int
    size: int


class Journal:
    """The append-only case file of one sweep (``OUT.parts/cases.journal``).

    Parameters
    ----------
    path : pathlib.Path
        The journal file (it need not exist yet).
    """

    def __init__(self, path: Path):
        self.path = Path(path)

    def read(self) -> dict[int, Entry]:
        """The whole entries, the latest per case index; a torn tail is cut off."""
        entries: dict[int, Entry] = {}
        if not self.path.is_file():
            return entries
        with open(self.path, "rb+") as handle:
            end = 0
            while True:
                head = handle.read(HEAD.size)
                if len(head) < HEAD.size:
                    break
                magic, size, checksum = HEAD.unpack(head)
                payload = handle.read(size) if magic == MAGIC else b""
                if magic != MAGIC or len(payload) < size or zlib.crc32(payload) != checksum:
                    break
                record = decode_record(payload)
                entries[int(record["index"])] = Entry(record, end + HEAD.size, size)
                end += HEAD.size + size
            if end < os.fstat(handle.fileno()).st_size:
                warn("%s: dropped a partly written case at byte %d (it runs again)",
                     self.path, end)
                handle.truncate(end)
        return entries

    def append(self, payload: bytes) -> None:
        """Add one case (one write of header and payload; flushed to the OS at once)."""
        frame = HEAD.pack(MAGIC, len(payload), zlib.crc32(payload)) + payload
        try:
            with open(self.path, "ab") as handle:
                handle.write(frame)
        except OSError as exc:  # a torn frame is cut off when the sweep resumes
            reason = (exc.strerror or str(exc)).lower()
            raise WriteError(f"{self.path}: cannot add a finished case ({reason}): it needs "
                             f"{byte_size(len(frame))} more; the cases written so far are "
                             f"kept, and the same command resumes from them") from None

    def payload(self, entry: Entry) -> bytes:
        with open(self.path, "rb") as handle:
            handle.seek(entry.offset)
            return handle.read(entry.size)
