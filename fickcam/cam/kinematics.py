"""Kinematics of the (aged) cam: the follower height and its derivatives over the cam
angle, and the working profile.

Swelling scales the profile (isotropic: every cam dimension by 1 + eps, the roller by
1 + eps_roller) or distorts it (anisotropic: x by 1 + eps_x, y by 1 + eps_y); the
follower motion is in closed form where the aged motion is the design motion scaled by
1 + eps (isotropic cam with a flat follower, or a radial knife/roller that swells like
the cam, as Singh & Sanyal (2017) scale their pitch circle and lift), or where the
eccentric disc keeps its circle (a flat face on any swollen disc; a knife or roller on a
uniformly swollen one), otherwise found geometrically (:mod:`fickcam.cam.geometry`).

The papers are cited in full in :mod:`fickcam.cam`.
"""
from __future__ import annotations

from dataclasses import replace
import functools
import math
from typing import Callable, NamedTuple

import numpy as np

from .design import CamDesign, CamState
from .geometry import (PiecewiseMotion, evaluate_geometric_motion, evaluate_geometric_motions,
                       fit_geometric_motion, fit_geometric_motions, pieces_of, prime_height,
                       rotate, working_outline)
from .motion import ORDERS, follower_motion
from . import arm
from .profile import aged_profile_motion


def _scales_exactly(design: CamDesign, state: CamState) -> bool:
    """True where the aged motion is the design motion times (1 + eps) (closed form)."""
    if design.arm is not None:  # the dry arm follows the design motion exactly
        return design.kind == "motion" and state.cam_strain_x == state.cam_strain_y == \
            state.roller_strain == state.arm_strain == 0.0
    if design.kind != "motion" or state.cam_strain_x != state.cam_strain_y:
        return False
    if state.cam_strain_x == 0.0 and state.roller_strain == 0.0:
        return True
    if design.follower_kind == "flat":
        return True
    return design.offset == 0.0 and (design.follower_kind == "knife" or
                                     state.roller_strain == state.cam_strain_x)


def _scaled_heights(design: CamDesign, state: CamState, theta):
    """The design motion scaled by 1 + eps_x above the aged prime circle (an arm: its angle)."""
    theta = np.asarray(theta, float)
    y, d1, d2, d3 = (np.reshape(v, theta.shape)
                     for v in follower_motion(design.segments, theta.ravel()))
    if design.arm is not None:  # the arm angle from its dry base position
        return y, d1, d2, d3
    scale = 1.0 + state.cam_strain_x
    floor = _scaled_floor(design, state)
    return floor + scale * y, scale * d1, scale * d2, scale * d3


def _scaled_floor(design: CamDesign, state: CamState):
    base = design.base_circle_radius * (1.0 + state.cam_strain_x)
    if design.follower_kind == "flat":
        return base
    return prime_height(base + design.roller_radius * (1 + state.roller_strain), design.offset)


def _scaled_extremes(design: CamDesign, state: CamState) -> tuple[float, float]:
    if design.arm is not None:
        return 0.0, _design_lift(design)
    floor = _scaled_floor(design, state)
    return floor, floor + (1.0 + state.cam_strain_x) * _design_lift(design)


def _flat_support(design: CamDesign, state: CamState):
    """e_y, a, A and B of the flat face's support function on the swollen disc."""
    e_y = design.eccentricity * (1 + state.cam_strain_y)
    a = design.disc_radius * (1 + state.cam_strain_x)
    b = design.disc_radius * (1 + state.cam_strain_y)
    return e_y, a, (a * a + b * b) / 2, (b * b - a * a) / 2


