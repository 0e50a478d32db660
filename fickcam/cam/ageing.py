"""The scene's cam over ageing: which part state feeds which input of
:func:`~fickcam.cam.model.cam_response`, and the response stacked over ageing times
(called by :mod:`fickcam.simulation.simulate`).

Parts: ``cam`` (a :class:`fickcam.diffusion.problem.geometry.CamPlate` of the dry working profile) and,
when the follower names a material, ``follower`` (a roller: a disc of the roller radius
and the contact width; a knife or flat follower: a bar of the contact width, stem
length 4 x width; a swinging arm: a bar of the arm length, or the pivot distance for a
flat face, and the contact width square). The cam's in-plane free strains along x (fibre)
and y scale/distort the profile, the roller's mean in-plane strain (eps_L + eps_T)/2 its
radius, a swinging arm's strain along its length (x) its length and face offset; the follower's mass is
m (1 + M/100) with M its mean moisture (Singh & Sanyal 2017, p. 281: m_w = 1.648 kg for
3 %); contact uses the cam's surface-layer modulus (the wet skin, not the bulk).

The papers are cited in full in :mod:`fickcam.cam`.
"""
from __future__ import annotations

import numpy as np

from ..mechanisms.ageing import over_ageing
from ..mechanisms.response import Response, peak
from .design import CamState, design_from_scene
from .kinematics import working_profile
from .model import cam_response, closed_form_jump_speeds
from .oscillating import follower_response


def scene_parts(section, materials) -> list[tuple]:
    """(part name, material name, diffusion geometry, dry mass kg) for cam and follower.

    Parameters
    ----------
    section : CamSection
        The scene's validated ``cam:`` section (SI).
    materials : dict of str to Material
        The scene's materials by name (their dry densities [kg/m^3] give the cam's mass).

    Returns
    -------
    list of tuple
        One (name, material name, geometry with dimensions [m], dry mass [kg]) per part.
    """
    from ..diffusion.problem.geometry import Bar, CamPlate, Disc
    from ..materials.bodies import plate_body

    design = design_from_scene(section)
    x, y = working_profile(design)
    _, cam_mass, _ = plate_body(x, y, section.thickness, section.bore_radius,
                                materials[section.material].dry_density)
    if section.eccentric is not None and section.bore_radius == 0:
        # a solid eccentric disc is a finite cylinder about its own centre: exact series
        geometry = Disc(section.eccentric.radius, section.thickness)
    else:  # the bore is on the rotation axis: a plate with the profile outline
        geometry = CamPlate(x, y, section.thickness, section.bore_radius)
    parts = [("cam", section.material, geometry, float(cam_mass))]
    follower = section.follower
    if follower.material:
        width = design.contact_length
        if design.arm is not None:  # the arm, a bar of the contact width, roller included
            geometry = Bar(design.arm.length or design.arm.pivot_distance, width, width)
        elif follower.kind == "roller":
            geometry = Disc(follower.roller_radius, width)
        else:
            geometry = Bar(4.0 * width, width, width)
        parts.append(("follower", follower.material, geometry, float(follower.mass)))
    return parts


def _at(state: dict, name: str, k: int, default=None):
    value = state.get(name)
    return default if value is None else float(np.asarray(value)[k])


def cam_state(design, histories: dict, k: int) -> CamState:
    """The :class:`~fickcam.cam.design.CamState` at ageing index k from the part histories.

    Parameters
    ----------
    design : CamDesign
        The dry design.
    histories : dict of str to PartHistory
        The ``cam`` (and ``follower``) histories: strains [-], moisture [weight %],
        moduli [Pa] over ageing time.
    k : int
        The ageing time's index.

    Returns
    -------
    CamState
    """
    cam = histories["cam"].state
    follower = histories.get("follower")
    fstate = follower.state if follower is not None else {}
    moisture = _at(fstate, "moisture_content", k, 0.0)
    return CamState(
        cam_strain_x=_at(cam, "strain_longitudinal", k, 0.0),
        cam_strain_y=_at(cam, "strain_transverse", k, 0.0),
        roller_strain=0.5 * (_at(fstate, "strain_longitudinal", k, 0.0) +
                             _at(fstate, "strain_transverse", k, 0.0))
        if design.follower_kind == "roller" else 0.0,
        arm_strain=_at(fstate, "strain_longitudinal", k, 0.0) if design.arm is not None else 0.0,
        follower_mass=design.follower_mass * (1.0 + moisture / 100.0),
        cam_surface_modulus=_at(cam, "surface_modulus", k),
        cam_surface_poisson=_at(cam, "surface_poisson_ratio", k, 0.3),
        follower_modulus=_at(fstate, "surface_modulus", k),
        follower_poisson=_at(fstate, "surface_poisson_ratio", k),
        follower_train_modulus=_at(fstate, "longitudinal_modulus", k))


def scene_response(section, histories: dict, times, angles, valid, on_step=lambda: None) -> Response:
    """The cam over ageing: variables (time, ...) and notices; ``wear_depth`` accumulates
    the deepest Archard wear rate over the ageing times (trapezoid rule).

    Parameters
    ----------
    section : CamSection
        The scene's validated ``cam:`` section (SI).
    histories : dict of str to PartHistory
        The parts' histories by name.
    times : array_like
        The ageing times [s].
    angles : array_like
        The cam angles [rad] of the outputs over a turn.
    valid : array_like of bool
        Per ageing time: the parts are within their models' range (False: NaN there).
    on_step : callable
        Called once per ageing time evaluated (a progress bar).

    Returns
    -------
    fickcam.mechanisms.response.Response
        Variables over (time, ...) in SI, and the notices.
    """
    design = design_from_scene(section)
    if design.polydyne_speed is not None:
        from .polydyne import polydyne_design

        follower = histories.get("follower")
        dry = None if follower is None else float(follower.part.material.ply_properties(1.0)["e11"])
        design = polydyne_design(design, dry)
    times = np.asarray(times, float)
    valid = np.asarray(valid, bool)
    states = {k: cam_state(design, histories, k) for k in np.flatnonzero(valid).tolist()}
    # the closed-form motions' jump speeds, searched for all ageing times at once
    jumps = closed_form_jump_speeds(design, states, angles)

    def evaluate(k: int) -> Response:
        state = states[k]
        response = cam_response(design, state, angles, jump_speed=jumps[k]) if k in jumps \
            else follower_response(design, state, angles)
        if design.train is not None:  # elastic follower train (Norton ch. 15)
            from .train import dynamic_response

            elastic = dynamic_response(design, state, angles, response.variables)
            response.variables.update(elastic.variables)
            response.notices.extend(elastic.notices)
        return response

    result = over_ageing(times, valid, evaluate, on_step)
    rate = result.variables.get("wear_rate")
    if rate is not None:
        steps = np.diff(times) * 0.5 * (rate[1:] + rate[:-1])
        result.variables["wear_depth"] = np.concatenate([[0.0], np.cumsum(steps)])
    force = result.variables.get("contact_force")
    if force is not None:
        result.variables["peak_contact_force"] = peak(force, axis=1)
        result.variables["peak_cam_torque"] = peak(np.abs(result.variables["cam_torque"]), axis=1)
        for name in ("contact_stress", "subsurface_shear_stress"):
            result.variables[f"peak_{name}"] = peak(result.variables[name], axis=1)
    return result
