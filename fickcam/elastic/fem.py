r"""Plane-stress linear elasticity on a triangle mesh with scikit-fem (the only module
that imports skfem).

Constitutive law in Voigt form (xx, yy, engineering xy): sigma = Q (eps - eps*), with the
reduced (plane-stress) stiffness of an orthotropic ply whose axis 1 is x,

.. math::

    Q_{11} = \frac{E_1}{1 - \nu_{12} \nu_{21}}, \quad Q_{22} = \frac{E_2}{1 - \nu_{12} \nu_{21}},
    \quad Q_{12} = \frac{\nu_{12} E_2}{1 - \nu_{12} \nu_{21}}, \quad Q_{66} = G_{12},
    \quad \nu_{21} = \nu_{12} \frac{E_2}{E_1}

(Jones, Mechanics of Composite Materials, 2nd ed. 1999, eq. 2.61)

(isotropic and quasi-isotropic: E1 = E2, G12 = E / (2 (1 + nu))). The weak form of
equilibrium in a plate of thickness t (Zienkiewicz & Taylor, The Finite Element Method
vol. 1, 6th ed. 2005, eq. 6.12 and ch. 4 for the initial strain eps*):

.. math::

    t \int B(v)^T Q\, B(u)\, dA = t \int B(v)^T Q\, \varepsilon^*\, dA
    + t \oint v \cdot \text{traction}\, ds,

with Lagrange P1 or P2 elements. Displacements then converge in L2 as h^(p+1) for smooth
solutions on a domain the mesh represents (Ciarlet 1978, Theorem 3.2.5); a curved edge
approximated by straight chords adds O(h^2) (Strang & Fix 1973 sec. 4.4), so P2 on a
polygonal circle converges as h^2 in general (h^3 where the boundary is straight).
"""
from __future__ import annotations

import functools
import logging
from dataclasses import dataclass, field

import numpy as np
from scipy import sparse
from scipy.sparse.linalg import splu

import skfem
from skfem.helpers import sym_grad

from ..materials.micromechanics import reduced_stiffness
from ..messages import quieter


def _quiet_skfem(method):
    """``method`` with scikit-fem's logger at WARNING at least while it runs (it logs each
    mesh, basis and assembly at INFO), restored after: importing this module leaves
    scikit-fem's logging as it was."""
    @functools.wraps(method)
    def quiet(*args, **kwargs):
        with quieter("skfem", logging.WARNING):
            return method(*args, **kwargs)
    return quiet


def stiffness_matrix(e1, e2, g12, nu12) -> np.ndarray:
    """Plane-stress Q (3 x 3, Voigt xx, yy, xy) of an orthotropic ply, axis 1 = x: the
    reduced stiffnesses (``materials.micromechanics.reduced_stiffness``, Jones 1999 eq.
    2.61) as a matrix; arrays broadcast (shape (3, 3, ...)).

    Parameters
    ----------
    e1, e2 : float or array_like
        The Young's moduli along the axes 1 (= x) and 2 [Pa].
    g12 : float or array_like
        The in-plane shear modulus [Pa].
    nu12 : float or array_like
        The major Poisson's ratio [-].

    Returns
    -------
    numpy.ndarray
        Q [Pa], shape (3, 3, ...).
    """
    q11, q22, q12, q66 = reduced_stiffness(*(np.asarray(v, float) for v in (e1, e2, g12, nu12)))
    zero = 0.0 * q11
    return np.array([[q11, q12, zero],
                     [q12, q22, zero],
                     [zero, zero, q66 + zero]])


def isotropic_stiffness(e, nu) -> np.ndarray:
    """Plane-stress Q of an isotropic material (E1 = E2 = E, G = E / (2 (1 + nu))).

    Parameters
    ----------
    e : float or array_like
        Young's modulus [Pa].
    nu : float or array_like
        Poisson's ratio [-].

    Returns
    -------
    numpy.ndarray
        Q [Pa], shape (3, 3, ...).
    """
    shear = np.asarray(e, float) / (2.0 * (1.0 + np.asarray(nu, float)))
    return stiffness_matrix(e, e, shear, nu)


def _voigt(eps) -> tuple:
    """(eps_xx, eps_yy, gamma_xy) of a symmetric strain field."""
    return eps[0, 0], eps[1, 1], 2.0 * eps[0, 1]


def _stress_of(q, strain) -> tuple:
    """Q strain in Voigt form; q (3, 3, ...) indexable as q[i][j]."""
    return tuple(sum(q[i][j] * strain[j] for j in range(3)) for i in range(3))


_UPPER = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))


