"""Climate history and moisture uptake per part."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .common import days, figure, legend_outside, Figures, returns_figures

#: names of the climate summary's interval lengths [s]
INTERVALS = {3600.0: "hourly", 86400.0: "daily", 7 * 86400.0: "weekly", 30 * 86400.0: "30-day"}
CLIMATE = (("temperature", "temperature [°C]", -273.15, "C3"),
           ("relative_humidity", "relative humidity [%]", 0.0, "C0"))


@returns_figures
def plot(ds, outdir=None, save=None) -> Figures:
    """uptake.png: temperature, relative humidity (each on its own axes, so neither hides
    the other) and the mean and surface moisture of each part over ageing time.

    Parameters
    ----------
    ds : xarray.Dataset
        Any run's result (``moisture_content`` of each part).
    outdir : str or pathlib.Path, optional
        uptake.png is written here. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. A one-element list: uptake.png.
    """
    plt = figure()
    fig, (t_ax, rh_ax, moist_ax) = plt.subplots(
        3, 1, figsize=(7, 8), sharex=True, gridspec_kw={"height_ratios": [1, 1, 2]})
    for ax, row in zip((t_ax, rh_ax), CLIMATE):
        _climate_panel(ax, ds, *row)
    t_ax.set_title(f"{ds.attrs.get('scene_name', '')}: climate and moisture uptake")
    _moisture_panel(moist_ax, ds, days(ds))
    return [save(fig, Path(outdir) / "uptake.png")]


def climate_edges(centres_days: np.ndarray) -> np.ndarray:
    """The interval edges of a climate summary from its interval middles.

    The intervals start at 0 and follow each other; the last may be shorter.

    Parameters
    ----------
    centres_days : numpy.ndarray
        The middles of the intervals [d].

    Returns
    -------
    numpy.ndarray
        The edges, one more than the middles [d].
    """
    edges = np.zeros(centres_days.size + 1)
    for i, centre in enumerate(centres_days):
        edges[i + 1] = 2.0 * centre - edges[i]
    return edges


def _climate_panel(ax, ds, name: str, ylabel: str, offset: float, colour) -> None:
    """The climate the parts saw: the mean over each interval of the stored summary and its
    range shaded; a result without one shows the values at the stored ageing times, as
    points (nothing is known between them)."""
    summary = f"climate_{name}"
    if summary in ds:
        edges = climate_edges(np.asarray(ds["climate_time"].values, float))
        step = INTERVALS.get(round(float(edges[1] - edges[0]) * 86400.0), "interval")
        low = ds[f"{summary}_min"].values + offset
        high = ds[f"{summary}_max"].values + offset
        if np.nanmax(high - low, initial=0.0) > 0:  # a constant climate has no range to shade
            ax.fill_between(edges, np.append(low, low[-1]), np.append(high, high[-1]),
                            step="post", color=colour, alpha=0.25, lw=0, label=f"{step} range")
        ax.stairs(ds[summary].values + offset, edges, baseline=None, color=colour,
                  label=f"{step} mean")
    else:
        ax.plot(days(ds), ds[name].values + offset, "o", ms=4, color=colour,
                label="at the stored ageing times")  # states given directly, or an older file
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    legend_outside(ax)


def _moisture_panel(ax, ds, t) -> None:
    absorbing = [p for p in ds["part"].values if _absorbs(ds, p)]
    for part in absorbing:
        line, = ax.plot(t, ds["moisture_content"].sel(part=part).values, "-o", ms=3,
                        label=str(part))
        if "surface_moisture_content" in ds:
            ax.plot(t, ds["surface_moisture_content"].sel(part=part).values, ":",
                    color=line.get_color())
    if "surface_moisture_content" in ds and absorbing:  # one key for the two line styles
        ax.plot([], [], "k-o", ms=3, label="volume mean")
        ax.plot([], [], "k:", label="surface layer")
    skipped = [str(p) for p in ds["part"].values if p not in absorbing]
    if skipped:
        ax.set_title(f"no moisture uptake: {', '.join(skipped)}", fontsize=9)
    ax.set_xlabel("ageing time [d]")
    ax.set_ylabel("moisture content [wt %]")
    if absorbing:
        legend_outside(ax)
    else:  # a legend without entries: matplotlib warns, and the user sees nothing
        ax.text(0.5, 0.5, "no part takes up moisture", ha="center", va="center",
                transform=ax.transAxes)
    ax.grid(alpha=0.3)


def _absorbs(ds, part) -> bool:
    """A part that takes up moisture (steel and other metals do not: no line for them)."""
    info = ds.attrs.get("diffusion", {})
    if isinstance(info, dict) and info.get(str(part), {}).get("model") == "none":
        return False
    return bool(np.nanmax(np.abs(ds["moisture_content"].sel(part=part).values), initial=0.0) > 0)
