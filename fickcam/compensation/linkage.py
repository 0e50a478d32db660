"""What compensation changes on a four-bar: the pin-to-pin length of every link (the
frame too: a steel frame still expands thermally) and the coupler point's distance from
the crank pin, which grows with the coupler (fickcam.linkage.model scales it with the
coupler's length). The link sections (width, thickness, bosses) are left as designed:
they carry the load, not the motion.

A drawn link (``linkage.crank: {drawing: crank.dxf}``) is made from its drawing scaled to
the made length (:func:`fickcam.compensation.drawn.made_link_writer`), written beside the
made scene as ``<stem>_<link>.dxf``, which the made scene's link names. Where its aged
length is its displaced pins' distance (``aged_length: field``), the strain the
compensation takes up is that distance's, L_aged / L - 1 (the mean strain plus the
unevenness of its moisture field), not the mean strain alone.
"""
from __future__ import annotations

from pathlib import Path

from ..linkage.mechanism import LINKS
from ..linkage.spec import DRAWN_LINKS, DrawnLinkSpec
from ..errors import InputError
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

    Raises
    ------
    fickcam.errors.InputError
        A link given by ``outline:``, whose made outline compensation does not write.
    """
    drawn = drawn_links(section)
    outlined = [link for link in drawn if getattr(section, link).drawing is None]
    if outlined:
        raise InputError(f"linkage.{outlined[0]}: compensation writes a drawn link's made "
                         f"drawing; give the link as a drawing (drawing: FILE.dxf), or by "
                         f"its length")
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
            for link in drawn_links(section)}


def _made_link(entry, path: Path) -> dict:
    """A drawn link's mapping (as the scene gives it) naming the made drawing ``path``."""
    entry = dict(entry)
    drawing = entry["drawing"]
    entry["drawing"] = {**({"file": drawing} if isinstance(drawing, str) else drawing),
                        "file": str(path)}
    return entry


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
        if target.name == "length" and target.part in drawn:
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
