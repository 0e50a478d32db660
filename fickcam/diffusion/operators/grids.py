"""FiPy meshes of the Sheet (Grid1D), the Disc or annulus (CylindricalGrid2D) and the
Bar (Grid3D), uniform or graded, assembled into ``Discretisation`` operators.

Every mesh is built in non-dimensional, anisotropy-scaled coordinates
x_i' = (x_i / L) sqrt(D_z / D_i) (``scaling``), so that the operator is the isotropic
Laplacian with unit coefficient; time is then tau* = tau D_z(T_ref) / L^2.
"""
from __future__ import annotations

import numpy as np

from ..problem.scaling import axis_scale
from .discretisation import Discretisation
from .fipy_backend import assemble, box_mesh, cylindrical_mesh, interval_mesh


def interval_overlap(lo: np.ndarray, hi: np.ndarray, a: float, b: float) -> np.ndarray:
    """Length of [lo, hi] ∩ [a, b], elementwise.

    Parameters
    ----------
    lo, hi : numpy.ndarray
        The intervals' ends [m].
    a, b : float
        The other interval's ends [m].

    Returns
    -------
    numpy.ndarray
        The overlaps' lengths [m], 0 where they do not meet.
    """
    return np.clip(np.minimum(hi, b) - np.maximum(lo, a), 0.0, None)


def normalised(weights: np.ndarray) -> np.ndarray:
    """The weights scaled to sum to 1 (all equal where they sum to 0).

    Parameters
    ----------
    weights : numpy.ndarray
        Non-negative weights (volumes [m^3] or scaled volumes [-]).

    Returns
    -------
    numpy.ndarray
        The weights over their sum [-].
    """
    total = weights.sum()
    return weights / total if total > 0 else np.full_like(weights, 1.0 / weights.size)


def sheet(thickness: float, cells: int, layer_depth: float) -> Discretisation:
    """Sheet through its thickness, Grid1D in z/h; layer: both faces (Crank §4.3).

    Parameters
    ----------
    thickness : float
        h [m].
    cells : int
        Uniform cells through the thickness [-].
    layer_depth : float
        The contact layer's depth from each face [m].

    Returns
    -------
    Discretisation
        The operator in z/h, cell centres ``z`` [m].
    """
    mesh = sheet_mesh(cells)
    volumes, stiffness, boundary = assemble(mesh)
    z_lo = np.arange(cells) / cells * thickness
    z_hi = z_lo + thickness / cells
    layer = thickness / cells - interval_overlap(z_lo, z_hi, layer_depth, thickness - layer_depth)
    return Discretisation(volumes, stiffness, boundary, normalised(volumes),
                          normalised(layer), {"z": 0.5 * (z_lo + z_hi)})


def sheet_mesh(cells: int):
    """FiPy Grid1D of a sheet in z/h, ``cells`` uniform cells.

    Parameters
    ----------
    cells : int
        The number of cells [-].

    Returns
    -------
    fipy.Grid1D
        The mesh of [0, 1] in z/h.
    """
    return interval_mesh(1.0 / cells, nx=cells)


def _uniform_widths(lengths, counts) -> tuple[np.ndarray, ...]:
    return tuple(np.full(int(n), float(size) / int(n)) for size, n in zip(lengths, counts))


