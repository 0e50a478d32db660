r"""A swinging-arm (oscillating) follower at one ageing time:
:func:`~fickcam.cam.oscillating.arm_response`, and
:func:`~fickcam.cam.oscillating.follower_response`, the response of either follower type.

The aged arm angle psi(theta) comes from the aged cam geometry (:mod:`fickcam.cam.geometry`
with :mod:`fickcam.cam.arm`): the cam and the roller swell with their strains, the arm's
length and face offset with the follower's strain along the arm; the pivot (the frame) and
the torsional spring's seat do not swell, so an arm lifted by a swollen base circle also
winds up its spring. Kinetostatics about the pivot (Norton, Design of Machinery 5th ed.,
sec. 8.x 'dynamic force analysis' and ch. 15 for an oscillating follower; Chen 1982 ch. 9):

.. math::

    T_{arm} = I \psi'' \omega^2 + k_t (\psi - \psi_0) + T_0 + T_{load}, \qquad
    F_n = T_{arm} / \mathrm{lever},

with lever = l cos(alpha) for a roller (the force acts along the common normal through the
roller centre) and sense (X - A) x N for a flat face; the camshaft torque is the moment
of Fn N about the cam axis at the contact point, T = Fn (X x N), which equals T_arm psi'
by virtual work (no friction).
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..mechanisms.response import Response
from . import arm as geo
from .design import CamDesign, CamState
from .kinematics import cam_frame_point, grown_arm, motion_function
from .model import (aged_base_circle, cam_response, continuous_jump_speed, geometry_notices,
                    hertz_contact, jump_notices)
from .motion import joint_notices


def follower_response(design: CamDesign, state: CamState, cam_angle) -> Response:
    """:func:`arm_response` for a swinging arm, else :func:`~fickcam.cam.model.cam_response`.

    Parameters
    ----------
    design : CamDesign
        The dry design (SI).
    state : CamState
        The aged state.
    cam_angle : array_like
        Cam angles [rad].

    Returns
    -------
    Response
        The follower's variables (SI) and the notices.
    """
    if design.arm is not None:
        return arm_response(design, state, cam_angle)
    return cam_response(design, state, cam_angle)


def _aged_arm(design: CamDesign, state: CamState) -> tuple[geo.Arm, float]:
    """The arm with its length and face offset grown by the follower's strain along it and
    its inertia by the follower's moisture mass ratio m/m_dry, and its dry base angle."""
    ratio = 1.0 if state.follower_mass is None else state.follower_mass / design.follower_mass
    grown = grown_arm(design, state.arm_strain)
    return replace(grown["arm"], inertia=grown["arm"].inertia * ratio), grown["base"]


def _arm_contact(design: CamDesign, state: CamState, psi, d1, d2) -> geo.Contact:
    """Contact geometry of the aged arm at arm angles psi from the dry base position."""
    arm, base = _aged_arm(design, state)
    if design.follower_kind == "flat":
        return geo.face_contact(arm, base, psi, d1, d2)
    return geo.roller_contact(arm, base, design.roller_radius * (1 + state.roller_strain),
                              psi, d1, d2)


def _holding_torque(arm: geo.Arm, psi):
    """Speed-independent torque the cam must supply about the pivot: k_t psi + T_0 + T_load
    (psi from the dry base position, where the spring has its preload)."""
    return arm.spring_rate * psi + arm.spring_preload + arm.load_torque


