r"""Means of a planform's cell values over the part and over its contact band, corrected
to second order for where each cell's value sits.

On the admissible cells (``admissible``) the finite-volume value of cell K approximates u at
its circumcentre x_K, not its mean (Eymard, Gallouet & Herbin 2000, Handbook of
Numerical Analysis VII, §9: the two-point flux is consistent because x_K is the
circumcentre). Over a region R of the cell (the whole cell, or its part within the
contact band), the Taylor expansion about x_K gives

.. math::

    \int_R u\, dA = |R|\, u(x_K) + \nabla u(x_K) \cdot \big(|R| (c_R - x_K)\big)
    + O(h^2 |R|),

c_R the centroid of R. Summing |R| u_K alone (the plain weights) leaves the first-order
term, which does not cancel where the cells are graded (their circumcentres lean one
way) and which the layer, a band only a few cells deep, feels most: on a circular plate
the band's unit-step response erred 2.3e-2 after delta^2/D on 15 000 cells, 2e-4 with
the term. The gradient is the least-squares fit to the neighbours' values and to the
surface value at the midpoints of the exposed sides (Barth 1991, AIAA 91-1548; Blazek
2015, Computational Fluid Dynamics, §5.3.4), linear in the cell values, so the corrected
mean is again a fixed vector of weights on them (``corrected_weights``).

References
----------
- Eymard, R., Gallouët, T. & Herbin, R. (2000). Finite volume methods. Handbook of Numerical
  Analysis VII:713-1020. doi:10.1016/S1570-8659(00)07005-8
- Barth, T. J. (1991). A 3-D upwind Euler solver for unstructured meshes. AIAA Paper 91-1548.
  doi:10.2514/6.1991-1548
- Blazek, J. (2015). Computational Fluid Dynamics: Principles and Applications, 3rd ed.
  Butterworth-Heinemann. doi:10.1016/C2013-0-19038-1
"""
from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.spatial import cKDTree

from ..problem.curves import segment_distance
from .polygon import unique_edges


def _triangle(a, b, c) -> tuple[np.ndarray, np.ndarray]:
    """(area, first moment area x centroid) of triangles a b c, each (m, 2)."""
    area = 0.5 * np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    return area, area[:, None] * (a + b + c) / 3.0


def _share(numerator, denominator) -> np.ndarray:
    return np.clip(np.divide(numerator, denominator, out=np.zeros_like(numerator),
                             where=denominator > 0), 0.0, 1.0)


def sublevel_moments(corners: np.ndarray, values: np.ndarray, level: float):
    """(area, first moment) of the part of each triangle (``corners`` (m, 3, 2)) where the
    linear interpolant of its vertex ``values`` (m, 3) is <= ``level``: with sorted values
    v1 <= v2 <= v3, the corner triangle at v1 cut at ``level`` (level <= v2), else the
    whole minus the corner triangle at v3 (the cuts of ``admissible.linear_sublevel_fraction``).

    Parameters
    ----------
    corners : numpy.ndarray
        The triangles' corners, shape (m, 3, 2) [m].
    values : numpy.ndarray
        The function at the corners, shape (m, 3) (a distance [m]).
    level : float
        The level, in the values' unit [m].

    Returns
    -------
    area : numpy.ndarray
        The sublevel part's area of each triangle [m^2].
    moment : numpy.ndarray
        Its first moment, area x centroid [m^3], shape (m, 2).
    """
    order = np.argsort(values, axis=1)
    v = np.take_along_axis(values, order, axis=1)
    p = np.take_along_axis(corners, order[:, :, None], axis=1)
    whole_area, whole_moment = _triangle(p[:, 0], p[:, 1], p[:, 2])
    s12 = _share(level - v[:, 0], v[:, 1] - v[:, 0])[:, None]
    s13 = _share(level - v[:, 0], v[:, 2] - v[:, 0])[:, None]
    r31 = _share(v[:, 2] - level, v[:, 2] - v[:, 0])[:, None]
    r32 = _share(v[:, 2] - level, v[:, 2] - v[:, 1])[:, None]
    low = _triangle(p[:, 0], p[:, 0] + s12 * (p[:, 1] - p[:, 0]), p[:, 0] + s13 * (p[:, 2] - p[:, 0]))
    high = _triangle(p[:, 2], p[:, 2] + r31 * (p[:, 0] - p[:, 2]), p[:, 2] + r32 * (p[:, 1] - p[:, 2]))
    below, none, every = level <= v[:, 1], level <= v[:, 0], level >= v[:, 2]
    area = np.where(below, low[0], whole_area - high[0])
    moment = np.where(below[:, None], low[1], whole_moment - high[1])
    area = np.where(none, 0.0, np.where(every, whole_area, area))
    moment = np.where(none[:, None], 0.0, np.where(every[:, None], whole_moment, moment))
    return area, moment