def _q_of(w) -> tuple:
    """The symmetric Q from the six form arguments q00 ... q22 (each (elements, points))."""
    c = {(i, j): getattr(w, f"q{i}{j}") for i, j in _UPPER}
    return tuple(tuple(c[min(i, j), max(i, j)] for j in range(3)) for i in range(3))


@skfem.BilinearForm
def _stiffness_form(u, v, w):
    su = _stress_of(_q_of(w), _voigt(sym_grad(u)))
    ev = _voigt(sym_grad(v))
    return w.t * sum(s * e for s, e in zip(su, ev))


@skfem.LinearForm
def _eigenstrain_form(v, w):
    s_star = _stress_of(_q_of(w), (w.exx, w.eyy, w.gxy))
    ev = _voigt(sym_grad(v))
    return w.t * sum(s * e for s, e in zip(s_star, ev))


def _per_point(values, basis) -> np.ndarray:
    """A scalar, per-element (n_elements,) or per-point (n_elements, n_points) array as
    (n_elements, n_points) for skfem's forms."""
    values = np.asarray(values, float)
    shape = (basis.mesh.t.shape[1], basis.X.shape[-1])
    if values.ndim == 1 and values.size == shape[0]:
        values = values[:, None]
    return np.broadcast_to(values, shape)


def _q_field(q, basis) -> np.ndarray:
    """Q as a (3, 3, n_elements, n_points) view of (3, 3), (3, 3, n_elements) or
    (3, 3, n_elements, n_points)."""
    q = np.asarray(q, float)
    q = q.reshape(q.shape + (1,) * (4 - q.ndim)) if q.ndim < 4 else q
    return np.broadcast_to(q, (3, 3, basis.mesh.t.shape[1], basis.X.shape[-1]))


def _q_arguments(q, basis) -> dict:
    """The six independent entries of Q as contiguous (elements, points) form arguments."""
    field_ = _q_field(q, basis)
    return {f"q{i}{j}": np.ascontiguousarray(field_[i, j]) for i, j in _UPPER}


