"""A part written back as a DXF drawing (ezdxf, the ``dxf`` extra), layer by layer.

Under a similarity (a uniform scale, a rotation, a shift) each entity is copied and
transformed by ezdxf: lines stay lines, arcs arcs, circles circles, polylines keep their
bulges. Under any other map (a strain field's displacement, a scale that differs along x
and y) each entity becomes a polyline through its mapped chord points, on its own layer.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..extras import require
from ..messages import quieter
from .planform import Planform
from ..files import replaced_atomically

OUTLINE_LAYER, HOLE_LAYER = "OUTLINE", "HOLES"


@dataclass(frozen=True)
class Similarity:
    """x -> scale R(angle) x + shift, in the drawing's plane.

    Parameters
    ----------
    scale : float
        The uniform scale [-].
    angle : float
        The rotation, counter-clockwise [rad].
    shift : tuple of float
        The translation [m].
    """

    scale: float = 1.0
    angle: float = 0.0
    shift: tuple[float, float] = (0.0, 0.0)

    def __call__(self, points) -> np.ndarray:
        """The mapped points [m], shape (n, 2)."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        p = np.asarray(points, float).reshape(-1, 2)
        return self.scale * (p @ np.array([[c, s], [-s, c]])) + np.asarray(self.shift, float)

    def matrix(self, unit: float):
        """The map as an ezdxf ``Matrix44`` in drawing units of ``unit`` [m]."""
        # deferred: keeps ezdxf off the start-up path
        from ezdxf.math import Matrix44

        return Matrix44.chain(Matrix44.scale(self.scale), Matrix44.z_rotate(self.angle),
                              Matrix44.translate(self.shift[0] / unit, self.shift[1] / unit, 0.0))


def _document(unit: float, layers):
    ezdxf = require("dxf")
    # deferred: keeps ezdxf off the start-up path
    from ezdxf.units import METER_FACTOR

    codes = [i for i, f in enumerate(METER_FACTOR) if f and math.isclose(1.0 / f, unit)]
    document = ezdxf.new("R2010", units=codes[0] if codes else 4)
    for name in sorted(set(layers) - {"0"}):
        document.layers.add(name)
    return document


def _save(document, path) -> Path:
    with replaced_atomically(path) as tmp:
        document.saveas(tmp)
    return Path(path)


def write_planform(path, planform: Planform, unit: float = 1e-3) -> Path:
    """Each loop as a closed polyline, on its own layer (``OUTLINE`` / ``HOLES`` when it has
    none), in a drawing of ``unit``.

    Parameters
    ----------
    path : str or pathlib.Path
        The DXF file (written atomically).
    planform : Planform
        The loops [m].
    unit : float
        The drawing's unit [m] (1e-3: millimetres).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    layers = [planform.outer.layer or OUTLINE_LAYER] + [h.layer or HOLE_LAYER for h in planform.holes]
    with quieter("ezdxf", logging.WARNING):
        document = _document(unit, layers)
        space = document.modelspace()
        for loop, layer in zip(planform.loops, layers):
            space.add_lwpolyline((loop.points / unit).tolist(), close=True,
                                 dxfattribs={"layer": layer})
        return _save(document, path)


def write_drawing(path, drawing, move, kept=(), carried=()) -> Path:
    """``drawing`` written again, every entity through ``move``, in its own unit and layers.

    Parameters
    ----------
    path : str or pathlib.Path
        The DXF file (written atomically).
    drawing : fickcam.drawing.dxfread.Drawing
        The drawing read, with its pieces.
    move : Similarity or callable
        A :class:`Similarity` (entities transformed as they are), or any map of points
        (n, 2) [m] -> (n, 2) [m] (entities as polylines through their mapped chord points).
    kept : sequence of Piece
        Pieces of ``drawing`` written as drawn, not moved (a cam's bore, which fits its shaft).
    carried : sequence of tuple
        (piece, map) pairs: pieces of ``drawing`` moved by a map of their own instead of
        ``move``, a :class:`Similarity` (a link's pin hole, carried with its centre at its
        drawn size) or any map of points (a cam's outline through its made vertices).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    unit = drawing.unit
    own = {id(piece): Similarity() for piece in kept}  # the identity: the entity as drawn
    own.update((id(piece), similarity) for piece, similarity in carried)
    with quieter("ezdxf", logging.WARNING):
        document = _document(unit, [p.layer for p in drawing.pieces])
        space = document.modelspace()
        for piece in drawing.pieces:
            piece_move = own.get(id(piece), move)
            if isinstance(piece_move, Similarity) and piece.entity is not None:
                copy = piece.entity.copy()
                copy.transform(piece_move.matrix(unit))
                space.add_foreign_entity(copy, copy=False)
            else:
                space.add_lwpolyline((np.asarray(piece_move(piece.points)) / unit).tolist(),
                                     close=piece.closed, dxfattribs={"layer": piece.layer})
        for layer, points in drawing.points.items():
            for point in np.asarray(move(np.asarray(points))) / unit:
                space.add_point(tuple(point), dxfattribs={"layer": layer})
        return _save(document, path)
