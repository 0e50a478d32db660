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

from pydantic import BeforeValidator, Discriminator, Field, Tag, field_validator, model_validator

from ..drawing.spec import DrawingFile, Hole, Point, drawing_file, plausible_outline
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


class LinkDrawing(DrawingFile):
    """A link's DXF drawing: ``file`` and ``units`` as in
    :class:`fickcam.drawing.spec.DrawingFile`, and the layer of its pin holes.

    Parameters
    ----------
    pin_layer : str, optional
        The layer of the two pin holes; None: the two largest round holes.
    """

    pin_layer: str | None = Field(
        None, description="The layer of the two pin holes (default: the two largest round holes)")


class DrawnLinkSpec(StrictModel):
    """A link as drawn (``{drawing: crank.dxf}``) or written (``{outline: ..., holes: ...}``)
    in place of its length: the outer loop with its holes, the two pin holes giving the
    pin centres, whose distance is the link's length.

    Parameters
    ----------
    drawing : LinkDrawing, optional
        The link's DXF drawing.
    outline : list of tuple of float, optional
        The link's outline (x, y) [m].
    holes : list, optional
        The outline's holes [m], round ``{centre, radius}`` or points.
    """

    drawing: Annotated[LinkDrawing | None, BeforeValidator(drawing_file)] = Field(
        None, description="The link's DXF drawing, its length the distance of its pin holes "
                          "(the dxf extra)")
    outline: list[Point] | None = Field(
        None, min_length=3, description="The link's outline (x, y) instead of a drawing [m]")
    holes: list[Hole] | None = Field(
        None, description="The outline's holes, round {centre, radius} or points; the two "
                          "largest round ones are the pins [m]")

    @field_validator("outline")
    @classmethod
    def _outline_span(cls, value):
        return plausible_outline(value)

    @model_validator(mode="after")
    def _one_shape(self):
        if (self.drawing is None) == (self.outline is None):
            raise ValueError("give the link's drawing or its outline (with holes), one of them")
        if self.holes is not None and self.outline is None:
            raise ValueError("holes belong to an outline: give outline too")
        return self


#: a link given by its length, or drawn (a mapping)
LinkLength = Annotated[
    Annotated[DrawnLinkSpec, Tag("DrawnLinkSpec")] | Annotated[Length, Tag("Length")],
    Discriminator(lambda v: "DrawnLinkSpec" if isinstance(v, dict | DrawnLinkSpec) else "Length")]
#: the links that may be drawn (the frame is the ground between the fixed pivots)
DRAWN_LINKS = ("crank", "coupler", "rocker")


def four_bar_problem(lengths, boss_outer_radius: float, drawn=()) -> str | None:
    """Why link lengths a, b, c, d [m] are no four-bar, or None: it cannot assemble at
    any crank angle, or a link given by its length is shorter than two boss radii.

    Parameters
    ----------
    lengths : tuple of float
        a, b, c, d [m].
    boss_outer_radius : float
        The section's boss radius [m] (links given by their length).
    drawn : collection of str
        The drawn links (their bosses are drawn).

    Returns
    -------
    str or None
        The reason, in one line.
    """
    a, b, c, d = lengths
    if not can_assemble_somewhere(a, b, c, d):
        return (f"the linkage cannot assemble at any crank angle: the distance from the "
                f"crank pin to the rocker pivot spans {abs(d - a) * 1e3:g}-{(d + a) * 1e3:g} mm "
                f"but coupler and rocker reach only {abs(b - c) * 1e3:g}-{(b + c) * 1e3:g} mm")
    two_r = 2.0 * boss_outer_radius
    for name, length in zip(("crank", "coupler", "rocker", "frame"), lengths):
        if name not in drawn and length < two_r:
            return (f"{name} ({length * 1e3:g} mm) is shorter than two boss radii "
                    f"({two_r * 1e3:g} mm): its bosses would overlap")
    return None


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
    crank, coupler, rocker : float or DrawnLinkSpec
        Link lengths a, b, c, pin to pin [m], or the link as drawn.
    frame : float
        Frame length d, between the fixed pivots [m].
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
        (:mod:`fickcam.elastic`), a drawn link's on its drawn planform with every hole.
    aged_length : {"field", "mean_strain"}
        How a drawn link's aged pin-to-pin length is found: the distance between its pins
        displaced by its moisture field over the drawn planform (``field``,
        :func:`fickcam.linkage.drawn.aged_drawn_length`), or L (1 + eps) of its mean
        moisture (``mean_strain``, as a link given by its length).

    Raises
    ------
    ValueError
        (to pydantic) A linkage that cannot assemble at any crank angle, bosses that
        overlap on a link, or a centre-of-mass fraction outside [0, 1].
    """

    material: str = Field(description="The links' material (a name under materials)")
    frame_material: str | None = Field(
        None, description="The frame's material; default the links' material")
    crank: LinkLength = Field(description="Crank length a, pin to pin, or its drawing [m]")
    coupler: LinkLength = Field(description="Coupler length b, pin to pin, or its drawing [m]")
    rocker: LinkLength = Field(description="Rocker length c, pin to pin, or its drawing [m]")
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
    aged_length: Literal["field", "mean_strain"] = Field(
        "field", description="A drawn link's aged length: its pins moved by its moisture field, "
                             "or L (1 + eps) of its mean")

    @model_validator(mode="after")
    def _is_a_four_bar(self):
        drawn = [name for name in DRAWN_LINKS if isinstance(getattr(self, name), DrawnLinkSpec)]
        if not drawn:  # a drawn link's length is known once its drawing is read
            reason = four_bar_problem((self.crank, self.coupler, self.rocker, self.frame),
                                      self.section.boss_outer_radius)
            if reason:
                raise ValueError(reason)
        if not all(0.0 <= f <= 1.0 for f in self.centre_of_mass):
            raise ValueError("centre_of_mass fractions must lie between 0 and 1")
        return self
