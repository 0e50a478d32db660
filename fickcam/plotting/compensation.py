"""The drift of each banded output against its band over ageing, for the mechanism as
designed and as made to compensate (`fickcam compensate --plot`)."""
from __future__ import annotations

import math

import numpy as np

from .common import Figures, days, figure, legend, one_figure
from ..results.limits import crossing_text, stored_limits, worst_value


def _spec_text(ds, variable: str) -> str:
    """'out of spec at 41.2 d' or 'in spec throughout' from the result's time_out_of_spec
    (only the digits its error estimate supports, in the result's time unit)."""

    failed = float(ds["time_out_of_spec"].sel(limit=variable))
    return "in spec throughout" if math.isnan(failed) else \
        f"out of spec at {crossing_text(ds, variable)}"


def plot_against_band(before, after, path=None, window=(), save=None) -> Figures:
    """One panel per ``deviation`` limit: the worst deviation before and after compensation.

    Each panel shows the largest |x - design| over the cycle at every ageing time for both
    results.

    Parameters
    ----------
    before : xarray.Dataset
        The result as designed (its limits are drawn).
    after : xarray.Dataset
        The result of the compensated design.
    path : str or pathlib.Path, optional
        The figure file (PNG unless its suffix names another format); None: the figure is
        only returned.
    window : sequence of float
        The ageing times compensated for [d], drawn dotted.
    save : callable, optional
        ``save(fig, path) -> path`` writes the figure; default
        :func:`~fickcam.plotting.common.save_figure` (atomic).

    Returns
    -------
    Figures
        The one figure, shown inline in a notebook; ``.paths``: the file written.
    """

    limits = [limit for limit in stored_limits(before).values()
              if limit.deviation is not None and limit.variable in after]
    plt = figure()
    fig, axes = plt.subplots(1, max(len(limits), 1), figsize=(5.4 * max(len(limits), 1), 4.8),
                             squeeze=False)
    for ax, limit in zip(axes[0], limits):
        scale, units = limit.display_scale, limit.display_units or limit.units
        band = limit.deviation * scale
        ax.axhspan(0.0, band, color="g", alpha=0.12, label=f"band: {band:g} {units}")
        for end in window:
            ax.axvline(end, color="0.4", lw=1, ls=":")
        if window:
            ax.plot([], [], ":", color="0.4", label="compensated for " + "-".join(
                f"{end:g}" for end in window) + " d")
        for ds, label, style in ((before, "as designed", "-o"), (after, "compensated", "-s")):
            t = days(ds)
            worst = worst_value(ds, limit.variable, "deviation") * scale
            inside = (t >= window[0] - 1e-9) & (t <= window[-1] + 1e-9) if window else t >= 0
            ax.plot(t, worst, style, ms=3, label=f"{label}: {_spec_text(ds, limit.variable)}, "
                                                 f"worst {np.nanmax(worst[inside]):.3g} {units}"
                                                 + (" in the window" if window else ""))
        ax.set_xlabel("ageing time [d]")
        ax.set_ylabel(f"largest |{limit.variable} - design| [{units}]")
        ax.set_title(f"{limit.variable}: {limit.text}", fontsize=10)
        ax.set_ylim(bottom=0.0)
        ax.grid(alpha=0.3)
        legend(ax, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    if not limits:
        axes[0][0].text(0.5, 0.5, "the scene has no deviation limits", ha="center",
                        transform=axes[0][0].transAxes)
    fig.suptitle(f"{before.attrs.get('scene_name', '')}: drift against the band, "
                 f"as designed and compensated", fontsize=11)
    fig.set_label("against_band")
    return one_figure(fig, path, save)
