"""Text a person reads: the plan `fickcam check` prints and the summary after a run.

Units and scales come from the schema (:mod:`fickcam.schema`): a value is shown in
its variable's ``display`` unit (converted from the stored unit with pint), or in
the stored unit. The summary gives each key output as design → t = 0 → end, its
drift against the design and against t = 0 and, for a history that goes up and
down, its peak and when it happened.
"""
from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from ..results.dataset import ageing_seconds, report_time_unit
from ..errors import format_duration, format_time, times_in
from ..results.limits import crossing, crossing_text, stored_limits
from ..results.query import drift
from ..schema import VARIABLES, design_name
from ..quantities.parsing import convert
from ..simulation.resultsize import estimate as result_size
from ..simulation.planning import STATE_GIVEN, plan_parts
from ..results.query import swept_values

#: scalar results over ageing the summary reports, in this order (when present)
KEY_OUTPUTS = ("lift", "arm_swing", "base_circle_radius", "jump_speed", "peak_cam_torque",
               "peak_contact_stress", "elastic_lift_error", "minimum_transmission_angle",
               "peak_input_torque")
#: results over the cycle whose largest change over the cycle the summary reports
CYCLE_OUTPUTS = ("follower_displacement", "follower_arm_angle", "rocker_angle")
#: a history "goes up and down" when it passes beyond both its ends by more than this
#: share of its largest change from the start (smaller wiggles are not worth a peak)
PEAK_SHARE = 0.02


# --------------------------------------------------------------------- plan


def _model_text(model) -> str:
    if isinstance(model, Mapping):
        return ", ".join(f"{part}: {name}" for part, name in model.items()) + " (others auto)"
    return model


def describe_plan(scene, accuracy: float | None = None) -> str:
    """The plan ``fickcam check`` prints: parts, diffusion model, cells, steps.

    Parameters
    ----------
    scene : fickcam.scene.load.Scene
        A validated scene.
    accuracy : float, optional
        The diffusion accuracy asked for [-] (relative error of the mean moisture); None for
        the scene's own.

    Returns
    -------
    str
        Lines: the climate, each part's diffusion model with its cells, steps and estimated
        error, the mechanisms, the follower and the limits.
    """

    environment, times, options, plans = plan_parts(scene, accuracy)
    climate = (f"{len(times)} state(s) given directly (no diffusion)"
               if environment.state_times is not None else
               f"{len(environment.change_times) - 1} segment(s), {format_duration(environment.end)}; "
               f"{len(times)} ageing times")
    lines = [f"scene {scene.name}: valid", f"  environment: {climate}",
             f"  diffusion: model {_model_text(options.model)}, accuracy {options.accuracy:g}"]
    for part, p in plans:
        head = f"  part {part.name:<9} material {part.material_name}"
        if p is None:
            lines.append(f"{head}: does not absorb moisture (thermal strain only)")
        elif p == STATE_GIVEN:
            lines.append(f"{head}: moisture given by the environment's state (no diffusion)")
        else:
            lines.append(f"{head}: {type(part.geometry).__name__} → {p.model}, {p.cells} cells, "
                         f"{p.steps} steps, est. error {p.error_estimate:.1e} ({p.reason})")
    lines.append(f"  mechanisms: {', '.join(m.section_name for m in scene.mechanisms)}; angle "
                 f"step {np.degrees(scene.model.outputs.angle_step):g} deg")
    lines += [f"  {line}" for mechanism in scene.mechanisms for line in mechanism.described()]
    if scene.limits:
        lines.append("  limits: " + "; ".join(f"{limit.variable} {limit.text}"
                                             for limit in scene.limits))
    cells = max((p.cells for _, p in plans if hasattr(p, "cells")), default=0)
    lines.append(f"  result: {result_size(scene, times, cells).text()}")
    return "\n".join(lines)


# ------------------------------------------------------------------ summary


