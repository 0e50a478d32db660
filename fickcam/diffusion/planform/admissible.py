"""Delaunay-admissible cells of a planform, extruded into prisms by ``prisms.prism``.

FiPy's two-point flux (c_j - c_i) / |x_j - x_i| across a face is consistent only
where the line between the two cell points is normal to the face. On triangles
whose cell point is the centroid it is not, and the error does not vanish under
refinement (measured on a 12 x 8 mm rectangle, nested refinement: the uptake
error settles near 2e-3 of the step instead of falling as h^2). With the
circumcentre as the cell point of a Delaunay triangulation, the line between two
neighbouring cell points lies on the perpendicular bisector of their shared edge
and the scheme is the classical admissible finite-volume mesh (Eymard, Gallouet
& Herbin 2000, Handbook of Numerical Analysis VII, §9, Definition 9.1, triangles
with circumcentres), consistent and, in the measurements here, second order.

Admissible means: (i) Delaunay, so the signed distance between the circumcentres
of two neighbours is >= 0; triangles whose circumcentres coincide (cocircular
points, distance ~0) are merged into one cyclic polygon cell centred on that
circle's centre; (ii) every boundary segment's diametral disc is empty (it is a
Gabriel edge: the angle opposite it is acute and its circumcentre lies inside),
obtained by dropping interior points from such discs and by splitting boundary
segments that other boundary points encroach (Ruppert 1995, J. Algorithms 18,
548-585, §3). Refinement adds the midpoint of every edge and re-triangulates,
so the point sets are nested; the outline is the polygon of the first mesh
(arcs stay chords).

Everything is built in stretched coordinates (x sqrt(D_z/D_x), y sqrt(D_z/D_y)),
where diffusion is isotropic (Crank 1975 §2.6, eq. 2.13): circumcentres and the
Delaunay property are not invariant under unequal stretching.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Eymard, R., Gallouët, T. & Herbin, R. (2000). Finite volume methods. Handbook of Numerical
  Analysis VII:713-1020. doi:10.1016/S1570-8659(00)07005-8
- Ruppert, J. (1995). A Delaunay refinement algorithm for quality 2-dimensional mesh
  generation. Journal of Algorithms 18(3):548-585. doi:10.1006/jagm.1995.1021
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, replace

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import Delaunay, cKDTree

from ...errors import InputError
from ..problem.curves import inside_polygon, segment_distance
from .polygon import centre_offsets, circumcentres, drop_unused, triangle_areas, unique_edges

log = logging.getLogger(__name__)

GABRIEL_MARGIN = 0.05  # a point within (1 + margin) r of a segment's midpoint encroaches it
MERGE_TOLERANCE = 1e-3  # neighbours closer than this many edge lengths share a cell
MAX_PASSES = 30
CUT_SNAP = 0.3  # a point this many of its shortest edges from a mirror line moves onto it


@dataclass(frozen=True)
class Tessellation:
    """Delaunay-admissible polygon cells of a planform (stretched coordinates, m).

    Parameters
    ----------
    points : numpy.ndarray
        The vertices in stretched coordinates [m], shape (n, 2).
    triangles : numpy.ndarray
        The Delaunay triangles' vertex indices, shape (m, 3).
    cell_of : numpy.ndarray
        The cell of each triangle, shape (m,).
    centres : numpy.ndarray
        Each cell's circumcentre [m], shape (c, 2).
    outline : numpy.ndarray
        The outline polygon's segments [m], shape (k, 2, 2) (refinement keeps it).
    contact : numpy.ndarray
        The contact edge's segments [m], shape (j, 2, 2).
    stretch : numpy.ndarray
        stretched = physical x stretch, per axis [-] (the larger 1).
    mirrors : tuple
        ((axis, value [m]), ...): the insulated lines of mirror symmetry, stretched.
    """

    points: np.ndarray     # (n, 2) stretched coordinates
    triangles: np.ndarray  # (m, 3)
    cell_of: np.ndarray    # (m,) cell of each triangle
    centres: np.ndarray    # (c, 2) circumcentre of each cell
    outline: np.ndarray    # (k, 2, 2) segments of the outline polygon (refinement keeps it)
    contact: np.ndarray    # (j, 2, 2) the segments of the contact edge
    stretch: np.ndarray    # (2,) stretched = physical * stretch
    mirrors: tuple = ()    # ((axis, value), ...) insulated lines of mirror symmetry (stretched)

    @property
    def cells(self) -> int:
        return int(self.centres.shape[0])

    def physical(self, stretched: np.ndarray) -> np.ndarray:
        return stretched / self.stretch[None, :]


# ------------------------------------------------------------ admissible


def _delaunay_inside(points: np.ndarray, outline: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Delaunay triangles (scipy.spatial / Qhull) whose centroid lies inside the outline,
    without the flat ones Qhull leaves between collinear hull points (a chord's midpoint);
    unused points dropped."""
    triangles = Delaunay(points).simplices
    area = triangle_areas(points, triangles)
    triangles = triangles[inside_polygon(points[triangles].mean(axis=1), outline)
                          & (area > 1e-9 * np.median(area))]
    points, triangles, _ = drop_unused(points, triangles)
    return points, triangles


