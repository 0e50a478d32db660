"""Swinging-arm (oscillating) follower geometry: pure functions of arrays.

Frame (as :mod:`fickcam.cam.geometry`): the cam turns counter-clockwise about the
origin by theta; a point p of the cam frame is at R(theta) p in the fixed frame
(kinematic inversion, Norton, Design of Machinery 5th ed., ch. 8; Chen, Mechanics and
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
    """A swinging arm (SI).

    Parameters
    ----------
    pivot_x, pivot_y : float
        The pivot in the fixed frame [m].
    length : float
        Arm length, pivot to roller centre [m].
    face_offset : float
        Distance of a flat face from the pivot [m].
    sense : int
        +1: the arm turns counter-clockwise as the follower rises; -1: clockwise.
    inertia : float
        Moment of inertia about the pivot [kg m^2].
    spring_rate : float
        Torsional return spring [N m/rad].
    spring_preload : float
        Its preload [N m].
    load_torque : float
        A constant load torque against the rise [N m].
    """

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
    """J (x, y) = (-y, x): a quarter turn counter-clockwise.

    Parameters
    ----------
    x, y : array_like
        A vector [any unit].

    Returns
    -------
    tuple of array_like
        (-y, x) [the vector's unit].
    """
    return -y, x


def cross(ax, ay, bx, by):
    """z component of a x b.

    Parameters
    ----------
    ax, ay, bx, by : array_like
        Two vectors a and b [any units].

    Returns
    -------
    array_like
        ax by - ay bx [the product of their units].
    """
    return ax * by - ay * bx


def roller_arm_opening(d, length, radius):
    """delta in (0, pi) with d^2 + l^2 - 2 d l cos(delta) = radius^2 (law of cosines): the
    angle at the pivot between the pivot-to-cam-axis line and the arm; NaN where the arm
    cannot reach ``radius``.

    Parameters
    ----------
    d : float
        Distance from the cam axis to the pivot [m].
    length : float
        Arm length, pivot to roller centre [m].
    radius : array_like
        Distance of the roller centre from the cam axis [m].

    Returns
    -------
    numpy.ndarray
        delta [rad]; NaN where unreachable.
    """
    with np.errstate(invalid="ignore"):
        return np.arccos((d * d + length * length - radius * radius) / (2.0 * d * length))


def roller_base_angle(arm: Arm, prime_radius: float, length: float | None = None) -> float:
    """phi0: the arm angle at which the roller centre lies on the prime circle Rb + Rf, on
    the branch where turning the arm by ``sense`` moves the roller away from the cam
    (d|C|^2/dphi = 2 l d sin(delta) has the sign of sense).

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    prime_radius : float
        Prime-circle radius Rb + Rf [m].
    length : float, optional
        Arm length [m]; None: ``arm.length``.

    Returns
    -------
    float
        phi0 [rad] in the fixed frame.

    References
    ----------
    Norton (2012), ch. 8; in full in :mod:`fickcam.cam`.
    """
    delta = roller_arm_opening(arm.pivot_distance, length or arm.length, prime_radius)
    return float(arm.pivot_angle + np.pi + arm.sense * delta)


def face_opening(d, face_offset, support):
    """delta in [0, pi] with d cos(delta) = support + face_offset: the angle between the
    face normal and the line from the cam axis to the pivot; NaN where no such face
    exists (the face cannot be that far from the cam axis).

    Parameters
    ----------
    d : float
        Distance from the cam axis to the pivot [m].
    face_offset : float
        Distance of the face from the pivot [m].
    support : array_like
        Distance of the face from the cam axis [m].

    Returns
    -------
    numpy.ndarray
        delta [rad]; NaN where no such face exists.
    """
    with np.errstate(invalid="ignore"):
        return np.arccos((support + face_offset) / d)


def face_base_angle(arm: Arm, base_radius: float, face_offset: float | None = None) -> float:
    """gamma0: the face-normal angle at which the face touches the base circle (p = Rb), on
    the branch where turning by ``sense`` pushes the face out (dp/dgamma = d sin(delta)).

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    base_radius : float
        Base-circle radius Rb [m].
    face_offset : float, optional
        Distance of the face from the pivot [m]; None: ``arm.face_offset``.

    Returns
    -------
    float
        gamma0 [rad] in the fixed frame.
    """
    offset = arm.face_offset if face_offset is None else face_offset
    delta = face_opening(arm.pivot_distance, offset, base_radius)
    return float(arm.pivot_angle - arm.sense * delta)


def roller_centre(arm: Arm, phi0: float, psi, d1, d2):
    """C, dC/dtheta, d2C/dtheta2 (tuples of x, y arrays) of the roller centre for the
    angular motion psi(theta) and its first two derivatives per radian of cam angle.

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    phi0 : float
        The arm angle on the base circle [rad] (:func:`roller_base_angle`).
    psi, d1, d2 : array_like
        The arm's angular motion psi(theta) [rad] and its first two derivatives per
        radian of cam angle [rad/rad, rad/rad^2].

    Returns
    -------
    tuple
        C [m], dC/dtheta [m/rad] and d2C/dtheta2 [m/rad^2], each an (x, y) pair of
        arrays in the fixed frame.
    """
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
    (d/dtheta R(-theta) = -R(-theta) J; Norton ch. 8 kinematic inversion).

    Parameters
    ----------
    centre, velocity, acceleration : tuple of array_like
        C [m], dC/dtheta [m/rad] and d2C/dtheta2 [m/rad^2] of the roller centre, (x, y)
        in the fixed frame (:func:`roller_centre`).

    Returns
    -------
    tuple
        (a [m/rad], b [m/rad^2]), each an (x, y) pair.
    """
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
    kappa = (x'y'' - y'x'')/(x'^2 + y'^2)^1.5; the rotation R(-theta) keeps the cross product).

    Parameters
    ----------
    a, b : tuple of array_like
        First and second theta-derivatives of the pitch curve [m/rad, m/rad^2]
        (:func:`pitch_derivatives`).

    Returns
    -------
    numpy.ndarray
        rho [m], positive where convex.
    """
    (ax, ay), (bx, by) = a, b
    return -np.hypot(ax, ay) ** 3 / cross(ax, ay, bx, by)


def pitch_normal(a):
    """Unit common normal N = J a/|a| in the fixed frame: the outward normal of the pitch
    curve at the roller centre, along which the cam pushes the roller.

    Parameters
    ----------
    a : tuple of array_like
        The pitch curve's first theta-derivative [m/rad], (x, y).

    Returns
    -------
    tuple of numpy.ndarray
        (Nx, Ny) [-], unit.
    """
    ax, ay = a
    norm = np.hypot(ax, ay)
    nx, ny = perp(ax, ay)
    return nx / norm, ny / norm


def face_support(arm: Arm, gamma0: float, psi, d1, d2):
    """Flat face at cam angle theta: (gamma_f, p, dp/dtheta, d2p/dtheta2): face-normal angle in
    the fixed frame and the face's distance from the cam axis, p = A.m(gamma_f) - f.

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    gamma0 : float
        The face-normal angle on the base circle [rad] (:func:`face_base_angle`).
    psi, d1, d2 : array_like
        The angular motion [rad] and its derivatives, as :func:`roller_centre` takes them.

    Returns
    -------
    tuple
        (gamma_f [rad], p [m], dp/dtheta [m/rad], d2p/dtheta2 [m/rad^2]).
    """
    gamma, g1, g2 = gamma0 + arm.sense * psi, arm.sense * d1, arm.sense * d2
    along = arm.pivot_x * np.cos(gamma) + arm.pivot_y * np.sin(gamma)      # A.m
    across = -arm.pivot_x * np.sin(gamma) + arm.pivot_y * np.cos(gamma)    # A.m', m' = J m
    return gamma, along - arm.face_offset, across * g1, across * g2 - along * g1 ** 2


def face_envelope(p, p1, p2, g1, g2):
    """(dp/dgamma, rho) of the cam outline as the envelope of the face lines n(gamma).X = p
    in the cam frame, gamma = gamma_f - theta: the contact point is X = p n + p_gamma n'
    and the radius of curvature rho = p + p_gamma,gamma (support function of a convex
    curve; reduces to Norton ch. 8, rho = Rb + y + y'', for a translating face).
    ``g1``, ``g2`` are dgamma_f/dtheta and d2gamma_f/dtheta2.

    Parameters
    ----------
    p, p1, p2 : array_like
        The face's distance from the cam axis [m] and its first two theta-derivatives
        [m/rad, m/rad^2].
    g1, g2 : array_like
        dgamma_f/dtheta [rad/rad] and d2gamma_f/dtheta2 [rad/rad^2].

    Returns
    -------
    tuple of numpy.ndarray
        (dp/dgamma [m/rad], rho [m]).
    """
    gt, gtt = g1 - 1.0, g2
    pg = p1 / gt
    pgg = (p2 * gt - p1 * gtt) / gt ** 3
    return pg, p + pgg


def pressure_angle(ux, uy, nx, ny):
    """Signed angle from the direction of motion u of the follower point at the contact
    (the rise direction) to the common normal N: cos(alpha) = u.N, as dynamics.pressure_angle
    for a translating follower (u = +y).

    Parameters
    ----------
    ux, uy : array_like
        Unit direction of motion of the follower point [-].
    nx, ny : array_like
        Unit common normal [-].

    Returns
    -------
    numpy.ndarray
        The pressure angle [rad], signed.
    """
    return np.arctan2(cross(ux, uy, nx, ny), ux * nx + uy * ny)


def rotate(angle, x, y):
    """Points turned counter-clockwise about the origin.

    Parameters
    ----------
    angle : array_like
        Rotation, counter-clockwise [rad].
    x, y : array_like
        Points [m].

    Returns
    -------
    tuple of array_like
        The rotated (x, y) [m].
    """
    c, s = np.cos(angle), np.sin(angle)
    return c * x - s * y, s * x + c * y


@dataclass(frozen=True)
class Contact:
    """The arm and cam at cam angles theta (fixed frame): contact point X, common normal N
    (the cam pushes the follower with Fn N), arm lever (arm torque about the pivot per unit
    contact force, in the rise sense), pressure angle, pitch radius of curvature (the
    working profile's for a flat face) and working radius of curvature.

    Parameters
    ----------
    x, y : numpy.ndarray
        Contact point X [m].
    nx, ny : numpy.ndarray
        Unit common normal N [-].
    lever : numpy.ndarray
        Arm torque about the pivot per unit contact force [m], in the rise sense.
    pressure_angle : numpy.ndarray
        Pressure angle [rad].
    pitch_radius : numpy.ndarray
        Radius of curvature of the pitch curve [m] (a flat face: of the working profile).
    radius : numpy.ndarray
        Radius of curvature of the working profile [m].
    """

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
    line of action passes through the roller centre); working radius rho_pitch - Rf.

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    phi0 : float
        The arm angle on the base circle [rad].
    roller : float
        Roller radius Rf [m].
    psi, d1, d2 : array_like
        The angular motion [rad] and its derivatives, as :func:`roller_centre` takes them.

    Returns
    -------
    Contact
        At each cam angle.
    """
    centre, velocity, acceleration = roller_centre(arm, phi0, psi, d1, d2)
    a, b = pitch_derivatives(centre, velocity, acceleration)
    nx, ny = pitch_normal(a)
    ux, uy, r = _rise_direction(arm, *centre)
    rho = pitch_radius_of_curvature(a, b)
    return Contact(centre[0] - roller * nx, centre[1] - roller * ny, nx, ny,
                   r * (ux * nx + uy * ny), pressure_angle(ux, uy, nx, ny), rho, rho - roller)


def face_contact(arm: Arm, gamma0: float, psi, d1, d2) -> Contact:
    """Contact of a flat-face arm: X = p m + p_gamma m' (fixed frame), N = m; lever =
    sense (X - A) x m.

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    gamma0 : float
        The face-normal angle on the base circle [rad].
    psi, d1, d2 : array_like
        The angular motion [rad] and its derivatives, as :func:`roller_centre` takes them.

    Returns
    -------
    Contact
        At each cam angle; its pitch radius is the working profile's own.
    """
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
    flat: the envelope point).

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    kind : {"roller", "flat"}
        The follower's face.
    base_radius : float
        Base-circle radius Rb [m].
    roller : float
        Roller radius Rf [m] (ignored for a flat face).
    theta : array_like
        Cam angles [rad].
    motion : sequence of array_like
        psi [rad], psi' [rad/rad], psi'' [rad/rad^2], ... at ``theta``.

    Returns
    -------
    tuple of numpy.ndarray
        (W0x, W0y [m], T0x, T0y [-]) in the cam frame.
    """
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
    :func:`roller_base_angle`), and theta turns Q onto it; psi = sense (phi - phi0_dry).

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    phi0_dry : float
        The dry arm's base angle [rad].
    length : float
        The aged arm length [m].
    wx, wy : array_like
        Aged working-profile points W in the cam frame [m].
    nx, ny : array_like
        Their outward unit normals n [-].
    roller : float
        The aged roller radius Rf [m].

    Returns
    -------
    tuple of numpy.ndarray
        (theta [rad], psi [rad]).
    """
    qx, qy = wx + roller * nx, wy + roller * ny
    delta = roller_arm_opening(arm.pivot_distance, length, np.hypot(qx, qy))
    phi = arm.pivot_angle + np.pi + arm.sense * delta
    cx, cy = arm.pivot_x + length * np.cos(phi), arm.pivot_y + length * np.sin(phi)
    return np.arctan2(cy, cx) - np.arctan2(qy, qx), arm.sense * (phi - phi0_dry)


