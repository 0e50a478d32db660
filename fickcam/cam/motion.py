"""Follower motion laws and their assembly into a full turn.

Every law is a normalised rise S(x), x = (theta - theta_0)/beta in [0, 1], S(0) = 0,
S(1) = 1, returned with its derivatives with respect to x: (S, S', S'', S''').
A segment of lift h over beta gives y = h S, dy/dtheta = h S'/beta, ... and at a
constant cam speed omega the true time derivatives v = h S' omega/beta,
a = h S'' omega^2/beta^2, j = h S''' omega^3/beta^3 (Norton, Design of Machinery
5th ed., sec. 8.3, eqs. 8.1-8.3). A return is y = h (1 - S).

The papers are cited in full in :mod:`fickcam.cam`.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..messages import design_notice
from .fourier import at_angles, correction_motion
from .spline import spline_motion

#: the derivative orders of a follower motion: Y, dY/dtheta, d2Y/dtheta2, d3Y/dtheta3
ORDERS = (0, 1, 2, 3)

PI = math.pi

_LAW_SECTIONS = """

    Parameters
    ----------
    x : float or array_like
        Fraction of the segment, (theta - theta_0)/beta [-].

    Returns
    -------
    tuple of numpy.ndarray
        S, dS/dx, d2S/dx2, d3S/dx3 [-].

    References
    ----------
    {}; in full in :mod:`fickcam.cam`.
    """


def _law(reference: str):
    """Give a motion law the numpydoc sections every law shares (its argument, its
    results) and its source."""
    def documented(function):
        if function.__doc__:  # None under python -OO
            function.__doc__ = function.__doc__.rstrip() + _LAW_SECTIONS.format(reference)
        return function
    return documented


@_law('Norton (2012), ch. 8; Singh & Sanyal (2017), Table 17')
def uniform_velocity(x):
    """S = x (Norton ch. 8, 'constant velocity'; Singh & Sanyal 2017 Table 17). Infinite
    acceleration at both ends."""
    x = np.asarray(x, float)
    return x, np.ones_like(x), np.zeros_like(x), np.zeros_like(x)


@_law('Norton (2012), ch. 8; Singh & Sanyal (2017), Table 17')
def simple_harmonic(x):
    """S = (1 - cos pi x)/2 (Norton ch. 8; Singh & Sanyal 2017 Table 17 and p. 281)."""
    x = np.asarray(x, float)
    return ((1 - np.cos(PI * x)) / 2, PI / 2 * np.sin(PI * x), PI ** 2 / 2 * np.cos(PI * x),
            -PI ** 3 / 2 * np.sin(PI * x))


@_law('Norton (2012), ch. 8; Singh & Sanyal (2017), Table 17')
def cycloidal(x):
    """S = x - sin(2 pi x)/(2 pi) (Norton ch. 8; Singh & Sanyal 2017 Table 17;
    Yadav et al. 2017 p. 2)."""
    x = np.asarray(x, float)
    w = 2 * PI
    return (x - np.sin(w * x) / w, 1 - np.cos(w * x), w * np.sin(w * x), w ** 2 * np.cos(w * x))


def _polynomial(coefficients, x):
    """S = sum c_n x^n and its first three derivatives."""
    poly = np.polynomial.Polynomial(coefficients)
    x = np.asarray(x, float)
    return poly(x), poly.deriv(1)(x), poly.deriv(2)(x), poly.deriv(3)(x)


@_law('Norton (2012), ch. 8')
def polynomial_345(x):
    """S = 10 x^3 - 15 x^4 + 6 x^5 (Norton ch. 8)."""
    return _polynomial([0, 0, 0, 10, -15, 6], x)


@_law('Norton (2012), ch. 8')
def polynomial_4567(x):
    """S = 35 x^4 - 84 x^5 + 70 x^6 - 20 x^7 (Norton ch. 8)."""
    return _polynomial([0, 0, 0, 0, 35, -84, 70, -20], x)


# ---- piecewise laws given by their acceleration: a(x) = c0 + c1 sin k(x-x0) + c2 cos k(x-x0)


@dataclass(frozen=True)
class _Piece:
    start: float
    end: float
    c0: float
    c1: float
    c2: float
    k: float


def _integrated(piece: _Piece, t, v0, s0):
    """(S, S', S'', S''') of one piece at t = x - start, from its start values v0, s0
    (closed-form integrals of c0 + c1 sin kt + c2 cos kt)."""
    c0, c1, c2, k = piece.c0, piece.c1, piece.c2, piece.k
    sin, cos = np.sin(k * t), np.cos(k * t)
    acc = c0 + c1 * sin + c2 * cos
    jerk = k * (c1 * cos - c2 * sin)
    vel = v0 + c0 * t + c1 / k * (1 - cos) + c2 / k * sin
    pos = s0 + v0 * t + c0 * t ** 2 / 2 + c1 / k * (t - sin / k) + c2 / k ** 2 * (1 - cos)
    return pos, vel, acc, jerk


@functools.lru_cache(maxsize=None)
def _normalised(pieces: tuple[_Piece, ...]):
    """Start values (v0, s0) of each piece for unit peak acceleration, and the scale
    making S(1) = 1."""
    starts, v0, s0 = [], 0.0, 0.0
    for piece in pieces:
        starts.append((v0, s0))
        s, v, _, _ = _integrated(piece, np.float64(piece.end - piece.start), v0, s0)
        v0, s0 = float(v), float(s)
    return tuple(starts), 1.0 / s0


def _piecewise(pieces: tuple[_Piece, ...], x):
    """Each x is given to the piece it falls in (the first piece extends below 0, the
    last above 1, so that the law stays analytic just outside a segment)."""
    x = np.asarray(x, float)
    starts, scale = _normalised(pieces)
    ends = np.array([p.end for p in pieces[:-1]])
    index = np.searchsorted(ends, x, side="right")
    out = [np.zeros_like(x) for _ in range(4)]
    for k, (piece, (v0, s0)) in enumerate(zip(pieces, starts)):
        inside = index == k
        values = _integrated(piece, x[inside] - piece.start, v0, s0)
        for o, v in zip(out, values):
            o[inside] = v * scale
    return tuple(out)


_CONSTANT_ACCELERATION = (_Piece(0.0, 0.5, 1.0, 0.0, 0.0, 1.0), _Piece(0.5, 1.0, -1.0, 0.0, 0.0, 1.0))
_K = 4 * PI
_MODIFIED_TRAPEZOIDAL = (
    _Piece(0.0, 1 / 8, 0.0, 1.0, 0.0, _K), _Piece(1 / 8, 3 / 8, 1.0, 0.0, 0.0, _K),
    _Piece(3 / 8, 5 / 8, 0.0, 0.0, 1.0, _K), _Piece(5 / 8, 7 / 8, -1.0, 0.0, 0.0, _K),
    _Piece(7 / 8, 1.0, 0.0, 0.0, -1.0, _K))
_MODIFIED_SINE = (
    _Piece(0.0, 1 / 8, 0.0, 1.0, 0.0, _K), _Piece(1 / 8, 7 / 8, 0.0, 0.0, 1.0, 4 * PI / 3),
    _Piece(7 / 8, 1.0, 0.0, 0.0, -1.0, _K))


@_law('Norton (2012), ch. 8')
def constant_acceleration(x):
    """Parabolic: S = 2 x^2 (x <= 1/2), 1 - 2 (1 - x)^2 (Norton ch. 8; Singh & Sanyal
    2017 Table 17, whose second half is misprinted as h[1 - 2{1 - k^2}]). Infinite jerk at
    ends and middle."""
    return _piecewise(_CONSTANT_ACCELERATION, x)


@_law('Norton (2012), ch. 8')
def modified_trapezoidal(x):
    """Modified trapezoid: sine ramps of period 1/2 over x in [0, 1/8], [3/8, 5/8], [7/8, 1]
    and constant acceleration between (Norton ch. 8, peak C_a = 4.8881)."""
    return _piecewise(_MODIFIED_TRAPEZOIDAL, x)


@_law('Norton (2012), ch. 8')
def modified_sine(x):
    """Modified sine: sine of period 1/2 over [0, 1/8] and [7/8, 1], of period 3/2 between
    (Norton ch. 8, peak C_a = 5.5280)."""
    return _piecewise(_MODIFIED_SINE, x)


LAW_FUNCTIONS = {f.__name__: f for f in (uniform_velocity, constant_acceleration, simple_harmonic,
                                         cycloidal, polynomial_345, polynomial_4567,
                                         modified_trapezoidal, modified_sine)}


# ------------------------------------------------------------------ a full turn


@dataclass(frozen=True)
class MotionSegment:
    """One segment of the design motion (SI): start angle, span, signed height, law.

    Parameters
    ----------
    start : float
        Cam angle where the segment starts [rad].
    span : float
        Cam angle the segment spans [rad].
    height : float
        Signed lift over the segment: + rise, - return, 0 dwell [m].
    level : float
        Follower position at the segment start [m].
    law : str or None
        Name of the motion law (a key of ``LAW_FUNCTIONS`` or ``"spline"``); None for a
        dwell.
    spline : SplineLaw or None
        The normalised law of a ``spline`` segment (:mod:`fickcam.cam.spline`).
    correction : tuple of complex
        Fourier harmonics of a polydyne correction [m] (:mod:`fickcam.cam.polydyne`).
    """

    start: float
    span: float
    height: float  # + rise, - return, 0 dwell
    level: float   # follower position at the segment start (m)
    law: str | None
    spline: object = None  # SplineLaw of a ``spline`` segment (fickcam.cam.spline)
    correction: tuple = ()  # harmonics of a polydyne profile correction (fickcam.cam.polydyne)


def segments_from_spec(specs) -> tuple[MotionSegment, ...]:
    """Turn scene segments into :class:`MotionSegment` s laid end to end from 0 rad.

    Parameters
    ----------
    specs : sequence of Segment
        Scene segments with ``.angle`` [rad], ``.height`` [m], ``.law`` and, for a spline,
        ``.spline``.

    Returns
    -------
    tuple of MotionSegment
        The segments, each starting where the previous one ends, at the level it reached.
    """
    out, start, level = [], 0.0, 0.0
    for s in specs:
        out.append(MotionSegment(start, float(s.angle), float(s.height), level,
                                 getattr(s, "law", None), _spline_of(s)))
        start += float(s.angle)
        level += float(s.height)
    return tuple(out)


def _spline_of(spec):
    """The normalised :class:`~fickcam.cam.spline.SplineLaw` of a scene ``spline`` segment."""
    given = getattr(spec, "spline", None)
    if given is None:
        return None
    # deferred: keeps the command's modules off the start-up path
    from .spline import spline_law

    return spline_law(given.points, spec.height, spec.angle, given.degree,
                      given.start_derivatives, given.end_derivatives)


def segment_motion(segment: MotionSegment, theta):
    """(y, y', y'', y''') per radian of cam angle inside one segment, with the segment's
    polydyne correction when it has one.

    Parameters
    ----------
    segment : MotionSegment
        The segment.
    theta : float or array_like
        Cam angle, inside the segment [rad].

    Returns
    -------
    tuple of numpy.ndarray
        y [m], dy/dtheta [m/rad], d2y/dtheta2 [m/rad^2], d3y/dtheta3 [m/rad^3].
    """
    law = _law_motion(segment, theta)
    if not segment.correction:
        return law
    return tuple(a + b for a, b in zip(law, correction_motion(np.asarray(segment.correction), theta)))


def _law_motion(segment: MotionSegment, theta):
    """The segment's own law (no polydyne correction), as :func:`segment_motion`."""
    theta = np.asarray(theta, float)
    if segment.law is None or segment.height == 0.0:
        zero = np.zeros_like(theta)
        return zero + segment.level, zero, zero, zero
    x = (theta - segment.start) / segment.span
    if segment.law == "spline":
        s, s1, s2, s3 = spline_motion(segment.spline, x)
    else:
        s, s1, s2, s3 = LAW_FUNCTIONS[segment.law](x)
    h, b = segment.height, segment.span
    return segment.level + h * s, h * s1 / b, h * s2 / b ** 2, h * s3 / b ** 3


