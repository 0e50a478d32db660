"""The scene's four-bar as a mechanism
(:class:`~fickcam.linkage.mechanism.LinkageMechanism`): built once from its ``linkage:``
section, it names its links and their materials, and answers the run's questions: which
bodies age, which coordinates its results have, and its response over the ageing times
(which part state feeds which link).

Each link (crank, coupler, rocker, frame) is a diffusion part of geometry
:class:`~fickcam.diffusion.problem.geometry.LinkBar`. At every ageing time its pin-to-pin
length is L (1 + eps_x) with eps_x the free hygrothermal strain along the link,
eps = alpha dT + beta dm (Singh & Sanyal 2016 eqs. 11-14, read as
a_1 = a (1 + alpha dT + beta dm); the printed a (alpha dT + beta dm) is a slip: it is the
change of length, not the wet length), and its mass and inertia come from
:func:`fickcam.materials.bodies.aged_link_body`. A metal frame only expands
thermally (eq. 14, last line).

The paper is cited in full in :mod:`fickcam.linkage`.
"""
from __future__ import annotations

from functools import cached_property

import numpy as np

from ..materials.bodies import aged_link_body, link_body
from ..mechanisms.ageing import over_ageing
from ..mechanisms.part import Part
from ..mechanisms.response import Response
from .classify import class_changes
from .drawn import (aged_drawn_body, aged_drawn_length, centre_fraction, describe_link,
                    in_plane_half_size, link_lengths, read_drawn_links)
from .dynamics import JOINTS
from .model import FourBarDesign, FourBarState, fourbar_response
from .spec import LinkageSection

#: the links, each a part that ages, in their order
LINKS = ("crank", "coupler", "rocker", "frame")


def _link_material(section, link: str) -> str:
    return section.frame_material or section.material if link == "frame" else section.material


