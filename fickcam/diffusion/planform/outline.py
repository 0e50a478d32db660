"""The planform of a prismatic part (CamPlate, LinkBar): which points are inside, samples
along its edges, its closed boundary loops (material on the left) and its extent."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..problem.geometry import CamPlate
from .polygon import circle, inside_polygon, polygon_segments, resample_polyline

ARC_POINTS = 1024  # samples of a full circle in the outline (chord error (2 pi / N)^2 / 8)


@dataclass(frozen=True)
class Outline:
    """A planform: ``inside(x, y)``, boundary samples (all edges) and the contact edge.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The part whose planform this is (lengths in [m]).
    boundary : numpy.ndarray
        Points along every edge [m], shape (n, 2).
    contact : numpy.ndarray
        Points along the contact edge [m], shape (m, 2).
    """

    part: object
    boundary: np.ndarray   # (n, 2) points along every edge, spacing <= requested
    contact: np.ndarray    # (m, 2) points along the contact edge

    def inside(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return inside_part(self.part, x, y)


def inside_part(part, x, y) -> np.ndarray:
    """Which points (x, y) (m, 1-D arrays) lie inside the planform.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    x, y : array_like
        The points' coordinates [m], 1-D.

    Returns
    -------
    numpy.ndarray
        True inside the material (outside any bore).
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if isinstance(part, CamPlate):
        segments = polygon_segments(part.profile_x, part.profile_y)
        return inside_polygon(np.column_stack([x, y]), segments) & (
            np.hypot(x, y) > part.bore_radius)
    half = 0.5 * part.width
    near_a, near_b = np.hypot(x, y), np.hypot(x - part.length, y)
    solid = (((x >= 0) & (x <= part.length) & (np.abs(y) <= half)) |
             (near_a <= part.boss_outer_radius) | (near_b <= part.boss_outer_radius))
    return solid & (near_a > part.boss_inner_radius) & (near_b > part.boss_inner_radius)


def outline(part, spacing: float) -> Outline:
    """Boundary samples of a CamPlate (contact: the profile) or LinkBar (contact: every edge).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    spacing : float
        The largest gap between samples [m].

    Returns
    -------
    Outline
        The planform with its boundary and contact samples [m].
    """
    if isinstance(part, CamPlate):
        profile = resample_polyline(np.asarray(part.profile_x), np.asarray(part.profile_y), spacing)
        bore = (circle(0.0, 0.0, part.bore_radius, spacing) if part.bore_radius > 0
                else np.empty((0, 2)))
        return Outline(part, np.vstack([profile, bore]), profile)
    half, length = 0.5 * part.width, part.length
    ro, ri = part.boss_outer_radius, part.boss_inner_radius
    pieces = [circle(0.0, 0.0, ro, spacing), circle(length, 0.0, ro, spacing),
              resample_polyline([0.0, length], [half, half], spacing, closed=False),
              resample_polyline([0.0, length], [-half, -half], spacing, closed=False)]
    candidates = np.vstack(pieces)
    shrink = 1 - 1e-9
    x, y = candidates.T
    strictly_inside = ((x > 0) & (x < length) & (np.abs(y) < half * shrink)) | (
        np.hypot(x, y) < ro * shrink) | (np.hypot(x - length, y) < ro * shrink)
    outer = candidates[~strictly_inside]
    holes = np.vstack([circle(0.0, 0.0, ri, spacing), circle(length, 0.0, ri, spacing)])
    boundary = np.vstack([outer, holes])
    return Outline(part, boundary, boundary)


def outline_extent(part) -> tuple[float, float]:
    """Bounding-box size of the planform (m).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].

    Returns
    -------
    tuple of float
        The width along x and the height along y [m].
    """
    if isinstance(part, CamPlate):
        return (float(np.ptp(part.profile_x)), float(np.ptp(part.profile_y)))
    return (part.length + 2 * part.boss_outer_radius, max(part.width, 2 * part.boss_outer_radius))


def arc_circle(cx, cy, radius, spacing) -> np.ndarray:
    """A circle sampled at least ``ARC_POINTS`` times (``polygon.circle``).

    Parameters
    ----------
    cx, cy : float
        Where the circle is centred [m].
    radius : float
        Its radius [m] (a bore or a boss).
    spacing : float
        The largest gap along the arc [m].

    Returns
    -------
    numpy.ndarray
        Counter-clockwise points [m], shape (k, 2).
    """
    return circle(cx, cy, radius, min(spacing, 2 * np.pi * radius / ARC_POINTS))


def boundary_loops(part, spacing: float) -> tuple[list[np.ndarray], list[bool]]:
    """Closed polylines (material on the left: outer CCW, holes CW) and whether each
    is a contact edge; None when the outline is not covered (overlapping bosses).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    spacing : float
        The largest gap along straight pieces and arcs [m].

    Returns
    -------
    tuple or None
        The loops [m] (outer counter-clockwise, holes clockwise) and a contact flag per
        loop; None for a LinkBar whose bosses overlap.
    """
    if isinstance(part, CamPlate):
        outer = np.column_stack([part.profile_x, part.profile_y]).astype(float)
        loops, contact = [outer], [True]
        if part.bore_radius > 0:
            loops.append(arc_circle(0.0, 0.0, part.bore_radius, spacing)[::-1])
            contact.append(False)
        return loops, contact
    half, length = 0.5 * part.width, part.length
    ro, ri = part.boss_outer_radius, part.boss_inner_radius
    if length <= 2 * ro:
        return None
    holes = [arc_circle(cx, 0.0, ri, spacing)[::-1] for cx in (0.0, length)] if ri > 0 else []
    if half > ro:  # bosses narrower than the bar: half discs on its ends
        return [narrow_boss_outline(length, half, ro, spacing)] + holes, [True] * (1 + len(holes))
    phi = math.asin(half / ro)
    x0 = math.sqrt(ro * ro - half * half)
    count = max(ARC_POINTS, math.ceil((2 * np.pi - 2 * phi) * ro / spacing))
    arc_a = np.linspace(phi, 2 * np.pi - phi, count)
    arc_b = np.linspace(-np.pi + phi, np.pi - phi, count)
    bottom = resample_polyline([x0, length - x0], [-half, -half], spacing, closed=False)[1:-1]
    top = resample_polyline([length - x0, x0], [half, half], spacing, closed=False)[1:-1]
    outer = np.vstack([np.column_stack([ro * np.cos(arc_a), ro * np.sin(arc_a)]), bottom,
                       np.column_stack([length + ro * np.cos(arc_b), ro * np.sin(arc_b)]), top])
    return [outer] + holes, [True] * (1 + len(holes))


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

