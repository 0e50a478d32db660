"""The scene's four-bar over ageing: which part state feeds which link, and the
response stacked over ageing times (called by :mod:`fickcam.simulate`).

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

from ..mechanisms import over_ageing
from ..response import Response
from .classify import class_changes
from .model import FourBarDesign, FourBarState, fourbar_response

LINKS = ("crank", "coupler", "rocker", "frame")


def _link_material(section, link: str) -> str:
    return section.frame_material or section.material if link == "frame" else section.material


def scene_parts(section, materials) -> list[tuple]:
    """(part name, material name, diffusion geometry, dry mass kg) for each link."""
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
    """(lengths, masses, inertias) of crank, coupler, rocker, frame at every ageing time,
    each shape (times, 4): the bodies are vectorised over the times (one evaluation for
    the whole history, not one per ageing time)."""
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
    """(lengths, masses, inertias) of crank, coupler, rocker, frame at ageing index k."""
    return tuple(values[k] for values in link_states(section, histories))


def scene_response(section, histories: dict, times, angles, valid, on_step=lambda: None) -> Response:
    """The linkage over ageing: variables (time, ...) and notices, including a warning
    where ageing changes the Grashof class or removes the crank's full rotation.
    Toggle positions are reported at the first and last computed ageing time."""
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

