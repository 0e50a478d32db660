"""Triangle meshes of a planform: graded from the outline, or a uniform lattice.

After a change of the surface value the in-plane solution varies over a
layer of depth ~ sqrt(tau) along every edge (Crank 1975 eq. 2.45), so the mesh is
finest at the outline and grows inward: boundary samples at the finest spacing
h0, then rows of points offset inward along the normals, row k with spacing
s_k = h0 (1 + g)^k (geometric growth, as ``grading``) one equilateral height
below the last, d_k - d_{k-1} = (sqrt 3 / 2)(s_{k-1} + s_k) / 2 ("advancing
layers"). A row is resampled at its own spacing, loses the points whose distance
to the outline is not its depth (swallowtails at convex corners, the medial axis
where rows from opposite edges meet) and the points closer than 0.7 s_k to one
already placed; a hexagonal lattice at the coarsest spacing fills what is left.
The points are triangulated by Delaunay (scipy.spatial) and the triangles whose
centroid lies outside are dropped.


Outlines without closed loops (a LinkBar whose bosses are narrower than the bar, or
overlap) get boundary samples plus a uniform hexagonal lattice instead.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import Delaunay, cKDTree

from .outline import outline
from .polygon import (Wall, drop_unused, edge_normals, loop_resampler, resample_loop,
                      triangle_areas)

log = logging.getLogger(__name__)

ROW = math.sqrt(3.0) / 2.0   # height of an equilateral triangle of unit side
FAN_STEP = 0.1               # rad between offset normals around a reflex corner
DEPTH_TOLERANCE = 0.25       # a row point must lie within this many spacings of its depth
MIN_GAP = 0.7                # points closer than this many local spacings are dropped


def fanned(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points with offset normals: the bisector at ordinary vertices and a fan of normals
    every ``FAN_STEP`` at reflex corners (right turns), whose offsets are arcs.

    Parameters
    ----------
    points : numpy.ndarray
        Samples along one closed loop [m], material on the left.

    Returns
    -------
    points : numpy.ndarray
        The samples, a reflex corner repeated once per normal of its fan [m].
    normals : numpy.ndarray
        The unit offset normal of each [-].
    """
    after = edge_normals(points)
    before = np.roll(after, 1, axis=0)
    both = before + after   # ``vertex_normals``, from the edge normals at hand
    bisector = both / np.hypot(*both.T)[:, None]
    turn = np.arctan2(before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0],
                      np.einsum("ij,ij->i", before, after))
    if not np.any(turn < -FAN_STEP):
        return points, bisector
    count = np.where(turn < -FAN_STEP, np.ceil(-turn / FAN_STEP).astype(int), 0) + 1
    index = np.repeat(np.arange(points.size // 2), count)
    step = np.arange(index.size) - np.repeat(np.cumsum(count) - count, count)
    fan = count[index] > 1
    angle = (np.arctan2(before[index, 1], before[index, 0])
             + turn[index] * step / np.maximum(count[index] - 1, 1))
    normals = np.where(fan[:, None], np.column_stack([np.cos(angle), np.sin(angle)]),
                       bisector[index])
    return points[index], normals


def _runs(mask: np.ndarray) -> tuple[list[np.ndarray], bool]:
    """Index runs of True in a cyclic mask, and whether the single run is the whole loop."""
    if mask.all():
        return [np.arange(mask.size)], True
    start = int(np.argmin(mask))
    order = np.roll(np.arange(mask.size), -start)
    flags = np.concatenate([[0], mask[order].astype(int), [0]])
    edges = np.flatnonzero(np.diff(flags))
    return [order[a:b] for a, b in zip(edges[::2], edges[1::2])], False


def _along(points: np.ndarray, spacing: float, closed: bool, shifted: bool) -> np.ndarray:
    """Points along a polyline every ~``spacing`` (``shifted``: half a step along,
    staggering consecutive rows)."""
    if closed:
        points = np.vstack([points, points[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    count = max(1, round(arc[-1] / spacing))
    s = (np.arange(count if closed else count + 1) + 0.5 * shifted) * arc[-1] / count
    s = s[s <= arc[-1]]
    return np.column_stack([np.interp(s, arc, points[:, 0]), np.interp(s, arc, points[:, 1])])


def _sparse_enough(candidates: np.ndarray, placed: np.ndarray, gap: float) -> np.ndarray:
    """Candidates at least ``gap`` from every placed point and from each other (greedy)."""
    if candidates.size == 0:
        return candidates
    # only which distances reach ``gap`` counts: a bounded search, trees built unbalanced
    if placed.size:
        nearest = cKDTree(placed, balanced_tree=False).query(candidates,
                                                             distance_upper_bound=gap)[0]
        candidates = candidates[nearest >= gap]
    pairs = cKDTree(candidates, balanced_tree=False).query_pairs(gap, output_type="ndarray")
    drop = np.zeros(len(candidates), bool)
    for i, j in pairs[np.lexsort(pairs.T[::-1])]:
        if not drop[i]:
            drop[j] = True
    return candidates[~drop]


def row_spacings(finest: float, growth: float, coarsest: float):
    """(spacing, depth) of successive rows: s_k = min(h0 (1+g)^k, coarsest),
    d_k = d_{k-1} + (sqrt 3 / 2)(s_{k-1} + s_k) / 2.

    Parameters
    ----------
    finest : float
        h0, the outline's spacing [m].
    growth : float
        g, the spacing's growth per row [-].
    coarsest : float
        The largest spacing [m].

    Returns
    -------
    iterator of tuple
        (s_k, d_k) for k = 1, 2, ...: each row's spacing and depth [m], endless.
    """
    spacing, depth = finest, 0.0
    while True:
        wider = min(spacing * (1.0 + growth), coarsest)
        depth += ROW * 0.5 * (spacing + wider)
        spacing = wider
        yield spacing, depth


def graded_points(loops: list[np.ndarray], finest: float, growth: float,
                  coarsest: float = np.inf) -> tuple[np.ndarray, np.ndarray, Wall]:
    """(outline points, interior points, wall) of a graded mesh (see the module docstring).

    Parameters
    ----------
    loops : list of numpy.ndarray
        Closed outline polylines, material on the left, mesh coordinates [m].
    finest : float
        h0, the spacing along the outline [m].
    growth : float
        g, the growth per row [-].
    coarsest : float
        The spacing at which rows stop and a lattice fills the rest [m].

    Returns
    -------
    boundary : numpy.ndarray
        The outline samples [m].
    interior : numpy.ndarray
        The rows' and lattice's points [m].
    wall : Wall
        The outline's signed distance.
    """
    boundary = np.vstack([resample_loop(loop, finest) for loop in loops])
    wall = Wall.of(loops, finest / 4)
    placed = boundary
    spacing = depth = finest
    resamplers = [loop_resampler(loop) for loop in loops]
    for k, (spacing, depth) in enumerate(row_spacings(finest, growth, coarsest), start=1):
        pieces = []
        for points, normals in (fanned(along(spacing / 4)) for along in resamplers):
            moved = points + depth * normals
            gap, inside = wall.distance(moved, depth + DEPTH_TOLERANCE * spacing)
            runs, closed = _runs(inside & (np.abs(gap - depth) <= DEPTH_TOLERANCE * spacing))
            pieces += [_along(moved[run], spacing, closed, bool(k % 2)) for run in runs
                       if run.size > 1]
        row = _sparse_enough(np.vstack(pieces) if pieces else np.empty((0, 2)), placed,
                             MIN_GAP * spacing)
        if row.size == 0:
            break
        placed = np.vstack([placed, row])
        if spacing >= coarsest:
            placed = np.vstack([placed, _lattice_fill(placed, wall, coarsest, depth)])
            break
    return boundary, placed[len(boundary):], wall



def hex_lattice(lo: np.ndarray, hi: np.ndarray, spacing: float) -> np.ndarray:
    """Points of a hexagonal lattice of side ``spacing`` covering the box [lo, hi].

    Parameters
    ----------
    lo, hi : numpy.ndarray
        The box's lower-left and upper-right corners [m].
    spacing : float
        The lattice's side [m].

    Returns
    -------
    numpy.ndarray
        The lattice points [m], shape (k, 2).
    """
    rows = np.arange(lo[1], hi[1] + spacing, ROW * spacing)
    xs = np.arange(lo[0], hi[0] + spacing, spacing)
    return np.vstack([np.column_stack([xs + 0.5 * spacing * (i % 2), np.full(xs.size, y)])
                      for i, y in enumerate(rows)])


def _lattice_fill(placed: np.ndarray, wall: Wall, spacing: float, depth: float) -> np.ndarray:
    """Hexagonal lattice at ``spacing`` deeper than ``depth``, away from placed points."""
    lattice = hex_lattice(placed.min(axis=0), placed.max(axis=0), spacing)
    gap, inside = wall.distance(lattice)
    lattice = lattice[inside & (gap > depth + 0.5 * ROW * spacing)]
    return _sparse_enough(lattice, placed, MIN_GAP * spacing)


def delaunay_inside(points: np.ndarray, wall: Wall, finest: float) -> np.ndarray:
    """Delaunay triangles whose centroid is inside the outline (slivers of collinear
    outline points dropped).

    Parameters
    ----------
    points : numpy.ndarray
        The mesh points [m].
    wall : Wall
        The outline's signed distance.
    finest : float
        The finest spacing [m] (slivers below 1e-6 finest^2 are dropped).

    Returns
    -------
    numpy.ndarray
        The kept triangles' vertex indices, shape (m, 3).
    """
    triangles = Delaunay(points).simplices
    corners = points[triangles]
    inside = wall.distance(corners.mean(axis=1))[1]
    return triangles[inside & (triangle_areas(points, triangles) > 1e-6 * finest ** 2)]


def angles(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """(m, 3) interior angles (rad) of each triangle.

    Parameters
    ----------
    points : numpy.ndarray
        The vertices [m].
    triangles : numpy.ndarray
        Vertex indices, shape (m, 3).

    Returns
    -------
    numpy.ndarray
        The angle at each corner [rad], shape (m, 3).
    """
    corners = points[triangles]
    out = []
    for i in range(3):
        a = corners[:, (i + 1) % 3] - corners[:, i]
        b = corners[:, (i + 2) % 3] - corners[:, i]
        cosine = np.einsum("ij,ij->i", a, b) / (np.hypot(*a.T) * np.hypot(*b.T))
        out.append(np.arccos(np.clip(cosine, -1.0, 1.0)))
    return np.column_stack(out)


@dataclass(frozen=True)
class GradedMesh:
    """Points (mesh coordinates), triangles and which points lie on the outline.

    Parameters
    ----------
    points : numpy.ndarray
        The mesh points [m], shape (n, 2).
    triangles : numpy.ndarray
        Vertex indices, shape (m, 3).
    on_outline : numpy.ndarray
        True for a point on the outline, shape (n,).
    """

    points: np.ndarray
    triangles: np.ndarray
    on_outline: np.ndarray  # (n,) bool


def graded_mesh(loops: list[np.ndarray], finest: float, growth: float,
                coarsest: float = np.inf) -> GradedMesh:
    """Triangulated graded points; unused points removed.

    Parameters
    ----------
    loops : list of numpy.ndarray
        Closed outline polylines, material on the left, mesh coordinates [m].
    finest : float
        h0 along the outline [m].
    growth : float
        g per row [-].
    coarsest : float
        The spacing where rows give way to a lattice [m].

    Returns
    -------
    GradedMesh
        The points, triangles and outline flags.
    """
    boundary, interior, wall = graded_points(loops, finest, growth, coarsest)
    points = np.vstack([boundary, interior])
    triangles = delaunay_inside(points, wall, finest)
    kept, triangles, used = drop_unused(points, triangles)
    return GradedMesh(kept, triangles, used < len(boundary))



@dataclass(frozen=True)
class Triangulation:
    """Triangles of a planform (physical metres) with each triangle's distance to the contact
    edge; ``on_outline`` marks the points on the outline, ``contact(points, bound)`` gives
    their distance to the contact edge (inf beyond ``bound``).

    Parameters
    ----------
    points : numpy.ndarray
        The nodes in physical coordinates [m].
    triangles : numpy.ndarray
        Each triangle's three nodes.
    contact_distance : numpy.ndarray
        Each triangle's centroid's distance to the contact edge [m], shape (m,); a graded
        mesh's is inf beyond 2 finest spacings of the edge (its least is what is read).
    on_outline : numpy.ndarray, optional
        True for a point on the outline, shape (n,).
    contact : callable, optional
        ``contact(points, bound)``: distance [m] to the contact edge, inf beyond ``bound``.
    """

    points: np.ndarray      # (n, 2)
    triangles: np.ndarray   # (m, 3)
    contact_distance: np.ndarray  # (m,)
    on_outline: np.ndarray | None = None  # (n,) bool
    contact: object = field(default=None, repr=False, compare=False)


def triangulate(part, spacing: float, *, growth: float | None = None,
                stretch: tuple[float, float] = (1.0, 1.0)) -> Triangulation:
    """Triangles of a planform with edges of about ``spacing`` (m) along the outline.

    Without ``growth``: boundary samples plus a uniform hexagonal lattice. With ``growth``
    g: rows graded from the outline, spacing (1 + g)^k ``spacing`` (``triangles``), built in
    the coordinates (stretch_x x, stretch_y y), where ``spacing`` is measured and the
    triangles are near-equilateral (the scaled coordinates of anisotropic diffusion,
    Crank 1975 eq. 2.13). Outlines without closed loops (a LinkBar whose bosses are
    narrower than the bar, or overlap) get the uniform lattice.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The part, its lengths in [m].
    spacing : float
        The edge length along the outline [m], in stretched coordinates.
    growth : float, optional
        g, the rows' growth [-]; None: a uniform lattice.
    stretch : tuple of float
        sqrt(D_z / D_x), sqrt(D_z / D_y) [-].

    Returns
    -------
    Triangulation
        The triangles in physical coordinates [m].

    References
    ----------
    Crank (1975), eqs. 2.13 and 2.45 (see the module docstring).
    """
    found = None if growth is None else part.boundary_loops(spacing / max(stretch))
    if found is None:
        return _lattice_triangulation(part, spacing / max(stretch))
    loops, contact = found
    factor = np.asarray(stretch, float)
    mesh = graded_mesh([loop * factor for loop in loops], spacing, growth)
    points = mesh.points / factor
    distance = _distance_to([loop for loop, edge in zip(loops, contact) if edge], spacing / 8)
    log.debug("graded mesh of %s: %d points, %d triangles", type(part).__name__, len(points),
              len(mesh.triangles))
    return Triangulation(points, mesh.triangles, _nearest_distances(
        distance, points[mesh.triangles].mean(axis=1), 2 * spacing / float(factor.min())),
                         mesh.on_outline, distance)


def _nearest_distances(distance, points: np.ndarray, bound: float) -> np.ndarray:
    """``distance(points, bound)`` (a bounded search: deep inside a nearly round outline an
    unbounded one visits most of the tree), unbounded where no point lies within it."""
    found = distance(points, bound)
    return found if np.isfinite(found).any() else distance(points)


def _distance_to(loops: list[np.ndarray], spacing: float):
    """Distance (m) from points to the closed polylines ``loops``, by samples every ``spacing``
    (inf beyond an optional bound: a bounded search is much faster)."""
    return _bounded_query(cKDTree(np.vstack([resample_loop(loop, spacing) for loop in loops])))


def _bounded_query(tree):
    """points, bound -> distance to the nearest sample of ``tree`` (inf beyond ``bound``)."""
    return lambda points, bound=np.inf: tree.query(points, distance_upper_bound=bound)[0]


def _lattice_triangulation(part, spacing: float) -> Triangulation:
    """Delaunay triangulation of boundary samples plus a hexagonal interior lattice."""
    shape = outline(part, spacing)
    lattice = hex_lattice(shape.boundary.min(axis=0), shape.boundary.max(axis=0), spacing)
    boundary_tree = cKDTree(shape.boundary)
    keep = shape.inside(*lattice.T) & (boundary_tree.query(lattice)[0] > 0.5 * spacing)
    points = np.vstack([shape.boundary, lattice[keep]])
    triangles = Delaunay(points).simplices
    centroid = points[triangles].mean(axis=1)
    area = triangle_areas(points, triangles)
    # inside the outline, and not a sliver of collinear boundary points (zero volume)
    triangles = triangles[shape.inside(*centroid.T) & (area > 1e-6 * spacing ** 2)]
    points, triangles, used = drop_unused(points, triangles)
    centroid = points[triangles].mean(axis=1)
    contact_tree = cKDTree(_resample_points(shape.contact, spacing / 8))
    log.debug("triangulated %s: %d points, %d triangles", type(part).__name__, len(points),
              len(triangles))
    return Triangulation(points, triangles, contact_tree.query(centroid)[0],
                         used < len(shape.boundary),
                         _bounded_query(contact_tree))


def _resample_points(points: np.ndarray, spacing: float) -> np.ndarray:
    """Denser samples between consecutive boundary points closer than 4 spacings."""
    nxt = np.roll(points, -1, axis=0)
    gap = np.hypot(*(nxt - points).T)
    near = gap < 40 * spacing
    fractions = np.arange(8) / 8
    extra = points[near, None, :] + (nxt - points)[near, None, :] * fractions[None, :, None]
    return np.vstack([points, extra.reshape(-1, 2)])

