"""What compensation changes on a four-bar: the pin-to-pin length of every link (the
frame too: a steel frame still expands thermally) and the coupler point's distance from
the crank pin, which grows with the coupler (fickcam.linkage.model scales it with the
coupler's length). The link sections (width, thickness, bosses) are left as designed:
they carry the load, not the motion.

A drawn link (``linkage.crank: {drawing: crank.dxf}``) is made from its drawing scaled to
the made length (:func:`fickcam.compensation.drawn.made_link_writer`), written beside the
made scene as ``<stem>_<link>.dxf``, which the made scene's link names; a link written in
the scene (``outline:``, ``holes:``) is made the same way, in the scene (:func:`made_outline`). Where its aged
length is its displaced pins' distance (``aged_length: field``), the strain the
compensation takes up is that distance's, L_aged / L - 1 (the mean strain plus the
unevenness of its moisture field), not the mean strain alone.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..cam.drawn import DEFAULT_ACCURACY
from ..drawing.planform import pin_holes
from ..drawing.spec import RoundHole, polygon_key, polygon_of
from ..linkage.drawn import CHORD_SHARE
from ..linkage.mechanism import LINKS
from ..linkage.spec import DRAWN_LINKS, DrawnLinkSpec
from .core import Target
from .drawn import made_link_writer

LONGITUDINAL = ("strain_longitudinal",)
#: (the result variable, its coordinate, the target of its dry length) of a link's aged
#: pin-to-pin length
AGED_LENGTH = ("link_length", "link", "length")


def drawn_links(section) -> list[str]:
    """The links of a ``linkage`` section given by a drawing or an outline.

    Parameters
    ----------
    section : LinkageSection
        The validated section.

    Returns
    -------
    list of str
        Their names, in the section's order.
    """
    return [link for link in DRAWN_LINKS if isinstance(getattr(section, link), DrawnLinkSpec)]


def targets(section, points: bool = False, mechanism=None) -> list[Target]:
    """Link lengths (crank, coupler, rocker, frame) and the coupler point distance.

    Parameters
    ----------
    section : LinkageSection
        The design's validated ``linkage`` section.
    points : bool
        Compensate a profile's points (a cam's option; a four-bar has no profile).
    mechanism : LinkageMechanism, optional
        The design's four-bar (its dry lengths [m], a drawn link's between its pins);
        None: the lengths the section gives (a four-bar without a drawn link).

    Returns
    -------
    list of Target
        The dimensions, design values [m].

    """
    drawn = drawn_links(section)
    lengths = mechanism.design.lengths if drawn else [float(getattr(section, k)) for k in LINKS]
    field = set(drawn) if section.aged_length == "field" else set()
    found = [Target(link, "length", link, LONGITUDINAL, float(length),
                    grown=AGED_LENGTH if link in field else ())
             for link, length in zip(LINKS, lengths)]
    if section.coupler_point.distance > 0:
        found.append(Target("coupler", "coupler point distance", "coupler", LONGITUDINAL,
                            float(section.coupler_point.distance),
                            grown=AGED_LENGTH if "coupler" in field else ()))
    return found


def drawing_path(stem: Path, link: str) -> Path:
    """Where a drawn link's made drawing goes: ``<stem>_<link>.dxf``.

    Parameters
    ----------
    stem : pathlib.Path
        The made scene's path without its suffix (relative to its folder, or absolute).
    link : str
        The link's name.

    Returns
    -------
    pathlib.Path
        The drawing's path, as ``stem`` is (relative or absolute).
    """
    return stem.with_name(f"{stem.name}_{link}.dxf")


def made_drawings(scene, targets: list[Target], made: list, stem: Path) -> dict:
    """The made drawings of the design's drawn links: path -> writer (``tmp path -> None``).

    Parameters
    ----------
    scene : Scene
        The design scene (its ``linkage`` section with the drawings' paths absolute, and
        its accuracy).
    targets : list of Target
        The dimensions.
    made : list
        Their made values [m].
    stem : pathlib.Path
        The made scene's path without its suffix; each drawing is
        :func:`drawing_path` of it.

    Returns
    -------
    dict
        The drawings' paths -> their writers; empty without a drawn link.
    """
    if not scene.has("linkage"):
        return {}
    section = scene.mechanism("linkage").section
    accuracy = scene.model.diffusion.accuracy
    lengths = {t.part: (t.design, m) for t, m in zip(targets, made)
               if t.name == "length" and t.mechanism == "linkage"}
    return {drawing_path(stem, link): made_link_writer(getattr(section, link), accuracy,
                                                       lengths[link][1] / lengths[link][0])
            for link in drawn_links(section) if getattr(section, link).drawing is not None}


def _made_link(entry, path: Path) -> dict:
    """A drawn link's mapping (as the scene gives it) naming the made drawing ``path``."""
    entry = dict(entry)
    drawing = entry["drawing"]
    entry["drawing"] = {**({"file": drawing} if isinstance(drawing, str) else drawing),
                        "file": str(path)}
    return entry


