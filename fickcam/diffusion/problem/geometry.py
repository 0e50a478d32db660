"""Part geometries for the diffusion engine (dry dimensions, SI metres), and what each
answers about itself.

Axes: x, y in the plane of the part, z through its thickness; for a ``Disc``
x = y = radial. All surfaces named in each docstring are exposed to the
environment. The contact layer, whose mean every result reports beside the part's mean,
lies within a depth of the contact surface (``LAYER_DEPTH`` unless the caller gives one).

The geometry protocol
---------------------
The engine never asks which class a part is; it asks the part. Every geometry has a
``thickness`` [m] along z and answers:

- ``grid``: the finite-volume grid the backends build for it: ``"sheet"`` (1-D through the
  thickness), ``"disc"`` ((r, z)), ``"box"`` (3-D cells) or ``"prisms"`` (a planform's
  triangles x graded layers through the thickness);
- ``exact_route``: the exact series that solves it (``exact.separable``: ``"sheet"``,
  ``"disc"``, ``"box"``, a product of sheets), or None; ``exact_refusal()`` says why not;
- ``planform``: True for a prismatic part whose outline the planform meshers read (below);
- ``axisymmetric``: True where the field depends on (r, z) alone;
- ``mirror_axes``: the layout axes a concentration-dependent solve cuts at its mirror
  planes (a bar's octant: (0, 1, 2); a prism's mid-plane: (1,); none: ());
- ``in_plane_sizes()``: the extent of each in-plane axis of its grid [m] (a planform: its
  bounding box), and ``exposed_ends()``: which ends of each grid axis are exposed.

A planform geometry (``planform`` True) also answers for its outline:

- ``inside(x, y)``: which points lie in the material;
- ``edge_samples(spacing)``: points along every edge and along the contact edge;
- ``boundary_loops(spacing)``: closed polylines with the material on their left (outer
  counter-clockwise, holes clockwise) and a contact flag per loop, or None where the
  outline cannot be drawn as loops (then the meshers fall back to a lattice);
- ``on_contact(points)``: which outline points lie on the contact surface.

A new part type implements these and every model that can take it does so unchanged: a
plate drawn as a polygon with holes (an outer loop and hole loops, both lists of points)
is a planform with ``grid = "prisms"``, ``exact_route = None``, ``mirror_axes = (1,)``,
whose ``boundary_loops`` are its own loops (the outer one counter-clockwise, each hole
clockwise) resampled at ``spacing`` (``curves.resample_polyline``), ``inside`` the even-odd
test against all of them (``curves.inside_polygon``), and ``edge_samples`` their points.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .curves import (ARC_POINTS, arc_circle, circle, inside_polygon, polygon_segments,
                     resample_polyline, segment_distance)

LAYER_DEPTH = 5e-4  # m, the contact layer's depth when none is given


@dataclass(frozen=True)
class Sheet:
    """Infinite plate of ``thickness``, both faces exposed (Crank 1975, §4.3).

    Parameters
    ----------
    thickness : float
        The plate's thickness [m].

    References
    ----------
    J. Crank, *The Mathematics of Diffusion*, 2nd ed., Oxford: Clarendon Press, 1975,
    §4.3 (plane sheet, surface concentration constant).
    """

    thickness: float

    grid = "sheet"
    exact_route = "sheet"
    planform = False
    axisymmetric = False
    mirror_axes = ()

    def exact_refusal(self) -> str | None:
        """None: the exact series always solves a sheet."""
        return None

    def in_plane_sizes(self) -> tuple[float, ...]:
        """No in-plane axis: the sheet is infinite."""
        return ()

    def exposed_ends(self) -> tuple[str, ...]:
        """Both faces of the thickness."""
        return ("both",)


@dataclass(frozen=True)
class Disc:
    """Axisymmetric disc (``inner_radius`` = 0) or annulus; faces, rim and bore exposed.

    Parameters
    ----------
    outer_radius : float
        The rim's radius [m].
    thickness : float
        The disc's thickness [m].
    inner_radius : float
        The bore's radius [m]; 0 for a full disc.
    """

    outer_radius: float
    thickness: float
    inner_radius: float = 0.0

    grid = "disc"
    planform = False
    axisymmetric = True
    mirror_axes = ()

    @property
    def exact_route(self) -> str | None:
        """``"disc"`` (cylinder x sheet) for a solid disc; an annulus has no product form."""
        return "disc" if self.inner_radius == 0.0 else None

    def exact_refusal(self) -> str | None:
        """Why the exact series does not solve this disc (None: it does)."""
        return (None if self.exact_route else
                "an annulus has no product solution (use axisymmetric)")

    def in_plane_sizes(self) -> tuple[float, ...]:
        """The radial extent of the material [m]."""
        return (self.outer_radius - self.inner_radius,)

    def exposed_ends(self) -> tuple[str, ...]:
        """The rim (and the bore, if any) and both faces."""
        return ("both" if self.inner_radius > 0 else "high", "both")


@dataclass(frozen=True)
class Bar:
    """Rectangular bar, all six faces exposed (x = length, y = width, z = thickness).

    Parameters
    ----------
    length : float
        The bar's length along x [m].
    width : float
        Its width along y [m].
    thickness : float
        Its thickness along z [m].
    """

    length: float
    width: float
    thickness: float

    grid = "box"
    exact_route = "box"
    planform = False
    axisymmetric = False
    mirror_axes = (0, 1, 2)

    def exact_refusal(self) -> str | None:
        """None: a bar is the product of three sheets."""
        return None

    def in_plane_sizes(self) -> tuple[float, ...]:
        """Length and width [m]."""
        return (self.length, self.width)

    def exposed_ends(self) -> tuple[str, ...]:
        """All six faces."""
        return ("both",) * 3


class _Planform:
    """What every planform geometry answers alike (see the module docstring)."""

    grid = "prisms"
    exact_route = None
    planform = True
    axisymmetric = False
    mirror_axes = (1,)

    def exact_refusal(self) -> str | None:
        """A planform has no separable exact solution."""
        return "no separable exact solution (use plane)"

    def in_plane_sizes(self) -> tuple[float, ...]:
        """The outline's bounding box [m] (``extent``)."""
        return self.extent()

    def exposed_ends(self) -> tuple[str, ...]:
        """Both faces (the outline's edges are the planform mesh's own)."""
        return ("both",)


