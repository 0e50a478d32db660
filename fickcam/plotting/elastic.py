"""Elasticity (`fickcam plot --kind elastic`): the cam's contact deflection and stress over
the cam angle at several ages, the peak swelling stress and failure index of each part over
ageing, and the swelling stress field of each part at its worst time."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .common import legend, days, figure, Figures, returns_figures
from .cam import angle_panels
from .fields import cell_triangulation

CONTACT = (("elastic_deflection", "deflection [µm]", 1e6),
           ("elastic_stress_tensile", "largest tension [MPa]", 1e-6),
           ("elastic_stress_compressive", "largest compression [MPa]", 1e-6))


@returns_figures
def plot(ds, outdir=None, save=None) -> Figures:
    """elastic_contact.png (when the cam is elastic), swelling_stress.png and
    swelling_field_<part>.png (when swelling stresses are stored).

    Parameters
    ----------
    ds : xarray.Dataset
        A result with ``failure_index`` (an elastic scene).
    outdir : str or pathlib.Path, optional
        Folder of the elastic figures. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. Every figure drawn; none when nothing elastic is stored.
    """
    plt = figure()
    name = ds.attrs.get("scene_name", "")
    written = []
    if "elastic_deflection" in ds:
        fig = angle_panels(plt, ds, CONTACT, f"{name}: cam plate under the contact force")
        written.append(save(fig, outdir / "elastic_contact.png"))
    if "swelling_stress_tensile" in ds:
        written.append(_over_ageing(plt, ds, outdir, name, save))
    if "swelling_stress_field" in ds:
        written += [_field(plt, ds, part, outdir, name, save) for part in ds["part"].values
                    if np.isfinite(ds["swelling_stress_field"].sel(part=part).values).any()]
    return written


def _over_ageing(plt, ds, outdir: Path, name: str, save) -> Path:
    """Largest tension and compression, and the failure index, of each part over ageing."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 6), sharex=True)
    t = days(ds)
    for i, part in enumerate(ds["part"].values):
        tension = ds["swelling_stress_tensile"].sel(part=part).values
        if not np.isfinite(tension).any():
            continue
        compression = ds["swelling_stress_compressive"].sel(part=part).values
        top.plot(t, tension * 1e-6, "-o", color=f"C{i}", ms=3, label=f"{part} tension")
        top.plot(t, compression * 1e-6, "--s", color=f"C{i}", ms=3, label=f"{part} compression")
        bottom.plot(t, ds["failure_index"].sel(part=part).values, "-o", color=f"C{i}", ms=3,
                    label=str(part))
    top.axhline(0, color="k", lw=0.6)
    top.set_ylabel("principal stress [MPa]")
    top.set_title(f"{name}: hygrothermal (swelling) stress")
    bottom.set_ylabel("failure index (Tsai-Wu 1/R)")
    bottom.set_xlabel("ageing time [d]")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
        legend(ax, fontsize=8)
    return save(fig, outdir / "swelling_stress.png")


def _field(plt, ds, part, outdir: Path, name: str, save) -> Path:
    """The part's face stress at the time of its largest failure index (element centroids)."""
    row = ds.sel(part=part)
    stress = row["swelling_stress_field"].values
    keep = np.isfinite(stress)
    x, y = row["stress_point_x"].values[keep] * 1e3, row["stress_point_y"].values[keep] * 1e3
    index = row["failure_index"].values
    worst = row["swelling_stress_compressive"].values if not np.isfinite(index).any() else -index
    when = days(ds)[int(np.nanargmin(worst))]
    limit = float(np.max(np.abs(stress[keep]))) * 1e-6 or 1.0
    fig, ax = plt.subplots(figsize=(7.5, 6))
    shown = ax.tripcolor(cell_triangulation(x, y), stress[keep] * 1e-6, shading="gouraud",
                         cmap="RdBu_r", vmin=-limit, vmax=limit)
    fig.colorbar(shown, ax=ax, label="principal stress of larger magnitude [MPa]")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"{name}: {part}, stress at the faces\nt = {when:g} d (largest failure index)",
                 fontsize=10)
    return save(fig, outdir / f"swelling_field_{part}.png")
