"""Combine per-case result files into one Dataset along a new ``case`` dimension.

Per-case files are opened lazily (dask arrays, one chunk per variable and
case), so writing the combined file streams case by case instead of holding
every case in memory. A failed case contributes NaN data (empty text for text
variables). Coordinates along ``case``: every varied parameter (SI, angles in
degrees, speeds in rpm), ``case_status``, ``case_message`` and
``case_wall_time``.
"""
from __future__ import annotations

import json
import time
from contextlib import ExitStack

import numpy as np

from .._version import __version__
from .spec import Sweep
from .workdir import WorkFolder


def open_case(path, stack: ExitStack):
    """A per-case result opened lazily (closed when ``stack`` closes)."""
    import xarray as xr

    dataset = xr.open_dataset(path, engine="h5netcdf", decode_timedelta=True, chunks={})
    stack.callback(dataset.close)
    return dataset


def missing_like(template):
    """A case without data: the template's variables filled with NaN (text with "")."""
    import xarray as xr

    filled = {}
    for name, variable in template.data_vars.items():
        kind = variable.dtype.kind
        if kind in "fc":
            filled[name] = xr.full_like(variable, np.nan)
        elif kind in "iub":
            filled[name] = xr.full_like(variable, np.nan, dtype=float)
        else:
            filled[name] = xr.full_like(variable, "", dtype=object)
    return template.assign(filled)


def case_coordinates(sweep: Sweep, records: dict[int, dict]) -> dict:
    """Coordinates along ``case``: parameters, status, message, wall time."""
    import xarray as xr

    n = len(sweep.cases)
    coords = {"case": xr.Variable("case", np.arange(n), {"long_name": "case index"})}
    values = sweep.coordinates()
    for parameter in sweep.parameters:
        attrs = {"units": parameter.units, "long_name": f"swept scene value {parameter.path}",
                 "dotted_path": parameter.path}
        given = parameter.given_unit([c.values[parameter.path] for c in sweep.cases])
        if given and given != parameter.units:
            attrs["given_units"] = given  # the unit the sweep file wrote (degC): for display
        coords[parameter.name] = xr.Variable("case", values[parameter.name], attrs)
    coords["case_description"] = xr.Variable(
        "case", np.asarray([sweep.describe(c) for c in sweep.cases], dtype=object),
        {"long_name": "the values the case sets, as the sweep file gives them", "units": "1"})
    status = [records.get(i, {}).get("status", "failed") for i in range(n)]
    message = [records.get(i, {}).get("message", "not run") for i in range(n)]
    wall = [float(records.get(i, {}).get("wall_time", np.nan)) for i in range(n)]
    coords["case_status"] = xr.Variable("case", np.asarray(status, dtype=object),
                                        {"long_name": "ok or failed", "units": "1"})
    coords["case_message"] = xr.Variable(
        "case", np.asarray(message, dtype=object),
        {"long_name": "why the case failed, or the notices of an ok case", "units": "1"})
    coords["case_wall_time"] = xr.Variable("case", np.asarray(wall),
                                           {"long_name": "wall time of the case", "units": "s"})
    return coords


def sweep_attributes(sweep: Sweep, records: dict[int, dict], started: float | None) -> dict:
    failed = [i for i in range(len(sweep.cases)) if records.get(i, {}).get("status") != "ok"]
    attrs = {
        "title": f"fickcam sweep: {sweep.base_data.get('name', '')}",
        "fickcam_version": __version__,
        "scene_name": str(sweep.base_data.get("name", "")),
        "sweep_file": sweep.file,
        "sweep_text": sweep.text,
        "sweep_kind": sweep.kind,
        "sweep_parameters": json.dumps([p.path for p in sweep.parameters]),
        "scene_file": sweep.base_file,
        "scene_text": sweep.base_text,
        "cases": len(sweep.cases),
        "failed_cases": len(failed),
        "Conventions": "CF-1.8",
    }
    if sweep.kind == "monte_carlo":
        attrs.update(samples=sweep.model.samples, seed=sweep.model.seed)
    if started is not None:
        attrs["wall_time"] = time.perf_counter() - started
    return attrs


def combine(sweep: Sweep, folder: WorkFolder, records: dict[int, dict], stack: ExitStack,
            started: float | None = None):
    """The sweep's Dataset (lazy where it can be); files stay open until ``stack`` closes."""
    import xarray as xr

    ok = [i for i in range(len(sweep.cases)) if records.get(i, {}).get("status") == "ok"]
    coords = case_coordinates(sweep, records)
    attrs = sweep_attributes(sweep, records, started)
    if not ok:
        return xr.Dataset(coords=coords, attrs=attrs)
    opened = {i: open_case(folder.result(i), stack) for i in ok}
    template = missing_like(opened[ok[0]])
    parts = [opened.get(i, template) for i in range(len(sweep.cases))]
    combined = xr.concat(parts, dim="case", data_vars="all", coords="minimal", compat="override",
                         join="outer", combine_attrs="override")
    combined = combined.assign_coords(coords)
    if "time_out_of_spec" in combined:
        from .scatter import fractions

        combined = combined.merge(fractions(combined), compat="override")
    combined.attrs = attrs
    return combined
