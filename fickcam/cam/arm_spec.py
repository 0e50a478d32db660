"""The scene's ``cam.follower.arm`` (a swinging-arm follower, :mod:`fickcam.cam.arm`) and
what the motion and the arm cannot do together (:func:`~fickcam.cam.arm_spec.arm_problems`, reported by
:mod:`fickcam.scene.load` at the key's line)."""
from __future__ import annotations

import itertools
import math
from typing import Literal

from pydantic import Field

from ..quantities.types import (Length, MomentOfInertia, SignedLength, StrictModel, Torque,
                     TorsionalStiffness)
from .arm import Arm, face_opening, roller_arm_opening


class SwingingArm(StrictModel):
    """``follower.arm``: a swinging (oscillating) follower (:mod:`fickcam.cam.arm`): the
    ``pivot`` [x, y] in the fixed frame (cam axis at the origin, cam angle 0); ``length``
    pivot to roller centre (roller only); ``face_offset`` the distance from the pivot to the
    face line, the pivot on the follower's side (flat only, default 0); ``rises``: the sense
    in which the arm turns as the follower rises; ``inertia`` of arm and roller about the
    pivot; a torsional return spring ``spring_rate`` (N m/rad) with ``spring_preload`` (N m)
    at the dry cam's lowest position, and a constant ``load_torque`` (N m) against the rise.

    Parameters
    ----------
    pivot : tuple of float
        The pivot's x and y in the fixed frame [m].
    length : float or None
        Pivot to roller centre [m] (roller only).
    face_offset : float
        Pivot to the face line [m] (flat only).
    rises : {"counter_clockwise", "clockwise"}
        The sense in which the arm turns as the follower rises.
    inertia : float
        Moment of inertia of arm and roller about the pivot [kg m^2].
    spring_rate : float
        Torsional return spring rate [N m/rad].
    spring_preload : float
        Spring torque at the dry cam's lowest position [N m].
    load_torque : float
        Constant torque against the rise [N m].
    """

    pivot: tuple[SignedLength, SignedLength] = Field(
        description="x and y of the arm's pivot in the fixed frame [m]")
    length: Length | None = Field(
        None, description="Distance from the pivot to the roller centre (roller only) [m]")
    face_offset: SignedLength = Field(
        0.0, description="Distance from the pivot to the face line (flat face only) [m]")
    rises: Literal["counter_clockwise", "clockwise"] = Field(
        "counter_clockwise", description="The sense in which the arm turns as the follower rises")
    inertia: MomentOfInertia = Field(
        description="Moment of inertia of arm and roller about the pivot [kg m^2]")
    spring_rate: TorsionalStiffness = Field(
        0.0, description="Rate of the torsional return spring [N m/rad]")
    spring_preload: Torque = Field(
        0.0, description="Spring torque at the dry cam's lowest position [N m]")
    load_torque: Torque = Field(0.0, description="Constant torque against the rise [N m]")


#: translating-follower keys that have a torsional counterpart on (or no meaning for) an arm
NOT_ON_AN_ARM = {"offset": "the pivot places the arm",
                  "spring_rate": "use arm.spring_rate (torsional, N m/rad)",
                  "spring_preload": "use arm.spring_preload (N m)",
                  "external_load": "use arm.load_torque (N m)",
                  "guide": "an arm has no guide bush", "stiffness": "the elastic follower train "
                  "models a translating follower only"}


def arm_problems(section) -> list[tuple[tuple, str]]:
    """(key path inside ``cam:``, reason) for what the motion and the follower cannot do
    together: rises as lengths on a swinging arm (or angles on a translating follower), an arm
    that cannot reach the base circle or that would swing through the line from the cam axis
    to its pivot (:mod:`fickcam.cam.arm`).

    Parameters
    ----------
    section : CamSection
        The validated ``cam`` section.

    Returns
    -------
    list of tuple
        (key path, reason) per problem; empty when there is none.
    """
    arm = section.follower.arm
    problems = []
    for k, segment in enumerate(section.motion or ()):
        key = "rise" if segment.rise is not None else "return"
        if arm is not None and segment.angular is False:
            problems.append((("motion", k, key), "a swinging-arm follower rises by an angle "
                             "(e.g. '15 deg'), not a length"))
        if arm is None and segment.angular:
            problems.append((("motion", k, key), "a translating follower rises by a length; an "
                             "angle is for a swinging arm (follower.arm)"))
    if arm is None or problems or section.base_circle_radius is None:
        return problems
    swing = max(itertools.accumulate(s.height for s in section.motion))
    return reach_problems(section, section.base_circle_radius, swing)


def reach_problems(section, rb: float, swing: float = 0.0) -> list[tuple[tuple, str]]:
    """An arm that cannot touch a base circle of radius ``rb`` or would swing through the line
    from the cam axis to its pivot on a swing of ``swing`` rad (see :func:`arm_problems`).

    Parameters
    ----------
    section : CamSection
        The validated ``cam`` section.
    rb : float
        Base circle radius [m].
    swing : float
        The arm's swing [rad].

    Returns
    -------
    list of tuple
        (key path, reason) per problem; empty when there is none.
    """

    arm = section.follower.arm
    geometry = Arm(arm.pivot[0], arm.pivot[1], arm.length or 0.0, arm.face_offset)
    d = geometry.pivot_distance
    where = ("follower", "arm")
    if section.follower.kind == "roller":
        prime = rb + section.follower.roller_radius
        opening = roller_arm_opening(d, arm.length, prime)
        if not math.isfinite(opening) or opening <= 0.0:
            return [(where + ("length",), f"the arm cannot reach the prime circle: the roller centre "
                     f"stays {abs(d - arm.length) * 1e3:g}..{(d + arm.length) * 1e3:g} mm from the "
                     f"cam axis, the base circle + roller is {prime * 1e3:g} mm")]
        if opening + swing >= math.pi:
            return [(where + ("pivot",), f"the arm would swing through the line from the cam axis to "
                     f"the pivot ({math.degrees(opening):.4g} deg from it at the base circle, swing "
                     f"{math.degrees(swing):.4g} deg)")]
        return []
    opening = face_opening(d, arm.face_offset, rb)
    if not math.isfinite(opening) or opening <= 0.0:
        return [(where + ("pivot",), f"the face cannot touch the base circle: the pivot is "
                 f"{d * 1e3:g} mm from the cam axis, base circle + face offset is "
                 f"{(rb + arm.face_offset) * 1e3:g} mm")]
    if swing >= opening:
        return [(where + ("pivot",), f"the face would turn past the line from the cam axis to the "
                 f"pivot (swing {math.degrees(swing):.4g} deg >= {math.degrees(opening):.4g} deg)")]
    return []


__all__ = ["NOT_ON_AN_ARM", "SwingingArm", "arm_problems", "reach_problems"]
