"""Time-history queries on a result: select by part/angle, interpolate in time.

``--time`` takes units ("30 d", "6 months") and interpolates linearly between
the stored ageing times; angles are matched to the stored grid by linear
interpolation too (they are in degrees, as stored).
"""
from __future__ import annotations

import json

import numpy as np

from ..quantities.options import ageing_time
from .dataset import ageing_seconds
from ..errors import InputError, format_duration, time_unit
from ..scene.keys import closest_names, short_names
from ..schema import VARIABLES, design_name
from ..errors import supported_digits
from .dataset import report_time_unit

def select(ds, variable: str, *, time=None, part=None, cam_angle=None, crank_angle=None, link=None,
           against: str | None = None):
    """The DataArray of ``variable`` (or its :func:`drift` ``against`` the design or the
    start) restricted/interpolated as asked.

    ``time`` is a duration (string with units, or seconds as a number from Python; a bare
    number as text, as ``--time 45`` gives, is read and judged as a scene's ageing time:
    45 s is refused with '45 d' suggested); angles in degrees. Interpolation is linear in time and angle; outside the stored range it is
    an error, not an extrapolation. ``attrs["selection"]`` says what was answered, e.g.
    ``time = 45 d (interpolated between 30 d and 60 d)``.

    Parameters
    ----------
    ds : xarray.Dataset
        A result (:func:`fickcam.run` or :func:`fickcam.open_result`).
    variable : str
        The result variable, e.g. ``pressure_angle_max`` (``fickcam schema`` lists them).
    time : str or float, optional
        The ageing time [s]: a duration with units ("45 d") or seconds as a number.
    part, link : str, optional
        The part's or the link's name, for variables with that dimension.
    cam_angle, crank_angle : float, optional
        The cam angle or the four-bar's crank angle [degree], wrapped into [0, 360).
    against : {"design", "start"}, optional
        Answer the :func:`drift` from the design or the first ageing time instead.

    Returns
    -------
    xarray.DataArray
        The selection, in the variable's stored unit (its ``units`` attribute).

    Raises
    ------
    fickcam.errors.InputError
        When the variable, part or link is not in the result, the variable lacks the
        dimension asked for, or the time or angle is outside the stored range.
    """
    if variable not in ds.data_vars:
        raise InputError(unknown_variable(variable, ds.data_vars))
    array = ds[variable] if against is None else drift(ds, variable, against)
    answered, selected = [], {}
    for dim, value in (("part", part), ("link", link)):
        if value is None:
            continue
        if dim not in array.dims:
            raise InputError(f"{variable} has no {dim} dimension")
        names = [str(v) for v in array[dim].values]
        if value not in names:
            raise InputError(f"no {dim} {value!r} (have: {', '.join(names)})")
        array = array.sel({dim: value})
        answered.append(f"{dim} = {value}")
        selected[dim] = value
    for dim, value in (("cam_angle", cam_angle), ("crank_angle", crank_angle)):
        if value is None:
            continue
        if dim not in array.dims:
            raise InputError(f"{variable} has no {dim} dimension")
        angle = float(value) % 360.0
        grid = array[dim].values
        array, between = _interp_along(array, dim, grid, angle, period=360.0)
        answered.append(_answered(dim, angle, between, lambda x: f"{x % 360:g} deg"))
        selected[dim] = angle
    if time is not None:
        array = _at_time(ds, variable, array, time, answered, selected)
    error = VARIABLES[variable].error if variable in VARIABLES and against is None else ""
    if error in ds and set(ds[error].dims) == set(array.dims):  # its error estimate, alike
        array.attrs["error"] = ds[error].transpose(*array.dims).values
    array.attrs["selection"] = ", ".join(answered)
    array.attrs["selected"] = selected
    if "time" in ds.coords:  # the result's last ageing time: its times' unit (format_result)
        array.attrs["time_span_s"] = float(ageing_seconds(ds)[-1])  # [s], named with its unit
    return array