def _encroached(points: np.ndarray, segments: np.ndarray) -> list[tuple[int, np.ndarray]]:
    """(segment index, indices of the points inside its diametral disc widened by
    ``GABRIEL_MARGIN``), endpoints excluded."""
    middle = segments.mean(axis=1)
    radius = 0.5 * np.hypot(*(segments[:, 1] - segments[:, 0]).T) * (1 + GABRIEL_MARGIN)
    near = cKDTree(points).query_ball_point(middle, radius)
    found = []
    for k, hits in enumerate(near):
        hits = np.asarray(hits, int)
        ends = np.min(np.hypot(*(points[hits][:, None, :] - segments[k][None]).transpose(2, 0, 1)),
                      axis=1) if hits.size else hits
        hits = hits[ends > 1e-9 * radius[k]]
        if hits.size:
            found.append((k, hits))
    return found


def _split(segments: np.ndarray, which: np.ndarray) -> np.ndarray:
    middle = segments[which].mean(axis=1)
    halves = np.concatenate([np.stack([segments[which, 0], middle], axis=1),
                             np.stack([middle, segments[which, 1]], axis=1)])
    return np.concatenate([np.delete(segments, which, axis=0), halves])


def _conform(points: np.ndarray, segments: np.ndarray, drop_interior: bool):
    """Make every boundary segment a Gabriel edge: drop interior points from its disc
    (``drop_interior``) and split segments that boundary points encroach (Ruppert 1995 §3)."""
    for _ in range(MAX_PASSES):
        found = _encroached(points, segments)
        if not found:
            return points, segments
        boundary = _on_segments(points, segments)
        drop = np.unique(np.concatenate([hits[~boundary[hits]] for _, hits in found]))
        if drop_interior and drop.size:
            points = np.delete(points, drop, axis=0)
            continue
        segments = _split(segments, np.array([k for k, _ in found]))
        points = np.vstack([points, segments[-len(found):, 0]])  # each split's midpoint
    raise InputError(f"diffusion.model solid: outline segments still encroached after "
                     f"{MAX_PASSES} splits (a corner sharper than 60 deg?); use plane")


