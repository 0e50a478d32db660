"""What compensation changes on a four-bar: the pin-to-pin length of every link (the
frame too: a steel frame still expands thermally) and the coupler point's distance from
the crank pin, which grows with the coupler (fickcam.linkage.model scales it with the
coupler's length). The link sections (width, thickness, bosses) are left as designed:
they carry the load, not the motion."""
from __future__ import annotations

from ..errors import InputError
from ..linkage.mechanism import LINKS
from ..linkage.spec import DRAWN_LINKS, DrawnLinkSpec
from .core import Target

LONGITUDINAL = ("strain_longitudinal",)


def targets(section, points: bool = False) -> list[Target]:
    """Link lengths (crank, coupler, rocker, frame) and the coupler point distance.

    Parameters
    ----------
    section : LinkageSection
        The design's validated ``linkage`` section.
    points : bool
        Compensate a profile's points (a cam's option; a four-bar has no profile).

    Returns
    -------
    list of Target
        The dimensions, design values [m].

    Raises
    ------
    fickcam.errors.InputError
        A drawn link, whose drawing compensation does not write yet.
    """
    drawn = [link for link in DRAWN_LINKS if isinstance(getattr(section, link), DrawnLinkSpec)]
    if drawn:
        raise InputError(f"linkage.{drawn[0]}: compensation does not write a drawn link yet; "
                         f"give its length to compensate it")
    found = [Target(link, "length", link, LONGITUDINAL, float(getattr(section, link)))
             for link in LINKS]
    if section.coupler_point.distance > 0:
        found.append(Target("coupler", "coupler point distance", "coupler", LONGITUDINAL,
                            float(section.coupler_point.distance)))
    return found


def write(data: dict, section, targets: list[Target], made: list, profile,
          length_text) -> None:
    """Put the made values into the scene's ``linkage:`` mapping (in place).

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
    profile : str
        A made cam's points file (a cam's; a four-bar writes none).
    length_text : callable
        Length [m] -> the text the scene stores.

    Returns
    -------
    None
        A four-bar has no points for the caller to write.
    """
    linkage = data["linkage"]
    for target, value in zip(targets, made):
        if target.name == "length":
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
