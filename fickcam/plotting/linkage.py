"""Four-bar over ageing: coupler curves, rocker angle and its drift (as Singh & Sanyal
2016, Figs. 6-9, plot theta_41 - theta_4) against the design
and against t = 0, transmission angle and input torque."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..schema import design_name
from .common import (age_colour, age_label, ages, days, drift_panel, exaggerated_outlines,
                     figure, legend_outside, length_drift_panel, reference_curve, Figures, returns_figures)


def _wrapped_degrees(x):
    return (np.asarray(x) + 180.0) % 360.0 - 180.0


def _over_crank(ax, ds, name, picks, t, ylabel, transform=None, style="-", prefix=""):
    """One line per ageing index k in ``picks``, coloured by k (the same in every panel)."""
    crank = ds["crank_angle"].values
    for k in picks:
        y = ds[name].isel(time=k).values
        ax.plot(crank, transform(y) if transform else y, style, color=age_colour(ds, k),
                label=prefix + age_label(t[k], t[-1]))
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)


@returns_figures
def plot(ds, outdir=None, save=None) -> Figures:
    """Three figures: linkage_coupler_curve.png, linkage_rocker.png (angle and drift
    vs crank angle), linkage_transmission_torque.png.

    Parameters
    ----------
    ds : xarray.Dataset
        A four-bar result (``rocker_angle`` over the crank angle).
    outdir : str or pathlib.Path, optional
        Output folder of the three linkage figures. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. Coupler curve, rocker and transmission-torque figures, in that order.
    """
    plt = figure()
    t = days(ds)
    picks = ages(ds)
    name = ds.attrs.get("scene_name", "")
    written = []

    if "coupler_point_x" in ds:
        written.append(_coupler_figure(plt, ds, picks, t, name, outdir, save))

    written.append(_rocker_figure(plt, ds, picks, t, name, outdir, save))

    # no drift panel here: the transmission angle folds at 90 deg (the acute angle), so its
    # difference jumps where the aged and design curves fold at different crank angles
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    if "transmission_angle" in ds:
        _over_crank(top, ds, "transmission_angle", picks, t, "transmission angle [deg]")
    if "input_torque" in ds:
        _over_crank(bottom, ds, "input_torque", picks, t, "input torque [N m]")
    legend_outside(top)
    top.set_title(f"{name}: transmission angle and input torque")
    bottom.set_xlabel("crank angle theta2 [deg]")
    written.append(save(fig, outdir / "linkage_transmission_torque.png"))
    return written


def _coupler_figure(plt, ds, picks, t, name, outdir, save) -> Path:
    """linkage_coupler_curve.png: the coupler curve with its drift from the design (else
    from the first ageing time) exaggerated by a stated factor, and the coupler point's
    distance from that position at each crank angle."""
    names = ("coupler_point_x", "coupler_point_y")
    reference, against = reference_curve(ds, names)
    deviation = {k: tuple(ds[c].isel(time=k).values - r for c, r in zip(names, reference))
                 for k in picks}
    fig, (plan, over) = plt.subplots(1, 2, figsize=(12, 5.6), gridspec_kw={"width_ratios": [1, 1.3]})
    exaggerated_outlines(plan, ds, reference, deviation, picks, f"{name}: coupler curve", against)
    distance = {k: np.hypot(*d) for k, d in deviation.items()}
    crank = _closed(ds["crank_angle"].values)
    crank[-1] += 360.0
    length_drift_panel(over, ds, crank, {k: _closed(d) for k, d in distance.items()},
                       "crank angle theta2 [deg]", f"coupler point distance from {against}",
                       "coupler point: distance from its "
                       + ("as-designed position" if against == "design" else f"position at {against}"))
    over.set_ylim(bottom=0.0)
    return save(fig, outdir / "linkage_coupler_curve.png")


def _closed(values: np.ndarray) -> np.ndarray:
    """A curve over a full turn of the crank with its first point repeated at the end
    (the crank angle grid stops one step short of 360 deg), so it closes."""
    return np.append(values, values[:1])


def _rocker_figure(plt, ds, picks, t, name, outdir, save) -> Path:
    """linkage_rocker.png: theta4, then theta4 and theta3 minus the design (the t = 0 line:
    the thermal change alone), then minus their t = 0 values (the moisture drift)."""
    with_design = design_name("rocker_angle") in ds
    fig, axes = plt.subplots(2 + with_design, 1, figsize=(7, 3.0 * (2 + with_design) + 0.6),
                             sharex=True)
    _over_crank(axes[0], ds, "rocker_angle", picks, t, "rocker angle theta4 [deg]")
    if with_design:
        drift_panel(axes[1], ds["crank_angle"].values, ds, "rocker_angle", picks, 1.0,
                    "theta4 − design [deg]")
    start = ds["rocker_angle"].isel(time=0).values
    _over_crank(axes[-1], ds, "rocker_angle", picks[1:], t, "change since t = 0 [deg]",
                lambda y: _wrapped_degrees(y - start), prefix="theta4, ")
    if "coupler_angle" in ds:
        start3 = ds["coupler_angle"].isel(time=0).values
        _over_crank(axes[-1], ds, "coupler_angle", picks[1:], t, "change since t = 0 [deg]",
                    lambda y: _wrapped_degrees(y - start3), style=":", prefix="theta3, ")
    axes[0].set_title(f"{name}: rocker angle and its drift")
    legend_outside(axes[0])
    legend_outside(axes[-1])
    axes[-1].set_xlabel("crank angle theta2 [deg]")
    return save(fig, outdir / "linkage_rocker.png")
