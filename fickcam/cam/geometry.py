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

import numpy as np
from numpy.polynomial import chebyshev

from . import arm
from .motion import segment_motion

TWO_PI = 2.0 * np.pi


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


def prime_height(prime_radius: float, offset: float) -> float:
    """Height of the follower's pitch point on the prime circle: sqrt(Rp^2 - e^2)
    (its denominator in Norton ch. 8).

    Parameters
    ----------
    prime_radius : float
        The prime circle's radius Rp [m].
    offset : float
        The follower's offset e [m].

    Returns
    -------
    float
        The height [m].
    """
    return float(np.sqrt(prime_radius ** 2 - offset ** 2))


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


def _aged_contact(design, segment, psi, strain_x, strain_y, roller_radius, arm_strain=0.0):
    """(theta, Y) for aged profile points psi: the cam angle at which psi touches the
    follower and the follower height then (pitch point for knife/roller, face for flat;
    a swinging arm's angle from its dry base position, :mod:`fickcam.cam.arm`, whose length
    and face offset grow by 1 + ``arm_strain``)."""
    wx, wy, tx, ty = dry_profile(design, segment, psi)
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
    points in one call)."""
    psi = np.array(guess, float)
    h = 1e-6
    n = psi.size
    for _ in range(steps):
        theta = contact(np.concatenate([psi, psi + h, psi - h]))[0]
        slope = (theta[n:2 * n] - theta[2 * n:]) / (2 * h)
        step = (theta[:n] - theta_target) / slope
        psi = psi - step
        if np.max(np.abs(step), initial=0.0) < 1e-15:
            break
    return psi


def _lobatto(n: int) -> np.ndarray:
    """Chebyshev-Lobatto points on [-1, 1], increasing."""
    return -np.cos(np.pi * np.arange(n + 1) / n)


def fit_geometric_motion(design, pieces, strain_x, strain_y, roller_radius, nodes: int = 40,
                         arm_strain: float = 0.0):
    """The aged follower height as Chebyshev series, one per design piece: a tuple of
    ((series and its first three derivatives), theta_start, theta_end), the angle origin,
    and (lowest, highest) Y over the turn. ``pieces`` are (segment, psi_start, psi_end).

    Each swollen profile point psi is put where it touches the follower (Newton on the
    contact angle) at the Chebyshev-Lobatto nodes of its piece, and the height there is
    fitted by a Chebyshev series of degree ``nodes``.

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
    fitted : tuple
        ((Y, dY/dtheta, d2Y/dtheta2, d3Y/dtheta3 series), theta_start [rad],
        theta_end [rad]) per piece.
    origin : float
        Cam angle where the first piece starts [rad].
    extremes : tuple of float
        Lowest and highest Y over the turn: follower height [m], or arm angle [rad] for a
        swinging arm.
    """
    lowest, highest = np.inf, -np.inf
    spans = []
    for segment, a, b in pieces:
        contact = (lambda s, seg=segment: _aged_contact(design, seg, s, strain_x, strain_y,
                                                       roller_radius, arm_strain))
        ta, tb = contact(np.array([a, b]))[0]
        spans.append((contact, ta, tb))
    fitted = []
    for contact, ta, tb in spans:
        t_nodes = ta + (tb - ta) * (_lobatto(nodes) + 1) / 2
        psi = _solve_psi(contact, t_nodes, t_nodes)  # swelling shifts theta(psi) only slightly
        series = chebyshev.Chebyshev.fit(t_nodes, contact(psi)[1], nodes, domain=[ta, tb])
        fitted.append(((series,) + tuple(series.deriv(k) for k in (1, 2, 3)), ta, tb))
        turning = series.deriv().roots()
        turning = turning.real[(np.abs(turning.imag) < 1e-9) & (turning.real > ta) &
                               (turning.real < tb)]
        extremes = series(np.r_[ta, tb, turning])
        lowest, highest = min(lowest, float(extremes.min())), max(highest, float(extremes.max()))
    return tuple(fitted), spans[0][1], (lowest, highest)


def evaluate_geometric_motion(fitted, origin, theta):
    """(Y, dY/dtheta, d2Y, d3Y) at cam angles ``theta`` from :func:`fit_geometric_motion`.

    Parameters
    ----------
    fitted : tuple
        The per-piece series of :func:`fit_geometric_motion`.
    origin : float
        Cam angle where the first piece starts [rad].
    theta : float or array_like
        Cam angles, taken modulo 2 pi [rad].

    Returns
    -------
    tuple of numpy.ndarray
        Y [m] and its first three derivatives [m/rad^k] (arm angle [rad] and [rad/rad^k]
        for a swinging arm).
    """
    theta = np.mod(np.asarray(theta, float), TWO_PI)
    out = [np.full(theta.shape, np.nan) for _ in range(4)]
    shifted = origin + np.mod(theta - origin, TWO_PI)
    for series, ta, tb in fitted:
        inside = (shifted >= ta) & (shifted < tb) if tb < origin + TWO_PI - 1e-12 else \
            (shifted >= ta)
        if not inside.any():  # the search for the jump speed reads one angle at a time
            continue
        at = shifted[inside]
        for k in range(4):
            out[k][inside] = series[k](at)
    return tuple(out)


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
