"""Swinging-arm (oscillating) follower geometry: pure functions of arrays.

Frame (as :mod:`fickcam.cam.geometry`): the cam turns counter-clockwise about the
origin by theta; a point p of the cam frame is at R(theta) p in the fixed frame
(kinematic inversion, Norton, Design of Machinery 5th ed., sec. 8.6; Chen, Mechanics and
Design of Cam Mechanisms 1982, ch. 4; Rothbart, Cam Design Handbook 2004, ch. 3). The
arm turns about the fixed pivot A = d (cos alpha, sin alpha) by its angular motion
psi(theta) (the motion laws, in rad), in the sense ``sense`` (+1 counter-clockwise, -1
clockwise) as the follower rises.

Roller: the roller centre C = A + l e(phi), e(phi) = (cos phi, sin phi), arm angle
phi = phi0 + sense psi; phi0 puts C on the prime circle Rp = Rb + Rf (law of cosines in
the triangle O A C: |C|^2 = d^2 + l^2 - 2 d l cos(delta), phi = alpha + pi + sense delta).
Flat face: the face is the line at distance ``face_offset`` f from the pivot (pivot on
the follower's side) with unit normal m(gamma) = (cos gamma, sin gamma) pointing from
the cam into the follower, gamma = gamma0 + sense psi; its distance from the cam axis is
p = A.m - f (the support function of the cam, Rb at the base circle).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Arm:
    """A swinging arm (SI): pivot (x, y) in the fixed frame, arm length pivot to roller
    centre, face offset (flat face), sense (+1: the arm turns counter-clockwise as the
    follower rises), moment of inertia about the pivot, torsional return spring (N m/rad)
    and its preload and a constant load torque (N m) against the rise."""

    pivot_x: float
    pivot_y: float
    length: float = 0.0
    face_offset: float = 0.0
    sense: int = 1
    inertia: float = 0.0
    spring_rate: float = 0.0
    spring_preload: float = 0.0
    load_torque: float = 0.0

    @property
    def pivot_distance(self) -> float:
        return float(np.hypot(self.pivot_x, self.pivot_y))

    @property
    def pivot_angle(self) -> float:
        return float(np.arctan2(self.pivot_y, self.pivot_x))


def perp(x, y):
    """J (x, y) = (-y, x): a quarter turn counter-clockwise."""
    return -y, x


def cross(ax, ay, bx, by):
    """z component of a x b."""
    return ax * by - ay * bx


def roller_arm_opening(d, length, radius):
    """delta in (0, pi) with d^2 + l^2 - 2 d l cos(delta) = radius^2 (law of cosines): the
    angle at the pivot between the pivot-to-cam-axis line and the arm; NaN where the arm
    cannot reach ``radius``."""
    with np.errstate(invalid="ignore"):
        return np.arccos((d * d + length * length - radius * radius) / (2.0 * d * length))


def roller_base_angle(arm: Arm, prime_radius: float, length: float | None = None) -> float:
    """phi0: the arm angle at which the roller centre lies on the prime circle Rb + Rf, on
    the branch where turning the arm by ``sense`` moves the roller away from the cam
    (d|C|^2/dphi = 2 l d sin(delta) has the sign of sense)."""
    delta = roller_arm_opening(arm.pivot_distance, length or arm.length, prime_radius)
    return float(arm.pivot_angle + np.pi + arm.sense * delta)


def face_opening(d, face_offset, support):
    """delta in [0, pi] with d cos(delta) = support + face_offset: the angle between the
    face normal and the line from the cam axis to the pivot; NaN where no such face
    exists (the face cannot be that far from the cam axis)."""
    with np.errstate(invalid="ignore"):
        return np.arccos((support + face_offset) / d)


def face_base_angle(arm: Arm, base_radius: float, face_offset: float | None = None) -> float:
    """gamma0: the face-normal angle at which the face touches the base circle (p = Rb), on
    the branch where turning by ``sense`` pushes the face out (dp/dgamma = d sin(delta))."""
    offset = arm.face_offset if face_offset is None else face_offset
    delta = face_opening(arm.pivot_distance, offset, base_radius)
    return float(arm.pivot_angle - arm.sense * delta)


def roller_centre(arm: Arm, phi0: float, psi, d1, d2):
    """C, dC/dtheta, d2C/dtheta2 (tuples of x, y arrays) of the roller centre for the
    angular motion psi(theta) and its first two derivatives per radian of cam angle."""
    phi, phi1, phi2 = phi0 + arm.sense * psi, arm.sense * d1, arm.sense * d2
    ex, ey = np.cos(phi), np.sin(phi)
    tx, ty = perp(ex, ey)
    centre = (arm.pivot_x + arm.length * ex, arm.pivot_y + arm.length * ey)
    velocity = (arm.length * phi1 * tx, arm.length * phi1 * ty)
    acceleration = (arm.length * (phi2 * tx - phi1 ** 2 * ex),
                    arm.length * (phi2 * ty - phi1 ** 2 * ey))
    return centre, velocity, acceleration


def pitch_derivatives(centre, velocity, acceleration):
    """(a, b): R(theta) times the first and second theta-derivatives of the pitch curve
    P = R(-theta) C in the cam frame, a = C' - J C, b = a' - J a with a' = C'' - J C'
    (d/dtheta R(-theta) = -R(-theta) J; Norton sec. 8.6 kinematic inversion)."""
    (cx, cy), (vx, vy), (ax2, ay2) = centre, velocity, acceleration
    jx, jy = perp(cx, cy)
    ax, ay = vx - jx, vy - jy
    jvx, jvy = perp(vx, vy)
    dax, day = ax2 - jvx, ay2 - jvy
    jax, jay = perp(ax, ay)
    return (ax, ay), (dax - jax, day - jay)


def pitch_radius_of_curvature(a, b):
    """rho = -|P'|^3 / (P' x P''), positive where the pitch curve (traced clockwise as the
    cam turns counter-clockwise) is convex (curvature of a plane parametric curve,
    kappa = (x'y'' - y'x'')/(x'^2 + y'^2)^1.5; the rotation R(-theta) keeps the cross product)."""
    (ax, ay), (bx, by) = a, b
    return -np.hypot(ax, ay) ** 3 / cross(ax, ay, bx, by)


def pitch_normal(a):
    """Unit common normal N = J a/|a| in the fixed frame: the outward normal of the pitch
    curve at the roller centre, along which the cam pushes the roller."""
    ax, ay = a
    norm = np.hypot(ax, ay)
    nx, ny = perp(ax, ay)
    return nx / norm, ny / norm


def face_support(arm: Arm, gamma0: float, psi, d1, d2):
    """Flat face at cam angle theta: (gamma_f, p, dp/dtheta, d2p/dtheta2): face-normal angle in
    the fixed frame and the face's distance from the cam axis, p = A.m(gamma_f) - f."""
    gamma, g1, g2 = gamma0 + arm.sense * psi, arm.sense * d1, arm.sense * d2
    along = arm.pivot_x * np.cos(gamma) + arm.pivot_y * np.sin(gamma)      # A.m
    across = -arm.pivot_x * np.sin(gamma) + arm.pivot_y * np.cos(gamma)    # A.m', m' = J m
    return gamma, along - arm.face_offset, across * g1, across * g2 - along * g1 ** 2