def follower_motion(segments, theta, corrected: bool = True):
    """(y, dy/dtheta, d2y/dtheta2, d3y/dtheta3) of the design motion, theta (rad) taken
    modulo 2 pi; at a joint the value of the segment that starts there. A polydyne
    correction is added unless ``corrected`` is False (the chosen motion alone).

    Parameters
    ----------
    segments : sequence of MotionSegment
        The motion over one turn (:func:`segments_from_spec`), angles [rad], heights [m].
    theta : float or array_like
        The cam angle [rad].
    corrected : bool
        Add the polydyne correction, where the motion has one.

    Returns
    -------
    tuple of numpy.ndarray
        y [m], dy/dtheta [m/rad], d2y/dtheta2 [m/rad^2], d3y/dtheta3 [m/rad^3].

    References
    ----------
    R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill, 2012, ch. 8.
    """
    theta = np.mod(np.asarray(theta, float), 2 * PI)
    out = [np.zeros_like(theta) for _ in range(4)]
    for k, seg in enumerate(segments):
        last = k == len(segments) - 1
        inside = (theta >= seg.start) & ((theta < seg.start + seg.span) | last)
        for o, v in zip(out, _law_motion(seg, theta[inside])):
            o[inside] = v
    if corrected and segments[0].correction:
        coefficients = np.asarray(segments[0].correction)
        out = [o + at_angles(coefficients, theta, order) for order, o in enumerate(out)]
    return tuple(out)


