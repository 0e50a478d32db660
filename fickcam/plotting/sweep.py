"""Sweep results (a ``case`` dimension): chosen outputs against the varied values.

Outputs per case over ageing time (:func:`outputs`): lift change (swelling
grows the lift, drying or shrinkage loses it), jump speed,
peak cam torque, cam moisture, peak crank torque, minimum transmission angle,
largest rocker angle shift — whichever the result has. A grid sweep plots each
output at one ageing time (the last by default) against the first varied value,
one line per combination of the others. A Monte Carlo sweep plots the quantiles
(5-95 %, 25-75 %, median) of each output over ageing time, and each case's value
at that ageing time against every varied value. A grid over text values (weather
files of several sites) also plots each output over ageing time, one line per case.
Failed cases are left out and counted in the title.
"""
from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np

from .common import legend, days, figure, legend_outside, Figures, returns_figures
from ..quantities.parsing import convert
from ..sweep.scatter import out_of_spec_counts, wilson_interval

QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)


def _peak(array, dim):
    with warnings.catch_warnings():  # all-NaN slices (failed cases) give NaN, as they should
        warnings.simplefilter("ignore", RuntimeWarning)
        return abs(array).max(dim)


def outputs(ds) -> dict[str, tuple[str, object]]:
    """The outputs of a sweep result that its figures show, with their axis labels.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result.

    Returns
    -------
    dict of str to tuple of (str, xarray.DataArray)
        name -> (axis label with unit, values over (case, time) in that unit): lift change
        [mm], jump speed [rpm], peak torques [N m], moisture [wt %], transmission angle and
        rocker shift [deg], those ``ds`` has.
    """
    found: dict[str, tuple[str, object]] = {}
    if "lift" in ds:
        found["lift_change"] = ("lift change since age 0 [mm]",
                                (ds["lift"] - ds["lift"].isel(time=0)) * 1e3)
    if "jump_speed" in ds:
        found["jump_speed"] = ("jump speed [rpm]", ds["jump_speed"])
    if "peak_cam_torque" in ds:
        found["peak_cam_torque"] = ("peak cam torque [N m]", ds["peak_cam_torque"])
    elif "cam_torque" in ds:
        found["peak_cam_torque"] = ("peak cam torque [N m]", _peak(ds["cam_torque"], "cam_angle"))
    if "moisture_content" in ds and "part" in ds.coords:
        for part in ("cam", "crank"):
            if part in ds["part"].values:
                found[f"{part}_moisture"] = (f"{part} moisture [wt %]",
                                             ds["moisture_content"].sel(part=part, drop=True))
    if "input_torque" in ds:
        found["peak_input_torque"] = ("peak crank torque [N m]", _peak(ds["input_torque"], "crank_angle"))
    if "transmission_angle" in ds:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            found["min_transmission_angle"] = ("minimum transmission angle [deg]",
                                               ds["transmission_angle"].min("crank_angle"))
    if "rocker_angle" in ds:
        shift = ds["rocker_angle"] - ds["rocker_angle"].isel(time=0)
        found["rocker_angle_shift"] = ("largest rocker angle shift [deg]", _peak(shift, "crank_angle"))
    return found


def parameters(ds) -> list[str]:
    """Names of the varied values: the coordinates along ``case`` that a sweep path set.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep's combined result, its varied values as coordinates along ``case``.

    Returns
    -------
    list of str
        The coordinate names, in the sweep file's order.
    """
    return [name for name, coord in ds.coords.items()
            if coord.dims == ("case",) and "dotted_path" in coord.attrs]


def _shown(ds, name: str) -> tuple[np.ndarray, str]:
    """A varied value in the unit the sweep file gave it (degC, not K), and that unit."""

    coord = ds[name]
    unit = coord.attrs.get("given_units") or coord.attrs.get("units", "1")
    if coord.values.dtype.kind not in "fiu":
        return coord.values, unit
    return convert(coord.values, coord.attrs.get("units", "1"), unit), unit


def _label(ds, name: str) -> str:
    _, units = _shown(ds, name)
    path = ds[name].attrs.get("dotted_path", name)
    return path if units in ("1", "") else f"{path} [{_degrees(units)}]"


def _degrees(units: str) -> str:
    """A unit as a reader writes it on a figure: degC as °C."""
    return units.replace("degC", "°C")


def _value_label(ds, name: str, value) -> str:
    """``temperature = 60 degC`` for a legend (the value as the sweep file gave it); a
    weather file by its site (``Sand Point, AK``: ``value_labels``) where it names one."""
    short = ds[name].attrs.get("dotted_path", name).split(".")[-1]
    _, units = _shown(ds, name)
    if isinstance(value, float):
        return f"{short} = {value:g}" + ("" if units in ("1", "") else f" {_degrees(units)}")
    return _sites(ds, name).get(str(value)) or f"{short} = {value}"


