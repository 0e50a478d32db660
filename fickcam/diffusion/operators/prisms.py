"""A planform's Delaunay-admissible cells (``admissible.Tessellation``) as FiPy meshes with given
cell points: the planform alone (a ``Mesh2D``, the in-plane operator of the plane model) or
extruded through the thickness into prisms (a generic 3-D ``Mesh``)."""
from __future__ import annotations

import numpy as np

from ..planform.admissible import cell_loops
from ..planform.polygon import unique_edges
from ..problem.scaling import axis_scale
from .discretisation import Discretisation
from .fipy_backend import assemble, centred_mesh
from .grids import normalised


def prism(tess, thickness: float, z_widths: np.ndarray, layer_share: np.ndarray,
          d: tuple[float, float, float], mid_plane: bool = False) -> Discretisation:
    """A planform's admissible cells (``admissible.Tessellation``) extruded through the
    thickness into FiPy prisms with the given z widths (m, from a face; summing to
    ``thickness``, or to half of it with ``mid_plane``: the top is then the mid-plane,
    a mirror, insulated; so are the tessellation's mirror lines).

    The mesh is FiPy's generic ``Mesh``: polygon faces top and bottom (triangles,
    or the cyclic polygons of merged cocircular triangles), quadrilateral faces on
    the sides, shorter vertex lists padded with -1 (masked, as FiPy's Gmsh reader
    does for mixed elements). The cell point is the planform cell's circumcentre at
    mid-layer, so every line between neighbouring cell points is normal to their
    face (see ``admissible``) and FiPy's two-point flux is consistent. Layer: cells
    weighted by ``layer_share`` (fraction of the planform cell within the contact
    band), over the whole thickness, as in the plane model.

    Parameters
    ----------
    tess : Tessellation
        The planform's admissible cells (``admissible.Tessellation``), points [m].
    thickness : float
        The part's thickness [m].
    z_widths : numpy.ndarray
        The layers' widths from a face [m].
    layer_share : numpy.ndarray
        Each planform cell's share within the contact band [-].
    d : tuple of float
        D0 along x, y, z [m^2/s].
    mid_plane : bool
        True: the widths cover half the thickness and the top is an insulated mirror.

    Returns
    -------
    Discretisation
        The prisms' operator, cell centres ``x``, ``y``, ``z`` [m].

    Raises
    ------
    ValueError
        When the tessellation was stretched for another ratio of in-plane diffusivities.
    """
    scale = np.array([axis_scale(thickness, d[i], d[2]) for i in range(2)]) / tess.stretch
    if not np.isclose(scale[0], scale[1], rtol=1e-9):
        raise ValueError("the tessellation was stretched for another diffusivity ratio")
    z_nodes = np.concatenate([[0.0], np.cumsum(z_widths)]) / thickness
    mesh, insulated = prism_mesh(tess, float(scale[0]), z_nodes, mid_plane)
    exterior = np.asarray(mesh.exteriorFaces, bool)
    volumes, stiffness, boundary = assemble(mesh, exposed=exterior & ~insulated)
    layers = z_widths.size
    planar = tess.physical(tess.centres)
    coordinates = {"x": np.tile(planar[:, 0], layers), "y": np.tile(planar[:, 1], layers),
                   "z": np.repeat(0.5 * (z_nodes[1:] + z_nodes[:-1]) * thickness, tess.cells)}
    layer = volumes * np.tile(layer_share, layers)
    return Discretisation(volumes, stiffness, boundary, normalised(volumes), normalised(layer),
                          coordinates)


def planar(tess, scale: float, layer_share: np.ndarray) -> Discretisation:
    """The in-plane operator of a planform's admissible cells (``admissible.Tessellation``): a
    FiPy ``Mesh2D`` whose faces are the cells' sides and whose cell points are the
    circumcentres, so the line between neighbouring cell points is normal to their side
    and FiPy's two-point flux is consistent (Eymard, Gallouet & Herbin 2000, Definition
    9.1; see ``admissible``). Coordinates: stretched planform x ``scale`` (scaled units).
    Every outline side holds the surface value; the mirror lines are insulated.
    Layer: cells weighted by ``layer_share`` (fraction within the contact band).

    Parameters
    ----------
    tess : Tessellation
        The planform's admissible cells (``admissible.Tessellation``), points [m].
    scale : float
        Stretched planform -> scaled coordinate factor [1/m].
    layer_share : numpy.ndarray
        Each cell's share within the contact band [-].

    Returns
    -------
    Discretisation
        The planar operator, cell centres ``x``, ``y`` [m].

    References
    ----------
    Eymard, Gallouet & Herbin (2000), Definition 9.1 (see ``fipy_backend``).
    """
    sides, cell_sides = sides_of_cells(tess)
    cell_faces = _padded(cell_sides, max(s.size for s in cell_sides))
    mesh = centred_mesh(2, tess.points.T * scale, sides.T, cell_faces, tess.centres.T * scale)
    exposed = np.asarray(mesh.exteriorFaces, bool) & ~_on_mirror(tess, sides)
    volumes, stiffness, boundary = assemble(mesh, exposed=exposed)
    planar_centres = tess.physical(tess.centres)
    return Discretisation(volumes, stiffness, boundary, normalised(volumes),
                          normalised(volumes * layer_share),
                          {"x": planar_centres[:, 0], "y": planar_centres[:, 1]})


