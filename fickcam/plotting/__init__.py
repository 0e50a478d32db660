"""Figures from a result Dataset; one module per kind of plot.

Each module exposes functions ``(ds, outdir=None, save=None) -> Figures``: the figures
are :class:`matplotlib.figure.Figure` objects made without pyplot (the caller's backend is
never changed), returned so that a notebook shows them, and written as PNG files to
``outdir`` when it is given. matplotlib is imported inside them, so ``import
fickcam.plotting`` stays light.
"""
from __future__ import annotations

import importlib
from pathlib import Path

from ..errors import InputError
from .common import Figures, age_colour, age_label, ages, days, drift_panel, figure, finish_plan_view, legend_outside, returns_figures, save_figure, tidy_ticks

__all__ = ["KINDS", "Figures", "available_kinds", "plot", "returns_figures", "age_colour", "age_label", "ages", "days", "drift_panel", "figure", "finish_plan_view", "legend_outside", "save_figure", "tidy_ticks"]

# kind -> (module, function, variables the kind needs)
KINDS = {
    "uptake": ("uptake", "plot", ("moisture_content",)),
    "kinematics": ("cam", "plot_kinematics", ("pressure_angle",)),  # translating or swinging arm
    "dynamics": ("cam", "plot_dynamics", ("contact_force",)),
    "vibration": ("train", "plot", ("dynamic_contact_force",)),
    "linkage": ("linkage", "plot", ("rocker_angle",)),
    "fields": ("fields", "plot", ("moisture",)),
    "elastic": ("elastic", "plot", ("failure_index",)),
    "limits": ("limits", "plot", ("limit_ratio",)),
    "sweep": ("sweep", "plot", ("case",)),
}


def available_kinds(ds) -> list[str]:
    """The plot kinds this result has data for.

    Parameters
    ----------
    ds : xarray.Dataset
        A result of a run or of a sweep.

    Returns
    -------
    list of str
        Keys of ``KINDS``; ``["sweep"]`` for a sweep result (a ``case`` dimension).
    """
    if "case" in ds.dims:  # a sweep result: one figure set over its varied parameters
        return ["sweep"]
    names = set(ds.variables)
    return [k for k, (_, _, needs) in KINDS.items() if k != "sweep" and all(n in names for n in needs)]


@returns_figures
def plot(ds, outdir=None, kind: str = "all", save=None) -> Figures:
    """The figures of ``kind`` (or of every kind the result supports), written as PNG files
    to ``outdir`` when it is given.

    In a notebook the returned figures show inline; matplotlib's backend and pyplot's
    figures are left as they were.

    Parameters
    ----------
    ds : xarray.Dataset
        A result (of a run or of a sweep).
    outdir : str or pathlib.Path, optional
        The folder the PNG files are written to (created when missing); None: the
        figures are only returned.
    kind : str
        One of ``KINDS`` ("uptake", "kinematics", "dynamics", "vibration", "linkage",
        "fields", "elastic", "limits", "sweep"), or "all": every kind the result has
        data for.
    save : callable
        ``save(fig, path) -> path`` writes one figure and returns the path written; the
        default, :func:`~fickcam.plotting.common.save_figure`, writes the file atomically. Another writer (a
        different format) goes here. Used only with ``outdir``.

    Returns
    -------
    Figures
        The figures (a list of :class:`matplotlib.figure.Figure`, each labelled with its
        file's stem), shown inline in a notebook; ``.paths``: the files written.

    Raises
    ------
    fickcam.errors.InputError
        When the kind is unknown or the result holds no data for it.
    """
    kinds = available_kinds(ds) if kind == "all" else [kind]
    if kind != "all":
        if kind not in KINDS:
            raise InputError(f"unknown plot kind {kind!r} (one of: {', '.join(KINDS)}, all)")
        if kind not in available_kinds(ds):
            raise InputError(f"this result has no data for --kind {kind} "
                             f"(available: {', '.join(available_kinds(ds)) or 'none'})")
    for name in kinds:
        module_name, function, _ = KINDS[name]
        module = importlib.import_module(f".{module_name}", __name__)
        getattr(module, function)(ds, outdir, save=save)