def _at_time(ds, variable: str, array, time, answered: list, selected: dict):
    """``array`` interpolated at the ageing ``time`` (text with units, or [s]), what was
    answered appended to ``answered`` and ``selected``."""
    if "time" not in array.dims:
        raise InputError(f"{variable} does not vary with time")
    stored = ageing_seconds(ds)
    seconds = ageing_time("--time", time, stored[-1]) if isinstance(time, str) else float(time)
    if seconds < stored[0] - 1e-9 or seconds > stored[-1] + 1e-9:
        raise InputError(f"time {time} is outside the stored ageing times "
                         f"({stored[0] / 86400:g} to {stored[-1] / 86400:g} d)")
    array, between = _interp_along(array, "time", stored, seconds)
    answered.append(_answered("time", seconds, between,
                              lambda x: format_duration(x, stored[-1])))
    selected["time_d"] = seconds / 86400
    return array


def unknown_variable(name: str, known) -> str:
    """Why ``name`` cannot be queried: the closest names the result has, not all of them.

    Parameters
    ----------
    name : str
        The variable asked for.
    known : iterable of str
        The variables the result holds.

    Returns
    -------
    str
        One line: a variable of the schema the scene does not compute, or a misspelling with
        the nearest names (:func:`fickcam.scene.keys.closest_names`).
    """
    near = closest_names(name, sorted(known))
    if name in VARIABLES:  # spelt right, but the scene does not compute it
        what = (f"this result holds no {name} (a {VARIABLES[name].section} variable: the scene "
                f"does not compute it)")
        return what + (f"; did you mean {', '.join(near)}?" if near else "")
    hint = f"did you mean {', '.join(near)}?" if near else "fickcam schema lists the variables"
    return f"no variable {name!r} in this result; {hint}"


AGAINST = ("design", "start")


def wrapped_degrees(change):
    """An angle's change [degree] wrapped into [-180, 180): a cam that turned by 359 deg
    drifted by -1 deg.

    Parameters
    ----------
    change : array_like or xarray.DataArray
        The change [degree].

    Returns
    -------
    array_like or xarray.DataArray
        The same change wrapped [degree].
    """
    return (change + 180.0) % 360.0 - 180.0


def drift(ds, name: str, against: str = "design"):
    """``name`` minus its as-designed value (``against="design"``: ``<name>_design``, dry at
    the reference temperature) or minus its value at the first ageing time
    (``against="start"``), as an xarray.DataArray in the stored unit. Angles (degrees)
    are wrapped into [-180, 180).

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    name : str
        A variable that changes with ageing time.
    against : {"design", "start"}
        The reference: the as-designed value or the value at the first ageing time.

    Returns
    -------
    xarray.DataArray
        The change, in the variable's stored unit.

    Raises
    ------
    fickcam.errors.InputError
        When the variable is missing, does not change with time, has no as-designed value,
        or ``against`` is neither "design" nor "start".
    """
    if name not in ds.data_vars:
        raise InputError(f"variable {name!r} is not in this result")
    array = ds[name]
    if "time" not in array.dims or array.dtype.kind not in "fc":
        raise InputError(f"{name} is not a number that changes with ageing time: no drift")
    if against == "design":
        if design_name(name) not in ds.data_vars:
            raise InputError(f"this result holds no as-designed value of {name} "
                             f"({design_name(name)}); use --drift start")
        reference = ds[design_name(name)]
        what = "the design (dry, reference temperature)"
    elif against == "start":
        reference = array.isel(time=0, drop=True)
        what = "the first ageing time"
    else:
        raise InputError(f"drift against {against!r}: use one of {', '.join(AGAINST)}")
    change = array - reference
    if array.attrs.get("units") == "degree":
        change = wrapped_degrees(change)
    return change.assign_attrs(units=array.attrs.get("units", ""),
                               long_name=f"{array.attrs.get('long_name', name)}: change from {what}")


def _answered(dim, value, between, show) -> str:
    """``dim = value (stored)`` or ``(interpolated between a and b)``."""
    low, high = between
    how = "stored" if low == high else f"interpolated between {show(low)} and {show(high)}"
    return f"{dim} = {show(value)} ({how})"


