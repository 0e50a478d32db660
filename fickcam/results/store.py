"""Result files: netCDF4/HDF5 through xarray's h5netcdf engine, written atomically.

:func:`~fickcam.results.store.save` writes to a temporary file in the target folder, flushes it to
disk and renames it over the target (``os.replace`` is atomic on POSIX), so a
crash or ``kill -9`` at any moment leaves either the old file or the new one,
never a damaged file.
"""
from __future__ import annotations

import json
import math
import os
import shutil
from pathlib import Path

from ..errors import InputError, WriteError
from ..files import remove_stale_temporaries, temporary_beside


#: a result above this [bytes, in memory] is written in chunks, its large variables
#: compressed, and read lazily (:func:`open_result`)
CHUNKED_ABOVE = 64 * 2**20
#: the bytes of one chunk of a large variable: a query reads the chunks it needs
CHUNK_BYTES = 2**20


def chunked_encoding(variable) -> dict:
    """The encoding of one variable of a large result: chunks of about :data:`CHUNK_BYTES`
    along its first dimension (``time``: an ageing time's angles stay together), deflated
    (zlib level 1 after the byte shuffle, lossless); {} for a variable smaller than a chunk.

    Parameters
    ----------
    variable : xarray.Variable
        A number variable of the result.

    Returns
    -------
    dict
        The encoding to add (``chunksizes``, ``zlib``, ``complevel``, ``shuffle``).
    """
    if variable.nbytes <= CHUNK_BYTES or variable.dtype.kind not in "fiub" or not variable.ndim:
        return {}
    row = variable.dtype.itemsize * math.prod(variable.shape[1:])
    first = max(1, min(variable.shape[0], CHUNK_BYTES // max(row, 1)))
    return {"chunksizes": (first, *variable.shape[1:]), "zlib": True, "complevel": 1,
            "shuffle": True}


def _netcdf_attrs(attrs: dict) -> dict:
    """netCDF attributes must be str, numbers or 1-D arrays: dicts/lists go to JSON."""
    out = {}
    for key, value in attrs.items():
        if isinstance(value, (dict, list, tuple)) or value is None:
            out[key] = json.dumps(value)
        elif isinstance(value, bool):
            out[key] = int(value)
        else:
            out[key] = value
    return out


class GuardedFile:
    """A binary file for HDF5's file-object driver that never shows HDF5 a failed write.

    HDF5 cannot recover from a write that fails half-way (a full disk): every later call
    fails, h5py's objects fail again as they are freed, and the interpreter can crash at exit.
    Through this file, HDF5 sees every write succeed: the first :class:`OSError` is kept in
    ``error``, the writes after it only advance ``size``, and the caller, once HDF5
    has closed the file, removes it and reports the error with the size the whole file needed.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write (created or truncated).

    Attributes
    ----------
    error : OSError or None
        The first write that failed.
    size : int
        The file's size had every write succeeded [bytes].
    """

    def __init__(self, path):
        self.path = str(path)
        self.error: OSError | None = None
        self.size = 0
        self._file = open(path, "w+b", buffering=0)  # unbuffered: a seek never writes

    def _guard(self, call, *args):
        if self.error is None:
            try:
                return call(*args)
            except OSError as exc:
                self.error = exc
        return None

    def seek(self, offset: int, whence: int = 0) -> int:
        return self._file.seek(offset, whence)

    def tell(self) -> int:
        return self._file.tell()

    def readinto(self, buffer) -> int:
        return self._file.readinto(buffer)

    def read(self, size: int = -1) -> bytes:
        return self._file.read(size)

    def write(self, data) -> int:
        view = memoryview(data).cast("B")
        end = self._file.tell() + view.nbytes
        self.size = max(self.size, end)
        done = 0
        while self.error is None and done < view.nbytes:  # a raw write may write less
            done += self._guard(self._file.write, view[done:]) or 0
        self._file.seek(end)  # as if all written: HDF5 goes on from its end
        return view.nbytes

    def truncate(self, size: int | None = None) -> int:
        size = self._file.tell() if size is None else size
        self.size = size
        self._guard(self._file.truncate, size)
        return size

    def flush(self) -> None:
        self._guard(self._file.flush)

    def seekable(self) -> bool:
        return True

    def readable(self) -> bool:
        return True

    def writable(self) -> bool:
        return True

    def close(self, sync: bool = True) -> None:
        """Sync to the disk (``sync``) and close; a failure is kept in ``error``."""
        if sync:
            self._guard(os.fsync, self._file.fileno())
        try:
            self._file.close()
        except OSError as exc:
            self.error = self.error or exc

    @property
    def closed(self) -> bool:
        return self._file.closed


def free_space(folder) -> int | None:
    """The bytes free to this user on ``folder``'s file system (None when unknown).

    Parameters
    ----------
    folder : str or pathlib.Path
        An existing folder.

    Returns
    -------
    int or None
        The free space [bytes].
    """

    try:
        return shutil.disk_usage(folder).free
    except OSError:
        return None


def byte_size(count: float) -> str:
    """``4.8 GB``, ``478 kB``: a size in bytes for people (decimal units, 3 digits).

    Parameters
    ----------
    count : float
        The size [bytes].

    Returns
    -------
    str
        The size with its unit.
    """
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if count >= scale:
            return f"{count / scale:.3g} {unit}"
    return f"{count:.0f} B"


def write_failure(path: Path, error: OSError, needed: int | None, kept: bool) -> WriteError:
    """The one line for a result that could not be written: the path, why, the space.

    Parameters
    ----------
    path : pathlib.Path
        The file that was to be written.
    error : OSError
        The failure (a full disk, a file size limit, a quota).
    needed : int or None
        The size the file needed [bytes].
    kept : bool
        Whether an earlier file at ``path`` is still there, untouched.

    Returns
    -------
    fickcam.errors.WriteError
        The error to raise.
    """
    reason = error.strerror or str(error)
    free = free_space(path.parent if str(path.parent) else ".")
    space = "" if needed is None else f": the result needs {byte_size(needed)}" + (
        "" if free is None else f", {byte_size(free)} free there")
    earlier = "the earlier file there is kept" if kept else "nothing was written"
    return WriteError(f"{path}: cannot write ({reason.lower()}){space}; {earlier}")


def _write_netcdf(ds, target: GuardedFile) -> None:
    """What ``ds.to_netcdf(filename, engine="h5netcdf")`` writes for in-memory data, through
    xarray's own store on an open h5netcdf.File, with the coordinates created first
    (:func:`coordinates_first`) and the number variables' attributes written in one go per
    variable (:func:`hold_attributes`): ``to_netcdf`` and ``H5NetCDFStore.open`` first ask
    dask for its scheduler, which imports dask.distributed (about 0.5 s) even when no variable
    is a dask array. Dask-backed data (a sweep's lazily combined cases) goes through
    ``to_netcdf``, which computes and writes it (data variables first). An in-memory dataset
    whose encodings :mod:`fickcam.results.ncwrite` knows is written by it in one pass through h5py
    (the same file, without h5netcdf's per-variable bookkeeping)."""
    # deferred: keeps numpy off the start-up path
    from . import ncwrite

    if ncwrite.writable(ds):
        ncwrite.write(ds, target)
        return
    # deferred: keeps h5netcdf off the start-up path
    import h5netcdf
    import h5py

    h5file = h5py.File(target, "w", track_order=True)  # as h5netcdf would make it
    try:
        if any(variable.chunks is not None for variable in ds.variables.values()):
            ds.to_netcdf(h5file, engine="h5netcdf")
            return
        # deferred: keeps h5netcdf off the start-up path
        from xarray.backends import H5NetCDFStore

        held: dict[str, dict] = {}

        def encoder(variables: dict, attributes: dict) -> tuple[dict, dict]:
            variables, attributes = coordinates_first(variables, attributes, tuple(ds.coords))
            return hold_attributes(variables, held), attributes

        store = H5NetCDFStore(h5netcdf.File(h5file, "w"), mode="w")  # .open() asks dask too
        try:
            ds.dump_to_store(store, encoder=encoder)
            write_held_attributes(store.ds, held)
        finally:
            store.close()
    finally:
        h5file.close()  # here, not when the interpreter frees it


def coordinates_first(variables: dict, attributes: dict, coordinates=()) -> tuple[dict, dict]:
    """The variables xarray is about to write, the coordinates first.

    xarray writes a Dataset's variables in its own order, data before coordinates: h5netcdf
    then attaches each data variable to a placeholder scale of each of its dimensions, and
    when the dimension's coordinate comes, detaches them all, replaces the placeholder with
    the coordinate and attaches them again (a sixth of the demo cam's write in CPU seconds).
    Written first, each coordinate is its dimension's scale from the start. Reading the file
    gives the same Dataset, in the same order (xarray lists the data variables, then the
    coordinates, whatever their order in the file).

    Parameters
    ----------
    variables : dict
        Name -> xarray.Variable, as xarray's ``dump_to_store`` hands them to its encoder.
    attributes : dict
        The file's attributes (returned as they are).
    coordinates : sequence of str
        The Dataset's coordinates, in its order.

    Returns
    -------
    tuple of (dict, dict)
        The same variables, ``coordinates`` first, then the others in their order; the
        attributes.
    """
    first = {name: variables[name] for name in coordinates if name in variables}
    return {**first, **{name: v for name, v in variables.items() if name not in first}}, attributes


#: attributes xarray's encoding reads or writes: a variable carrying one keeps its
#: attributes for xarray to write (:func:`hold_attributes`)
ENCODING_ATTRIBUTES = frozenset({"_FillValue", "missing_value", "scale_factor", "add_offset",
                                 "_Unsigned", "_Encoding", "dtype", "calendar"})


def hold_attributes(variables: dict, held: dict) -> dict:
    """Move the attributes of the number variables xarray is about to write into ``held``.

    xarray writes a variable's attributes one by one, and h5netcdf looks the variable up in
    the file again for each (the demo cam's 282 attributes: 7 % of its write in CPU
    seconds); :func:`write_held_attributes` writes each variable's through one look-up, in
    the same order. Only float and integer variables without an attribute xarray's encoding
    reads or writes (:data:`ENCODING_ATTRIBUTES`) give theirs: their encoding neither reads
    nor changes them, so the file reads back to the same Dataset, attributes in the same
    order.

    Parameters
    ----------
    variables : dict
        Name -> xarray.Variable, xarray's own copies as its ``dump_to_store`` hands them to
        its encoder (their attributes are replaced by empty ones).
    held : dict
        Receives name -> attributes.

    Returns
    -------
    dict
        ``variables``.
    """
    for name, variable in variables.items():
        if (variable.dtype.kind in "fiu" and variable.attrs
                and not ENCODING_ATTRIBUTES & variable.attrs.keys()):
            held[name] = variable.attrs
            variable.attrs = {}
    return variables


def write_held_attributes(group, held: dict) -> None:
    """Write the attributes :func:`hold_attributes` took, each variable's in one go.

    Parameters
    ----------
    group : h5netcdf.Group
        The file (its root group) the variables were written to.
    held : dict
        Name -> attributes.
    """
    for name, attributes in held.items():
        target = group.variables[name].attrs
        for key, value in attributes.items():
            target[key] = value


def save(dataset, path, compress: bool = False) -> Path:
    """Write ``dataset`` to ``path`` (netCDF4/HDF5) atomically and return the path.

    The data go to a temporary file in the target folder, flushed to disk and renamed over the
    target, so a crash leaves the old file or the new one, never a damaged one. Dict and list
    attributes are stored as JSON. An in-memory dataset's coordinates are written before its
    data variables (:func:`coordinates_first`) and its number variables' attributes each in
    one go (:func:`hold_attributes`); a sweep's dask-backed one goes through ``to_netcdf``.

    Parameters
    ----------
    dataset : xarray.Dataset
        A result (:func:`fickcam.run`, a sweep's combined result).
    path : str or pathlib.Path
        The file to write (its folder is made if needed).
    compress : bool
        Deflate the numbers (zlib level 1 after the byte shuffle, lossless): the demo cam's
        sweep results shrink 1.5-2.2 x for about 40 % more write time. A result above
        :data:`CHUNKED_ABOVE` has its large variables chunked and deflated whatever this
        says (:func:`chunked_encoding`).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    folder.mkdir(parents=True, exist_ok=True)
    ds = dataset.copy(deep=False)  # new Variable objects: the caller's are left as they are
    ds.attrs = _netcdf_attrs(ds.attrs)
    large = ds.nbytes > CHUNKED_ABOVE
    for variable in ds.variables.values():  # each Variable itself (no DataArray per access)
        variable.attrs = _netcdf_attrs(variable.attrs)
        if variable.dtype.kind == "f" and "_FillValue" not in variable.encoding:
            # a missing value is NaN itself: no _FillValue attribute (15 % of the write)
            variable.encoding["_FillValue"] = None
        if compress and variable.dtype.kind in "fiub" and variable.ndim:
            variable.encoding.update(zlib=True, complevel=1, shuffle=True)
        if large:
            variable.encoding.update(chunked_encoding(variable))
    remove_stale_temporaries(path)
    with temporary_beside(path) as tmp:
        target = GuardedFile(tmp)
        try:
            _write_netcdf(ds, target)
        except Exception:
            if target.error is None:  # else HDF5 tripped over what the failed write lost
                raise
        finally:
            target.close()
        if target.error is not None:
            Path(tmp).unlink(missing_ok=True)  # before the free space is measured
            raise write_failure(path, target.error, target.size, path.exists())
        os.replace(tmp, path)
    try:  # make the rename durable too
        dir_fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)
    except OSError:
        pass
    return path


JSON_ATTRIBUTES = ("diffusion", "notices", "sweep_parameters", "limits")


def open_result(path):
    """Open a result written by :func:`save`, with ``time`` in float days.

    A file written when fickcam stored a timedelta ``time`` is read into days too; the JSON
    attributes (``JSON_ATTRIBUTES``) are decoded.

    Parameters
    ----------
    path : str or pathlib.Path
        A netCDF/HDF5 file written by :func:`save`.

    Returns
    -------
    xarray.Dataset
        The result, loaded into memory (the file is closed); a result above
        :data:`CHUNKED_ABOVE` (in memory) is read lazily instead: each variable is read when its values
        are asked for, only the chunks asked for (the file stays open until the Dataset is
        closed or freed).

    Raises
    ------
    fickcam.errors.InputError
        When the file does not exist or is not a netCDF/HDF5 result.
    """
    # deferred: keeps xarray off the start-up path
    import xarray as xr

    # deferred: keeps numpy off the start-up path
    from .dataset import with_time_in_days

    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such result file")
    try:
        ds = xr.open_dataset(path, engine="h5netcdf", decode_timedelta=True)
        if ds.nbytes <= CHUNKED_ABOVE:  # the shapes only: nothing is read for it
            ds.load()
            ds.close()
        ds = with_time_in_days(ds)
    except Exception as exc:  # h5py/xarray raise many types for a non-netCDF file
        raise InputError(f"{path}: not a fickcam result file ({type(exc).__name__}: {exc})") from None
    for key in JSON_ATTRIBUTES:
        if isinstance(ds.attrs.get(key), str):
            try:
                ds.attrs[key] = json.loads(ds.attrs[key])
            except json.JSONDecodeError:
                pass
    return ds