class LinkageMechanism:
    """A four-bar, built once from the scene's ``linkage:`` section: its dry design and
    its links as parts.

    Parameters
    ----------
    section : LinkageSection
        The validated ``linkage:`` section (lengths and section [m]).
    materials : dict of str to Material
        The scene's resolved materials by name (the links' dry densities [kg/m^3] give
        their masses).
    files : dict of str to DrawnLink, optional
        The drawn links by name, as :meth:`read_files` read them (:mod:`fickcam.linkage.drawn`).
    """

    #: the scene's section this mechanism is built from
    section_name = "linkage"

    def __init__(self, section: LinkageSection, materials: dict, files=None):
        self.section = section
        self.materials = materials
        #: the drawn links by name (none: every link a bar between bosses)
        self.drawn = dict(files or {})
        #: the dry four-bar
        self.design = FourBarDesign.from_section(section, link_lengths(section, self.drawn))
        self.elastic_parts = frozenset(LINKS if section.elastic else ())
        #: the drawn links, each one's aged length its displaced pins' distance (none with
        #: ``aged_length: mean_strain``)
        self.field_parts = frozenset(self.drawn if section.aged_length == "field" else ())

    @staticmethod
    def part_names(section: LinkageSection) -> tuple[str, ...]:
        """The parts that age: the four links; see
        :meth:`fickcam.mechanisms.Mechanism.part_names`."""
        return LINKS

    @staticmethod
    def materials_used(section: LinkageSection) -> list[tuple[tuple, str]]:
        """(key path inside the section, material name) of every material it names; see
        :meth:`fickcam.mechanisms.Mechanism.materials_used`."""
        refs = [(("material",), section.material)]
        if section.frame_material:
            refs.append((("frame_material",), section.frame_material))
        return refs

    @staticmethod
    def absorber_sizes(section: LinkageSection, files=None) -> list[tuple[str, str, float]]:
        """(part, material name, half-size [m]) of the bodies whose uptake time the scene's
        plausibility readings judge a history's length by: the links given by their length
        (half of the section's thickness or width) and each drawn link (half of its
        thickness, or its planform's in-plane half-size,
        :func:`fickcam.linkage.drawn.in_plane_half_size`, whichever is smaller); see
        :meth:`fickcam.mechanisms.Mechanism.absorber_sizes`.

        Parameters
        ----------
        section : LinkageSection
            The validated section (thickness and width [m]).
        files : dict of str to DrawnLink, optional
            The drawn links by name, as :meth:`read_files` read them.

        Returns
        -------
        list of tuple
            (part, material name, half-size [m]).
        """
        s, drawn = section.section, dict(files or {})
        half = 0.5 * s.thickness
        sizes = [("links", section.material, min(half, 0.5 * s.width))] if \
            len(drawn) < len(LINKS) else []
        return sizes + [(link, section.material, min(half, in_plane_half_size(shape)))
                        for link, shape in drawn.items()]

    @staticmethod
    def section_problems(section: LinkageSection) -> list[tuple[tuple, str]]:
        """None: a four-bar's section is checked whole by its model; see
        :meth:`fickcam.mechanisms.Mechanism.section_problems`."""
        return []

    @staticmethod
    def read_files(section: LinkageSection, base_dir, read: dict, accuracy: float):
        """Read the drawn links (:func:`fickcam.linkage.drawn.read_drawn_links`): (problems
        as (key path inside the section, reason), the section with the drawings' paths
        absolute, the drawn links by name); see :meth:`fickcam.mechanisms.Mechanism.read_files`."""
        return read_drawn_links(section, base_dir, accuracy)

    @staticmethod
    def coordinates(angles: np.ndarray) -> dict:
        """The coordinates of its results: ``crank_angle`` [rad], ``link`` and ``joint``; see
        :meth:`fickcam.mechanisms.Mechanism.coordinates`."""
        return {"crank_angle": angles, "link": list(LINKS), "joint": list(JOINTS)}

    @cached_property
    def parts(self) -> tuple[Part, ...]:
        """The links as parts that age, each a link bar with bosses (built on first use:
        the diffusion geometries are the run's, not the scene's validation's)."""
        # imported here: the geometries bring scipy.sparse, which validating a scene needs not
        from ..diffusion.problem.geometry import DrawnPlate, LinkBar

        section, s = self.section, self.section.section
        parts = []
        for link, length in zip(self.part_names(section), self.design.lengths):
            name = _link_material(section, link)
            density = self.materials[name].dry_density
            if link in self.drawn:  # the drawn planform, every edge exposed
                planform = self.drawn[link].planform
                geometry = DrawnPlate(planform.outer.points,
                                      tuple(h.points for h in planform.holes), s.thickness)
                mass = planform.mass_properties(s.thickness, density).mass
            else:
                geometry = LinkBar(length, s.width, s.thickness, s.boss_outer_radius,
                                   s.boss_inner_radius)
                _, mass, _ = link_body(length, s.width, s.thickness, s.boss_outer_radius,
                                       s.boss_inner_radius, density)
            parts.append(Part.made(link, name, self.materials, geometry, float(mass)))
        return tuple(parts)

    def shape_problems(self) -> list[tuple[tuple, str]]:
        """What the built four-bar's shape cannot be: nothing that its section's checks
        (:meth:`section_problems`) have not refused already.

        Returns
        -------
        list of tuple
            Empty.
        """
        return []

    def described(self) -> list[str]:
        """What `fickcam check` says of the four-bar beyond its parts: each drawn link's
        length, dry mass and centre of mass along it.

        Returns
        -------
        list of str
            A line per drawn link, without indent.
        """
        thickness = self.section.section.thickness
        return [f"{link}: {describe_link(drawn, thickness, self.materials[self.section.material].dry_density)}"
                for link, drawn in self.drawn.items()]

    def response(self, histories: dict, times, angles, valid,
                 on_step=lambda: None, wanted=None) -> Response:
        """The four-bar over ageing (:func:`linkage_response`).

        Parameters
        ----------
        histories : dict of str to PartHistory
            The links' histories, by link name.
        times : array_like
            Ageing times [s].
        angles : array_like
            Crank angles over one turn [rad].
        valid : array_like of bool
            Per ageing time, whether every link is within its model's range.
        on_step : callable
            Called after each ageing time is evaluated (progress).
        wanted : frozenset of str, optional
            The variables the caller reads; unused (a four-bar's are all made together).

        Returns
        -------
        fickcam.mechanisms.response.Response
            SI variables over (time, ...) and the notices.
        """
        return linkage_response(self.section, histories, times, angles, valid, on_step,
                                self.design, self.drawn)


