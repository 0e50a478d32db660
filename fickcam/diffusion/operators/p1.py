"""The P1 finite-element operator of the in-plane problem on a triangle mesh (``triangles``).

Kept by measurement (docs/architecture.md, "The in-plane operator"): FiPy's two-point flux between
triangle centroids is not consistent on such a mesh (measured on a graded disc: relative
uptake error ~0.08 g that does not fall with h0), and on the same mesh made
Delaunay-admissible (``prisms.planar``, circumcentre cell points) it is second order
but 4-6x less accurate than P1 on 2.2x the unknowns: FiPy needs 11-50x P1's CPU time
for the same accuracy on the demo cam and a link. The P1 Galerkin method is: stiffness
by the cotangent formula K_jk = -(cot a_jk + cot b_jk) / 2 over the angles opposite edge jk (Duffin 1959;
Pinkall & Polthier 1993; with a lumped mass it is the vertex-centred finite volume
scheme on the Voronoi cells, MacNeal 1953), consistent mass M_jk = |T| (1 + delta_jk) / 12
per triangle, the outline nodes held at the surface value. Its error after a step
of the boundary value is O(h^2 / t) (Thomée 2006, Galerkin Finite Element
Methods for Parabolic Problems, Theorem 3.1, non-smooth data), measured here as
a relative uptake error ~ ``error_model.MESH_ERROR`` (h0 / sqrt(tau) + ``GROWTH_REACH`` g)^2
(0.6-1.1x the error on graded discs against Crank eq. 5.23, on the demo cam and a link
against fine meshes). On a
Delaunay mesh cot a + cot b >= 0, so K is an M-matrix (Xu & Zikatanov 1999,
Math. Comp. 68, 1429-1446); the consistent mass (3x more accurate than the
lumped one here) gives up the discrete maximum principle, so early fields may
undershoot slightly (Thomée 2006 ch. 15).

References
----------
- Duffin, R. J. (1959). Distributed and lumped networks. Journal of Mathematics and Mechanics
  8(5):793-826.
- MacNeal, R. H. (1953). An asymmetrical finite difference network. Quarterly of Applied
  Mathematics 11:295-310. doi:10.1090/qam/99978
- Pinkall, U. & Polthier, K. (1993). Computing discrete minimal surfaces and their conjugates.
  Experimental Mathematics 2(1):15-36. doi:10.1080/10586458.1993.10504266
- Xu, J. & Zikatanov, L. (1999). A monotone finite element scheme for convection-diffusion
  equations. Mathematics of Computation 68(228):1429-1446. doi:10.1090/S0025-5718-99-01148-5
- Thomée, V. (2006). Galerkin Finite Element Methods for Parabolic Problems, 2nd ed. Springer
  Series in Computational Mathematics 25. doi:10.1007/3-540-33122-0
"""
from __future__ import annotations

import numpy as np
from scipy import sparse

from ..planform.polygon import triangle_areas
from ..planform.triangles import Triangulation
from ..problem.scaling import planar_scale
from .discretisation import Discretisation


def cotangent_stiffness(points: np.ndarray, triangles: np.ndarray) -> sparse.csr_matrix:
    """P1 stiffness K_jk = -(1/2) sum over the triangles at edge jk of cot(angle opposite),
    K_jj = -sum_k K_jk (Duffin 1959; Pinkall & Polthier 1993).

    Parameters
    ----------
    points : numpy.ndarray
        The nodes, shape (n, 2), in scaled coordinates [-].
    triangles : numpy.ndarray
        The triangles' node indices, shape (m, 3).

    Returns
    -------
    scipy.sparse.csr_matrix
        K, shape (n, n) [-] (the Laplacian's stiffness is scale-free in 2-D).

    References
    ----------
    Duffin (1959); Pinkall & Polthier (1993): see the module docstring.
    """
    n = len(points)
    corners = points[triangles]
    rows, cols, values = [], [], []
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        a, b = corners[:, j] - corners[:, i], corners[:, k] - corners[:, i]
        half_cot = 0.5 * np.einsum("ij,ij->i", a, b) / np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
        rows += [triangles[:, j], triangles[:, k], triangles[:, j], triangles[:, k]]
        cols += [triangles[:, k], triangles[:, j], triangles[:, j], triangles[:, k]]
        values += [-half_cot, -half_cot, half_cot, half_cot]
    return sparse.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(n, n))


