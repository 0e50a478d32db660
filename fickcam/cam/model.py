"""The cam and follower at one ageing time: :func:`~fickcam.cam.model.cam_response`.

The design motion defines the dry profile; swelling scales it (isotropic: every
cam dimension by 1 + eps, the roller by 1 + eps_roller) or distorts it (anisotropic:
x by 1 + eps_x, y by 1 + eps_y), and the follower motion is recomputed from the aged
geometry: in closed form where the aged motion is the design motion scaled by
1 + eps (isotropic cam with a flat follower, or a radial knife/roller that swells like
the cam, as Singh & Sanyal (2017) scale their pitch circle and lift), otherwise
geometrically (:mod:`fickcam.cam.geometry`). The follower's frame (offset, spring seat)
does not swell, so a swollen base circle also compresses the spring.

The jump speed is searched between the angle grid's points (:func:`continuous_jump_speed`);
where the aged motion is in closed form, for all ageing times at once
and where it is a spectral fit of the aged geometry, for all ageing times at once
(:func:`jump_speeds_over_ageing`, whose speeds :func:`cam_response` is then given, with the
fits made together, :func:`~fickcam.cam.kinematics.fitted_motions`).
"""
from __future__ import annotations

import logging
import math

import numpy as np

from ..messages import note
from ..mechanisms.response import Response
from . import dynamics as dyn
from .design import CamDesign, CamState
from .kinematics import (cam_frame_point, closed_form, dry_lowest_height, motion_function, picked,
                         stacked_state)
from .motion import ORDERS, joint_notices

log = logging.getLogger(__name__)

#: Norton (Design of Machinery, ch. 8) keeps the pressure angle of a translating
#: follower below 30 deg and the pitch radius of curvature above 2-3 roller radii
PRESSURE_ANGLE_LIMIT = math.radians(30.0)
CURVATURE_RATIO_LIMIT = 2.0


def _contact_point(design, height, dy, phi, roller):
    """Contact point in the fixed frame (roller: pitch point minus R along the normal)."""
    if design.follower_kind == "flat":
        return dy, height
    return design.offset + roller * np.sin(phi), height - roller * np.cos(phi)


def _slide_ratio(design, height, rho):
    """Sliding speed over the speed at which the contact travels along the cam:
    0 for a rolling roller, 1 for a knife edge, (Rb + y)/rho for a flat face."""
    if design.follower_kind == "roller":
        return np.zeros_like(height)
    if design.follower_kind == "knife":
        return np.ones_like(height)
    return height / np.abs(rho)


