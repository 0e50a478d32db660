"""Plane geometry of outlines and triangles, the one place each of these algorithms
lives: turning angles and corners, resampling of closed loops, normals, the signed
distance to an outline (``Wall``), triangle areas, edges, circumcentres and distances to
segments. Sampling polylines and circles and point in polygon, which the geometries
build their outlines with, are in ``problem.curves``."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

CORNER_TURN = 0.2  # rad: a vertex turning more is a corner, less samples a smooth arc


def turning_angles(loop: np.ndarray) -> np.ndarray:
    """Signed turn (rad, left positive) of a closed polyline at each vertex.

    Parameters
    ----------
    loop : numpy.ndarray
        A closed polyline, one vertex (x, y) a row [m] (or scaled [-]).

    Returns
    -------
    numpy.ndarray
        The turn at each vertex [rad], in (-pi, pi].
    """
    edge = np.roll(loop, -1, axis=0) - loop
    incoming = np.roll(edge, 1, axis=0)
    return np.arctan2(incoming[:, 0] * edge[:, 1] - incoming[:, 1] * edge[:, 0],
                      np.einsum("ij,ij->i", incoming, edge))


def corners_of(loop: np.ndarray) -> np.ndarray:
    """Indices of the vertices of a closed polyline that turn by more than ``CORNER_TURN``.

    Parameters
    ----------
    loop : numpy.ndarray
        The vertices of a closed polyline [m].

    Returns
    -------
    numpy.ndarray
        The corners' vertex indices (|turn| >= 0.2 rad).
    """
    return np.flatnonzero(np.abs(turning_angles(loop)) >= CORNER_TURN)


def resample_loop(loop: np.ndarray, spacing: float) -> np.ndarray:
    """Points along a closed polyline at equal arc steps <= ``spacing`` between its corners
    (corners kept as points).

    Parameters
    ----------
    loop : numpy.ndarray
        The loop to resample, shape (n, 2) [m].
    spacing : float
        The largest step along the polyline [m], in the loop's unit.

    Returns
    -------
    numpy.ndarray
        The resampled points, shape (k, 2) [m].
    """
    return loop_resampler(loop)(spacing)


def loop_resampler(loop: np.ndarray):
    """``spacing -> resample_loop(loop, spacing)`` with the loop's arc lengths and corners
    found once, for a loop resampled at many spacings (the same points, bit for bit).

    Parameters
    ----------
    loop : numpy.ndarray
        The loop to resample, shape (n, 2) [m].

    Returns
    -------
    callable
        spacing [m] -> the resampled points [m], shape (k, 2).
    """
    closed = np.vstack([loop, loop[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    total = arc[-1]
    corners = corners_of(loop)
    starts = arc[corners] if corners.size else np.array([0.0])
    span = np.append(starts[1:], starts[0] + total) - starts

    def at(spacing: float) -> np.ndarray:
        count = np.maximum(1, np.ceil(span / spacing)).astype(int)
        step = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        s = (np.repeat(starts, count) + np.repeat(span, count) * step / np.repeat(count, count)
             ) % total
        return np.column_stack([np.interp(s, arc, closed[:, 0]),
                                np.interp(s, arc, closed[:, 1])])
    return at


def loop_length(loop: np.ndarray) -> float:
    """The perimeter of a closed polyline.

    Parameters
    ----------
    loop : numpy.ndarray
        A closed polyline's vertices [m]; the last joins the first.

    Returns
    -------
    float
        The sum of its edges' lengths [m].
    """
    return float(np.sum(np.hypot(*(np.roll(loop, -1, axis=0) - loop).T)))


def edge_normals(points: np.ndarray) -> np.ndarray:
    """Unit normals to the left of each edge i -> i+1 (towards the material).

    Parameters
    ----------
    points : numpy.ndarray
        A closed loop's vertices, shape (n, 2) [m].

    Returns
    -------
    numpy.ndarray
        The unit normals [-], shape (n, 2).
    """
    edge = np.roll(points, -1, axis=0) - points
    edge /= np.hypot(*edge.T)[:, None]
    return np.column_stack([-edge[:, 1], edge[:, 0]])


def vertex_normals(points: np.ndarray) -> np.ndarray:
    """Unit bisectors of the normals of the two edges at each vertex.

    Parameters
    ----------
    points : numpy.ndarray
        The loop's points [m], material on their left.

    Returns
    -------
    numpy.ndarray
        The unit vertex normals [-], shape (n, 2), to the left of the loop.
    """
    after = edge_normals(points)
    both = np.roll(after, 1, axis=0) + after
    return both / np.hypot(*both.T)[:, None]


def first_exits(starts: np.ndarray, directions: np.ndarray, loops: list[np.ndarray],
                near: float) -> np.ndarray:
    """Distance along each ray to where it first leaves the region the closed polylines
    ``loops`` bound (material on their left, holes included), exactly: each ray is
    intersected with the segments of every run of ``RUN`` consecutive ones whose bounding
    circle its half-line meets. A vertex's side of a ray is decided once (on the line: the
    left side), so a ray through a vertex crosses one of its two segments, a ray along a
    segment crosses where its neighbours say, and a ray that touches the outline at a vertex
    from inside (an entry and an exit at one distance) goes on. Crossings up to ``near``
    (the ray's own start on the outline) do not count.

    Parameters
    ----------
    starts : numpy.ndarray
        The rays' starts, shape (r, 2) [m] (or scaled [-]), inside or on the outline.
    directions : numpy.ndarray
        The rays' unit directions [-], shape (r, 2).
    loops : list of numpy.ndarray
        Closed polylines, material on the left [m] (or scaled [-], as the starts).
    near : float
        Crossings up to this distance from the start are skipped [m] (or scaled [-]).

    Returns
    -------
    numpy.ndarray
        The distance to the first exit, shape (r,), in the starts' unit (inf: none).
    """
    ray, tail, head = _ray_segment_pairs(starts, directions, loops, near)
    (dx, dy), (sx, sy) = directions[ray].T, starts[ray].T
    side = [dx * (p[:, 1] - sy) - dy * (p[:, 0] - sx) for p in (tail, head)]  # > 0: left
    along = [dx * (p[:, 0] - sx) + dy * (p[:, 1] - sy) for p in (tail, head)]
    exits = (side[0] < 0) & (side[1] >= 0)          # right -> left: leaving the material
    crossing = exits | ((side[0] >= 0) & (side[1] < 0))
    fraction = side[0][crossing] / (side[0][crossing] - side[1][crossing])
    at = np.where(fraction == 1.0, along[1][crossing],
                  along[0][crossing] + fraction * (along[1][crossing] - along[0][crossing]))
    ray, exits = ray[crossing][at > near], exits[crossing][at > near]
    at = at[at > near]
    order = np.lexsort((exits, at, ray))              # by ray, distance, entries first
    ray, at, count = ray[order], at[order], np.cumsum(np.where(exits[order], 1, -1))
    first_of_ray = np.searchsorted(ray, ray)          # the rays' own sums start at 0
    count -= np.where(first_of_ray > 0, count[first_of_ray - 1], 0)
    out = count == 1
    rays, first = np.unique(ray[out], return_index=True)
    found = np.full(len(starts), np.inf)
    found[rays] = at[out][first]
    return found


RUN = 16  # segments per bounding circle in ``first_exits``


def _ray_segment_pairs(starts, directions, loops, near):
    """(ray, segment tail, segment head) of every segment in a run of ``RUN`` whose bounding
    circle the ray's half-line beyond ``near`` meets (margin ``near``)."""
    tails = np.vstack(loops)
    heads = np.vstack([np.roll(loop, -1, axis=0) for loop in loops])
    begin = np.arange(0, len(tails), RUN)
    centre = np.add.reduceat(tails, begin) / np.diff(np.append(begin, len(tails)))[:, None]
    own = np.repeat(centre, RUN, axis=0)[:len(tails)]   # each segment's run's centre
    reach = np.maximum(np.hypot(*(tails - own).T), np.hypot(*(heads - own).T))
    radius = np.maximum.reduceat(reach, begin) * (1 + 1e-9) + near
    offset = centre[None, :, :] - starts[:, None, :]
    across = np.abs(directions[:, None, 0] * offset[..., 1]
                    - directions[:, None, 1] * offset[..., 0])
    ahead = np.einsum("rgk,rk->rg", offset, directions)
    ray, run = np.nonzero((across <= radius) & (ahead >= near - radius))
    size = np.minimum(begin[run] + RUN, len(tails)) - begin[run]
    ray = np.repeat(ray, size)
    segment = (np.repeat(begin[run], size) + np.arange(size.sum())
               - np.repeat(np.cumsum(size) - size, size))
    return ray, tails[segment], heads[segment]


@dataclass(frozen=True)
class Wall:
    """Signed distance to an outline from dense samples: the distance to the nearest sample,
    inside where the offset from it points along its inward normal.

    Parameters
    ----------
    samples : numpy.ndarray
        Dense points along the outline, shape (n, 2) [m].
    normals : numpy.ndarray
        The inward unit normal at each sample [-].
    tree : scipy.spatial.cKDTree
        The samples' search tree.
    """

    samples: np.ndarray
    normals: np.ndarray
    tree: object

    @classmethod
    def of(cls, loops: list[np.ndarray], spacing: float) -> Wall:
        dense = [resample_loop(loop, spacing) for loop in loops]
        samples = np.vstack(dense)
        return cls(samples, np.vstack([vertex_normals(d) for d in dense]), cKDTree(samples))

    def distance(self, points: np.ndarray, beyond: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
        """(distance, inside) of each point; points farther than ``beyond`` get an infinite
        distance and count as outside (a bounded search is much faster)."""
        gap, nearest = self.tree.query(points, distance_upper_bound=beyond)
        found = np.isfinite(gap)
        offset = points[found] - self.samples[nearest[found]]
        inside = np.zeros(len(points), bool)
        inside[found] = np.einsum("ij,ij->i", offset, self.normals[nearest[found]]) > 0
        return gap, inside


def triangle_areas(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The area of each triangle (half the cross product of two sides).

    Parameters
    ----------
    points : numpy.ndarray
        The mesh's nodes [m], one row (x, y) each.
    triangles : numpy.ndarray
        Each triangle's three node indices.

    Returns
    -------
    numpy.ndarray
        The areas [m^2], shape (m,).
    """
    a, b, c = (points[triangles[:, k]] for k in range(3))
    return 0.5 * np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])


def unique_edges(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(edges (e, 2) sorted, (m, 3) edge of each triangle side k = (k, k+1)).

    Parameters
    ----------
    triangles : numpy.ndarray
        The mesh's triangles as node triples, shape (m, 3).

    Returns
    -------
    edges : numpy.ndarray
        The distinct edges, each (low, high) vertex index, sorted.
    side_edge : numpy.ndarray
        The index into ``edges`` of each triangle's side k, shape (m, 3).
    """
    sides = np.sort(np.stack([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]],
                             axis=1).reshape(-1, 2), axis=1)
    edges, inverse = np.unique(sides, axis=0, return_inverse=True)
    return edges, inverse.reshape(-1, 3)


def circumcentres(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Centre of each triangle's circumscribed circle (intersection of the perpendicular
    bisectors, in coordinates relative to the first vertex).

    Parameters
    ----------
    points : numpy.ndarray
        Node coordinates [m], shape (n, 2).
    triangles : numpy.ndarray
        The node triples of the triangles whose circles are wanted.

    Returns
    -------
    numpy.ndarray
        The circumcentres [m], shape (m, 2).
    """
    a, b, c = (points[triangles[:, k]] for k in range(3))
    (bx, by), (cx, cy) = (b - a).T, (c - a).T
    twice = 2.0 * (bx * cy - by * cx)
    b2, c2 = bx * bx + by * by, cx * cx + cy * cy
    return a + np.column_stack([cy * b2 - by * c2, bx * c2 - cx * b2]) / twice[:, None]


def centre_offsets(points: np.ndarray, triangles: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """(m, 3) signed distance from each triangle's circumcentre to its side k, positive
    towards the triangle's interior (the triangle's half of the dual edge).

    Parameters
    ----------
    points : numpy.ndarray
        Where the nodes lie [m].
    triangles : numpy.ndarray
        The triangles, by their nodes.
    centres : numpy.ndarray
        The triangles' circumcentres [m], shape (m, 2).

    Returns
    -------
    numpy.ndarray
        The signed distances [m], shape (m, 3).
    """
    out = np.empty(triangles.shape)
    for k in range(3):
        a, b, c = (points[triangles[:, (k + j) % 3]] for j in range(3))
        edge = b - a
        normal = np.column_stack([-edge[:, 1], edge[:, 0]]) / np.hypot(*edge.T)[:, None]
        side = np.sign(np.einsum("ij,ij->i", c - a, normal))
        out[:, k] = np.einsum("ij,ij->i", centres - 0.5 * (a + b), normal) * side
    return out


def drop_unused(points: np.ndarray, triangles: np.ndarray):
    """(points, triangles, used): the points some triangle uses, triangles renumbered, and
    the old index of each kept point.

    Parameters
    ----------
    points : numpy.ndarray
        All candidate points [m], some perhaps in no triangle.
    triangles : numpy.ndarray
        The triangles, indexing ``points``.

    Returns
    -------
    points : numpy.ndarray
        The used points [m].
    triangles : numpy.ndarray
        The triangles renumbered to them.
    used : numpy.ndarray
        The old index of each kept point.
    """
    used = np.unique(triangles)
    renumber = np.full(len(points), -1)
    renumber[used] = np.arange(used.size)
    return points[used], renumber[triangles], used