def time_derivatives(per_angle, omega):
    """(y, v, a, j) from derivatives per radian at a constant speed omega (rad/s).

    Parameters
    ----------
    per_angle : tuple of numpy.ndarray
        y [m], dy/dtheta [m/rad], d2y/dtheta2 [m/rad^2], d3y/dtheta3 [m/rad^3].
    omega : float
        The cam speed [rad/s].

    Returns
    -------
    tuple of numpy.ndarray
        y [m], v [m/s], a [m/s^2], j [m/s^3].
    """
    y, d1, d2, d3 = per_angle
    return y, d1 * omega, d2 * omega ** 2, d3 * omega ** 3


def _joints(joints) -> str:
    """``the 105 and 255 deg joints of its simple_harmonic segments`` from (angle [degree],
    laws meeting there) per joint."""
    angles = [f"{angle:.4g}" for angle, _ in joints]
    listed = angles[0] if len(angles) == 1 else ", ".join(angles[:-1]) + " and " + angles[-1]
    laws = sorted(set().union(*(laws for _, laws in joints)))
    return (f"the {listed} deg joint{'s' * (len(angles) > 1)}"
            + (f" of its {' and '.join(laws)} segments" if laws else ""))


def joint_notices(segments, tolerance: float = 1e-9) -> list[str]:
    """Warnings where the motion leaves infinite acceleration (velocity step) or infinite
    jerk (acceleration step) at a segment joint or inside a law (Norton ch. 8, the
    'fundamental law of cam design').

    Parameters
    ----------
    segments : sequence of MotionSegment
        The motion over one turn.
    tolerance : float
        Step in velocity (times the span) or in acceleration (times the span squared)
        that counts as a jump, relative to the largest lift [-].

    Returns
    -------
    list of fickcam.messages.DesignNotice
        One sentence per joint or law with a step, true at every age (a run tells it once);
        empty when the motion is smooth.

    References
    ----------
    Norton (2012), ch. 8; in full in :mod:`fickcam.cam`.
    """
    return list(_joint_notices(tuple(segments), tolerance))