def cam_response(design: CamDesign, state: CamState, cam_angle,
                 jump_speed: float | None = None, motion=None) -> Response:
    """Kinematics, dynamics and contact of the (aged) cam at cam angles (rad).

    Scalars: base_circle_radius, lift (m), jump_speed (rad/s; the schema stores rpm),
    wear_rate (m/s, deepest Archard wear per unit time). Arrays over cam_angle:
    follower_displacement (m, from the aged lowest position), follower_position (m, the
    pitch point or flat face above the cam axis), follower_velocity,
    follower_acceleration, follower_jerk (time derivatives at design.speed),
    pressure_angle (rad), radius_of_curvature (m, working profile; pitch curve minus roller),
    pitch_radius_of_curvature (m), contact_force (N, common normal), cam_torque (N m),
    friction_force (N, sliding friction at the contact), guide_friction_force (N),
    friction_torque (N m), contact_stress (Pa, Hertz p0), subsurface_shear_stress (Pa) and
    subsurface_shear_depth (m) under it, profile_x/profile_y (m, working
    profile point in contact, cam frame), wear_per_revolution (m).

    Parameters
    ----------
    design : CamDesign
        The dry design (SI: lengths [m], speed [rad/s], masses [kg], forces [N]).
    state : CamState
        The aged state: strains [-], moduli [Pa], follower mass [kg].
    cam_angle : array_like
        Cam angles [rad].
    jump_speed : float, optional
        The jump speed [rad/s] where it was already searched for this state together with
        other ageing times (:func:`jump_speeds_over_ageing`); by default it is searched here
        (:func:`continuous_jump_speed`).
    motion : tuple, optional
        The aged motion and its (lowest, highest) Y [m] as
        :func:`~fickcam.cam.kinematics.motion_function` gives them, where it was already
        fitted for this state together with other ageing times
        (:meth:`~fickcam.cam.kinematics.FittedMotions.motion`); by default made here.

    Returns
    -------
    Response
        The variables above, in SI, and the notices (one sentence each).

    References
    ----------
    Norton (2012), ch. 8; Chen (1982); in full in :mod:`fickcam.cam`.
    """
    theta = np.asarray(cam_angle, float)
    omega = design.speed
    mass = _follower_mass(design, state)
    roller = design.roller_radius * (1 + state.roller_strain)
    motion, (lowest, highest) = motion_function(design, state) if motion is None else motion
    height, d1, d2, d3 = motion(theta)
    notices: list[str] = joint_notices(design.segments) if design.kind == "motion" else []
    phi, rho_pitch, rho = _angle_and_curvature(design, height, d1, d2, roller)
    notices += geometry_notices(design, theta, phi, rho_pitch, rho, roller)

    velocity, acceleration = d1 * omega, d2 * omega ** 2
    holding = _holding_force(design, mass, height)
    axial = holding + mass * acceleration
    jump = continuous_jump_speed(design, motion, mass, theta, d2, holding) \
        if jump_speed is None else jump_speed
    notices += jump_notices(theta, axial, jump, omega)
    if design.follower_kind == "knife":
        notices.append(note("knife-edge follower: Hertz line-contact stress is not defined"))
    variables = {
        "base_circle_radius": aged_base_circle(design, state),
        "lift": highest - lowest,
        "jump_speed": jump,
        "follower_displacement": height - lowest,
        "follower_position": height,
        "follower_velocity": velocity,
        "follower_acceleration": acceleration,
        "follower_jerk": d3 * omega ** 3,
        "pressure_angle": phi,
        "radius_of_curvature": rho,
        "pitch_radius_of_curvature": rho_pitch,
    }
    variables.update(_contact(design, state, theta, (height, d1), phi, rho, roller,
                              (axial, velocity)))
    return Response(variables, notices)


def _angle_and_curvature(design: CamDesign, height, d1, d2, roller):
    """(pressure angle [rad], pitch curve's and working profile's radii of curvature [m])
    of the aged motion (a flat face: no pressure angle, one radius)."""
    if design.follower_kind == "flat":
        rho = dyn.flat_radius_of_curvature(height, d2)
        return np.zeros_like(height), rho, rho
    phi = dyn.pressure_angle(height, d1, design.offset)
    rho_pitch = dyn.pitch_radius_of_curvature(height, d1, d2, design.offset)
    return phi, rho_pitch, rho_pitch - roller


def _contact(design: CamDesign, state: CamState, theta, motion, phi, rho, roller,
             load) -> dict:
    """The contact's variables of :func:`cam_response`: forces, torques, Hertz stress,
    the contact point in the cam's frame and wear; ``motion``: the follower's (height [m],
    dY/dtheta [m/rad]), ``load``: (axial force on the follower [N], its velocity [m/s])."""
    (height, d1), (axial, velocity) = motion, load
    force = dyn.normal_force(axial, phi, velocity, design.guide_factor)
    cx, cy = _contact_point(design, height, d1, phi, roller)
    torque = dyn.contact_torque(cx, cy, force, phi)
    sliding = design.follower_kind != "roller"
    friction = design.friction_coefficient * np.maximum(force, 0.0) * sliding
    lever = np.abs(cx * np.sin(phi) - cy * np.cos(phi))
    stress, shear, shear_depth = hertz_contact(design, state, force, rho, roller)
    wear = (dyn.archard_wear_per_revolution(design.archard_coefficient, design.hardness, force,
                                            design.contact_length, _slide_ratio(design, height, rho))
            if design.hardness else np.zeros_like(theta))
    px, py = cam_frame_point(design, theta, cx, cy)
    return {
        "contact_force": force,
        "cam_torque": torque,
        "friction_force": friction,
        "guide_friction_force": force * np.cos(phi) - axial,
        "friction_torque": friction * lever,
        "contact_stress": stress,
        "subsurface_shear_stress": shear,
        "subsurface_shear_depth": shear_depth,
        "profile_x": px,
        "profile_y": py,
        "wear_per_revolution": wear,
        "wear_rate": float(np.max(wear)) * design.speed / (2 * np.pi),
    }


