"""The cam and follower at one ageing time: :func:`cam_response`.

The design motion defines the dry profile; swelling scales it (isotropic: every
cam dimension by 1 + eps, the roller by 1 + eps_roller) or distorts it (anisotropic:
x by 1 + eps_x, y by 1 + eps_y), and the follower motion is recomputed from the aged
geometry: in closed form where the aged motion is the design motion scaled by
1 + eps (isotropic cam with a flat follower, or a radial knife/roller that swells like
the cam, as seeds/000_c9d2754e3bf549ac.txt scales its pitch circle and lift), otherwise
geometrically (:mod:`fickcam.cam.geometry`). The follower's frame (offset, spring seat)
does not swell, so a swollen base circle also compresses the spring.
"""
from __future__ import annotations

import functools
import logging
import math
from dataclasses import dataclass

import numpy as np

from ..response import Response
from . import dynamics as dyn
from .geometry import (evaluate_geometric_motion, fit_geometric_motion, pieces_of, prime_height,
                       rotate, working_outline)
from .motion import follower_motion, joint_notices, segments_from_spec

log = logging.getLogger(__name__)

#: Norton (Design of Machinery, sec. 8.7) keeps the pressure angle of a translating
#: follower below 30 deg and the pitch radius of curvature above 2-3 roller radii
PRESSURE_ANGLE_LIMIT = math.radians(30.0)
CURVATURE_RATIO_LIMIT = 2.0


@dataclass(frozen=True)
class CamDesign:
    """The dry cam and follower (SI, angles in rad, speed in rad/s)."""

    kind: str                      # motion | eccentric | profile
    base_circle_radius: float
    thickness: float
    speed: float
    follower_kind: str             # knife | roller | flat
    follower_mass: float
    segments: tuple = ()
    eccentricity: float = 0.0
    disc_radius: float = 0.0
    bore_radius: float = 0.0
    roller_radius: float = 0.0
    offset: float = 0.0
    spring_rate: float = 0.0
    spring_preload: float = 0.0
    external_load: float = 0.0
    follower_width: float | None = None
    friction_coefficient: float = 0.0
    guide_factor: float = 0.0
    gravity: bool = False
    archard_coefficient: float = 0.0
    hardness: float | None = None
    follower_modulus: float = 210e9
    follower_poisson: float = 0.3
    profile: object = None         # fickcam.cam.profile.CamProfile (kind "profile")
    train: tuple | None = None     # None: rigid; ("stiffness", k) | ("rod", L, d) | ("lever", L, w, h)
    damping_ratio: float = 0.05
    polydyne_speed: float | None = None  # design speed of a polydyne cam (fickcam.cam.polydyne)
    arm: object = None             # fickcam.cam.arm.Arm of a swinging-arm follower (None: translating)
    clockwise: bool = False        # the cam turns clockwise: computed as its mirror image x -> -x

    @property
    def contact_length(self) -> float:
        return min(self.thickness, self.follower_width or self.thickness)


@dataclass(frozen=True)
class CamState:
    """Ageing-time state: cam in-plane strains along x (fibre) and y, roller strain,
    follower mass (kg), cam surface-layer modulus/Poisson ratio, follower modulus/Poisson."""

    cam_strain_x: float = 0.0
    cam_strain_y: float = 0.0
    roller_strain: float = 0.0
    follower_mass: float | None = None
    cam_surface_modulus: float = 70e9
    cam_surface_poisson: float = 0.3
    follower_modulus: float | None = None
    follower_poisson: float | None = None
    follower_train_modulus: float | None = None
    arm_strain: float = 0.0        # swinging arm: strain along its length (and face offset)


def _train(stiffness) -> tuple | None:
    """The follower train of ``follower.stiffness`` as a hashable tuple (None: rigid)."""
    if stiffness is None:
        return None
    if isinstance(stiffness, float | int):
        return ("stiffness", float(stiffness))
    if stiffness.rod is not None:
        return ("rod", stiffness.rod.length, stiffness.rod.diameter)
    lever = stiffness.lever
    return ("lever", lever.length, lever.width, lever.height)