def display(name: str, values):
    """(values in the variable's display unit, that unit): ``lift`` in mm, not m.

    Parameters
    ----------
    name : str
        A schema variable.
    values : float or array_like
        Its values in the stored unit [schema ``units``].

    Returns
    -------
    values : numpy.ndarray
        The values [display unit].
    unit : str
        The display unit (``"1"`` for none).
    """
    var = VARIABLES[name]
    return convert(values, var.units, var.display), var.display or var.units or "1"


def _finite_ends(values: np.ndarray) -> tuple[int, int] | None:
    """Indices of the first and last finite values, None when none is."""
    index = np.nonzero(np.isfinite(values))[0]
    return (int(index[0]), int(index[-1])) if index.size else None


def peak(values: np.ndarray) -> int | None:
    """Index of the interior extreme of a history that goes up and down.

    The extreme is the value furthest from the start that lies beyond both ends by more than
    :data:`PEAK_SHARE` of the history's range.

    Parameters
    ----------
    values : numpy.ndarray
        A history over ageing times (NaN where unknown) [any unit].

    Returns
    -------
    int or None
        The index, or None for a monotonic history (or fewer than three finite values).
    """
    ends = _finite_ends(values)
    if ends is None or ends[1] - ends[0] < 2:
        return None
    first, last = values[ends[0]], values[ends[1]]
    tolerance = PEAK_SHARE * np.nanmax(np.abs(values - first))
    beyond = (values > max(first, last) + tolerance) | (values < min(first, last) - tolerance)
    if not beyond.any():
        return None
    away = np.where(beyond, np.abs(values - first), -np.inf)
    return int(np.argmax(away))


def _number(value: float) -> str:
    return "-" if not np.isfinite(value) else f"{value:.5g}"


def _change(value: float) -> str:
    return "-" if not np.isfinite(value) else f"{value:+.3g}"


def _row(label: str, unit: str, design: float, series: np.ndarray, seconds: np.ndarray) -> list[str]:
    """One summary row: design, t = 0, end, drift against design and t = 0, peak."""
    ends = _finite_ends(series)
    if ends is None:
        return [f"{label} [{unit}]", _number(design), "-", "-", "-", "-", ""]
    start, end = series[ends[0]], series[ends[1]]
    end_text = _number(end)
    if ends[1] != len(series) - 1:
        end_text += f" (at {format_duration(seconds[ends[1]], seconds[-1])})"
    top = peak(series)
    peak_text = "" if top is None else \
        f"{_number(series[top])} ({_change(series[top] - start)}) at " \
        f"{format_duration(seconds[top], seconds[-1])}"
    return [f"{label} [{unit}]", _number(design), _number(start), end_text,
            _change(end - design), _change(end - start), peak_text]


def _series_rows(ds, seconds) -> list[list[str]]:
    rows = []
    diffusion = ds.attrs.get("diffusion", {})
    if "part" in ds.coords and "moisture_content" in ds:
        for part in ds["part"].values:
            if isinstance(diffusion, dict) and diffusion.get(str(part), {}).get("model") == "none":
                continue  # takes up no moisture (a metal)
            series, unit = display("moisture_content", ds["moisture_content"].sel(part=part).values)
            design = ds[design_name("moisture_content")].sel(part=part).values \
                if design_name("moisture_content") in ds else np.nan
            rows.append(_row(f"moisture {part}", unit, float(display("moisture_content", design)[0]),
                             series, seconds))
    for name in KEY_OUTPUTS:
        if name not in ds:
            continue
        series, unit = display(name, ds[name].values)
        design = float(display(name, ds[design_name(name)].values)[0]) \
            if design_name(name) in ds else np.nan
        rows.append(_row(name, unit, design, series, seconds))
    return rows


