"""Time-history queries on a result: select by part/angle, interpolate in time.

``--time`` takes units ("30 d", "6 months") and interpolates linearly between
the stored ageing times; angles are matched to the stored grid by linear
interpolation too (they are in degrees, as stored).
"""
from __future__ import annotations

import json

import numpy as np

from .errors import InputError
from .schema import VARIABLES
from .units import parse_duration

SECONDS = np.timedelta64(1, "s")


def _time_seconds(ds) -> np.ndarray:
    return ds["time"].values / SECONDS


def select(ds, variable: str, *, time=None, part=None, cam_angle=None, crank_angle=None, link=None):
    """The DataArray of ``variable`` restricted/interpolated as asked.

    ``time`` is a duration (string with units or seconds); angles in degrees.
    Interpolation is linear in time and angle; outside the stored range it is
    an error, not an extrapolation.
    """
    if variable not in ds.data_vars:
        known = ", ".join(sorted(v for v in ds.data_vars))
        raise InputError(f"variable {variable!r} is not in this result (it has: {known})")
    array = ds[variable]
    for dim, value in (("part", part), ("link", link)):
        if value is None:
            continue
        if dim not in array.dims:
            raise InputError(f"{variable} has no {dim} dimension")
        names = [str(v) for v in array[dim].values]
        if value not in names:
            raise InputError(f"no {dim} {value!r} (have: {', '.join(names)})")
        array = array.sel({dim: value})
    for dim, value in (("cam_angle", cam_angle), ("crank_angle", crank_angle)):
        if value is None:
            continue
        if dim not in array.dims:
            raise InputError(f"{variable} has no {dim} dimension")
        angle = float(value) % 360.0
        grid = array[dim].values
        array = _interp_along(array, dim, grid, angle, period=360.0)
    if time is not None:
        if "time" not in array.dims:
            raise InputError(f"{variable} does not vary with time")
        try:
            seconds = parse_duration(time) if isinstance(time, str) else float(time)
        except ValueError as exc:
            raise InputError(f"--time: {exc}") from None
        stored = _time_seconds(ds)
        if seconds < stored[0] - 1e-9 or seconds > stored[-1] + 1e-9:
            raise InputError(f"time {time} is outside the stored ageing times "
                             f"({stored[0] / 86400:g} to {stored[-1] / 86400:g} d)")
        array = _interp_along(array, "time", stored, seconds)
    return array


def _interp_along(array, dim, grid, value, period=None):
    """Linear interpolation of ``array`` along ``dim`` at ``value`` (grid ascending)."""
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
    if array.dtype.kind not in "fc":
        return lower if weight < 0.5 else upper
    return lower * (1.0 - weight) + upper * weight


def to_records(array) -> tuple[list[str], list[list]]:
    """(columns, rows) of a DataArray in tidy form: one column per dim + value."""
    dims = list(array.dims)
    columns = [("time_d" if d == "time" else d) for d in dims] + ["value"]
    if not dims:
        return columns, [[_plain(array.values)]]
    frame = array.to_dataframe(name="value").reset_index()
    rows = []
    for record in frame[dims + ["value"]].itertuples(index=False):
        rows.append([_plain(v, d) for v, d in zip(record, dims + ["value"])])
    return columns, rows


def _plain(value, dim=None):
    if isinstance(value, np.timedelta64) or (dim == "time" and hasattr(value, "total_seconds")):
        seconds = value / SECONDS if isinstance(value, np.timedelta64) else value.total_seconds()
        return float(seconds) / 86400.0
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.item()
    return value


def format_result(array, variable: str, fmt: str = "table", limit: str | None = None) -> str:
    """Render a selection as an aligned table, CSV or JSON; ``limit`` (the variable's limit
    and when it fails) goes under the table and into the JSON, not into the CSV."""
    columns, rows = to_records(array)
    units = VARIABLES[variable].units if variable in VARIABLES else array.attrs.get("units", "")
    if fmt == "json":
        extra = {"limit": limit} if limit else {}
        return json.dumps({"variable": variable, "units": units, "columns": columns, "rows": rows,
                           **extra})
    if fmt == "csv":
        lines = [",".join(columns)] + [",".join(_csv_cell(v) for v in row) for row in rows]
        return "\n".join(lines)
    if fmt != "table":
        raise InputError(f"unknown format {fmt!r} (table, csv or json)")
    header = columns[:-1] + [f"{variable} [{units}]"]
    cells = [[_table_cell(v) for v in row] for row in rows]
    widths = [max(len(h), *(len(r[i]) for r in cells)) if cells else len(h) for i, h in enumerate(header)]
    out = ["  ".join(h.rjust(w) for h, w in zip(header, widths))]
    out += ["  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in cells]
    if limit:
        out.append(f"limit: {limit}")
    return "\n".join(out)


def _csv_cell(value) -> str:
    return repr(value) if isinstance(value, float) else str(value)


def _table_cell(value) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