def design_from_scene(section) -> CamDesign:
    """CamDesign from a validated :class:`~fickcam.cam.spec.CamSection` (or the dict of a
    scene's ``cam:`` section, validated here)."""
    if isinstance(section, dict):
        from .spec import CamSection

        section = CamSection.model_validate(section)
    f = section.follower
    guide = 0.0 if f.guide is None else dyn.guide_friction_factor(
        f.guide.friction_coefficient, f.guide.overhang, f.guide.length, f.guide.diameter)
    mirror = -1.0 if section.direction == "clockwise" else 1.0
    common = dict(thickness=section.thickness, speed=section.speed, follower_kind=f.kind,
                  follower_mass=f.mass, bore_radius=section.bore_radius, clockwise=mirror < 0,
                  roller_radius=f.roller_radius or 0.0, offset=mirror * f.offset,
                  spring_rate=f.spring_rate,
                  spring_preload=f.spring_preload, external_load=f.external_load,
                  follower_width=f.width, friction_coefficient=f.friction_coefficient,
                  guide_factor=guide, gravity=section.gravity,
                  archard_coefficient=section.wear.archard_coefficient if section.wear else 0.0,
                  hardness=section.wear.hardness if section.wear else None,
                  follower_modulus=f.modulus, follower_poisson=f.poisson_ratio,
                  train=_train(f.stiffness), damping_ratio=f.damping_ratio,
                  polydyne_speed=None if section.polydyne is None else
                  (section.polydyne.speed or section.speed))
    if f.arm is not None:
        from .arm import Arm

        sense = 1 if f.arm.rises == "counter_clockwise" else -1
        common["arm"] = Arm(mirror * f.arm.pivot[0], f.arm.pivot[1], f.arm.length or 0.0,
                            f.arm.face_offset, int(mirror) * sense, f.arm.inertia,
                            f.arm.spring_rate, f.arm.spring_preload, f.arm.load_torque)
    if section.profile_file is not None:
        from .profile import load_profile

        profile = load_profile(section.profile_file, f.roller_radius or 0.0, mirror=mirror < 0)
        return CamDesign("profile", profile.radii()[0], profile=profile, **common)
    if section.eccentric is not None:
        e, r = section.eccentric.eccentricity, section.eccentric.radius
        return CamDesign("eccentric", r - e, eccentricity=e, disc_radius=r, **common)
    return CamDesign("motion", section.base_circle_radius,
                     segments=segments_from_spec(section.motion), **common)


# ------------------------------------------------------------------ kinematics


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


def _closed_form(design: CamDesign, state: CamState, theta):
    scale = 1.0 + state.cam_strain_x
    y, d1, d2, d3 = follower_motion(design.segments, theta)
    if design.arm is not None:  # the arm angle from its dry base position
        return (y, d1, d2, d3), (0.0, _design_lift(design))
    base = design.base_circle_radius * scale
    if design.follower_kind == "flat":
        floor = base
    else:
        floor = prime_height(base + design.roller_radius * (1 + state.roller_strain), design.offset)
    return (floor + scale * y, scale * d1, scale * d2, scale * d3), \
        (floor, floor + scale * _design_lift(design))


def _eccentric_flat(design: CamDesign, state: CamState, theta):
    """Flat face on the (swollen) eccentric disc, in closed form: the face height is the
    support function of the ellipse with centre (0, -e_y) and semi-axes a = R(1 + eps_x),
    b = R(1 + eps_y) in the direction n = (sin theta, cos theta) (kinematic inversion,
    Norton sec. 8.6): Y = -e_y cos theta + f, f = sqrt(A + B cos 2 theta),
    A = (a^2 + b^2)/2, B = (b^2 - a^2)/2; a circle (a = b) gives pure SHM
    Y = R - e cos theta (seeds/003_b8317aa6e553b071.txt sec. 5.2). The derivatives of f
    follow from differentiating f^2 = g three times."""
    theta = np.asarray(theta, float)
    e_y = design.eccentricity * (1 + state.cam_strain_y)
    a = design.disc_radius * (1 + state.cam_strain_x)
    b = design.disc_radius * (1 + state.cam_strain_y)
    big_a, big_b = (a * a + b * b) / 2, (b * b - a * a) / 2

    def support(t):
        return -e_y * np.cos(t) + np.sqrt(big_a + big_b * np.cos(2 * t))

    f = np.sqrt(big_a + big_b * np.cos(2 * theta))
    g1, g2, g3 = (-2 * big_b * np.sin(2 * theta), -4 * big_b * np.cos(2 * theta),
                  8 * big_b * np.sin(2 * theta))
    f1 = g1 / (2 * f)
    f2 = (g2 / 2 - f1 ** 2) / f
    f3 = (g3 / 2 - 3 * f1 * f2) / f
    c, s = np.cos(theta), np.sin(theta)
    heights = (support(theta), e_y * s + f1, e_y * c + f2, -e_y * s + f3)
    return heights, _support_extremes(support, e_y, a, big_b)