def _links(tess):
    """(cell i, cell j or -1 for the surface, offset x_j - x_i): each side between two
    cells both ways, and each exposed outline side (not a mirror line) at its midpoint."""
    edges, side = unique_edges(tess.triangles)
    edge, owner = side.ravel(), np.repeat(tess.cell_of, 3)
    order = np.argsort(edge, kind="stable")
    edge, owner = edge[order], owner[order]
    count = np.bincount(edge, minlength=len(edges))
    first = np.searchsorted(edge, np.arange(len(edges)))
    inner = np.flatnonzero(count == 2)
    a, b = owner[first[inner]], owner[first[inner] + 1]
    a, b = a[a != b], b[a != b]
    outer = np.flatnonzero(count == 1)
    on_mirror = np.zeros(outer.size, bool)
    for axis, value in tess.mirrors:
        on_mirror |= np.all(tess.points[edges[outer]][:, :, axis] == value, axis=1)
    outer = outer[~on_mirror]
    cell = owner[first[outer]]
    middle = 0.5 * (tess.points[edges[outer, 0]] + tess.points[edges[outer, 1]])
    centre = tess.centres
    return (np.concatenate([a, b, cell]), np.concatenate([b, a, np.full(cell.size, -1)]),
            np.concatenate([centre[b] - centre[a], centre[a] - centre[b], middle - centre[cell]]))


def gradient_matrix(tess) -> sparse.csr_matrix:
    """(2 cells, cells): rows 2i, 2i + 1 the least-squares gradient of cell i from the
    values at its neighbours' circumcentres and 0 (the surface value of an unsaturated
    fraction) at its exposed sides' midpoints (module docstring).

    Parameters
    ----------
    tess : Tessellation
        The planform's admissible cells, stretched coordinates [m].

    Returns
    -------
    scipy.sparse.csr_matrix
        The gradient operator [1/m], shape (2 cells, cells).

    References
    ----------
    Barth (1991); Blazek (2015), §5.3.4 (see the module docstring).
    """
    i, j, offset = _links(tess)
    normal = np.zeros((tess.cells, 2, 2))
    np.add.at(normal, i, offset[:, :, None] * offset[:, None, :])
    # pinv: a cell whose links lie along one line gets no gradient across it
    coefficient = np.einsum("kab,kb->ka", np.linalg.pinv(normal)[i], offset)
    neighbour = j >= 0
    rows = np.concatenate([2 * i[neighbour], 2 * i[neighbour] + 1, 2 * i, 2 * i + 1])
    cols = np.concatenate([j[neighbour], j[neighbour], i, i])
    values = np.concatenate([coefficient[neighbour, 0], coefficient[neighbour, 1],
                             -coefficient[:, 0], -coefficient[:, 1]])
    return sparse.csr_matrix((values, (rows, cols)), shape=(2 * tess.cells, tess.cells))


def contact_distance(tess, depth: float) -> np.ndarray:
    """Distance (physical m) of each mesh point to the contact edge, exact at the corners of
    every triangle that can reach within ``depth`` of it (the band's cuts interpolate them),
    2 x that reach elsewhere (only that it exceeds ``depth`` matters): a point within
    ``depth`` of a segment is within ``depth`` + half its length of its midpoint.

    Parameters
    ----------
    tess : Tessellation
        The planform's admissible cells, stretched coordinates [m].
    depth : float
        The contact layer's depth [m].

    Returns
    -------
    numpy.ndarray
        The distance of each point [m] (exact near the band, 2 x the reach elsewhere).
    """
    points = tess.physical(tess.points)
    segments = tess.physical(tess.contact.reshape(-1, 2)).reshape(-1, 2, 2)
    reach = depth + 0.5 * float(np.max(np.hypot(*(segments[:, 1] - segments[:, 0]).T)))
    near = cKDTree(segments.mean(axis=1)).query(points, distance_upper_bound=reach)[0] <= reach
    corners = np.zeros(len(points), bool)
    corners[tess.triangles[np.any(near[tess.triangles], axis=1)].ravel()] = True
    distance = np.full(len(points), 2.0 * reach)
    distance[corners] = segment_distance(points[corners], segments)
    return distance


def corrected_weights(tess, depth: float) -> tuple[np.ndarray, np.ndarray]:
    """(mean, layer) weights on the cell values: sum_K |R_K| u_K + grad u_K . |R_K| (c_K -
    x_K) over the whole cells and over their parts within ``depth`` (physical m) of the
    contact edge, each divided by its region's area (module docstring).

    Parameters
    ----------
    tess : Tessellation
        The cells whose values the weights multiply (stretched points [m]).
    depth : float
        How deep the band under the contact edge reaches [m].

    Returns
    -------
    mean : numpy.ndarray
        Weights [-] giving the planform mean from the cell values.
    layer : numpy.ndarray
        Weights [-] giving the mean over the band within ``depth`` of the contact edge.
    """
    corners = tess.points[tess.triangles]
    distance = contact_distance(tess, depth)
    whole = _triangle(corners[:, 0], corners[:, 1], corners[:, 2])
    band = sublevel_moments(corners, distance[tess.triangles], depth)
    gradient = gradient_matrix(tess)
    weights = []
    for area, moment in (whole, band):
        cell_area = np.bincount(tess.cell_of, area, minlength=tess.cells)
        cell_moment = np.stack([np.bincount(tess.cell_of, moment[:, k], minlength=tess.cells)
                                for k in range(2)], axis=1)
        lever = cell_moment - cell_area[:, None] * tess.centres
        weights.append((cell_area + gradient.T @ lever.ravel()) / cell_area.sum())
    return weights[0], weights[1]