@dataclass(frozen=True, eq=False)
class CamPlate(_Planform):
    """Prismatic cam plate: closed counter-clockwise outline (m) of the working
    profile, last point not repeated; the two faces, the profile edge and the
    bore are exposed. The profile edge is the contact surface.

    Parameters
    ----------
    profile_x, profile_y : numpy.ndarray
        The outline's points [m], counter-clockwise, about the cam's centre of rotation
        (copied and made read-only).
    thickness : float
        The plate's thickness [m].
    bore_radius : float
        The bore's radius [m]; 0 for none.
    """

    profile_x: np.ndarray = field(repr=False)
    profile_y: np.ndarray = field(repr=False)
    thickness: float = 0.0
    bore_radius: float = 0.0

    def __post_init__(self):
        """Own read-only copies of the outline: equality and hash below are by value (the
        caches of meshes and step responses are keyed by them), so the arrays must not
        change afterwards."""
        for name in ("profile_x", "profile_y"):
            array = np.array(getattr(self, name), dtype=float)
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    def _values(self) -> tuple:
        return (self.profile_x.tobytes(), self.profile_y.tobytes(), float(self.thickness),
                float(self.bore_radius))

    def __eq__(self, other) -> bool:
        return type(other) is CamPlate and self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())

    def inside(self, x, y) -> np.ndarray:
        """Which points lie in the material: inside the profile, outside the bore.

        Parameters
        ----------
        x, y : array_like
            The points' coordinates [m], 1-D.

        Returns
        -------
        numpy.ndarray
            True inside the material.
        """
        x, y = np.asarray(x, float), np.asarray(y, float)
        segments = polygon_segments(self.profile_x, self.profile_y)
        return inside_polygon(np.column_stack([x, y]), segments) & (
            np.hypot(x, y) > self.bore_radius)

    def edge_samples(self, spacing: float) -> tuple[np.ndarray, np.ndarray]:
        """Points along every edge (the profile and the bore) and along the contact edge
        (the profile).

        Parameters
        ----------
        spacing : float
            The largest gap between samples [m].

        Returns
        -------
        tuple of numpy.ndarray
            The boundary and contact samples [m], shapes (n, 2) and (m, 2).
        """
        profile = resample_polyline(self.profile_x, self.profile_y, spacing)
        bore = (circle(0.0, 0.0, self.bore_radius, spacing) if self.bore_radius > 0
                else np.empty((0, 2)))
        return np.vstack([profile, bore]), profile

    def extent(self) -> tuple[float, float]:
        """The outline's bounding box: its width along x and height along y [m]."""
        return (float(np.ptp(self.profile_x)), float(np.ptp(self.profile_y)))

    def boundary_loops(self, spacing: float) -> tuple[list[np.ndarray], list[bool]] | None:
        """The profile (counter-clockwise, the contact edge) and the bore (clockwise).

        Parameters
        ----------
        spacing : float
            The largest gap along the bore's arc [m].

        Returns
        -------
        tuple
            The loops [m] and a contact flag per loop.
        """
        loops, contact = [np.column_stack([self.profile_x, self.profile_y]).astype(float)], [True]
        if self.bore_radius > 0:
            loops.append(arc_circle(0.0, 0.0, self.bore_radius, spacing)[::-1])
            contact.append(False)
        return loops, contact

    def on_contact(self, points: np.ndarray) -> np.ndarray:
        """Which outline points lie on the profile, not on the bore's circle.

        Parameters
        ----------
        points : numpy.ndarray
            Points of the outline [m], shape (n, 2).

        Returns
        -------
        numpy.ndarray
            True on the contact edge.
        """
        if self.bore_radius <= 0:
            return np.ones(len(points), bool)
        radius = np.hypot(*np.asarray(points, float).T)
        return ~(np.abs(radius - self.bore_radius) <= 1e-6 * self.bore_radius)


