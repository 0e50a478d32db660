r"""A part's planform as drawn: one outer loop and its holes, in metres, checked for being a
part, and its area, centre and second moments by Green's theorem.

For a polygon with vertices :math:`(x_i, y_i)`, :math:`i = 0 \ldots n-1` taken cyclically,
and :math:`c_i = x_i y_{i+1} - x_{i+1} y_i` (Steger, On the calculation of arbitrary
moments of polygons, Technical Report FGBV-96-05, TU Munich, 1996, eqs. 5-8; Green's
theorem turns each area integral into a sum over the edges):

.. math::

    A = \tfrac{1}{2} \sum_i c_i, \qquad
    S_x = \tfrac{1}{6} \sum_i (x_i + x_{i+1})\, c_i = A\, x_c, \qquad
    S_y = \tfrac{1}{6} \sum_i (y_i + y_{i+1})\, c_i = A\, y_c,

    I_{yy} = \tfrac{1}{12} \sum_i (x_i^2 + x_i x_{i+1} + x_{i+1}^2)\, c_i = \int x^2\, dA,
    \qquad
    I_{xx} = \tfrac{1}{12} \sum_i (y_i^2 + y_i y_{i+1} + y_{i+1}^2)\, c_i = \int y^2\, dA,

    I_{xy} = \tfrac{1}{24} \sum_i (x_i y_{i+1} + 2 x_i y_i + 2 x_{i+1} y_{i+1}
    + x_{i+1} y_i)\, c_i.

The outer loop runs counter-clockwise and the holes clockwise, so that each sum over all
loops is the planform's (material on the left of every loop). These are exact for the
polygon; a drawn arc flattened to chords of sagitta at most ``tolerance`` changes the area
by less than (2/3) x perimeter x tolerance.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError

ROUND = 0.1  # a hole is round when its vertices' and edge midpoints' distances from its centre
             # differ by less than 10 % (a regular octagon's by 7.6 %, a square's by 29 %)


class DrawingError(InputError, ValueError):
    """A drawing (or a scene's polygon) that cannot be a part: one line naming the entity
    and its layer. A ValueError too, so that a scene's checks report it at its key.

    Parameters
    ----------
    *args
        The message.
    """


def _frozen(points) -> np.ndarray:
    array = np.array(points, dtype=float).reshape(-1, 2)
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class Loop:
    """A closed polyline (last point not repeated) and what it was drawn as.

    Parameters
    ----------
    points : numpy.ndarray
        The vertices [m], shape (n, 2) (copied and made read-only).
    layer : str
        The drawing layer ("" when written in a scene).
    source : str
        What drew it, for messages (``"CIRCLE on layer HOLES"``, ``"given as outline"``).
    """

    points: np.ndarray
    layer: str = ""
    source: str = ""

    def __post_init__(self):
        object.__setattr__(self, "points", _frozen(self.points))

    def reversed(self) -> Loop:
        """The same loop run the other way."""
        return replace(self, points=self.points[::-1])

    def mapped(self, points) -> Loop:
        """The same loop through new vertices [m] (a displaced or scaled copy)."""
        return replace(self, points=points)


def edge_lengths(points: np.ndarray) -> np.ndarray:
    """The lengths of a closed loop's edges, from each vertex to the next [m].

    Parameters
    ----------
    points : numpy.ndarray
        The loop's vertices, shape (n, 2) [m], the last joined to the first.

    Returns
    -------
    numpy.ndarray
        Shape (n,) [m].
    """
    return np.hypot(*(np.roll(points, -1, axis=0) - points).T)


def edge_sums(points: np.ndarray) -> np.ndarray:
    """(A, S_x, S_y, I_xx, I_yy, I_xy) of one closed polygon about the origin, signed by
    its orientation (positive counter-clockwise), by Green's theorem (module docstring).

    Parameters
    ----------
    points : numpy.ndarray
        The vertices [m], shape (n, 2), last not repeating the first.

    Returns
    -------
    numpy.ndarray
        Area [m^2], first moments [m^3] and second moments [m^4].

    References
    ----------
    C. Steger, On the calculation of arbitrary moments of polygons, TU Munich, Technical
    Report FGBV-96-05, 1996.
    """
    x, y = np.asarray(points, float).T
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    c = x * yn - xn * y
    return np.array([c.sum() / 2, ((x + xn) * c).sum() / 6, ((y + yn) * c).sum() / 6,
                     ((y * y + y * yn + yn * yn) * c).sum() / 12,
                     ((x * x + x * xn + xn * xn) * c).sum() / 12,
                     ((x * yn + 2 * x * y + 2 * xn * yn + xn * y) * c).sum() / 24])


def signed_area(points: np.ndarray) -> float:
    """Shoelace area [m^2], positive for a counter-clockwise polygon.

    Parameters
    ----------
    points : numpy.ndarray
        The vertices [m], shape (n, 2).

    Returns
    -------
    float
        The signed area [m^2].
    """
    return float(edge_sums(points)[0])


@dataclass(frozen=True)
class MassProperties:
    """A plate's mass, centre of mass and moment of inertia.

    Parameters
    ----------
    mass : float
        ``density`` x ``thickness`` x area [kg].
    centre : tuple of float
        The centre of mass in the drawing's plane [m].
    inertia : float
        About the axis normal to the plate through the centre of mass [kg m^2].
    """

    mass: float
    centre: tuple[float, float]
    inertia: float


@dataclass(frozen=True, eq=False)
class Planform:
    """A part's outline (counter-clockwise) and holes (clockwise), in metres.

    Build one with :func:`planform_of` (checked); the constructor checks nothing.

    Parameters
    ----------
    outer : Loop
        The outline [m].
    holes : tuple of Loop
        The holes [m].
    """

    outer: Loop
    holes: tuple[Loop, ...] = field(default=())

    @property
    def loops(self) -> list[Loop]:
        """Outer loop first, then the holes: material on the left of each."""
        return [self.outer, *self.holes]

    def sums(self) -> np.ndarray:
        """(A, S_x, S_y, I_xx, I_yy, I_xy) of the planform about the origin [m^2..m^4]."""
        return sum(edge_sums(loop.points) for loop in self.loops)

    @property
    def area(self) -> float:
        """The planform's area [m^2]."""
        return float(self.sums()[0])

    @property
    def perimeter(self) -> float:
        """The length of all its edges, the outer loop's and the holes' [m]."""
        return float(sum(edge_lengths(loop.points).sum() for loop in self.loops))

    @property
    def centroid(self) -> tuple[float, float]:
        """The centre of its area [m]."""
        a, sx, sy = self.sums()[:3]
        return float(sx / a), float(sy / a)

    def second_moments(self) -> tuple[float, float, float]:
        """(I_xx, I_yy, I_xy) about the centroid [m^4]: int y^2, int x^2, int x y over the area
        (parallel axes, Steiner)."""
        a, sx, sy, ixx, iyy, ixy = self.sums()
        xc, yc = sx / a, sy / a
        return float(ixx - a * yc * yc), float(iyy - a * xc * xc), float(ixy - a * xc * yc)

    def mass_properties(self, thickness: float, density: float) -> MassProperties:
        """Mass, centre of mass and polar moment of inertia of the planform as a plate.

        Parameters
        ----------
        thickness : float
            The plate's thickness [m].
        density : float
            Its density [kg/m^3].

        Returns
        -------
        MassProperties
            The prism's mass [kg], centre [m] and moment about its centre normal to the
            plate [kg m^2] (exact for a prism: int (x^2 + y^2) dm).
        """
        ixx, iyy, _ = self.second_moments()
        rho_t = density * thickness
        return MassProperties(rho_t * self.area, self.centroid, rho_t * (ixx + iyy))

    def extent(self) -> float:
        """The largest side of the bounding box [m]."""
        return float(np.ptp(self.outer.points, axis=0).max())

    def mapped(self, move) -> Planform:
        """Every vertex through ``move`` ((n, 2) [m] -> (n, 2) [m]): a displaced or scaled
        planform, loops and layers kept."""
        return Planform(self.outer.mapped(move(self.outer.points)),
                        tuple(h.mapped(move(h.points)) for h in self.holes))

    def hole_centre(self, hole: Loop) -> tuple[float, float]:
        """The centre of a hole's area [m] (a circle's centre; exact under any affine map)."""
        a, sx, sy = edge_sums(hole.points)[:3]
        return float(sx / a), float(sy / a)

    def round_holes(self) -> list[tuple[Loop, float]]:
        """The holes whose vertices and edge midpoints lie within ``ROUND`` of a circle about
        their centre, with the mean distance of the vertices [m], largest first."""
        found = []
        for hole in self.holes:
            middle = 0.5 * (hole.points + np.roll(hole.points, -1, axis=0))
            r = np.hypot(*(np.vstack([hole.points, middle]) - self.hole_centre(hole)).T)
            if np.ptp(r) <= ROUND * r.mean():  # the radius of the vertices, on the circle
                found.append((hole, float(r[:len(hole.points)].mean())))
        return sorted(found, key=lambda pair: -pair[1])


def where(point) -> str:
    """A point [m] as ``(x, y) mm`` for messages."""
    return f"({point[0] * 1e3:.6g}, {point[1] * 1e3:.6g}) mm"


def pin_holes(planform: Planform, layer: str | None = None) -> tuple[Loop, Loop]:
    """A link's two pin holes: the holes on ``layer``, or else its two largest round holes.

    Parameters
    ----------
    planform : Planform
        The link's planform [m].
    layer : str, optional
        The layer the pin holes are drawn on.

    Returns
    -------
    tuple of Loop
        The two holes, the one nearer the origin first.

    Raises
    ------
    DrawingError
        Not exactly two holes on ``layer``, or fewer than two round holes.
    """
    if layer is not None:
        found = [h for h in planform.holes if h.layer.casefold() == layer.casefold()]
        if len(found) != 2:
            raise DrawingError(f"no pin holes: a link needs two holes on layer {layer}, the drawing "
                               f"has {len(found)} ({_layers(planform)})")
    else:
        found = [hole for hole, _ in planform.round_holes()[:2]]
        if len(found) < 2:
            raise DrawingError(f"no pin holes: a link needs two round holes (its pins), the drawing "
                               f"has {len(found)} ({_layers(planform)}); draw them as circles or "
                               f"name their layer")
    return tuple(sorted(found, key=lambda h: float(np.hypot(*planform.hole_centre(h)))))


def _layers(planform: Planform) -> str:
    names = sorted({h.layer or "(no layer)" for h in planform.holes})
    return f"holes on layers {', '.join(names)}" if names else "no holes"


def crossing(segments_a: np.ndarray, segments_b: np.ndarray, same: bool) -> tuple[int, int] | None:
    """The first pair of segments that cross or touch, or None.

    Parameters
    ----------
    segments_a, segments_b : numpy.ndarray
        Segments (n, 2, 2) and (m, 2, 2) [m], consecutive ones joined (closed loops).
    same : bool
        Both are the same loop: neighbouring segments (which share a vertex) are skipped.

    Returns
    -------
    tuple of int or None
        Indices of one crossing pair.
    """
    b0, b1 = segments_b[:, 0], segments_b[:, 1]
    m = len(segments_b)
    for start in range(0, len(segments_a), 256):
        a0 = segments_a[start:start + 256, None, 0]
        a1 = segments_a[start:start + 256, None, 1]
        d1, d2 = _orient(a0, a1, b0), _orient(a0, a1, b1)
        d3, d4 = _orient(b0, b1, a0), _orient(b0, b1, a1)
        # round-off: a point within 1e-10 of a segment's length from its line is on it
        tiny = 1e-10 * np.hypot(*(a1 - a0).T).T * np.hypot(*(b1 - b0).T)
        collinear = (np.abs(d1) <= tiny) & (np.abs(d2) <= tiny)
        apart = np.zeros(collinear.shape, bool)
        for axis in (0, 1):
            apart |= ((np.maximum(a0[..., axis], a1[..., axis]) < np.minimum(b0[:, axis], b1[:, axis]))
                      | (np.maximum(b0[:, axis], b1[:, axis]) < np.minimum(a0[..., axis], a1[..., axis])))
        hit = (d1 * d2 <= 0) & (d3 * d4 <= 0) & ~(collinear & apart)
        if same:
            i = np.arange(start, start + hit.shape[0])[:, None]
            j = np.arange(m)[None, :]
            hit &= (j > i + 1) & ~((i == 0) & (j == m - 1))
        found = np.argwhere(hit)
        if found.size:
            return int(found[0, 0] + start), int(found[0, 1])
    return None


def _orient(p, q, r) -> np.ndarray:
    """Twice the signed area of (p, q, r), arrays of points broadcast."""
    return ((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
            - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))


def _segments(points: np.ndarray) -> np.ndarray:
    return np.stack([points, np.roll(points, -1, axis=0)], axis=1)


def _check_crossings(loops: list[Loop]) -> None:
    segments = [_segments(loop.points) for loop in loops]
    for i, a in enumerate(loops):
        for j in range(i, len(loops)):
            pair = crossing(segments[i], segments[j], same=i == j)
            if pair is not None:
                at = where(segments[i][pair[0]].mean(axis=0))
                what = ("crosses itself" if i == j else f"crosses the loop {loops[j].source}")
                raise DrawingError(f"self-intersection: the loop {a.source} {what} near {at}")


def inside(points: np.ndarray, loop: Loop) -> np.ndarray:
    """Which points [m] (k, 2) lie inside the closed loop (matplotlib's even-odd test).

    Parameters
    ----------
    points : numpy.ndarray
        The points [m], shape (k, 2).
    loop : Loop
        The loop [m].

    Returns
    -------
    numpy.ndarray
        True inside.
    """
    # deferred: keeps matplotlib off the start-up path
    from matplotlib.path import Path

    return Path(loop.points, closed=False).contains_points(np.asarray(points, float).reshape(-1, 2))


def planform_of(loops: list[Loop]) -> Planform:
    """The planform of closed loops: the largest is the outline, every other a hole.

    Parameters
    ----------
    loops : list of Loop
        Closed loops [m], any orientation.

    Returns
    -------
    Planform
        The outline counter-clockwise, the holes clockwise.

    Raises
    ------
    DrawingError
        No loop, a degenerate loop, loops that cross (themselves or each other), a hole
        outside the outline or inside another hole; the message names the loop's entity
        and layer.
    """
    if not loops:
        raise DrawingError("the drawing has no closed outline")
    _check_crossings(loops)
    for loop in loops:
        if len(loop.points) < 3 or abs(signed_area(loop.points)) <= 0.0:
            raise DrawingError(f"the loop {loop.source} encloses no area")
    ordered = sorted(loops, key=lambda loop: -abs(signed_area(loop.points)))
    outer, holes = ordered[0], ordered[1:]
    for hole in holes:
        if not inside(hole.points[:1], outer)[0]:
            raise DrawingError(f"hole outside the outline: the loop {hole.source} lies outside "
                               f"the outline {outer.source}")
        for other in holes:
            if other is not hole and inside(hole.points[:1], other)[0]:
                raise DrawingError(f"the loop {hole.source} lies inside the hole {other.source}: "
                                   f"an island is not part of the plate")
    ccw = outer if signed_area(outer.points) > 0 else outer.reversed()
    return Planform(ccw, tuple(h if signed_area(h.points) < 0 else h.reversed() for h in holes))


def circle_points(centre, radius: float, tolerance: float) -> np.ndarray:
    """A circle as the polygon whose chords stray at most ``tolerance`` from it
    (sagitta r (1 - cos(pi / n)) <= tolerance), counter-clockwise.

    Parameters
    ----------
    centre : array_like
        The centre [m].
    radius : float
        The radius [m].
    tolerance : float
        The largest sagitta [m].

    Returns
    -------
    numpy.ndarray
        The vertices [m], on the circle, shape (n, 2).
    """
    ratio = max(-1.0, 1.0 - tolerance / radius)
    n = max(8, int(np.ceil(np.pi / np.arccos(ratio))))
    angle = 2 * np.pi * np.arange(n) / n
    return np.column_stack([centre[0] + radius * np.cos(angle), centre[1] + radius * np.sin(angle)])


def polygon_planform(outline, holes=(), tolerance: float = 1e-5) -> Planform:
    """The planform of a polygon written in a scene (``outline:`` points, ``holes:``).

    Parameters
    ----------
    outline : array_like
        The outline's vertices [m], shape (n, 2), any orientation.
    holes : sequence
        Each hole as vertices [m], shape (k, 2), or as ``(centre, radius)`` [m] for a round
        hole (flattened within ``tolerance``).
    tolerance : float
        The chord tolerance of round holes [m].

    Returns
    -------
    Planform
        The checked planform.

    Raises
    ------
    DrawingError
        As :func:`planform_of`.
    """
    loops = [Loop(outline, "", "given as outline")]
    for i, hole in enumerate(holes):
        if isinstance(hole, tuple) and len(hole) == 2 and np.ndim(hole[1]) == 0:
            hole = circle_points(hole[0], float(hole[1]), tolerance)
        loops.append(Loop(hole, "", f"given as holes[{i}]"))
    planform = planform_of(loops)
    if planform.outer.source != loops[0].source:
        raise DrawingError(f"hole outside the outline: the loop {planform.outer.source} is "
                           f"larger than the outline")
    return planform
