"""Pieces of a drawing (flattened entities) joined end to end into closed loops.

A designer draws an outline as separate lines and arcs whose ends meet only to the
drawing's precision; two ends closer than the join tolerance are one point.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .planform import DrawingError, Loop, where


@dataclass(frozen=True, eq=False)
class Piece:
    """One drawn entity, flattened to a polyline.

    Parameters
    ----------
    points : numpy.ndarray
        The vertices [m], shape (k, 2), in drawing order; a closed piece does not repeat its
        first vertex at the end.
    closed : bool
        The entity closes on itself (a circle, a closed polyline).
    kind : str
        The entity's DXF type (``LINE``, ``ARC``...).
    layer : str
        Its layer.
    entity : object
        The entity itself (for writing it back), or None.
    """

    points: np.ndarray
    closed: bool
    kind: str
    layer: str
    entity: object = field(default=None, repr=False)

    @property
    def source(self) -> str:
        """``KIND on layer LAYER`` for messages."""
        return f"{self.kind} on layer {self.layer or '0'}"


def _gap(a, b) -> float:
    return float(np.hypot(*(np.asarray(a) - np.asarray(b))))


def _chain(start: Piece, open_pieces: list[Piece], tolerance: float) -> list[np.ndarray]:
    """The polylines of one loop, from ``start`` on, taking pieces from ``open_pieces``."""
    chain = [start.points]
    while _gap(chain[-1][-1], chain[0][0]) > tolerance:
        end = chain[-1][-1]
        ends = [(min(_gap(end, p.points[0]), _gap(end, p.points[-1])), i)
                for i, p in enumerate(open_pieces)]
        best = min(ends, default=(np.inf, -1))
        if best[0] > tolerance:
            raise DrawingError(
                f"open loop: the {start.source} and what joins it end at {where(end)}, no other "
                f"entity starts within {tolerance * 1e3:.3g} mm of that point")
        piece = open_pieces.pop(best[1])
        chain.append(piece.points if _gap(end, piece.points[0]) <= _gap(end, piece.points[-1])
                     else piece.points[::-1])
    return chain


def join(pieces: list[Piece], tolerance: float) -> list[Loop]:
    """Closed loops from pieces: closed ones alone, open ones joined end to end.

    Parameters
    ----------
    pieces : list of Piece
        The flattened entities [m].
    tolerance : float
        The largest gap between two ends that meet [m].

    Returns
    -------
    list of Loop
        The loops [m], each named by its first piece (and how many more it took).

    Raises
    ------
    DrawingError
        An open loop: names the entity where the chain stops, its layer and the point.
    """
    loops = [Loop(p.points, p.layer, p.source) for p in pieces if p.closed]
    open_pieces = [p for p in pieces if not p.closed]
    while open_pieces:
        start = open_pieces.pop(0)
        count = len(open_pieces)
        chain = _chain(start, open_pieces, tolerance)
        points = np.vstack([chain[0]] + [c[1:] for c in chain[1:]])
        if _gap(points[-1], points[0]) <= tolerance:
            points = points[:-1]
        more = count - len(open_pieces)
        source = start.source + (f" and {more} more" if more else "")
        loops.append(Loop(points, start.layer, source))
    return loops