def consistent_mass(points: np.ndarray, triangles: np.ndarray) -> sparse.csr_matrix:
    """P1 mass M_jk = sum over triangles |T| (1 + delta_jk) / 12.

    Parameters
    ----------
    points : numpy.ndarray
        Node coordinates, scaled [-], one row each.
    triangles : numpy.ndarray
        The elements as node triples.

    Returns
    -------
    scipy.sparse.csr_matrix
        M, shape (n, n), in the points' units squared ([-] when scaled).
    """
    n = len(points)
    local = (np.ones((3, 3)) + np.eye(3)).ravel() / 12.0
    values = triangle_areas(points, triangles)[:, None] * local[None, :]
    rows = np.repeat(triangles, 3, axis=1).ravel()
    cols = np.tile(triangles, (1, 3)).ravel()
    return sparse.csr_matrix((values.ravel(), (rows, cols)), shape=(n, n))


def p1_operator(points: np.ndarray, triangles: np.ndarray, fixed: np.ndarray, layer: np.ndarray,
                coordinates: dict[str, np.ndarray]) -> Discretisation:
    """The P1 operator on a mesh in scaled coordinates behind the interface of every mesh
    model (``discretisation.Discretisation``, marched by ``march``): backward-Euler steps
    M_ff (c_new - c_old)/dt + K_ff c_new = g f - M_fb 1 (g_new - g_old)/dt with f = -K_fb 1,
    the outline nodes (``fixed``) held at the surface value g and eliminated (Thomée 2006
    ch. 1). Its lumped form (``lumped``, the row sums of M over all nodes) is less
    accurate but monotone (M-matrix): the consistent mass undershoots while dt < h^2 / 6
    (1-D; Thomée 2006 ch. 15), fields down to -0.5 of the step at early outputs of coarse
    meshes; it serves the fields. (Lumping only the early steps spoils the accuracy for
    long after: 3.5x the error at 10 h0^2 on a link.) ``layer`` (n,): the integral
    weights of the contact layer (any scale).

    Parameters
    ----------
    points : numpy.ndarray
        The mesh's nodes in scaled coordinates [-], shape (n, 2).
    triangles : numpy.ndarray
        Node triples of the P1 elements, shape (m, 3).
    fixed : numpy.ndarray
        Bool mask (n,) of the outline nodes held at the surface value.
    layer : numpy.ndarray
        The contact layer's integral weight of each node (n,), any scale.
    coordinates : dict of str to numpy.ndarray
        Physical node coordinates [m] by axis name, each (n,).

    Returns
    -------
    Discretisation
        The operator on the free nodes, with the consistent mass and the held nodes'
        mass coupling and shares of the mean and the layer [-].

    References
    ----------
    Thomée (2006), ch. 1 and 15 (see the module docstring).
    """
    stiffness = cotangent_stiffness(points, triangles)
    mass = consistent_mass(points, triangles)
    free = ~fixed
    weights = np.asarray(mass.sum(axis=1)).ravel()  # integral of each hat function
    area, layer_total = weights.sum(), layer.sum()
    return Discretisation(
        weights[free], stiffness[free][:, free].tocsr(),
        -np.asarray(stiffness[free][:, fixed].sum(axis=1)).ravel(),
        weights[free] / area, layer[free] / layer_total,
        {name: value[free] for name, value in coordinates.items()},
        mass=mass[free][:, free].tocsr(),
        held_mass=np.asarray(mass[free][:, fixed].sum(axis=1)).ravel(),
        held_mean=float(weights[fixed].sum() / area),
        held_layer=float(layer[fixed].sum() / layer_total))


