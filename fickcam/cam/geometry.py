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
#: Y's round-off, in units in the last place of the largest |Y| of its piece
ROUNDOFF_ULPS = 16


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
    three derivatives (:func:`fit_geometric_motion`); stacked over ageing times
    (:func:`fit_geometric_motions`), each field has a leading time axis (the table's is its
    third).

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

    def at(self, k: int) -> PiecewiseMotion:
        """Ageing time k of a motion stacked over ageing times (:func:`fit_geometric_motions`:
        each field with a leading time axis, the table's third).

        Parameters
        ----------
        k : int
            The ageing time's index.

        Returns
        -------
        PiecewiseMotion
            That time's series.
        """
        return PiecewiseMotion(self.starts[k], self.ends[k], self.offsets[k], self.scales[k],
                               self.table[:, :, k])


def _series_table(coef, scales):
    """Coefficients (term, order, piece) of Y and dY, d2Y, d3Y per piece from Y's
    coefficients (term, piece), each derivative padded with zeros: the series
    Chebyshev.fit(...).deriv(k) make, all pieces at once (chebder multiplies by the scale
    before each differentiation, here each piece's own ``scales``)."""
    table = np.zeros((len(coef), 4, coef.shape[1]))
    table[:, 0] = coef
    for k in (1, 2, 3):
        coef = chebyshev.chebder(coef * scales, 1, 1.0)
        table[:len(coef), k] = coef
    return table


def _piece_extremes(table):
    """Lowest and highest Y of each piece's series over its whole piece, x in [-1, 1]: the
    largest and smallest of Y at its ends, on a grid of Chebyshev-Lobatto points of twice
    its degree and at the turning points between them (every sign change of dY/dx on the
    grid over which Y moves by more than its round-off, bracketed and closed by
    :func:`_slope_roots`), all pieces at once.

    Parameters
    ----------
    table : numpy.ndarray
        Coefficients (term, order, piece) of :func:`_series_table` [m/rad^k] ([rad/rad^k]
        for an arm).

    Returns
    -------
    tuple of numpy.ndarray
        The lowest and the highest Y of each piece [m] ([rad] for an arm), shape (piece,).
    """
    grid = _lobatto(2 * (len(table) - 1))
    heights, slopes = chebyshev.chebval(grid, table[:, :2])  # each (piece, point)
    lowest, highest = heights.min(axis=1), heights.max(axis=1)
    # a bracket over which Y moves by less than its round-off (a dwell's slope is noise)
    # holds no extreme beyond its ends' values
    moves = np.maximum(np.abs(slopes[:, :-1]), np.abs(slopes[:, 1:])) * np.diff(grid)
    noise = ROUNDOFF_ULPS * EPS * np.abs(heights).max(axis=1, keepdims=True)
    piece, left = np.nonzero((slopes[:, :-1] * slopes[:, 1:] < 0.0) & (moves > noise))
    if piece.size:
        roots = _slope_roots(table[:, 1, piece], grid[left], grid[left + 1],
                             slopes[piece, left], slopes[piece, left + 1])
        turning = chebyshev.chebval(roots, table[:, 0, piece], tensor=False)
        np.minimum.at(lowest, piece, turning)
        np.maximum.at(highest, piece, turning)
    return lowest, highest


def _slope_roots(slope, low, high, at_low, at_high, steps: int = 60):
    """The root of each series ``slope`` (term, bracket; dY/dtheta as a series in x) inside
    its bracket (low, high) on x, where it changes sign from ``at_low`` to ``at_high``:
    Newton steps on the series from the chord's root, a step that would leave the bracket
    replaced by bisection, the bracket shrunk to the side that keeps the sign change, until
    every step is a few units in the last place of x."""
    both = np.stack([slope, np.pad(chebyshev.chebder(slope), ((0, 1), (0, 0)))], axis=1)
    x = low + (high - low) * at_low / (at_low - at_high)
    for _ in range(steps):
        value, derivative = chebyshev.chebval(x, both, tensor=False)
        same = np.signbit(value) == np.signbit(at_low)
        low, high = np.where(same, x, low), np.where(same, high, x)
        at_low = np.where(same, value, at_low)
        with np.errstate(divide="ignore", invalid="ignore"):
            guess = x - value / derivative
        inside = (guess >= low) & (guess <= high)
        moved = np.where(value == 0.0, x, np.where(inside, guess, 0.5 * (low + high)))
        done = np.max(np.abs(moved - x), initial=0.0) <= STEP_ULPS * EPS
        x = moved
        if done:
            break
    return x