def _bounds(widths: np.ndarray, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) edges along one axis of the cells with axis index ``index``."""
    edges = np.concatenate([[0.0], np.cumsum(widths)])
    return edges[index], edges[index + 1]


def grid_axis(widths: np.ndarray, scale: float, uniform: bool) -> dict:
    """FiPy grid arguments for one axis: a count and a spacing, or the array of widths.

    Parameters
    ----------
    widths : numpy.ndarray
        The cells' widths [m].
    scale : float
        Physical -> scaled coordinate factor [1/m].
    uniform : bool
        True: the widths are equal (a count and one spacing).

    Returns
    -------
    dict
        ``{"n": count or None, "d": scaled spacing or widths}`` [-].
    """
    return ({"n": widths.size, "d": float(widths[0]) * scale} if uniform
            else {"n": None, "d": widths * scale})


def disc(outer_radius: float, thickness: float, inner_radius: float, radial_cells: int,
         axial_cells: int, layer_depth: float, radial_d: float, axial_d: float,
         widths: tuple[np.ndarray, np.ndarray] | None = None) -> Discretisation:
    """Disc or annulus in (r, z), FiPy CylindricalGrid2D; layer: the outer rim.
    ``widths``: (radial from the bore or axis, axial) cell widths in m, graded
    (FiPy's non-uniform grid), instead of the uniform ``radial_cells`` x ``axial_cells``.

    Parameters
    ----------
    outer_radius, thickness, inner_radius : float
        The disc's radius, thickness and bore radius [m].
    radial_cells, axial_cells : int
        Uniform cells along r and z [-].
    layer_depth : float
        The rim layer's depth [m].
    radial_d, axial_d : float
        D0 along r and along z [m^2/s].
    widths : tuple of numpy.ndarray, optional
        Graded radial and axial widths [m].

    Returns
    -------
    Discretisation
        The operator in scaled (r, z), cell centres ``x`` (= r) and ``z`` [m].
    """
    mesh, scale_r, (dr, dz) = disc_mesh(outer_radius, thickness, inner_radius, radial_cells,
                                        axial_cells, radial_d, axial_d, widths)
    volumes, stiffness, boundary = assemble(mesh)
    r_c, z_c = (np.asarray(a) for a in mesh.cellCenters)
    r_lo, r_hi = (inner_radius + edge for edge in _bounds(dr, np.arange(volumes.size) % dr.size))
    band_lo = max(outer_radius - layer_depth, inner_radius)
    ring = np.clip(np.minimum(r_hi, outer_radius) ** 2 - np.maximum(r_lo, band_lo) ** 2, 0, None)
    ring *= dz[np.arange(volumes.size) // dr.size]
    return Discretisation(volumes, stiffness, boundary, normalised(volumes), normalised(ring),
                          {"x": r_c / scale_r, "z": z_c * thickness})


def disc_mesh(outer_radius, thickness, inner_radius, radial_cells, axial_cells, radial_d,
              axial_d, widths=None):
    """(FiPy CylindricalGrid2D in scaled (r, z), radial scale, (dr, dz) widths in m).

    Parameters
    ----------
    outer_radius, thickness, inner_radius : float
        Outer radius, thickness and inner (bore) radius [m].
    radial_cells, axial_cells : int
        Cell counts in r and z when uniform [-].
    radial_d, axial_d : float
        D0 along r and along z [m^2/s].
    widths : tuple of numpy.ndarray, optional
        Graded (dr, dz) [m]; None: uniform.

    Returns
    -------
    tuple
        The mesh, the radial scale sqrt(D_z / D_r) / h [1/m] and (dr, dz) [m].
    """
    scale_r = axis_scale(thickness, radial_d, axial_d)
    uniform = widths is None
    dr, dz = widths or _uniform_widths((outer_radius - inner_radius, thickness),
                                       (radial_cells, axial_cells))
    r_axis, z_axis = grid_axis(dr, scale_r, uniform), grid_axis(dz, 1.0 / thickness, uniform)
    mesh = cylindrical_mesh(r_axis, z_axis, inner_radius * scale_r)
    return mesh, scale_r, (dr, dz)


def bar(length: float, width: float, thickness: float, cells: tuple[int, int, int],
        layer_depth: float, d: tuple[float, float, float],
        widths: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> Discretisation:
    """Rectangular bar, FiPy Grid3D; layer: within ``layer_depth`` of any face.
    ``widths``: (x, y, z) cell widths in m, graded (FiPy's non-uniform grid),
    instead of the uniform ``cells``.

    Parameters
    ----------
    length, width, thickness : float
        The bar's sides along x, y, z [m].
    cells : tuple of int
        Uniform cells along x, y, z [-].
    layer_depth : float
        The contact layer's depth from every face [m].
    d : tuple of float
        D0 along x, y, z [m^2/s].
    widths : tuple of numpy.ndarray, optional
        Graded widths along x, y, z [m].

    Returns
    -------
    Discretisation
        The operator in scaled coordinates, cell centres ``x``, ``y``, ``z`` [m].
    """
    size = np.array([length, width, thickness])
    scale = np.array([axis_scale(thickness, d[i], d[2]) for i in range(3)])
    uniform = widths is None
    widths = widths or _uniform_widths(size, cells)
    axes = [grid_axis(w, s, uniform) for w, s in zip(widths, scale)]
    mesh = box_mesh(axes)
    volumes, stiffness, boundary = assemble(mesh)
    centres = [np.asarray(a) / s for a, s in zip(mesh.cellCenters, scale)]
    return Discretisation(volumes, stiffness, boundary, normalised(volumes),
                          normalised(near_faces(widths, size, layer_depth)),
                          dict(zip("xyz", centres)))


def near_faces(widths, size, layer_depth: float) -> np.ndarray:
    """Volume (m^3) of each cell of a Grid3D (x fastest) of these axis widths (m) within
    ``layer_depth`` of a face of the box ``size`` (cell volume minus its inner core).

    Parameters
    ----------
    widths : sequence of numpy.ndarray
        The cells' widths along x, y, z [m].
    size : numpy.ndarray
        The box's sides [m].
    layer_depth : float
        The layer's depth [m].

    Returns
    -------
    numpy.ndarray
        Each cell's volume within the layer [m^3].
    """
    count = int(np.prod([w.size for w in widths]))
    index = np.unravel_index(np.arange(count), tuple(w.size for w in widths[::-1]))[::-1]
    whole, inner = np.ones(count), np.ones(count)
    for w, i, length in zip(widths, index, size):
        lo, hi = _bounds(w, i)
        whole *= hi - lo
        inner *= interval_overlap(lo, hi, layer_depth, length - layer_depth)
    return whole - inner

