"""A result written as a netCDF4 file through h5py in one pass.

xarray's ``h5netcdf`` engine keeps netCDF's dimension bookkeeping by asking h5netcdf, which
looks every dimension and variable up in the file again for each variable it writes and
attaches each variable to its dimension scales one call at a time (each call rewrites the
scale's whole list of the variables attached to it). For a result's ~140 small variables
that bookkeeping, not the numbers, was most of the write. :func:`write` lays out the same
file in one pass: xarray's own CF encoding (``xarray.conventions.cf_encoder``), then
each variable as an HDF5 dataset with its attributes, and each dimension scale's list of
the variables attached to it written once, at the end.

The file is the one h5netcdf writes: netCDF4's dimension scales (``CLASS``, ``NAME``,
``REFERENCE_LIST``; ``DIMENSION_LIST`` on the variables), netCDF-C's dimension ids
(``_Netcdf4Dimid``, ``_Netcdf4Coordinates``), attributes and links in creation order and
``_NCProperties``; xarray, h5netcdf and netCDF-C read it as they read h5netcdf's.
:func:`writable` says which datasets it takes (in memory, with the encodings listed in
:data:`ENCODINGS`); :mod:`fickcam.results.store` writes the others through xarray.
"""
from __future__ import annotations

import numpy as np
from xarray import conventions

#: encoding keys :func:`write` applies (``zlib``/``complevel``/``shuffle``/``chunksizes``/
#: ``fletcher32``), those xarray's encoder applies before (``dtype``, ``_FillValue``,
#: ``units``, ``calendar``), and those an opened file's variables carry that say how they
#: were stored and that xarray's h5netcdf engine leaves out too
ENCODINGS = frozenset({"zlib", "complevel", "shuffle", "chunksizes", "fletcher32", "contiguous",
                       "dtype", "_FillValue", "units", "calendar", "source", "original_shape",
                       "preferred_chunks", "coordinates", "szip", "zstd", "bzip2", "blosc", "compression",
                       "compression_opts"})
#: compressions other than deflate (their filters need plugins): such a variable is written
#: through xarray
OTHER_FILTERS = ("szip", "zstd", "bzip2", "blosc")
#: a dimension without a coordinate variable: the name netCDF-C gives its scale (its length
#: follows in ten characters)
NOT_A_VARIABLE = b"This is a netCDF dimension but not a netCDF variable."


def writable(ds) -> bool:
    """Whether :func:`write` writes ``ds``: its variables in memory, their names free of the
    dimension names other variables hold, their encodings among :data:`ENCODINGS`,
    compressed, if at all, by deflate, and without a fill value (a float's missing value is
    NaN itself: ``encoding["_FillValue"] = None``, as :func:`fickcam.results.store.save` sets).

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset to write.

    Returns
    -------
    bool
        True when :func:`write` writes it as xarray's h5netcdf engine would.
    """
    for name, variable in ds.variables.items():
        encoding = variable.encoding
        if (variable.chunks is not None or not ENCODINGS.issuperset(encoding)
                or any(encoding.get(key) for key in OTHER_FILTERS)
                or encoding.get("_FillValue", variable.attrs.get("_FillValue")) is not None
                or (variable.dtype.kind == "f" and "_FillValue" not in encoding)
                or "missing_value" in variable.attrs
                or encoding.get("compression") not in (None, "gzip", "zlib")
                or (name in ds.dims and variable.dims != (name,))
                or variable.dtype.kind not in "fiubUO"):
            return False
    return True


def encoded(ds, coordinates=()) -> tuple[dict, dict]:
    """The variables and attributes as xarray writes them: non-dimension coordinates named in
    each variable's ``coordinates`` attribute, CF encoding, ``coordinates`` first (each
    dimension's coordinate is then its scale before a variable is attached to it)."""

    variables, attributes = conventions.encode_dataset_coordinates(ds)
    variables, attributes = conventions.cf_encoder(variables, attributes)
    first = [name for name in coordinates if name in variables]
    order = first + [name for name in variables if name not in first]
    return {name: variables[name] for name in order}, attributes


def dimension_ids(variables: dict) -> dict[str, tuple[int, int]]:
    """Dimension name -> (netCDF id, length), numbered in the order the variables first use
    them (as xarray creates them)."""
    ids: dict[str, tuple[int, int]] = {}
    for variable in variables.values():
        for dim, length in zip(variable.dims, variable.shape):
            ids.setdefault(dim, (len(ids), length))
    return ids


def stored(variable):
    """The values and HDF5 type of one encoded variable (text as variable-length UTF-8)."""
    # deferred: keeps h5py off the start-up path
    import h5py

    values = np.asarray(variable.values)
    if values.dtype.kind in "UO":
        return np.array(values.tolist(), dtype=object).reshape(values.shape), h5py.string_dtype()
    return values, values.dtype


def storage(variable) -> dict:
    """h5py's ``create_dataset`` options for a variable's encoding (deflate, shuffle, chunks,
    checksum), as xarray's h5netcdf engine passes them."""
    encoding = variable.encoding
    options = {}
    if encoding.get("zlib") or encoding.get("compression") in ("gzip", "zlib"):
        options.update(compression="gzip",
                       compression_opts=encoding.get("complevel")
                       or encoding.get("compression_opts") or 4)
    if encoding.get("shuffle") and variable.ndim:
        options["shuffle"] = True
    if encoding.get("fletcher32") and variable.ndim:
        options["fletcher32"] = True
    chunks = encoding.get("chunksizes")
    if chunks and variable.ndim:
        options["chunks"] = tuple(min(int(c), n) for c, n in zip(chunks, variable.shape))
    return options


