"""The scene's ``linkage:`` section: a four-bar with the crank as input.

Values are parsed to SI by :mod:`fickcam.quantities.types`. Validation refuses what cannot be
a link or a four-bar: non-positive lengths, bosses that would overlap on a link,
a bar wider than its bosses, a hole as large as its boss, and a linkage that
cannot assemble at any crank angle (the diagonal O4-A ranges over
[|d - a|, d + a] while the coupler-rocker dyad spans [|b - c|, b + c]; Norton,
Design of Machinery 5th ed., ch. 4).
"""
from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import BeforeValidator, Field, model_validator

from ..quantities.types import StrictModel, Angle, AngularSpeed, Length, NonNegativeLength
from ..quantities.parsing import registry


def _in_si(si_unit: str, human: str):
    """A pydantic float type for a dimension :mod:`fickcam.quantities.types` does not list: bare
    numbers are SI, strings are parsed by pint and converted to ``si_unit``."""

    def parse(value):
        if isinstance(value, bool) or value is None:
            raise ValueError(f"expected {human}, got {value!r}")
        if isinstance(value, (int, float)):
            number = float(value)
        elif isinstance(value, str):
            try:
                number = float(registry().Quantity(value.replace("%", "percent")).to(si_unit).magnitude)
            except Exception:  # pint raises several error types
                raise ValueError(f"cannot read {value!r} as {human}") from None
        else:
            raise ValueError(f"expected {human}, got {type(value).__name__}")
        if not math.isfinite(number):
            raise ValueError(f"{value!r} is not a finite number")
        return number

    return Annotated[float, BeforeValidator(parse)]


Torque = _in_si("N*m", "a torque (e.g. '2 N m')")
AngularAcceleration = _in_si("rad/s**2", "an angular acceleration (e.g. '10 rad/s^2')")




class CouplerPoint(StrictModel):
    """Point P on the coupler (Norton ch. 4).

    Parameters
    ----------
    distance : float
        Distance from the crank-coupler pin A [m].
    angle : float
        Angle from the line A->B, counter-clockwise [rad].
    """

    distance: NonNegativeLength = Field(
        description="Distance of the coupler point from the crank-coupler pin A [m]")
    angle: Angle = Field(
        0.0, description="Angle of the coupler point from the line A to B, counter-clockwise [rad]")


class LinkSectionSpec(StrictModel):
    """Cross-section of every link (Singh & Sanyal 2016, Figure 3): a bar between two
    hollow bosses.

    Parameters
    ----------
    width, thickness : float
        The bar's width and thickness [m].
    boss_outer_radius, boss_inner_radius : float
        The bosses' outer radius and their holes' radius [m].

    Raises
    ------
    ValueError
        (to pydantic) A hole as large as its boss, or a bar wider than its bosses.
    """

    width: Length = Field(description="Width of each bar [m]")
    thickness: Length = Field(description="Thickness of each bar [m]")
    boss_outer_radius: Length = Field(description="Outer radius of the bosses at the pins [m]")
    boss_inner_radius: NonNegativeLength = Field(
        description="Radius of the pin holes in the bosses [m]")

    @model_validator(mode="after")
    def _is_a_link(self):
        if self.boss_inner_radius >= self.boss_outer_radius:
            raise ValueError("boss_inner_radius must be smaller than boss_outer_radius")
        if self.width > 2.0 * self.boss_outer_radius:
            raise ValueError("width must not exceed twice boss_outer_radius (the bar would be "
                             "wider than its bosses)")
        return self


def can_assemble_somewhere(crank: float, coupler: float, rocker: float, frame: float) -> bool:
    """True if some crank angle closes the loop: [|d - a|, d + a] meets [|b - c|, b + c]
    (the diagonal from the crank pin to the rocker pivot must be spanned by both sides).

    Parameters
    ----------
    crank, coupler, rocker, frame : float
        Link lengths a, b, c, d [m].

    Returns
    -------
    bool
        Whether the loop closes at some crank angle (to a relative 1e-12).
    """
    low = max(abs(frame - crank), abs(coupler - rocker))
    high = min(frame + crank, coupler + rocker)
    return low <= high * (1.0 + 1e-12)