def _may_reach(corners: np.ndarray, distance, depth: float) -> np.ndarray:
    """The triangles (corners (m, 3, 2) [m]) with a point within ``depth`` [m] of the contact
    edge: a distance is 1-Lipschitz, so no point of a triangle whose centroid lies farther
    than ``depth`` + its largest centroid-to-corner distance is (kept with a 1e-9 margin:
    the samples of the others are the same as those of every triangle)."""
    centroid = corners.mean(axis=1)
    reach = np.max(np.hypot(*(corners - centroid[:, None, :]).transpose(2, 0, 1)), axis=1)
    bound = (depth + reach) * (1.0 + 1e-9)
    return distance(centroid, float(bound.max())) <= bound


def layer_weights(points: np.ndarray, triangles: np.ndarray, distance, depth: float,
                  subdivisions: int = 4) -> np.ndarray:
    """Integral of each hat function over the layer {distance(x) <= depth}: the midpoint
    rule on ``subdivisions``^2 sub-triangles of every triangle (``distance(points, bound)``
    may return inf beyond ``bound``).

    Parameters
    ----------
    points : numpy.ndarray
        The nodes, shape (n, 2) [m].
    triangles : numpy.ndarray
        The triangles' node indices, shape (m, 3).
    distance : callable
        ``distance(xy, bound)``: each point's distance to the contact edge [m].
    depth : float
        The layer's depth [m].
    subdivisions : int
        Sub-triangles per triangle edge of the midpoint rule [-].

    Returns
    -------
    numpy.ndarray
        The integral of each node's hat function over the layer [m^2], shape (n,).
    """
    n = subdivisions
    up = [(i + 1 / 3, j + 1 / 3) for i in range(n) for j in range(n - i)]
    down = [(i + 2 / 3, j + 2 / 3) for i in range(n - 1) for j in range(n - 1 - i)]
    lam = np.array(up + down) / n                                  # (q, 2) barycentric
    bary = np.column_stack([1.0 - lam.sum(axis=1), lam])            # (q, 3)
    corners = points[triangles]                                     # (m, 3, 2)
    near = _may_reach(corners, distance, depth)
    samples = np.einsum("qi,mij->mqj", bary, corners[near])         # (near, q, 2)
    within = np.zeros((len(triangles), len(bary)), bool)
    within[near] = (distance(samples.reshape(-1, 2), depth) <= depth).reshape(samples.shape[:2])
    share = triangle_areas(points, triangles)[:, None] / n ** 2 * within  # (m, q)
    weights = np.zeros(len(points))
    np.add.at(weights, triangles.ravel(), (share @ bary).ravel())
    return weights



def plane_operator(mesh: Triangulation, part, layer_depth: float, d) -> Discretisation:
    """P1 finite elements of the in-plane problem in scaled coordinates (``triangles``), the
    outline nodes held at the surface value; layer: the integrals of the hat functions
    over the band within ``layer_depth`` of the contact edge (at least the first row).

    Parameters
    ----------
    mesh : Triangulation
        The planform's triangle mesh [m] (``triangles.triangulate``).
    part : CamPlate or LinkBar
        The part; its thickness [m] scales the coordinates.
    layer_depth : float
        The contact layer's depth [m].
    d : sequence of float
        D0 along x, y, z [m^2/s].

    Returns
    -------
    Discretisation
        The P1 operator in scaled coordinates, node coordinates ``x``, ``y`` [m].
    """
    depth = max(layer_depth, 1.0001 * float(mesh.contact_distance.min()))
    layer = layer_weights(mesh.points, mesh.triangles, mesh.contact, depth)
    scaled = mesh.points * np.asarray(planar_scale(part, d))[None, :]
    coordinates = {"x": mesh.points[:, 0], "y": mesh.points[:, 1]}
    return p1_operator(scaled, mesh.triangles, mesh.on_outline, layer, coordinates)