def _sites(ds, name: str) -> dict:
    """The sweep's ``value_labels`` of a text parameter (weather file -> its site), or {}."""
    return json.loads(ds[name].attrs.get("value_labels", "{}"))


def _ok(ds) -> np.ndarray:
    if "case_status" in ds.coords:
        return np.asarray(ds["case_status"].values == "ok")
    return np.ones(ds.sizes["case"], bool)


def _title(ds, name: str, age: float) -> str:
    failed = int((~_ok(ds)).sum())
    note = f", {failed} failed case(s) left out" if failed else ""
    return f"{ds.attrs.get('scene_name', '')}: {name.replace('_', ' ')} at {age:g} d{note}"


def _axis_values(values: np.ndarray, names: dict | None = None):
    """Numeric positions for a coordinate (text values get 0, 1, 2...) and tick labels
    (a text value's name in ``names`` where it has one: a weather file's site)."""
    if values.dtype.kind in "fiu":
        return values.astype(float), None
    labels = sorted(set(values.tolist()))
    ticks = [(names or {}).get(str(v), v) for v in labels]
    return np.asarray([labels.index(v) for v in values], float), ticks


@returns_figures
def plot_grid(ds, outdir=None, age_index: int = -1, save=None) -> Figures:
    """Each output at one ageing time against the first varied value.

    One line per combination of the other varied values.

    Parameters
    ----------
    ds : xarray.Dataset
        A grid sweep's result.
    outdir : pathlib.Path, optional
        The folder the figures go to (``sweep_<output>.png``).
    age_index : int
        The ageing time shown, an index along ``time``.
    save : callable
        ``save(fig, path) -> path`` (:func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written.
    """
    plt = figure()
    names = parameters(ds)
    x_name, others = names[0], names[1:]
    ok = _ok(ds)
    x, ticks = _axis_values(_shown(ds, x_name)[0], _sites(ds, x_name))
    shown = {o: _shown(ds, o)[0] for o in others}
    age = float(days(ds)[age_index])
    written = []
    for key, (label, array) in outputs(ds).items():
        y = array.isel(time=age_index).values
        fig, ax = plt.subplots(figsize=(7, 4.5))
        combos = sorted(set(zip(*(shown[o].tolist() for o in others)))) if others else [()]
        for combo in combos:
            chosen = ok.copy()
            for name, value in zip(others, combo):
                chosen &= shown[name] == value
            order = np.argsort(x[chosen])
            text = ", ".join(_value_label(ds, n, v) for n, v in zip(others, combo))
            style = "o" if ticks is not None else "-o"  # categories (sites): no line between
            ax.plot(x[chosen][order], y[chosen][order], style, ms=5, label=text or None)
        if ticks is not None:
            ax.set_xticks(range(len(ticks)), ticks)
        ax.set_xlabel(_label(ds, x_name))
        ax.set_ylabel(label)
        ax.set_title(_title(ds, key, age), fontsize=10)
        if others:
            legend_outside(ax)
        ax.grid(alpha=0.3)
        written.append(save(fig, outdir / f"sweep_{key}.png"))
    return written


@returns_figures
def plot_histories(ds, outdir=None, save=None) -> Figures:
    """Each output over ageing time, one line per case labelled by its values.

    For a grid over text values (``environment.history_file``: weather files of several
    sites), so the sites' seasons and drift are compared, not only their last values.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result.
    outdir, save
        As for :func:`plot_grid`; the figures are ``sweep_<output>_over_time.png``.

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written.
    """
    plt = figure()
    names = parameters(ds)
    ok = _ok(ds)
    t = days(ds)
    shown = {name: _shown(ds, name)[0] for name in names}
    written = []
    for key, (label, array) in outputs(ds).items():
        values = array.transpose("case", "time").values
        fig, ax = plt.subplots(figsize=(8, 4.5))
        for case in np.flatnonzero(ok):
            text = ", ".join(_value_label(ds, n, shown[n][case]) for n in names)
            ax.plot(t, values[case], "-", lw=1.2, label=text)
        ax.set_xlabel("ageing time [d]")
        ax.set_ylabel(label)
        failed = int((~ok).sum())
        ax.set_title(f"{ds.attrs.get('scene_name', '')}: {key.replace('_', ' ')} by case"
                     + (f", {failed} failed case(s) left out" if failed else ""), fontsize=10)
        legend_outside(ax)
        ax.grid(alpha=0.3)
        written.append(save(fig, outdir / f"sweep_{key}_over_time.png"))
    return written


def _has_text_values(ds) -> bool:
    return any(ds[name].values.dtype.kind not in "fiub" for name in parameters(ds))


