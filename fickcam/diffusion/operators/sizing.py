"""Cells of the direct finite-volume models (slab, axisymmetric, solid) from the accuracy.

Uniform: spacing h* = sqrt(0.5 a tau*_lo / (S n)) on each of the n axes, S =
``error_model.space_error(tau*_lo)`` (err ~ S (h/L)^2 / tau*_lo per axis, measured on the
sheet against Crank eq. 4.18).

Graded (``grading``): cells w0 wide at the exposed faces growing by (1 + g) per cell.
Each graded axis adds S w0^2 / tau*_lo (the boundary layer after a change
sees only the finest cells, Crank 1975 eq. 2.45) and GROWTH_ERROR g^2
(``error_model.GROWTH_ERROR``); half the spatial budget goes to each. The graded
layout replaces the uniform one when it needs fewer cells. A prismatic part
(CamPlate, LinkBar) is always graded: rows graded from its outline in the plane
(``triangles.triangulate`` with a growth), the same widths through the thickness, on
Delaunay-admissible cells (``admissible``). Above the model's cell cap the finest width
grows (and with it the estimate) until the cells fit. The cap counts the cells of the
linear system (``unknowns``): a part solved cut at its mirror planes (``symmetry_cuts``: a
Bar's octant, a prism's half thickness) is counted on that cut part, ``halved`` naming
the axes cut in two.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..accuracy.error_model import GROWTH_ERROR, MIN_CELLS_PER_AXIS
from ..planform.admissible import admissible
from ..planform.triangles import triangulate
from ..problem.cache import RunCache, run_cache
from ..problem.scaling import axis_scale, stretch_of
from .grading import MAX_GROWTH, graded_widths, growth_rate

GRADED_GRIDS = ("disc", "box")  # the grids (``Geometry.grid``) whose cells may be graded
CAP_STEP = 1.15  # the finest width grows by this factor until the cells fit the cap


@dataclass(frozen=True)
class Layout:
    """Cells per axis (a prism: planform cells, z cells), and the grading if any.

    Parameters
    ----------
    cells : tuple of int
        Cells per axis [-] of the whole part.
    space_error : float
        The spatial error estimate [-], relative to the swing.
    finest : float
        The finest cells' width in scaled units [-]; 0: uniform.
    growth : float
        The widths' growth from cell to cell [-].
    note : str
        A few words for the plan's reason.
    halved : tuple of int
        The axes the solve cuts at their mirror plane.
    """

    cells: tuple[int, ...]
    space_error: float
    finest: float = 0.0   # scaled width of the finest cells (0: uniform)
    growth: float = 0.0
    note: str = ""
    halved: tuple[int, ...] = ()  # axes cut at their mirror plane by the solve

    @property
    def total(self) -> int:
        return int(math.prod(self.cells))

    @property
    def solved(self) -> int:
        """Cells of the linear system the solve assembles (``unknowns``)."""
        return unknowns(self.cells, self.halved)


def unknowns(cells, halved=()) -> int:
    """Cells of the linear system on ``cells`` per axis: the axes in ``halved`` cut at
    their mirror plane (``symmetry_cuts``: half of the count rounded up to even).

    Parameters
    ----------
    cells : sequence of int
        Cells per axis of the whole part [-].
    halved : sequence of int
        The axes cut in two.

    Returns
    -------
    int
        The cells the solve assembles [-].
    """
    return int(math.prod(-(-c // 2) if axis in halved else c for axis, c in enumerate(cells)))


def extents(geometry, d) -> tuple[float, ...]:
    """Scaled extents of the numerical model's axes: each physical extent times
    sqrt(D_z / D_i) / L (``scaling``).

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part, its lengths in [m].
    d : sequence of float
        D0 along x, y, z [m^2/s].

    Returns
    -------
    tuple of float
        The scaled extent of each axis [-] (the thickness: 1).
    """
    h = float(geometry.thickness)
    sizes = geometry.in_plane_sizes()
    return tuple(size * axis_scale(h, d[i], d[2]) for i, size in enumerate(sizes)) + (1.0,)


def exposed_ends(geometry) -> tuple[str, ...]:
    """Which ends of each axis are exposed: a Disc's radius only at the rim unless it has
    a bore; every face of a Bar; the faces of a prism (z).

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part.

    Returns
    -------
    tuple of str
        ``both``, ``low`` or ``high`` per axis (as ``grading.graded_widths`` takes).
    """
    return geometry.exposed_ends()


def uniform(extents, accuracy: float, t_lo: float, cap: int, space_error: float,
            halved=()) -> Layout:
    """Equal cells on every axis (see the module docstring), shrunk to the cap; a
    ``halved`` axis has an even count (its mirror plane a face) and half of it solved.

    Parameters
    ----------
    extents : sequence of float
        The axes' scaled extents [-].
    accuracy : float
        The relative accuracy asked for [-]; the space error takes half of it.
    t_lo : float
        The earliest output's scaled time tau* [-].
    cap : int
        The most cells [-] of the linear system.
    space_error : float
        The error model's factor S [-] (``error_model.space_error``).
    halved : sequence of int
        Axes cut at their mirror plane.

    Returns
    -------
    Layout
        The uniform cells and their error estimate [-].
    """
    dimensions = len(extents)
    spacing = math.sqrt(0.5 * accuracy * t_lo / (space_error * dimensions))
    parts = [2 if axis in halved else 1 for axis in range(dimensions)]
    solved = [max(-(-MIN_CELLS_PER_AXIS // p), math.ceil(e / spacing / p))
              for e, p in zip(extents, parts)]
    total = math.prod(solved)
    if total > cap:
        shrink = (cap / total) ** (1 / dimensions)
        solved = [max(-(-MIN_CELLS_PER_AXIS // p), int(n * shrink)) for n, p in zip(solved, parts)]
    cells = tuple(n * p for n, p in zip(solved, parts))
    h_eff = max(e / c for e, c in zip(extents, cells))
    return Layout(cells, space_error * h_eff ** 2 / t_lo * dimensions,
                  note=f"uniform dx*={spacing:.2g}", halved=tuple(halved))


def graded_error(finest: float, growth: float, t_lo: float, axes: int,
                 space_error: float) -> float:
    """The spatial error of a graded layout: n (S w0^2 / tau*_lo + GROWTH_ERROR g^2).

    Parameters
    ----------
    finest : float
        w0, the finest scaled width [-].
    growth : float
        g [-].
    t_lo : float
        The earliest output's scaled time [-].
    axes : int
        The graded axes n [-].
    space_error : float
        S [-].

    Returns
    -------
    float
        The relative error estimate [-].
    """
    return axes * (space_error * finest ** 2 / t_lo + GROWTH_ERROR * growth ** 2)


def finest_and_growth(accuracy: float, t_lo: float, axes: int, space_error: float):
    """(w0, g) spending half the spatial budget 0.5 a on each error term.

    Parameters
    ----------
    accuracy : float
        a, the relative accuracy [-].
    t_lo : float
        The earliest output's scaled time [-].
    axes : int
        The graded axes [-].
    space_error : float
        S [-].

    Returns
    -------
    tuple of float
        The finest scaled width w0 [-] and the growth g [-].
    """
    finest = math.sqrt(0.25 * accuracy * t_lo / (space_error * axes))
    return finest, growth_rate(0.25 * accuracy / axes)


def axis_widths(extents, ends, finest: float, growth: float) -> tuple[np.ndarray, ...]:
    """Scaled cell widths of each axis, graded towards its exposed ends.

    Parameters
    ----------
    extents : sequence of float
        The axes' scaled extents [-].
    ends : sequence of str
        Each axis' exposed ends (``exposed_ends``).
    finest : float
        w0 [-], held to half of each extent.
    growth : float
        g [-].

    Returns
    -------
    tuple of numpy.ndarray
        The scaled widths of each axis [-].
    """
    return tuple(graded_widths(e, min(finest, 0.5 * e), growth, end)
                 for e, end in zip(extents, ends))


def physical_widths(geometry, extents, d, finest: float, growth: float) -> tuple[np.ndarray, ...]:
    """Graded cell widths (m) of a Disc (r, z) or Bar (x, y, z): the scaled widths times
    L sqrt(D_i / D_z) (Crank 1975 eq. 2.13).

    Parameters
    ----------
    geometry : Disc or Bar
        The part, its lengths in [m].
    extents : sequence of float
        The scaled extents of its axes [-] (``extents``).
    d : sequence of float
        D0 along x, y, z [m^2/s].
    finest : float
        w0 [-].
    growth : float
        g [-].

    Returns
    -------
    tuple of numpy.ndarray
        The widths of each axis [m].
    """
    axes = (*range(len(geometry.in_plane_sizes())), 2)
    scaled = axis_widths(extents, exposed_ends(geometry), finest, growth)
    return tuple(w / axis_scale(geometry.thickness, d[i], d[2]) for w, i in zip(scaled, axes))


def graded(extents, ends, accuracy: float, t_lo: float, cap: int, space_error: float,
           count=None, halved=()) -> Layout:
    """Graded cells (see the module docstring); ``count(finest, growth)`` gives the cells
    per axis (default: the graded widths of ``extents``), ``halved`` the axes the solve
    cuts at their mirror plane (``unknowns``: what the cap counts).

    Parameters
    ----------
    extents : sequence of float
        Scaled extents of the axes [-].
    ends : sequence of str
        Each axis' exposed ends.
    accuracy : float
        Relative accuracy [-]; half of it is the spatial budget.
    t_lo : float
        Earliest output, scaled time tau* [-].
    cap : int
        Most cells [-] of the linear system; w0 and g coarsen until it holds.
    space_error : float
        The error model's factor S [-].
    count : callable, optional
        ``count(finest, growth)`` -> cells per axis.
    halved : sequence of int
        Axes cut at their mirror plane.

    Returns
    -------
    Layout
        The graded cells, w0, g and the error estimate [-].
    """
    count = count or (lambda w0, g: tuple(w.size for w in axis_widths(extents, ends, w0, g)))
    axes = len(extents)
    finest, growth = finest_and_growth(accuracy, t_lo, axes, space_error)
    cells = count(finest, growth)
    while unknowns(cells, halved) > cap and finest < 0.5 * min(extents):
        finest *= CAP_STEP
        growth = min(MAX_GROWTH, growth * CAP_STEP)
        cells = count(finest, growth)
    return Layout(tuple(cells), graded_error(finest, growth, t_lo, axes, space_error),
                  finest, growth, f"graded w0*={finest:.2g} growth {growth:.2g}", tuple(halved))


def choose(geometry, extents, accuracy: float, t_lo: float, cap: int,
           space_error: float, halved=()) -> Layout:
    """The layout of a Disc or Bar: graded when that needs fewer cells (of the linear
    system: ``halved`` axes cut at their mirror plane), else uniform; when either is shrunk
    to the cap (its error above the accuracy), the one of smaller error (a capped uniform
    grid has fewer cells but, on a drying D(c) link bar at 3e-3, 5x the error of the
    capped graded one: benchmarks/dc_bar.py link).

    Parameters
    ----------
    geometry : Sheet, Disc or Bar
        The part [m] (only a Disc or Bar may be graded).
    extents : sequence of float
        Its axes' scaled extents [-].
    accuracy : float
        The relative accuracy [-].
    t_lo : float
        The earliest output's tau* [-].
    cap : int
        The cell cap [-].
    space_error : float
        S [-].
    halved : sequence of int
        Mirror-cut axes.

    Returns
    -------
    Layout
        The graded or the uniform layout.
    """
    flat = uniform(extents, accuracy, t_lo, cap, space_error, halved)
    if geometry.grid not in GRADED_GRIDS:
        return flat
    steep = graded(extents, exposed_ends(geometry), accuracy, t_lo, cap, space_error,
                   halved=halved)
    if max(steep.space_error, flat.space_error) > accuracy:
        return steep if steep.space_error < flat.space_error else flat
    better = steep.solved < flat.solved or (steep.solved == flat.solved
                                            and steep.space_error < flat.space_error)
    return steep if better else flat


# ----------------------------------------------------------------- prisms


def planform_cells(part, finest: float, growth: float, stretch: tuple[float, float],
                   cache: RunCache | None = None):
    """Admissible cells (``admissible.Tessellation``) of a CamPlate or LinkBar planform, rows
    graded from the outline: ``finest`` and the spacing in stretched (scaled) units; made
    once per run (``cache``; None: a fresh one): plan and solve share them.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The part, its lengths in [m].
    finest : float
        The first row's spacing in thicknesses [-].
    growth : float
        The rows' growth [-].
    stretch : tuple of float
        sqrt(D_z / D_x), sqrt(D_z / D_y) [-].
    cache : RunCache, optional
        The run's cache.

    Returns
    -------
    Tessellation
        The Delaunay-admissible cells of the planform.
    """
    def build():
        mesh = triangulate(part, finest * part.thickness, growth=growth, stretch=stretch)
        return admissible(mesh, part, stretch)
    return run_cache(cache).get(("planform cells", part, finest, growth, stretch), build)


def prism_widths(finest: float, growth: float) -> np.ndarray:
    """Scaled z widths of a prism, graded towards both faces.

    Parameters
    ----------
    finest : float
        w0 in thicknesses [-], held to half the thickness.
    growth : float
        g [-].

    Returns
    -------
    numpy.ndarray
        The widths as fractions of the thickness [-], summing to 1.
    """
    return graded_widths(1.0, min(finest, 0.5), growth, "both")


def prism_layout(geometry, d, accuracy: float, t_lo: float, cap: int,
                 space_error: float, halved=(), cache: RunCache | None = None) -> Layout:
    """Graded prism cells: planform rows and z widths with the same w0 and g (three
    graded directions in the error model); ``halved`` (1,): the solve keeps half the
    thickness (``symmetry_cuts``), which the cap counts.

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The part, lengths in [m].
    d : sequence of float
        D0 along x, y, z [m^2/s].
    accuracy : float
        The relative accuracy [-].
    t_lo : float
        Scaled time tau* of the earliest output [-].
    cap : int
        Most cells of the solve [-].
    space_error : float
        S [-].
    halved : sequence of int
        (1,) where the solve keeps half the thickness.
    cache : RunCache, optional
        The run's cache (the planform's cells).

    Returns
    -------
    Layout
        (planform cells, z cells), w0, g and the error estimate [-].

    Raises
    ------
    TypeError
        For a part that is not a CamPlate or LinkBar.
    """
    if not geometry.planform:
        raise TypeError(f"no prism layout for {type(geometry).__name__}")
    stretch = stretch_of(d)
    layout = graded((1.0, 1.0, 1.0), ("both",) * 3, accuracy, t_lo, cap, space_error,
                    lambda w0, g: estimated_prism_cells(geometry, w0, g, stretch), halved)
    finest = min(layout.finest, widest_row(geometry, stretch))
    planform = planform_cells(geometry, finest, layout.growth, stretch, cache)
    cells = (planform.cells, prism_widths(finest, layout.growth).size)
    return Layout(cells, layout.space_error, finest, layout.growth, layout.note, layout.halved)


def widest_row(part, stretch) -> float:
    """The widest first row of a planform (scaled): half its smallest scaled extent, as
    ``prism_widths`` holds the z widths to half the thickness. A late first output makes the
    error model's w0 grow without bound (w0 ~ sqrt(accuracy t_lo)); rows wider than the
    planform leave the outline mesher no points (seen: the 4 x 3 x 2 mm plate, k = 5, first
    output 0.1 h^2/D: w0 = 6.4e4). Narrower rows only lower the error, so the estimate holds.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The part, lengths in [m].
    stretch : tuple of float
        The in-plane stretch sqrt(D_z / D_i) [-].

    Returns
    -------
    float
        The widest first row in thicknesses [-].
    """
    extent = np.asarray(part.extent()) * np.asarray(stretch) / part.thickness
    return 0.5 * float(extent.min())


def estimated_prism_cells(part, finest: float, growth: float, stretch) -> tuple[int, int]:
    """Cheap count for the cap: rows of spacing s(d) ~ w0 + g d at depth d under an
    outline of scaled perimeter P make about (2 / (sqrt(3)/2)) P integral dd / s^2
    triangles (two per rhombus of an equilateral lattice), up to the half width D:
    integral = D / (w0 (w0 + g D)).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The part, lengths in [m].
    finest : float
        w0 in thicknesses [-].
    growth : float
        g [-].
    stretch : tuple of float
        The in-plane stretch [-].

    Returns
    -------
    tuple of int
        The estimated planform triangles and the z cells [-].
    """
    extent = np.asarray(part.extent()) * np.asarray(stretch) / part.thickness
    perimeter, depth = 2.0 * float(extent.sum()), 0.5 * float(extent.min())
    rows = depth / (finest * (finest + growth * depth))
    planar = max(1, int(2.0 / (math.sqrt(3) / 2) * perimeter * rows))
    return planar, prism_widths(finest, growth).size
