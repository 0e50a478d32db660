"""Cam geometry: dry working profile, its distortion by swelling, and the follower
motion that the (aged) geometry imposes, found geometrically.

Frame: the cam turns counter-clockwise about the origin by theta; the follower
translates along +y on the line x = offset. A point p of the cam frame is at
R(theta) p in the fixed frame (kinematic inversion, Norton, Design of Machinery
5th ed., sec. 8.6). The dry profile is parametrised by the design cam angle psi;
swelling maps it by D = diag(1 + eps_x, 1 + eps_y) (x = the cam's fibre direction)
and the roller radius by (1 + eps_roller).

For every point psi of the aged profile the cam angle theta(psi) at which it is the
contact point, and the follower height Y(psi), are closed-form; within one design
segment both are analytic, so y(theta) = Y(psi(theta)) is sampled at Chebyshev-Lobatto
nodes (psi from theta by Newton) and differentiated spectrally (Trefethen, Spectral
Methods in MATLAB, 2000, ch. 6).

The papers are cited in full in :mod:`fickcam.cam`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev, polyutils

from . import arm
from .motion import ORDERS, segment_motion

TWO_PI = 2.0 * np.pi
EPS = float(np.finfo(float).eps)
#: Newton on the contact angle stops at steps below this many units in the last place of psi
STEP_ULPS = 8


def rotate(angle, x, y):
    """R(angle) (x, y): the point turned counter-clockwise about the origin, vectorised.

    Parameters
    ----------
    angle : float or array_like
        Angle of rotation, counter-clockwise [rad].
    x, y : float or array_like
        The point's coordinates [m].

    Returns
    -------
    tuple of numpy.ndarray
        The turned point's x and y [m].
    """
    c, s = np.cos(angle), np.sin(angle)
    return c * x - s * y, s * x + c * y


def prime_height(prime_radius, offset: float):
    """Height of the follower's pitch point on the prime circle: sqrt(Rp^2 - e^2)
    (its denominator in Norton ch. 8).

    Parameters
    ----------
    prime_radius : float or numpy.ndarray
        The prime circle's radius Rp [m] (one per ageing time, for a stacked state).
    offset : float
        The follower's offset e [m].

    Returns
    -------
    float or numpy.ndarray
        The height [m], of the shape of ``prime_radius``.
    """
    height = np.sqrt(prime_radius ** 2 - offset ** 2)
    return float(height) if np.ndim(height) == 0 else height


def dry_profile(design, segment, psi):
    """Dry working profile point W0 and tangent T0 (cam frame, traced clockwise) at the
    design angle psi inside ``segment`` (a MotionSegment, or None for the eccentric disc).

    Knife: W0 = R(-psi) (e, s0 + y); roller: pitch point minus Rf along the outward
    normal (Norton ch. 8); flat: W0 = R(-psi) (dy/dpsi, Rb + y) (Norton ch. 8);
    eccentric: a circle of radius R about (0, -eccentricity) (Madhukar et
    al. 2023, Fig. 5.1, lowest follower position at theta = 0).

    Parameters
    ----------
    design : CamDesign
        The dry design (:class:`fickcam.cam.design.CamDesign`), lengths [m].
    segment : MotionSegment or None
        The motion segment containing psi; None for the eccentric disc.
    psi : float or array_like
        Design cam angle [rad].

    Returns
    -------
    tuple of numpy.ndarray
        W0_x, W0_y [m] and the unit tangent T0_x, T0_y [-].

    References
    ----------
    Norton (2012), ch. 8; Madhukar et al. (2023), Fig. 5.1; in full in
    :mod:`fickcam.cam`.
    """
    psi = np.asarray(psi, float)
    if design.arm is not None:
        return arm.dry_profile(design.arm, design.follower_kind, design.base_circle_radius,
                               design.roller_radius, psi, segment_motion(segment, psi))
    if segment is None:
        wx, wy = rotate(-psi, 0.0, design.disc_radius)
        tx, ty = rotate(-psi, 1.0, 0.0)
        return wx, wy - design.eccentricity, tx, ty
    y, y1, _, _ = segment_motion(segment, psi)
    if design.follower_kind == "flat":
        wx, wy = rotate(-psi, y1, design.base_circle_radius + y)
        tx, ty = rotate(-psi, 1.0, 0.0)
        return wx, wy, tx, ty
    e = design.offset
    s0 = prime_height(design.base_circle_radius + design.roller_radius, e)
    # a = q' - J q with q = (e, s0 + y): tangent of the pitch curve in the follower frame
    ax, ay = s0 + y, y1 - e
    norm = np.hypot(ax, ay)
    nx, ny = -ay / norm, ax / norm  # outward normal J a/|a| (clockwise traversal)
    px, py = e - design.roller_radius * nx, s0 + y - design.roller_radius * ny
    wx, wy = rotate(-psi, px, py)
    tx, ty = rotate(-psi, ax / norm, ay / norm)
    return wx, wy, tx, ty


def _aged_contact(design, psi, dry, strain_x, strain_y, roller_radius, arm_strain):
    """(theta, Y) for aged profile points psi, whose dry points and tangents are ``dry`` =
    (W0x, W0y, T0x, T0y) (:func:`dry_profile`): the cam angle at which psi touches the
    follower and the follower height then (pitch point for knife/roller, face for flat;
    a swinging arm's angle from its dry base position, :mod:`fickcam.cam.arm`, whose length
    and face offset grow by 1 + ``arm_strain``). Elementwise: the strains and the roller
    radius may be arrays, one value per point."""
    wx, wy, tx, ty = dry
    wx, wy = (1 + strain_x) * wx, (1 + strain_y) * wy
    tx, ty = (1 + strain_x) * tx, (1 + strain_y) * ty
    norm = np.hypot(tx, ty)
    nx, ny = -ty / norm, tx / norm
    if design.arm is not None:
        theta, height = _arm_contact(design, wx, wy, nx, ny, roller_radius, 1.0 + arm_strain)
    elif design.follower_kind == "flat":
        theta = np.pi / 2 - np.arctan2(ny, nx)
        height = wx * nx + wy * ny
    else:
        cx, cy = wx + roller_radius * nx, wy + roller_radius * ny
        r = np.hypot(cx, cy)
        theta = np.arccos(design.offset / r) - np.arctan2(cy, cx)
        height = np.sqrt(r ** 2 - design.offset ** 2)
    theta = psi + np.mod(theta - psi + np.pi, TWO_PI) - np.pi
    return theta, height


def _pieces_contact(design, segments, label, strain_x, strain_y, roller_radius, arm_strain):
    """:func:`_aged_contact` of points psi of several pieces at once, ``label`` (an array of
    piece indices, one per point) telling which piece's dry profile each point is on."""
    masks = [label == k for k in range(len(segments))]

    def contact(psi):
        dry = [np.empty(psi.shape) for _ in range(4)]
        for segment, inside in zip(segments, masks):
            for whole, part in zip(dry, dry_profile(design, segment, psi[inside])):
                whole[inside] = part
        return _aged_contact(design, psi, dry, strain_x, strain_y, roller_radius, arm_strain)

    return contact