def _eccentric_flat_heights(design: CamDesign, state: CamState, theta):
    """Flat face on the (swollen) eccentric disc, in closed form: the face height is the
    support function of the ellipse with centre (0, -e_y) and semi-axes a = R(1 + eps_x),
    b = R(1 + eps_y) in the direction n = (sin theta, cos theta) (kinematic inversion,
    Norton ch. 8): Y = -e_y cos theta + f, f = sqrt(A + B cos 2 theta),
    A = (a^2 + b^2)/2, B = (b^2 - a^2)/2; a circle (a = b) gives pure SHM
    Y = R - e cos theta (Madhukar et al. 2023 sec. 5.2). The derivatives of f
    follow from differentiating f^2 = g three times."""
    theta = np.asarray(theta, float)
    e_y, _, big_a, big_b = _flat_support(design, state)
    f = np.sqrt(big_a + big_b * np.cos(2 * theta))
    g1, g2, g3 = (-2 * big_b * np.sin(2 * theta), -4 * big_b * np.cos(2 * theta),
                  8 * big_b * np.sin(2 * theta))
    f1 = g1 / (2 * f)
    f2 = (g2 / 2 - f1 ** 2) / f
    f3 = (g3 / 2 - 3 * f1 * f2) / f
    c, s = np.cos(theta), np.sin(theta)
    return -e_y * c + f, e_y * s + f1, e_y * c + f2, -e_y * s + f3


def _eccentric_flat_extremes(design: CamDesign, state: CamState) -> tuple[float, float]:
    """(lowest, highest) of the support function: theta = 0, pi and, for a flattened disc,
    the interior stationary points where e_y f = 2 B cos theta, i.e.
    cos^2 theta = e_y^2 a^2 / (2 B (2 B - e_y^2))."""
    e_y, a, _, big_b = _flat_support(design, state)
    candidates = [0.0, np.pi]
    denominator = 2 * big_b * (2 * big_b - e_y ** 2)
    if denominator > 0:
        c2 = e_y ** 2 * a ** 2 / denominator
        if c2 <= 1:
            c = math.sqrt(c2)
            candidates += [math.acos(c), math.acos(-c), -math.acos(c), -math.acos(-c)]
    values = _eccentric_flat_heights(design, state, np.array(candidates))[0]
    return float(values.min()), float(values.max())


def _pitch_circle(design: CamDesign, state: CamState):
    """e' and rho: the swollen disc centre's distance from the axis and the pitch circle's
    radius."""
    return (design.eccentricity * (1 + state.cam_strain_y),
            design.disc_radius * (1 + state.cam_strain_x) +
            design.roller_radius * (1 + state.roller_strain))


def _eccentric_pitch_heights(design: CamDesign, state: CamState, theta):
    """Knife or roller on the uniformly swollen eccentric disc, in closed form: the pitch
    curve is the circle of radius rho = R (1 + eps) + r_roller about the disc centre
    c = R(theta) (0, -e (1 + eps)) (kinematic inversion, Norton ch. 8), met by the
    follower's line x = offset at Y = -e' cos theta + f, f = sqrt(g),
    g = rho^2 - (offset - e' sin theta)^2 (Y = R + r - e cos theta for a centred
    follower with e << R is the disc's near-SHM). The derivatives of f follow from
    f^2 = g as for the flat face."""
    theta = np.asarray(theta, float)
    e, rho = _pitch_circle(design, state)
    c, s = np.cos(theta), np.sin(theta)
    u, u1, u2, u3 = design.offset - e * s, -e * c, e * s, e * c
    f = np.sqrt(rho * rho - u * u)
    g1, g2, g3 = -2 * u * u1, -2 * (u1 * u1 + u * u2), -2 * (3 * u1 * u2 + u * u3)
    f1 = g1 / (2 * f)
    f2 = (g2 / 2 - f1 ** 2) / f
    f3 = (g3 / 2 - 3 * f1 * f2) / f
    return -e * c + f, e * s + f1, e * c + f2, -e * s + f3


def _eccentric_pitch_extremes(design: CamDesign, state: CamState) -> tuple[float, float]:
    """Y is extreme where the axis, the disc centre and the pitch point are collinear:
    |P| = rho -/+ e', Y = sqrt(|P|^2 - offset^2)."""
    e, rho = _pitch_circle(design, state)
    return tuple(math.sqrt(reach ** 2 - design.offset ** 2) for reach in (rho - e, rho + e))