def aged_base_circle(design: CamDesign, state: CamState) -> float:
    """Smallest radius of the aged cam (a distorted base circle: its smaller semi-axis).

    Parameters
    ----------
    design : CamDesign
        The dry design, lengths [m].
    state : CamState
        The aged state (plate strains [-]).

    Returns
    -------
    float
        The radius [m].
    """
    if design.kind == "profile":
        return design.profile.radii(state.cam_strain_x, state.cam_strain_y)[0]
    return design.base_circle_radius * (1.0 + min(state.cam_strain_x, state.cam_strain_y))


def hertz_contact(design: CamDesign, state: CamState, force, rho, roller):
    """(p0, tau_max, its depth) of the Hertz line contact of the cam (working radius rho)
    with the roller (radius ``roller``) or flat face; NaN for a knife edge (dynamics module).

    Parameters
    ----------
    design : CamDesign
        The design (follower kind, contact length [m], follower modulus [Pa]).
    state : CamState
        The aged state (surface modulus [Pa], Poisson's ratios [-]).
    force : array_like
        Normal contact force [N].
    rho : array_like
        Radius of curvature of the working profile [m].
    roller : float
        Roller radius [m].

    Returns
    -------
    tuple of numpy.ndarray
        Peak pressure p0 [Pa], largest subsurface shear stress [Pa] and its depth [m].

    References
    ----------
    The Hertz line contact of :mod:`fickcam.cam.dynamics`, whose sources are cited there.
    """
    if design.follower_kind == "knife":
        nothing = np.full_like(np.asarray(force, float), np.nan)
        return nothing, nothing, nothing
    e_star = dyn.effective_modulus(state.cam_surface_modulus, state.cam_surface_poisson,
                                   state.follower_modulus or design.follower_modulus,
                                   state.follower_poisson or design.follower_poisson)
    radius = roller if design.follower_kind == "roller" else None
    stress = dyn.hertz_line_pressure(force, design.contact_length, rho, radius, e_star)
    half_width = dyn.hertz_line_half_width(stress, rho, radius, e_star)
    return (stress,) + dyn.subsurface_shear(stress, half_width)


#: the search for the jump speed: points per round and rounds, each narrowing the bracket
#: to two of its points (by 128x: 2 x 2 deg / 128^5 ~ 2e-12 rad, the bounded Brent
#: search's xatol of 1e-12 it replaces, in 5 vectorised calls instead of 25-30 single ones)
SEARCH_POINTS = 256
SEARCH_ROUNDS = 5


def _follower_mass(design: CamDesign, state: CamState) -> float:
    return design.follower_mass if state.follower_mass is None else state.follower_mass


def _holding_force(design: CamDesign, mass, height):
    """The speed-independent force holding a translating follower on the cam: spring,
    preload, load and weight (:func:`fickcam.cam.dynamics.axial_force` at no acceleration)."""
    return dyn.axial_force(mass, 0.0, design.spring_rate, height - dry_lowest_height(design),
                           design.spring_preload, design.external_load, design.gravity)