def _arm_contact(design, wx, wy, nx, ny, roller_radius, grow):
    """(theta, arm angle) of aged profile points on a swinging arm grown by ``grow``."""
    a = design.arm
    if design.follower_kind == "flat":
        return arm.aged_face_contact(a, arm.face_base_angle(a, design.base_circle_radius),
                                     a.face_offset * grow, wx, wy, nx, ny)
    phi0 = arm.roller_base_angle(a, design.base_circle_radius + design.roller_radius)
    return arm.aged_roller_contact(a, phi0, a.length * grow, wx, wy, nx, ny, roller_radius)


def _solve_psi(contact, theta_target, guess, steps: int = 30):
    """psi with contact(psi)[0] = theta_target (Newton, central-difference slope; the three
    points in one call), until the largest step is a few units in the last place of psi
    (the round-off of theta(psi) then moves psi back and forth by about that much)."""
    psi = np.array(guess, float)
    h = 1e-6
    n = psi.size
    for _ in range(steps):
        theta = contact(np.concatenate([psi, psi + h, psi - h]))[0]
        slope = (theta[n:2 * n] - theta[2 * n:]) / (2 * h)
        step = (theta[:n] - theta_target) / slope
        psi = psi - step
        largest = max(1.0, np.max(np.abs(psi), initial=0.0))
        if np.max(np.abs(step), initial=0.0) <= STEP_ULPS * EPS * largest:
            break
    return psi


def _lobatto(n: int) -> np.ndarray:
    """Chebyshev-Lobatto points on [-1, 1], increasing."""
    return -np.cos(np.pi * np.arange(n + 1) / n)


@dataclass(frozen=True)
class PiecewiseMotion:
    """The aged follower motion as one Chebyshev series per design piece, with its first
    three derivatives (:func:`fit_geometric_motion`).

    Parameters
    ----------
    starts, ends : numpy.ndarray
        Cam angles where each piece starts and ends [rad].
    offsets, scales : numpy.ndarray
        Each piece's map of the cam angle onto [-1, 1]: x = offset + scale theta [-], [1/rad].
    table : numpy.ndarray
        Coefficients (term, order, piece): Y and its derivatives d^kY/dtheta^k, k = 1..3,
        each derivative padded with zeros past its last term [m/rad^k] ([rad/rad^k] for an
        arm).
    """

    starts: np.ndarray
    ends: np.ndarray
    offsets: np.ndarray
    scales: np.ndarray
    table: np.ndarray