def _interp_along(array, dim, grid, value, period=None):
    """Linear interpolation of ``array`` along ``dim`` at ``value`` (grid ascending), and
    the two grid values used (equal when ``value`` is a stored one)."""
    grid = np.asarray(grid, float)
    if period is not None:  # wrap the angle grid for periodic interpolation
        grid_ext = np.concatenate([grid, [grid[0] + period]])
        index = int(np.clip(np.searchsorted(grid_ext, value, side="right") - 1, 0, grid.size - 1))
        hi = (index + 1) % grid.size
        x0, x1 = grid_ext[index], grid_ext[index + 1]
    else:
        index = int(np.clip(np.searchsorted(grid, value, side="right") - 1, 0, max(grid.size - 2, 0)))
        hi = min(index + 1, grid.size - 1)
        x0, x1 = grid[index], grid[hi]
    weight = 0.0 if x1 == x0 else (value - x0) / (x1 - x0)
    lower = array.isel({dim: index}, drop=True)
    upper = array.isel({dim: hi}, drop=True)
    stored = weight <= 1e-12 or weight >= 1 - 1e-12
    if stored:  # as stored, whatever stands beside it (a NaN times 0 is NaN)
        x0 = x1 = x0 if weight <= 0.5 else x1
    between = (float(x0), float(x1))
    if array.dtype.kind not in "fc" or stored:
        answer = lower if weight < 0.5 else upper
    else:
        answer = lower * (1.0 - weight) + upper * weight
    if period is None and array.dtype.kind in "fc" and bool(answer.isnull().any()):
        return _own_points(array, dim, grid, value).assign_coords(answer.coords), between
    return answer, between


def _own_points(array, dim, grid, value):
    """``array`` at ``value`` along ``dim``, each series between its own nearest grid points
    that hold a value (a sweep's case whose ageing times differ from the others', or
    that ends earlier), NaN outside them: never extrapolated, never NaN by a neighbour."""
    # deferred: keeps xarray off the start-up path
    import xarray as xr

    def own(values):
        known = np.isfinite(values)
        points = grid[known]
        if not points.size or not points[0] - 1e-9 <= value <= points[-1] + 1e-9:
            return np.nan
        return np.interp(value, points, values[known])

    return xr.apply_ufunc(own, array, input_core_dims=[[dim]], vectorize=True, keep_attrs=True)


def swept_values(array) -> dict[str, np.ndarray]:
    """The varied values of a sweep result along ``case``, in the units the sweep file gave them.

    Parameters
    ----------
    array : xarray.DataArray or xarray.Dataset
        A selection of a sweep result (coordinates along ``case`` with a ``dotted_path``).

    Returns
    -------
    dict of str to numpy.ndarray
        ``{"temperature [degC]": [60, 85, ...]}``, each varied value by its shortest distinct
        name and given unit; empty for a single run.
    """
    # deferred: keeps the command's modules off the start-up path
    from ..quantities.parsing import convert

    swept = [name for name, coord in array.coords.items()
             if "dotted_path" in coord.attrs and coord.dims == ("case",)]
    names = short_names([array[n].attrs["dotted_path"] for n in swept])
    out = {}
    for name in swept:
        coord = array[name]
        unit = coord.attrs.get("given_units") or coord.attrs.get("units", "")
        values = coord.values
        if values.dtype.kind in "fiu":
            values = convert(values, coord.attrs.get("units", ""), unit)
        out[f"{names[coord.attrs['dotted_path']]} [{unit}]" if unit not in ("", "1")
            else names[coord.attrs["dotted_path"]]] = values
    return out


def to_records(array) -> tuple[list[str], list[list]]:
    """(columns, rows) of a DataArray in tidy form.

    One column per dimension (``time`` as ``time_d``, in days) and, for a sweep, one per
    varied value beside ``case``, then ``value``.

    Parameters
    ----------
    array : xarray.DataArray
        A selection (:func:`select`).

    Returns
    -------
    columns : list of str
        The column names.
    rows : list of list
        One row per element, plain Python values.
    """
    dims = list(array.dims)
    swept = swept_values(array) if "case" in dims else {}
    columns = [("time_d" if d == "time" else d) for d in dims] + ["value"]
    if not dims:
        return columns, [[_plain(array.values)]]
    frame = array.to_dataframe(name="value").reset_index()
    rows = []
    for record in frame[dims + ["value"]].itertuples(index=False):
        rows.append([_plain(v) for v in record])
    if swept:
        where = dims.index("case") + 1
        columns[where:where] = list(swept)
        rows = [row[:where] + [_plain(v[int(row[where - 1])]) for v in swept.values()] + row[where:]
                for row in rows]
    return columns, rows


