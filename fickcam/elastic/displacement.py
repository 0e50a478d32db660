"""Free hygrothermal displacement of a drawn planform by finite elements.

A part free of load under a free (hygrothermal) strain eps*(x, y) takes the displacement
u of plane-stress equilibrium with eps* as the initial strain (Zienkiewicz & Taylor, The
Finite Element Method vol. 1, 6th ed. 2005, ch. 4; the weak form is ``fem``'s). Three
statically determinate supports stop its rigid motion and carry no load (the load of a
free strain is self-equilibrated), and the fitted rigid motion is taken out: u is the
part's change of shape in its own frame. Under a uniform eps* (and any compatible,
i.e. linear, field) the exact u is linear, which P1 and P2 elements hold exactly: every
distance between points of the part grows by (1 + eps) to round-off, today's L(1 + eps).
An uneven field (a wet skin around a dry web, heavy bosses) moves the pins by what the
field gives.

The mesh covers the drawn polygon exactly (``mesh.drawn_mesh``: every vertex kept), so the
discretisation error is the mesh's alone and falls as h^(p+1) for elements of order p on
smooth fields (Ciarlet 1978, Theorem 3.2.5); the polygon's own distance from the drawn
curves is the chord tolerance it was flattened with.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..drawing.planform import Planform, edge_sums
from .fem import PlaneElasticity, isotropic_stiffness
from .mesh import PlateMesh, drawn_mesh  # noqa: F401  (PlateMesh: the type of FreeDisplacement.mesh)

POISSON = 0.3  # of the default isotropic stiffness: a free part's u does not depend on E


@dataclass(frozen=True, eq=False)
class FreeDisplacement:
    """The displacement of a free planform's mesh vertices under one free strain field.

    Parameters
    ----------
    planform : Planform
        The part as drawn [m].
    mesh : PlateMesh
        Its mesh, every drawn vertex a mesh vertex [m].
    nodal : numpy.ndarray
        The displacement of each mesh vertex [m], shape (n, 2), rigid motion taken out.
    """

    planform: Planform
    mesh: PlateMesh
    nodal: np.ndarray

    def moved(self, points) -> np.ndarray:
        """Drawn vertices [m] (n, 2), each a mesh vertex, at their displaced places [m]."""
        points = np.asarray(points, float).reshape(-1, 2)
        gap, index = cKDTree(self.mesh.points).query(points)
        scale = max(self.planform.extent(), 1e-300)
        if np.any(gap > 1e-9 * scale):
            raise ValueError("a point to move is not a vertex of the mesh")
        return points + self.nodal[index]

    def displaced(self) -> Planform:
        """The planform through the displaced vertices [m], loops and layers kept."""
        return self.planform.mapped(self.moved)

    def hole_centre(self, hole) -> np.ndarray:
        """The centre of a hole's displaced area [m] (a pin's centre)."""
        a, sx, sy = edge_sums(self.moved(hole.points))[:3]
        return np.array([sx / a, sy / a])


def free_displacements(planform: Planform, strains, spacing: float, order: int = 2,
                       stiffness=None) -> list[FreeDisplacement]:
    """The free displacement of ``planform`` under each free strain field of ``strains``.

    Parameters
    ----------
    planform : Planform
        The part as drawn [m].
    strains : sequence of callable
        Each ``strain(x, y)`` of coordinate arrays [m] gives eps* [-]: one array (an
        isotropic strain) or a tuple (eps_xx, eps_yy, gamma_xy), each broadcast to x.
    spacing : float
        The mesh's edge length [m].
    order : int
        The Lagrange elements' order (1 or 2).
    stiffness : array_like, optional
        The plane-stress stiffness Q [Pa], (3, 3) or per element / quadrature point as
        ``fem.PlaneElasticity`` takes it; default isotropic with Poisson's ratio ``POISSON``
        (a uniform stiffness's size does not change u).

    Returns
    -------
    list of FreeDisplacement
        One per field, on one mesh and one factorisation.
    """
    mesh = drawn_mesh([loop.points for loop in planform.loops], spacing)
    model = PlaneElasticity(mesh.points, mesh.triangles, 1.0, order)
    q = isotropic_stiffness(1.0, POISSON) if stiffness is None else stiffness
    x, y = model.quadrature_points()
    loads = []
    for strain in strains:
        value = strain(x, y)
        parts = value if isinstance(value, tuple) else (value, value, 0.0)
        loads.append(model.eigenstrain_load(q, tuple(np.broadcast_to(p, x.shape) for p in parts)))
    solve = model.factorise(model.stiffness(q), model.statically_determinate_support())
    solved = solve(np.column_stack(loads))
    return [FreeDisplacement(planform, mesh,
                             model.displacement_at_nodes(model.without_rigid_motion(u)))
            for u in solved.T]


def pin_distance(displacement: FreeDisplacement, holes) -> float:
    """The distance between two displaced hole centres [m] (a link's aged length).

    Parameters
    ----------
    displacement : FreeDisplacement
        The part's displacement.
    holes : tuple of Loop
        The two pin holes, as drawn [m].

    Returns
    -------
    float
        The distance [m].
    """
    a, b = (displacement.hole_centre(h) for h in holes)
    return float(np.hypot(*(b - a)))
