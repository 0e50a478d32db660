"""The cam and follower at one ageing time: :func:`cam_response`.

The design motion defines the dry profile; swelling scales it (isotropic: every
cam dimension by 1 + eps, the roller by 1 + eps_roller) or distorts it (anisotropic:
x by 1 + eps_x, y by 1 + eps_y), and the follower motion is recomputed from the aged
geometry: in closed form where the aged motion is the design motion scaled by
1 + eps (isotropic cam with a flat follower, or a radial knife/roller that swells like
the cam, as Singh & Sanyal (2017) scale their pitch circle and lift), otherwise
geometrically (:mod:`fickcam.cam.geometry`). The follower's frame (offset, spring seat)
does not swell, so a swollen base circle also compresses the spring.
"""
from __future__ import annotations

import logging
import math

import numpy as np

from ..messages import note
from ..response import Response
from . import dynamics as dyn
from .design import CamDesign, CamState
from .kinematics import cam_frame_point, dry_lowest_height, motion_function
from .motion import joint_notices

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


def cam_response(design: CamDesign, state: CamState, cam_angle) -> Response:
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
    mass = design.follower_mass if state.follower_mass is None else state.follower_mass
    roller = design.roller_radius * (1 + state.roller_strain)
    motion, (lowest, highest) = motion_function(design, state)
    height, d1, d2, d3 = motion(theta)
    y = height - lowest
    notices: list[str] = joint_notices(design.segments) if design.kind == "motion" else []

    if design.follower_kind == "flat":
        phi = np.zeros_like(theta)
        rho = dyn.flat_radius_of_curvature(height, d2)
        rho_pitch = rho
    else:
        phi = dyn.pressure_angle(height, d1, design.offset)
        rho_pitch = dyn.pitch_radius_of_curvature(height, d1, d2, design.offset)
        rho = rho_pitch - roller
    notices += _geometry_notices(design, theta, phi, rho_pitch, rho, roller)

    velocity, acceleration = d1 * omega, d2 * omega ** 2
    deflection = height - dry_lowest_height(design)
    holding = dyn.axial_force(mass, 0.0, design.spring_rate, deflection, design.spring_preload,
                              design.external_load, design.gravity)
    axial = holding + mass * acceleration
    force = dyn.normal_force(axial, phi, velocity, design.guide_factor)
    cx, cy = _contact_point(design, height, d1, phi, roller)
    torque = dyn.contact_torque(cx, cy, force, phi)
    sliding = design.follower_kind != "roller"
    friction = design.friction_coefficient * np.maximum(force, 0.0) * sliding
    lever = np.abs(cx * np.sin(phi) - cy * np.cos(phi))
    jump = continuous_jump_speed(design, motion, mass, theta, d2, holding)
    notices += _jump_notices(theta, axial, jump, omega)

    if design.follower_kind == "knife":
        notices.append(note("knife-edge follower: Hertz line-contact stress is not defined"))
    stress, shear, shear_depth = hertz_contact(design, state, force, rho, roller)
    wear = (dyn.archard_wear_per_revolution(design.archard_coefficient, design.hardness, force,
                                            design.contact_length, _slide_ratio(design, height, rho))
            if design.hardness else np.zeros_like(theta))
    px, py = cam_frame_point(design, theta, cx, cy)
    variables = {
        "base_circle_radius": aged_base_circle(design, state),
        "lift": highest - lowest,
        "jump_speed": jump,
        "follower_displacement": y,
        "follower_position": height,
        "follower_velocity": velocity,
        "follower_acceleration": acceleration,
        "follower_jerk": d3 * omega ** 3,
        "pressure_angle": phi,
        "radius_of_curvature": rho,
        "pitch_radius_of_curvature": rho_pitch,
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
        "wear_rate": float(np.max(wear)) * omega / (2 * np.pi),
    }
    return Response(variables, notices)


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


def continuous_jump_speed(design: CamDesign, motion, mass: float, theta, d2, holding,
                          holding_of=None) -> float:
    """The jump speed as the minimum over the continuous cam angle, not the angle grid:
    omega_jump^2 = min S(theta) / (-m y''(theta)) over y'' < 0 (see dyn.jump_speed). The
    grid's smallest ratio brackets the minimum between its neighbours, where
    :func:`zoomed_minimum` on the closed-form or spectral motion finds it; at an
    acceleration jump (a segment joint) it converges to the one-sided limit.
    ``motion`` is the aged motion (:func:`motion_function`), ``d2`` and ``holding`` its grid
    values of d2Y/dtheta2 and of the speed-independent holding force; ``holding_of(Y)`` gives
    the holding force (a swinging arm's torque, with ``mass`` its inertia) at any Y
    (default: the translating follower's spring, preload, load and weight).

    Parameters
    ----------
    design : CamDesign
        The design (spring rate [N/m], preload [N], external load [N], gravity).
    motion : callable
        theta [rad] -> (Y, dY, d2Y, d3Y) of the aged motion (:func:`motion_function`; only
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
    on_grid = dyn.jump_speed(mass, d2, holding)
    if not np.isfinite(on_grid) or on_grid == 0.0 or theta.size < 3:
        return on_grid
    spacing = float(np.median(np.diff(np.sort(theta))))
    pulling = d2 < 0.0
    ratios = np.full(theta.shape, np.inf)
    ratios[pulling] = holding[pulling] / (-mass * d2[pulling])
    centre = float(theta[int(np.argmin(ratios))])
    low_height = dry_lowest_height(design)

    def ratio(angles):
        height, d2 = motion(angles, orders=(0, 2))
        holding = dyn.axial_force(mass, 0.0, design.spring_rate, height - low_height,
                                  design.spring_preload, design.external_load, design.gravity) \
            if holding_of is None else holding_of(height)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(d2 < 0.0, holding / (-mass * d2), np.inf)  # not pulling: no bound

    best = min(zoomed_minimum(ratio, centre - spacing, centre + spacing), on_grid ** 2)
    return float(np.sqrt(best))


def zoomed_minimum(function, low: float, high: float, points: int = SEARCH_POINTS,
                   rounds: int = SEARCH_ROUNDS) -> float:
    """The smallest value of a vectorised ``function`` on [low, high]: ``points`` + 1 equally
    spaced values a round, then the two intervals beside the smallest, ``rounds`` times.

    Parameters
    ----------
    function : callable
        Vectorised function of one variable.
    low, high : float
        The interval searched [unit of the variable].
    points : int
        Intervals per round.
    rounds : int
        Number of rounds.

    Returns
    -------
    float
        The smallest value found [unit of the function].
    """
    best = np.inf
    for _ in range(rounds):
        angles = np.linspace(low, high, points + 1)
        values = function(angles)
        k = int(np.argmin(values))
        best = min(best, float(values[k]))
        step = (high - low) / points
        low, high = max(angles[k] - step, low), min(angles[k] + step, high)
    return best


def _where(theta, index) -> str:
    return f"{math.degrees(theta[index]):.4g} deg"


def _geometry_notices(design, theta, phi, rho_pitch, rho, roller) -> list[str]:
    """Undercut, cusp, small curvature and steep pressure angle (Norton ch. 8; a flat-face
    arm has a pressure angle too)."""
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


def _jump_notices(theta, axial, jump, omega) -> list[str]:
    if omega < jump:
        return []
    k = int(np.argmin(axial))
    return [f"follower jumps at the running speed: contact force falls to zero near "
            f"{_where(theta, k)} (jump speed {jump * 30 / math.pi:.4g} rpm <= running "
            f"{omega * 30 / math.pi:.4g} rpm)"]
