"""Elastic follower train over ageing (`fickcam plot --kind vibration`): dynamic against
kinematic displacement and contact force over the cam angle at up to four ages, and the
natural frequency, jump speeds and residual vibration over ageing time."""
from __future__ import annotations

from pathlib import Path

from .common import legend, age_colour, age_label, ages, days, figure, legend_outside, Figures, returns_figures

ANGLE_PANELS = (("follower_displacement", "dynamic_follower_displacement", "displacement [mm]", 1e3),
                (None, "dynamic_displacement_error", "dynamic − kinematic [mm]", 1e3),
                ("contact_force", "dynamic_contact_force", "contact force [N]", 1.0))


@returns_figures
def plot(ds, outdir=None, save=None) -> Figures:
    """cam_vibration.png and cam_vibration_ageing.png.

    Parameters
    ----------
    ds : xarray.Dataset
        A cam result with the vibrating train's ``dynamic_contact_force``.
    outdir : str or pathlib.Path, optional
        Folder for the vibration PNGs. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. cam_vibration.png and cam_vibration_ageing.png.
    """
    plt = figure()
    name = ds.attrs.get("scene_name", "")
    return [_over_angle(plt, ds, outdir, name, save), _over_ageing(plt, ds, outdir, name, save)]


def _over_angle(plt, ds, outdir, name, save) -> Path:
    fig, axes = plt.subplots(3, 1, figsize=(7.5, 8), sharex=True)
    angle = ds["cam_angle"].values
    t = days(ds)
    for ax, (rigid, elastic, ylabel, scale) in zip(axes, ANGLE_PANELS):
        for k in ages(ds):
            color = age_colour(ds, k)
            if rigid is not None:
                ax.plot(angle, ds[rigid].isel(time=k).values * scale, "--", color=color, lw=0.9)
            ax.plot(angle, ds[elastic].isel(time=k).values * scale, color=color, label=age_label(t[k], t[-1]))
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    axes[2].axhline(0.0, color="k", lw=0.6)
    axes[0].set_title(f"{name}: elastic follower (solid) vs rigid (dashed)")
    legend_outside(axes[0])
    axes[-1].set_xlabel("cam angle [deg]")
    return save(fig, outdir / "cam_vibration.png")


def _over_ageing(plt, ds, outdir, name, save) -> Path:
    fig, axes = plt.subplots(3, 1, figsize=(7.5, 7.5), sharex=True)
    t = days(ds)
    axes[0].plot(t, ds["natural_frequency"].values, "o-")
    axes[0].set_ylabel("natural frequency [Hz]")
    axes[1].plot(t, ds["dynamic_jump_speed"].values, "o-", label="elastic (dynamic)")
    if "jump_speed" in ds:
        axes[1].plot(t, ds["jump_speed"].values, "s--", label="rigid")
    axes[1].set_ylabel("jump speed [rpm]")
    legend(axes[1], fontsize=8)
    axes[2].plot(t, ds["residual_vibration"].values * 1e3, "o-", color="C3")
    axes[2].set_ylabel("residual vibration [mm]")
    axes[2].set_xlabel("ageing time [d]")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].set_title(f"{name}: follower train over ageing")
    return save(fig, outdir / "cam_vibration_ageing.png")
