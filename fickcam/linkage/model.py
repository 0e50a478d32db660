"""One four-bar at one ageing time: positions, class, velocities, accelerations and
kinetostatics over the crank angle, as a :class:`fickcam.mechanisms.response.Response`."""
from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np

from ..messages import note
from ..mechanisms.response import Response
from .classify import FULL_ROTATION, grashof_class
from .dynamics import STANDARD_GRAVITY, kinetostatics, rms
from .kinematics import angular_accelerations, angular_velocities, centre_of_mass_motion
from .positions import (
    assembly_gaps,
    continuous,
    coupler_point,
    joint_positions,
    positions,
    toggle_crank_angles,
    transmission_angle,
)

log = logging.getLogger(__name__)




@dataclass(frozen=True)
class FourBarDesign:
    """The dry four-bar (SI).

    Parameters
    ----------
    crank, coupler, rocker, frame : float
        Link lengths a, b, c, d [m], pin to pin.
    coupler_point_distance : float
        Distance of the coupler point from the crank pin A [m].
    coupler_point_angle : float
        Its angle from the coupler line A->B [rad].
    crank_speed : float
        The crank's angular velocity [rad/s].
    crank_angular_acceleration : float
        The crank's angular acceleration [rad/s^2].
    assembly : {"open", "crossed"}
        The branch (:mod:`fickcam.linkage.positions`).
    gravity : bool
        Whether the links' weight acts (along -y).
    rocker_load_torque : float
        External torque on the rocker [N m], counter-clockwise positive.
    """

    crank: float
    coupler: float
    rocker: float
    frame: float
    coupler_point_distance: float = 0.0
    coupler_point_angle: float = 0.0
    crank_speed: float = 1.0            # rad/s
    crank_angular_acceleration: float = 0.0  # rad/s^2
    assembly: str = "open"
    gravity: bool = False
    rocker_load_torque: float = 0.0     # N m, counter-clockwise positive

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        return (self.crank, self.coupler, self.rocker, self.frame)

    @classmethod
    def from_section(cls, section, lengths=None) -> "FourBarDesign":
        """From a validated :class:`~fickcam.linkage.spec.LinkageSection`; ``lengths``:
        a, b, c, d [m] where some links are drawn (their lengths from their pins)."""
        a, b, c, d = lengths or (section.crank, section.coupler, section.rocker, section.frame)
        return cls(a, b, c, d,
                   section.coupler_point.distance, section.coupler_point.angle,
                   section.crank_speed, section.crank_angular_acceleration, section.assembly,
                   section.gravity, section.rocker_load_torque)


@dataclass(frozen=True)
class FourBarState:
    """The four-bar at one ageing time (SI).

    Parameters
    ----------
    link_lengths : tuple of float
        Swollen crank, coupler, rocker and frame lengths [m].
    link_masses : tuple of float
        Crank, coupler and rocker masses [kg].
    link_inertias : tuple of float
        Their moments of inertia about their centres of mass [kg m^2].
    centre_of_mass : tuple of float
        Each centre of mass as a fraction of the pin-to-pin length from its first pin
        (O2, A, O4) [-].
    coupler_point_distance : float or None
        Distance of the coupler point from A [m]; None: the design's, scaled with the
        coupler's length.
    """

    link_lengths: tuple[float, float, float, float]
    link_masses: tuple[float, float, float] = (0.0, 0.0, 0.0)
    link_inertias: tuple[float, float, float] = (0.0, 0.0, 0.0)
    centre_of_mass: tuple[float, float, float] = field(default=(0.5, 0.5, 0.5))
    coupler_point_distance: float | None = None


def _fmt_range(lo: float, hi: float) -> str:
    return f"{np.degrees(lo):.1f}-{np.degrees(hi):.1f} deg"


def fourbar_response(design: FourBarDesign, state: FourBarState, crank_angle) -> Response:
    """Positions, class, kinematics and kinetostatics over ``crank_angle``. Crank angles
    at which the aged linkage cannot assemble hold NaN and are named in the notices.

    Parameters
    ----------
    design : FourBarDesign
        The dry four-bar (its speed, branch, coupler point angle and loads are used).
    state : FourBarState
        The four-bar at this ageing time.
    crank_angle : array_like
        A grid over one revolution [rad].

    Returns
    -------
    fickcam.mechanisms.response.Response
        SI arrays (angles in rad), named, dimensioned and in the units of the "linkage"
        rows of ``fickcam.schema.VARIABLES``, and the notices.

    References
    ----------
    Norton (2012), chs. 4, 6, 7 and 11; in full in :mod:`fickcam.linkage`.
    """
    theta2 = np.asarray(crank_angle, float)
    a, b, c, d = (float(x) for x in state.link_lengths)
    branch = design.assembly
    theta3, theta4 = positions(a, b, c, d, theta2, branch)
    ok = np.isfinite(theta3) & np.isfinite(theta4)
    kinetics = _kinetics(design, state, theta2, theta3, theta4)
    torque = kinetics["input_torque"]
    mu = transmission_angle(theta3, theta4)
    label = grashof_class(a, b, c, d)
    toggles = toggle_crank_angles(a, b, c, d, branch)
    rocker = continuous(theta4)
    variables = {
        "coupler_angle": continuous(theta3),
        "rocker_angle": rocker,
        "transmission_angle": mu,
        **kinetics,
        "grashof_class": np.array(label),
        "minimum_transmission_angle": np.nanmin(mu) if ok.any() else np.nan,
        "maximum_transmission_angle": np.nanmax(mu) if ok.any() else np.nan,
        "peak_input_torque": np.nanmax(np.abs(torque)) if ok.any() else np.nan,
        "rms_input_torque": rms(torque),
        "rocker_swing": np.nanmax(rocker) - np.nanmin(rocker) if ok.any() else np.nan,
        "toggle_crank_angle_extended": toggles["extended"][0] if toggles["extended"] else np.nan,
        "toggle_crank_angle_folded": toggles["folded"][0] if toggles["folded"] else np.nan,
    }
    notices = fourbar_notices(label, assembly_gaps(theta2, ok), toggles, branch)
    for message in notices:
        log.debug("%s", message)
    return Response(variables, notices)