class Attributes:
    """New attributes written through HDF5's own calls (``h5py.h5a``), their types and
    dataspaces made once per kind and shape.

    h5py's attribute manager first looks the name up (to replace an attribute that exists)
    and makes the attribute's HDF5 types anew each time: for a result's ~760 attributes, all
    new and of a few kinds, that took 3-4 times the writing itself. Text, numbers and number
    arrays (and the dimension lists' references, their type given) are written here the way
    h5py writes them; anything else goes through h5py's manager.
    """

    def __init__(self):
        # deferred: keeps h5py off the start-up path
        import h5py

        self.h5py = h5py
        self.text = h5py.string_dtype()
        self.types: dict = {}
        self.spaces: dict = {}

    def put(self, target, name: str, value, dtype=None) -> None:
        """Create the attribute ``name`` of ``target``, which has none of that name.

        Parameters
        ----------
        target : h5py.Dataset or h5py.Group
            The object (a file's attributes are its root group's).
        name : str
            The attribute's name.
        value : str, number or numpy.ndarray
            Text is written as a variable-length UTF-8 string, numbers as they are.
        dtype : numpy.dtype, optional
            The type to write ``value`` as (h5py's, as for ``attrs.create``).
        """
        h5py = self.h5py
        if dtype is not None:
            data = np.asarray(value, dtype=dtype)
        elif isinstance(value, str):
            data, dtype = np.array(value, dtype=self.text), self.text
        else:
            data = np.asarray(value)
            dtype = data.dtype
            if dtype.kind not in "fiu" or not dtype.isnative or not name.isascii():
                target.attrs[name] = value
                return
        key = (dtype.str, repr(dtype.metadata))
        if key not in self.types:  # the type in the file, and the one in memory
            self.types[key] = (h5py.h5t.py_create(dtype, logical=True), h5py.h5t.py_create(dtype))
        stored, memory = self.types[key]
        if data.shape not in self.spaces:
            self.spaces[data.shape] = (h5py.h5s.create(h5py.h5s.SCALAR) if data.ndim == 0
                                       else h5py.h5s.create_simple(data.shape))
        attribute = h5py.h5a.create(target.id, name.encode(), stored, self.spaces[data.shape])
        try:
            attribute.write(np.ascontiguousarray(data), mtype=memory)
        finally:
            attribute.close()


def set_attributes(writer: Attributes, target, attributes: dict) -> None:
    """Write netCDF attributes as h5netcdf does: text as a variable-length string, a number
    as an array of one value, arrays as they are."""
    for key, value in attributes.items():
        if np.isscalar(value) and np.asarray(value).dtype.kind not in "SU":
            value = np.atleast_1d(value)
        writer.put(target, key, value)


def write(ds, filename) -> None:
    """Write an in-memory dataset (:func:`writable`) to a new netCDF4 file through h5py.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset (attributes already netCDF types: text, numbers, arrays).
    filename : str or file-like
        The file to create (overwritten), or a binary file object open for writing
        (h5py writes through it).
    """
    # deferred: keeps h5py off the start-up path
    import h5py

    variables, attributes = encoded(ds, tuple(ds.coords))
    dims = dimension_ids(variables)
    writer = Attributes()
    with h5py.File(filename, "w", track_order=True) as file:
        scales = {}
        for dim, (dimid, length) in dims.items():
            if dim not in variables:
                scale = file.create_dataset(dim, shape=(length,), dtype=">f4", track_order=True)
                h5py.h5ds.set_scale(scale.id, NOT_A_VARIABLE + f"{length:10}".encode())
                writer.put(scale, "_Netcdf4Dimid", np.int32(dimid))
                scales[dim] = scale
        attached: dict[str, list] = {dim: [] for dim in dims}
        for name, variable in variables.items():
            values, dtype = stored(variable)
            dataset = file.create_dataset(name, data=values, dtype=dtype, track_order=True,
                                          **storage(variable))
            ids = np.array([dims[dim][0] for dim in variable.dims], dtype=np.int32)
            if variable.dims == (name,):
                h5py.h5ds.set_scale(dataset.id, name.encode())
                scales[name] = dataset
            elif variable.dims:
                refs = np.empty(len(ids), dtype=object)
                for axis, dim in enumerate(variable.dims):
                    refs[axis] = np.array([scales[dim].ref], dtype=h5py.ref_dtype)
                    attached[dim].append((dataset.ref, axis))
                writer.put(dataset, "DIMENSION_LIST", refs, h5py.vlen_dtype(h5py.ref_dtype))
            if variable.dims:
                writer.put(dataset, "_Netcdf4Coordinates", ids)
                writer.put(dataset, "_Netcdf4Dimid", ids[0])
            set_attributes(writer, dataset, variable.attrs)
        reference = np.dtype({"names": ["dataset", "dimension"], "offsets": [0, 8],
                              "formats": [h5py.ref_dtype, "<u4"], "itemsize": 16})  # as H5DS's
        for dim, refs in attached.items():
            if refs:
                scales[dim].attrs["REFERENCE_LIST"] = np.array(refs, dtype=reference)
        set_attributes(writer, file["/"], attributes)
        properties = (f"version=2,h5py={h5py.__version__},"
                      f"hdf5={h5py.version.hdf5_version}")
        file.attrs["_NCProperties"] = np.array(
            properties, dtype=h5py.string_dtype("ascii", len(properties)))