def _on_segments(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Which points are segment ends."""
    scale = float(np.max(np.ptp(points, axis=0)))
    ends = np.unique(segments.reshape(-1, 2), axis=0)
    return cKDTree(ends).query(points)[0] <= 1e-12 * scale


def _boundary(triangles: np.ndarray) -> np.ndarray:
    edges, inverse = unique_edges(triangles)
    return edges[np.bincount(inverse.ravel(), minlength=len(edges)) == 1]


def _cells(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Group triangles whose circumcentres (nearly) coincide; (cell of each triangle,
    centre of each cell). Checks the result is admissible."""
    centres = circumcentres(points, triangles)
    offsets = centre_offsets(points, triangles, centres)
    edges, inverse = unique_edges(triangles)
    length = np.hypot(*(points[edges[:, 0]] - points[edges[:, 1]]).T)
    dual = np.bincount(inverse.ravel(), offsets.ravel(), minlength=len(edges))
    shared = np.bincount(inverse.ravel(), minlength=len(edges))
    if np.any(dual[shared == 1] <= 0) or np.any(dual[shared == 2] < -MERGE_TOLERANCE * length[
            shared == 2]):
        raise InputError("diffusion.model solid: the planform's triangulation is not "
                         "Delaunay-admissible; use plane")
    flat = inverse.ravel()
    order = np.argsort(flat, kind="stable")
    edge, owner = flat[order], np.repeat(np.arange(len(triangles)), 3)[order]
    pair = edge[1:] == edge[:-1]  # the two triangles of an interior edge, adjacent after sorting
    close = pair & (dual[edge[:-1]] < MERGE_TOLERANCE * length[edge[:-1]])
    graph = coo_matrix((np.ones(np.count_nonzero(close)), (owner[:-1][close], owner[1:][close])),
                       shape=(len(triangles),) * 2)
    count, cell_of = connected_components(graph, directed=False)
    weight = np.bincount(cell_of, minlength=count)
    centre = np.column_stack([np.bincount(cell_of, centres[:, i], minlength=count)
                              for i in range(2)]) / weight[:, None]
    return cell_of, centre


def _contact_segments(part, segments: np.ndarray, stretch: np.ndarray) -> np.ndarray:
    """The outline segments on the contact edge (an end on it, ``on_contact``): a LinkBar's
    whole outline, a CamPlate's profile (not the bore)."""
    ends = (segments / stretch[None, None, :]).reshape(-1, 2)
    return segments[np.any(part.on_contact(ends).reshape(len(segments), 2), axis=1)]


def tessellation(points: np.ndarray, outline: np.ndarray, contact: np.ndarray,
                 stretch: np.ndarray, drop_interior: bool) -> Tessellation:
    """Admissible cells of ``points`` inside the polygon ``outline`` (stretched coordinates).

    Parameters
    ----------
    points : numpy.ndarray
        Candidate points, stretched [m], shape (n, 2).
    outline : numpy.ndarray
        The outline's segments, stretched [m], shape (k, 2, 2).
    contact : numpy.ndarray
        The contact edge's segments, stretched [m].
    stretch : numpy.ndarray
        The per-axis stretch [-].
    drop_interior : bool
        True: drop interior points that encroach a boundary segment (else split the segment).

    Returns
    -------
    Tessellation
        The cells, their circumcentres and the conforming outline.

    Raises
    ------
    fickcam.errors.InputError
        When the triangulation does not follow the outline (use the plane model).

    References
    ----------
    Eymard, Gallouet & Herbin (2000), Definition 9.1; Ruppert (1995), §3 (module docstring).
    """
    boundary_points = np.unique(outline.reshape(-1, 2), axis=0)
    points = np.unique(np.vstack([boundary_points, points]), axis=0)
    points, segments = _conform(points, outline, drop_interior)
    points, triangles = _delaunay_inside(points, outline)
    if _boundary(triangles).shape[0] != segments.shape[0]:
        raise InputError("diffusion.model solid: the planform's triangulation does not "
                         "follow its outline; use plane")
    cell_of, centres = _cells(points, triangles)
    log.debug("admissible tessellation: %d points, %d triangles, %d cells", len(points),
              len(triangles), len(centres))
    return Tessellation(points, triangles, cell_of, centres, segments, contact,
                        np.asarray(stretch, float))


def admissible(triangulation, part, stretch=(1.0, 1.0), mirrors=()) -> Tessellation:
    """Admissible cells from the points and the outline (boundary edges) of a
    ``planform.Triangulation`` (physical m); ``stretch`` per axis (only the ratio matters).
    ``mirrors``: lines (axis, value in m) of mirror symmetry; only the side
    x_axis >= value is kept and the cut is an insulated boundary (``grids.prism``).

    Parameters
    ----------
    triangulation : Triangulation
        The planform's triangle mesh [m] (``triangles.triangulate``).
    part : CamPlate or LinkBar
        The part (its bore is not a contact edge).
    stretch : sequence of float
        sqrt(D_z / D_x), sqrt(D_z / D_y) [-]; only their ratio matters.
    mirrors : sequence of tuple
        (axis, value [m]) lines of mirror symmetry.

    Returns
    -------
    Tessellation
        The admissible cells of the kept side.

    Raises
    ------
    fickcam.errors.InputError
        When the triangulation does not follow the outline.
    """
    stretch = np.asarray(stretch, float) / max(stretch)
    points = np.asarray(triangulation.points, float) * stretch[None, :]
    triangles = np.asarray(triangulation.triangles)
    outline = points[_boundary(triangles)]
    contact = _contact_segments(part, outline, stretch)
    lines = tuple((int(axis), float(value) * stretch[axis]) for axis, value in mirrors)
    for axis, value in lines:
        points, outline, contact = _cut(points, triangles, outline, contact, axis, value)
        points, triangles = _delaunay_inside(points, outline)
    tess = tessellation(points, outline, contact, stretch, drop_interior=True)
    return _with_mirrors(tess, lines)


def _with_mirrors(tess: Tessellation, lines) -> Tessellation:
    return replace(tess, mirrors=tuple(lines))


def _crossing(a: np.ndarray, b: np.ndarray, axis: int, value: float) -> np.ndarray:
    """Where segments a-b cross the line x_axis = value, computed from the endpoints in
    lexicographic order (the same point whichever way a segment is stored)."""
    swap = (a[:, 0] > b[:, 0]) | ((a[:, 0] == b[:, 0]) & (a[:, 1] > b[:, 1]))
    lo, hi = np.where(swap[:, None], b, a), np.where(swap[:, None], a, b)
    t = (value - lo[:, axis]) / (hi[:, axis] - lo[:, axis])
    out = lo + t[:, None] * (hi - lo)
    out[:, axis] = value
    return out


def _cut(points, triangles, outline, contact, axis: int, value: float):
    """The side x_axis >= value of a triangulated polygon: its points, the outline
    clipped, and the cut's own segments (the intervals of the line inside the polygon).
    Points on the line: mesh points (the outline's too) within ``CUT_SNAP`` of their
    shortest edge from it, moved onto it, and the crossings of the other mesh edges but
    those as close to a point already on the line (no slivers along the cut)."""
    scale = float(np.max(np.ptp(points, axis=0)))
    edges, _ = unique_edges(triangles)
    length = np.hypot(*(points[edges[:, 1]] - points[edges[:, 0]]).T)
    shortest = np.full(len(points), np.inf)
    for end in (0, 1):
        np.minimum.at(shortest, edges[:, end], length)
    near = np.abs(points[:, axis] - value) < np.maximum(CUT_SNAP * shortest, 1e-9 * scale)
    tree = cKDTree(points)

    def snapped(q):  # the points' own coordinates, the near ones moved onto the line
        index = tree.query(q.reshape(-1, 2))[1]
        out = points[index]
        out[near[index], axis] = value
        return out.reshape(q.shape)

    outline, contact, points = snapped(outline), snapped(contact), snapped(points)
    a, b = points[edges[:, 0]], points[edges[:, 1]]
    crossing = (a[:, axis] - value) * (b[:, axis] - value) < 0
    on_line = _sparse_on_line(points[points[:, axis] == value],
                              _crossing(a[crossing], b[crossing], axis, value),
                              CUT_SNAP * length[crossing], 1 - axis)
    middle = 0.5 * (on_line[1:] + on_line[:-1])
    inside = inside_polygon(middle, outline) & (np.diff(on_line[:, 1 - axis]) > 1e-9 * scale)
    cut = np.stack([on_line[:-1][inside], on_line[1:][inside]], axis=1)
    kept = points[points[:, axis] >= value]
    return (np.unique(np.vstack([kept, on_line]), axis=0),
            np.concatenate([_clip_segments(outline, axis, value), cut]),
            _clip_segments(contact, axis, value))


def _sparse_on_line(fixed: np.ndarray, crossings: np.ndarray, gaps: np.ndarray,
                    along: int) -> np.ndarray:
    """Points on a line sorted along it: all ``fixed`` ones, and each crossing at least
    its ``gap`` away from the points kept so far."""
    keep = list(fixed)
    position = fixed[:, along]
    for index in np.argsort(gaps):  # the finest crossings first
        point = crossings[index]
        if position.size == 0 or np.min(np.abs(position - point[along])) >= gaps[index]:
            keep.append(point)
            position = np.append(position, point[along])
    out = np.array(keep).reshape(-1, 2)
    return out[np.argsort(out[:, along])]


def _clip_segments(segments: np.ndarray, axis: int, value: float) -> np.ndarray:
    """The parts of segments on the side x_axis >= value."""
    a, b = segments[:, 0], segments[:, 1]
    a_in, b_in = a[:, axis] >= value, b[:, axis] >= value
    whole = segments[a_in & b_in]
    partial = a_in != b_in
    crossing = _crossing(a[partial], b[partial], axis, value)
    inner = np.where(a_in[partial][:, None], a[partial], b[partial])
    piece = np.stack([inner, crossing], axis=1)
    return np.concatenate([whole, piece[np.any(inner != crossing, axis=1)]])  # not a touch


def refine(tess: Tessellation) -> Tessellation:
    """Nested refinement: every edge's midpoint added, re-triangulated (red refinement where
    that is Delaunay), outline segments halved.

    Parameters
    ----------
    tess : Tessellation
        The coarse cells (stretched coordinates [m]).

    Returns
    -------
    Tessellation
        The refined cells, whose points include the coarse ones.
    """
    edges, _ = unique_edges(tess.triangles)
    points = np.vstack([tess.points, tess.points[edges].mean(axis=1)])
    return _with_mirrors(tessellation(points, _halves(tess.outline), tess.contact, tess.stretch,
                                      drop_interior=False), tess.mirrors)


def _halves(segments: np.ndarray) -> np.ndarray:
    return _split(segments, np.arange(len(segments)))


# ------------------------------------------------------------------ cells


def cell_areas(tess: Tessellation) -> np.ndarray:
    """Area of each cell (stretched coordinates).

    Parameters
    ----------
    tess : Tessellation
        A planform's cells; points in stretched coordinates [m].

    Returns
    -------
    numpy.ndarray
        The cells' areas in stretched coordinates [m^2].
    """
    return np.bincount(tess.cell_of, triangle_areas(tess.points, tess.triangles),
                       minlength=tess.cells)


def cell_loops(tess: Tessellation) -> list[np.ndarray]:
    """Vertex loop of each cell, counter-clockwise (a merged cell is cyclic, so convex:
    its vertices sorted by angle about the centre).

    Parameters
    ----------
    tess : Tessellation
        The cells whose corners are wanted (stretched coordinates [m]).

    Returns
    -------
    list of numpy.ndarray
        The vertex indices round each cell.
    """
    loops: list[np.ndarray] = [np.empty(0, int)] * tess.cells
    single = np.bincount(tess.cell_of, minlength=tess.cells) == 1
    for cell in np.flatnonzero(~single):
        vertices = np.unique(tess.triangles[tess.cell_of == cell])
        offset = tess.points[vertices] - tess.centres[cell]
        loops[cell] = vertices[np.argsort(np.arctan2(offset[:, 1], offset[:, 0]))]
    triangles = tess.triangles
    a, b, c = (tess.points[triangles[:, k]] for k in range(3))
    clockwise = ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]) < 0
    ordered = np.where(clockwise[:, None], triangles[:, ::-1], triangles)
    for index in np.flatnonzero(single[tess.cell_of]):
        loops[tess.cell_of[index]] = ordered[index]
    return loops