def fit_geometric_motion(design, pieces, strain_x, strain_y, roller_radius, nodes: int = 40,
                         arm_strain: float = 0.0):
    """The aged follower height as Chebyshev series, one per design piece (a
    :class:`PiecewiseMotion`), the angle origin, and (lowest, highest) Y over the turn.
    ``pieces`` are (segment, psi_start, psi_end): :func:`fit_geometric_motions` for one
    ageing time.

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    pieces : sequence of tuple
        Each design piece's (segment, psi_start [rad], psi_end [rad]).
    strain_x, strain_y : float
        The plate's swelling strains along x and y [-].
    roller_radius : float
        The swollen roller's radius [m].
    nodes : int
        The series' degree.
    arm_strain : float
        A swinging arm's swelling strain along its length [-].

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
    stacked, origins, extremes = fit_geometric_motions(design, pieces, strain_x, strain_y,
                                                       roller_radius, nodes, arm_strain)
    return stacked.at(0), float(origins[0]), extremes[0]


def fit_geometric_motions(design, pieces, strain_x, strain_y, roller_radius, nodes: int = 40,
                          arm_strain=0.0):
    """The aged follower height of several ageing times at once (one per value of the
    strains), each as Chebyshev series, one per design piece; ``pieces`` are (segment,
    psi_start, psi_end).

    Each swollen profile point psi is put where it touches the follower (Newton on the
    contact angle, all pieces and times in one solve) at the Chebyshev-Lobatto nodes of its
    piece, and the height there is fitted by a Chebyshev series of degree ``nodes`` (one
    least-squares solve for every piece and time: the nodes are the same Lobatto points on
    [-1, 1]).

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    pieces : sequence of tuple
        (segment, psi_start [rad], psi_end [rad]) per piece (:func:`pieces_of`).
    strain_x, strain_y : float or array_like
        Swelling strain of the cam plate along its x and y axes [-], one per ageing time.
    roller_radius : float or array_like
        The (aged) roller radius [m], one per ageing time.
    nodes : int
        Degree of each Chebyshev series.
    arm_strain : float or array_like
        Swelling strain of a swinging arm's length and face offset [-], one per ageing time.

    Returns
    -------
    fitted : PiecewiseMotion
        The series of every time, its fields with a leading time axis: starts and ends
        (time, piece) [rad], table (term, order, time, piece).
    origins : numpy.ndarray
        Cam angle where each time's first piece starts [rad].
    extremes : list of tuple of float
        Each time's lowest and highest Y over the turn: follower height [m], or arm angle
        [rad] for a swinging arm.
    """
    strains = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, float)) for v in
                                    (strain_x, strain_y, roller_radius, arm_strain)))
    times, count, size = strains[0].size, len(pieces), nodes + 1
    segments = [segment for segment, _, _ in pieces]

    def contact(label, points_per_time, repeats=1):  # each point with its time's strains
        return _pieces_contact(design, segments, np.tile(label, times * repeats), *(
            np.tile(np.repeat(v, points_per_time), repeats) for v in strains))

    ends = np.array([[a, b] for _, a, b in pieces], float).ravel()
    spans = contact(np.repeat(np.arange(count), 2), 2 * count)(np.tile(ends, times))[0]
    starts, stops = spans[0::2].reshape(times, count), spans[1::2].reshape(times, count)
    label = np.repeat(np.arange(count), size)
    lobatto = _lobatto(nodes)
    t_nodes = (starts[..., None] + (stops - starts)[..., None] * (lobatto + 1) / 2).ravel()
    # swelling shifts theta(psi) only slightly: the nodes are the first guess
    psi = _solve_psi(contact(label, count * size, 3), t_nodes, t_nodes)
    heights = contact(label, count * size)(psi)[1].reshape(times * count, size)
    offsets, scales = polyutils.mapparms([starts.ravel(), stops.ravel()], [-1.0, 1.0])
    table = _series_table(chebyshev.chebfit(lobatto, heights.T, nodes), scales)
    lowest, highest = (v.reshape(times, count) for v in _piece_extremes(table))
    extremes = list(zip(lowest.min(axis=1).tolist(), highest.max(axis=1).tolist()))
    fitted = PiecewiseMotion(starts, stops, offsets.reshape(times, count),
                             scales.reshape(times, count),
                             table.reshape(size, 4, times, count))
    return fitted, starts[:, 0].copy(), extremes


def evaluate_geometric_motion(fitted, origin, theta, orders=ORDERS):
    """(Y, dY/dtheta, d2Y, d3Y) at cam angles ``theta`` from :func:`fit_geometric_motion`:
    :func:`evaluate_geometric_motions` for one ageing time.

    Parameters
    ----------
    fitted : PiecewiseMotion
        The per-piece series of :func:`fit_geometric_motion`.
    origin : float
        Cam angle where the first piece starts [rad].
    theta : float or array_like
        Cam angles, taken modulo 2 pi [rad].
    orders : tuple of int
        The derivative orders returned [-] (all four by default).

    Returns
    -------
    tuple of numpy.ndarray
        The derivatives ``orders`` [m/rad^k] ([rad/rad^k] for an arm), each of the shape of
        ``theta``; NaN outside every piece.
    """
    theta = np.asarray(theta, float)
    stacked = PiecewiseMotion(*(np.asarray(v)[None] for v in (
        fitted.starts, fitted.ends, fitted.offsets, fitted.scales)),
        fitted.table[:, :, None])
    values = evaluate_geometric_motions(stacked, np.array([origin]), theta.reshape(1, -1),
                                        orders)
    return tuple(v.reshape(theta.shape) for v in values)


def evaluate_geometric_motions(fitted, origins, theta, orders=ORDERS):
    """(Y, dY/dtheta, d2Y, d3Y) of several ageing times at cam angles ``theta``, one row
    of angles per time, from :func:`fit_geometric_motions` (all pieces, times and the orders
    asked for in one Clenshaw recursion, numpy's ``chebval``; NaN outside every piece).

    Parameters
    ----------
    fitted : PiecewiseMotion
        The series of :func:`fit_geometric_motions`, with a leading time axis.
    origins : numpy.ndarray
        Cam angle where each time's first piece starts [rad], shape (n,).
    theta : numpy.ndarray
        Cam angles, taken modulo 2 pi [rad], shape (n, k): row i for time i.
    orders : tuple of int
        The derivative orders returned, each in 0..3 [-] (all four by default).

    Returns
    -------
    tuple of numpy.ndarray
        Y [m] and its first three derivatives [m/rad^k] (arm angle [rad] and [rad/rad^k]
        for a swinging arm), or those of ``orders``, in that order, each (n, k).
    """
    theta = np.mod(np.asarray(theta, float), TWO_PI)
    origin = np.asarray(origins, float)[:, None]
    shifted = origin + np.mod(theta - origin, TWO_PI)
    piece = np.full(theta.shape, -1)
    for k in range(fitted.starts.shape[1]):
        ta, tb = fitted.starts[:, k, None], fitted.ends[:, k, None]
        inside = np.where(tb < origin + TWO_PI - 1e-12, (shifted >= ta) & (shifted < tb),
                          shifted >= ta)
        piece[inside] = k
    known, rows = np.maximum(piece, 0), np.arange(theta.shape[0])[:, None]
    x = fitted.offsets[rows, known] + fitted.scales[rows, known] * shifted
    # each angle's own time and piece: x broadcast over the (order, time, angle) columns;
    # the gathered coefficients laid out term by term, which the Clenshaw recursion reads
    # in turn (the gather leaves each term's values strided: twice the recursion's time)
    coefficients = np.ascontiguousarray(fitted.table[:, list(orders)][:, :, rows, known])
    values = chebyshev.chebval(x, coefficients, tensor=False)
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