@dataclass
class PlaneElasticity:
    """A plane-stress model on ``points`` (n, 2) / ``triangles`` (m, 3), thickness ``t`` (m),
    Lagrange elements of ``order`` 1 or 2. Nodal fields (moisture) are P1 on ``points``.

    Parameters
    ----------
    points : numpy.ndarray
        Vertices, shape (n, 2) [m].
    triangles : numpy.ndarray
        Vertex indices, shape (m, 3).
    thickness : float
        The plate's thickness [m].
    order : int
        Lagrange element order (1 or 2).

    Attributes
    ----------
    mesh, basis : object
        Built from the above (scikit-fem mesh and vector basis).
    """

    points: np.ndarray
    triangles: np.ndarray
    thickness: float
    order: int = 2
    mesh: object = field(init=False, repr=False)
    basis: object = field(init=False, repr=False)

    @_quiet_skfem
    def __post_init__(self):
        self.mesh = skfem.MeshTri(np.asarray(self.points, float).T.copy(),
                                  np.asarray(self.triangles, np.int64).T.copy())
        scalar = skfem.ElementTriP2() if self.order == 2 else skfem.ElementTriP1()
        self.basis = skfem.Basis(self.mesh, skfem.ElementVector(scalar), intorder=2 * self.order)
        self._p1 = skfem.Basis(self.mesh, skfem.ElementTriP1(), intorder=2 * self.order)

    # ------------------------------------------------------------ pieces
    @property
    def dofs(self) -> int:
        return self.basis.N

    @_quiet_skfem
    def stiffness(self, q) -> sparse.csr_matrix:
        """K for Q constant, per element or per quadrature point."""
        return _stiffness_form.assemble(self.basis, t=self.thickness, **_q_arguments(q, self.basis))

    def nodal_at_points(self, nodal) -> np.ndarray:
        """A P1 nodal field at the quadrature points, (n_elements, n_points)."""
        return np.asarray(self._p1.interpolate(np.asarray(nodal, float)))

    @_quiet_skfem
    def eigenstrain_load(self, q, strain) -> np.ndarray:
        """Load vector of the free strain eps* = (exx, eyy, gxy), each a scalar or an array
        per element / per quadrature point."""
        exx, eyy, gxy = (_per_point(s, self.basis) for s in strain)
        return _eigenstrain_form.assemble(self.basis, t=self.thickness, exx=exx, eyy=eyy, gxy=gxy,
                                          **_q_arguments(q, self.basis))

    @_quiet_skfem
    def boundary_facets(self, keep) -> np.ndarray:
        """Boundary facets whose midpoints (2, k) satisfy ``keep(x, y)``."""
        facets = self.mesh.boundary_facets()
        mid = self.mesh.p[:, self.mesh.facets[:, facets]].mean(axis=1)
        return facets[keep(mid[0], mid[1])]

    @_quiet_skfem
    def facet_dofs(self, facets) -> np.ndarray:
        return self.basis.get_dofs(facets).flatten()

    @_quiet_skfem
    def traction_operator(self, facets):
        """(points (q, 2), normals (q, 2), weights (q,), P (dofs x 2q)) on the facets: a
        traction (tx, ty) at the facet quadrature points gives the load P @ [tx; ty]
        (thickness included)."""
        fb = skfem.FacetBasis(self.mesh, self.basis.elem, facets=facets, intorder=2 * self.order + 2)
        dx = fb.dx.ravel() * self.thickness
        n_q = dx.size
        rows, cols, vals = [], [], []
        for i in range(fb.Nbfun):
            phi = np.asarray(fb.basis[i][0])  # (2, facets, points)
            dof = np.repeat(fb.element_dofs[i], fb.dx.shape[1])
            for c in range(2):
                rows.append(dof)
                cols.append(c * n_q + np.arange(n_q))
                vals.append(phi[c].ravel() * dx)
        matrix = sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                   shape=(self.dofs, 2 * n_q))
        x, y = np.asarray(fb.global_coordinates())
        nx, ny = np.asarray(fb.normals)
        points = np.column_stack([x.ravel(), y.ravel()])
        normals = np.column_stack([nx.ravel(), ny.ravel()])
        return points, normals, fb.dx.ravel(), matrix

    # ------------------------------------------------------------ solving
    def factorise(self, k, held: np.ndarray):
        """A solver ``solve(f, values=0)``: u with the dofs ``held`` at ``values`` (one LU
        factorisation, many loads; f may hold one load per column)."""
        held = np.asarray(held, int)
        free = np.setdiff1d(np.arange(self.dofs), held)
        k = k.tocsr()
        lu = splu(k[free][:, free].tocsc(), permc_spec="MMD_AT_PLUS_A",
                  options={"SymmetricMode": True})  # K is symmetric: less fill
        coupling = k[free][:, held]

        def solve(f, values=0.0):
            f = np.asarray(f, float)
            u = np.zeros(f.shape)
            shape = (held.size,) + f.shape[1:]
            u[held] = np.broadcast_to(np.asarray(values, float), shape)
            u[free] = lu.solve(np.ascontiguousarray(f[free] - coupling @ u[held]))
            return u
        return solve

    def statically_determinate_support(self) -> np.ndarray:
        """Three dofs (3-2-1) that stop the rigid-body motion of a free plate without
        reacting to a self-equilibrated load: ux, uy at the node nearest the centroid
        and the normal displacement at the node farthest from it."""
        p = self.mesh.p
        centre = p.mean(axis=1, keepdims=True)
        d = np.hypot(*(p - centre))
        a, b = int(np.argmin(d)), int(np.argmax(d))
        nodal = self.basis.nodal_dofs  # (2, n_nodes)
        dx, dy = p[:, b] - p[:, a]
        direction = 1 if abs(dx) >= abs(dy) else 0  # hold the component across the a-b line
        return np.array([nodal[0, a], nodal[1, a], nodal[direction, b]])

    def component(self) -> np.ndarray:
        """0 for an x dof, 1 for a y dof."""
        comp = np.zeros(self.dofs, int)
        comp[self.basis.nodal_dofs[1]] = 1
        if self.order == 2:
            comp[self.basis.facet_dofs[1]] = 1
        return comp

    def without_rigid_motion(self, u) -> np.ndarray:
        """u minus its least-squares rigid-body part (translation and small rotation) fitted
        at the vertices: the displacement of a free body in its own frame."""
        x, y = self.mesh.p
        ux, uy = u[self.basis.nodal_dofs[0]], u[self.basis.nodal_dofs[1]]
        xc, yc = x - x.mean(), y - y.mean()
        rotation = np.sum(xc * (uy - uy.mean()) - yc * (ux - ux.mean())) / np.sum(xc ** 2 + yc ** 2)
        cx, cy = self.basis.doflocs[0] - x.mean(), self.basis.doflocs[1] - y.mean()
        rigid = np.where(self.component() == 0, ux.mean() - rotation * cy, uy.mean() + rotation * cx)
        return np.asarray(u, float) - rigid

    # ------------------------------------------------------------ results
    @_quiet_skfem
    def strain(self, u) -> tuple:
        """(exx, eyy, gxy) at the quadrature points, each (n_elements, n_points)."""
        field_ = self.basis.interpolate(u)
        return tuple(np.asarray(e) for e in _voigt(sym_grad(field_)))

    @_quiet_skfem
    def stress(self, u, q, free_strain=(0.0, 0.0, 0.0)) -> np.ndarray:
        """sigma = Q (eps - eps*) at the quadrature points, (3, n_elements, n_points)."""
        eps = self.strain(u)
        star = tuple(_per_point(s, self.basis) for s in free_strain)
        qf = _q_field(q, self.basis)
        return np.array(_stress_of(qf, tuple(e - s for e, s in zip(eps, star))))

    @_quiet_skfem
    def strain_operator(self):
        """(E, centroids): the sparse map from dofs to the strains (exx, eyy, gxy) at the
        element centroids, rows [exx of every element; eyy ...; gxy ...], and the centroids
        (n_elements, 2). Many load cases at once: strains = E @ U."""
        centre = skfem.Basis(self.mesh, self.basis.elem, intorder=1)
        n = self.mesh.t.shape[1]
        rows, cols, vals = [], [], []
        for i in range(centre.Nbfun):
            grad = np.asarray(centre.basis[i][0].grad)[..., 0]  # (2, 2, elements)
            parts = (grad[0, 0], grad[1, 1], grad[0, 1] + grad[1, 0])
            for c, value in enumerate(parts):
                rows.append(c * n + np.arange(n))
                cols.append(centre.element_dofs[i])
                vals.append(value)
        matrix = sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                   shape=(3 * n, self.dofs))
        return matrix, self.mesh.p[:, self.mesh.t].mean(axis=1).T

    @_quiet_skfem
    def quadrature_points(self) -> np.ndarray:
        """(2, n_elements, n_points) coordinates of the quadrature points."""
        return np.asarray(self.basis.global_coordinates())

    def quadrature_weights(self) -> np.ndarray:
        """(n_elements, n_points) areas [m^2] the quadrature points stand for (their sum is
        the mesh's area)."""
        return np.asarray(self.basis.dx)

    @_quiet_skfem
    def mean_rotation(self, u) -> float:
        """The area mean of the small rotation (dv/dx - du/dy) / 2 of u [rad]: the rigid
        rotation a displacement carries (a rigid rotation's own angle)."""
        grad = np.asarray(self.basis.interpolate(u).grad)
        weights = self.quadrature_weights()
        return float(np.sum(0.5 * (grad[1, 0] - grad[0, 1]) * weights) / weights.sum())

    @_quiet_skfem
    def displacement_at(self, u, points) -> np.ndarray:
        """(k, 2) displacement at points [m] (k, 2) inside the mesh."""
        points = np.asarray(points, float).reshape(-1, 2).T
        return np.column_stack([basis.probes(points) @ part for part, basis in self.basis.split(u)])

    def displacement_at_nodes(self, u) -> np.ndarray:
        """(n_nodes, 2) displacement at the mesh vertices."""
        return np.column_stack([u[self.basis.nodal_dofs[0]], u[self.basis.nodal_dofs[1]]])