def band_share(tess: Tessellation, depth: float) -> np.ndarray:
    """Fraction of each cell's area within ``depth`` (physical m) of the contact edge,
    with the distance interpolated linearly over each triangle (exact area of the
    sublevel set of a linear function, below).

    Parameters
    ----------
    tess : Tessellation
        The admissible cells; stretched points [m], unstretched by ``physical``.
    depth : float
        The contact layer's depth [m].

    Returns
    -------
    numpy.ndarray
        Each cell's share of area within the layer [-], in [0, 1].
    """
    physical = tess.physical(tess.points)
    distance = segment_distance(physical, tess.physical(tess.contact.reshape(-1, 2)).reshape(
        -1, 2, 2))
    fraction = linear_sublevel_fraction(distance[tess.triangles], depth)
    area = triangle_areas(tess.points, tess.triangles)
    return np.bincount(tess.cell_of, fraction * area, minlength=tess.cells) / cell_areas(tess)


def linear_sublevel_fraction(values: np.ndarray, level: float) -> np.ndarray:
    """Area fraction of a triangle where the linear interpolant of its vertex ``values``
    (m, 3) is <= ``level``: with sorted values v1 <= v2 <= v3 it is
    (l - v1)^2 / ((v2 - v1)(v3 - v1)) for v1 <= l <= v2 and
    1 - (v3 - l)^2 / ((v3 - v1)(v3 - v2)) for v2 <= l <= v3 (the cut is a triangle
    similar to a corner of the triangle).

    Parameters
    ----------
    values : numpy.ndarray
        The function at each triangle's vertices, shape (m, 3) (a distance [m]).
    level : float
        The level, in the values' unit [m].

    Returns
    -------
    numpy.ndarray
        The fraction of each triangle's area at or below the level [-].
    """
    v1, v2, v3 = np.sort(values, axis=1).T
    below, above = (v2 - v1) * (v3 - v1), (v3 - v1) * (v3 - v2)  # 0 only where unused
    low = np.divide((level - v1) ** 2, below, out=np.zeros_like(v1), where=below > 0)
    high = 1.0 - np.divide((v3 - level) ** 2, above, out=np.zeros_like(v1), where=above > 0)
    out = np.where(level <= v2, low, high)
    return np.clip(np.where(level <= v1, 0.0, np.where(level >= v3, 1.0, out)), 0.0, 1.0)