def _kinetics(design: FourBarDesign, state: FourBarState, theta2, theta3, theta4) -> dict:
    """The variables of :func:`fourbar_response` over the crank angle that follow from the
    link angles [rad]: coupler point [m], angular velocities [rad/s] and accelerations
    [rad/s^2], the links' centre-of-mass motion, the input torque [N m], joint forces [N]."""
    a, b, c, d = (float(x) for x in state.link_lengths)
    omega2, alpha2 = design.crank_speed, design.crank_angular_acceleration
    omega3, omega4 = angular_velocities(a, b, c, theta2, theta3, theta4, omega2)
    alpha3, alpha4 = angular_accelerations(a, b, c, theta2, theta3, theta4, omega2, omega3,
                                           omega4, alpha2)
    p_dist = (state.coupler_point_distance if state.coupler_point_distance is not None
              else design.coupler_point_distance * b / design.coupler)
    px, py = coupler_point(a, theta2, theta3, p_dist, design.coupler_point_angle)
    omega2_arr = np.full_like(theta2, omega2)
    alpha2_arr = np.full_like(theta2, alpha2)
    position, velocity, acceleration = centre_of_mass_motion(
        (a, b, c, d), state.centre_of_mass, (theta2, theta3, theta4),
        (omega2_arr, omega3, omega4), (alpha2_arr, alpha3, alpha4))
    pins = joint_positions(a, b, c, d, theta2, theta3, theta4)
    forces, torque = kinetostatics(state.link_masses, state.link_inertias, acceleration,
                                   (alpha2_arr, alpha3, alpha4), pins, position,
                                   STANDARD_GRAVITY if design.gravity else 0.0,
                                   design.rocker_load_torque)
    zero = np.zeros((1,) + theta2.shape)  # the frame's centre of mass does not move
    return {
        "coupler_point_x": px,
        "coupler_point_y": py,
        "coupler_angular_velocity": omega3,
        "rocker_angular_velocity": omega4,
        "coupler_angular_acceleration": alpha3,
        "rocker_angular_acceleration": alpha4,
        "link_com_velocity_x": np.concatenate([velocity.real, zero]),
        "link_com_velocity_y": np.concatenate([velocity.imag, zero]),
        "link_com_acceleration_x": np.concatenate([acceleration.real, zero]),
        "link_com_acceleration_y": np.concatenate([acceleration.imag, zero]),
        "input_torque": torque,
        "joint_force_x": forces.real,
        "joint_force_y": forces.imag,
        "joint_force": np.abs(forces),
    }


def fourbar_notices(label: str, gaps, toggles: dict, branch: str) -> list[str]:
    """What :func:`fourbar_response` tells of one four-bar: its Grashof class, the crank
    angles where it cannot assemble and its toggle positions.

    Parameters
    ----------
    label : str
        The Grashof class (:func:`~fickcam.linkage.classify.grashof_class`).
    gaps : iterable of tuple of float
        (first, last) crank angle [rad] of each range where it cannot assemble.
    toggles : dict
        Toggle crank angles [rad] by kind (:func:`~fickcam.linkage.positions.toggle_crank_angles`).
    branch : str
        The assembly branch, ``"open"`` or ``"crossed"``.

    Returns
    -------
    list of str
        The notices, informational ones made with :func:`fickcam.messages.note`.
    """
    notices = [f"Grashof class: {label}" + ("" if label in FULL_ROTATION
                                            else " (the crank cannot make a full revolution)")]
    if label in FULL_ROTATION:  # what the mechanism is: for information
        notices[0] = note(notices[0])
    for lo, hi in gaps:
        notices.append(f"cannot assemble for crank angles {_fmt_range(lo, hi)} ({branch} branch)")
    named = {"extended": "crank and coupler extended in line (rocker limit)",
             "folded": "crank and coupler folded in line (rocker limit)",
             "crank_limits": "coupler and rocker in line (crank toggle, input stops)"}
    for key, what in named.items():
        if toggles[key]:
            angles = ", ".join(f"{np.degrees(t):.1f}" for t in toggles[key])
            notices.append(note(f"toggle: {what} at crank angle {angles} deg"))
    return notices
