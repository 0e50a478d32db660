"""Four-bar over ageing: coupler curves, rocker angle and its drift (as seed 001,
seeds/001_51a6f900df76f3cc.txt Figs. 6-9, plots theta_41 - theta_4), transmission
angle and input torque, dry vs aged."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .common import age_label, ages, days, figure, finish_plan_view, save_figure


def _wrapped_degrees(x):
    return (np.asarray(x) + 180.0) % 360.0 - 180.0


def _over_crank(ax, ds, name, picks, t, ylabel, transform=None, style="-", prefix=""):
    """One line per ageing index k in ``picks``, coloured by k (the same in every panel)."""
    crank = ds["crank_angle"].values
    for k in picks:
        y = ds[name].isel(time=k).values
        ax.plot(crank, transform(y) if transform else y, style, color=f"C{k % 10}",
                label=prefix + age_label(t[k]))
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)


def plot(ds, outdir) -> list[Path]:
    """Three figures: linkage_coupler_curve.png, linkage_rocker.png (angle and drift
    vs crank angle), linkage_transmission_torque.png."""
    plt = figure()
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    t = days(ds)
    picks = ages(ds)
    name = ds.attrs.get("scene_name", "")
    written = []

    fig, ax = plt.subplots(figsize=(6.5, 6))
    if "coupler_point_x" in ds:
        for k in picks:
            ax.plot(ds["coupler_point_x"].isel(time=k).values * 1e3,
                    ds["coupler_point_y"].isel(time=k).values * 1e3, color=f"C{k % 10}",
                    label=age_label(t[k]))
    finish_plan_view(ax, f"{name}: coupler curve")
    written.append(save_figure(fig, outdir / "linkage_coupler_curve.png"))

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    _over_crank(top, ds, "rocker_angle", picks, t, "rocker angle theta4 [deg]")
    dry = ds["rocker_angle"].isel(time=0).values
    _over_crank(bottom, ds, "rocker_angle", picks[1:], t, "aged - dry [deg]",
                lambda y: _wrapped_degrees(y - dry), prefix="theta4, ")
    if "coupler_angle" in ds:
        dry3 = ds["coupler_angle"].isel(time=0).values
        _over_crank(bottom, ds, "coupler_angle", picks[1:], t, "aged - dry [deg]",
                    lambda y: _wrapped_degrees(y - dry3), style=":", prefix="theta3, ")
    top.set_title(f"{name}: rocker angle and its drift")
    top.legend(fontsize=8)
    bottom.legend(fontsize=8)
    bottom.set_xlabel("crank angle theta2 [deg]")
    written.append(save_figure(fig, outdir / "linkage_rocker.png"))

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    if "transmission_angle" in ds:
        _over_crank(top, ds, "transmission_angle", picks, t, "transmission angle [deg]")
        top.legend(fontsize=8)
    if "input_torque" in ds:
        _over_crank(bottom, ds, "input_torque", picks, t, "input torque [N m]")
        bottom.legend(fontsize=8)
    top.set_title(f"{name}: transmission angle and input torque")
    bottom.set_xlabel("crank angle theta2 [deg]")
    written.append(save_figure(fig, outdir / "linkage_transmission_torque.png"))
    return written
