"""The made drawing of a drawn cam: the designer's DXF written again, compensated.

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
"""
from __future__ import annotations

import numpy as np

from ..cam.drawn import CHORD_SHARE
from ..drawing.dxfread import read_drawing
from ..drawing.dxfwrite import Similarity, write_drawing
from ..drawing.parts import CENTRED, cam_of
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


def _is_bore(piece, axis, radius: float) -> bool:
    """Whether a drawn piece lies on the bore's circle (``radius`` [m] about ``axis``)."""
    distance = np.hypot(*(piece.points - axis).T)
    return radius > 0 and bool(np.all(np.abs(distance - radius) <= CENTRED * radius))


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
    sx, sy = scales
    if abs(sx - sy) <= SAME_SCALE * abs(sx):
        move = Similarity(scale=sx, shift=tuple((1.0 - sx) * axis))
    else:
        def move(points):
            return axis + (np.asarray(points, float) - axis) * (sx, sy)
    kept = [p for p in drawing.pieces if _is_bore(p, axis, part.bore_radius)]
    return lambda tmp: write_drawing(tmp, drawing, move, kept=kept)
