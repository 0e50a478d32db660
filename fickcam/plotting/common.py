"""Helpers every plot module shares: the figure factory, ageing times in days, labels,
ticks, drift panels, legends, the plan-view finisher and the atomic save.

Figures are :class:`matplotlib.figure.Figure` objects made without pyplot: they need no
display and never change the caller's backend or pyplot's list of open figures.
"""
from __future__ import annotations

import io
import functools
import textwrap
import math
import base64
from pathlib import Path
from ..errors import times_in
import numpy as np
from ..errors import format_duration
from ..schema import design_name
from ..results.query import drift
from ..files import replaced_atomically


class FigureMaker:
    """Makes figures without pyplot: ``subplots`` as :func:`matplotlib.pyplot.subplots` takes
    it, on a :class:`matplotlib.figure.Figure` that belongs to no backend (PNG and the other
    file formats are drawn by matplotlib's own renderers, without a display)."""

    @property
    def rcParams(self):  # noqa: N802 (pyplot's name, so that plot code reads the same)
        """matplotlib's settings (colour cycle, fonts)."""
        # deferred: keeps matplotlib off the start-up path
        import matplotlib

        return matplotlib.rcParams

    @staticmethod
    def subplots(nrows: int = 1, ncols: int = 1, *, figsize=None, layout=None, **options):
        """A new figure and its axes, as :func:`matplotlib.pyplot.subplots` returns them.

        Parameters
        ----------
        nrows, ncols : int
            The grid of axes [1].
        figsize : tuple of float, optional
            Width and height [inch].
        layout : str, optional
            The figure's layout engine (``"constrained"``, ``"tight"``); None: none.
        **options
            Passed to :meth:`matplotlib.figure.Figure.subplots` (``sharex``, ``squeeze``,
            ``gridspec_kw``...).

        Returns
        -------
        tuple
            (:class:`matplotlib.figure.Figure`, axes).
        """
        # deferred: keeps matplotlib off the start-up path
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        fig = Figure(figsize=figsize, layout=layout)
        FigureCanvasAgg(fig)  # drawn by Agg whatever pyplot's backend is: no display needed
        return fig, fig.subplots(nrows, ncols, **options)


class Figures(list):
    """The figures a plotting function drew: a list of :class:`matplotlib.figure.Figure`,
    shown inline in a notebook (one image each), and ``paths``, the files written (empty
    when no folder was given).

    Parameters
    ----------
    figures : iterable of matplotlib.figure.Figure
        The figures, in order.
    """

    def __init__(self, figures=()):
        super().__init__(figures)
        self.paths: list[Path] = []

    def __repr__(self) -> str:
        names = ", ".join(fig.get_label() or "figure" for fig in self)
        return f"<{len(self)} fickcam figure{'s' * (len(self) != 1)}: {names}>"

    def _repr_html_(self) -> str:
        return "".join(f'<img src="data:image/png;base64,{base64.b64encode(png(fig)).decode()}"'
                       f' alt="{fig.get_label()}"/>' for fig in self)

    def _ipython_display_(self) -> None:
        # deferred: keeps IPython off the start-up path
        from IPython.display import Image, display

        for fig in self:
            display(Image(data=png(fig), format="png"))


def png(fig, dpi: float = 100.0) -> bytes:
    """``fig`` as PNG bytes, trimmed to what is drawn.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    dpi : float
        Its resolution [dots per inch].

    Returns
    -------
    bytes
        The PNG file's content.
    """

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    return buffer.getvalue()


def returns_figures(draw):
    """Make a plotting function ``draw(ds, outdir, *args, save=...)`` return its figures.

    The wrapped function takes ``outdir`` optionally: without it the figures are only
    returned (a notebook shows them); with it each is also written there by ``save(fig,
    path)`` (default :func:`save_figure`). It returns :class:`Figures`, whose ``paths`` are
    the files written. ``draw`` calls ``save(fig, path)`` once per figure, where ``path``
    names the figure (its stem becomes the figure's label).

    Parameters
    ----------
    draw : callable
        The plotting function.

    Returns
    -------
    callable
        The wrapped function.
    """


    @functools.wraps(draw)
    def wrapper(ds, outdir=None, *args, save=None, **kwargs):
        figures, write = Figures(), save_figure if save is None else save

        def keep(fig, path):
            tidy_ticks(fig)
            fig.set_label(Path(path).stem)
            if outdir is not None:
                figures.paths.append(write(fig, path))
            figures.append(fig)
            return fig

        if outdir is not None:
            Path(outdir).mkdir(parents=True, exist_ok=True)
        with times_in(getattr(ds, "attrs", {}).get("time_unit") or None):  # the scene's unit
            draw(ds, Path("." if outdir is None else outdir), *args, save=keep, **kwargs)
        return figures

    return wrapper


