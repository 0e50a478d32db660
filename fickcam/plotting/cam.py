"""Cam and follower over ageing (`fickcam plot --kind kinematics|dynamics`): S/V/A/J at
several ages, the working profile dry vs aged, contact force, torque and Hertz stress
vs cam angle at several ages, jump speed and peak stress vs ageing time. Works on the
result Dataset (cam_angle in degrees, jump_speed in rpm, SI otherwise)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..schema import design_name
from .common import (legend, age_colour, age_label, ages, days, drift_panel, exaggerated_outlines,
                     figure, legend_outside, length_drift_panel, reference_curve, Figures, returns_figures,
                     wet_tg_stop)

KINEMATICS = (("follower_displacement", "displacement [mm]", 1e3),
              ("follower_velocity", "velocity [m/s]", 1.0),
              ("follower_acceleration", "acceleration [m/s²]", 1.0),
              ("follower_jerk", "jerk [m/s³]", 1.0))
#: a swinging-arm follower (the arm angle is stored in degrees)
ARM_KINEMATICS = (("follower_arm_angle", "arm angle [deg]", 1.0),
                  ("follower_arm_angular_velocity", "angular velocity [rad/s]", 1.0),
                  ("follower_arm_angular_acceleration", "angular acceleration [rad/s²]", 1.0),
                  ("follower_arm_angular_jerk", "angular jerk [rad/s³]", 1.0))
DYNAMICS = (("contact_force", "contact force [N]", 1.0), ("cam_torque", "cam torque [N m]", 1.0),
            ("arm_torque", "arm torque [N m]", 1.0), ("contact_stress", "Hertz stress [MPa]", 1e-6))


def kinematic_rows(ds):
    """The S/V/A/J rows of a translating follower, or of a swinging arm.

    Parameters
    ----------
    ds : xarray.Dataset
        A cam result.

    Returns
    -------
    tuple
        (variable, axis label, scale from the stored unit) per panel row: ``KINEMATICS``
        when the result holds ``follower_displacement``, else :data:`ARM_KINEMATICS`.
    """
    return KINEMATICS if "follower_displacement" in ds else ARM_KINEMATICS


def angle_panels(plt, ds, rows, title: str, drift=None):
    """One panel per (variable, label, scale) in ``rows`` against the cam angle, a line per
    age, and, when ``drift`` = (variable, label, scale) and the result holds its design,
    a last panel of its change from the design (invisible at full scale).

    Parameters
    ----------
    plt : module
        The figure maker (:func:`~fickcam.plotting.common.figure`).
    ds : xarray.Dataset
        The result, over (time, cam_angle) in SI.
    rows : sequence of tuple
        (variable, axis label, scale from SI to the label's unit) per panel.
    title : str
        The figure's title.
    drift : tuple, optional
        (variable, label, scale) of the panel of change from the design.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (not saved).
    """
    present = [r for r in rows if r[0] in ds]
    with_drift = drift is not None and design_name(drift[0]) in ds
    n = len(present) + with_drift
    fig, axes = plt.subplots(n, 1, figsize=(7.5, 2.2 * n + 0.6), sharex=True, squeeze=False)
    angle = ds["cam_angle"].values
    t = days(ds)
    for ax, (name, ylabel, scale) in zip(axes[:, 0], present):
        for k in ages(ds):
            ax.plot(angle, ds[name].isel(time=k).values * scale, color=age_colour(ds, k), label=age_label(t[k], t[-1]))
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    if with_drift:
        name, ylabel, scale = drift
        drift_panel(axes[-1, 0], angle, ds, name, ages(ds), scale, f"{ylabel}\n− design")
    stop = wet_tg_stop(ds)
    axes[0, 0].set_title(title + (f"\n{stop}" if stop else ""), fontsize=9 if stop else None)
    legend_outside(axes[0, 0])
    axes[-1, 0].set_xlabel("cam angle [deg]")
    return fig


@returns_figures
def plot_kinematics(ds, outdir=None, save=None) -> Figures:
    """cam_kinematics.png (S/V/A/J vs cam angle at up to four ages), cam_drift.png (change
    of displacement and acceleration since the first age) and, when the profile is
    stored, cam_profile.png (working profile, first vs last age).

    Parameters
    ----------
    ds : xarray.Dataset
        A cam result (``pressure_angle`` over the cam angle).
    outdir : str or pathlib.Path, optional
        Where the two or three PNG files go (created if missing). None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. cam_kinematics.png, cam_drift.png and, with a stored profile, cam_profile.png.
    """
    plt = figure()
    name = ds.attrs.get("scene_name", "")
    rows = kinematic_rows(ds)
    written = [save(angle_panels(plt, ds, rows, f"{name}: follower motion", drift=rows[0]),
                    outdir / "cam_kinematics.png")]
    written.append(_drift(plt, ds, outdir, name, rows, save))
    if "profile_x" in ds:
        written.append(_profile(plt, ds, outdir, name, save))
    return written


def polar(x, y) -> tuple[np.ndarray, np.ndarray]:
    """(polar angle, radius) of points (x, y) in the cam frame.

    Parameters
    ----------
    x, y : numpy.ndarray
        The points [m].

    Returns
    -------
    angle : numpy.ndarray
        The polar angle [degree], in [0, 360).
    radius : numpy.ndarray
        The distance from the cam centre [m].
    """
    return np.degrees(np.arctan2(y, x)) % 360.0, np.hypot(x, y)


def radial_deviation(reference, x, y) -> np.ndarray:
    """The radius of the profile points (x, y) minus the ``reference`` at its polar angles.

    The aged radius is interpolated (periodically) at the reference's polar angles, as a
    roundness gauge reads a profile.

    Parameters
    ----------
    reference : tuple of numpy.ndarray
        (polar angle [degree], ascending; radius [m]) of the reference profile (:func:`polar`).
    x, y : numpy.ndarray
        The points of the profile compared [m].

    Returns
    -------
    numpy.ndarray
        Radius minus reference radius at each reference angle [m].
    """
    angle, radius = reference
    aged_angle, aged_radius = polar(x, y)
    order = np.argsort(aged_angle)
    return np.interp(angle, aged_angle[order], aged_radius[order], period=360.0) - radius


def _profile(plt, ds, outdir, name, save) -> Path:
    """cam_profile.png: the working profile with its drift from the design (else from the
    first ageing time) exaggerated by a stated factor, and the radial deviation against
    the polar angle."""
    picks = ages(ds)
    (x, y), against = reference_curve(ds, ("profile_x", "profile_y"))
    angle, radius = polar(x, y)
    order = np.argsort(angle)
    angle, radius = angle[order], radius[order]
    deviation = {k: radial_deviation((angle, radius), ds["profile_x"].isel(time=k).values,
                                     ds["profile_y"].isel(time=k).values) for k in picks}
    unit = np.radians(angle)
    fig, (plan, over) = plt.subplots(1, 2, figsize=(12, 5.6), gridspec_kw={"width_ratios": [1, 1.3]})
    exaggerated_outlines(plan, ds, (radius * np.cos(unit), radius * np.sin(unit)),
                         {k: (dr * np.cos(unit), dr * np.sin(unit)) for k, dr in deviation.items()},
                         picks, f"{name}: working profile", against)
    plan.plot([0], [0], "k+")
    length_drift_panel(over, ds, angle, deviation, "polar angle on the cam [deg]",
                       "radius − design radius" if against == "design" else f"radius − radius at {against}",
                       f"radial deviation of the working profile from {'the ' * (against == 'design')}{against}")
    over.axhline(0.0, color="k", lw=0.8, ls="--")
    return save(fig, outdir / "cam_profile.png")


def _drift(plt, ds, outdir, name, rows, save) -> Path:
    """cam_drift.png: displacement and acceleration minus their values at the first age,
    i.e. how far the follower drifts out of its as-made motion; after a wet-Tg stop, the
    ageing times computed and a line saying where and why the rest is not."""
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 5.5), sharex=True)
    angle = ds["cam_angle"].values
    t = days(ds)
    later = ages(ds)[1:]
    for ax, (var, ylabel, scale) in zip(axes, (rows[0], rows[2])):
        first = ds[var].isel(time=0).values
        for k in later:
            ax.plot(angle, (ds[var].isel(time=k).values - first) * scale, color=age_colour(ds, k),
                    label=age_label(t[k], t[-1]))
        ax.axhline(0.0, color="k", lw=0.8, ls="--")
        ax.set_ylabel(f"change in {ylabel}")
        ax.grid(alpha=0.3)
    stop = wet_tg_stop(ds)
    axes[0].set_title(f"{name}: drift from {age_label(t[0], t[-1])}" + (f"\n{stop}" if stop else ""),
                      fontsize=9 if stop else None)
    if not later:  # only the first age computed: nothing to compare with, say so
        for ax in axes:
            ax.set_yticks([])
            ax.text(0.5, 0.5, f"no ageing time after {age_label(t[0], t[-1])} is computed",
                    transform=ax.transAxes, ha="center", va="center", color="0.3")
    axes[-1].set_xlim(angle[0], angle[-1])
    legend_outside(axes[0])
    axes[-1].set_xlabel("cam angle [deg]")
    return save(fig, outdir / "cam_drift.png")


@returns_figures
def plot_dynamics(ds, outdir=None, save=None) -> Figures:
    """cam_dynamics.png (contact force, torque, stress vs cam angle at up to four ages) and
    cam_jump_stress.png (jump speed and peak Hertz stress vs ageing time).

    Parameters
    ----------
    ds : xarray.Dataset
        A cam result with ``contact_force``.
    outdir : str or pathlib.Path, optional
        The folder for both figures. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. The paths of cam_dynamics.png and cam_jump_stress.png.
    """
    plt = figure()
    name = ds.attrs.get("scene_name", "")
    written = [save(angle_panels(plt, ds, DYNAMICS, f"{name}: forces", drift=DYNAMICS[-1]),
                    outdir / "cam_dynamics.png")]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 5.5), sharex=True)
    t = days(ds)
    if "jump_speed" in ds:
        top.plot(t, ds["jump_speed"].values, "o-", label="aged")
        _design_line(top, ds, "jump_speed", 1.0)
    top.set_ylabel("jump speed [rpm]")
    top.grid(alpha=0.3)
    top.set_title(f"{name}: jump speed and peak contact stress")
    if "contact_stress" in ds:
        stress = ds["contact_stress"].values
        peak = np.array([np.nanmax(row) if np.isfinite(row).any() else np.nan for row in stress])
        bottom.plot(t, peak * 1e-6, "s-", color="C3", label="aged")
        _design_line(bottom, ds, "peak_contact_stress", 1e-6)
    bottom.set_ylabel("peak Hertz stress [MPa]")
    bottom.set_xlabel("ageing time [d]")
    bottom.grid(alpha=0.3)
    written.append(save(fig, outdir / "cam_jump_stress.png"))
    return written


def _design_line(ax, ds, name: str, scale: float) -> None:
    """The as-designed value (dry, reference temperature) as a dashed line, with a legend."""
    if design_name(name) in ds:
        ax.axhline(float(ds[design_name(name)]) * scale, color="k", ls="--", lw=1,
                   label="design (dry, reference temperature)")
    legend(ax, fontsize=8)