def refined_triangles(points, triangles, marked=None):
    """A triangle mesh refined by scikit-fem: every triangle split in four (``marked``
    None), or the marked ones and what conformity asks of their neighbours (red-green-blue
    refinement). The refined mesh's first nodes are the given ones; each new node is the
    midpoint of an edge of the given mesh.

    Parameters
    ----------
    points : numpy.ndarray
        The nodes [m], shape (n, 2).
    triangles : numpy.ndarray
        Three node indices per triangle, shape (m, 3).
    marked : array_like of int, optional
        The triangles to split; None: all.

    Returns
    -------
    tuple of numpy.ndarray
        The refined mesh's nodes [m] (n', 2) and triangles (m', 3), and the given mesh's
        edges (2, e) whose midpoints the new nodes may be.
    """
    mesh = skfem.MeshTri(np.asarray(points, float).T.copy(),
                         np.asarray(triangles, np.int64).T.copy())
    finer = mesh.refined() if marked is None else mesh.refined(np.asarray(marked, np.int64))
    return finer.p.T.copy(), finer.t.T.copy(), mesh.facets


def principal_stresses(sigma) -> tuple[np.ndarray, np.ndarray]:
    """(largest, smallest) in-plane principal stress of Voigt stresses (3, ...):
    (sxx + syy)/2 +- sqrt(((sxx - syy)/2)^2 + sxy^2) (Timoshenko & Goodier 1970, sec. 9).

    Parameters
    ----------
    sigma : array_like
        The stresses sxx, syy, sxy [Pa], shape (3, ...).

    Returns
    -------
    tuple of numpy.ndarray
        The largest and the smallest principal stress [Pa].
    """
    sxx, syy, sxy = sigma
    centre = 0.5 * (sxx + syy)
    radius = np.hypot(0.5 * (sxx - syy), sxy)
    return centre + radius, centre - radius
