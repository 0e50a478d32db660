"""Meshes of the ``solid`` parts cut at their planes of mirror symmetry, for the
concentration-dependent model (``concentration_dependent``), whose cost grows with the cells.

Every face of a Bar, CamPlate or LinkBar holds the same surface value and the initial
moisture is uniform, so the moisture field is mirror-symmetric about the mid-plane
z = h/2 of a prism and about the three mid-planes of a Bar: no flux crosses them
(Crank 1975 §4.3.1, the sheet's centre plane as an impermeable wall). The model keeps
one side: the half thickness of a prism (its planform has no symmetry in general), one
octant of a Bar, cut at the middle of the same graded widths the full mesh would have
(``grading.graded_widths`` is symmetric), so it is the full mesh's solution exactly, on
1/2 (prism) or 1/8 (Bar) of the cells. The means and the contact layer are volume
averages, the same over a mirror half as over the whole.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

import numpy as np

from ..planform.admissible import band_share
from ..problem.cache import RunCache
from ..problem.geometry import Bar
from ..problem.scaling import axis_scale, stretch_of
from . import sizing
from .discretisation import Discretisation
from .fipy_backend import assemble, box_mesh
from .grids import grid_axis, near_faces, normalised
from .prisms import prism


def halved_axes(geometry) -> tuple[int, ...]:
    """The axes of the layout's cells (``sizing.Layout``) that ``symmetry_cuts`` cuts in two:
    x, y, z of a Bar (octant), z of a CamPlate or LinkBar (cells: planform, z).

    Parameters
    ----------
    geometry : Bar, CamPlate or LinkBar
        The part, its lengths in [m].

    Returns
    -------
    tuple of int
        The layout axes cut: (0, 1, 2) for a Bar, (1,) for a prism.

    Raises
    ------
    TypeError
        For any other part.
    """
    if not geometry.mirror_axes:
        raise TypeError(f"no mirrored mesh for {type(geometry).__name__}")
    return geometry.mirror_axes


def half(widths: np.ndarray) -> np.ndarray:
    """The first half of a symmetric ``both``-graded axis (an even count of cells).

    Parameters
    ----------
    widths : numpy.ndarray
        The axis' cell widths [m] (or scaled [-]).

    Returns
    -------
    numpy.ndarray
        The widths up to the mid-plane, in the same unit [m].

    Raises
    ------
    ValueError
        When the count of cells is odd.
    """
    if widths.size % 2:
        raise ValueError("a mirrored axis needs an even number of cells")
    return widths[:widths.size // 2]


def mirrored(geometry, d, cells, finest: float, growth: float,
             layer_depth: float, cache: RunCache | None = None) -> Discretisation:
    """The FiPy operator of the mirror part of a Bar (octant) or a CamPlate or LinkBar
    (half thickness), graded from ``finest`` by ``growth`` (scaled units, ``sizing``), or
    a Bar on uniform ``cells`` (rounded up to even counts) when ``finest`` is 0.

    Parameters
    ----------
    geometry : Bar, CamPlate or LinkBar
        The part, its lengths in [m].
    d : sequence of float
        D0 along x, y, z [m^2/s].
    cells : tuple of int
        Uniform cells per axis of the whole Bar [-] (read when ``finest`` is 0).
    finest : float
        The finest width in scaled units [-]; 0: uniform.
    growth : float
        The widths' growth from cell to cell [-].
    layer_depth : float
        The contact layer's depth [m].
    cache : RunCache, optional
        The run's cache (a planform's cells); None: a fresh one.

    Returns
    -------
    Discretisation
        The operator of the mirror part, cell centres [m].

    Raises
    ------
    TypeError
        For a part that is not a Bar, CamPlate or LinkBar.

    References
    ----------
    Crank (1975) §4.3.1 (see the module docstring).
    """
    if geometry.planform:
        tess = sizing.planform_cells(geometry, finest, growth, stretch_of(d), cache)
        z = half(sizing.prism_widths(finest, growth)) * geometry.thickness
        return prism(tess, geometry.thickness, z, band_share(tess, layer_depth), d,
                     mid_plane=True)
    if geometry.grid == "box":
        return octant(geometry, d, cells, finest, growth, layer_depth)
    raise TypeError(f"no mirrored mesh for {type(geometry).__name__}")


def octant(bar: Bar, d, cells, finest: float, growth: float,
           layer_depth: float) -> Discretisation:
    """The octant x, y, z <= half of a Bar on FiPy's Grid3D: the faces x = 0, y = 0, z = 0
    exposed, the three mid-planes insulated (FiPy's default for unconstrained faces).
    Layer: within ``layer_depth`` of an exposed face (the whole bar's layer, by symmetry).

    Parameters
    ----------
    bar : Bar
        The bar, its sides in [m].
    d : sequence of float
        The bar's pre-exponential diffusivities per axis [m^2/s] (they scale the grid).
    cells : tuple of int
        Without grading: the whole bar's cells along x, y, z [-], made even.
    finest : float
        w0, the graded cells' finest scaled width [-] (0 for a uniform grid).
    growth : float
        g, each width over its neighbour's minus one [-].
    layer_depth : float
        The contact layer's depth [m].

    Returns
    -------
    Discretisation
        The octant's operator, cell centres ``x``, ``y``, ``z`` [m].
    """
    size = np.array([bar.length, bar.width, bar.thickness])
    full = (sizing.physical_widths(bar, sizing.extents(bar, d), d, finest, growth) if finest > 0
            else tuple(np.full(n, s / n) for s, n in zip(size, (2 * -(-c // 2) for c in cells))))
    widths = tuple(half(w) for w in full)
    scale = np.array([axis_scale(bar.thickness, d[i], d[2]) for i in range(3)])
    axes = [grid_axis(w, s, uniform=False) for w, s in zip(widths, scale)]
    mesh = box_mesh(axes)
    centres = np.asarray(mesh.faceCenters)
    exposed = np.asarray(mesh.exteriorFaces, bool) & np.any(np.isclose(centres, 0.0, atol=1e-12),
                                                           axis=0)
    volumes, stiffness, boundary = assemble(mesh, exposed=exposed)
    cells = [np.asarray(a) / s for a, s in zip(mesh.cellCenters, scale)]
    return Discretisation(volumes, stiffness, boundary, normalised(volumes),
                          normalised(near_faces(widths, size, layer_depth)),
                          dict(zip("xyz", cells)))