def face_envelope(p, p1, p2, g1, g2):
    """(dp/dgamma, rho) of the cam outline as the envelope of the face lines n(gamma).X = p
    in the cam frame, gamma = gamma_f - theta: the contact point is X = p n + p_gamma n'
    and the radius of curvature rho = p + p_gamma,gamma (support function of a convex
    curve; reduces to Norton eq. 8.36, rho = Rb + y + y'', for a translating face).
    ``g1``, ``g2`` are dgamma_f/dtheta and d2gamma_f/dtheta2."""
    gt, gtt = g1 - 1.0, g2
    pg = p1 / gt
    pgg = (p2 * gt - p1 * gtt) / gt ** 3
    return pg, p + pgg


def pressure_angle(ux, uy, nx, ny):
    """Signed angle from the direction of motion u of the follower point at the contact
    (the rise direction) to the common normal N: cos(alpha) = u.N, as dynamics.pressure_angle
    for a translating follower (u = +y)."""
    return np.arctan2(cross(ux, uy, nx, ny), ux * nx + uy * ny)


def rotate(angle, x, y):
    c, s = np.cos(angle), np.sin(angle)
    return c * x - s * y, s * x + c * y


@dataclass(frozen=True)
class Contact:
    """The arm and cam at cam angles theta (fixed frame): contact point X, common normal N
    (the cam pushes the follower with Fn N), arm lever (arm torque about the pivot per unit
    contact force, in the rise sense), pressure angle, pitch radius of curvature (the
    working profile's for a flat face) and working radius of curvature."""

    x: np.ndarray
    y: np.ndarray
    nx: np.ndarray
    ny: np.ndarray
    lever: np.ndarray
    pressure_angle: np.ndarray
    pitch_radius: np.ndarray
    radius: np.ndarray


def _rise_direction(arm: Arm, x, y):
    """Unit direction in which the arm point at (x, y) moves as the follower rises:
    sense J (X - A)/|X - A|, and |X - A|."""
    rx, ry = x - arm.pivot_x, y - arm.pivot_y
    r = np.hypot(rx, ry)
    ux, uy = perp(rx, ry)
    return arm.sense * ux / r, arm.sense * uy / r, r


def roller_contact(arm: Arm, phi0: float, roller: float, psi, d1, d2) -> Contact:
    """Contact of a roller arm: X = C - Rf N; lever = l cos(alpha) (the contact force's
    line of action passes through the roller centre); working radius rho_pitch - Rf."""
    centre, velocity, acceleration = roller_centre(arm, phi0, psi, d1, d2)
    a, b = pitch_derivatives(centre, velocity, acceleration)
    nx, ny = pitch_normal(a)
    ux, uy, r = _rise_direction(arm, *centre)
    rho = pitch_radius_of_curvature(a, b)
    return Contact(centre[0] - roller * nx, centre[1] - roller * ny, nx, ny,
                   r * (ux * nx + uy * ny), pressure_angle(ux, uy, nx, ny), rho, rho - roller)


