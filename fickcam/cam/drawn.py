"""A cam plate as drawn (``cam.drawing``): its DXF drawing read into the working profile,
the axis and the bore (:func:`fickcam.drawing.parts.cam_of`), which then go the way of a
cam given by points.

The drawing is flattened within a chord tolerance tied to the scene's accuracy
(``CHORD_SHARE``): the chords' sagitta s changes a plate's area, and so its mean
moisture, by at most (2/3) s x perimeter / area, below 0.1 x accuracy for any plate
wider than 1/15 of its extent.
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ..drawing.dxfread import read_drawing
from ..drawing.parts import DrawnCam, cam_of
from ..drawing.planform import DrawingError
from ..extras import MissingExtra
from .profile import CamProfile, make_profile

#: the chord tolerance of a drawing, as a share of its extent times the scene's accuracy
CHORD_SHARE = 0.01
#: the accuracy a drawing is read at where no scene gives one (the scene's default)
DEFAULT_ACCURACY = 1e-3
#: a bore the section gives agrees with the drawing's within this [m]
BORE_AGREES = 1e-9


def drawn_cam(section, accuracy: float = DEFAULT_ACCURACY) -> DrawnCam:
    """The cam plate a section's ``drawing`` names (its path absolute or relative to the
    working folder).

    Parameters
    ----------
    section : CamSection
        The validated ``cam:`` section, with a ``drawing``.
    accuracy : float
        The scene's relative accuracy [-]; the chord tolerance is ``CHORD_SHARE`` x it x
        the drawing's extent.

    Returns
    -------
    fickcam.drawing.parts.DrawnCam
        The plate about its axis [m].

    Raises
    ------
    fickcam.drawing.planform.DrawingError
        A drawing that cannot be a cam, in one line.
    fickcam.extras.MissingExtra
        Without the ``dxf`` extra.
    """
    spec = section.drawing
    drawing = read_drawing(spec.file, CHORD_SHARE * accuracy, spec.units, relative=True)
    return cam_of(drawing.planform, drawing.points, spec.axis_layer)


def drawn_profile(section, part: DrawnCam) -> CamProfile:
    """The working profile of a drawn plate, mirrored for a clockwise cam
    (:mod:`fickcam.cam.kinematics`), carrying the plate's planform.

    Parameters
    ----------
    section : CamSection
        The validated ``cam:`` section.
    part : fickcam.drawing.parts.DrawnCam
        The plate about its axis [m].

    Returns
    -------
    CamProfile
        The closed dry working profile, its ``planform`` the drawn plate.
    """
    x, y = part.profile
    profile = make_profile(-x if section.direction == "clockwise" else x, y, "working")
    return replace(profile, planform=part.planform)


def read_cam_drawing(section, base_dir: Path, accuracy: float):
    """Read ``cam.drawing`` (relative to the scene): (problems as (key path inside the
    section, reason), the section with the drawing's path absolute and the drawing's bore
    radius, the :class:`CamProfile` or None, the profile's smallest radius [m]).

    Parameters
    ----------
    section : CamSection
        The validated ``cam:`` section, with a ``drawing``.
    base_dir : pathlib.Path
        The folder the scene's relative paths start from.
    accuracy : float
        The scene's relative accuracy [-].

    Returns
    -------
    tuple
        As above; the profile None when the drawing is refused.
    """
    path = str((base_dir / section.drawing.file).resolve())
    section = section.model_copy(update={"drawing": section.drawing.model_copy(
        update={"file": path})})
    try:
        part = drawn_cam(section, accuracy)
    except (DrawingError, MissingExtra) as exc:
        return [(("drawing",), str(exc))], section, None, 0.0
    if part.other_holes:
        sources = ", ".join(h.source for h in part.other_holes)
        return [(("drawing",), f"{path}: holes besides the bore ({sources}) are not modelled "
                               f"in a cam yet; draw the plate without them")], section, None, 0.0
    problems = []
    if ("bore_radius" in section.model_fields_set
            and abs(section.bore_radius - part.bore_radius) > BORE_AGREES):
        problems.append((("bore_radius",), f"the drawing's bore has radius "
                                           f"{part.bore_radius * 1e3:.6g} mm; leave bore_radius out"))
    section = section.model_copy(update={"bore_radius": part.bore_radius})
    return problems, section, drawn_profile(section, part), part.smallest_radius
