"""Combine the cases of a sweep into one Dataset along a new ``case`` dimension.

The cases come from the sweep's journal one at a time and are copied into the
stacked arrays (the demo cam: 0.36 MB a case, so 1000 cases take 360 MB). A
failed case contributes NaN data (empty text for text variables). Coordinates
along ``case``: every varied parameter (SI, angles in degrees, speeds in rpm),
``case_status``, ``case_message`` and ``case_wall_time``.
"""
from __future__ import annotations

import json
import time
from collections.abc import Mapping

import numpy as np

from .._version import __version__
from ..results.dataset import ageing_seconds
from .journal import CaseArrays
from .spec import Sweep
import xarray as xr
from ..climate.records import site_name
from ..errors import format_duration
from .scatter import fractions


def missing_like(template):
    """A case without data: the template's variables filled with NaN (text with "").

    Parameters
    ----------
    template : xarray.Dataset
        The result of a case that ran.

    Returns
    -------
    xarray.Dataset
        Its layout, NaN data (integers and booleans become float NaN, text empty).
    """

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
    """Coordinates along ``case``: the varied values, description, status, message, wall time.

    Parameters
    ----------
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    records : dict of int to dict
        Case index -> its journal record (``status``, ``message``, ``wall_time`` [s]); a case
        without one is "failed", "not run".

    Returns
    -------
    dict of str to xarray.Variable
        The coordinates: each varied value in SI (angles in degrees, speeds in rpm) with the
        unit the sweep file wrote as ``given_units``; ``case_wall_time`` [s].
    """

    n = len(sweep.cases)
    coords = {"case": xr.Variable("case", np.arange(n), {"long_name": "case index"})}
    values = sweep.coordinates()
    for parameter in sweep.parameters:
        attrs = {"units": parameter.units, "long_name": f"swept scene value {parameter.path}",
                 "dotted_path": parameter.path}
        given = parameter.given_unit([c.values[parameter.path] for c in sweep.cases])
        if given and given != parameter.units:
            attrs["given_units"] = given  # the unit the sweep file wrote (degC): for display
        if parameter.path == "environment.history_file":
            attrs.update(_site_labels(values[parameter.name], sweep.base_dir))
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


def _site_labels(files, base_dir) -> dict:
    """``value_labels``: each weather file's site by the file's own metadata (JSON, value ->
    "Sand Point, AK"), for legends and ticks; {} when no value names a weather file."""

    labels = {str(f): site_name(str(f), base_dir) for f in dict.fromkeys(np.asarray(files).tolist())}
    labels = {value: site for value, site in labels.items() if site}
    return {"value_labels": json.dumps(labels)} if labels else {}


def sweep_attributes(sweep: Sweep, records: dict[int, dict], started: float | None) -> dict:
    """The global attributes of a sweep's result: its files and texts, counts, version.

    Parameters
    ----------
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    records : dict of int to dict
        Case index -> its journal record (cases without an ``ok`` one count as failed).
    started : float, optional
        ``time.perf_counter()`` when the sweep started [s]; gives ``wall_time_s``.

    Returns
    -------
    dict
        The attributes (CF-1.8), with ``samples`` and ``seed`` for a Monte Carlo sweep.
    """
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
        attrs["wall_time_s"] = time.perf_counter() - started  # [s], named with its unit
    return attrs


def _arrays(case) -> CaseArrays:
    return case if isinstance(case, CaseArrays) else CaseArrays.of(case)


def _dataset(case):
    return case.to_dataset() if isinstance(case, CaseArrays) else case


def stack_cases(case, n: int):
    """The ``n`` cases along a new leading ``case`` dimension.

    When every case has the same variables and coordinates (a sweep that varies no ageing
    times or angles) each case is copied into preallocated arrays and let go, so only the
    stacks and one case are held; else ``xarray.concat`` (outer join) of them all.

    Parameters
    ----------
    case : callable
        ``case(i)`` gives case i's Dataset or :class:`~.journal.CaseArrays` (the journal
        decodes it on demand).
    n : int
        The number of cases [1].

    Returns
    -------
    xarray.Dataset
        The stacked cases (without the ``case`` coordinates of :func:`case_coordinates`).
    """

    first = _arrays(case(0))
    stacks: dict[str, np.ndarray] = {}
    for index in range(n):
        part = first if index == 0 else _arrays(case(index))
        if not _same_layout(first, part):
            return xr.concat([_dataset(case(i)) for i in range(n)], dim="case",
                             data_vars="all", coords="minimal", compat="override",
                             join="outer", combine_attrs="override")
        for name, (_, values, _) in part.data.items():
            stack = stacks.get(name)
            if stack is None:
                stack = stacks[name] = np.empty((n,) + values.shape, values.dtype)
            elif np.result_type(stack, values) != stack.dtype:  # bool cases and NaN ones
                stack = stacks[name] = stack.astype(np.result_type(stack, values))
            stack[index, ...] = values  # a 0-d text array: its item, not the array object
    data = {name: xr.Variable(("case",) + dims, stacks[name], attrs)
            for name, (dims, _, attrs) in first.data.items()}
    return xr.Dataset(data, coords={name: xr.Variable(*v) for name, v in first.coords.items()})


