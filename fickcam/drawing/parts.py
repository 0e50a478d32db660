"""What a drawing means for a part: a cam's working profile, axis and bore; a link's pins.

A cam: the outer loop is the working profile; the axis is a point on the axis layer (as
``fickcam profile -o cam.dxf`` writes it), else the centre of the round hole nearest the
outline's centroid (the bore); the bore is the round hole about the axis, or a keyed one
(a round hole with a keyway cut into its edge: ``keyed_circle``). A link: the two pin holes
(``planform.pin_holes``), whose distance is its length.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .planform import DrawingError, Loop, Planform, edge_lengths, inside, pin_holes, where

AXIS_LAYER = "AXIS"
CENTRED = 1e-3  # a hole is about the axis when its centre is within 0.1 % of its radius
ON_ARC = 1e-3  # a keyed bore's vertices on its circle lie within 0.1 % of its radius of it
KEYED_SHARE = 0.5  # ... and carry at least half of its perimeter


@dataclass(frozen=True, eq=False)
class DrawnCam:
    """A cam plate as drawn, about its axis.

    Parameters
    ----------
    planform : Planform
        Outline and holes [m], moved so that the axis is the origin.
    bore : Loop or None
        The bore, a round hole about the axis.
    bore_radius : float
        Its radius [m] (0 without one).
    """

    planform: Planform
    bore: Loop | None
    bore_radius: float

    @property
    def profile(self) -> tuple[np.ndarray, np.ndarray]:
        """The working profile's points (x, y) [m], counter-clockwise about the axis."""
        points = self.planform.outer.points
        return points[:, 0].copy(), points[:, 1].copy()

    @property
    def smallest_radius(self) -> float:
        """The profile's smallest distance from the axis at its points [m]."""
        return float(np.hypot(*self.profile).min())

    @property
    def other_holes(self) -> tuple[Loop, ...]:
        """The holes besides the bore (a keyway, lightening holes)."""
        return tuple(h for h in self.planform.holes if h is not self.bore)


def keyed_circle(hole: Loop) -> tuple[np.ndarray, float] | None:
    """The circle a keyed hole is cut from: the least-squares circle (Kasa, A circle
    fitting procedure and its error analysis, IEEE Transactions on Instrumentation and
    Measurement, 1976) of the hole's vertices, refitted to those within ``ON_ARC`` of it;
    None unless those carry ``KEYED_SHARE`` of the perimeter (their edges between two of them).

    Parameters
    ----------
    hole : Loop
        The hole [m].

    Returns
    -------
    tuple or None
        The centre [m] and the radius [m].
    """
    points, on = hole.points, np.ones(len(hole.points), bool)
    for step in range(4):  # first the better half of the vertices, then those on the arc
        x, y = points[on].T
        a = np.column_stack([x, y, np.ones_like(x)])
        (cx2, cy2, c), *_ = np.linalg.lstsq(a, x * x + y * y, rcond=None)
        centre = np.array([cx2 / 2, cy2 / 2])
        radius = float(np.sqrt(max(c + centre @ centre, 0.0)))
        misfit = np.abs(np.hypot(*(points - centre).T) - radius)
        on = misfit <= (np.median(misfit) if step == 0 else ON_ARC * radius)
        if on.sum() < 3:
            return None
    edges = edge_lengths(points)
    arc = edges[on & np.roll(on, -1)].sum()
    return (centre, radius) if arc >= KEYED_SHARE * edges.sum() else None


def _circular_holes(planform: Planform) -> list[tuple[Loop, np.ndarray, float]]:
    """(hole, centre [m], radius [m]) of the round holes, then of the keyed ones."""
    found = [(h, np.asarray(planform.hole_centre(h)), r) for h, r in planform.round_holes()]
    round_ = {id(h) for h, _, _ in found}
    for hole in planform.holes:
        circle = None if id(hole) in round_ else keyed_circle(hole)
        if circle is not None:
            found.append((hole, *circle))
    return found


def cam_of(planform: Planform, points: dict | None = None, axis_layer: str = AXIS_LAYER) -> DrawnCam:
    """A cam from its planform: the axis, the bore, the profile about the axis.

    Parameters
    ----------
    planform : Planform
        The drawn planform [m].
    points : dict, optional
        The drawing's points by layer [m]; one on ``axis_layer`` is the axis.
    axis_layer : str
        The layer of the axis point.

    Returns
    -------
    DrawnCam
        The cam about its axis.

    Raises
    ------
    DrawingError
        Several axis points, no axis (no point, no round hole), or an axis outside the
        outline.
    """
    found = {k.casefold(): v for k, v in (points or {}).items()}.get(axis_layer.casefold(), [])
    if len(found) > 1:
        raise DrawingError(f"{len(found)} points on layer {axis_layer}: the cam's axis is one point")
    circles = _circular_holes(planform)
    if found:
        axis = np.asarray(found[0], float)
    elif circles:
        centre = np.asarray(planform.centroid)
        axis = min((c for _, c, _ in circles), key=lambda c: float(np.hypot(*(c - centre))))
    else:
        raise DrawingError(f"no axis: draw the bore as a circle, or a point on layer {axis_layer}")
    bore, radius = next(((h, r) for h, c, r in circles if np.hypot(*(c - axis)) <= CENTRED * r),
                        (None, 0.0))
    moved = planform.mapped(lambda p: p - axis)
    if bore is None and not _inside_outline(moved):
        raise DrawingError(f"the cam's axis {where(axis)} lies outside its outline")
    index = list(planform.holes).index(bore) if bore is not None else None
    return DrawnCam(moved, None if index is None else moved.holes[index], radius)


def _inside_outline(planform: Planform) -> bool:
    return bool(inside(np.zeros((1, 2)), planform.outer)[0])


@dataclass(frozen=True, eq=False)
class DrawnLink:
    """A link as drawn, its first pin at the origin and its second on +x.

    Parameters
    ----------
    planform : Planform
        Outline and holes [m] in the link's frame.
    pins : tuple of Loop
        The two pin holes (in ``planform``).
    """

    planform: Planform
    pins: tuple[Loop, Loop]

    @property
    def length(self) -> float:
        """The distance between the pin centres [m]."""
        a, b = (np.asarray(self.planform.hole_centre(h)) for h in self.pins)
        return float(np.hypot(*(b - a)))


def link_of(planform: Planform, pin_layer: str | None = None) -> DrawnLink:
    """A link from its planform: the pin holes, the frame with the first pin at the origin
    and the second on +x.

    Parameters
    ----------
    planform : Planform
        The drawn planform [m].
    pin_layer : str, optional
        The layer of the pin holes (default: the two largest round holes).

    Returns
    -------
    DrawnLink
        The link in its frame.

    Raises
    ------
    DrawingError
        No pin holes (``planform.pin_holes``).
    """
    first, second = pin_holes(planform, pin_layer)
    a, b = (np.asarray(planform.hole_centre(h)) for h in (first, second))
    angle = float(np.arctan2(*(b - a)[::-1]))
    c, s = np.cos(angle), np.sin(angle)
    frame = planform.mapped(lambda p: (p - a) @ np.array([[c, -s], [s, c]]))
    holes = list(planform.holes)
    return DrawnLink(frame, (frame.holes[holes.index(first)], frame.holes[holes.index(second)]))
