"""Build the result Dataset from SI arrays through the schema table."""
from __future__ import annotations

import numpy as np

from ..schema import COORDINATES, VARIABLES
from ..errors import TIME_UNITS, time_unit


DAY = 86400.0  # s


def ageing_days(seconds) -> np.ndarray:
    """Ageing times as the float days of the ``time`` coordinate.

    Parameters
    ----------
    seconds : array_like
        Ageing times [s].

    Returns
    -------
    numpy.ndarray
        The same times [d].
    """
    return np.asarray(seconds, float) / DAY


def ageing_seconds(ds) -> np.ndarray:
    """The ageing times of a result.

    Parameters
    ----------
    ds : xarray.Dataset
        A result, its ``time`` coordinate in float days [d].

    Returns
    -------
    numpy.ndarray
        Its ageing times [s].
    """
    return np.asarray(ds["time"].values, float) * DAY


def report_time_unit(ds) -> tuple[str, float]:
    """The unit a result's times are reported in: the one its scene's ageing times were
    written in (attribute ``time_unit``), else the one that suits its last ageing time.

    Parameters
    ----------
    ds : xarray.Dataset
        A result.

    Returns
    -------
    tuple of (str, float)
        The unit's name and its length [s].
    """

    name = ds.attrs.get("time_unit", "")
    known = {unit: length for unit, length, _ in TIME_UNITS}
    if name in known:
        return name, known[name]
    has_times = "time" in ds.coords and ds.sizes.get("time", 0) > 0
    return time_unit(ageing_seconds(ds)[-1] if has_times else float("nan"))


def ageing_time_days(seconds):
    """The ``ageing_time`` coordinate along ``time``: the same float days (units ``d``).

    It is kept beside ``time`` for code written when ``time`` was a timedelta.

    Parameters
    ----------
    seconds : array_like
        The ageing times [s].

    Returns
    -------
    xarray.Variable
        The ageing times [d].
    """
    # deferred: keeps xarray off the start-up path
    import xarray as xr

    units, long_name = COORDINATES["ageing_time"]
    return xr.Variable(("time",), ageing_days(seconds), {"units": units, "long_name": long_name})


def with_time_in_days(ds):
    """A result with its ``time`` in float days, whichever way its file stored it.

    Parameters
    ----------
    ds : xarray.Dataset
        A result; its ``time`` may be timedelta64 (files written by fickcam before time
        was stored in days) or float days [d].

    Returns
    -------
    xarray.Dataset
        ``ds`` itself when ``time`` is already in days, else a copy with ``time`` (and an
        ``ageing_time`` beside it) in float days [d], units ``d``.
    """
    if "time" not in ds.coords or ds["time"].dtype.kind != "m":
        return ds
    units, long_name = COORDINATES["time"]
    days = ds["time"].values / np.timedelta64(1, "D")
    ds = ds.assign_coords(time=("time", days, {"units": units, "long_name": long_name}))
    if "ageing_time" not in ds.coords:
        ds = ds.assign_coords(ageing_time=ageing_time_days(days * DAY))
    return ds


def stored_unit(name: str, value) -> np.ndarray:
    """A variable's values in its stored unit, as :func:`build_dataset` stores them.

    Parameters
    ----------
    name : str
        The variable's schema name.
    value : array_like
        Its values [SI]; text or flags as they are.

    Returns
    -------
    numpy.ndarray
        Numbers scaled to the schema's stored unit, anything else unchanged.
    """
    array = np.asarray(value)
    return array * VARIABLES[name].scale if array.dtype.kind in "fc" else array


def build_dataset(values: dict, coords: dict, attrs: dict | None = None):
    """An xarray.Dataset with every variable of ``values`` stored in its schema unit.

    Each variable gets ``units`` and ``long_name``; ``ageing_time`` (the same days as
    ``time``) is added beside ``time``. Variables a scene does not model are simply absent
    from ``values``.

    Parameters
    ----------
    values : dict of str to array_like
        Schema name -> values [SI units; scaled to the schema's stored unit here].
    coords : dict of str to array_like
        ``time`` [s] (stored as float days) and the other coordinates as the schema expects
        (angles [rad], stored in degrees; names as strings).
    attrs : dict, optional
        The dataset's attributes.

    Returns
    -------
    xarray.Dataset
        The result.

    Raises
    ------
    KeyError
        For a name the schema does not declare.
    ValueError
        For values whose shape does not match the variable's dimensions.
    """
    # deferred: keeps xarray off the start-up path
    import xarray as xr

    coordinates = {}
    for name, value in coords.items():
        units, long_name = COORDINATES[name]
        value = np.asarray(value)
        if units == "d":  # ageing times: given in s
            value = ageing_days(value)
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
        array = stored_unit(name, value)
        expected = tuple(coordinates[d].shape[0] for d in var.dims if d in coordinates)
        if len(expected) == len(var.dims) and array.shape != expected:
            raise ValueError(f"{name}: shape {array.shape} does not match dims {var.dims} {expected}")
        data_vars[name] = xr.Variable(var.dims, array,
                                      {"units": var.units or "1", "long_name": var.long_name})
    return xr.Dataset(data_vars, coords=coordinates, attrs=dict(attrs or {}))
