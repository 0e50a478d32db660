"""Elastic deflection of a cam plate under its contact force, at every cam angle.

The cam is a plane-stress plate (thickness t) held at its bore (u = 0 on the bore: a
shrink or key fit stiff against the plate). At cam angle theta the follower presses on
the profile with the force F along the common normal; it is spread over the Hertz
half-width b = 2 F / (pi p0 L) (L the contact length, p0 the Hertz peak pressure) as the
elliptical pressure p(s) = p0 sqrt(1 - s^2/b^2) of line contact (Johnson, Contact
Mechanics 1985, eq. 4.44), s the distance from the contact point. The deflection of the
profile along the common normal is the pressure-weighted mean of the normal displacement
over the contact patch, delta = f . u / F (the displacement work-conjugate to the load;
it includes the local indentation, which for a plane body depends on log(size / b),
Johnson 1985 eq. 2.25b, and so needs the mesh to resolve b near the profile).

A translating follower on a profile that recedes by delta along the normal moves back
by delta / cos(phi) along its axis (phi the pressure angle; the pitch curve is offset by
delta along its normal). The lift lost is the rigid lift minus the lift of the
deflected motion.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .fem import PlaneElasticity, principal_stresses
from scipy.spatial import cKDTree

#: load cases solved and reduced to stress extremes at a time (memory ~ 3 elements x this)
CHUNK = 48
#: the load is spread over at least this many mesh spacings either side of the contact
RESOLVED = 3.0


@dataclass
class CamPlateModel:
    """The plate's elements, the held bore dofs and the profile's quadrature points.

    Parameters
    ----------
    elasticity : PlaneElasticity
        The plate's plane-stress elements.
    held : numpy.ndarray
        The dofs held fixed on the bore.
    points : numpy.ndarray
        Quadrature points on the profile facets, shape (q, 2) [m].
    normals : numpy.ndarray
        Outward unit normals there, shape (q, 2) [-].
    lengths : numpy.ndarray
        Quadrature weights times facet lengths, without the thickness, shape (q,) [m].
    operator : scipy.sparse matrix
        Traction at the points [Pa] -> load vector [N], shape (dofs, 2q).
    strain : scipy.sparse matrix
        Dofs [m] -> element-centroid strains [-], shape (3 elements, dofs).
    spacing : float
        Mesh spacing along the profile [m].
    """

    elasticity: PlaneElasticity
    held: np.ndarray
    points: np.ndarray      # (q, 2) quadrature points on the profile facets
    normals: np.ndarray     # (q, 2) outward unit normals there
    lengths: np.ndarray     # (q,) quadrature weights x facet lengths (m), without thickness
    operator: object        # sparse (dofs, 2q): traction at the points -> load vector
    strain: object          # sparse (3 elements, dofs): dofs -> centroid strains
    spacing: float          # mesh spacing along the profile (m)


def cam_plate_model(points, triangles, thickness: float, bore_radius: float, spacing: float,
                    order: int = 2, loops=None) -> CamPlateModel:
    """Elements of a cam plate mesh held on the bore circle (radius ``bore_radius`` about
    the origin, the rotation axis), or, for a drawn plate with other holes (``loops``), held
    on its drawn bore and loaded on its drawn outline, every other hole free.

    Parameters
    ----------
    points : array_like
        Mesh vertices, shape (n, 2) [m].
    triangles : array_like
        Vertex indices, shape (m, 3).
    thickness : float
        The plate's thickness [m].
    bore_radius : float
        The bore's radius [m].
    spacing : float
        Mesh spacing along the profile [m].
    order : int
        Lagrange element order (1 or 2).
    loops : tuple of numpy.ndarray, optional
        (the outline, the bore) of a drawn plate, each its vertices [m], shape (k, 2): the
        facets within a quarter of ``spacing`` of each; None: by their distance from the axis.

    Returns
    -------
    CamPlateModel
        The model.
    """
    pe = PlaneElasticity(points, triangles, thickness, order)
    if loops is None:
        on_bore = pe.boundary_facets(lambda x, y: np.hypot(x, y) < bore_radius + 0.25 * spacing)
        profile = pe.boundary_facets(lambda x, y: np.hypot(x, y) >= bore_radius + 0.25 * spacing)
    else:
        profile, on_bore = (pe.boundary_facets(near_loop(loop, 0.25 * spacing)) for loop in loops)
    qp, normals, lengths, operator = pe.traction_operator(profile)
    strain, _ = pe.strain_operator()
    return CamPlateModel(pe, pe.facet_dofs(on_bore), qp, normals, lengths, operator, strain, spacing)


def near_loop(loop, distance: float):
    """``keep(x, y)``: whether points lie within ``distance`` of a closed loop's edges.

    Parameters
    ----------
    loop : array_like
        The loop's vertices [m], shape (k, 2).
    distance : float
        The largest distance [m].

    Returns
    -------
    callable
        ``keep(x, y)`` of coordinate arrays [m] -> bool array.
    """
    start = np.asarray(loop, float)
    edge = np.roll(start, -1, axis=0) - start
    length2 = np.maximum((edge * edge).sum(axis=1), np.finfo(float).tiny)

    def keep(x, y):
        p = np.column_stack([np.ravel(x), np.ravel(y)])[:, None, :] - start[None]
        t = np.clip((p * edge).sum(axis=2) / length2, 0.0, 1.0)
        gap = np.hypot(*(p - t[..., None] * edge).transpose(2, 0, 1)).min(axis=1)
        return (gap <= distance).reshape(np.shape(x))
    return keep


def hertz_half_width(force, peak_pressure, length):
    """b = 2 F / (pi p0 L): line contact under an elliptical pressure (Johnson 1985 eq. 4.44).

    Parameters
    ----------
    force : float or array_like
        The contact force F [N].
    peak_pressure : float or array_like
        The Hertz peak pressure p0 [Pa].
    length : float
        The contact length L [m].

    Returns
    -------
    numpy.ndarray
        The half-width b [m]; 0 where p0 <= 0.

    References
    ----------
    K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, eq. 4.44,
    doi:10.1017/CBO9781139171731.
    """
    force, peak_pressure = np.asarray(force, float), np.asarray(peak_pressure, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(peak_pressure > 0, 2.0 * force / (np.pi * peak_pressure * length), 0.0)


def _nearest(model: CamPlateModel, contact) -> np.ndarray:
    """Index of the profile quadrature point nearest each contact point."""

    return cKDTree(model.points).query(contact)[1]


def contact_loads(model: CamPlateModel, contact, force, half_width) -> np.ndarray:
    """Load vectors (dofs, n): at each contact point (n, 2; cam frame) the force F pressing
    along the inward normal, spread as p ~ sqrt(1 - s^2/b^2); b is widened to 1.5 mesh
    spacings where it is narrower (a point load the mesh cannot resolve).

    Parameters
    ----------
    model : CamPlateModel
        The plate.
    contact : numpy.ndarray
        Contact points, cam frame, shape (n, 2) [m].
    force : array_like
        Contact force at each point [N] (negative taken as 0).
    half_width : array_like
        Hertz half-width b at each point [m].

    Returns
    -------
    numpy.ndarray
        Load vectors, shape (dofs, n) [N].
    """
    direction = -model.normals[_nearest(model, contact)]                      # (n, 2) into the cam
    width = _spread_width(model, half_width)
    distance = np.linalg.norm(model.points[None, :, :] - contact[:, None, :], axis=2)
    shape = np.sqrt(np.clip(1.0 - (distance / width[:, None]) ** 2, 0.0, None))  # (n, q)
    total = (shape * model.lengths[None, :]).sum(axis=1) * model.elasticity.thickness
    magnitude = shape * (np.maximum(np.asarray(force, float), 0.0) / total)[:, None]
    traction = np.concatenate([magnitude * direction[:, :1], magnitude * direction[:, 1:]], axis=1)
    return np.asarray(model.operator @ traction.T)


def _spread_width(model: CamPlateModel, half_width) -> np.ndarray:
    """The half-width the load is spread over in the plate: b, or ``RESOLVED`` mesh spacings
    where b is narrower."""
    return np.maximum(np.nan_to_num(np.asarray(half_width, float)), RESOLVED * model.spacing)


def _rotated_compliance(q, angle):
    """(a11, a22, a12, a66) of the plane-stress compliance S = Q^-1 in axes turned by
    ``angle`` from x (Jones 1999 eq. 2.97; the coupling terms a16, a26 are not returned)."""
    a = np.linalg.inv(np.asarray(q, float))
    c2, s2 = np.cos(angle) ** 2, np.sin(angle) ** 2
    a11, a22, a12, a66 = a[0, 0], a[1, 1], a[0, 1], a[2, 2]
    return (a11 * c2 ** 2 + (2 * a12 + a66) * s2 * c2 + a22 * s2 ** 2,
            a11 * s2 ** 2 + (2 * a12 + a66) * s2 * c2 + a22 * c2 ** 2,
            a12 * (s2 ** 2 + c2 ** 2) + (a11 + a22 - a66) * s2 * c2,
            2 * (2 * a11 + 2 * a22 - 4 * a12 - a66) * s2 * c2 + a66 * (s2 ** 2 + c2 ** 2))


def half_plane_log_coefficient(q, tangent_angle):
    """C in v = -C P ln r + const, the normal surface displacement of an orthotropic
    plane-stress half-plane under a normal line load P (per unit thickness), its surface
    along ``tangent_angle``: with a_tt, a_nn the compliances along the surface and the
    normal, C = a_nn (beta1 + beta2) / pi, (beta1 + beta2)^2 = (2 a_nt + a66)/a_nn +
    2 sqrt(a_tt/a_nn) (Lekhnitskii, Anisotropic Plates 1968, sec. 28; isotropic:
    C = 2 / (pi E), Johnson 1985 eq. 2.19b). Exact along material axes (checked against the
    finite elements in the tests); in between the coupling terms a16, a26 are neglected.

    Parameters
    ----------
    q : array_like
        The plane-stress stiffness Q, shape (3, 3) [Pa].
    tangent_angle : float or array_like
        The surface's direction from the x axis [rad].

    Returns
    -------
    numpy.ndarray
        C [1/Pa].

    References
    ----------
    S. G. Lekhnitskii, *Anisotropic Plates*, Gordon and Breach, 1968, sec. 28.
    """
    a_tt, a_nn, a_nt, a66 = _rotated_compliance(q, tangent_angle)
    return np.sqrt(a_nn * (2 * a_nt + a66) + 2 * a_nn * np.sqrt(a_tt * a_nn)) / np.pi


def indentation_below_mesh(force, half_width, spread, coefficient, thickness):
    """Extra approach of an elliptical line load of half-width b over the same load spread
    over w > b: C P ln(w / b), P = F / t: two loads of the same shape on a half-plane
    differ by the log of their widths (see :func:`half_plane_log_coefficient`).

    Parameters
    ----------
    force : float or array_like
        The contact force F [N].
    half_width : float or array_like
        The Hertz half-width b [m].
    spread : float or array_like
        The half-width w the mesh spreads the load over [m].
    coefficient : float or array_like
        C [1/Pa] (:func:`half_plane_log_coefficient`).
    thickness : float
        The plate's thickness t [m].

    Returns
    -------
    numpy.ndarray
        The extra approach [m].
    """
    force = np.maximum(np.asarray(force, float), 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(half_width > 0, spread / np.maximum(half_width, 1e-300), 1.0)
    return coefficient * force / thickness * np.log(np.maximum(ratio, 1.0))


@dataclass(frozen=True)
class ContactResult:
    """Per cam angle: deflection along the common normal (m, towards the cam), largest
    tensile and compressive principal stress in the plate (Pa).

    Parameters
    ----------
    deflection : numpy.ndarray
        Deflection along the common normal, towards the cam [m].
    tensile : numpy.ndarray
        Largest tensile principal stress [Pa].
    compressive : numpy.ndarray
        Largest compressive (most negative) principal stress [Pa].
    """

    deflection: np.ndarray
    tensile: np.ndarray
    compressive: np.ndarray


def contact_response(model: CamPlateModel, q, contact, force, half_width,
                     q_skin=None) -> ContactResult:
    """Solve the plate for every contact load with one factorisation of K(Q); a Hertz
    half-width below the mesh adds the half-plane indentation of the wet skin (stiffness
    ``q_skin``, default Q) between b and the resolved spread.

    Parameters
    ----------
    model : CamPlateModel
        The plate.
    q : array_like
        Plane-stress stiffness matrix Q of the plate, 3 x 3 [Pa].
    contact : numpy.ndarray
        Contact points, cam frame, shape (n, 2) [m].
    force : numpy.ndarray
        Contact forces [N].
    half_width : numpy.ndarray
        Hertz half-widths [m].
    q_skin : array_like, optional
        Q of the wet skin [Pa]; default ``q``.

    Returns
    -------
    ContactResult
        Deflection [m] and principal stresses [Pa] per contact.
    """
    pe = model.elasticity
    solve = pe.factorise(pe.stiffness(q), model.held)
    n = len(force)
    deflection, tensile, compressive = np.zeros(n), np.zeros(n), np.zeros(n)
    q = np.asarray(q, float)
    elements = pe.mesh.t.shape[1]
    for start in range(0, n, CHUNK):
        chunk = slice(start, min(start + CHUNK, n))
        loads = contact_loads(model, contact[chunk], force[chunk], half_width[chunk])
        u = solve(loads)
        with np.errstate(invalid="ignore", divide="ignore"):
            deflection[chunk] = np.where(force[chunk] > 0,
                                         np.einsum("ij,ij->j", loads, u) / force[chunk], 0.0)
        strain = (model.strain @ u).reshape(3, elements, -1)
        stress = np.einsum("ij,jek->iek", q, strain)
        largest, smallest = principal_stresses(stress)
        tensile[chunk] = largest.max(axis=0)
        compressive[chunk] = smallest.min(axis=0)
    normal = model.normals[_nearest(model, contact)]
    tangent = np.arctan2(normal[:, 0], -normal[:, 1])
    coefficient = half_plane_log_coefficient(q if q_skin is None else q_skin, tangent)
    deflection += indentation_below_mesh(force, half_width, _spread_width(model, half_width),
                                         coefficient, pe.thickness)
    return ContactResult(deflection, tensile, compressive)


def follower_shift(deflection, pressure_angle):
    """Follower displacement lost to a profile deflection delta along the normal:
    delta / cos(phi) (the pitch curve offset by delta along its normal).

    Parameters
    ----------
    deflection : float or array_like
        The profile's deflection delta along the common normal [m].
    pressure_angle : float or array_like
        phi [rad].

    Returns
    -------
    numpy.ndarray
        The follower displacement lost [m].
    """
    return np.asarray(deflection, float) / np.cos(np.asarray(pressure_angle, float))


def lift_error(displacement, shift) -> float:
    """Rigid lift minus the lift of the deflected follower motion (m; > 0: lift lost).

    Parameters
    ----------
    displacement : array_like
        The rigid follower displacement over the cycle [m].
    shift : array_like
        The displacement lost at each angle [m] (:func:`follower_shift`).

    Returns
    -------
    float
        The lift lost [m].
    """
    displacement = np.asarray(displacement, float)
    deflected = displacement - np.asarray(shift, float)
    return float(np.ptp(displacement) - np.ptp(deflected))
