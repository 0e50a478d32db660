"""Build the result Dataset from SI arrays through the schema table."""
from __future__ import annotations

import numpy as np

from .schema import COORDINATES, VARIABLES


def ageing_time_days(seconds):
    """The ``ageing_time`` coordinate along ``time``: float days (units ``d``), which
    matplotlib plots and ``interp`` interpolates, unlike the timedelta ``time``."""
    import xarray as xr

    units, long_name = COORDINATES["ageing_time"]
    return xr.Variable(("time",), np.asarray(seconds, float) / 86400.0,
                       {"units": units, "long_name": long_name})


def build_dataset(values: dict, coords: dict, attrs: dict | None = None):
    """An xarray.Dataset with every variable of ``values`` (SI arrays keyed by
    schema name) stored in its schema unit, with ``units`` and ``long_name``.

    ``coords`` gives ``time`` in seconds and the other coordinates as the
    schema expects (angles in rad, names as strings); ``ageing_time`` (days)
    is added beside ``time``. Variables a scene does
    not model are simply absent from ``values``.
    """
    import xarray as xr

    coordinates = {}
    for name, value in coords.items():
        units, long_name = COORDINATES[name]
        value = np.asarray(value)
        if name == "time":
            value = (np.asarray(value, float) * 1e9).round().astype("timedelta64[ns]")
        elif units == "degree":
            value = np.degrees(np.asarray(value, float))
        attrs_c = {"long_name": long_name}
        if units:
            attrs_c["units"] = units
        coordinates[name] = xr.Variable((name,), value, attrs_c)
    if "time" in coords:
        coordinates["ageing_time"] = ageing_time_days(coords["time"])
    data_vars = {}
    for name, value in values.items():
        if name not in VARIABLES:  # no silent drops: every result has its row in the schema
            raise KeyError(f"{name!r} is not declared in fickcam/schema.py (add its row there)")
        var = VARIABLES[name]
        array = np.asarray(value)
        if array.dtype.kind in "fc":
            array = array * var.scale
        expected = tuple(coordinates[d].shape[0] for d in var.dims if d in coordinates)
        if len(expected) == len(var.dims) and array.shape != expected:
            raise ValueError(f"{name}: shape {array.shape} does not match dims {var.dims} {expected}")
        data_vars[name] = xr.Variable(var.dims, array,
                                      {"units": var.units or "1", "long_name": var.long_name})
    return xr.Dataset(data_vars, coords=coordinates, attrs=dict(attrs or {}))