class ClosedForm(NamedTuple):
    """An aged motion in closed form.

    ``heights(design, state, theta)`` gives (Y, dY, d2Y, d3Y) [m/rad^k] at cam angles theta
    [rad]; it is elementwise in theta and in the state's strains, so a state stacked over
    ageing times (:func:`stacked_state`, strains of shape (n, 1)) gives rows over time.
    ``extremes(design, state)`` gives the (lowest, highest) Y [m] of one state.
    """

    heights: Callable
    extremes: Callable


SCALED = ClosedForm(_scaled_heights, _scaled_extremes)
ECCENTRIC_FLAT = ClosedForm(_eccentric_flat_heights, _eccentric_flat_extremes)
ECCENTRIC_PITCH = ClosedForm(_eccentric_pitch_heights, _eccentric_pitch_extremes)


def closed_form(design: CamDesign, state: CamState) -> ClosedForm | None:
    """The closed form of the aged motion, or None where the aged geometry must be fitted.

    Parameters
    ----------
    design : CamDesign
        The dry design (its kind and follower; lengths [m]).
    state : CamState
        The aged state (strains [-] of the plate along x and y, the roller and the arm).

    Returns
    -------
    ClosedForm or None
        The design motion scaled by 1 + eps (``SCALED``), the flat face on the eccentric
        disc (``ECCENTRIC_FLAT``) or a knife or roller on the uniformly swollen
        eccentric disc (``ECCENTRIC_PITCH``); None for a cam given by points and for
        any other aged geometry.
    """
    if _scales_exactly(design, state):
        return SCALED
    if design.kind != "eccentric":
        return None
    if design.follower_kind == "flat":
        return ECCENTRIC_FLAT
    if design.arm is None and state.cam_strain_x == state.cam_strain_y:
        return ECCENTRIC_PITCH
    return None


def stacked_state(states) -> CamState:
    """The strains of several states as columns (n, 1), for a :class:`ClosedForm`'s
    ``heights`` over ageing times.

    Parameters
    ----------
    states : sequence of CamState
        The states, one per ageing time (strains [-]).

    Returns
    -------
    CamState
        A state whose cam and roller strains [-], the ones the closed forms read, are
        arrays of shape (n, 1); its other fields are those of a default state.
    """
    def column(name):
        return np.array([getattr(state, name) for state in states], float)[:, None]

    return CamState(cam_strain_x=column("cam_strain_x"), cam_strain_y=column("cam_strain_y"),
                    roller_strain=column("roller_strain"))


def follower_heights(design: CamDesign, state: CamState, theta):
    """(Y, dY/dtheta, d2Y/dtheta2, d3Y/dtheta3), (lowest, highest) Y: the follower's pitch point
    (face for a flat follower) above the cam axis at cam angles theta.

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    state : CamState
        The aged state (strains [-]).
    theta : float or array_like
        Cam angles [rad].

    Returns
    -------
    motion : tuple of numpy.ndarray
        Y [m] and dY/dtheta [m/rad], d2Y/dtheta2 [m/rad^2], d3Y/dtheta3 [m/rad^3]; a
        swinging arm's angle [rad] and its derivatives [rad/rad^k] instead.
    extremes : tuple of float
        Lowest and highest Y over the turn [m] ([rad] for an arm).
    """
    motion, extremes = motion_function(design, state)
    return motion(theta), extremes


def picked(values: tuple, orders: tuple) -> tuple:
    """The derivative ``orders`` of a motion's (Y, dY, d2Y, d3Y), in that order.

    Parameters
    ----------
    values : tuple of numpy.ndarray
        Y [m] and its first three derivatives [m/rad^k] (an arm's angle [rad/rad^k]).
    orders : tuple of int
        The orders wanted, each in 0..3.

    Returns
    -------
    tuple of numpy.ndarray
        The values of those orders.
    """
    return tuple(values[k] for k in orders)