def _support_extremes(support, e_y, a, big_b):
    """(lowest, highest) of the support function: theta = 0, pi and, for a flattened disc,
    the interior stationary points where e_y f = 2 B cos theta, i.e.
    cos^2 theta = e_y^2 a^2 / (2 B (2 B - e_y^2))."""
    candidates = [0.0, np.pi]
    denominator = 2 * big_b * (2 * big_b - e_y ** 2)
    if denominator > 0:
        c2 = e_y ** 2 * a ** 2 / denominator
        if c2 <= 1:
            c = math.sqrt(c2)
            candidates += [math.acos(c), math.acos(-c), -math.acos(c), -math.acos(-c)]
    values = support(np.array(candidates))
    return float(values.min()), float(values.max())


def follower_heights(design: CamDesign, state: CamState, theta):
    """(Y, dY/dtheta, d2Y/dtheta2, d3Y/dtheta3), (lowest, highest) Y: the follower's pitch point
    (face for a flat follower) above the cam axis at cam angles theta (rad)."""
    motion, extremes = motion_function(design, state)
    return motion(theta), extremes


def motion_function(design: CamDesign, state: CamState):
    """(theta -> (Y, dY, d2Y, d3Y), (lowest, highest) Y): the closed form where it exists,
    else the aged geometry's spectral fit, made once and evaluated at any angle."""
    if _scales_exactly(design, state):
        return (lambda theta: _closed_form(design, state, theta)[0],
                _closed_form(design, state, np.zeros(1))[1])
    if design.kind == "profile":
        from .profile import profile_motion

        aged = (design.profile, state.cam_strain_x, state.cam_strain_y,
                design.roller_radius * (1 + state.roller_strain), design.offset,
                design.follower_kind == "flat")
        arm = {} if design.arm is None else _grown_arm(design, state.arm_strain)
        return (lambda theta: profile_motion(*aged, theta, **arm)[0],
                profile_motion(*aged, np.zeros(1), **arm)[1])
    if design.kind == "eccentric" and design.follower_kind == "flat":
        return (lambda theta: _eccentric_flat(design, state, theta)[0],
                _eccentric_flat(design, state, np.zeros(1))[1])
    fitted, origin, extremes = fit_geometric_motion(
        design, pieces_of(design), state.cam_strain_x, state.cam_strain_y,
        design.roller_radius * (1 + state.roller_strain),
        nodes=96 if design.kind == "eccentric" else 40, arm_strain=state.arm_strain)
    return (lambda theta: evaluate_geometric_motion(fitted, origin, theta)), extremes


def _grown_arm(design: CamDesign, strain: float) -> dict:
    """``arm`` (length and face offset grown by 1 + strain) and its dry ``base`` angle, for
    :func:`fickcam.cam.profile.profile_motion`."""
    from dataclasses import replace

    from . import arm

    a, rb = design.arm, design.base_circle_radius
    base = (arm.face_base_angle(a, rb) if design.follower_kind == "flat" else
            arm.roller_base_angle(a, rb + design.roller_radius))
    return {"arm": replace(a, length=a.length * (1 + strain), face_offset=a.face_offset * (1 + strain)),
            "base": base}


@functools.lru_cache(maxsize=64)
def dry_lowest_height(design: CamDesign) -> float:
    """Lowest follower height of the dry cam: where the spring has its preload."""
    return follower_heights(design, CamState(), np.linspace(0, 2 * np.pi, 8, endpoint=False))[1][0]


def working_profile(design: CamDesign, strain_x: float = 0.0, strain_y: float = 0.0,
                    n: int = 720):
    """Closed counter-clockwise outline (x, y) of the working profile (m), cam frame as seen
    from the front, last point != first, for the diffusion mesh
    (:class:`fickcam.diffusion.CamPlate`)."""
    x, y = working_outline(design, strain_x, strain_y, n)
    if design.clockwise:  # mirror back, still counter-clockwise
        return -x[::-1].copy(), y[::-1].copy()
    return x, y


def cam_frame_point(design: CamDesign, theta, x, y):
    """Fixed-frame point (x, y) at cam angle theta in the cam frame, seen from the front:
    R(-theta) (x, y), mirrored back for a clockwise cam."""
    px, py = rotate(-theta, x, y)
    return (-px if design.clockwise else px), py