def _series_table(coef, mapping):
    """Coefficients (term, order, piece) of Y and dY, d2Y, d3Y per piece from Y's
    coefficients (term, piece), each derivative padded with zeros: the series
    Chebyshev.fit(...).deriv(k) make, all pieces at once (chebder multiplies by the scale
    before each differentiation, here each piece's own)."""
    table = np.zeros((len(coef), 4, coef.shape[1]))
    table[:, 0] = coef
    scales = np.array([scl for _, scl in mapping])
    for k in (1, 2, 3):
        coef = chebyshev.chebder(coef * scales, 1, 1.0)
        table[:len(coef), k] = coef
    return table


def _turning_points(table, starts, ends):
    """Real roots of each piece's dY/dtheta strictly inside the piece [rad] (the companion
    matrices' eigenvalues in one call where the pieces' degrees agree)."""
    slopes = [polyutils.as_series([table[:, 1, p]])[0] for p in range(table.shape[2])]
    if len({len(c) for c in slopes}) == 1 and len(slopes[0]) > 2:
        stack = np.stack([chebyshev.chebcompanion(c)[::-1, ::-1] for c in slopes])
        roots = list(np.linalg.eigvals(stack))
    else:
        roots = [chebyshev.chebroots(c) for c in slopes]
    turning = []
    for r, ta, tb in zip(roots, starts, ends):
        back_off, back_scl = polyutils.mapparms([-1.0, 1.0], [ta, tb])
        r = back_off + back_scl * r
        turning.append(r.real[(np.abs(r.imag) < 1e-9) & (r.real > ta) & (r.real < tb)])
    return turning


def fit_geometric_motion(design, pieces, strain_x, strain_y, roller_radius, nodes: int = 40,
                         arm_strain: float = 0.0):
    """The aged follower height as Chebyshev series, one per design piece (a
    :class:`PiecewiseMotion`), the angle origin, and (lowest, highest) Y over the turn.
    ``pieces`` are (segment, psi_start, psi_end).

    Each swollen profile point psi is put where it touches the follower (Newton on the
    contact angle, all pieces in one solve) at the Chebyshev-Lobatto nodes of its piece,
    and the height there is fitted by a Chebyshev series of degree ``nodes``.

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    pieces : sequence of tuple
        (segment, psi_start [rad], psi_end [rad]) per piece (:func:`pieces_of`).
    strain_x, strain_y : float
        Swelling strain of the cam plate along its x and y axes [-].
    roller_radius : float
        The (aged) roller radius [m].
    nodes : int
        Degree of each Chebyshev series.
    arm_strain : float
        Swelling strain of a swinging arm's length and face offset [-].

    Returns
    -------
    fitted : PiecewiseMotion
        The series of Y and of dY/dtheta, d2Y/dtheta2, d3Y/dtheta3 per piece, with the
        cam angles where the pieces start and end [rad].
    origin : float
        Cam angle where the first piece starts [rad].
    extremes : tuple of float
        Lowest and highest Y over the turn: follower height [m], or arm angle [rad] for a
        swinging arm.
    """
    segments = [segment for segment, _, _ in pieces]
    count = len(pieces)
    ends = np.array([[a, b] for _, a, b in pieces], float).ravel()
    spans = _pieces_contact(design, segments, np.repeat(np.arange(count), 2), strain_x,
                            strain_y, roller_radius, arm_strain)(ends)[0]
    starts, stops = spans[0::2], spans[1::2]
    size = nodes + 1
    label = np.repeat(np.arange(count), size)
    contact = _pieces_contact(design, segments, np.tile(label, 3), strain_x, strain_y,
                              roller_radius, arm_strain)
    t_nodes = np.concatenate([ta + (tb - ta) * (_lobatto(nodes) + 1) / 2
                              for ta, tb in zip(starts, stops)])
    # swelling shifts theta(psi) only slightly: the nodes are the first guess
    psi = _solve_psi(contact, t_nodes, t_nodes)
    heights = _pieces_contact(design, segments, label, strain_x, strain_y, roller_radius,
                              arm_strain)(psi)[1]
    coef = np.empty((size, count))
    mapping = []
    for k, (ta, tb) in enumerate(zip(starts, stops)):
        group = slice(k * size, (k + 1) * size)
        coef[:, k] = chebyshev.chebfit(polyutils.mapdomain(t_nodes[group], [ta, tb], [-1.0, 1.0]),
                                       heights[group], nodes)
        mapping.append(polyutils.mapparms([ta, tb], [-1.0, 1.0]))
    table = _series_table(coef, mapping)
    fitted = PiecewiseMotion(starts, stops, np.array([m[0] for m in mapping]),
                             np.array([m[1] for m in mapping]), table)
    turning = _turning_points(table, starts, stops)
    at = [np.r_[ta, tb, points] for ta, tb, points in zip(starts, stops, turning)]
    piece = np.repeat(np.arange(count), [len(a) for a in at])
    at = np.concatenate(at)
    extremes = chebyshev.chebval(fitted.offsets[piece] + fitted.scales[piece] * at,
                                 table[:, 0, piece], tensor=False)
    lowest, highest = float(extremes.min()), float(extremes.max())
    return fitted, float(starts[0]), (lowest, highest)