def face_contact(arm: Arm, gamma0: float, psi, d1, d2) -> Contact:
    """Contact of a flat-face arm: X = p m + p_gamma m' (fixed frame), N = m; lever =
    sense (X - A) x m."""
    gamma, p, p1, p2 = face_support(arm, gamma0, psi, d1, d2)
    pg, rho = face_envelope(p, p1, p2, arm.sense * d1, arm.sense * d2)
    mx, my = np.cos(gamma), np.sin(gamma)
    tx, ty = perp(mx, my)
    x, y = p * mx + pg * tx, p * my + pg * ty
    ux, uy, r = _rise_direction(arm, x, y)
    return Contact(x, y, mx, my, r * (ux * mx + uy * my), pressure_angle(ux, uy, mx, my), rho, rho)


def dry_profile(arm: Arm, kind: str, base_radius: float, roller: float, theta, motion):
    """Dry working profile point W0 and unit tangent T0 (cam frame, traced clockwise) at cam
    angles theta for the angular motion ``motion`` = (psi, psi', psi'', ...): the contact
    point rotated back, W0 = R(-theta) X (roller: pitch point minus Rf along the normal;
    flat: the envelope point)."""
    psi, d1, d2 = motion[:3]
    if kind == "flat":
        contact = face_contact(arm, face_base_angle(arm, base_radius), psi, d1, d2)
    else:
        contact = roller_contact(arm, roller_base_angle(arm, base_radius + roller), roller,
                                 psi, d1, d2)
    wx, wy = rotate(-theta, contact.x, contact.y)
    tx, ty = rotate(-theta, contact.ny, -contact.nx)  # -J N: clockwise along the outline
    return wx, wy, tx, ty


def aged_roller_contact(arm: Arm, phi0_dry: float, length: float, wx, wy, nx, ny, roller):
    """(theta, psi) at which the aged profile point W (outward normal n, cam frame) touches
    a roller of radius ``roller`` on an arm of ``length``: the roller centre Q = W + Rf n
    must lie on the arm's circle, |A + l e(phi)| = |Q| (law of cosines, same branch as
    :func:`roller_base_angle`), and theta turns Q onto it; psi = sense (phi - phi0_dry)."""
    qx, qy = wx + roller * nx, wy + roller * ny
    delta = roller_arm_opening(arm.pivot_distance, length, np.hypot(qx, qy))
    phi = arm.pivot_angle + np.pi + arm.sense * delta
    cx, cy = arm.pivot_x + length * np.cos(phi), arm.pivot_y + length * np.sin(phi)
    return np.arctan2(cy, cx) - np.arctan2(qy, qx), arm.sense * (phi - phi0_dry)


def aged_face_contact(arm: Arm, gamma0_dry: float, face_offset: float, wx, wy, nx, ny):
    """(theta, psi) at which the aged profile point W (outward normal n, cam frame) touches
    the face: the face normal m = R(theta) n at distance W.n from the cam axis, d cos(delta) =
    W.n + f (same branch as :func:`face_base_angle`); psi = sense (gamma_f - gamma0_dry)."""
    delta = face_opening(arm.pivot_distance, face_offset, wx * nx + wy * ny)
    gamma = arm.pivot_angle - arm.sense * delta
    return gamma - np.arctan2(ny, nx), arm.sense * (gamma - gamma0_dry)


def arm_slope(arm: Arm, px, py, nx, ny):
    """dpsi/dtheta from the contact alone: along the common normal N the cam point at P
    (velocity J P per unit cam speed, counter-clockwise) and the arm point at P (velocity
    sense psi' J (P - A)) move alike, so psi' = (J P . N) / (sense J (P - A) . N), P the
    roller centre or the face contact (the normal-velocity condition of higher pairs;
    Norton sec. 8.6, Chen 1982 ch. 4)."""
    jx, jy = perp(px, py)
    ax, ay = perp(px - arm.pivot_x, py - arm.pivot_y)
    return (jx * nx + jy * ny) / (arm.sense * (ax * nx + ay * ny))


def aged_profile_contact(arm: Arm, kind: str, base: float, roller: float, wx, wy, nx, ny):
    """(theta, psi, dpsi/dtheta) at which the aged profile point W (outward normal n, cam
    frame) touches the arm (``arm`` already grown; ``base`` the dry base angle)."""
    if kind == "flat":
        theta, psi = aged_face_contact(arm, base, arm.face_offset, wx, wy, nx, ny)
        px, py = rotate(theta, wx, wy)
    else:
        theta, psi = aged_roller_contact(arm, base, arm.length, wx, wy, nx, ny, roller)
        px, py = rotate(theta, wx + roller * nx, wy + roller * ny)
    fx, fy = rotate(theta, nx, ny)
    return theta, psi, arm_slope(arm, px, py, fx, fy)
