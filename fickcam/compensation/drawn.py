"""The made drawings of drawn parts: the designer's DXF written again, compensated.

A cam given by its drawing (``cam.drawing``) is compensated as points
(:mod:`fickcam.compensation.cam`): every x of the working profile by one scale, every y by
another, about the cam's axis. The same map, applied to the drawing, is the drawing to make.
Where the two scales are equal (a material that swells the same way in the plane) the map is
a similarity, a uniform scale about the axis, and every entity is scaled as it is (lines stay
lines, arcs arcs, circles circles: :func:`fickcam.drawing.dxfwrite.write_drawing`); otherwise
each entity becomes a polyline through its mapped chord points, which stray from the mapped
curve by no more than the chords strayed from the drawn one times the larger scale. The bore
is written as drawn, as the made scene keeps it (a bore fits its shaft); the axis point maps
to itself.

A drawn link (``linkage.crank: {drawing: ...}``) is compensated in its pin-to-pin length
(:mod:`fickcam.compensation.linkage`), L_made = L_design / (1 + eps). Its drawing to make is
the drawing scaled as a whole by L_made / L_design about its first pin, a similarity (lines,
arcs and circles stay as they are): the pins are then L_made apart, and the outline, web,
bosses and lightening holes are made as much smaller as the part swells back (for a material
that swells alike along and across the link, the aged part is the drawn one). The pin holes
keep their drawn diameter, each carried with its centre: a bearing or pin fits them at
assembly, dry, as a cam's bore fits its shaft.
"""
from __future__ import annotations

import numpy as np

from ..cam.drawn import CHORD_SHARE
from ..drawing.dxfread import JOIN, read_drawing
from ..drawing.dxfwrite import Similarity, write_drawing
from ..drawing.parts import cam_of
from ..drawing.planform import pin_holes
from ..linkage.drawn import CHORD_SHARE as LINK_CHORD_SHARE
from .cam import PROFILE_NAMES

#: two scales closer than this (relative) make a similarity
SAME_SCALE = 1e-12


def profile_scales(targets, made) -> tuple[float, float]:
    """The scales (x, y) [-] that made the working profile's points from the design's.

    Parameters
    ----------
    targets : list of fickcam.compensation.core.Target
        The compensation's targets, the profile's x and y among them.
    made : list
        Their made values [m].

    Returns
    -------
    tuple of float
        made / design along x and along y [-], each from the point farthest along it.
    """
    found = {t.name: (np.asarray(t.design, float), np.asarray(m, float))
             for t, m in zip(targets, made) if t.name in PROFILE_NAMES}
    scales = []
    for name in PROFILE_NAMES:
        design, value = found[name]
        k = int(np.argmax(np.abs(design)))
        scales.append(float(value[k] / design[k]))
    return scales[0], scales[1]


def pieces_of(drawing, loop) -> list:
    """The drawn pieces a loop of ``drawing`` was joined from: those whose every vertex is one
    of the loop's (within the join tolerance).

    Parameters
    ----------
    drawing : fickcam.drawing.dxfread.Drawing
        The drawing read, with its pieces [m].
    loop : fickcam.drawing.planform.Loop
        One of its planform's loops [m].

    Returns
    -------
    list of fickcam.drawing.pieces.Piece
        The pieces, in drawing order.
    """
    vertices = np.asarray(loop.points, float)
    found = []
    for piece in drawing.pieces:
        gaps = np.hypot(*(piece.points[:, None, :] - vertices[None, :, :]).transpose(2, 0, 1))
        if np.all(gaps.min(axis=1) <= JOIN):
            found.append(piece)
    return found


def scaled_about(centre, scales: tuple[float, float]):
    """x -> centre + (x - centre) (sx, sy): a :class:`~fickcam.drawing.dxfwrite.Similarity`
    where the two scales are equal (every entity kept as it is), else a map of points.

    Parameters
    ----------
    centre : array_like
        The fixed point (x, y) [m].
    scales : tuple of float
        The scales along x and y [-].

    Returns
    -------
    Similarity or callable
        The map, (n, 2) [m] -> (n, 2) [m].
    """
    centre = np.asarray(centre, float)
    sx, sy = scales
    if abs(sx - sy) <= SAME_SCALE * abs(sx):
        return Similarity(scale=sx, shift=tuple((1.0 - sx) * centre))

    def move(points):
        return centre + (np.asarray(points, float) - centre) * (sx, sy)
    return move


def made_drawing_writer(section, accuracy: float, scales: tuple[float, float]):
    """A writer of the made drawing: ``tmp path -> None``.

    Parameters
    ----------
    section : CamSection
        The design's validated ``cam`` section, with its ``drawing`` (path absolute).
    accuracy : float
        The scene's relative accuracy [-]: the drawing is read at the chord tolerance the
        run reads it at (:data:`fickcam.cam.drawn.CHORD_SHARE` x it x the drawing's extent).
    scales : tuple of float
        The made working profile's scales along x and y about the axis [-]
        (:func:`profile_scales`).

    Returns
    -------
    callable
        Writes the made drawing, in the drawing's unit and layers, to the path it is given.
    """
    spec = section.drawing
    drawing = read_drawing(spec.file, CHORD_SHARE * accuracy, spec.units, relative=True)
    part = cam_of(drawing.planform, drawing.points, spec.axis_layer)
    axis = drawing.planform.outer.points[0] - part.planform.outer.points[0]
    move = scaled_about(axis, scales)
    kept = []
    if part.bore is not None:  # the bore as drawn, in the drawing's own place
        bore = drawing.planform.holes[list(part.planform.holes).index(part.bore)]
        kept = pieces_of(drawing, bore)
    return lambda tmp: write_drawing(tmp, drawing, move, kept=kept)


def made_link_writer(spec, accuracy: float, scale: float):
    """A writer of a drawn link's made drawing (module docstring): ``tmp path -> None``.

    Parameters
    ----------
    spec : fickcam.linkage.spec.DrawnLinkSpec
        The design's link, with its ``drawing`` (path absolute) and pin layer.
    accuracy : float
        The scene's relative accuracy [-]: the drawing is read at the chord tolerance the
        run reads it at (:data:`fickcam.linkage.drawn.CHORD_SHARE` x it x its extent).
    scale : float
        The made pin-to-pin length over the design's [-].

    Returns
    -------
    callable
        Writes the made drawing, in the drawing's unit and layers, to the path it is given:
        the whole drawing scaled by ``scale`` about the first pin, the pin holes at their
        drawn size, each carried with its centre.
    """
    given = spec.drawing
    drawing = read_drawing(given.file, LINK_CHORD_SHARE * accuracy, given.units, relative=True)
    planform = drawing.planform
    pins = pin_holes(planform, given.pin_layer)
    first = np.asarray(planform.hole_centre(pins[0]))
    carried = [(piece, Similarity(shift=tuple((scale - 1.0) * (centre - first))))
               for pin, centre in ((p, np.asarray(planform.hole_centre(p))) for p in pins)
               for piece in pieces_of(drawing, pin)]
    move = scaled_about(first, (scale, scale))
    return lambda tmp: write_drawing(tmp, drawing, move, carried=carried)