def one_figure(fig, path=None, save=None) -> Figures:
    """``fig`` as the :class:`Figures` a plotting function returns, written to ``path`` when given.

    For the plotting functions that draw one figure to one file (not a folder of them): the
    figure is labelled with the file's stem, its ticks are tidied, and it is shown inline
    in a notebook.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : str or pathlib.Path, optional
        The file; its suffix gives the format. None: the figure is only returned.
    save : callable, optional
        ``save(fig, path) -> path`` writes the figure; default :func:`save_figure`.

    Returns
    -------
    Figures
        The one figure; ``.paths`` holds ``path`` when it was written.
    """
    tidy_ticks(fig)
    figures = Figures([fig])
    if path is not None:
        fig.set_label(Path(path).stem)
        figures.paths.append((save_figure if save is None else save)(fig, Path(path)))
    return figures


def figure() -> FigureMaker:
    """The maker of new figures (:class:`FigureMaker`): no pyplot, no backend change."""
    return FigureMaker()


def days(ds):
    """Ageing times of ``ds`` in days.

    Parameters
    ----------
    ds : xarray.Dataset
        A result (``time`` in days, as :func:`fickcam.open_result` gives it).

    Returns
    -------
    numpy.ndarray
        The ageing times [d], float.
    """

    return np.asarray(ds["time"].values, float)


#: a mechanism's motion: ageing times where it is NaN have no valid state (beyond the wet Tg)
MOTIONS = ("follower_displacement", "follower_arm_angle", "rocker_angle")


def ages(ds, most: int = 4) -> list[int]:
    """Indices of up to ``most`` ageing times spread from the first to the last.

    Only ageing times where the mechanism has a valid state (a finite motion, a line to draw)
    are picked.

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    most : int
        The most indices returned [1].

    Returns
    -------
    list of int
        Ascending indices along ``time``.
    """

    valid = np.arange(ds.sizes["time"])
    motion = next((name for name in MOTIONS if name in ds), None)
    if motion is not None:
        values = ds[motion].transpose("time", ...).values.reshape(valid.size, -1)
        valid = valid[np.isfinite(values).any(axis=1)] if np.isfinite(values).any() else valid
    n = valid.size
    return sorted(set(valid[np.linspace(0, n - 1, min(n, most)).round().astype(int)].tolist()))


def wet_tg_stop(ds) -> str | None:
    """Where and why the result stops: the sentence a figure prints when parts passed their
    wet glass transition before the last ageing time (nothing is computed from then on).

    Parameters
    ----------
    ds : xarray.Dataset
        A result (``within_wet_tg`` over time and part, ``temperature`` over time [K]).

    Returns
    -------
    str or None
        ``"not computed from t = 10 d: at 150 °C the cam and follower passed their wet Tg
        (157 °C at t = 0 d)"``, in lines of at most 72 characters; None when every ageing
        time was computed.
    """


    if "within_wet_tg" not in ds:
        return None
    within = ds["within_wet_tg"].transpose("time", ...).values.astype(bool)
    stopped = ~within.reshape(within.shape[0], -1).all(axis=1)
    if not stopped.any():
        return None
    k = int(np.argmax(stopped))
    t = days(ds)
    parts = [str(p) for p, ok in zip(np.atleast_1d(ds["part"].values), np.atleast_1d(within[k]))
             if not ok] if "part" in ds.coords else []
    who = " and ".join([", ".join(parts[:-1]), parts[-1]] if len(parts) > 1 else parts) or "parts"
    text = f"not computed from {age_label(t[k], t[-1])}: "
    if "temperature" in ds:
        text += f"at {float(ds['temperature'].values[k]) - 273.15:.0f} °C "
    text += f"the {who} passed {'their' if len(parts) != 1 else 'its'} wet Tg"
    tgs = [ds[name].isel(time=k - 1).values for name in ("glass_transition_temperature",
                                                          "surface_glass_transition_temperature")
           if name in ds and k > 0]
    if tgs and np.isfinite(tgs).any():
        tg = float(np.nanmin(tgs)) - 273.15
        text += f" ({tg:.0f} °C at {age_label(t[k - 1], t[-1])})"
    return "\n".join(textwrap.wrap(text, 72))


def age_colour(ds, k: int):
    """The colour of ageing index ``k`` of ``ds`` in every figure of the result.

    viridis from the first ageing time (dark) to the last (green), so order reads as time.

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    k : int
        An index along ``time``.

    Returns
    -------
    tuple of float
        An RGBA colour.
    """
    # deferred: keeps matplotlib off the start-up path
    from matplotlib import colormaps

    return colormaps["viridis"](0.85 * k / max(ds.sizes["time"] - 1, 1))