def arm_response(design: CamDesign, state: CamState, cam_angle) -> Response:
    """Kinematics, kinetostatics and contact of the swinging arm at cam angles (rad).

    Scalars: base_circle_radius, arm_swing (rad), jump_speed (rad/s). Arrays over cam_angle:
    follower_arm_angle (rad, from the aged lowest position) and its time derivatives at
    design.speed, pressure_angle, radius_of_curvature (working profile),
    pitch_radius_of_curvature, contact_force (N), arm_torque (N m, about the pivot),
    cam_torque (N m), friction_force and friction_torque (sliding flat face), contact_stress,
    subsurface_shear_stress/depth, profile_x/profile_y (contact point, cam frame).

    Parameters
    ----------
    design : CamDesign
        The dry design with its arm (SI: lengths [m], inertia [kg m^2], speed [rad/s]).
    state : CamState
        The aged state: cam, roller and arm strains [-], moduli [Pa].
    cam_angle : array_like
        Cam angles at which the arm is evaluated [rad].

    Returns
    -------
    Response
        The variables above (SI) and the notices.

    References
    ----------
    Norton (2012), ch. 8; Chen (1982), ch. 4; in full in :mod:`fickcam.cam`.
    """
    theta = np.asarray(cam_angle, float)
    omega = design.speed
    motion, (lowest, highest) = motion_function(design, state)
    psi, d1, d2, d3 = motion(theta)
    arm = _aged_arm(design, state)[0]
    contact = _arm_contact(design, state, psi, d1, d2)
    roller = design.roller_radius * (1 + state.roller_strain)
    notices = joint_notices(design.segments) if design.kind == "motion" else []
    notices += geometry_notices(design, theta, contact.pressure_angle, contact.pitch_radius,
                                 contact.radius, roller)

    holding = _holding_torque(arm, psi)
    needed = arm.inertia * d2 * omega ** 2 + holding
    with np.errstate(divide="ignore", invalid="ignore"):
        force = needed / contact.lever
    stuck = np.nonzero(contact.lever <= 0.0)[0]
    if stuck.size:
        notices.append(f"the arm locks: the contact force has no moment about the pivot "
                       f"(pressure angle {math.degrees(contact.pressure_angle[stuck[0]]):.4g} deg) "
                       f"at {math.degrees(theta[stuck[0]]):.4g} deg")
    jump = continuous_jump_speed(design, motion, arm.inertia, theta, d2, holding,
                                 holding_of=lambda angle: _holding_torque(arm, angle))
    notices += jump_notices(theta, needed, jump, omega)
    stress, shear, shear_depth = hertz_contact(design, state, force, contact.radius, roller)
    sliding = design.follower_kind == "flat"
    friction = design.friction_coefficient * np.maximum(force, 0.0) * sliding
    px, py = cam_frame_point(design, theta, contact.x, contact.y)
    return Response({
        "base_circle_radius": aged_base_circle(design, state),
        "arm_swing": highest - lowest,
        "jump_speed": jump,
        "follower_arm_angle": psi - lowest,
        "follower_arm_angular_velocity": d1 * omega,
        "follower_arm_angular_acceleration": d2 * omega ** 2,
        "follower_arm_angular_jerk": d3 * omega ** 3,
        "pressure_angle": contact.pressure_angle,
        "radius_of_curvature": contact.radius,
        "pitch_radius_of_curvature": contact.pitch_radius,
        "contact_force": force,
        "arm_torque": needed,
        "cam_torque": force * geo.cross(contact.x, contact.y, contact.nx, contact.ny),
        "friction_force": friction,
        "friction_torque": friction * np.abs(contact.x * contact.nx + contact.y * contact.ny),
        "contact_stress": stress,
        "subsurface_shear_stress": shear,
        "subsurface_shear_depth": shear_depth,
        "profile_x": px,
        "profile_y": py,
    }, notices)


def describe_arm(design: CamDesign) -> str:
    """One line for `fickcam check`: the arm, where it sits on the base circle, and the dry
    design's largest pressure angle and smallest radius of curvature.

    Parameters
    ----------
    design : CamDesign
        The dry design with its arm.

    Returns
    -------
    str
        The line, in mm and degrees.
    """
    arm = design.arm
    theta = np.radians(np.arange(0.0, 360.0, 0.25))
    v = arm_response(design, CamState(), theta).variables
    if design.follower_kind == "flat":
        what = f"flat-face arm, face {arm.face_offset * 1e3:g} mm from the pivot"
    else:
        what = f"roller arm {arm.length * 1e3:g} mm long, roller {design.roller_radius * 1e3:g} mm"
    sense = "counter-clockwise" if arm.sense > 0 else "clockwise"
    return (f"swinging {what}, pivot {arm.pivot_distance * 1e3:.4g} mm from the cam axis; swings "
            f"{math.degrees(v['arm_swing']):.4g} deg {sense} on the rise; dry: pressure angle up "
            f"to {math.degrees(np.nanmax(np.abs(v['pressure_angle']))):.3g} deg, smallest radius of "
            f"curvature {np.nanmin(v['radius_of_curvature']) * 1e3:.4g} mm")


__all__ = ["arm_response", "describe_arm", "follower_response"]
