"""Sampled curves of a planform: points along polylines and circles, the segments of a
polygon and which points it holds (even-odd ray casting). The geometries build their
outlines from these (``geometry``); the planform meshers use them too."""
from __future__ import annotations

import math

import numpy as np

ARC_POINTS = 1024  # samples of a full circle in an outline (chord error (2 pi / N)^2 / 8)


def resample_polyline(px, py, spacing: float, closed: bool = True) -> np.ndarray:
    """Points every <= ``spacing`` along a polyline (closed: back to the start), each
    vertex kept.

    Parameters
    ----------
    px, py : array_like
        The vertices' coordinates [m].
    spacing : float
        The largest gap between points [m].
    closed : bool
        True: the last vertex joins the first.

    Returns
    -------
    numpy.ndarray
        The points, shape (k, 2) [m]; an open polyline ends on its last vertex.
    """
    pts = np.column_stack([px, py]).astype(float)
    if closed:
        pts = np.vstack([pts, pts[:1]])
    out = []
    for a, b in zip(pts[:-1], pts[1:]):
        count = max(1, math.ceil(np.hypot(*(b - a)) / spacing))
        out.append(a + (b - a) * (np.arange(count) / count)[:, None])
    if not closed:
        out.append(pts[-1:])
    return np.vstack(out)


def circle(cx: float, cy: float, radius: float, spacing: float) -> np.ndarray:
    """Counter-clockwise points every <= ``spacing`` round a circle (at least 12).

    Parameters
    ----------
    cx, cy : float
        The centre [m].
    radius : float
        The radius [m].
    spacing : float
        The largest gap along the circle [m].

    Returns
    -------
    numpy.ndarray
        The points, shape (k, 2) [m], from angle 0.
    """
    count = max(12, math.ceil(2 * np.pi * radius / spacing))
    angle = 2 * np.pi * np.arange(count) / count
    return np.column_stack([cx + radius * np.cos(angle), cy + radius * np.sin(angle)])


def arc_circle(cx, cy, radius, spacing) -> np.ndarray:
    """A circle sampled at least ``ARC_POINTS`` times (``circle``).

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


def polygon_segments(px, py) -> np.ndarray:
    """(n, 2, 2) segments of the closed polygon with vertices (px, py).

    Parameters
    ----------
    px, py : array_like
        The vertices' coordinates [m].

    Returns
    -------
    numpy.ndarray
        Each edge's start and end [m], shape (n, 2, 2), the last closing the loop.
    """
    vertices = np.column_stack([px, py]).astype(float)
    return np.stack([vertices, np.roll(vertices, -1, axis=0)], axis=1)


def inside_polygon(query: np.ndarray, segments: np.ndarray, chunk: int = 2048) -> np.ndarray:
    """Even-odd ray casting against a set of segments (Shimrat 1962, CACM algorithm 112).

    Parameters
    ----------
    query : numpy.ndarray
        The points, shape (q, 2) [m].
    segments : numpy.ndarray
        The polygons' edges, shape (n, 2, 2) [m].
    chunk : int
        Points tested at once (memory).

    Returns
    -------
    numpy.ndarray
        True for a point inside (an odd number of crossings).

    References
    ----------
    M. Shimrat, "Algorithm 112: Position of point relative to polygon", *Communications of
    the ACM* 5(8), 434, 1962.
    """
    a, b = segments[:, 0], segments[:, 1]
    inside = np.zeros(len(query), bool)
    for lo in range(0, len(query), chunk):
        x, y = query[lo:lo + chunk, :1], query[lo:lo + chunk, 1:]
        crosses = (a[None, :, 1] > y) != (b[None, :, 1] > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = a[None, :, 0] + (y - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (
                b[None, :, 1] - a[None, :, 1])
        inside[lo:lo + chunk] = np.count_nonzero(crosses & (x < at), axis=1) % 2 == 1
    return inside


def segment_distance(query: np.ndarray, segments: np.ndarray, chunk: int = 1024) -> np.ndarray:
    """Distance from each point to the nearest of ``segments`` (exact, by chunks).

    Parameters
    ----------
    query : numpy.ndarray
        The points, shape (q, 2) [m].
    segments : numpy.ndarray
        The segments, shape (n, 2, 2) [m].
    chunk : int
        Points measured at once (memory).

    Returns
    -------
    numpy.ndarray
        The distances [m], shape (q,).
    """
    a, b = segments[:, 0], segments[:, 1]
    edge = b - a
    length2 = np.maximum(np.einsum("ij,ij->i", edge, edge), np.finfo(float).tiny)
    out = np.empty(len(query))
    for lo in range(0, len(query), chunk):
        q = query[lo:lo + chunk, None, :]
        along = np.clip(np.einsum("qsi,si->qs", q - a[None], edge) / length2[None], 0.0, 1.0)
        nearest = a[None] + along[..., None] * edge[None]
        out[lo:lo + chunk] = np.sqrt(np.min(np.sum((q - nearest) ** 2, axis=2), axis=1))
    return out
