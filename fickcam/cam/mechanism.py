"""The scene's cam as a mechanism (:class:`~fickcam.cam.mechanism.CamMechanism`): built once
from its ``cam:`` section, it names its parts and their materials, and answers the run's
questions: which bodies age, which coordinates its results have, and its response over the
ageing times (which part state feeds which input of
:func:`~fickcam.cam.model.cam_response`).

Parts: ``cam`` (a :class:`fickcam.diffusion.problem.geometry.CamPlate` of the dry working
profile; a drawn plate's :class:`~fickcam.diffusion.problem.geometry.DrawnPlate` with all its
holes) and,
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

from functools import cached_property, partial
from pathlib import Path

import numpy as np

from ..materials.bodies import plate_body
from ..mechanisms.ageing import over_ageing
from ..mechanisms.part import Part
from ..mechanisms.response import Response, peak
from .arm_spec import reach_problems
from .design import CamDesign, CamState, cam_design
from .drawn import aged_drawn_designs, describe_plate, read_cam_drawing
from .kinematics import fitted_motions, working_profile
from .model import cam_response, jump_speeds_over_ageing
from .oscillating import describe_arm, follower_response
from .polydyne import polydyne_design
from .spec import CamSection, arm_problems
from .train import dynamic_response


class CamMechanism:
    """A cam and its follower, built once from the scene's ``cam:`` section: the dry
    design (its profile and swinging arm), the design its motion is computed from (with
    the polydyne correction where asked), the dry working profile and the parts.

    Parameters
    ----------
    section : CamSection
        The validated ``cam:`` section (SI); a profile file's path absolute.
    materials : dict of str to Material
        The scene's resolved materials by name (their dry densities [kg/m^3] give the
        cam's mass, the follower's dry modulus [Pa] a polydyne correction).
    profile : CamProfile, optional
        A cam given by points: its profile as :meth:`read_files` read it; None: read here.
    """

    #: the scene's section this mechanism is built from
    section_name = "cam"

    def __init__(self, section: CamSection, materials: dict, profile=None):
        self.section = section
        self.materials = materials
        #: the dry cam and follower as the section gives them
        self.design = cam_design(section, profile)
        #: the design whose motion the follower runs: the polydyne-corrected one where asked
        self.motion_design = self.design
        if self.design.polydyne_speed is not None:
            material = section.follower.material
            dry = float(materials[material].ply_properties(1.0)["e11"]) if material else None
            self.motion_design = polydyne_design(self.design, dry)
        #: the dry working profile, x and y [m]
        self.profile = working_profile(self.design)
        #: a drawn plate's outline and holes about the axis [m] (None: not drawn)
        self.planform = getattr(self.design.profile, "planform", None)
        self.elastic_parts = frozenset({"cam"} if section.elastic else ())
        #: a drawn cam whose aged profile is its outline displaced by its moisture field
        #: (none: the cam ages by its mean strains)
        self.field_parts = frozenset({"cam"} if self.planform is not None
                                     and section.aged_profile == "field" else ())

    # ---------------------------------------------------------- from the section alone

    @staticmethod
    def part_names(section: CamSection) -> tuple[str, ...]:
        """The parts that age, in their order: the cam, and the follower when it names a
        material; see :meth:`fickcam.mechanisms.Mechanism.part_names`."""
        return ("cam", "follower") if section.follower.material else ("cam",)

    @staticmethod
    def materials_used(section: CamSection) -> list[tuple[tuple, str]]:
        """(key path inside the section, material name) of every material it names; see
        :meth:`fickcam.mechanisms.Mechanism.materials_used`."""
        refs = [(("material",), section.material)]
        if section.follower.material:
            refs.append((("follower", "material"), section.follower.material))
        return refs

    @staticmethod
    def absorber_sizes(section: CamSection, files=None) -> list[tuple[str, str, float]]:
        """(part, material name, half-size [m]) of the bodies whose uptake time the scene's
        plausibility readings judge a history's length by: the cam (half of its thickness
        or radius, whichever is smaller) and a roller (half of its width or diameter); see
        :meth:`fickcam.mechanisms.Mechanism.absorber_sizes` (``files``: unused)."""
        radius = section.base_circle_radius or (section.eccentric.radius if section.eccentric
                                                else section.thickness)
        sizes = [("cam", section.material, 0.5 * min(section.thickness, radius))]
        follower = section.follower
        if follower.material and follower.roller_radius:
            width = follower.width or section.thickness
            sizes.append(("follower", follower.material,
                          0.5 * min(width, 2.0 * follower.roller_radius)))
        return sizes

    @staticmethod
    def section_problems(section: CamSection) -> list[tuple[tuple, str]]:
        """(key path inside the section, reason) for a swinging arm that does not fit; see
        :meth:`fickcam.mechanisms.Mechanism.section_problems`."""
        return arm_problems(section)

    @staticmethod
    def read_files(section: CamSection, base_dir: Path, read: dict, accuracy: float):
        """Read the file the section names (a cam given by points or drawn) once: (problems
        as (key path inside the section, reason), the section with the file's path
        absolute (a drawing's bore radius set), the profile
        (:class:`~fickcam.cam.profile.CamProfile`, mirrored for a clockwise cam) or None).
        ``read``: the points of the files this scene's validation has read, by path (a
        ``design:`` that keeps the shape reads no file twice), added to; ``accuracy``: the
        scene's [-], which sets a drawing's chord tolerance; see
        :meth:`fickcam.mechanisms.Mechanism.read_files`."""
        if section.drawing is not None or section.outline is not None:
            problems, section, profile, smallest = read_cam_drawing(section, base_dir, accuracy)
            if profile is None or problems:
                return problems, section, profile
            return _profile_problems(section, smallest), section, profile
        if section.profile_file is None:
            return [], section, None
        from .profile import profile_of, read_profile_csv  # only a cam given by points needs it

        path = str((base_dir / section.profile_file).resolve())
        section = section.model_copy(update={"profile_file": path})
        try:
            if path not in read:
                read[path] = read_profile_csv(path)
            profile = profile_of(read[path], section.follower.roller_radius or 0.0,
                                 mirror=section.direction == "clockwise")
        except (OSError, ValueError) as exc:
            return [(("profile_file",), str(exc))], section, None
        return _profile_problems(section, profile.radii()[0]), section, profile

    @staticmethod
    def coordinates(angles: np.ndarray) -> dict:
        """The coordinates of its results: ``cam_angle`` [rad]; see
        :meth:`fickcam.mechanisms.Mechanism.coordinates`."""
        return {"cam_angle": angles}

    # ------------------------------------------------------------------ the mechanism

    @cached_property
    def parts(self) -> tuple[Part, ...]:
        """The bodies that age, cam then follower (built on first use: the diffusion
        geometries are the run's, not the scene's validation's)."""
        # imported here: the geometries bring scipy.sparse, which validating a scene needs not
        from ..diffusion.problem.geometry import Bar, CamPlate, Disc, DrawnPlate

        section, design, (x, y) = self.section, self.design, self.profile
        density = self.materials[section.material].dry_density
        planform = self.planform
        if planform is not None:  # drawn: the plate with every hole (Green's theorem)
            cam_mass = planform.mass_properties(section.thickness, density).mass
            geometry = DrawnPlate(planform.outer.points, tuple(h.points for h in planform.holes),
                                  section.thickness, contact_holes=False)
        else:
            _, cam_mass, _ = plate_body(x, y, section.thickness, section.bore_radius, density)
            geometry = CamPlate(x, y, section.thickness, section.bore_radius)
        if section.eccentric is not None and section.bore_radius == 0:
            # a solid eccentric disc is a finite cylinder about its own centre: exact series
            geometry = Disc(section.eccentric.radius, section.thickness)
        names = self.part_names(section)
        parts = [Part.made(names[0], section.material, self.materials, geometry, float(cam_mass))]
        follower = section.follower
        if len(names) > 1:
            width = design.contact_length
            if design.arm is not None:  # the arm, a bar of the contact width, roller included
                geometry = Bar(design.arm.length or design.arm.pivot_distance, width, width)
            elif follower.kind == "roller":
                geometry = Disc(follower.roller_radius, width)
            else:
                geometry = Bar(4.0 * width, width, width)
            parts.append(Part.made(names[1], follower.material, self.materials, geometry,
                                   float(follower.mass)))
        return tuple(parts)

    def shape_problems(self) -> list[tuple[tuple, str]]:
        """A dry profile given by motion segments that is no cam: a flat face's profile
        with a cusp, or a roller's working profile with an undercut (its smallest convex
        radius of curvature at most 0); see :meth:`fickcam.mechanisms.Mechanism.shape_problems`.

        Returns
        -------
        list of tuple
            ``(("base_circle_radius",), reason)``, the reason naming the smallest base
            circle whose profile is a cam; empty when the profile is one.
        """
        from .sizing import profile_fault  # the sizing's search only for a faulty profile

        fault = profile_fault(self.design)
        return [] if fault is None else [(("base_circle_radius",), fault)]

    def described(self) -> list[str]:
        """What `fickcam check` says of the cam beyond its parts: a drawn plate's mass,
        centre of mass and moment of inertia, a swinging arm's follower (where it sits, the
        dry design's pressure angle and curvature).

        Returns
        -------
        list of str
            Lines, without indent; none for a cam not drawn with a translating follower.
        """
        lines = []
        if self.planform is not None:
            density = self.materials[self.section.material].dry_density
            lines.append(f"cam plate: {describe_plate(self.planform, self.section.thickness, density)}")
        if self.design.arm is None:
            return lines
        return lines + [f"follower: {describe_arm(self.design)}"]

    def response(self, histories: dict, times, angles, valid,
                 on_step=lambda: None) -> Response:
        """The cam over ageing: variables (time, ...) and notices; ``wear_depth`` accumulates
        the deepest Archard wear rate over the ageing times (trapezoid rule); the cam
        plate's elastic contact when the section asks for it.

        Parameters
        ----------
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
        aged = None
        if "cam" in self.field_parts:  # the profile its moisture field displaces
            aged = partial(aged_drawn_designs, self.motion_design, self.planform, histories["cam"])
        result = rigid_response(self.motion_design, histories, times, angles, valid, on_step, aged)
        if self.section.elastic:
            from ..elastic.cam import cam_elastic_response  # scikit-fem: only an elastic cam

            elastic = cam_elastic_response(self.design, histories["cam"].state,
                                           result.variables, valid)
            result.variables.update(elastic.variables)
            result.notices += elastic.notices
        return result


def _profile_problems(section: CamSection, smallest: float) -> list[tuple[tuple, str]]:
    """What a cam given by points (its smallest radius [m]) refuses: a bore that does not
    fit inside, an arm that does not reach, a follower offset beyond the prime circle."""
    problems = []
    if section.bore_radius >= smallest:
        problems.append((("bore_radius",), f"must be smaller than the profile's smallest "
                                           f"radius ({smallest * 1e3:g} mm)"))
    if section.follower.arm is not None:
        problems += reach_problems(section, smallest)
    reach = smallest + (section.follower.roller_radius or 0.0)
    if section.follower.kind != "flat" and abs(section.follower.offset) >= reach:
        problems.append((("follower", "offset"),
                         "follower offset must be smaller than the prime circle radius"))
    return problems


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


def rigid_response(design: CamDesign, histories: dict, times, angles, valid,
                   on_step=lambda: None, aged=None) -> Response:
    """The rigid cam of ``design`` over ageing (:meth:`CamMechanism.response` but the
    elastic contact).

    Parameters
    ----------
    design : CamDesign
        The design the follower's motion is computed from (polydyne-corrected where asked).
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
    aged : callable, optional
        ``aged(states)`` of the states by ageing index gives the design of each index whose
        profile is not the design's scaled by the state's strains (a drawn cam's displaced
        outline, :func:`fickcam.cam.drawn.aged_drawn_designs`); None: none.

    Returns
    -------
    fickcam.mechanisms.response.Response
        Variables over (time, ...) in SI, and the notices.
    """
    times = np.asarray(times, float)
    valid = np.asarray(valid, bool)
    states = {k: cam_state(design, histories, k) for k in np.flatnonzero(valid).tolist()}
    designs = {} if aged is None else aged(states)
    # the fitted motions made together, and every closed-form or fitted motion's jump speed
    # searched for all ageing times at once
    fitted = fitted_motions(design, states)
    fitted = None if fitted is None else fitted.sampled(angles)  # every time at once
    motions = {} if fitted is None else {k: fitted.motion(k) for k in fitted.indices}
    jumps = jump_speeds_over_ageing(design, states, angles, fitted)

    def evaluate(k: int) -> Response:
        state, aged_design = states[k], designs.get(k, design)
        response = cam_response(design, state, angles, jump_speed=jumps[k],
                                motion=motions.get(k)) if k in jumps \
            else follower_response(aged_design, state, angles)
        if design.train is not None:  # elastic follower train (Norton ch. 15)
            elastic = dynamic_response(aged_design, state, angles, response.variables)
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
