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

A link's aged length from its moisture field (``uneven_pin_shifts``, ``aged_pin_distance``)
splits the free strain beta (M - M0) into its area mean, which stretches the part by a
similarity (today's L (1 + eps) with eps from the mean moisture), and the field's departure
from that mean, whose displacement shifts one pin from the other; the model is linear, so
the two add, and a uniform field (at saturation) gives L (1 + eps) to round-off.

The mesh covers the drawn polygon exactly (``mesh.drawn_mesh``: every vertex kept), so the
discretisation error is the mesh's alone and falls as h^(p+1) for elements of order p on
smooth fields (Ciarlet 1978, Theorem 3.2.5); the polygon's own distance from the drawn
curves is the chord tolerance it was flattened with.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..diffusion.problem.curves import polygon_segments
from ..drawing.planform import Planform, edge_lengths, edge_sums, inside
from .corners import GRADED_ZONE, reentrant_corners
from .fem import PlaneElasticity, isotropic_stiffness, stiffness_matrix
from .nodal import NodalField
from .swelling import plate_moisture
from .mesh import PlateMesh, drawn_mesh  # noqa: F401  (PlateMesh: the type of FreeDisplacement.mesh)

POISSON = 0.3  # of the default isotropic stiffness: a free part's u does not depend on E
#: an outline's displacement keeps the components of wavelengths of this many mesh edges and
#: longer: P2 elements' displacement converges at the vertices, but not its second
#: derivative along an edge (the aged profile's curvature, which the contact reads), whose
#: error at the mesh's own scale is O(1)
SHORTEST_WAVE = 4


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
    mesh, model = _model(planform, spacing, order)
    x, y = model.quadrature_points()
    fields = []
    for strain in strains:
        value = strain(x, y)
        parts = value if isinstance(value, tuple) else (value, value, 0.0)
        fields.append(tuple(np.broadcast_to(p, x.shape) for p in parts))
    return _solved(planform, mesh, model, fields, stiffness)


def _model(planform: Planform, spacing: float, order: int):
    """(mesh, plane-stress model) of a drawn planform."""
    mesh = drawn_mesh([loop.points for loop in planform.loops], spacing)
    return mesh, PlaneElasticity(mesh.points, mesh.triangles, 1.0, order)


def _solved(planform, mesh, model, fields, stiffness) -> list[FreeDisplacement]:
    """The free displacement under each (eps_xx, eps_yy, gamma_xy) at the quadrature
    points, on one factorisation."""
    return [FreeDisplacement(planform, mesh,
                             model.displacement_at_nodes(model.without_rigid_motion(u)))
            for u in _solutions(model, fields, stiffness).T]


def _solutions(model, fields, stiffness) -> np.ndarray:
    """The displacement dofs (dofs, fields) under each free strain field, held by three
    statically determinate supports, on one factorisation."""
    q = isotropic_stiffness(1.0, POISSON) if stiffness is None else stiffness
    loads = [model.eigenstrain_load(q, parts) for parts in fields]
    solve = model.factorise(model.stiffness(q), model.statically_determinate_support())
    return solve(np.column_stack(loads))


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


def uneven_pin_shifts(planform: Planform, pins, moisture, expansion, spacing: float,
                      order: int = 2, stiffness=None) -> np.ndarray:
    """How far the moisture field's unevenness moves a link's second pin from its first.

    The free strain beta (M(x, y) - M0) splits into the strain of the field's area mean,
    beta (M_mean - M0), which moves every point by a similarity (the pins part by
    L beta (M_mean - M0): the mean-strain length), and the strain of the field's
    departure from its mean, beta (M(x, y) - M_mean), whose displacement this solves for.
    The model is linear, so the pin-to-pin vector is their sum; a uniform field gives no
    shift at all.

    Parameters
    ----------
    planform : Planform
        The link as drawn [m], its first pin at the origin and its second on +x.
    pins : tuple of Loop
        The two pin holes, as drawn [m].
    moisture : callable
        ``moisture(points)`` of points [m] (n, 2) gives the thickness-mean moisture
        [weight %] there at each ageing time, shape (times, n).
    expansion : array_like
        The moisture expansion coefficients along and across the link [1/weight %], shape
        (2,) or (times, 2).
    spacing : float
        The mesh's edge length [m].
    order : int
        The Lagrange elements' order (1 or 2).
    stiffness : array_like, optional
        The plane-stress stiffness [Pa] (3, 3), as for :func:`free_displacements`.

    Returns
    -------
    numpy.ndarray
        The change of the vector from the first pin's centre to the second's [m], shape
        (times, 2): along the link, then across it.
    """
    mesh, model, fields = _uneven_fields(planform, moisture, expansion, spacing, order)
    drawn = np.subtract(*(planform.hole_centre(h) for h in pins[::-1]))
    return np.array([np.subtract(*(moved.hole_centre(h) for h in pins[::-1])) - drawn
                     for moved in _solved(planform, mesh, model, fields, stiffness)])


def _uneven_fields(planform: Planform, moisture, expansion, spacing: float, order: int):
    """(mesh, model, the free strains (eps_xx, eps_yy, gamma_xy) at the quadrature points
    of the moisture field's departure from its area mean at each time)."""
    mesh, model = _model(planform, spacing, order)
    x, y = model.quadrature_points()
    values = np.asarray(moisture(np.column_stack([x.ravel(), y.ravel()])), float)
    return mesh, model, _uneven_strains(model, values.reshape(-1, *x.shape), expansion)


def _uneven_strains(model, values, expansion) -> list[tuple]:
    """The free strains (eps_xx, eps_yy, gamma_xy) of the moisture's departure from its area
    mean, from the moisture at the quadrature points (times, elements, points)."""
    weights = model.quadrature_weights()
    uneven = values - np.einsum("tep,ep->t", values, weights)[:, None, None] / weights.sum()
    expansion = np.broadcast_to(np.asarray(expansion, float), (len(uneven), 2))
    return [(bx * d, by * d, 0.0 * d) for d, (bx, by) in zip(uneven, expansion)]


def field_pin_shifts(field: NodalField, planform: Planform, pins, expansion,
                     refinements: int = 0, order: int = 2, stiffness=None) -> np.ndarray:
    """How far the moisture field's unevenness moves a link's second pin from its first, on
    the plane model's own mesh: as :func:`uneven_pin_shifts`, the free strain of the
    field's departure from its area mean, solved on the field's mesh refined
    ``refinements`` times and graded toward the drawn re-entrant corners
    (:mod:`fickcam.elastic.corners`), so that the strain is exactly the engine's field and
    the pins' shift converges at O(h^(2p)) (order p elements) in spite of the corners'
    singularities. A pin's centre is the centre of the area of its hole as the mesh draws
    it (its nodes on the hole's edge).

    Parameters
    ----------
    field : NodalField
        The thickness-mean moisture [weight %] at the nodes [m] of the plane model's mesh
        (:func:`fickcam.elastic.swelling.plane_nodal_moisture`), (times, nodes).
    planform : Planform
        The link as drawn [m], its first pin at the origin and its second on +x.
    pins : tuple of Loop
        The two pin holes, as drawn [m].
    expansion : array_like
        The moisture expansion coefficients along and across the link [1/weight %], shape
        (2,) or (times, 2).
    refinements : int
        How many times every element is split in four before the grading.
    order : int
        The Lagrange elements' order (1 or 2).
    stiffness : array_like, optional
        The plane-stress stiffness [Pa] (3, 3), as for :func:`free_displacements`.

    Returns
    -------
    numpy.ndarray
        The change of the vector from the first pin's centre to the second's [m], shape
        (times, 2): along the link, then across it.
    """
    for _ in range(refinements):
        field = field.refined()
    field = field.graded_toward(reentrant_corners([loop.points for loop in planform.loops]),
                                GRADED_ZONE * planform.extent(), order)
    model = PlaneElasticity(field.points, field.triangles, 1.0, order)
    values = np.array([model.nodal_at_points(v) for v in field.values])
    holes = [_hole_nodes(field, pin.points) for pin in pins]

    def vector(points):  # first pin's area centre to the second's
        (a0, x0, y0), (a1, x1, y1) = (edge_sums(points[h])[:3] for h in holes)
        return np.array([x1 / a1 - x0 / a0, y1 / a1 - y0 / a0])
    drawn = vector(field.points)
    return np.array([vector(field.points + model.displacement_at_nodes(model.without_rigid_motion(u)))
                     - drawn for u in _solutions(model, _uneven_strains(model, values, expansion),
                                                 stiffness).T])


def _hole_nodes(field: NodalField, hole) -> np.ndarray:
    """The nodes of the mesh's boundary on a hole's edge, in order along it: those within
    1e-3 of the hole's extent (a mesh's chord may cut a drawn vertex by far less; the
    other loops are much farther)."""
    edges = np.sort(field.triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    boundary = np.unique(unique[count == 1])
    segments = polygon_segments(*np.asarray(hole, float).T)
    start, step = segments[:, 0], segments[:, 1] - segments[:, 0]
    relative = field.points[boundary][:, None, :] - start[None]
    along = np.clip(np.einsum("nsk,sk->ns", relative, step) / np.sum(step * step, axis=1), 0, 1)
    gap = np.hypot(*(relative - along[..., None] * step[None]).transpose(2, 0, 1))
    nearest = np.argmin(gap, axis=1)
    rows = np.arange(len(boundary))
    on = np.flatnonzero(gap[rows, nearest] <= 1e-3 * np.ptp(hole, axis=0).max())
    return boundary[on[np.argsort(nearest[on] + along[on, nearest[on]], kind="stable")]]


def uneven_outline_shifts(planform: Planform, moisture, expansion, spacing: float,
                          order: int = 2, stiffness=None) -> np.ndarray:
    """How far the moisture field's unevenness moves a cam plate's outline about its axis.

    As :func:`uneven_pin_shifts`, the free strain's area mean moves the plate by a
    similarity about the axis (the mean-strain profile); this solves for the displacement
    of the field's departure from its mean, in the cam's frame: its mean rotation
    (:meth:`fickcam.elastic.fem.PlaneElasticity.mean_rotation`) taken out, and the
    translation that keeps the axis where the shaft holds it, the mean displacement of the
    bore's round edge (the centre of a displaced circle, to first order), or the
    displacement at the axis where the plate has no bore. A uniform field moves nothing.
    The outline's displacement keeps its components of wavelengths of ``SHORTEST_WAVE``
    mesh edges and longer (:func:`band_limited`), so that the displaced profile's curvature
    is the field's, not the mesh's.

    Parameters
    ----------
    planform : Planform
        The plate as drawn [m], its axis at the origin.
    moisture, spacing, order, stiffness
        The thickness-mean moisture ``moisture(points)`` [weight %] of points [m], the
        mesh's edge [m], the elements' order and the plane-stress stiffness [Pa], as for
        :func:`uneven_pin_shifts`.
    expansion : array_like
        The moisture expansion coefficients along x and y [1/weight %], shape (2,) or
        (times, 2).

    Returns
    -------
    numpy.ndarray
        The displacement of each vertex of the outline [m], shape (times, n, 2).
    """
    mesh, model, fields = _uneven_fields(planform, moisture, expansion, spacing, order)
    outer = planform.outer.points
    shifts = []
    for u in _solutions(model, fields, stiffness).T:
        nodal = FreeDisplacement(planform, mesh, model.displacement_at_nodes(u))
        turn = model.mean_rotation(u)
        axis = _axis_displacement(planform, nodal, model, u, turn)
        moved = nodal.moved(outer) - outer
        shift = moved - axis - turn * np.column_stack([-outer[:, 1], outer[:, 0]])
        shifts.append(band_limited(outer, shift, SHORTEST_WAVE * spacing))
    return np.array(shifts)


def band_limited(points, values, wavelength: float) -> np.ndarray:
    """Values at the vertices of a closed loop with their components shorter than
    ``wavelength`` along it taken out: the least-squares Fourier series in the arc length
    s of the harmonics k <= L / wavelength (L the loop's length), at the vertices. A
    band-limited set of values (a uniform or linear field's displacement of a circle) is
    returned to round-off; with too few vertices for that series, the values as they are.

    Parameters
    ----------
    points : numpy.ndarray
        The loop's vertices [m], shape (n, 2).
    values : numpy.ndarray
        A value per vertex [any unit], shape (n, m).
    wavelength : float
        The shortest wavelength kept [m].

    Returns
    -------
    numpy.ndarray
        The values, shape (n, m).
    """
    edges = edge_lengths(points)
    length = edges.sum()
    count = int(length / wavelength)
    if 2 * count + 1 >= len(points):
        return values
    phase = 2 * np.pi * np.concatenate([[0.0], np.cumsum(edges[:-1])]) / length
    k = np.arange(1, count + 1)
    basis = np.column_stack([np.ones_like(phase), np.cos(np.outer(phase, k)),
                             np.sin(np.outer(phase, k))])
    coefficients, *_ = np.linalg.lstsq(basis, values, rcond=None)
    return basis @ coefficients


def _axis_displacement(planform: Planform, nodal: FreeDisplacement, model, u,
                       turn: float) -> np.ndarray:
    """The displacement of the cam's axis (the origin) once the rotation ``turn`` [rad] is
    taken out [m]: the mean over the bore's vertices on its circle, weighted by the edge
    each stands for, or the field at the origin where no hole holds it."""
    origin = np.zeros((1, 2))
    bore = next((h for h in planform.holes if inside(origin, h)[0]), None)
    if bore is None:
        return model.displacement_at(u, origin)[0]
    points = bore.points
    radius = np.hypot(*points.T)
    on = np.abs(radius - radius.min()) <= 1e-3 * radius.min()
    edges = edge_lengths(points)
    weight = np.where(on, 0.5 * (edges + np.roll(edges, 1)), 0.0)
    moved = nodal.moved(points) - points - turn * np.column_stack([-points[:, 1], points[:, 0]])
    return weight @ moved / weight.sum()


def field_inputs(history, planform: Planform):
    """(moisture, expansion, stiffness): what the free displacement of a drawn part's
    moisture field reads from its ageing: the field over the planform
    (:func:`drawn_moisture`), the moisture expansion coefficients along x and y at each
    ageing time [1/weight %] (0 where the state gives none) and the dry plane-stress
    stiffness of its material [Pa].

    Parameters
    ----------
    history : fickcam.simulation.parts.PartHistory
        The part's ageing, with its diffusion fields and its sheet.
    planform : Planform
        The part as drawn [m].

    Returns
    -------
    tuple
        As above.
    """
    state, material = history.state, history.part.material
    expansion = np.nan_to_num(np.column_stack([state["moisture_expansion_longitudinal"],
                                               state["moisture_expansion_transverse"]]))
    dry = {k: float(np.ravel(v)[0]) for k, v in material.ply_properties(np.ones(1)).items()}
    stiffness = stiffness_matrix(dry["e11"], dry["e22"], dry["g12"], dry["nu12"])
    moisture = drawn_moisture(history.diffusion, history.part.geometry, history.sheet, planform)
    return moisture, expansion, stiffness


def aged_pin_distance(length, strain, shift) -> np.ndarray:
    """A link's aged pin-to-pin length [m]: the mean strain's L (1 + eps) plus the shift of
    the field's unevenness (:func:`uneven_pin_shifts`).

    Parameters
    ----------
    length : float
        The dry pin-to-pin length L [m].
    strain : array_like
        The free strain along the link of the field's mean [-], shape (times,).
    shift : array_like
        The unevenness's shift of the pin-to-pin vector [m], shape (times, 2).

    Returns
    -------
    numpy.ndarray
        The aged lengths [m], shape (times,); L (1 + eps) exactly where the shift is zero.
    """
    shift = np.asarray(shift, float)
    return np.hypot(length * (1.0 + np.asarray(strain, float)) + shift[:, 0], shift[:, 1])


def drawn_moisture(result, geometry, sheet, planform: Planform):
    """The thickness-mean moisture over a drawn planform at each stored time, as a function
    of the points: the plane model's field on its mid-thickness level, the drawn edges at
    the sheet's face value, carried through the thickness with the exact sheet
    (:func:`fickcam.elastic.swelling.plate_moisture`).

    Parameters
    ----------
    result : fickcam.diffusion.DiffusionResult
        The part's diffusion result with its ``fields`` [weight %].
    geometry : fickcam.diffusion.problem.geometry.DrawnPlate
        Its diffusion geometry [m].
    sheet : fickcam.elastic.thickness.SheetProfile
        The exact sheet of its thickness under its exposure [weight %].
    planform : Planform
        The part as drawn [m] (its loops the exposed edges).

    Returns
    -------
    callable
        ``moisture(points)`` of points [m] (n, 2): the moisture [weight %], (times, n).
    """
    edge = np.vstack([loop.points for loop in planform.loops])

    def moisture(points):
        points = np.vstack([edge, np.asarray(points, float).reshape(-1, 2)])
        _, mean = plate_moisture(result, geometry, points, sheet.surface, sheet,
                                 np.arange(len(edge)))
        return mean[:, len(edge):]

    return moisture