class LinkageSection(StrictModel):
    """The ``linkage:`` section, in SI once validated.

    Parameters
    ----------
    material : str
        The links' material (a name under ``materials:``).
    frame_material : str or None
        The frame's; None: the links'.
    crank, coupler, rocker, frame : float
        Link lengths a, b, c, d, pin to pin [m].
    coupler_point : CouplerPoint
        The coupler point.
    section : LinkSectionSpec
        Every link's cross-section.
    crank_speed : float
        The crank's angular velocity [rad/s].
    assembly : {"open", "crossed"}
        The branch (:mod:`fickcam.linkage.positions`).
    gravity : bool
        Whether the links' weight acts (g = 9.80665 m/s^2 along -y, the frame line O2->O4
        being +x).
    crank_angular_acceleration : float
        The crank's angular acceleration [rad/s^2].
    rocker_load_torque : float
        A constant torque on the rocker [N m], counter-clockwise positive.
    centre_of_mass : tuple of float
        Centres of mass as fractions of the crank's, coupler's and rocker's pin-to-pin
        lengths from their first pins [-].
    elastic : bool
        Whether to compute the links' swelling stress and failure index
        (:mod:`fickcam.elastic`).

    Raises
    ------
    ValueError
        (to pydantic) A linkage that cannot assemble at any crank angle, bosses that
        overlap on a link, or a centre-of-mass fraction outside [0, 1].
    """

    material: str = Field(description="The links' material (a name under materials)")
    frame_material: str | None = Field(
        None, description="The frame's material; default the links' material")
    crank: Length = Field(description="Crank length a, pin to pin [m]")
    coupler: Length = Field(description="Coupler length b, pin to pin [m]")
    rocker: Length = Field(description="Rocker length c, pin to pin [m]")
    frame: Length = Field(description="Frame length d, between the fixed pivots [m]")
    coupler_point: CouplerPoint = Field(description="The coupler point whose path is traced")
    section: LinkSectionSpec = Field(description="Cross-section of every link")
    crank_speed: AngularSpeed = Field(description="Angular velocity of the crank [rad/s]")
    assembly: Literal["open", "crossed"] = Field(
        "open", description="The branch the linkage is assembled in")
    gravity: bool = Field(
        False, description="Whether the links' weight acts (along -y, the frame line along +x)")
    crank_angular_acceleration: AngularAcceleration = Field(
        0.0, description="Angular acceleration of the crank [rad/s^2]")
    rocker_load_torque: Torque = Field(
        0.0, description="Constant torque on the rocker, counter-clockwise positive [N m]")
    centre_of_mass: tuple[float, float, float] = Field(
        (0.5, 0.5, 0.5), description="Centres of mass of crank, coupler, rocker as fractions of their lengths [1]")
    elastic: bool = Field(
        False, description="Whether to compute the links' swelling stress and failure index")

    @model_validator(mode="after")
    def _is_a_four_bar(self):
        a, b, c, d = self.crank, self.coupler, self.rocker, self.frame
        if not can_assemble_somewhere(a, b, c, d):
            raise ValueError(
                f"the linkage cannot assemble at any crank angle: the distance from the "
                f"crank pin to the rocker pivot spans {abs(d - a) * 1e3:g}-{(d + a) * 1e3:g} mm "
                f"but coupler and rocker reach only {abs(b - c) * 1e3:g}-{(b + c) * 1e3:g} mm")
        two_r = 2.0 * self.section.boss_outer_radius
        for name in ("crank", "coupler", "rocker", "frame"):
            if getattr(self, name) < two_r:
                raise ValueError(f"{name} ({getattr(self, name) * 1e3:g} mm) is shorter than two "
                                 f"boss radii ({two_r * 1e3:g} mm): its bosses would overlap")
        if not all(0.0 <= f <= 1.0 for f in self.centre_of_mass):
            raise ValueError("centre_of_mass fractions must lie between 0 and 1")
        return self