def motion_function(design: CamDesign, state: CamState):
    """(theta -> (Y, dY, d2Y, d3Y), (lowest, highest) Y): the closed form where it exists,
    else the aged geometry's spectral fit, made once and evaluated at any angle.

    Parameters
    ----------
    design : CamDesign
        The dry design: its kind, follower and lengths [m].
    state : CamState
        The aged state: plate, roller and arm strains [-].

    Returns
    -------
    motion : callable
        ``motion(theta, orders=ORDERS)``: theta [rad] -> (Y [m], dY/dtheta [m/rad],
        d2Y/dtheta2 [m/rad^2], d3Y/dtheta3 [m/rad^3]), or only the derivative orders
        ``orders`` asked for, in that order (a fitted or profile motion then sums only
        those); a swinging arm's angle [rad] instead of Y.
    extremes : tuple of float
        Lowest and highest Y over the turn [m] ([rad] for an arm).
    """
    form = closed_form(design, state)
    if form is not None:
        return (lambda theta, orders=ORDERS: picked(form.heights(design, state, theta), orders),
                form.extremes(design, state))
    if design.kind == "profile":
        arm = {} if design.arm is None else grown_arm(design, state.arm_strain)
        motion = aged_profile_motion(design.profile, state.cam_strain_x, state.cam_strain_y,
                                     design.roller_radius * (1 + state.roller_strain),
                                     design.offset, design.follower_kind == "flat", **arm)
        return motion, motion.extremes
    fitted, origin, extremes = fit_geometric_motion(
        design, pieces_of(design), state.cam_strain_x, state.cam_strain_y,
        design.roller_radius * (1 + state.roller_strain), nodes=_fit_nodes(design),
        arm_strain=state.arm_strain)
    return _fitted_motion(fitted, origin), extremes


def _fit_nodes(design: CamDesign) -> int:
    """The degree of each piece's spectral fit: the disc's one piece is a whole turn."""
    return 96 if design.kind == "eccentric" else 40


def _fitted_motion(fitted: PiecewiseMotion, origin: float) -> Callable:
    return lambda theta, orders=ORDERS: evaluate_geometric_motion(fitted, origin, theta, orders)


class FittedMotions(NamedTuple):
    """The spectral fits of several ageing times' aged motions, made together
    (:func:`fitted_motions`).

    ``indices`` are the ageing indices fitted, in the order of the stacked fit's rows;
    ``motion(k)`` gives ageing index k's (motion, extremes) as :func:`motion_function`
    does; ``rows(angles, orders)`` evaluates every fitted time at once, angles [rad] of shape
    (n, k) (or (k,), the same for every time) -> the derivative ``orders`` (Y [m], dY/dtheta
    [m/rad], ...), each (n, k). ``grid``: (angles [rad], every time's Y and its derivatives
    there) once :meth:`sampled` has made them; both answer at those angles from it.
    """

    indices: list
    fitted: PiecewiseMotion
    origins: np.ndarray
    extremes: list
    grid: tuple = ()

    def sampled(self, angles) -> FittedMotions:
        """The same fits with every time's motion at ``angles`` [rad] made at once, every
        order (the output angles, which the responses and the jump speeds' grid read):
        the same values as each time's alone, element by element."""
        angles = np.asarray(angles, float)
        return self._replace(grid=(angles, self.rows(angles)))

    def _on_grid(self, angles, orders) -> tuple | None:
        """Every time's ``orders`` at ``angles`` where they are the sampled angles, else None."""
        if not self.grid or np.shape(angles) != self.grid[0].shape \
                or not np.array_equal(angles, self.grid[0]):
            return None
        return tuple(self.grid[1][ORDERS.index(order)] for order in orders)

    def motion(self, k: int) -> tuple[Callable, tuple[float, float]]:
        """Ageing index k's (motion, (lowest, highest) Y [m])."""
        row = self.indices.index(k)
        alone = _fitted_motion(self.fitted.at(row), float(self.origins[row]))

        def motion(theta, orders=ORDERS):
            stored = self._on_grid(theta, orders)
            return alone(theta, orders) if stored is None else tuple(v[row] for v in stored)

        return motion, self.extremes[row]

    def rows(self, angles, orders=ORDERS) -> tuple:
        """Every fitted time's motion at its row of ``angles`` [rad]."""
        stored = self._on_grid(angles, orders)
        if stored is not None:
            return stored
        angles = np.asarray(angles, float)
        angles = np.broadcast_to(angles, (len(self.indices), angles.shape[-1]))
        return evaluate_geometric_motions(self.fitted, self.origins, angles, orders)