def _scaled(points, centre, scale: float, length_text) -> list:
    """Points [m] scaled about ``centre`` [m], as the scene's text (to the picometre)."""
    moved = centre + (np.asarray(points, float) - centre) * scale
    return [[length_text(x, digits=9), length_text(y, digits=9)] for x, y in moved]


def made_outline(spec, scale: float, length_text) -> dict:
    """A link written in the scene (``outline:``, ``holes:``) made as a drawn one is
    (:mod:`fickcam.compensation.drawn`): scaled by ``scale`` about its first pin, its pin
    holes at their given size, carried with their centres.

    Parameters
    ----------
    spec : fickcam.linkage.spec.DrawnLinkSpec
        The design's link, with its ``outline`` and ``holes`` [m].
    scale : float
        The made pin-to-pin length over the design's [-].
    length_text : callable
        Length [m] -> the text the scene stores.

    Returns
    -------
    dict
        The made link's ``outline`` and ``holes``, lengths as text.
    """
    extent = max(max(abs(v) for v in point) for point in spec.outline)
    planform = polygon_of(spec.outline, spec.holes, CHORD_SHARE * DEFAULT_ACCURACY * extent)
    pins = {polygon_key(pin.source)[1]: np.asarray(planform.hole_centre(pin))
            for pin in pin_holes(planform)}
    first = pins[min(pins, key=lambda i: float(np.hypot(*pins[i])))]
    holes = []
    for i, hole in enumerate(spec.holes or ()):
        carried = (scale - 1.0) * (pins[i] - first) if i in pins else None
        if isinstance(hole, RoundHole):
            centre = _scaled([hole.centre], first, scale, length_text)[0]
            radius = hole.radius if carried is not None else hole.radius * scale
            holes.append({"centre": centre, "radius": length_text(radius, digits=9)})
        elif carried is not None:
            holes.append(_scaled(np.asarray(hole, float) + carried, 0.0, 1.0, length_text))
        else:
            holes.append(_scaled(hole, first, scale, length_text))
    return {"outline": _scaled(spec.outline, first, scale, length_text), "holes": holes}


def write(data: dict, section, targets: list[Target], made: list, stem: Path,
          length_text) -> None:
    """Put the made values into the scene's ``linkage:`` mapping (in place): a link given
    by its length its made length, a drawn link its made drawing (:func:`drawing_path`).

    Parameters
    ----------
    data : dict
        The made scene's YAML mapping.
    section : LinkageSection
        The design's validated ``linkage`` section (its lengths are all in ``targets``).
    targets : list of Target
        The dimensions.
    made : list
        Their made values [m].
    stem : pathlib.Path
        The made scene's path without its suffix (its drawings are named from it).
    length_text : callable
        Length [m] -> the text the scene stores.

    Returns
    -------
    None
        A four-bar has no points for the caller to write.
    """
    linkage, drawn = data["linkage"], drawn_links(section)
    for target, value in zip(targets, made):
        spec = getattr(section, target.part, None)
        if target.name == "length" and target.part in drawn and spec.drawing is None:
            linkage[target.part] = made_outline(spec, value / target.design, length_text)
        elif target.name == "length" and target.part in drawn:
            linkage[target.part] = _made_link(linkage[target.part],
                                              drawing_path(stem, target.part))
        elif target.name == "length":
            linkage[target.part] = length_text(value)
        else:
            point = dict(linkage.get("coupler_point") or {})
            point["distance"] = length_text(value)
            linkage["coupler_point"] = point


def design_entry(section: dict, targets=()) -> dict:
    """The ``design:`` entry of a compensated scene: the design's link lengths and point.

    Parameters
    ----------
    section : dict
        The design scene's ``linkage`` mapping.
    targets : list of Target
        The dimensions compensated (every link's: the entry names them all).

    Returns
    -------
    dict
        The entry, lengths as the scene gives them.
    """
    return {key: section[key] for key in LINKS + ("coupler_point",) if key in section}