def continuous_jump_speed(design: CamDesign, motion, mass: float, theta, d2, holding,
                          holding_of=None) -> float:
    """The jump speed as the minimum over the continuous cam angle, not the angle grid:
    omega_jump^2 = min S(theta) / (-m y''(theta)) over y'' < 0 (see dyn.jump_speed): the
    search of :func:`continuous_jump_speeds` for one ageing time.

    Parameters
    ----------
    design : CamDesign
        The design (spring rate [N/m], preload [N], external load [N], gravity).
    motion : callable
        theta [rad] -> (Y, dY, d2Y, d3Y) of the aged motion (:func:`~fickcam.cam.kinematics.motion_function`; only
        Y and d2Y are asked for).
    mass : float
        Follower mass [kg] (a swinging arm's inertia [kg m^2]).
    theta : numpy.ndarray
        The angle grid [rad].
    d2 : numpy.ndarray
        d2Y/dtheta2 on the grid [m/rad^2] ([rad/rad^2] for an arm).
    holding : numpy.ndarray
        Speed-independent holding force on the grid [N] ([N m] for an arm).
    holding_of : callable, optional
        Y -> holding force [N] ([N m]).

    Returns
    -------
    float
        The jump speed [rad/s]; inf where nothing pulls the follower off.

    References
    ----------
    Norton (2012), ch. 15 (follower jump); in full in :mod:`fickcam.cam`.
    """
    def rows(angles, orders=ORDERS):  # the one time's motion at angles of shape (1, k)
        return tuple(np.reshape(value, angles.shape) for value in motion(angles.ravel(), orders))

    return float(continuous_jump_speeds(design, rows, [mass], theta, np.asarray(d2)[None],
                                        np.asarray(holding)[None], holding_of)[0])


