"""Mechanisms over ageing: what a mechanism is to the rest of fickcam
(:class:`~fickcam.mechanisms.Mechanism`), and which mechanisms there are
(:func:`~fickcam.mechanisms.mechanism_types`, one line each).

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

    Its class answers from its scene section alone, before any material is resolved:
    ``part_names``, ``materials_used``, ``absorber_sizes``, ``section_problems``,
    ``read_files``, ``coordinates``. An instance, built once from the validated section,
    the scene's resolved materials and what ``read_files`` read, holds what it is made of
    (its dry ``design``) and answers the run: ``parts``, ``elastic_parts``, ``field_parts``, ``described``,
    ``response``. Its as-designed values are its ``response`` to its parts' dry state.

    Parameters
    ----------
    section : pydantic.BaseModel
        Its validated section of the scene (SI).
    materials : dict of str to Material
        The scene's resolved materials by name.
    files : object, optional
        What ``read_files`` read for it (a cam's profile); None: nothing, or read here.
    """

    #: the key of its section in a scene (``cam``, ``linkage``)
    section_name: ClassVar[str]
    #: the names of its parts whose swelling stress the scene asks for
    elastic_parts: frozenset[str]
    #: the names of its parts whose moisture field over the planform its ``response``
    #: reads (a drawn link's aged length): their histories carry the field and the sheet
    field_parts: frozenset[str]

    def __init__(self, section, materials: dict, files=None) -> None: ...

    @staticmethod
    def part_names(section) -> tuple[str, ...]:
        """The names of the parts it builds, in their order: the one place they are given.

        Parameters
        ----------
        section : pydantic.BaseModel
            Its section.

        Returns
        -------
        tuple of str
            Part names, unique in a scene.
        """

    @staticmethod
    def materials_used(section) -> list[tuple[tuple, str]]:
        """Every material its section names.

        Parameters
        ----------
        section : pydantic.BaseModel
            Its section.

        Returns
        -------
        list of tuple
            (key path inside the section, material name).
        """

    @staticmethod
    def absorber_sizes(section, files=None) -> list[tuple[str, str, float]]:
        """The bodies whose moisture uptake time the plausibility readings judge a bare
        history length by (:func:`fickcam.quantities.plausibility.fastest_absorber`).

        Parameters
        ----------
        section : pydantic.BaseModel
            Its section.
        files : object, optional
            What :meth:`read_files` read (a drawn part's outline), or None.

        Returns
        -------
        list of tuple
            (part, material name, half-size [m]).
        """

    @staticmethod
    def section_problems(section) -> list[tuple[tuple, str]]:
        """What its section's model cannot check alone (a swinging arm that does not fit).

        Parameters
        ----------
        section : pydantic.BaseModel
            Its section.

        Returns
        -------
        list of tuple
            (key path inside the section, reason); empty when there is none.
        """

    @staticmethod
    def read_files(section, base_dir: Path, read: dict, accuracy: float) -> tuple[list, object, object]:
        """Read the files its section names, once per scene.

        Parameters
        ----------
        section : pydantic.BaseModel
            Its section.
        base_dir : pathlib.Path
            The folder the scene's relative paths start from.
        read : dict
            What the scene's validation has read so far, by path (added to).
        accuracy : float
            The scene's relative accuracy [-] (a drawing's chord tolerance follows it).

        Returns
        -------
        tuple
            (problems as (key path inside the section, reason), the section with its
            paths absolute, what was read: the constructor's ``files``).
        """

    @staticmethod
    def coordinates(angles: np.ndarray) -> dict:
        """The coordinates of its results.

        Parameters
        ----------
        angles : numpy.ndarray
            The output angles over a turn [rad].

        Returns
        -------
        dict
            Coordinate name -> values (its angle [rad], and e.g. links and joints).
        """

    @property
    def parts(self) -> tuple[Part, ...]:
        """The bodies that age, in the order of ``part_names``."""

    def shape_problems(self) -> list[tuple[tuple, str]]:
        """What its dry shape cannot be, found once it is built: a cam profile with a cusp
        or an undercut. A run and `fickcam check` refuse it; `fickcam size` starts from a
        size without it.

        Returns
        -------
        list of tuple
            (key path inside its section, reason); empty when there is none.
        """

    def described(self) -> list[str]:
        """What `fickcam check` prints of it beyond its parts.

        Returns
        -------
        list of str
            Lines without indent; empty when there is nothing to add.
        """

    def response(self, histories: dict, times, angles, valid,
                 on_step: Callable[[], object] = lambda: None,
                 wanted: frozenset | None = None) -> Response:
        """Its variables over the ageing times, from its parts' histories.

        Parameters
        ----------
        histories : dict of str to fickcam.simulation.parts.PartHistory
            The parts' histories by name (strains [-], moisture [weight %], moduli [Pa]).
        times : array_like
            The ageing times [s].
        angles : array_like
            The output angles over a turn [rad].
        valid : array_like of bool
            Per ageing time: its parts are within their models' range (NaN where not).
        on_step : callable
            Called once per ageing time evaluated (a progress bar).
        wanted : frozenset of str, optional
            The only variables the caller reads (the limit search's limited ones): what
            none of them needs may be left out, with its notices. None: every variable.

        Returns
        -------
        Response
            Variables over (time, ...) [SI, schema names] and the notices.
        """


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
