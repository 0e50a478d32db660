"""A cam plate as drawn (``cam.drawing``) or written in the scene (``cam.outline`` with
``cam.holes``, about the axis at the origin): read into the working profile, the axis and
the bore (:func:`fickcam.drawing.parts.cam_of`), which then go the way of a cam given by
points. A bore given by ``bore_radius`` alone is added to the plate as a round hole. The
plate ages with all its holes (a keyed bore, lightening holes), every edge exposed
(:class:`fickcam.diffusion.problem.geometry.DrawnPlate`).

The drawing is flattened within a chord tolerance tied to the scene's accuracy
(``CHORD_SHARE``): the chords' sagitta s changes a plate's area, and so its mean
moisture, by at most (2/3) s x perimeter / area, below 0.1 x accuracy for any plate
wider than 1/15 of its extent.
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from ..drawing.dxfread import read_drawing
from ..drawing.parts import AXIS_LAYER, DrawnCam, cam_of
from ..drawing.planform import DrawingError, Loop, circle_points
from ..drawing.spec import polygon_key, polygon_of
from ..extras import MissingExtra
from .profile import CamProfile, make_profile

#: the chord tolerance of a drawing, as a share of its extent times the scene's accuracy
CHORD_SHARE = 0.01
#: the accuracy a drawing is read at where no scene gives one (the scene's default)
DEFAULT_ACCURACY = 1e-3
#: a bore the section gives agrees with the drawing's within this [m]
BORE_AGREES = 1e-9
#: the displacement mesh's edge, a share 1/MESH_ROWS of the plate's extent (P2 elements, as
#: a drawn link's: :data:`fickcam.linkage.drawn.MESH_ROWS`)
MESH_ROWS = 100


def drawn_cam(section, accuracy: float = DEFAULT_ACCURACY) -> DrawnCam:
    """The cam plate a section's ``drawing`` names (its path absolute or relative to the
    working folder), or its ``outline`` and ``holes``.

    Parameters
    ----------
    section : CamSection
        The validated ``cam:`` section, with a ``drawing`` or an ``outline``.
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
    if spec is None:
        extent = max(max(abs(v) for v in point) for point in section.outline)
        planform = polygon_of(section.outline, section.holes, CHORD_SHARE * accuracy * extent)
        return cam_of(planform, {AXIS_LAYER: [(0.0, 0.0)]})
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
    fickcam.cam.profile.CamProfile
        The closed dry working profile, its ``planform`` the drawn plate.
    """
    x, y = part.profile
    profile = make_profile(-x if section.direction == "clockwise" else x, y, "working")
    return replace(profile, planform=part.planform)


def with_bore(part: DrawnCam, radius: float, accuracy: float = DEFAULT_ACCURACY) -> DrawnCam:
    """The plate with a round bore about the axis added, where it has none.

    Parameters
    ----------
    part : fickcam.drawing.parts.DrawnCam
        The plate about its axis [m].
    radius : float
        The bore's radius [m] (0: none).
    accuracy : float
        The scene's relative accuracy [-] (the bore's chords stray ``CHORD_SHARE`` x it x
        the radius at most).

    Returns
    -------
    fickcam.drawing.parts.DrawnCam
        The plate, its bore drawn.
    """
    if part.bore is not None or radius <= 0:
        return part
    bore = Loop(circle_points((0.0, 0.0), radius, CHORD_SHARE * accuracy * radius)[::-1], "",
                "bore_radius")
    planform = replace(part.planform, holes=(*part.planform.holes, bore))
    return DrawnCam(planform, bore, radius)


def read_cam_drawing(section, base_dir: Path, accuracy: float):
    """Read ``cam.drawing`` (relative to the scene), or ``cam.outline`` with ``cam.holes``:
    (problems as (key path inside the section, reason), the section with the drawing's path
    absolute and the plate's bore radius, the :class:`~fickcam.cam.profile.CamProfile` or
    None, the profile's smallest radius [m]).

    Parameters
    ----------
    section : CamSection
        The validated ``cam:`` section, with a ``drawing`` or an ``outline``.
    base_dir : pathlib.Path
        The folder the scene's relative paths start from.
    accuracy : float
        The scene's relative accuracy [-].

    Returns
    -------
    tuple
        As above; the profile None when the plate is refused.
    """
    drawn = section.drawing is not None
    if drawn:
        path = str((base_dir / section.drawing.file).resolve())
        section = section.model_copy(update={"drawing": section.drawing.model_copy(
            update={"file": path})})
    try:
        part = drawn_cam(section, accuracy)
    except (DrawingError, MissingExtra) as exc:
        return [(("drawing",) if drawn else polygon_key(str(exc)), str(exc))], section, None, 0.0
    problems = []
    if part.other_holes and part.bore is None and section.elastic:
        sources = ", ".join(h.source for h in part.other_holes)
        problems.append((("elastic",), f"the elastic contact holds a plate with holes ({sources}) "
                                       f"at its bore, and this one has none: draw the bore, or "
                                       f"leave elastic out"))
    given = "bore_radius" in section.model_fields_set
    if given and part.bore is not None and abs(section.bore_radius - part.bore_radius) > BORE_AGREES:
        problems.append((("bore_radius",), f"the plate's bore has radius "
                                           f"{part.bore_radius * 1e3:.6g} mm; leave bore_radius out"))
    part = with_bore(part, section.bore_radius if given else 0.0, accuracy)
    section = section.model_copy(update={"bore_radius": part.bore_radius})
    return problems, section, drawn_profile(section, part), part.smallest_radius


def aged_drawn_designs(design, planform, history, states: dict) -> dict:
    """The design of each ageing time whose working profile is the drawn outline displaced
    by the plate's moisture field (``cam.aged_profile: field``): the mean strains' scaling
    (1 + eps_x, 1 + eps_y) about the axis plus the displacement of the field's unevenness
    (:func:`fickcam.elastic.displacement.uneven_outline_shifts`), carried as the dry profile
    through the outline's points moved by that displacement over (1 + eps), so that the
    state's strains scale it onto the displaced outline. A uniform field moves nothing:
    today's scaled profile, to round-off.

    Parameters
    ----------
    design : CamDesign
        The dry design, its profile the drawn outline (mirrored for a clockwise cam).
    planform : fickcam.drawing.planform.Planform
        The plate as drawn, about its axis [m].
    history : fickcam.simulation.parts.PartHistory
        The cam's ageing: its diffusion fields and sheet [weight %], its moisture
        expansion along x and y [1/weight %].
    states : dict of int to CamState
        The aged state at each ageing index (the cam's strains along x and y [-]).

    Returns
    -------
    dict of int to CamDesign
        The design at each of those indices; empty where the history holds no field (the
        as-designed state, a state given directly).
    """
    shifts = outline_shifts(planform, history) if states else None
    if shifts is None:
        return {}
    (x, y), mirror = planform.outer.points.T, -1.0 if design.clockwise else 1.0
    designs = {}
    for k, state in states.items():
        px = x + shifts[k, :, 0] / (1.0 + state.cam_strain_x)
        py = y + shifts[k, :, 1] / (1.0 + state.cam_strain_y)
        profile = replace(make_profile(mirror * px, py, "working"), planform=planform)
        designs[k] = replace(design, profile=profile)
    return designs


def outline_shifts(planform, history) -> np.ndarray | None:
    """The displacement of a drawn plate's outline by its moisture field's unevenness, about
    its axis, at each ageing time (:func:`fickcam.elastic.displacement.uneven_outline_shifts`
    on a mesh of edge 1/``MESH_ROWS`` of the plate's extent).

    Parameters
    ----------
    planform : fickcam.drawing.planform.Planform
        The plate as drawn, about its axis [m].
    history : fickcam.simulation.parts.PartHistory
        The cam's ageing: its diffusion fields and sheet [weight %], its moisture
        expansion along x and y [1/weight %].

    Returns
    -------
    numpy.ndarray or None
        The displacement of each outline vertex [m], shape (times, n, 2); None where the
        history holds no field (the as-designed state, a state given directly).
    """
    if getattr(history.diffusion, "fields", None) is None or history.sheet is None:
        return None
    # imported here: scikit-fem and scipy's interpolation, which only a drawn cam's run needs
    from ..elastic.displacement import field_inputs, uneven_outline_shifts

    moisture, expansion, stiffness = field_inputs(history, planform)
    return uneven_outline_shifts(planform, moisture, expansion, planform.extent() / MESH_ROWS,
                                 stiffness=stiffness)


def describe_plate(planform, thickness: float, density: float) -> str:
    """``M g, centre of mass (x, y) mm from the axis, J kg m^2 about it`` of a drawn plate
    (:meth:`fickcam.drawing.planform.Planform.mass_properties`).

    Parameters
    ----------
    planform : fickcam.drawing.planform.Planform
        The plate about its axis [m].
    thickness : float
        The plate's thickness [m].
    density : float
        Its dry density [kg/m^3].

    Returns
    -------
    str
        The line: four significant digits (the chords change the area by less than
        ``CHORD_SHARE`` x the accuracy), the centre to the micrometre.
    """
    mass = planform.mass_properties(thickness, density)
    about_axis = mass.inertia + mass.mass * float(np.hypot(*mass.centre)) ** 2
    x, y = np.round(np.asarray(mass.centre) * 1e3, 3) + 0.0  # to the micrometre, no -0
    return (f"{mass.mass * 1e3:.4g} g, centre of mass ({x:g}, {y:g}) mm from the axis, "
            f"moment of inertia {about_axis:.4g} kg m^2 about it (dry)")
