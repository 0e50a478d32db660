"""Moisture fields (``moisture`` over time, part, cell; cell centres ``cell_x``,
``cell_y``, ``cell_z`` over part, cell, NaN where a part has fewer cells or
does not use an axis) at a few ageing times, one figure per part."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .common import legend, age_label, ages, days, figure, Figures, returns_figures

PANELS = 4


@returns_figures
def plot(ds, outdir=None, save=None) -> Figures:
    """One PNG per part with stored fields: up to four ageing times side by side.

    Parameters
    ----------
    ds : xarray.Dataset
        A result holding the ``moisture`` fields of its parts.
    outdir : str or pathlib.Path, optional
        One PNG per part goes here. None: the figures are only returned.
    save : callable
        Writes one figure: ``save(fig, path) -> path`` (default :func:`~fickcam.plotting.common.save_figure`).

    Returns
    -------
    Figures
        The figures, shown inline in a notebook; ``.paths``: the files written. One path per part with a stored field.
    """
    written = []
    for part in ds["part"].values:
        field = ds["moisture"].sel(part=part).values          # (time, cell)
        if not np.isfinite(field).any():
            continue
        coords = {axis: ds[f"cell_{axis}"].sel(part=part).values for axis in "xyz"
                  if f"cell_{axis}" in ds}
        written.append(_plot_part(ds, str(part), field, coords, Path(outdir), save))
    return written


def _used_axes(coords: dict[str, np.ndarray], valid: np.ndarray) -> list[str]:
    return [a for a, v in coords.items() if np.isfinite(v[valid]).all() and np.ptp(v[valid]) > 0]


def _mid_slice(coords, valid, axes) -> np.ndarray:
    """Cells of a 3-D part nearest its mid-thickness plane (z)."""
    z = coords["z"]
    middle = 0.5 * (np.nanmin(z[valid]) + np.nanmax(z[valid]))
    nearest = np.nanmin(np.abs(z[valid] - middle))
    return valid & (np.abs(z - middle) <= nearest * (1 + 1e-9) + 1e-15)


def _plot_part(ds, part, field, coords, outdir: Path, save) -> Path:
    plt = figure()
    t = days(ds)
    valid = np.isfinite(field).any(axis=0)
    axes = _used_axes(coords, valid)
    if len(axes) == 3:
        valid = _mid_slice(coords, valid, axes)
        axes = ["x", "y"]
    indices = ages(ds, PANELS)
    lo, hi = np.nanmin(field[:, valid]), np.nanmax(field[:, valid])
    if len(axes) <= 1:
        fig, ax = plt.subplots(figsize=(6, 4))
        axis = axes[0] if axes else "z"
        order = np.argsort(coords[axis][valid])
        for k in indices:
            ax.plot(coords[axis][valid][order] * 1e3, field[k, valid][order],
                    label=age_label(t[k], t[-1]))
        ax.set_xlabel(f"{axis} [mm]")
        ax.set_ylabel("moisture [wt %]")
        legend(ax, fontsize=8)
        ax.set_title(f"{part}: moisture through the thickness")
    else:
        fig, panels = plt.subplots(1, len(indices), figsize=(3.2 * len(indices), 3.4),
                                   squeeze=False)
        first, second = axes[:2]
        triangulation = cell_triangulation(coords[first][valid] * 1e3, coords[second][valid] * 1e3)
        for ax, k in zip(panels[0], indices):
            image = ax.tripcolor(triangulation, field[k, valid], shading="gouraud", vmin=lo, vmax=hi)
            ax.set_aspect("equal")
            ax.set_title(age_label(t[k], t[-1]), fontsize=9)
            ax.set_xlabel(f"{first} [mm]")
        panels[0][0].set_ylabel(f"{second} [mm]")
        fig.colorbar(image, ax=panels[0].tolist(), label="moisture [wt %]")
        fig.suptitle(f"{part}: moisture field")
    return save(fig, outdir / f"fields_{part}.png")


def cell_triangulation(x, y, stretch: float = 4.0):
    """Delaunay triangulation of the cell centres with the triangles that bridge
    holes and concave notches (an edge much longer than the local cell size)
    masked, so a bore is drawn empty rather than interpolated across.

    Parameters
    ----------
    x, y : numpy.ndarray
        The cell centres [any one length unit, the same for both].
    stretch : float
        A triangle is masked where its longest edge exceeds this many times the largest
        of its corners' shortest edges [-].

    Returns
    -------
    matplotlib.tri.Triangulation
        The triangulation, with its mask set.
    """
    # deferred: keeps matplotlib off the start-up path
    import matplotlib.tri as mtri

    triangulation = mtri.Triangulation(x, y)
    corners = triangulation.triangles
    edges = np.stack([np.hypot(x[corners[:, i]] - x[corners[:, j]], y[corners[:, i]] - y[corners[:, j]])
                      for i, j in ((0, 1), (1, 2), (2, 0))], axis=1)
    shortest_at = np.full(x.size, np.inf)
    for column in range(3):
        np.minimum.at(shortest_at, corners[:, column], edges.min(axis=1))
    local = shortest_at[corners].max(axis=1)
    triangulation.set_mask(edges.max(axis=1) > stretch * local)
    return triangulation

