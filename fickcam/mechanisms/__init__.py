"""Mechanisms over ageing: what a mechanism is to the rest of fickcam (:class:`Mechanism`),
and which mechanisms there are (:func:`mechanism_types`, one line each).

A mechanism is built once, from its section of a validated scene and the scene's resolved
materials: it names its parts (:class:`~fickcam.mechanisms.part.Part`) and the materials
they are made of, gives the coordinates of its results and its response over the ageing
times to its parts' histories. The run (:mod:`fickcam.simulation.simulate`) asks only
these questions, so it has no branch per mechanism; its as-designed values are the
response of the scene's mechanisms as designed (``design:``) to their parts' dry state.

:mod:`fickcam.mechanisms.ageing` evaluates a mechanism at every ageing time and stacks its
arrays; :mod:`fickcam.mechanisms.response` is what one evaluation returns.
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable, ClassVar, Protocol

import numpy as np

from .part import Part
from .response import Response


class Mechanism(Protocol):
    """What a mechanism answers (:class:`fickcam.cam.mechanism.CamMechanism`,
    :class:`fickcam.linkage.mechanism.LinkageMechanism`).

    Its class answers from its scene section alone (before any material is resolved):
    ``part_names``, ``materials_used``, ``section_problems``, ``read_files``,
    ``coordinates``. An instance, built once from the validated section, the scene's
    materials and the files ``read_files`` read, holds what it is made of (its dry
    ``design``) and answers the run: ``parts``, ``elastic_parts``, ``response``.
    """

    #: the key of its section in a scene (``cam``, ``linkage``)
    section_name: ClassVar[str]
    #: the names of its parts whose swelling stress the scene asks for
    elastic_parts: frozenset[str]

    def __init__(self, section, materials: dict, files=None) -> None: ...

    @staticmethod
    def part_names(section) -> tuple[str, ...]:
        """The names of the parts it builds, in their order."""

    @staticmethod
    def materials_used(section) -> list[tuple[tuple, str]]:
        """(key path inside the section, material name) of every material it names."""

    @staticmethod
    def section_problems(section) -> list[tuple[tuple, str]]:
        """(key path inside the section, reason) of what its model cannot check alone."""

    @staticmethod
    def read_files(section, base_dir: Path, read: dict) -> tuple[list, object, object]:
        """(problems, the section with absolute paths, what was read) of the files it names."""

    @staticmethod
    def coordinates(angles: np.ndarray) -> dict:
        """Coordinate name -> values of its results (its angle [rad], ...)."""

    @property
    def parts(self) -> tuple[Part, ...]:
        """The bodies that age, in the order of ``part_names``."""

    def described(self) -> list[str]:
        """Lines `fickcam check` prints of it beyond its parts (none: nothing to add)."""

    def response(self, histories: dict, times, angles, valid,
                 on_step: Callable[[], object] = lambda: None) -> Response:
        """Its variables over (time, ...) [SI] and notices, from the parts' histories by name."""


def mechanism_types() -> dict[str, type]:
    """The registry: scene section -> the mechanism built from it, in the order of their
    parts in a run. A new mechanism is a module with its class and one line here.

    Returns
    -------
    dict of str to type
        Section name -> mechanism class.
    """
    # imported here, not at the top: each mechanism's module imports this package's part
    # and ageing modules, and the scene's validation imports this one
    from ..cam.mechanism import CamMechanism
    from ..linkage.mechanism import LinkageMechanism

    return {"cam": CamMechanism, "linkage": LinkageMechanism}


def scene_sections(model) -> dict[str, object]:
    """The mechanism sections a scene model gives, by name, in the registry's order.

    Parameters
    ----------
    model : fickcam.scene.sections.SceneModel
        The validated scene model.

    Returns
    -------
    dict
        Section name -> its validated section (only those the scene has).
    """
    return {name: getattr(model, name) for name in mechanism_types()
            if getattr(model, name, None) is not None}


__all__ = ["Mechanism", "Part", "Response", "mechanism_types", "scene_sections"]
