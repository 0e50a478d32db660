"""The fit figure: moisture gain against sqrt(time) per condition (the D5229
convention) with the fitted curves, and the residuals below."""
from __future__ import annotations

import numpy as np

from ..plotting.common import Figures, figure, legend, one_figure
from .models import fickian_fraction, two_phase_fraction
from .report import FitReport

DAY = 86400.0
MARKERS = "osD^v<>px*"


def _curve_times(report: FitReport) -> np.ndarray:
    end = max(s.time[-1] for s in report.specimens)
    return (np.linspace(0.0, 1.0, 300) ** 2) * end


def _condition_specimens(report: FitReport, condition):
    return [s for s in report.specimens if s.name in condition.specimens]


def _draw_condition(ax, res_ax, report, condition, anomaly, color, times):
    specimens = _condition_specimens(report, condition)
    d, mm = condition.diffusivity.value, condition.saturation.value
    geometries = {(s.thickness, s.width, s.length) for s in specimens}
    for index, s in enumerate(specimens):
        fitted = mm * fickian_fraction(s, d, report.in_plane)
        marker = MARKERS[index % len(MARKERS)]
        ax.plot(np.sqrt(s.time / DAY), s.moisture, marker, color=color, ms=4, mfc="none", ls="none")
        res_ax.plot(np.sqrt(s.time / DAY), s.moisture - fitted, marker, color=color, ms=3, mfc="none",
                    ls="none")
        if index == 0 or len(geometries) > 1:
            label = f"{condition.label}: Fick" if index == 0 else None
            ax.plot(np.sqrt(times / DAY), mm * fickian_fraction(s, d, report.in_plane, times), "-",
                    color=color, lw=1.2, label=label)
    if anomaly.non_fickian:
        fit = anomaly.langmuir
        ax.plot(np.sqrt(times / DAY), fit.saturation.value * two_phase_fraction(
            specimens[0], fit.diffusivity.value, fit.binding_rate.value, fit.release_rate.value,
            report.in_plane, times), "--", color=color, lw=1.2,
            label=f"{condition.label}: two-phase (NOT Fickian)")


def plot_fit(report: FitReport, path=None, save=None) -> Figures:
    """The fit's figure: moisture gain against sqrt(time) per condition with the fitted
    curves, and the Fickian residuals; written to ``path`` when it is given.

    Parameters
    ----------
    report : FitReport
        The fit.
    path : str or pathlib.Path, optional
        The figure file (PNG unless its suffix names another format); None: the figure is
        only returned.
    save : callable, optional
        ``save(fig, path) -> path`` writes the figure; default
        :func:`~fickcam.plotting.common.save_figure` (atomic).

    Returns
    -------
    Figures
        The one figure, shown inline in a notebook; ``.paths``: the file written.
    """
    plt = figure()
    fig, (ax, res_ax) = plt.subplots(2, 1, figsize=(8, 7), sharex=True,
                                     gridspec_kw={"height_ratios": [3, 1.2]})
    times = _curve_times(report)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for index, (condition, anomaly) in enumerate(zip(report.conditions, report.anomalies)):
        _draw_condition(ax, res_ax, report, condition, anomaly, colors[index % len(colors)], times)
    ax.set_ylabel("moisture gain M [wt %]")
    origin = "" if report.source.startswith("<") else f" from {report.source}"
    ax.set_title(f"{report.name}: weight gain{origin} (points) and fits (lines)")
    legend(ax, fontsize=8, loc="lower right")
    ax.grid(alpha=0.3)
    top = ax.secondary_xaxis("top", functions=(lambda x: np.square(x), lambda t: np.sqrt(np.maximum(t, 0))))
    top.set_xlabel("time [d]")
    res_ax.axhline(0.0, color="k", lw=0.8)
    res_ax.set_xlabel("sqrt(time) [sqrt(d)]")
    res_ax.set_ylabel("Fick residual [wt %]")
    res_ax.grid(alpha=0.3)
    fig.set_label(f"fit_{report.name}")
    return one_figure(fig, path, save)