def age_label(t_days: float, span_days: float | None = None) -> str:
    """Legend text of an ageing time, in the run's natural unit and to four digits at most.

    Parameters
    ----------
    t_days : float
        The ageing time [d].
    span_days : float, optional
        The run's last ageing time [d], so that every label of a run shares one unit (a
        3-hour history in h, a 60-day one in d, a 5-year one in yr); by default the
        ageing time itself.

    Returns
    -------
    str
        ``"t = 30 d"``, ``"t = 2.5 h"`` or ``"t = 20 min"``.
    """

    span = None if span_days is None else float(span_days) * DAY
    return f"t = {format_duration(float(t_days) * DAY, span)}"


#: one day [s]
DAY = 86400.0


def finish_plan_view(ax, title: str) -> None:
    """Equal-aspect x-y axes in mm with title, legend and grid (profiles, coupler curves).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes, with curves drawn in mm.
    title : str
        Their title.
    """
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title)
    legend(ax, fontsize=8)
    ax.grid(alpha=0.3)


def length_scale(largest: float) -> tuple[float, str]:
    """(scale from m, unit) to show lengths up to ``largest``: µm below a millimetre.

    Parameters
    ----------
    largest : float
        The largest length to show [m].

    Returns
    -------
    scale : float
        Displayed value / value in m [unit/m]: 1e6 or 1e3.
    unit : str
        ``"µm"`` or ``"mm"``.
    """
    return (1e6, "µm") if largest < 1e-3 else (1e3, "mm")


def exaggeration(size: float, deviation: float) -> float:
    """A factor of 1, 2 or 5 x 10^n that makes the largest ``deviation`` about 8 % of ``size``.

    Parameters
    ----------
    size : float
        The size of the outline drawn [m].
    deviation : float
        The largest deviation from it [m].

    Returns
    -------
    float
        The factor [-]: the largest of 1, 2, 5 x 10^n not above 0.08 ``size``/``deviation``;
        1 (the deviation shown as it is) when it is already that large, or not positive.
    """

    if not deviation > 0 or deviation >= 0.08 * size:
        return 1.0
    wanted = 0.08 * size / deviation
    decade = 10.0 ** math.floor(math.log10(wanted))
    return max(f * decade for f in (1.0, 2.0, 5.0) if f * decade <= wanted)


def reference_curve(ds, names) -> tuple[tuple, str]:
    """The as-designed values of the variables ``names``, or their values at the first ageing time.

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    names : sequence of str
        Variables with an as-designed counterpart (``<name>_design``).

    Returns
    -------
    values : tuple of numpy.ndarray
        One array per name [stored unit].
    label : str
        ``"design"``, or the first ageing time's label in a result without design values.
    """

    if all(design_name(n) in ds for n in names):
        return tuple(ds[design_name(n)].values for n in names), "design"
    return tuple(ds[n].isel(time=0).values for n in names), age_label(days(ds)[0], days(ds)[-1])


def exaggerated_outlines(ax, ds, reference, deviations, picks, what: str,
                         against: str = "design") -> None:
    """Plan view in mm of a reference outline and its aged outlines, deviations magnified.

    ``reference`` is drawn dashed; for each ageing index in ``picks`` the reference plus its
    deviation multiplied by one stated factor (:func:`exaggeration`), so that
    sub-millimetre drift shows.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    ds : xarray.Dataset
        The result (ageing times, colours).
    reference : tuple of numpy.ndarray
        (x, y) of the reference outline [m].
    deviations : mapping of int to tuple of numpy.ndarray
        (dx, dy) from the reference at each ageing index [m].
    picks : sequence of int
        The ageing indices drawn.
    what : str
        The title's first line.
    against : str
        The reference's legend label (``"design"`` or an ageing time).
    """

    x, y = reference
    size = float(np.ptp(np.concatenate([x, y])))
    largest = max(float(np.nanmax(np.hypot(*deviations[k]))) for k in picks)
    factor = exaggeration(size, largest)
    ax.plot(np.append(x, x[0]) * 1e3, np.append(y, y[0]) * 1e3, "k--", lw=1, label=against)
    t = days(ds)
    for k in picks:
        dx, dy = deviations[k]
        ax.plot(np.append(x + factor * dx, x[0] + factor * dx[0]) * 1e3,
                np.append(y + factor * dy, y[0] + factor * dy[0]) * 1e3,
                color=age_colour(ds, k), label=age_label(t[k], t[-1]))
    shown = f"deviation from {'the ' * (against == 'design')}{against} ×{factor:g}" if factor > 1 \
        else "to scale"
    finish_plan_view(ax, f"{what}\n({shown})")