def fitted_motions(design: CamDesign, states: dict) -> FittedMotions | None:
    """The spectral fits of the ageing times whose aged motion has neither a closed form
    nor a profile of points, made together (:func:`~fickcam.cam.geometry.fit_geometric_motions`:
    one contact solve and one least-squares fit for all of them, each time equal to its own
    :func:`motion_function` to round-off); a translating follower only.

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    states : dict of int to CamState
        The aged state at each ageing index (strains [-]).

    Returns
    -------
    FittedMotions or None
        The fits, or None where no time needs one (or the follower swings on an arm).
    """
    indices = [k for k, state in states.items()
               if design.kind != "profile" and closed_form(design, state) is None]
    if not indices or design.arm is not None:
        return None
    chosen = [states[k] for k in indices]

    def strains(name):
        return np.array([getattr(state, name) for state in chosen], float)

    fitted, origins, extremes = fit_geometric_motions(
        design, pieces_of(design), strains("cam_strain_x"), strains("cam_strain_y"),
        design.roller_radius * (1 + strains("roller_strain")), nodes=_fit_nodes(design))
    return FittedMotions(indices, fitted, origins, extremes)


def grown_arm(design: CamDesign, strain: float) -> dict:
    """The swinging arm grown by the follower's swelling, and its dry base angle.

    Parameters
    ----------
    design : CamDesign
        The dry design with its arm (lengths [m]).
    strain : float
        The follower's swelling strain along the arm [-].

    Returns
    -------
    dict
        ``arm``: the :class:`~fickcam.cam.arm.Arm` with its length and face offset [m]
        grown by 1 + strain; ``base``: its dry base angle [rad]; the keywords of
        :func:`fickcam.cam.profile.profile_motion`.
    """


    a, rb = design.arm, design.base_circle_radius
    base = (arm.face_base_angle(a, rb) if design.follower_kind == "flat" else
            arm.roller_base_angle(a, rb + design.roller_radius))
    return {"arm": replace(a, length=a.length * (1 + strain), face_offset=a.face_offset * (1 + strain)),
            "base": base}


@functools.lru_cache(maxsize=64)
def dry_lowest_height(design: CamDesign) -> float:
    """Lowest follower height of the dry cam: where the spring has its preload.

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].

    Returns
    -------
    float
        The lowest Y of :func:`follower_heights` for the dry cam [m] ([rad] for an arm).
    """
    return follower_heights(design, CamState(), np.linspace(0, 2 * np.pi, 8, endpoint=False))[1][0]


def working_profile(design: CamDesign, strain_x: float = 0.0, strain_y: float = 0.0,
                    n: int = 720):
    """Closed counter-clockwise outline (x, y) of the working profile (m), cam frame as seen
    from the front, last point != first, for the diffusion mesh
    (:class:`fickcam.diffusion.problem.geometry.CamPlate`).

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    strain_x, strain_y : float
        Swelling strain of the plate along its x and y axes [-].
    n : int
        Number of outline points.

    Returns
    -------
    tuple of numpy.ndarray
        The outline's x and y [m].
    """
    x, y = working_outline(design, strain_x, strain_y, n)
    if design.clockwise:  # mirror back, still counter-clockwise
        return -x[::-1].copy(), y[::-1].copy()
    return x, y


def cam_frame_point(design: CamDesign, theta, x, y):
    """Fixed-frame point (x, y) at cam angle theta in the cam frame, seen from the front:
    R(-theta) (x, y), mirrored back for a clockwise cam.

    Parameters
    ----------
    design : CamDesign
        The design (its turning sense).
    theta : float or array_like
        Cam angle [rad].
    x, y : float or array_like
        The point in the fixed frame [m].

    Returns
    -------
    tuple of numpy.ndarray
        The point's x and y in the cam frame [m].
    """
    px, py = rotate(-theta, x, y)
    return (-px if design.clockwise else px), py


def _design_lift(design: CamDesign) -> float:
    level, top = 0.0, 0.0
    for s in design.segments:
        level += s.height
        top = max(top, level)
    return top