def evaluate_geometric_motion(fitted, origin, theta, orders=ORDERS):
    """(Y, dY/dtheta, d2Y, d3Y) at cam angles ``theta`` from :func:`fit_geometric_motion`
    (all pieces and the orders asked for in one Clenshaw recursion, numpy's ``chebval``;
    NaN outside every piece).

    Parameters
    ----------
    fitted : PiecewiseMotion
        The per-piece series of :func:`fit_geometric_motion`.
    origin : float
        Cam angle where the first piece starts [rad].
    theta : float or array_like
        Cam angles, taken modulo 2 pi [rad].
    orders : tuple of int
        The derivative orders returned, each in 0..3 [-] (all four by default).

    Returns
    -------
    tuple of numpy.ndarray
        Y [m] and its first three derivatives [m/rad^k] (arm angle [rad] and [rad/rad^k]
        for a swinging arm), or those of ``orders``, in that order.
    """
    theta = np.mod(np.asarray(theta, float), TWO_PI)
    shifted = origin + np.mod(theta - origin, TWO_PI)
    piece = np.full(theta.shape, -1)
    for k, (ta, tb) in enumerate(zip(fitted.starts, fitted.ends)):
        inside = (shifted >= ta) & (shifted < tb) if tb < origin + TWO_PI - 1e-12 else \
            (shifted >= ta)
        piece[inside] = k
    known = np.maximum(piece, 0)
    x = fitted.offsets[known] + fitted.scales[known] * shifted
    # each angle's own piece: x broadcast over the (order, angle) columns of its series
    values = chebyshev.chebval(x, fitted.table[:, list(orders)][:, :, known], tensor=False)
    values[:, piece < 0] = np.nan
    return tuple(values)


def geometric_motion(design, pieces, strain_x, strain_y, roller_radius, theta, nodes: int = 40):
    """Follower height Y and dY/dtheta, d2Y, d3Y at cam angles ``theta`` for the aged
    geometry, and (lowest, highest) Y over the turn. ``pieces`` are (segment, psi_start, psi_end).

    Parameters
    ----------
    design, pieces, strain_x, strain_y, roller_radius
        As :func:`fit_geometric_motion` takes them: lengths [m], angles [rad], strains [-].
    theta : float or array_like
        Cam angles [rad].
    nodes : int
        Degree of each Chebyshev series.

    Returns
    -------
    motion : tuple of numpy.ndarray
        Y [m] and its first three derivatives [m/rad^k] (arm angle [rad] for an arm).
    extremes : tuple of float
        Lowest and highest Y over the turn [m] ([rad] for an arm).
    """
    fitted, origin, extremes = fit_geometric_motion(design, pieces, strain_x, strain_y,
                                                    roller_radius, nodes)
    return evaluate_geometric_motion(fitted, origin, theta), extremes


def pieces_of(design):
    """(segment, psi_start, psi_end) for each design segment (one piece for the disc).

    Parameters
    ----------
    design : CamDesign
        The dry design.

    Returns
    -------
    tuple of tuple
        (MotionSegment or None, psi_start [rad], psi_end [rad]) per piece.
    """
    if design.kind == "eccentric":
        return ((None, 0.0, TWO_PI),)
    return tuple((s, s.start, s.start + s.span) for s in design.segments)


def working_outline(design, strain_x: float = 0.0, strain_y: float = 0.0, n: int = 720):
    """Closed working profile (x, y) in m, counter-clockwise, last point != first.

    Parameters
    ----------
    design : CamDesign
        The cam.
    strain_x, strain_y : float
        Uniform free strains of the plate along the cam axes [-].
    n : int
        The number of points.

    Returns
    -------
    tuple of numpy.ndarray
        x and y [m] of the outline.
    """
    if design.kind == "profile":
        x, y = design.profile.outline(n)
        return (1 + strain_x) * x, (1 + strain_y) * y
    psi = np.linspace(0.0, TWO_PI, n, endpoint=False)
    x = np.empty(n)
    y = np.empty(n)
    for segment, a, b in pieces_of(design):
        inside = (psi >= a) & (psi < b) if b < TWO_PI else psi >= a
        wx, wy, _, _ = dry_profile(design, segment, psi[inside])
        x[inside], y[inside] = wx, wy
    x, y = (1 + strain_x) * x, (1 + strain_y) * y
    return x[::-1].copy(), y[::-1].copy()
