"""The made drawings of drawn parts: the designer's DXF written again, compensated.

A cam given by its drawing (``cam.drawing``) is compensated in the vertices of its drawn
outline (:mod:`fickcam.compensation.cam`). Its drawing to make: the outline through the made
vertices, every other entity (the lightening holes) mapped by the scales along x and y that
fit the made outline best about the axis (:func:`best_scales`), the bore with its keyway as
drawn (a bore fits its shaft, dry), the axis point where it was. Where the made outline is
that map too (the mean strain's compensation, ``aged_profile: mean_strain``) and its two
scales are equal (a material that swells the same way in the plane), the map is a
similarity, a uniform scale about the axis, and every entity is scaled as it is (lines stay
lines, arcs arcs, circles circles: :func:`fickcam.drawing.dxfwrite.write_drawing`);
otherwise each entity of the outline becomes a polyline through its made chord points, and
under two scales each other entity a polyline through its mapped chord points: these stray
from the made curve by no more than the drawn chords strayed from the drawn one, times the
larger scale.

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
from scipy.spatial import cKDTree

from ..cam.drawn import CHORD_SHARE
from ..drawing.dxfread import JOIN, read_drawing
from ..drawing.dxfwrite import Similarity, write_drawing
from ..drawing.parts import AXIS_LAYER, cam_of
from ..drawing.planform import circle_points, pin_holes
from ..drawing.spec import RoundHole, polygon_key, polygon_of
from ..linkage.drawn import CHORD_SHARE as LINK_CHORD_SHARE

#: two scales closer than this (relative) make a similarity
SAME_SCALE = 1e-12
#: two in-plane changes (a cam's strains along and across, a made outline's two best
#: scales' departures from 1) that differ by more than this share of the larger are
#: anisotropic: a parametric cam is then better made as points, a made plate's holes are
#: not scaled alike in x and y
ANISOTROPY = 0.1


def best_scales(design, made) -> tuple[float, float]:
    """The scales (x, y) [-] about the axis that take the design's outline vertices closest
    to the made ones (least squares: sum(m d) / sum(d d)), one for both axes where their
    changes from 1 agree within ``ANISOTROPY`` of the larger (a plate that swells alike in its
    plane, whose field's displacement alone sets them apart: its holes stay round), one per
    axis otherwise; exactly the made outline's where it is the design's scaled.

    Parameters
    ----------
    design, made : array_like
        The outline's vertices about the axis, designed and made [m], shape (n, 2).

    Returns
    -------
    tuple of float
        The scales along x and along y [-].
    """
    design, made = np.asarray(design, float), np.asarray(made, float)
    sx, sy = (made * design).sum(axis=0) / (design * design).sum(axis=0)
    if abs(sx - sy) <= ANISOTROPY * max(abs(1.0 - sx), abs(1.0 - sy)):
        sx = sy = float((made * design).sum() / (design * design).sum())
    return float(sx), float(sy)


def made_outline_holes(section, scales: tuple[float, float], tolerance: float) -> list:
    """The ``holes:`` of a cam plate written in the scene, made: the bore (the hole about the
    axis) as given, every other hole scaled about the axis (a round one stays round under
    one scale, else becomes the polygon of its mapped chord points).

    Parameters
    ----------
    section : CamSection
        The design's ``cam`` section, with its ``outline`` and ``holes`` [m].
    scales : tuple of float
        The made outline's scales along x and y about the axis [-] (:func:`best_scales`).
    tolerance : float
        The chord tolerance of a round hole that becomes a polygon [m].

    Returns
    -------
    list
        Per hole: ``(centre, radius)`` of a round one [m], or its vertices [m], (k, 2).
    """
    part = cam_of(polygon_of(section.outline, section.holes, tolerance), {AXIS_LAYER: [(0, 0)]})
    bore = None if part.bore is None else polygon_key(part.bore.source)[1]
    move = scaled_about((0.0, 0.0), scales)
    found = []
    for i, hole in enumerate(section.holes or ()):
        if i == bore and isinstance(hole, RoundHole):
            found.append((tuple(hole.centre), hole.radius))
        elif i == bore:
            found.append(np.asarray(hole, float))
        elif isinstance(hole, RoundHole) and isinstance(move, Similarity):
            found.append((tuple(move([hole.centre])[0]), hole.radius * move.scale))
        elif isinstance(hole, RoundHole):
            found.append(move(circle_points(hole.centre, hole.radius, tolerance)))
        else:
            found.append(move(hole))
    return found


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


def _vertex_map(design, made):
    """The map of the design's outline vertices [m] onto the made ones (each point taken to
    the made vertex of the design vertex it is)."""
    tree, made = cKDTree(design), np.asarray(made, float)

    def move(points):
        gap, index = tree.query(np.asarray(points, float).reshape(-1, 2))
        if np.any(gap > JOIN):
            raise ValueError("a point to move is not a vertex of the drawn outline")
        return made[index]
    return move


def made_cam_writer(section, accuracy: float, design, made):
    """A writer of a drawn cam's made drawing (module docstring): ``tmp path -> None``.

    Parameters
    ----------
    section : CamSection
        The design's validated ``cam`` section, with its ``drawing`` (path absolute).
    accuracy : float
        The scene's relative accuracy [-]: the drawing is read at the chord tolerance the
        run reads it at (:data:`fickcam.cam.drawn.CHORD_SHARE` x it x the drawing's extent).
    design, made : array_like
        The outline's vertices about the axis, designed (the drawing's, as the run reads
        them) and made [m], shape (n, 2).

    Returns
    -------
    callable
        Writes the made drawing, in the drawing's unit and layers, to the path it is given.
    """
    spec = section.drawing
    drawing = read_drawing(spec.file, CHORD_SHARE * accuracy, spec.units, relative=True)
    part = cam_of(drawing.planform, drawing.points, spec.axis_layer)
    axis = drawing.planform.outer.points[0] - part.planform.outer.points[0]
    design, made = np.asarray(design, float), np.asarray(made, float)
    scales = best_scales(design, made)
    move = scaled_about(axis, scales)
    kept, carried = [], []
    if part.bore is not None:  # the bore as drawn, in the drawing's own place
        bore = drawing.planform.holes[list(part.planform.holes).index(part.bore)]
        kept = pieces_of(drawing, bore)
    similar = np.abs(move(design + axis) - axis - made).max() <= SAME_SCALE * np.abs(made).max()
    if not (similar and isinstance(move, Similarity)):  # the outline through its made vertices
        outline = _vertex_map(design + axis, made + axis)
        carried = [(piece, outline) for piece in pieces_of(drawing, drawing.planform.outer)]
    return lambda tmp: write_drawing(tmp, drawing, move, kept=kept, carried=carried)


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