def aged_face_contact(arm: Arm, gamma0_dry: float, face_offset: float, wx, wy, nx, ny):
    """(theta, psi) at which the aged profile point W (outward normal n, cam frame) touches
    the face: the face normal m = R(theta) n at distance W.n from the cam axis, d cos(delta) =
    W.n + f (same branch as :func:`face_base_angle`); psi = sense (gamma_f - gamma0_dry).

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI), grown.
    gamma0_dry, face_offset : float
        The dry face's base angle [rad] and the aged face's offset from the pivot [m].
    wx, wy, nx, ny : array_like
        Aged profile points W [m] and their outward unit normals n [-], cam frame.

    Returns
    -------
    theta, psi : numpy.ndarray
        The cam angle at which each point touches, and the arm's angle then [rad].
    """
    delta = face_opening(arm.pivot_distance, face_offset, wx * nx + wy * ny)
    gamma = arm.pivot_angle - arm.sense * delta
    return gamma - np.arctan2(ny, nx), arm.sense * (gamma - gamma0_dry)


def arm_slope(arm: Arm, px, py, nx, ny):
    """dpsi/dtheta from the contact alone: along the common normal N the cam point at P
    (velocity J P per unit cam speed, counter-clockwise) and the arm point at P (velocity
    sense psi' J (P - A)) move alike, so psi' = (J P . N) / (sense J (P - A) . N), P the
    roller centre or the face contact (the normal-velocity condition of higher pairs;
    Norton ch. 8, Chen 1982 ch. 4).

    Parameters
    ----------
    arm : Arm
        The swinging arm (SI).
    px, py : array_like
        The roller centre or the face contact in the fixed frame [m].
    nx, ny : array_like
        The unit common normal there [-].

    Returns
    -------
    numpy.ndarray
        dpsi/dtheta [rad/rad].

    References
    ----------
    Norton (2012), ch. 8; in full in :mod:`fickcam.cam`.
    Chen (1982), ch. 4; in full in :mod:`fickcam.cam`.
    """
    jx, jy = perp(px, py)
    ax, ay = perp(px - arm.pivot_x, py - arm.pivot_y)
    return (jx * nx + jy * ny) / (arm.sense * (ax * nx + ay * ny))


def aged_profile_contact(arm: Arm, kind: str, base: float, roller: float, wx, wy, nx, ny):
    """(theta, psi, dpsi/dtheta) at which the aged profile point W (outward normal n, cam
    frame) touches the arm (``arm`` already grown; ``base`` the dry base angle).

    Parameters
    ----------
    arm, kind
        As in :func:`dry_profile`, the arm grown.
    base : float
        The dry base angle [rad] (phi0 or gamma0).
    roller : float
        The aged roller radius [m].
    wx, wy, nx, ny : array_like
        Aged profile points W [m] and their outward unit normals n [-], cam frame.

    Returns
    -------
    tuple of numpy.ndarray
        (theta [rad], psi [rad], dpsi/dtheta [rad/rad]).
    """
    if kind == "flat":
        theta, psi = aged_face_contact(arm, base, arm.face_offset, wx, wy, nx, ny)
        px, py = rotate(theta, wx, wy)
    else:
        theta, psi = aged_roller_contact(arm, base, arm.length, wx, wy, nx, ny, roller)
        px, py = rotate(theta, wx + roller * nx, wy + roller * ny)
    fx, fy = rotate(theta, nx, ny)
    return theta, psi, arm_slope(arm, px, py, fx, fy)