def write_profile_csv(path, design: CamDesign, strain_x: float = 0.0, strain_y: float = 0.0,
                      n: int = 720):
    """Write the working profile (cam frame, counter-clockwise) as CSV columns x_m, y_m."""
    x, y = working_profile(design, strain_x, strain_y, n)
    np.savetxt(path, np.c_[x, y], delimiter=",", header="x_m,y_m", comments="", fmt="%.9e")
    return path


# ------------------------------------------------------------------ response


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
    follower_displacement (m, from the aged lowest position), follower_velocity,
    follower_acceleration, follower_jerk (time derivatives at design.speed),
    pressure_angle (rad), radius_of_curvature (m, working profile; pitch curve minus roller),
    pitch_radius_of_curvature (m), contact_force (N, common normal), cam_torque (N m),
    friction_force (N, sliding friction at the contact), guide_friction_force (N),
    friction_torque (N m), contact_stress (Pa, Hertz p0), subsurface_shear_stress (Pa) and
    subsurface_shear_depth (m) under it, profile_x/profile_y (m, working
    profile point in contact, cam frame), wear_per_revolution (m)."""
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
        notices.append("knife-edge follower: Hertz line-contact stress is not defined")
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
    """Smallest radius of the aged cam (a distorted base circle: its smaller semi-axis)."""
    if design.kind == "profile":
        return design.profile.radii(state.cam_strain_x, state.cam_strain_y)[0]
    return design.base_circle_radius * (1.0 + min(state.cam_strain_x, state.cam_strain_y))


def hertz_contact(design: CamDesign, state: CamState, force, rho, roller):
    """(p0, tau_max, its depth) of the Hertz line contact of the cam (working radius rho)
    with the roller (radius ``roller``) or flat face; NaN for a knife edge (dynamics module)."""
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


def continuous_jump_speed(design: CamDesign, motion, mass: float, theta, d2, holding,
                          holding_of=None) -> float:
    """The jump speed as the minimum over the continuous cam angle, not the angle grid:
    omega_jump^2 = min S(theta) / (-m y''(theta)) over y'' < 0 (see dyn.jump_speed). The
    grid's smallest ratio brackets the minimum between its neighbours, where a bounded
    Brent search (scipy.optimize.minimize_scalar) on the closed-form or spectral motion
    finds it; at an acceleration jump (a segment joint) it converges to the one-sided limit.
    ``motion`` is the aged motion (:func:`motion_function`), ``d2`` and ``holding`` its grid
    values of d2Y/dtheta2 and of the speed-independent holding force; ``holding_of(Y)`` gives
    the holding force (a swinging arm's torque, with ``mass`` its inertia) at any Y
    (default: the translating follower's spring, preload, load and weight)."""
    on_grid = dyn.jump_speed(mass, d2, holding)
    if not np.isfinite(on_grid) or on_grid == 0.0 or theta.size < 3:
        return on_grid
    from scipy.optimize import minimize_scalar

    spacing = float(np.median(np.diff(np.sort(theta))))
    pulling = d2 < 0.0
    ratios = np.full(theta.shape, np.inf)
    ratios[pulling] = holding[pulling] / (-mass * d2[pulling])
    centre = float(theta[int(np.argmin(ratios))])
    low_height = dry_lowest_height(design)

    def ratio(angle):
        height, _, d2, _ = motion(np.array([angle]))
        if not d2[0] < 0.0:  # not pulling away here: no bound (large, finite for Brent)
            return 1e300
        holding = dyn.axial_force(mass, 0.0, design.spring_rate, height[0] - low_height,
                                  design.spring_preload, design.external_load, design.gravity) \
            if holding_of is None else holding_of(height[0])
        return holding / (-mass * d2[0])

    found = minimize_scalar(ratio, bounds=(centre - spacing, centre + spacing), method="bounded",
                            options={"xatol": 1e-12})
    best = min(float(found.fun), on_grid ** 2)
    return float(np.sqrt(best))


def _design_lift(design: CamDesign) -> float:
    level, top = 0.0, 0.0
    for s in design.segments:
        level += s.height
        top = max(top, level)
    return top


def _where(theta, index) -> str:
    return f"{math.degrees(theta[index]):.4g} deg"


def _geometry_notices(design, theta, phi, rho_pitch, rho, roller) -> list[str]:
    """Undercut, cusp, small curvature and steep pressure angle (Norton sec. 8.7; a flat-face
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