def continuous_jump_speeds(design: CamDesign, motion, masses, theta, d2, holding,
                           holding_of=None) -> np.ndarray:
    """The jump speeds of several ageing times at once, each the minimum over the continuous
    cam angle: omega_jump^2 = min S(theta) / (-m y''(theta)) over y'' < 0 (see
    dyn.jump_speed). Each time's smallest ratio on the grid brackets its minimum between
    its neighbours, where :func:`zoomed_minimum` on the closed-form or spectral motion
    finds it, all times in the same rounds; at an acceleration jump (a segment joint) it
    converges to the one-sided limit.

    Parameters
    ----------
    design : CamDesign
        The design (spring rate [N/m], preload [N], external load [N], gravity).
    motion : callable
        ``motion(angles, orders)``: angles [rad] of shape (n, k), one row per ageing time ->
        the aged motion's derivatives ``orders`` (Y [m], d2Y [m/rad^2]) at them, each (n, k).
    masses : array_like
        Follower mass per ageing time [kg] (a swinging arm's inertia [kg m^2]), shape (n,).
    theta : numpy.ndarray
        The angle grid [rad], shape (m,).
    d2 : numpy.ndarray
        d2Y/dtheta2 on the grid [m/rad^2] ([rad/rad^2] for an arm), shape (n, m).
    holding : numpy.ndarray
        Speed-independent holding force on the grid [N] ([N m] for an arm), shape (n, m).
    holding_of : callable, optional
        Y -> holding force [N] ([N m]) (default: the translating follower's spring,
        preload, load and weight).

    Returns
    -------
    numpy.ndarray
        The jump speeds [rad/s], shape (n,); inf where nothing pulls the follower off, 0
        where it is not held.

    References
    ----------
    Norton (2012), ch. 15 (follower jump); in full in :mod:`fickcam.cam`.
    """
    masses = np.asarray(masses, float)
    on_grid = np.array([dyn.jump_speed(mass, row_d2, row_holding)
                        for mass, row_d2, row_holding in zip(masses, d2, holding)])
    searched = np.isfinite(on_grid) & (on_grid != 0.0)
    if not searched.any() or theta.size < 3:
        return on_grid
    spacing = float(np.median(np.diff(np.sort(theta))))
    mass = masses[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratios = np.where(d2 < 0.0, holding / (-mass * d2), np.inf)
    centre = theta[np.argmin(ratios, axis=1)]

    def ratio(angles):
        height, d2 = motion(angles, orders=(0, 2))
        holding = _holding_force(design, mass, height) if holding_of is None \
            else holding_of(height)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(d2 < 0.0, holding / (-mass * d2), np.inf)  # not pulling: no bound

    best = np.minimum(zoomed_minimum(ratio, centre - spacing, centre + spacing), on_grid ** 2)
    return np.where(searched, np.sqrt(best), on_grid)


def jump_speeds_over_ageing(design: CamDesign, states: dict, theta, fitted=None,
                            search: bool = True) -> dict:
    """The jump speeds of the ageing times whose aged motion has a closed form, and of those
    ``fitted`` together, searched for all of them at once (:func:`continuous_jump_speeds`);
    a translating follower only.

    Parameters
    ----------
    design : CamDesign
        The dry design (SI).
    states : dict of int to CamState
        The aged state at each ageing index.
    theta : numpy.ndarray
        The angle grid [rad].
    fitted : fickcam.cam.kinematics.FittedMotions, optional
        The spectral fits of the other ageing times, made together
        (:func:`~fickcam.cam.kinematics.fitted_motions`).
    search : bool
        Search them; False: the same indices with NaN (the jump speed is not asked for).

    Returns
    -------
    dict of int to float
        The jump speed [rad/s] by ageing index, for the indices whose motion is in closed
        form (:func:`~fickcam.cam.kinematics.closed_form`) or fitted; the others are left
        to :func:`cam_response`.
    """
    if design.arm is not None:
        return {}
    theta = np.asarray(theta, float)
    groups: dict = {}
    for k, state in states.items():
        form = closed_form(design, state)
        if form is not None:
            groups.setdefault(form, []).append(k)
    speeds = {}
    for form, indices in groups.items():
        stacked = stacked_state([states[k] for k in indices])

        def motion(angles, orders=ORDERS, form=form, stacked=stacked):
            return picked(form.heights(design, stacked, angles), orders)

        speeds.update(_stacked_jump_speeds(design, motion, indices, states, theta) if search
                      else dict.fromkeys(indices, math.nan))
    if fitted is not None:
        speeds.update(_stacked_jump_speeds(design, fitted.rows, fitted.indices, states, theta)
                      if search else dict.fromkeys(fitted.indices, math.nan))
    return speeds


def _stacked_jump_speeds(design: CamDesign, motion, indices: list, states: dict, theta) -> dict:
    """:func:`continuous_jump_speeds` of ageing ``indices`` whose motions ``motion`` gives as
    rows, by index."""
    masses = np.array([_follower_mass(design, states[k]) for k in indices], float)
    height, d2 = np.broadcast_arrays(*motion(theta, orders=(0, 2)))
    holding = _holding_force(design, masses[:, None], height)
    return dict(zip(indices, continuous_jump_speeds(design, motion, masses, theta, d2,
                                                    holding).tolist()))


def zoomed_minimum(function, low, high, points: int = SEARCH_POINTS,
                   rounds: int = SEARCH_ROUNDS):
    """The smallest value of a vectorised ``function`` on [low, high]: ``points`` + 1 equally
    spaced values a round, then the two intervals beside the smallest, ``rounds`` times;
    for several intervals at once where ``low`` and ``high`` are arrays.

    Parameters
    ----------
    function : callable
        Vectorised function of one variable: values at points of shape (points + 1,), or
        (n, points + 1) for n intervals, one row each.
    low, high : float or numpy.ndarray
        The interval searched [unit of the variable], or n intervals, shape (n,).
    points : int
        Intervals per round.
    rounds : int
        Number of rounds.

    Returns
    -------
    float or numpy.ndarray
        The smallest value found [unit of the function], one per interval.
    """
    low, high = np.asarray(low, float), np.asarray(high, float)
    best = np.full(low.shape, np.inf)
    for _ in range(rounds):
        angles = np.linspace(low, high, points + 1, axis=-1)
        values = function(angles)
        k = np.argmin(values, axis=-1)[..., None]
        best = np.fmin(best, np.take_along_axis(values, k, axis=-1)[..., 0])
        at = np.take_along_axis(angles, k, axis=-1)[..., 0]
        step = (high - low) / points
        low, high = np.maximum(at - step, low), np.minimum(at + step, high)
    return float(best) if best.ndim == 0 else best


def _where(theta, index) -> str:
    return f"{math.degrees(theta[index]):.4g} deg"


def geometry_notices(design: CamDesign, theta, phi, rho_pitch, rho, roller) -> list[str]:
    """Undercut, cusp, small curvature and steep pressure angle (Norton ch. 8; a flat-face
    arm has a pressure angle too).

    Parameters
    ----------
    design : CamDesign
        The design (its follower kind and arm).
    theta : numpy.ndarray
        Cam angles [rad].
    phi : numpy.ndarray
        Pressure angle at them [rad].
    rho_pitch, rho : numpy.ndarray
        Radius of curvature of the pitch curve and of the working profile [m].
    roller : float
        The (aged) roller radius [m].

    Returns
    -------
    list of str
        One sentence per problem found, at the first angle where it occurs.
    """
    notices = []
    if design.follower_kind == "flat":
        bad = np.nonzero(rho <= 0)[0]
        if bad.size:
            notices.append(f"flat follower: the profile needs a cusp (rho <= 0) at "
                           f"{_where(theta, bad[0])}; raise the base circle")
        if design.arm is None:  # a translating face: phi = 0
            return notices
    k = int(np.argmax(np.abs(phi)))
    if abs(phi[k]) > PRESSURE_ANGLE_LIMIT:
        notices.append(f"pressure angle {math.degrees(phi[k]):.3g} deg at {_where(theta, k)} "
                       f"exceeds 30 deg")
    if design.follower_kind == "roller":
        convex = rho_pitch > 0
        undercut = np.nonzero(convex & (rho_pitch < roller))[0]
        if undercut.size:
            notices.append(f"undercut: pitch radius of curvature {rho_pitch[undercut[0]] * 1e3:.4g} mm "
                           f"< roller radius {roller * 1e3:.4g} mm at {_where(theta, undercut[0])}")
        else:
            small = np.nonzero(np.abs(rho_pitch) < CURVATURE_RATIO_LIMIT * roller)[0]
            if small.size:
                notices.append(f"small pitch radius of curvature {rho_pitch[small[0]] * 1e3:.4g} mm "
                               f"(< 2 roller radii) at {_where(theta, small[0])}")
    return notices


def jump_notices(theta, axial, jump: float, omega: float) -> list[str]:
    """The notice that the follower jumps, where the running speed reaches the jump speed.

    Parameters
    ----------
    theta : numpy.ndarray
        Cam angles [rad].
    axial : numpy.ndarray
        The force the cam must supply at them [N] (an arm's torque [N m]): the notice
        names the angle where it is least.
    jump : float
        The jump speed [rad/s]; NaN where it was not searched.
    omega : float
        The running speed [rad/s].

    Returns
    -------
    list of str
        One sentence, or none where the running speed is below the jump speed (or the
        jump speed is not known).
    """
    if not omega >= jump:
        return []
    k = int(np.argmin(axial))
    return [f"follower jumps at the running speed: contact force falls to zero near "
            f"{_where(theta, k)} (jump speed {jump * 30 / math.pi:.4g} rpm <= running "
            f"{omega * 30 / math.pi:.4g} rpm)"]