def link_states(section, histories, drawn=None):
    """The swollen links at every ageing time: lengths grown by the longitudinal strain,
    masses and inertias of the swollen, wet bodies, evaluated for the whole history at once.

    Parameters
    ----------
    section : LinkageSection
        The scene's validated ``linkage:`` section (dry lengths [m]).
    histories : dict of str to PartHistory
        Each link's history: strains [-] and moisture [weight %] over ageing time.
    drawn : dict of str to DrawnLink, optional
        The drawn links by name (:mod:`fickcam.linkage.drawn`).

    Returns
    -------
    tuple of numpy.ndarray
        Lengths [m], masses [kg] and moments of inertia about the centres of mass
        [kg m^2] of crank, coupler, rocker and frame, each of shape (ageing times, 4).
    """
    s, drawn = section.section, drawn or {}
    lengths, masses, inertias = [], [], []
    for link, length in zip(LINKS, link_lengths(section, drawn)):
        state = histories[link].state
        eps_x = np.asarray(state["strain_longitudinal"], float)
        lengths.append(aged_drawn_length(drawn[link], histories[link], eps_x) if link in drawn
                       else length * (1.0 + eps_x))
        if link in drawn:
            mass, inertia = aged_drawn_body(
                drawn[link], s.thickness, histories[link].part.material.dry_density,
                state["moisture_content"], eps_x, state["strain_transverse"])
            masses.append(mass)
            inertias.append(inertia)
            continue
        _, mass, inertia = aged_link_body(
            length, s.width, s.thickness, s.boss_outer_radius, s.boss_inner_radius,
            histories[link].part.material.dry_density,
            np.asarray(state["moisture_content"], float), eps_x,
            np.asarray(state["strain_transverse"], float),
            np.asarray(state["strain_through_thickness"], float))
        masses.append(mass)
        inertias.append(inertia)
    return tuple(np.stack(np.broadcast_arrays(*values), axis=-1)
                 for values in (lengths, masses, inertias))


def link_state(section, histories, k: int):
    """The swollen links at one ageing time: one row of :func:`link_states`.

    Parameters
    ----------
    section : LinkageSection
        The ``linkage:`` section, as for :func:`link_states` (lengths [m]).
    histories : dict of str to PartHistory
        The links' histories, as for :func:`link_states` (strains [-], moisture [weight %]).
    k : int
        Index of the ageing time [-].

    Returns
    -------
    tuple of numpy.ndarray
        Lengths [m], masses [kg] and moments of inertia [kg m^2] of crank, coupler,
        rocker and frame, each of shape (4,).
    """
    return tuple(values[k] for values in link_states(section, histories))


def linkage_response(section, histories: dict, times, angles, valid, on_step=lambda: None,
                     design: FourBarDesign | None = None, drawn=None) -> Response:
    """The linkage over ageing: variables (time, ...) and notices, including a warning
    where ageing changes the Grashof class or removes the crank's full rotation.
    Toggle positions are reported at the first and last computed ageing time.

    Parameters
    ----------
    section : LinkageSection
        The validated ``linkage:`` section of the scene.
    histories : dict of str to PartHistory
        The links' histories, by link name.
    times : array_like
        Ageing times [s].
    angles : array_like
        Crank angles over one turn [rad].
    valid : array_like of bool
        Per ageing time, whether every link is within its model's range (NaN where not).
    on_step : callable
        Called after each ageing time is evaluated (progress).
    design : FourBarDesign, optional
        The section's dry four-bar when already built; None: built here.
    drawn : dict of str to DrawnLink, optional
        The drawn links by name (:mod:`fickcam.linkage.drawn`).

    Returns
    -------
    fickcam.mechanisms.response.Response
        SI variables over (time, ...) and the notices.
    """
    drawn = drawn or {}
    design = (FourBarDesign.from_section(section, link_lengths(section, drawn))
              if design is None else design)
    valid = np.asarray(valid, bool)
    computed = np.nonzero(valid)[0]
    ends = {int(computed[0]), int(computed[-1])} if computed.size else set()
    states = link_states(section, histories, drawn)
    fractions = tuple(centre_fraction(drawn[link]) if link in drawn else fraction
                      for link, fraction in zip(LINKS, section.centre_of_mass))

    def evaluate(k: int) -> Response:
        lengths, masses, inertias = (values[k] for values in states)
        state = FourBarState(tuple(lengths), tuple(masses[:3]), tuple(inertias[:3]),
                             fractions)
        response = fourbar_response(design, state, angles)
        response.variables.update(link_length=lengths, link_mass=masses, link_inertia=inertias)
        response.notices = [n for n in response.notices
                            if k in ends or not n.startswith("toggle")]
        return response

    result = over_ageing(np.asarray(times, float), valid, evaluate, on_step)
    if "grashof_class" in result.variables:
        result.notices += class_changes(result.variables["grashof_class"], times)
    return result

