"""Export a result for use elsewhere: tidy CSV, netCDF or JSON."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..errors import InputError
from .query import csv_cell, to_records
from ..files import write_text_atomically
from .store import save
from .query import supported_values
from ..schema import VARIABLES


def _chosen(ds, variables):
    names = list(variables) if variables else [v for v in ds.data_vars]
    missing = [v for v in names if v not in ds.data_vars]
    if missing:
        raise InputError(f"not in this result: {', '.join(missing)}")
    return names


def export_csv(ds, path, variables=None) -> Path:
    """Tidy CSV: columns variable, units, one per dimension (time in days as
    ``time_d``; blank where a variable lacks that dimension) and value.

    Parameters
    ----------
    ds, path, variables
        As in :func:`export`; ``path`` is the CSV file.

    Returns
    -------
    pathlib.Path
        The tidy CSV file.
    """
    names = _chosen(ds, variables)
    dims: list[str] = []
    for name in names:
        for d in ds[name].dims:
            if d not in dims:
                dims.append(d)
    header_dims = [("time_d" if d == "time" else d) for d in dims]
    lines = [",".join(["variable", "units"] + header_dims + ["value"])]
    for name in names:
        columns, rows = to_records(ds[name])
        position = {c: i for i, c in enumerate(columns)}
        units = ds[name].attrs.get("units", "")
        for row in rows:
            cells = [name, units]
            cells += [csv_cell(row[position[c]]) if c in position else "" for c in header_dims]
            cells.append(csv_cell(row[-1]))
            lines.append(",".join(cells))
    path = Path(path)
    write_text_atomically(path, "\n".join(lines) + "\n")
    return path


def export_json(ds, path, variables=None) -> Path:
    """JSON: coordinates and, per variable, dims, units, long_name and nested data.

    Parameters
    ----------
    ds, path, variables
        As in :func:`export` (NaN is written as null).

    Returns
    -------
    pathlib.Path
        The JSON document, one line.
    """
    names = _chosen(ds, variables)
    coords = {}
    for name in ds.coords:
        coords["time_d" if name == "time" else name] = ds[name].values.tolist()
    document = {
        "attributes": {k: (v if isinstance(v, (str, int, float, list, dict)) else str(v))
                       for k, v in ds.attrs.items()},
        "coordinates": coords,
        "variables": {
            name: {"dims": list(ds[name].dims), "units": ds[name].attrs.get("units", ""),
                   "long_name": ds[name].attrs.get("long_name", ""),
                   "data": np.where(np.isnan(ds[name].values), None, ds[name].values).tolist()
                   if ds[name].dtype.kind == "f" else ds[name].values.tolist()}
            for name in names
        },
    }
    path = Path(path)
    write_text_atomically(path, json.dumps(document))
    return path


def export_netcdf(ds, path, variables=None) -> Path:
    """netCDF-4 (HDF5): the chosen variables, written by :func:`fickcam.save`.

    Parameters
    ----------
    ds, path, variables
        As in :func:`export`; the file is netCDF-4 (HDF5).

    Returns
    -------
    pathlib.Path
        What :func:`fickcam.save` wrote.
    """

    names = _chosen(ds, variables)
    return save(ds[names], path)


def with_supported_digits(ds):
    """A copy of ``ds`` whose variables with an error estimate (the schema's ``error``,
    e.g. ``time_out_of_spec``) hold only the digits it supports, as the CSV and JSON
    exports write them (the estimate is written beside them; netCDF keeps every digit).

    Parameters
    ----------
    ds : xarray.Dataset
        A result.

    Returns
    -------
    xarray.Dataset
        The copy.
    """

    out = ds.copy()
    for name in ds.data_vars:
        error = VARIABLES[name].error if name in VARIABLES else ""
        if error in ds and ds[error].dims == ds[name].dims:
            out[name] = ds[name].copy(data=supported_values(ds[name].values, ds[error].values,
                                                            text=False))
    return out


EXPORTERS = {"csv": export_csv, "json": export_json, "netcdf": export_netcdf}


def export(ds, path, fmt: str, variables=None) -> Path:
    """Write a result in the format ``fmt`` (``fickcam export``).

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    path : str or pathlib.Path
        The file to write (atomically).
    fmt : {"csv", "json", "netcdf"}
        The format: tidy CSV (:func:`export_csv`), JSON (:func:`export_json`) or
        netCDF-4 (:func:`export_netcdf`).
    variables : list of str, optional
        The variables to write; None: all of them.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    fickcam.errors.InputError
        When the format is unknown or a variable asked for is not in the result.
    """
    if fmt not in EXPORTERS:
        raise InputError(f"unknown export format {fmt!r} (csv, netcdf or json)")
    return EXPORTERS[fmt](ds if fmt == "netcdf" else with_supported_digits(ds), path, variables)