def _cycle_lines(ds) -> list[str]:
    """The largest change over the cycle of each cycle output, against design and t = 0."""
    lines = []
    for name in CYCLE_OUTPUTS:
        if name not in ds:
            continue
        angle = next(d for d in ds[name].dims if d != "time")
        parts = []
        for against in ("design", "start"):
            if against == "design" and design_name(name) not in ds:
                continue
            shift = np.abs(drift(ds, name, against)).max(angle, skipna=True).values
            if np.isfinite(shift).any():
                shown, unit = display(name, shift)
                if VARIABLES[name].display in ("degC",):
                    unit = "K"
                parts.append(f"{np.nanmax(shown):.4g} {unit} against "
                             f"{'the design' if against == 'design' else 't = 0'}")
        if parts:
            lines.append(f"  largest {name} change over the cycle: {', '.join(parts)}")
    return lines


def _swelling_lines(ds) -> list[str]:
    """Per part with a swelling analysis: its extreme swelling stresses and failure index."""
    if "failure_index" not in ds:
        return []
    lines = []
    seconds = ageing_seconds(ds)
    for part in ds["part"].values:
        row = ds.sel(part=part)
        tension = row["swelling_stress_tensile"].values
        if not np.isfinite(tension).any():
            continue
        compression, index = row["swelling_stress_compressive"].values, row["failure_index"].values
        worst = int(np.nanargmin(compression))
        text = (f"  {part} swelling stress: tension up to {np.nanmax(tension) * 1e-6:.3g} MPa, "
                f"compression down to {compression[worst] * 1e-6:.3g} MPa "
                f"(at {format_duration(seconds[worst], seconds[-1])})")
        if np.isfinite(index).any():
            text += f", failure index up to {np.nanmax(index):.3g}"
        lines.append(text)
    return lines


def _table(rows: list[list[str]], header: list[str]) -> list[str]:
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(len(header))]
    lines = []
    for row in [header] + rows:
        cells = [row[0].ljust(widths[0])] + [c.rjust(w) for c, w in zip(row[1:], widths[1:])]
        lines.append(("  " + "  ".join(cells)).rstrip())
    return lines


# ------------------------------------------------------------------- limits


def limit_line(ds, name: str) -> str | None:
    """One line on a limit of a result: its band and whether and when it fails.

    Parameters
    ----------
    ds : xarray.Dataset
        A result with ``time_out_of_spec`` and ``limit_ratio``.
    name : str
        The limited variable.

    Returns
    -------
    str or None
        The line (for the run summary, under a query's table); None when the result holds
        no such limit.
    """
    limit = stored_limits(ds).get(name)
    if limit is None or "time_out_of_spec" not in ds:
        return None
    failed = crossing(ds, name)[0]
    ratio = np.asarray(ds["limit_ratio"].sel(limit=name).values, float)
    times = ageing_seconds(ds)
    unit = report_time_unit(ds)
    known = np.flatnonzero(np.isfinite(ratio))
    last = int(known[-1]) if known.size else 0
    # no ratio past a part's leaving the model's domain: the limit is judged up to there only
    unknown = (f"; no value after {format_time(times[last], unit)}, see the notices"
               if last < times.size - 1 else "")
    if math.isnan(failed):
        state = (f"holds to {format_time(times[last], unit)} (largest ratio "
                 f"{np.nanmax(ratio):.4f}{unknown})")
    elif failed <= times[0]:
        state = f"out of spec from the start (ratio {ratio[0]:.4f}{unknown})"
    else:
        state = (f"out of spec from {crossing_text(ds, name)} "
                 f"(ratio {ratio[last]:.4f} at {format_time(times[last], unit)}{unknown})")
    band = limit.text + (" around the as-designed value" if limit.deviation is not None else "")
    return f"{name} ({band}): {state}"


