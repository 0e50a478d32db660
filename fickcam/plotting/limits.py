"""Each limit's variable against its band over ageing (and over the cycle)."""
from __future__ import annotations

import textwrap
import math
from pathlib import Path

from ..results.limits import crossing_text, stored_limits, worst_value
from ..results.query import drift
from .common import legend, age_colour, age_label, ages, days, figure, Figures, returns_figures

ANGLES = ("cam_angle", "crank_angle")


def _units(limit) -> tuple[float, str]:
    """(scale, unit) to show a limit's variable in the unit the scene wrote."""
    return limit.display_scale, limit.display_units or limit.units


def worst_label(variable: str, kind: str, over_cycle: bool) -> str:
    """What :func:`~fickcam.results.limits.worst_value` gives, in words.

    Parameters
    ----------
    variable : str
        The limited variable.
    kind : {"deviation", "max", "min"}
        The kind of limit.
    over_cycle : bool
        The variable varies over the cycle (the worst over it is taken).

    Returns
    -------
    str
        ``|x - design|`` for a deviation, the largest or smallest value over the cycle for a
        max or min.
    """
    if kind == "deviation":
        return f"largest |{variable} − design|" if over_cycle else f"|{variable} − design|"
    if not over_cycle:
        return variable
    return f"{'largest' if kind == 'max' else 'smallest'} {variable} over the cycle"


def _over_time(ax, ds, limit) -> None:
    """The worst value per ageing time, the limits dashed, the crossing marked; the y label
    names what is plotted (|x - design| for a deviation)."""
    t = days(ds)
    scale, units = _units(limit)
    kinds = [k for k in ("deviation", "max", "min") if getattr(limit, k) is not None]
    over = ds[limit.variable].ndim > 1
    for kind in kinds:
        ax.plot(t, worst_value(ds, limit.variable, kind) * scale, "-o", ms=3, color="C0",
                label=worst_label(limit.variable, kind, over))
        ax.axhline(getattr(limit, kind) * scale, color="r", lw=1.2, ls="--", label=f"limit ({kind})")
    failed = float(ds["time_out_of_spec"].sel(limit=limit.variable))
    if not math.isnan(failed):
        ax.axvline(failed, color="k", lw=1, ls=":",
                   label=f"out of spec at {crossing_text(ds, limit.variable)}")
    ax.set_xlabel("ageing time [d]")
    ax.set_ylabel(_wrapped(f"{worst_label(limit.variable, kinds[0], over)} [{units}]"))
    ax.set_title(f"{limit.variable}: {limit.text}", fontsize=10)
    _legend_below(ax)
    ax.grid(alpha=0.3)


def _over_cycle(ax, ds, limit, dim: str) -> None:
    """The variable (its drift from the design for a deviation) over the cycle, with the band."""
    scale, units = _units(limit)
    deviation = limit.deviation is not None
    array = (drift(ds, limit.variable, "design") if deviation else ds[limit.variable]) * scale
    for k in ages(ds):
        values = array.isel(time=k)
        if values.ndim > 1:  # e.g. joint forces: the worst over the other dimension
            values = values.max([d for d in values.dims if d != dim])
        ax.plot(ds[dim].values, values.values, color=age_colour(ds, k),
                label=age_label(days(ds)[k], days(ds)[-1]))
    if deviation:
        band = limit.deviation * scale
        ax.fill_between(ds[dim].values, -band, band, color="g", alpha=0.12,
                        label=f"band ±{band:g} {units}")
    for kind in ("max", "min"):
        if getattr(limit, kind) is not None:
            ax.axhline(getattr(limit, kind) * scale, color="r", lw=1.2, ls="--",
                       label=f"limit ({kind})")
    ax.set_xlabel(f"{dim.replace('_', ' ')} [deg]")
    suffix = " − design" if deviation else ""
    ax.set_ylabel(_wrapped(f"{limit.variable}{suffix} [{units}]"))
    _legend_below(ax)
    ax.grid(alpha=0.3)


def _legend_below(ax) -> None:
    """The legend under the axes, where it covers no curve."""
    legend(ax, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=2, frameon=False)


def _wrapped(label: str, width: int = 34) -> str:
    """An axis label broken into lines of about ``width`` characters (a limits row is short)."""

    return "\n".join(textwrap.wrap(label, width))


@returns_figures
def plot(ds, outdir=None, save=None) -> Figures:
    """limits.png: one row per limit, over ageing time and (angle variables) over the cycle.

    Parameters
    ----------
    ds : xarray.Dataset
        A result of a scene with ``limits`` (its ``limit_ratio``).
    outdir : str or pathlib.Path, optional
        Where limits.png is saved. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. [limits.png], or no path without stored limits.
    """
    plt = figure()
    limits = list(stored_limits(ds).values())
    cycle = {limit.variable: next((d for d in ds[limit.variable].dims if d in ANGLES), None)
             for limit in limits}
    columns = 2 if any(cycle.values()) else 1
    fig, axes = plt.subplots(len(limits), columns, figsize=(5.5 * columns, 4.3 * len(limits)),
                             squeeze=False)
    for row, limit in zip(axes, limits):
        _over_time(row[0], ds, limit)
        if cycle[limit.variable] is not None:
            _over_cycle(row[1], ds, limit, cycle[limit.variable])
        elif columns == 2:
            row[1].set_axis_off()
    fig.suptitle(f"{ds.attrs.get('scene_name', '')}: limits", y=1.0)
    fig.tight_layout()
    return [save(fig, Path(outdir) / "limits.png")]
