"""The scene's cam plate under its contact force over ageing (``cam.elastic: true``):
which state and cam results feed :mod:`fickcam.elastic.contact`, and the variables
stacked over ageing times (called by :mod:`fickcam.simulation.simulate`).

Mesh: the diffusion engine's graded planform mesh of the dry working profile, spacing
``PROFILE_SAMPLES`` per perimeter along the outline, growing by ``GROWTH`` per row
inward; P2 elements. A drawn plate with holes besides its bore is meshed as drawn, every
hole in it, held on its drawn bore (a keyway's edges too) and loaded on its outline. The load is spread over the Hertz half-width where the mesh
resolves it and the log term of the half-plane adds the rest (``contact``); measured on
the demo cam: deflection at the peak contact force 78.13 um (spacing 1 mm) against
78.35 um (0.5 mm). Moduli: the cam's aged bulk ply moduli at each ageing time
(E11 along x), the wet skin's for the local indentation.
"""
from __future__ import annotations

import logging

import numpy as np

from ..messages import note
from ..mechanisms.response import Response
from .contact import (cam_plate_model, contact_response, follower_shift, hertz_half_width,
                      lift_error)
from .fem import stiffness_matrix
from ..cam.kinematics import working_profile
from ..diffusion.problem.geometry import CamPlate, DrawnPlate
from ..drawing.planform import edge_lengths, inside
from .mesh import planform_mesh

log = logging.getLogger(__name__)

PROFILE_SAMPLES = 400   # mesh spacing = profile perimeter / this
GROWTH = 0.2            # row-to-row growth of the graded mesh


def _ply_stiffness(state: dict, k: int, prefix: str = "") -> np.ndarray:
    """Plane-stress Q of the part's ply axes at ageing index k from its material state
    (``prefix`` 'surface_': the wet contact skin)."""
    def at(name):
        return float(np.asarray(state[prefix + name])[k])
    return stiffness_matrix(at("longitudinal_modulus"), at("transverse_modulus"),
                            at("shear_modulus"), at("poisson_ratio"))


def _cam_plate(design, drawn: bool | None = None):
    """(the dry plate held at its bore, the mesh spacing, the model's ``loops``): the working
    profile about a round bore, or a drawn plate with holes besides its bore (``drawn``
    None: where it has them; True: any drawn plate) as drawn, every hole in it, held on its
    drawn bore (a keyway's edges too) and loaded on its outline."""
    planform = getattr(design.profile, "planform", None)
    bore = None if planform is None else next(
        (h for h in planform.holes if inside(np.zeros((1, 2)), h)[0]), None)
    if drawn is None:
        drawn = bore is not None and len(planform.holes) > 1
    if drawn:
        outline = planform.outer.points
        spacing = float(edge_lengths(outline).sum()) / PROFILE_SAMPLES
        plate = DrawnPlate(outline, tuple(h.points for h in planform.holes), design.thickness,
                           contact_holes=False)
        return plate, spacing, (outline, bore.points)
    x, y = working_profile(design)
    perimeter = float(np.sum(np.hypot(np.diff(x, append=x[:1]), np.diff(y, append=y[:1]))))
    spacing = perimeter / PROFILE_SAMPLES
    return CamPlate(x, y, design.thickness, design.bore_radius), spacing, None


def cam_elastic_response(design, cam_state: dict, variables: dict, valid,
                         drawn: bool | None = None) -> Response:
    """elastic_deflection, elastic_stress_tensile, elastic_stress_compressive (time,
    cam_angle) and elastic_lift_error (time) from the cam's
    material state and the rigid cam results (contact force and stress, contact point,
    pressure angle, follower displacement).

    Parameters
    ----------
    design : CamDesign
        The dry cam (its working profile, thickness and bore [m]).
    cam_state : dict
        The cam's material state over ageing times: bulk and ``surface_`` ply moduli [Pa]
        and Poisson's ratio [-].
    variables : dict
        The rigid cam results over (time, cam_angle): contact_force [N], contact_stress
        [Pa], profile_x/profile_y [m], pressure angle [rad], follower displacement [m].
    valid : array_like of bool
        Which ageing times to solve (the others stay NaN).
    drawn : bool, optional
        Mesh a drawn plate as drawn, every hole in it, held on its drawn bore: None where it
        has holes besides its bore, True for any drawn plate.

    Returns
    -------
    Response
        elastic_deflection [m], elastic_stress_tensile/compressive [Pa] over (time,
        cam_angle) and elastic_lift_error [m] over time.
    """

    plate, spacing, loops = _cam_plate(design, drawn)
    mesh = planform_mesh(plate, spacing, GROWTH)
    model = cam_plate_model(mesh.points, mesh.triangles, design.thickness, design.bore_radius,
                            spacing, loops=loops)
    log.debug("cam plate: %d nodes, %d dofs, spacing %.3g mm", len(mesh.points),
             model.elasticity.dofs, spacing * 1e3)
    force = variables["contact_force"]
    shape = force.shape
    out = {name: np.full(shape, np.nan) for name in
           ("elastic_deflection", "elastic_stress_tensile", "elastic_stress_compressive")}
    lift = np.full(shape[0], np.nan)
    for k in np.flatnonzero(np.asarray(valid, bool)):
        contact = np.column_stack([variables["profile_x"][k], variables["profile_y"][k]])
        width = hertz_half_width(force[k], variables["contact_stress"][k], design.contact_length)
        result = contact_response(model, _ply_stiffness(cam_state, k), contact, force[k], width,
                                  _ply_stiffness(cam_state, k, "surface_"))
        out["elastic_deflection"][k] = result.deflection
        out["elastic_stress_tensile"][k] = result.tensile
        out["elastic_stress_compressive"][k] = result.compressive
        shift = follower_shift(result.deflection, variables["pressure_angle"][k])
        lift[k] = lift_error(variables["follower_displacement"][k], shift)
    out["elastic_lift_error"] = lift
    notices = []
    if design.follower_kind == "knife":
        notices.append(note(f"knife-edge follower: the contact force is a point load, spread "
                            f"over {2 * 3 * spacing * 1e3:.2g} mm of the cam profile for its "
                            f"deflection"))
    return Response(out, notices)