@dataclass(frozen=True)
class LinkBar(_Planform):
    """A link: a bar of ``length`` between boss centres, ``width`` x ``thickness``
    section, with a hollow cylindrical boss (outer/inner radius, same thickness)
    at each end; every surface, the two holes included, is exposed.

    Parameters
    ----------
    length : float
        The distance between the boss centres [m].
    width : float
        The bar's width in the plane of the link [m].
    thickness : float
        The thickness of bar and bosses [m].
    boss_outer_radius : float
        The bosses' outer radius [m].
    boss_inner_radius : float
        The radius of the bosses' holes [m].
    """

    length: float
    width: float
    thickness: float
    boss_outer_radius: float
    boss_inner_radius: float

    def inside(self, x, y) -> np.ndarray:
        """Which points lie in the material: the bar or a boss, outside both holes.

        Parameters
        ----------
        x, y : array_like
            The points' coordinates [m], 1-D.

        Returns
        -------
        numpy.ndarray
            True inside the material.
        """
        x, y = np.asarray(x, float), np.asarray(y, float)
        half = 0.5 * self.width
        near_a, near_b = np.hypot(x, y), np.hypot(x - self.length, y)
        solid = (((x >= 0) & (x <= self.length) & (np.abs(y) <= half)) |
                 (near_a <= self.boss_outer_radius) | (near_b <= self.boss_outer_radius))
        return solid & (near_a > self.boss_inner_radius) & (near_b > self.boss_inner_radius)

    def edge_samples(self, spacing: float) -> tuple[np.ndarray, np.ndarray]:
        """Points along every edge, the holes' included; every edge is a contact edge.

        Parameters
        ----------
        spacing : float
            The largest gap between samples [m].

        Returns
        -------
        tuple of numpy.ndarray
            The boundary and contact samples [m] (the same), shape (n, 2).
        """
        half, length = 0.5 * self.width, self.length
        ro, ri = self.boss_outer_radius, self.boss_inner_radius
        candidates = np.vstack([
            circle(0.0, 0.0, ro, spacing), circle(length, 0.0, ro, spacing),
            resample_polyline([0.0, length], [half, half], spacing, closed=False),
            resample_polyline([0.0, length], [-half, -half], spacing, closed=False)])
        shrink = 1 - 1e-9
        x, y = candidates.T
        strictly_inside = ((x > 0) & (x < length) & (np.abs(y) < half * shrink)) | (
            np.hypot(x, y) < ro * shrink) | (np.hypot(x - length, y) < ro * shrink)
        holes = np.vstack([circle(0.0, 0.0, ri, spacing), circle(length, 0.0, ri, spacing)])
        boundary = np.vstack([candidates[~strictly_inside], holes])
        return boundary, boundary

    def extent(self) -> tuple[float, float]:
        """The outline's bounding box: its width along x and height along y [m]."""
        return (self.length + 2 * self.boss_outer_radius,
                max(self.width, 2 * self.boss_outer_radius))

    def boundary_loops(self, spacing: float) -> tuple[list[np.ndarray], list[bool]] | None:
        """The outer outline (counter-clockwise) and the holes (clockwise), all contact
        edges; None when the bosses overlap (the outline is then not one loop).

        Parameters
        ----------
        spacing : float
            The largest gap along straight pieces and arcs [m].

        Returns
        -------
        tuple or None
            The loops [m] and a contact flag per loop; None for overlapping bosses.
        """
        half, length = 0.5 * self.width, self.length
        ro, ri = self.boss_outer_radius, self.boss_inner_radius
        if length <= 2 * ro:
            return None
        holes = [arc_circle(cx, 0.0, ri, spacing)[::-1] for cx in (0.0, length)] if ri > 0 else []
        if half > ro:  # bosses narrower than the bar: half discs on its ends
            outer = narrow_boss_outline(length, half, ro, spacing)
        else:
            outer = _wide_boss_outline(length, half, ro, spacing)
        return [outer] + holes, [True] * (1 + len(holes))

    def on_contact(self, points: np.ndarray) -> np.ndarray:
        """Every point of a link's outline is on its contact surface.

        Parameters
        ----------
        points : numpy.ndarray
            Points of the outline [m], shape (n, 2).

        Returns
        -------
        numpy.ndarray
            True for every point.
        """
        return np.ones(len(points), bool)