def limit_lines(ds) -> list[str]:
    """The summary's limit lines: the first limit to fail and when, then each limit.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's result, with the limits its scene set.

    Returns
    -------
    list of str
        Indented lines; empty when the result holds no limits.
    """
    limits = stored_limits(ds)
    if not limits or "time_out_of_spec" not in ds:
        return []
    failed = {name: crossing(ds, name)[0] for name in limits}
    failing = sorted((t, name) for name, t in failed.items() if not math.isnan(t))
    if failing:
        name = failing[0][1]
        head = (f"  first limit to fail: {name} ({limits[name].text}) at "
                f"{crossing_text(ds, name)}; {len(failing)} of {len(limits)} limit(s) fail")
    else:
        head = f"  all {len(limits)} limit(s) hold"
    return [head] + [f"    {limit_line(ds, name)}" for name in limits]


def summary(ds, *, notices: bool = True) -> str:
    """The lines a user reads after ``fickcam run``.

    Each key output as design, t = 0 and end with its drift against both, the peak of a
    history that goes up and down, the cycle and swelling lines and the limits.

    Parameters
    ----------
    ds : xarray.Dataset
        A single run's result.
    notices : bool
        List the run's notices at the end (the command line logs them instead).

    Returns
    -------
    str
        The summary, without a trailing newline.
    """
    with times_in(ds.attrs.get("time_unit") or None):
        return _summary(ds, notices)


def _summary(ds, notices: bool) -> str:
    """:func:`summary`'s lines, times in the unit in force."""
    seconds = ageing_seconds(ds)
    wall = float(ds.attrs.get("wall_time_s", ds.attrs.get("wall_time", 0.0)))  # older files
    lines = [f"{ds.attrs.get('scene_name', '')}: {len(seconds)} ageing times to "
             f"{format_duration(seconds[-1])}, wall time {wall:.2f} s"]
    diffusion = ds.attrs.get("diffusion", {})
    if isinstance(diffusion, dict) and diffusion:
        lines.append("  diffusion: " + ", ".join(
            f"{part} {info.get('model', '?')}" + ("" if info.get("model") == "none" else
                                                  f" (est. error {info.get('error_estimate', 0):.1e})")
            for part, info in diffusion.items()))
    rows = _series_rows(ds, seconds)
    if rows:
        header = ["", "design", "t = 0", f"t = {format_duration(seconds[-1])}",
                  "Δ vs design", "Δ vs t = 0", "peak (Δ vs t = 0)"]
        lines += _table(rows, header)
    lines += _cycle_lines(ds)
    lines += _swelling_lines(ds)
    lines += limit_lines(ds)
    stored = ds.attrs.get("notices", [])
    if notices and isinstance(stored, list) and stored:  # (the command line logs them instead)
        lines.append(f"  {len(stored)} notice(s):")
        lines += [f"    - {n}" for n in stored]
    return "\n".join(lines)


# -------------------------------------------------------------------- sweep

#: cases listed after a sweep (the rest: `fickcam query` or the plots)
SWEEP_ROWS = 30


def _sweep_outputs(ds) -> list[str]:
    """The moisture and the first key outputs the sweep result holds."""
    names = [n for n in KEY_OUTPUTS if n in ds and set(ds[n].dims) == {"case", "time"}]
    return (["moisture_content"] if "moisture_content" in ds else []) + names[:3]


def _sweep_cell(ds, name: str, case: int) -> str:
    """The value at the last ageing time (largest over parts), and its drift against the
    design."""
    if "case_status" in ds.coords and str(ds["case_status"].values[case]) != "ok":
        return "-"
    array = ds[name].isel(case=case, time=-1)
    design = ds[design_name(name)].isel(case=case) if design_name(name) in ds else np.nan
    if "part" in array.dims:
        index = int(np.nanargmax(np.where(np.isfinite(array.values), array.values, -np.inf)))
        array, design = array.isel(part=index), design.isel(part=index) if design_name(name) in ds \
            else np.nan
    value = float(display(name, array.values)[0])
    change = np.nan if name == "moisture_content" else value - float(display(name, design)[0])
    return f"{_number(value)} ({_change(change)})" if np.isfinite(change) else _number(value)