@functools.lru_cache(maxsize=64)
def _joint_notices(segments: tuple, tolerance: float) -> tuple:
    """:func:`joint_notices` of a motion, once per motion (every ageing time and every
    evaluation of the limit search tells the same)."""
    lift = max(abs(s.height) for s in segments) or 1.0
    steps: dict[str, list[tuple[float, set]]] = {"velocity": [], "acceleration": []}
    n = len(segments)
    for k in range(n):
        a, b = segments[k], segments[(k + 1) % n]
        end = segment_motion(a, np.array([a.start + a.span]))
        start = segment_motion(b, np.array([b.start]))
        where = (math.degrees((a.start + a.span) % (2 * PI)), {a.law, b.law} - {None, ""})
        span = min(a.span, b.span)
        if abs(end[1][0] - start[1][0]) * span > tolerance * lift:
            steps["velocity"].append(where)
        elif abs(end[2][0] - start[2][0]) * span ** 2 > tolerance * lift:
            steps["acceleration"].append(where)
    effect = {"velocity": "infinite acceleration and jerk there, a shock each turn",
              "acceleration": "infinite jerk there, which excites vibration (a cycloidal or "
                              "polynomial law has none)"}
    notices = [f"motion as designed: {what} jumps at {_joints(joints)}: {effect[what]}"
               for what, joints in steps.items() if joints]
    for seg in segments:
        if seg.law == "constant_acceleration" and seg.height != 0.0:
            notices.append(f"motion as designed: constant_acceleration leaves infinite jerk at "
                           f"mid-segment ({math.degrees(seg.start + seg.span / 2):.4g} deg)")
        if seg.law == "spline" and seg.spline.degree < 5 and len(seg.spline.x) > 2:
            what = "velocity (infinite acceleration)" if seg.spline.degree == 1 else \
                "acceleration (infinite jerk)" if seg.spline.degree == 3 else ""
            notices.append(f"motion as designed: a degree-{seg.spline.degree} spline steps its "
                           f"{what} at its inner points ({math.degrees(seg.start):.4g} deg segment)")
    return tuple(design_notice(text) for text in notices)