def _same_layout(first: CaseArrays, other: CaseArrays) -> bool:
    """Same data variables (names, dims, shapes) and equal coordinates."""
    if list(other.data) != list(first.data) or set(other.coords) != set(first.coords):
        return False
    mine, theirs = first.data, other.data
    if any(theirs[n][0] != mine[n][0] or theirs[n][1].shape != mine[n][1].shape for n in mine):
        return False
    mine, theirs = first.coords, other.coords
    return all(theirs[n][0] == mine[n][0] and np.array_equal(theirs[n][1], mine[n][1])
               for n in mine)


def combine(sweep: Sweep, records: dict[int, dict], cases: Mapping,
            started: float | None = None):
    """The sweep's Dataset from its records and the results of its ok cases.

    Failed cases hold NaN (:func:`missing_like`); with limits, the fractions out of spec
    (:func:`fickcam.sweep.scatter.fractions`) are added.

    Parameters
    ----------
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    records : dict of int to dict
        Case index -> its journal record.
    cases : Mapping
        Index -> Dataset or :class:`~.journal.CaseArrays` of each ok case (e.g. the
        journal's :class:`~.runner.JournalCases`).
    started : float, optional
        ``time.perf_counter()`` when the sweep started [s].

    Returns
    -------
    xarray.Dataset
        The combined result along ``case``; only coordinates and attributes when no case ran.
    """

    coords = case_coordinates(sweep, records)
    attrs = sweep_attributes(sweep, records, started)
    ok = [i for i in range(len(sweep.cases)) if i in cases]
    if not ok:
        return xr.Dataset(coords=coords, attrs=attrs)
    template = CaseArrays.of(missing_like(_dataset(cases[ok[0]])))
    combined = stack_cases(lambda i: cases[i] if i in cases else template, len(sweep.cases))
    combined = combined.assign_coords(coords)
    if "time_out_of_spec" in combined:
        combined = combined.merge(fractions(combined), compat="override")
    combined.attrs = attrs
    return combined


def case_ends(ds) -> np.ndarray:
    """Each case's last ageing time with a value.

    The ageing times of cases that vary the history's length differ (``every`` ends on each
    case's own history), and the combined result holds NaN at the others' times.

    Parameters
    ----------
    ds : xarray.Dataset
        A combined sweep result (NaN where a case holds no value).

    Returns
    -------
    numpy.ndarray
        (case,): the last ageing time holding a finite value [s]; NaN for a case without any.
    """
    times = ageing_seconds(ds)
    held = np.zeros((ds.sizes["case"], times.size), bool)
    for variable in ds.data_vars.values():
        if variable.dims[:2] == ("case", "time") and variable.dtype.kind in "fc":
            held |= variable.notnull().any(list(variable.dims[2:])).values
    last = np.where(held.any(axis=1), times.size - 1 - np.argmax(held[:, ::-1], axis=1), -1)
    return np.where(last >= 0, times[np.maximum(last, 0)], np.nan)


def early_ends(ds) -> str | None:
    """One line when some ok cases end before the result's last ageing time, else None.

    Their cells at that time are empty in the sweep's table and plots.

    Parameters
    ----------
    ds : xarray.Dataset
        A combined sweep result.

    Returns
    -------
    str or None
        The line, naming the cases and when they end.
    """

    if "time" not in ds.dims or "case" not in ds.dims:
        return None
    ends = case_ends(ds)
    ok = (ds["case_status"].values == "ok") if "case_status" in ds.coords else np.isfinite(ends)
    last = float(ageing_seconds(ds)[-1])
    early = np.flatnonzero(ok & np.isfinite(ends) & (ends < last))
    if not early.size:
        return None
    shown = ", ".join(f"{k} at {format_duration(ends[k], last)}" for k in early[:3])
    more = f", {early.size - 3} more" if early.size > 3 else ""
    return (f"{early.size} case(s) end before {format_duration(last)} (case {shown}{more}): "
            f"empty there in the table and plots")