def length_drift_panel(ax, ds, x, lengths: dict, xlabel: str, quantity: str, title: str) -> None:
    """A line per ageing index of a length against ``x``, in µm or mm as their size asks.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel.
    ds : xarray.Dataset
        The result, for its ageing times and their colours.
    x : array_like
        The abscissa [unit named in ``xlabel``].
    lengths : dict of int to numpy.ndarray
        Ageing index -> the lengths along ``x`` [m].
    xlabel : str
        The x label, with its unit.
    quantity : str
        The y label, without unit (the unit chosen is appended).
    title : str
        The panel's title.
    """

    scale, units = length_scale(max(float(np.nanmax(np.abs(v))) for v in lengths.values()))
    t = days(ds)
    for k, values in lengths.items():
        ax.plot(x, values * scale, color=age_colour(ds, k), label=age_label(t[k], t[-1]))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"{quantity} [{units}]")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    legend_outside(ax)


def tidy_ticks(fig) -> None:
    """Plain, few tick labels on every linear axis left to matplotlib's defaults.

    No offset (``+1.4377e-2``), no crowding: at most 5 ticks on x, 6 on y.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, changed in place.
    """
    # deferred: keeps matplotlib off the start-up path
    from matplotlib.ticker import AutoLocator, MaxNLocator, ScalarFormatter

    for ax in fig.axes:
        for axis, bins in ((ax.xaxis, 5), (ax.yaxis, 6)):
            if axis.get_scale() != "linear" or not isinstance(axis.get_major_formatter(),
                                                             ScalarFormatter):
                continue
            axis.get_major_formatter().set_useOffset(False)
            if type(axis.get_major_locator()) is AutoLocator:
                axis.set_major_locator(MaxNLocator(nbins=bins, steps=[1, 2, 2.5, 5, 10]))


def drift_panel(ax, x, ds, name: str, picks, scale: float, ylabel: str) -> None:
    """``name`` minus its as-designed value over an angle, a line per ageing index in ``picks``.

    The t = 0 line is the thermal change alone; the others add the moisture. A spike at a
    step of the curve is clipped from the y range, and the panel says so.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    x : array_like
        The angles [degree].
    ds : xarray.Dataset
        A result holding ``name`` and ``<name>_design``.
    name : str
        The variable.
    picks : sequence of int
        The ageing indices drawn.
    scale : float
        Displayed value / stored value [display unit / stored unit].
    ylabel : str
        The y label, naming the displayed unit.

    Raises
    ------
    fickcam.errors.InputError
        When the result holds no as-designed value of ``name`` (:func:`fickcam.results.query.drift`).
    """


    change = drift(ds, name, "design")
    t = days(ds)
    shown = []
    for k in picks:
        shown.append(change.isel(time=k).values * scale)
        ax.plot(x, shown[-1], color=age_colour(ds, k), label=age_label(t[k], t[-1]))
    ax.axhline(0.0, color="k", lw=0.8, ls="--")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    _clip_spikes(ax, np.concatenate(shown))


def _clip_spikes(ax, values) -> None:
    """y limits from the 1st to 99th percentile: a step of the curve (a joint of the motion
    law) moves a little with the swelling, and its pointwise difference is a spike that
    would flatten the drift everywhere else; say so when one is cut."""

    values = values[np.isfinite(values)]
    if values.size < 20:
        return
    low, high = np.percentile(values, [1, 99])
    low, high = min(low, 0.0), max(high, 0.0)
    pad = 0.15 * (high - low) or 1.0
    if values.min() < low - pad or values.max() > high + pad:
        ax.set_ylim(low - pad, high + pad)
        ax.text(0.99, 0.03, "spikes at steps of the curve cut off", transform=ax.transAxes,
                ha="right", va="bottom", fontsize=7, color="0.4")


def legend(ax, **kwargs) -> None:
    """``ax``'s legend, drawn only when a curve has a label (an ageing time past a part's wet
    glass transition draws none): no matplotlib warning about an empty legend.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    **kwargs
        Passed to :meth:`matplotlib.axes.Axes.legend`.
    """
    if ax.get_legend_handles_labels()[0]:
        ax.legend(**kwargs)


def legend_outside(ax, **kwargs) -> None:
    """The legend to the right of the axes, where it hides no curve.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    **kwargs
        Passed to :meth:`matplotlib.axes.Axes.legend`.
    """
    legend(ax, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
           **kwargs)


def save_figure(fig, path: Path) -> Path:
    """Write ``fig`` to ``path`` through a temporary file and a rename.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (its ticks are tidied first, :func:`tidy_ticks`).
    path : pathlib.Path
        The file; its suffix gives the format (png by default), 120 dpi.

    Returns
    -------
    pathlib.Path
        ``path``.
    """

    tidy_ticks(fig)
    with replaced_atomically(path) as tmp:
        fig.savefig(tmp, format=Path(path).suffix.lstrip(".").lower() or "png", dpi=120,
                    bbox_inches="tight")
    return path