def _wide_boss_outline(length: float, half: float, radius: float, spacing: float) -> np.ndarray:
    """Counter-clockwise outline of a bar of half-width ``half`` between bosses of a larger
    ``radius`` centred at x = 0 and x = length [m]."""
    phi = math.asin(half / radius)
    x0 = math.sqrt(radius * radius - half * half)
    count = max(ARC_POINTS, math.ceil((2 * np.pi - 2 * phi) * radius / spacing))
    arc_a = np.linspace(phi, 2 * np.pi - phi, count)
    arc_b = np.linspace(-np.pi + phi, np.pi - phi, count)
    bottom = resample_polyline([x0, length - x0], [-half, -half], spacing, closed=False)[1:-1]
    top = resample_polyline([length - x0, x0], [half, half], spacing, closed=False)[1:-1]
    return np.vstack([np.column_stack([radius * np.cos(arc_a), radius * np.sin(arc_a)]), bottom,
                      np.column_stack([length + radius * np.cos(arc_b), radius * np.sin(arc_b)]),
                      top])


def narrow_boss_outline(length: float, half: float, radius: float, spacing: float) -> np.ndarray:
    """Counter-clockwise outline of a bar of half-width ``half`` with half discs of a smaller
    ``radius`` on its ends (x = 0 and x = length): straight pieces every <= ``spacing``.

    Parameters
    ----------
    length : float
        The distance between the boss centres [m].
    half : float
        The bar's half-width [m].
    radius : float
        The bosses' radius [m], below ``half``.
    spacing : float
        The largest gap along the straight pieces [m].

    Returns
    -------
    numpy.ndarray
        The outline's points [m], shape (k, 2).
    """
    count = max(ARC_POINTS // 2, math.ceil(np.pi * radius / spacing))
    arc = np.linspace(0.5 * np.pi, 1.5 * np.pi, count, endpoint=False)

    def straight(*corners):
        xs, ys = np.array(corners, float).T
        return resample_polyline(xs, ys, spacing, closed=False)[:-1]
    return np.vstack([
        np.column_stack([radius * np.cos(arc), radius * np.sin(arc)]),
        straight((0.0, -radius), (0.0, -half), (length, -half), (length, -radius)),
        np.column_stack([length - radius * np.cos(arc), -radius * np.sin(arc)]),
        straight((length, radius), (length, half), (0.0, half), (0.0, radius))])


Geometry = Sheet | Disc | Bar | CamPlate | LinkBar


@dataclass(frozen=True, eq=False)
class DrawnPlate(_Planform):
    """A prismatic part as drawn: its outline and holes, every edge (the holes' too) and
    both faces exposed; every edge a contact edge (a link's), or the outline alone (a cam
    plate's working profile, ``contact_holes`` False).

    Parameters
    ----------
    outer : numpy.ndarray
        The outline's vertices [m], shape (n, 2), counter-clockwise, last not repeated
        (copied and made read-only).
    holes : tuple of numpy.ndarray
        Each hole's vertices [m], clockwise (copied and made read-only).
    thickness : float
        The plate's thickness [m].
    contact_holes : bool
        The holes' edges are contact edges too (False: the outline alone, as a cam's).
    """

    outer: np.ndarray = field(repr=False)
    holes: tuple = field(default=(), repr=False)
    thickness: float = 0.0
    contact_holes: bool = True

    def __post_init__(self):
        """Own read-only copies of the loops: equality and hash are by value (the caches
        of meshes and step responses are keyed by them)."""
        loops = [np.array(loop, dtype=float).reshape(-1, 2) for loop in (self.outer, *self.holes)]
        for loop in loops:
            loop.setflags(write=False)
        object.__setattr__(self, "outer", loops[0])
        object.__setattr__(self, "holes", tuple(loops[1:]))

    def _values(self) -> tuple:
        return (tuple(loop.tobytes() for loop in (self.outer, *self.holes)),
                tuple(len(loop) for loop in (self.outer, *self.holes)), float(self.thickness),
                bool(self.contact_holes))

    def __eq__(self, other) -> bool:
        return type(other) is DrawnPlate and self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())

    def inside(self, x, y) -> np.ndarray:
        """Which points lie in the material: inside the outline, outside every hole
        (the even-odd test against all the loops).

        Parameters
        ----------
        x, y : array_like
            The points' coordinates [m], 1-D.

        Returns
        -------
        numpy.ndarray
            True inside the material.
        """
        segments = np.concatenate([polygon_segments(*loop.T) for loop in (self.outer, *self.holes)])
        return inside_polygon(np.column_stack([np.asarray(x, float), np.asarray(y, float)]),
                              segments)

    def edge_samples(self, spacing: float) -> tuple[np.ndarray, np.ndarray]:
        """Points along every edge, the holes' included, and along the contact edges.

        Parameters
        ----------
        spacing : float
            The largest gap between samples [m].

        Returns
        -------
        tuple of numpy.ndarray
            The boundary and contact samples [m], shapes (n, 2) and (m, 2).
        """
        loops, contact = self.boundary_loops(spacing)
        return np.vstack(loops), np.vstack([loop for loop, c in zip(loops, contact) if c])

    def extent(self) -> tuple[float, float]:
        """The outline's bounding box: its width along x and height along y [m]."""
        width, height = np.ptp(self.outer, axis=0)
        return (float(width), float(height))

    def boundary_loops(self, spacing: float) -> tuple[list[np.ndarray], list[bool]]:
        """The outline (counter-clockwise) and the holes (clockwise), each resampled at
        ``spacing`` with its vertices kept, all contact edges.

        Parameters
        ----------
        spacing : float
            The largest gap between points [m].

        Returns
        -------
        tuple
            The loops [m] and a contact flag per loop.
        """
        loops = [resample_polyline(*loop.T, spacing) for loop in (self.outer, *self.holes)]
        return loops, [True] + [bool(self.contact_holes)] * len(self.holes)

    def on_contact(self, points: np.ndarray) -> np.ndarray:
        """Which points of the part's edges lie on its contact surface: every one, or
        (``contact_holes`` False) those on the outline, within 1e-9 of its extent.

        Parameters
        ----------
        points : numpy.ndarray
            Points of the outline [m], shape (n, 2).

        Returns
        -------
        numpy.ndarray
            True on a contact edge.
        """
        if self.contact_holes:
            return np.ones(len(points), bool)
        gap = segment_distance(np.asarray(points, float).reshape(-1, 2),
                               polygon_segments(*self.outer.T))
        return gap <= 1e-9 * max(self.extent())