def sweep_limit_lines(ds) -> list[str]:
    """Per limit of a sweep: how many of the cases that ran are out of spec by its last
    ageing time, with the Wilson 95 % interval of that fraction, and when the first and the
    last of them left it, each case's time as a single run reports it
    (:func:`~fickcam.results.limits.crossing_text`: the digits its error estimate supports,
    in the scene's time unit).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep's combined result with limits (``time_out_of_spec`` over case and limit,
        and the fractions of :func:`fickcam.sweep.scatter.fractions`).

    Returns
    -------
    list of str
        A heading, one line per limit and where the fractions by each ageing time are;
        empty without fractions.
    """
    if "fraction_out_of_spec" not in ds:
        return []
    n = int(ds["cases_out_of_spec"].attrs.get("cases", 0))
    last = ds.isel(time=-1)
    with times_in(ds.attrs.get("time_unit") or None):
        by = format_duration(ageing_seconds(ds)[-1])
    lines = [f"out of spec (of {n} case(s) that ran; Wilson 95 % interval):"]
    for limit in ds["limit"].values.tolist():
        row = last.sel(limit=limit)
        fraction, low, high = (float(row[v]) for v in ("fraction_out_of_spec",
                                                       "fraction_out_of_spec_low",
                                                       "fraction_out_of_spec_high"))
        text = (f"  {limit}: {int(row['cases_out_of_spec'])} of {n} by {by} ({fraction:.3g} % "
                f"[{low:.3g}, {high:.3g}])")
        days = ds["time_out_of_spec"].sel(limit=limit).values
        failed = np.flatnonzero(np.isfinite(days))
        if failed.size:
            ends = sorted({int(failed[np.argmin(days[failed])]), int(failed[np.argmax(days[failed])])},
                          key=lambda case: days[case])
            when = [f"{crossing_text(ds.isel(case=case), limit)} (case {case})" for case in ends]
            text += "; first at " + when[0] + (f", last at {when[1]}" if len(when) > 1 else "")
        lines.append(text)
    return lines + ["  (the fraction by each ageing time: fickcam query RESULT fraction_out_of_spec)"]


def sweep_summary(ds) -> str:
    """One line per case after ``fickcam sweep``.

    The varied values as the sweep file gave them, the status and, at the last ageing time,
    the moisture (wettest part) and the key outputs with their drift against the design; at
    most :data:`SWEEP_ROWS` cases.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep's combined result (dimension ``case``).

    Returns
    -------
    str
        The table, without a trailing newline.
    """

    swept = swept_values(ds)
    outputs = _sweep_outputs(ds)
    n = ds.sizes.get("case", 0)
    header = ["case", *swept, "status"] + [
        f"{'moisture (wettest part)' if n_ == 'moisture_content' else n_} [{display(n_, 0.0)[1]}]"
        for n_ in outputs]
    rows = []
    for case in range(min(n, SWEEP_ROWS)):
        status = str(ds["case_status"].values[case]) if "case_status" in ds.coords else "ok"
        rows.append([str(case), *(f"{v[case]:.6g}" if isinstance(v[case], (float, np.floating))
                                  else str(v[case]) for v in swept.values()), status]
                    + [_sweep_cell(ds, name, case) for name in outputs])
    seconds = ageing_seconds(ds)[-1] if "time" in ds.coords else np.nan
    when = f"; at t = {format_duration(seconds)} (Δ against the design)" \
        if np.isfinite(seconds) else ""  # (no time when no case ran)
    lines = [f"{ds.attrs.get('scene_name', '')}: {n} case(s), {int(ds.attrs.get('failed_cases', 0))} "
             f"failed{when}:"]
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(len(header))]
    lines += ["  " + "  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in [header] + rows]
    if n > SWEEP_ROWS:
        lines.append(f"  ... {n - SWEEP_ROWS} more case(s): fickcam query RESULT VARIABLE")
    return "\n".join(lines)