def _padded(rows: list[np.ndarray], width: int) -> np.ndarray:
    """Ragged integer rows as a (width, n) array padded with -1 (FiPy's masked entries)."""
    out = np.full((width, len(rows)), -1, dtype=np.int64)
    for k, row in enumerate(rows):
        out[:row.size, k] = row
    return out


def sides_of_cells(tess) -> tuple[np.ndarray, list[np.ndarray]]:
    """Planform edges that bound a cell (between two cells or on the outline), and the
    indices of those edges around each cell.

    Parameters
    ----------
    tess : Tessellation
        The planform's cells, whose sides are wanted (points [m]).

    Returns
    -------
    sides : numpy.ndarray
        The bounding edges' vertex pairs, shape (s, 2).
    cell_sides : list of numpy.ndarray
        Indices into ``sides`` around each cell.
    """
    edges, side_edge = unique_edges(tess.triangles)
    pairs = np.unique(np.column_stack([side_edge.ravel(), np.repeat(tess.cell_of, 3)]), axis=0)
    cells_at = np.bincount(pairs[:, 0], minlength=len(edges))        # distinct cells at an edge
    triangles_at = np.bincount(side_edge.ravel(), minlength=len(edges))
    inside_one_cell = (cells_at == 1) & (triangles_at == 2)
    pairs = pairs[~inside_one_cell[pairs[:, 0]]]
    kept, face_of_pair = np.unique(pairs[:, 0], return_inverse=True)
    order = np.argsort(pairs[:, 1], kind="stable")
    split = np.cumsum(np.bincount(pairs[:, 1], minlength=tess.cells))[:-1]
    return edges[kept], np.split(face_of_pair[order], split)


def prism_mesh(tess, scale: float, z_nodes: np.ndarray, mid_plane: bool):
    """FiPy ``Mesh`` of the prisms (coordinates: stretched planform x ``scale``, z / L)
    and the mask of its insulated faces (mirror lines; the top with ``mid_plane``).
    Numbering: vertex p of level k is k n + p; the planform cells' faces at level k
    come first (k c + cell), then the side faces of layer k (k s + side); cell
    c of layer k is k c + cell.

    Parameters
    ----------
    tess : Tessellation
        The cells to extrude (stretched points [m]).
    scale : float
        The factor [1/m] taking stretched planform points to the mesh's scaled ones.
    z_nodes : numpy.ndarray
        The layers' boundaries as fractions of the thickness, z / L [-].
    mid_plane : bool
        True: the top is the insulated mid-plane.

    Returns
    -------
    mesh : fipy.meshes.mesh.Mesh
        The prisms in scaled coordinates [-].
    insulated : numpy.ndarray
        Bool mask of the insulated faces.
    """
    n, cells, layers = len(tess.points), tess.cells, z_nodes.size - 1
    sides, cell_sides = sides_of_cells(tess)
    vertices = np.vstack([np.tile(tess.points.T * scale, layers + 1),
                          np.repeat(z_nodes, n)[None, :]])
    faces = _prism_faces(cell_loops(tess), sides, n, layers)
    first_side = cells * (layers + 1)
    around = _padded(cell_sides, max(s.size for s in cell_sides))
    cell_faces = np.concatenate([
        np.vstack([np.arange(cells) + k * cells, np.arange(cells) + (k + 1) * cells,
                   np.where(around >= 0, around + first_side + k * len(sides), -1)])
        for k in range(layers)], axis=1)
    centre_z = np.repeat(0.5 * (z_nodes[1:] + z_nodes[:-1]), cells)
    cell_centres = np.vstack([np.tile(tess.centres.T * scale, layers), centre_z[None, :]])
    face_centres = np.vstack([np.tile(tess.centres.T * scale, layers + 1),
                              np.repeat(z_nodes, cells)[None, :]])
    mesh = centred_mesh(3, vertices, faces, cell_faces, cell_centres, np.arange(first_side),
                        face_centres)
    insulated = np.zeros(faces.shape[1], bool)
    insulated[first_side:] = np.tile(_on_mirror(tess, sides), layers)
    if mid_plane:
        insulated[layers * cells:first_side] = True
    return mesh, insulated


def _prism_faces(loops: list[np.ndarray], sides: np.ndarray, n: int, layers: int) -> np.ndarray:
    """Vertex ids (padded with -1) of the horizontal faces, level by level, then of the
    quadrilateral side faces (a_k, b_k, b_k+1, a_k+1), layer by layer."""
    corners = max(4, max(loop.size for loop in loops))
    flat = _padded(loops, corners)
    horizontal = np.concatenate([np.where(flat >= 0, flat + k * n, -1)
                                 for k in range(layers + 1)], axis=1)
    a, b = sides.T
    vertical = np.concatenate([np.stack([a + k * n, b + k * n, b + (k + 1) * n, a + (k + 1) * n])
                               for k in range(layers)], axis=1)
    return np.concatenate([horizontal, np.pad(vertical, ((0, corners - 4), (0, 0)),
                                              constant_values=-1)], axis=1)


def _on_mirror(tess, sides: np.ndarray) -> np.ndarray:
    """Planform edges lying on one of the tessellation's mirror lines."""
    on = np.zeros(len(sides), bool)
    for axis, value in tess.mirrors:
        on |= np.all(tess.points[sides][:, :, axis] == value, axis=1)
    return on
