"""The scene's four-bar over ageing: which part state feeds which link, and the
response stacked over ageing times (called by :mod:`fickcam.simulation.simulate`).

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

import numpy as np

from ..mechanisms.ageing import over_ageing
from ..mechanisms.response import Response
from .classify import class_changes
from .model import FourBarDesign, FourBarState, fourbar_response

LINKS = ("crank", "coupler", "rocker", "frame")


def _link_material(section, link: str) -> str:
    return section.frame_material or section.material if link == "frame" else section.material


def scene_parts(section, materials) -> list[tuple]:
    """The links as parts that age: each a link bar with bosses.

    Parameters
    ----------
    section : LinkageSection
        The scene's validated ``linkage:`` section (lengths and section in m).
    materials : dict of str to Material
        The scene's materials by name; the links' dry densities [kg/m^3] give their masses.

    Returns
    -------
    list of tuple
        (link name, material name, LinkBar with dimensions [m], dry mass [kg]) for crank,
        coupler, rocker and frame.
    """
    from ..diffusion.problem.geometry import LinkBar
    from ..materials.bodies import link_body

    s = section.section
    parts = []
    for link in LINKS:
        name = _link_material(section, link)
        length = getattr(section, link)
        geometry = LinkBar(length, s.width, s.thickness, s.boss_outer_radius, s.boss_inner_radius)
        _, mass, _ = link_body(length, s.width, s.thickness, s.boss_outer_radius,
                               s.boss_inner_radius, materials[name].dry_density)
        parts.append((link, name, geometry, float(mass)))
    return parts


def link_states(section, histories):
    """The swollen links at every ageing time: lengths grown by the longitudinal strain,
    masses and inertias of the swollen, wet bodies, evaluated for the whole history at once.

    Parameters
    ----------
    section : LinkageSection
        The scene's validated ``linkage:`` section (dry lengths [m]).
    histories : dict of str to PartHistory
        Each link's history: strains [-] and moisture [weight %] over ageing time.

    Returns
    -------
    tuple of numpy.ndarray
        Lengths [m], masses [kg] and moments of inertia about the centres of mass
        [kg m^2] of crank, coupler, rocker and frame, each of shape (ageing times, 4).
    """
    from ..materials.bodies import aged_link_body

    s = section.section
    lengths, masses, inertias = [], [], []
    for link in LINKS:
        state = histories[link].state
        eps_x = np.asarray(state["strain_longitudinal"], float)
        length = getattr(section, link)
        _, mass, inertia = aged_link_body(
            length, s.width, s.thickness, s.boss_outer_radius, s.boss_inner_radius,
            histories[link].part.material.dry_density,
            np.asarray(state["moisture_content"], float), eps_x,
            np.asarray(state["strain_transverse"], float),
            np.asarray(state["strain_through_thickness"], float))
        lengths.append(length * (1.0 + eps_x))
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


def scene_response(section, histories: dict, times, angles, valid, on_step=lambda: None) -> Response:
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

    Returns
    -------
    fickcam.mechanisms.response.Response
        SI variables over (time, ...) and the notices.
    """
    design = FourBarDesign.from_section(section)
    valid = np.asarray(valid, bool)
    computed = np.nonzero(valid)[0]
    ends = {int(computed[0]), int(computed[-1])} if computed.size else set()
    states = link_states(section, histories)

    def evaluate(k: int) -> Response:
        lengths, masses, inertias = (values[k] for values in states)
        state = FourBarState(tuple(lengths), tuple(masses[:3]), tuple(inertias[:3]),
                             tuple(section.centre_of_mass))
        response = fourbar_response(design, state, angles)
        response.variables.update(link_length=lengths, link_mass=masses, link_inertia=inertias)
        response.notices = [n for n in response.notices
                            if k in ends or not n.startswith("toggle")]
        return response

    result = over_ageing(np.asarray(times, float), valid, evaluate, on_step)
    if "grashof_class" in result.variables:
        result.notices += class_changes(result.variables["grashof_class"], times)
    return result

