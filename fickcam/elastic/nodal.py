"""A piecewise-linear field on a triangle mesh, refined without changing it.

The plane model solves a drawn part's moisture with P1 elements on its own graded mesh
(``fickcam.diffusion.planform.triangles``). Its free displacement is solved on that mesh,
refined: every element of the refined mesh lies in one element of the field's, so the
free strain is exactly the engine's field, linear on each element, and its kinks lie on
element edges. A field read at points of an unrelated mesh would instead put the kinks
(and the edge layer, rows of a few hundredths of a millimetre at early ages) inside the
elements, and the displacement would converge only once the mesh resolved them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from .corners import ROUNDS, SPLIT_ABOVE, target_sizes
from .fem import refined_triangles


@dataclass(frozen=True, eq=False)
class NodalField:
    """A P1 field at the nodes of a triangle mesh, at each of several times.

    Parameters
    ----------
    points : numpy.ndarray
        The nodes [m], shape (n, 2).
    triangles : numpy.ndarray
        Three node indices per triangle, shape (m, 3).
    values : numpy.ndarray
        The field at the nodes at each time (any unit), shape (times, n).
    """

    points: np.ndarray
    triangles: np.ndarray
    values: np.ndarray

    def longest_edges(self) -> np.ndarray:
        """Each triangle's longest edge [m], shape (m,)."""
        corners = self.points[self.triangles]
        return np.max([np.hypot(*(corners[:, i] - corners[:, i - 1]).T) for i in range(3)],
                      axis=0)

    def refined(self, triangles=None) -> "NodalField":
        """The same field on a finer mesh: every triangle split in four (``triangles``
        None), or those listed and what conformity asks of their neighbours
        (scikit-fem's red-green-blue refinement). The new nodes are edge midpoints, where
        a P1 field is its edge's mean: the field is the same function.

        Parameters
        ----------
        triangles : array_like of int, optional
            The triangles to split; None: all.

        Returns
        -------
        NodalField
            The field on the refined mesh, its first nodes this mesh's.
        """
        points, finer, edges = refined_triangles(self.points, self.triangles, triangles)
        new = points[len(self.points):]
        gap, edge = cKDTree(self.points[edges].mean(axis=0)).query(new)
        if len(new) and gap.max() > 1e-9 * np.ptp(self.points, axis=0).max():
            raise ValueError("a refined mesh's new node is not an edge's midpoint")
        ends = edges[:, edge]
        values = np.hstack([self.values, 0.5 * (self.values[:, ends[0]] + self.values[:, ends[1]])])
        return NodalField(points, finer, values)

    def graded_toward(self, corners, radius: float, order: int) -> "NodalField":
        """The same field on a mesh graded toward re-entrant corners
        (:func:`fickcam.elastic.corners.target_sizes`): triangles split until each is at
        most ``SPLIT_ABOVE`` times its target size; the size at the graded zone's edge is
        this mesh's longest edge within it.

        Parameters
        ----------
        corners : list of tuple
            (corner [m], Williams exponent [-]) (:func:`fickcam.elastic.corners.reentrant_corners`).
        radius : float
            The graded zone's radius [m].
        order : int
            The elements' order p the grading serves.

        Returns
        -------
        NodalField
            The field on the graded mesh (this one where there is no corner).
        """
        field = self
        near = np.min([np.hypot(*(self.points[self.triangles].mean(axis=1) - c).T)
                       for c, _ in corners], axis=0) < radius if corners else []
        if not np.any(near):
            return field
        size = float(self.longest_edges()[near].max())
        for _ in range(ROUNDS):
            centroids = field.points[field.triangles].mean(axis=1)
            split = np.flatnonzero(field.longest_edges()
                                   > SPLIT_ABOVE * target_sizes(centroids, corners, size, radius, order))
            if not len(split):
                break
            field = field.refined(split)
        return field