def _plain(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.item()
    return value


def format_result(array, variable: str, fmt: str = "table", against: str | None = None,
                  limit: str | None = None, units: str | None = None) -> str:
    """Render a selection as an aligned table, CSV or JSON.

    Every column is headed ``name [unit]`` (``time [d]``, ``cam_angle [degree]``,
    ``lift [mm]``); the ageing time is shown in one unit chosen from the result's span.

    Parameters
    ----------
    array : xarray.DataArray
        A selection (:func:`select`), in the variable's stored unit.
    variable : str
        Its schema name.
    fmt : {"table", "csv", "json"}
        The form.
    against : {"design", "start"}, optional
        The selection is the drift against the design or the start (a temperature change
        stays in K).
    limit : str, optional
        The variable's limit and when it fails: under the table and in the JSON, not in the
        CSV.
    units : str, optional
        A pint unit to show the values in; default the variable's display unit (mm, MPa,
        degC).

    Returns
    -------
    str
        The text, without a trailing newline.

    Raises
    ------
    fickcam.errors.InputError
        For an unknown ``fmt`` or a unit the variable cannot be shown in.
    """
    values, unit = shown_values(array, variable, units, drift=against is not None)
    if "error" in array.attrs:  # only the digits the error estimate supports
        values = supported_values(values, shown_values(array.copy(data=array.attrs["error"]),
                                                       variable, unit, drift=True)[0],
                                  text=fmt != "json")
    columns, rows = to_records(array.copy(data=values) if array.dtype.kind in "fc" else array)
    label = variable if against is None else f"{variable} drift vs {against}"
    span = array.attrs.get("time_span_s")  # one unit of time for the table, from the result's
    time_name, days = time_unit(span) if span is not None else ("d", 86400.0)
    days /= 86400.0  # (the rows hold days)
    fixed = array.attrs.get("selected", {})
    fixed = {column_label(k, time_name): v / days if k in TIME_COLUMNS else v
             for k, v in fixed.items()}
    rows = [[v / days if c in TIME_COLUMNS else v for c, v in zip(columns, row)] for row in rows]
    header = [column_label(c, time_name) for c in columns[:-1]] + [_labelled(label, unit)]
    selection = array.attrs.get("selection", "")
    if fmt == "json":
        extra = {"limit": limit} if limit else {}
        return json.dumps({"variable": variable, "units": unit, "selection": selection,
                           "columns": header, "rows": rows, **extra}
                          | ({"drift_against": against} if against else {}))
    if fmt == "csv":  # tidy: the selected values as columns of their own
        lines = [",".join([*fixed, *header])]
        lines += [",".join(csv_cell(v) for v in [*fixed.values(), *row]) for row in rows]
        return "\n".join(lines)
    if fmt != "table":
        raise InputError(f"unknown format {fmt!r} (table, csv or json)")
    title = [f"{label} at {selection}"] if selection else []
    cells = [[_table_cell(v) for v in row] for row in rows]
    widths = [max(len(h), *(len(r[i]) for r in cells)) if cells else len(h) for i, h in enumerate(header)]
    out = title + ["  ".join(h.rjust(w) for h, w in zip(header, widths))]
    out += ["  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in cells]
    if limit:
        out.append(f"limit: {limit}")
    return "\n".join(out)


#: the names :func:`to_records` and ``select`` give the ageing time (in days)
TIME_COLUMNS = ("time_d", "ageing_time")
#: units of the angles a query's rows are labelled with; part, link, joint and case have none
COLUMN_UNITS = {"cam_angle": "degree", "crank_angle": "degree"}


def column_label(name: str, time_name: str = "d") -> str:
    """A column's heading, ``name [unit]`` (``time_d`` is shown as ``time [d]``).

    Parameters
    ----------
    name : str
        The column (a dimension of the result, or ``time_d``).
    time_name : str
        The unit the ageing time is shown in (``"d"``, ``"h"``, ``"year"``...).

    Returns
    -------
    str
        The heading; a name without unit stays bare.
    """
    if name in TIME_COLUMNS:
        return _labelled("time", time_name)
    return _labelled(name, COLUMN_UNITS.get(name, ""))


def _labelled(name: str, unit: str) -> str:
    return f"{name} [{unit}]" if unit and unit != "1" else name


def shown_values(array, variable: str, units: str | None = None, drift: bool = False):
    """The values of a selection in the unit a person reads them in.

    Parameters
    ----------
    array : xarray.DataArray
        Values in the variable's stored unit (SI; angles in degrees).
    variable : str
        Its schema name.
    units : str, optional
        A pint unit to show (``um``, ``degF``); by default the variable's display unit from
        the schema (``lift``: m stored, mm shown). One of another dimension is refused.
    drift : bool
        The values are changes: a temperature difference stays in K (degC would add 273.15).

    Returns
    -------
    tuple of (numpy.ndarray, str)
        The values and their unit.
    """
    # deferred: keeps the command's modules off the start-up path
    from ..quantities.parsing import convert

    var = VARIABLES.get(variable)
    stored = var.units if var is not None else array.attrs.get("units", "")
    wanted = units or (var.display if var is not None else "") or stored
    if array.dtype.kind not in "fc" or wanted == stored:
        return array.values, stored
    if drift and _is_offset(wanted):
        return array.values, stored  # a difference of temperature: K, not degC
    # deferred: keeps pint off the start-up path
    from pint.errors import PintError

    try:
        return convert(array.values, stored, wanted), wanted
    except UNIT_ERRORS + (PintError,) as exc:  # an unknown unit, or one of another dimension
        raise InputError(f"--units {wanted}: not a unit {variable} can be shown in (stored in "
                         f"{stored or 'no unit'}){': ' + str(exc) if str(exc) else ''}") from None


#: what pint's parser raises on text that is no unit besides its own errors ('mm/' fails
#: an assertion inside it)
UNIT_ERRORS = (ValueError, AttributeError, TypeError, AssertionError)


def _is_offset(unit: str) -> bool:
    """True for a unit whose zero is offset (degC, degF): a difference is not converted
    as a value is."""
    # deferred: keeps pint off the start-up path
    from pint.errors import PintError

    # deferred: keeps the command's modules off the start-up path
    from ..quantities.parsing import convert

    try:
        return bool(convert(0.0, unit, "K") != 0.0)
    except UNIT_ERRORS + (PintError,):  # not a temperature
        return False


def csv_cell(value) -> str:
    """A CSV cell that reads back as the same value: a float at full precision (its repr).

    Parameters
    ----------
    value : float, int or str
        The value, in the unit of its column.

    Returns
    -------
    str
        The cell's text.
    """
    return repr(value) if isinstance(value, float) else str(value)


def supported_values(values, errors, text: bool = True) -> np.ndarray:
    """``values`` with only the digits their ``errors`` support
    (:func:`fickcam.errors.supported_digits`), as text or as the numbers the text reads.

    Parameters
    ----------
    values, errors : array_like
        The values and their error estimates [the same unit].
    text : bool
        Text (a table, CSV) rather than numbers (JSON).

    Returns
    -------
    numpy.ndarray
        Of str, or of float.
    """

    cells = [supported_digits(float(v), float(e)) for v, e in
             zip(np.ravel(values), np.ravel(np.broadcast_to(errors, np.shape(values))))]
    shaped = np.array(cells, dtype=object).reshape(np.shape(values))
    return shaped if text else shaped.astype(float)


def time_units(ds, variable: str) -> str | None:
    """The unit a time-valued variable (``time_out_of_spec``) is shown in by default: the
    result's time unit (:func:`fickcam.results.dataset.report_time_unit`); None for others.

    Parameters
    ----------
    ds : xarray.Dataset
        The result.
    variable : str
        The variable asked for.

    Returns
    -------
    str or None
        A pint unit (``d``, ``h``, ``yr``), or None: the variable's own display unit.
    """

    var = VARIABLES.get(variable)
    return report_time_unit(ds)[0] if var is not None and var.units == "d" else None


def _table_cell(value) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
