"""The ``spline`` motion law: a B-spline through user points (Norton, Design of Machinery
5th ed., sec. 8.x 'splines'; DYNACAM's B-spline segments), built with
:func:`scipy.interpolate.make_interp_spline`.

A segment's points are (angle within the segment, distance travelled from its start);
in the normalised form of :mod:`fickcam.cam.motion` they are (x, S) = (angle/beta,
distance/h), from (0, 0) to (1, 1). A spline of odd degree k is C^(k-1) inside and takes
(k-1)/2 end conditions at each end: the derivatives d^j S/dx^j, j = 1 .. (k-1)/2, zero by
default (a smooth start from and stop into a dwell). S, S', S'', S''' are the spline's
own derivatives, exact for the spline.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SplineLaw:
    """Normalised spline data (hashable).

    Parameters
    ----------
    degree : int
        The spline's degree k [-], odd.
    x : tuple of float
        The points' normalised angles, angle / span [-], from 0 to 1.
    s : tuple of float
        The points' normalised distances, distance / height [-], from 0 to 1.
    start, end : tuple of float
        The derivatives d^j S / dx^j, j = 1 .. (k-1)/2, at x = 0 and at x = 1 [-].
    """

    degree: int
    x: tuple[float, ...]
    s: tuple[float, ...]
    start: tuple[float, ...]
    end: tuple[float, ...]


def end_condition_count(degree: int) -> int:
    """(k - 1)/2 derivatives fixed at each end of a spline of odd degree k.

    Parameters
    ----------
    degree : int
        The degree k [-].

    Returns
    -------
    int
        The number of end conditions at each end [-].
    """
    return (degree - 1) // 2


@functools.lru_cache(maxsize=64)
def bspline(law: SplineLaw):
    """The interpolating B-spline of ``law`` (cached by law: the law is hashable).

    Parameters
    ----------
    law : SplineLaw
        The normalised points and end conditions.

    Returns
    -------
    scipy.interpolate.BSpline
        S(x) [-] of the normalised angle x [-].

    Raises
    ------
    ValueError
        Where scipy cannot build it (and numpy.linalg.LinAlgError for a singular system).
    """
    # deferred: keeps scipy.interpolate off the start-up path
    from scipy.interpolate import make_interp_spline

    conditions = ([(j + 1, v) for j, v in enumerate(law.start)],
                  [(j + 1, v) for j, v in enumerate(law.end)])
    return make_interp_spline(np.asarray(law.x), np.asarray(law.s), k=law.degree,
                              bc_type=conditions if law.degree > 1 else None)


def spline_motion(law: SplineLaw, x):
    """(S, S', S'', S''') of the spline at normalised x (extrapolated outside [0, 1]).

    Parameters
    ----------
    law : SplineLaw
        The normalised spline.
    x : array_like
        Normalised angles, angle / span [-].

    Returns
    -------
    tuple of numpy.ndarray
        S and its first three derivatives with respect to x [-].

    References
    ----------
    Norton (2012), ch. 8; in full in :mod:`fickcam.cam`.
    """
    x = np.asarray(x, float)
    curve = bspline(law)
    return tuple(curve.derivative(j)(x) if j else curve(x) for j in range(4))


def spline_law(points, height: float, span: float, degree: int, start=None, end=None) -> SplineLaw:
    """Normalise user points of a segment of ``height`` over ``span`` and check that a
    spline goes through them.

    Parameters
    ----------
    points : sequence of (float, float)
        (angle within the segment [rad], distance travelled from its start [m]), from
        (0, 0) to (span, |height|), angles strictly increasing.
    height : float
        The segment's rise (positive) or return (negative) [m].
    span : float
        The segment's cam angle [rad].
    degree : int
        The spline's degree [-]: 1, 3, 5 or 7.
    start, end : sequence of float, optional
        The normalised end derivatives d^j S / dx^j [-], j = 1 .. (degree-1)/2; None:
        zero (a smooth start from and stop into a dwell).

    Returns
    -------
    SplineLaw
        The normalised points and end conditions.

    Raises
    ------
    ValueError
        Where the points do not start at (0, 0), end at (span, |height|) or increase,
        the degree is even, the end conditions are not (degree-1)/2 each, or scipy finds
        no spline through them.
    """
    angles = np.array([p[0] for p in points], float)
    distance = np.array([p[1] for p in points], float)
    h = abs(height)
    if degree % 2 == 0:
        raise ValueError(f"spline degree must be odd (1, 3, 5, 7), not {degree}")
    if len(points) < 2 or np.any(np.diff(angles) <= 0):
        raise ValueError("spline points need at least two strictly increasing angles")
    if abs(angles[0]) > 1e-9 * span or abs(distance[0]) > 1e-9 * h:
        raise ValueError("the first spline point must be (0 deg, 0 mm): the segment start")
    if abs(angles[-1] - span) > 1e-9 * span or abs(distance[-1] - h) > 1e-9 * h:
        raise ValueError("the last spline point must be (over, rise or return): the segment end")
    count = end_condition_count(degree)
    start = tuple(float(v) for v in (start if start is not None else [0.0] * count))
    end = tuple(float(v) for v in (end if end is not None else [0.0] * count))
    if len(start) != count or len(end) != count:
        raise ValueError(f"a degree-{degree} spline takes {count} end derivative(s) at each end")
    x = angles / span
    x[0], x[-1] = 0.0, 1.0
    s = distance / h
    s[0], s[-1] = 0.0, 1.0
    law = SplineLaw(degree, tuple(x), tuple(s), start, end)
    try:
        bspline(law)
    except (ValueError, np.linalg.LinAlgError) as exc:
        raise ValueError(f"no spline of degree {degree} through these points: {exc}") from None
    return law