@returns_figures
def plot_monte_carlo(ds, outdir=None, age_index: int = -1, save=None) -> Figures:
    """Per output: its quantile fan over ageing time and its scatter against the varied values.

    The fan shows the 5, 25, 50, 75 and 95 % quantiles.

    Parameters
    ----------
    ds : xarray.Dataset
        A Monte Carlo sweep's result.
    outdir, save
        As for :func:`plot_grid`.
    age_index : int
        The ageing time of the scatter panels, an index along ``time``.

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written.
    """
    plt = figure()
    names = parameters(ds)[:4]
    ok = _ok(ds)
    t = days(ds)
    age = float(t[age_index])
    written = []
    for key, (label, array) in outputs(ds).items():
        values = array.transpose("case", "time").values[ok]
        fig, axes = plt.subplots(1, 1 + len(names), figsize=(4.5 * (1 + len(names)), 4), squeeze=False,
                                 layout="constrained")
        fan = axes[0, 0]
        if values.size:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                q = np.nanquantile(values, QUANTILES, axis=0)
            fan.fill_between(t, q[0], q[4], alpha=0.2, color="C0", label="5-95 %")
            fan.fill_between(t, q[1], q[3], alpha=0.4, color="C0", label="25-75 %")
            fan.plot(t, q[2], "C0-", label="median")
            legend(fan, fontsize=7)
        fan.set_xlabel("ageing time [d]")
        fan.set_ylabel(label)
        fan.set_title(_title(ds, key, age), fontsize=9)
        for panel, (ax, name) in enumerate(zip(axes[0, 1:], names)):
            x, ticks = _axis_values(_shown(ds, name)[0], _sites(ds, name))
            ax.plot(x[ok], values[:, age_index] if values.size else [], ".", ms=4)
            if ticks is not None:
                ax.set_xticks(range(len(ticks)), ticks)
            ax.set_xlabel(_label(ds, name))
            if panel == 0:
                ax.set_ylabel(f"at {age:g} d: {label}")
        for ax in axes[0]:
            ax.grid(alpha=0.3)
        written.append(save(fig, outdir / f"sweep_{key}.png"))
    return written


@returns_figures
def plot_out_of_spec(ds, outdir=None, save=None) -> Figures:
    """The fraction of cases out of spec by each ageing time, per limit, with its 95 % interval.

    The interval is Wilson's score interval.

    A step curve from every case's continuous time out of spec
    (:func:`fickcam.sweep.scatter.out_of_spec_counts`), the stored ageing times marked.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep result with ``time_out_of_spec`` and ``fraction_out_of_spec``.
    outdir, save
        As for :func:`plot_grid`; the figure is ``sweep_out_of_spec.png``.

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. The file written.

    References
    ----------
    E. B. Wilson, "Probable inference, the law of succession, and statistical
    inference", Journal of the American Statistical Association 22 (158), 209-212, 1927,
    doi:10.1080/01621459.1927.10502953.
    """

    plt = figure()
    t = days(ds)
    fine = np.linspace(t[0], t[-1], 400)
    ran = _ok(ds)
    failed = ds["time_out_of_spec"].transpose("case", "limit").values
    k, n = out_of_spec_counts(failed, fine, ran)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for j, limit in enumerate(ds["limit"].values):
        bounds = np.array([wilson_interval(kk, n) for kk in k[:, j]]) * 100
        line, = ax.step(fine, 100 * k[:, j] / max(n, 1), where="post", label=str(limit))
        ax.fill_between(fine, bounds[:, 0], bounds[:, 1], step="post", color=line.get_color(),
                        alpha=0.15)
        ax.plot(t, ds["fraction_out_of_spec"].sel(limit=limit).values, "o", ms=4,
                color=line.get_color())
    ax.set_xlabel("ageing time [d]")
    ax.set_ylabel("cases out of spec [%]")
    ax.set_ylim(-2, 102)
    ax.set_title(f"{ds.attrs.get('scene_name', '')}: out of spec by each age, {n} case(s) "
                 "(band: Wilson 95 % interval)", fontsize=9)
    legend(ax, fontsize=8)
    ax.grid(alpha=0.3)
    return [save(fig, outdir / "sweep_out_of_spec.png")]


@returns_figures
def plot(ds, outdir=None, time_index: int = -1, save=None) -> Figures:
    """Figures of a sweep result; outputs are taken at ageing time ``time_index`` (last).

    Parameters
    ----------
    ds : xarray.Dataset
        A result of a sweep (a ``case`` dimension).
    outdir : str or pathlib.Path, optional
        The sweep figures are written here. None: the figures are only returned.
    time_index : int
        The ageing time [-] (an index into ``time``) the outputs are taken at; -1: the last.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. The figures drawn; none without varied parameters or ageing times.

    """
    outdir = Path(outdir)
    if not parameters(ds) or "time" not in ds.dims:
        return []
    age_index = int(np.arange(ds.sizes["time"])[time_index])
    written = plot_out_of_spec(ds, outdir, save=save) if "fraction_out_of_spec" in ds else []
    if ds.attrs.get("sweep_kind") == "monte_carlo":
        return written + plot_monte_carlo(ds, outdir, age_index, save=save)
    written += plot_grid(ds, outdir, age_index, save=save)
    return written + (plot_histories(ds, outdir, save=save) if _has_text_values(ds) else [])
