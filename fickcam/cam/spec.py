"""The scene's ``cam:`` section: a plate cam and a translating follower.

Values are parsed to SI by :mod:`fickcam.quantities.types` (angles in rad, speed in rad/s).
Validation refuses what cannot be a cam: motion segments that do not add up to
360 deg or do not return the follower to its start, an unknown motion law, a roller
follower without a roller radius, ``eccentric`` or ``profile_file`` together with ``motion`` or
``base_circle_radius``, a bore that reaches the profile.
"""
from __future__ import annotations

import math
from typing import Annotated, Literal

from ..quantities.types import StrictModel
from .arm_spec import NOT_ON_AN_ARM, SwingingArm, arm_problems
from pydantic import (AfterValidator, BeforeValidator, ConfigDict, Discriminator, Field, PrivateAttr,
                      Tag, field_validator, model_validator)

from ..quantities.types import (Angle, AngularSpeed, Force, Length, Mass, NonNegativeLength, PositiveAngle,
                     Pressure, SignedLength, Stiffness, quantity)
from ..quantities.parsing import is_bare_number, to_si
from .spline import spline_law
from ..drawing.spec import DrawingFile, Hole, Point, drawing_file, plausible_outline

#: follower train stiffness: zero would leave the follower mass unconnected to the cam
PositiveStiffness = quantity("stiffness", positive=True)

#: motion law names -> module-level functions in :mod:`fickcam.cam.motion`
LAWS = ("uniform_velocity", "constant_acceleration", "simple_harmonic", "cycloidal",
        "polynomial_345", "polynomial_4567", "modified_trapezoidal", "modified_sine", "spline")
Law = Literal["uniform_velocity", "constant_acceleration", "simple_harmonic", "cycloidal",
              "polynomial_345", "polynomial_4567", "modified_trapezoidal", "modified_sine", "spline"]

#: tolerance on the sum of the motion segments (rad)
TURN_TOLERANCE = math.radians(1e-6)


def _positive(x: float) -> float:
    if not x > 0:
        raise ValueError("must be positive")
    return x


class _Strict(StrictModel):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


class Spline(_Strict):
    """A ``spline`` law: ``points`` [angle within the segment, distance travelled from its
    start] from [0 deg, 0] to [over, rise/return]; ``degree`` (5: C4 inside); the
    derivatives dS/dx, d2S/dx2, ... of the normalised law at the segment's start and end,
    (degree - 1)/2 each, zero by default (see :mod:`fickcam.cam.spline`).

    Parameters
    ----------
    points : list of tuple
        (angle within the segment [rad], distance travelled from its start [m]) pairs.
    degree : int
        Odd spline degree, 1 to 9.
    start_derivatives, end_derivatives : list of float, optional
        dS/dx, d2S/dx2, ... of the normalised law at the start and end [-].
    """

    points: list[tuple[Angle, SignedLength]] = Field(
        description="(angle in the segment [rad], distance travelled from its start [m]) pairs")
    degree: int = Field(default=5, ge=1, le=9, description="Odd degree of the spline, 1 to 9 [1]")
    start_derivatives: list[float] | None = Field(
        None, description="dS/dx, d2S/dx2, ... of the normalised law at the segment's start [1]")
    end_derivatives: list[float] | None = Field(
        None, description="dS/dx, d2S/dx2, ... of the normalised law at the segment's end [1]")


def _lift(value):
    """A rise or return: a length (translating follower) or an angle (swinging arm), in SI."""
    try:
        return to_si(value, "length")
    except ValueError as length_error:
        try:
            return to_si(value, "angle")
        except ValueError:
            raise length_error from None


def _given_as_angle(value) -> bool | None:
    """True for a value with angle units, False otherwise, None for a bare number."""
    if is_bare_number(value):
        return None
    try:
        to_si(value, "angle")
    except ValueError:
        return False
    return True


Lift = Annotated[float, BeforeValidator(_lift), AfterValidator(_positive)]


class Segment(_Strict):
    """One motion segment: ``{dwell: angle}``, ``{rise: length, over: angle, law: name}``
    or ``{return: length, over: angle, law: name}``; a swinging arm's rise and return are
    angles (``{rise: 15 deg, ...}``; a bare number is m or rad).

    Parameters
    ----------
    dwell : float, optional
        Angle of a dwell [rad].
    rise : float, optional
        Lift of a rise [m] (a swinging arm's: [rad]).
    return_ : float, optional
        Fall of a return (scene key ``return``) [m] (a swinging arm's: [rad]).
    over : float, optional
        Cam angle of a rise or return [rad].
    law : str, optional
        The motion law's name.
    spline : Spline, optional
        The points of a ``spline`` law.
    """

    dwell: PositiveAngle | None = Field(None, description="Cam angle of a dwell [rad]")
    rise: Lift | None = Field(None, description="Lift of a rise (an angle for a swinging arm) [m]")
    return_: Lift | None = Field(
        default=None, alias="return", description="Fall of a return (an angle for a swinging arm) [m]")
    over: PositiveAngle | None = Field(
        None, description="Cam angle over which a rise or return happens [rad]")
    law: Law | None = Field(None, description="The motion law of a rise or return")
    spline: Spline | None = Field(None, description="The points of a spline law")
    _angular: bool | None = PrivateAttr(default=None)

    @model_validator(mode="wrap")
    @classmethod
    def _remember_units(cls, data, handler):
        segment = handler(data)
        if isinstance(data, dict):
            lift = data.get("rise", data.get("return"))
            segment._angular = None if lift is None else _given_as_angle(lift)
        return segment

    @property
    def angular(self) -> bool | None:
        """True: the rise/return was given as an angle; False: a length; None: bare/dwell."""
        return self._angular

    @model_validator(mode="after")
    def _one_kind(self):
        kinds = [k for k in ("dwell", "rise", "return_") if getattr(self, k) is not None]
        if len(kinds) != 1:
            raise ValueError("a segment is exactly one of dwell, rise or return")
        if kinds[0] == "dwell":
            if self.over is not None or self.law is not None:
                raise ValueError("a dwell takes only its angle (no over/law)")
        elif self.over is None or self.law is None:
            raise ValueError("a rise or return needs 'over' (angle) and 'law'")
        if (self.law == "spline") != (self.spline is not None):
            raise ValueError("law: spline goes with spline: {points: ...} (and only it)")
        if self.spline is not None:
            spline_law(self.spline.points, self.height, self.over, self.spline.degree,
                       self.spline.start_derivatives, self.spline.end_derivatives)
        return self

    @property
    def kind(self) -> str:
        return "dwell" if self.dwell is not None else ("rise" if self.rise is not None else "return")

    @property
    def angle(self) -> float:
        return self.dwell if self.dwell is not None else self.over

    @property
    def height(self) -> float:
        """Signed change of follower position over the segment (m)."""
        return {"dwell": 0.0, "rise": self.rise, "return": -(self.return_ or 0.0)}[self.kind]


class Eccentric(_Strict):
    """Circular disc of ``radius`` turning about a point ``eccentricity`` from its centre.

    Parameters
    ----------
    eccentricity : float
        Distance from the disc's centre to the rotation axis [m].
    radius : float
        The disc's radius [m].
    """

    eccentricity: Length = Field(
        description="Distance from the disc's centre to the rotation axis [m]")
    radius: Length = Field(description="Radius of the disc [m]")

    @model_validator(mode="after")
    def _axis_inside(self):
        if self.eccentricity >= self.radius:
            raise ValueError("eccentricity must be smaller than the disc radius")
        return self


class Guide(_Strict):
    """Follower stem in a guide bush (Yadav et al. 2017, cited in full in
    :mod:`fickcam.cam`; Rothbart, Cam Design Handbook 2004, ch. 6):
    ``overhang`` l1 from the contact to the near bush end, bush ``length`` l2, stem
    ``diameter`` d, guide friction coefficient.

    Parameters
    ----------
    friction_coefficient : float
        Friction coefficient in the bush [-].
    overhang : float
        l1, contact to the near bush end [m].
    length : float
        l2, the bush's length [m].
    diameter : float
        d, the stem's diameter [m].
    """

    friction_coefficient: float = Field(
        ge=0.0, le=1.0, description="Friction coefficient in the guide bush [1]")
    overhang: NonNegativeLength = Field(
        description="Distance from the cam contact to the near end of the bush, l1 [m]")
    length: Length = Field(description="Length of the bush, l2 [m]")
    diameter: NonNegativeLength = Field(0.0, description="Diameter of the stem in the bush [m]")


class Wear(_Strict):
    """Archard wear: dimensionless coefficient K and the cam surface hardness H
    (wear depth rate = K/H x pressure x sliding speed).

    Parameters
    ----------
    archard_coefficient : float
        K [-].
    hardness : float
        H [Pa].
    """

    archard_coefficient: float = Field(ge=0.0, description="Archard wear coefficient K [1]")
    hardness: Pressure = Field(description="Hardness H of the worn surface [Pa]")


class Rod(_Strict):
    """A round follower stem loaded along its axis: k = E pi d^2/(4 L).

    Parameters
    ----------
    length : float
        L [m].
    diameter : float
        d [m].
    """

    length: Length = Field(description="Length of the stem [m]")
    diameter: Length = Field(description="Diameter of the stem [m]")


class Lever(_Strict):
    """A cantilever lever loaded at its tip: k = 3 E I/L^3, I = width height^3/12.

    Parameters
    ----------
    length : float
        L [m].
    width : float
        Width [m].
    height : float
        Height, in the direction of the load [m].
    """

    length: Length = Field(description="Length of the lever to the load [m]")
    width: Length = Field(description="Width of the lever [m]")
    height: Length = Field(description="Height of the lever, in the direction of the load [m]")


class TrainSection(_Strict):
    """``follower.stiffness`` given by the follower's geometry: exactly one of ``rod`` or
    ``lever``; E is the follower material's aged longitudinal modulus at each ageing time
    (``follower.modulus`` when the follower has no material).

    Parameters
    ----------
    rod : Rod, optional
        A round stem loaded along its axis.
    lever : Lever, optional
        A cantilever lever loaded at its tip.
    """

    rod: Rod | None = Field(None, description="A round stem loaded along its axis")
    lever: Lever | None = Field(None, description="A cantilever lever loaded at its tip")

    @model_validator(mode="after")
    def _one(self):
        if (self.rod is None) == (self.lever is None):
            raise ValueError("give exactly one of rod: {length, diameter} or "
                             "lever: {length, width, height}")
        return self


#: ``follower.stiffness``: a number with units, or a section (a mapping)
TrainStiffness = Annotated[
    Annotated[TrainSection, Tag("TrainSection")] | Annotated[PositiveStiffness, Tag("Stiffness")],
    Discriminator(lambda v: "TrainSection" if isinstance(v, dict | TrainSection) else "Stiffness")]


class Follower(_Strict):
    """Translating follower. Optional keys (defaults): ``width`` (the cam
    thickness) the contact length for Hertz, ``friction_coefficient`` (0) at the cam
    contact (sliding: knife and flat), ``modulus`` (210 GPa) / ``poisson_ratio`` (0.3)
    used when the follower has no absorbing material, ``guide`` (none). ``stiffness``
    (absent: rigid follower) is the follower train stiffness, N/m or a
    :class:`TrainSection`; ``damping_ratio`` (0.05) its damping (:mod:`fickcam.cam.train`).

    Parameters
    ----------
    kind : {"knife", "roller", "flat"}
        The follower's contact.
    roller_radius : float, optional
        Roller radius [m] (roller only).
    offset : float
        Offset of the follower's axis from the cam axis [m].
    mass : float
        Follower mass [kg].
    material : str, optional
        Material of an absorbing follower (roller or arm).
    spring_rate : float
        Return spring rate [N/m].
    spring_preload : float
        Spring force at the dry cam's lowest position [N].
    external_load : float
        Constant load against the lift [N].
    width : float, optional
        Contact length for Hertz [m]; default the cam's thickness.
    friction_coefficient : float
        Friction coefficient at the cam contact [-].
    modulus : float
        Young's modulus [Pa] when the follower has no absorbing material.
    poisson_ratio : float
        Poisson's ratio [-] then.
    guide : Guide, optional
        The stem's guide bush.
    stiffness : float or TrainSection, optional
        Follower train stiffness [N/m], or the geometry that gives it; absent: rigid.
    damping_ratio : float
        Damping ratio of the train [-].
    arm : SwingingArm, optional
        A swinging arm instead of a translating follower.
    """

    kind: Literal["knife", "roller", "flat"] = Field(
        description="The follower's contact with the cam")
    roller_radius: Length | None = Field(
        None, description="Radius of the roller (roller follower only) [m]")
    offset: SignedLength = Field(
        0.0, description="Offset of the follower's axis from the cam axis [m]")
    mass: Mass = Field(description="Mass of the follower train [kg]")
    material: str | None = Field(
        None, description="Material of an absorbing follower (a name under materials)")
    spring_rate: Stiffness = Field(0.0, description="Rate of the return spring [N/m]")
    spring_preload: Force = Field(
        0.0, description="Spring force at the dry cam's lowest position [N]")
    external_load: Force = Field(0.0, description="Constant load against the lift [N]")
    width: Length | None = Field(
        None, description="Contact length for the Hertz stress; default the cam's thickness [m]")
    friction_coefficient: float = Field(
        default=0.0, ge=0.0, le=1.0, description="Friction coefficient at the cam contact [1]")
    modulus: Pressure = Field(
        210e9, description="Young's modulus of a follower with no absorbing material [Pa]")
    poisson_ratio: float = Field(
        default=0.3, ge=0.0, lt=0.5, description="Poisson's ratio of a follower with no absorbing material [1]")
    guide: Guide | None = Field(None, description="The guide bush of a translating follower's stem")
    stiffness: TrainStiffness | None = Field(
        None, description="Stiffness of the follower train, or the rod or lever that gives it; absent: rigid [N/m]")
    damping_ratio: float = Field(
        default=0.05, ge=0.0, lt=1.0, description="Damping ratio of the follower train [1]")
    arm: SwingingArm | None = Field(
        None, description="A swinging arm instead of a translating follower")

    @model_validator(mode="after")
    def _roller_needs_radius(self):
        if self.kind == "roller" and self.roller_radius is None:
            raise ValueError("a roller follower needs roller_radius")
        if self.kind != "roller" and self.roller_radius is not None:
            raise ValueError(f"roller_radius applies to a roller follower, not {self.kind}")
        if self.arm is not None:
            self._an_arm()
        return self

    def _an_arm(self):
        if self.kind == "knife":
            raise ValueError("a swinging arm carries a roller or a flat face (kind: roller | flat)")
        if self.kind == "roller" and self.arm.length is None:
            raise ValueError("a swinging roller arm needs arm.length (pivot to roller centre)")
        if self.kind == "flat" and self.arm.length is not None:
            raise ValueError("a flat-face arm is placed by arm.face_offset; arm.length is for a roller")
        if self.kind == "roller" and self.arm.face_offset != 0.0:
            raise ValueError("arm.face_offset is for a flat face; a roller arm has arm.length")
        for key, why in NOT_ON_AN_ARM.items():
            if getattr(self, key) not in (None, 0.0):
                raise ValueError(f"{key} does not apply to a swinging arm: {why}")


class Polydyne(_Strict):
    """``cam.polydyne``: cut the cam so that the elastic follower (``follower.stiffness``)
    follows the chosen motion at ``speed`` (default: the cam's speed); ``true`` = {}.

    Parameters
    ----------
    speed : float, optional
        The design speed [rad/s]; default the cam's.
    """

    speed: AngularSpeed | None = Field(
        None, description="Speed the cam is cut for; default the cam's speed [rad/s]")


class Drawing(DrawingFile):
    """A cam plate given by its DXF drawing: ``file`` and ``units`` as in
    :class:`fickcam.drawing.spec.DrawingFile`, and the layer of its axis.

    Parameters
    ----------
    axis_layer : str
        The layer of a point marking the cam's axis of rotation.
    """

    axis_layer: str = Field("AXIS", description="The layer of a point marking the axis of rotation "
                                                "(without one: the centre of the bore)")


class CamSection(_Strict):
    """The ``cam:`` section. Optional keys (defaults): ``gravity`` (false; g along
    the follower axis, against the lift), ``wear`` (none: no Archard wear),
    ``follower.width``, ``follower.friction_coefficient``, ``follower.modulus``,
    ``follower.poisson_ratio``, ``follower.guide`` (see :class:`Follower`); ``elastic``
    (false: no elastic deflection or swelling stress, :mod:`fickcam.elastic`). The cam turns
    at ``speed`` in ``direction`` (counter_clockwise, seen from the front); the follower moves
    along +y at x = offset, or swings about ``follower.arm.pivot``. A clockwise cam is
    computed as its mirror image x -> -x (a counter-clockwise cam seen from the back), and
    profile points are mirrored back on output.

    Parameters
    ----------
    material : str
        The cam plate's material.
    base_circle_radius : float, optional
        Base circle radius [m] (a cam given by its motion).
    thickness : float
        Plate thickness [m].
    bore_radius : float
        Bore radius [m].
    speed : float
        Cam speed [rad/s].
    follower : Follower
        The follower.
    motion : list of Segment, optional
        The design motion over one turn.
    eccentric : Eccentric, optional
        An eccentric disc instead of a motion.
    profile_file : str, optional
        A CSV file of profile points instead of a motion.
    drawing : Drawing, optional
        The plate's DXF drawing instead of a motion.
    outline : list of tuple of float, optional
        The plate's outline (x, y) [m] about the axis instead of a motion: its working
        profile.
    holes : list, optional
        The holes of an ``outline`` [m]: a round hole about the axis is the bore.
    gravity : bool
        Weight of the follower along its axis, against the lift.
    wear : Wear, optional
        Archard wear.
    elastic : bool
        Compute the elastic deflection and swelling stress.
    polydyne : Polydyne, optional
        Cut the cam for the elastic follower.
    direction : {"counter_clockwise", "clockwise"}
        Turning sense, seen from the front.
    aged_profile : {"field", "mean_strain"}
        How a drawn cam's aged working profile is found: its outline displaced by its
        moisture field over the drawn plate (``field``,
        :func:`fickcam.cam.drawn.aged_drawn_designs`), or scaled by (1 + eps) of its mean
        (``mean_strain``); a cam not drawn is always scaled.
    """

    material: str = Field(description="The cam plate's material (a name under materials)")
    base_circle_radius: Length | None = Field(
        None, description="Radius of the base circle of a cam given by its motion [m]")
    thickness: Length = Field(description="Thickness of the cam plate [m]")
    bore_radius: NonNegativeLength = Field(
        0.0, description="Radius of the bore the shaft passes through [m]")
    speed: AngularSpeed = Field(description="Cam speed [rad/s]")
    follower: Follower = Field(description="The follower")
    motion: list[Segment] | None = Field(
        None, description="The design motion over one turn, as dwell, rise and return segments")
    eccentric: Eccentric | None = Field(
        None, description="An eccentric disc cam instead of a motion")
    profile_file: str | None = Field(
        None, description="A CSV file of profile points instead of a motion")
    drawing: Annotated[Drawing | None, BeforeValidator(drawing_file)] = Field(
        None, description="The cam plate's DXF drawing instead of a motion (the dxf extra)")
    outline: list[Point] | None = Field(
        None, min_length=3, description="The plate's outline (x, y) about the axis, its working "
                                        "profile, instead of a motion [m]")
    holes: list[Hole] | None = Field(
        None, description="Holes of the outline, round {centre, radius} or points; the one "
                          "about the axis is the bore [m]")
    gravity: bool = Field(
        False, description="Whether the follower's weight acts along its axis, against the lift")
    wear: Wear | None = Field(None, description="Archard wear of the cam surface")
    elastic: bool = Field(
        False, description="Whether to compute the cam's elastic deflection and swelling stress")
    polydyne: Polydyne | None = Field(
        None, description="Cut the cam so that the elastic follower moves as designed")
    direction: Literal["counter_clockwise", "clockwise"] = Field(
        "counter_clockwise", description="Turning sense of the cam, seen from the front")
    aged_profile: Literal["field", "mean_strain"] = Field(
        "field", description="A drawn cam's aged profile: its outline moved by its moisture "
                             "field, or scaled by (1 + eps) of its mean")

    @field_validator("polydyne", mode="before")
    @classmethod
    def _polydyne_true(cls, value):
        return {} if value is True else (None if value is False else value)

    @field_validator("outline")
    @classmethod
    def _outline_span(cls, value):
        return plausible_outline(value)

    @field_validator("motion")
    @classmethod
    def _closed_turn(cls, value):
        if value is not None:
            _check_motion(value)
        return value

    @model_validator(mode="after")
    def _a_cam(self):
        if self.follower.arm is not None:
            arm_only = {"eccentric": self.eccentric, "polydyne": self.polydyne, "wear": self.wear}
            for key, value in arm_only.items():
                if value is not None:
                    raise ValueError(f"a swinging-arm follower needs a cam given by angular motion "
                                     f"segments (or profile_file), without {key}")
            if self.gravity or self.elastic:
                raise ValueError("gravity and elastic are not modelled for a swinging arm")
        if self.holes is not None and self.outline is None:
            raise ValueError("holes belong to an outline: give outline too")
        if self.profile_file is not None or self.drawing is not None or self.outline is not None:
            given = (self.motion, self.base_circle_radius, self.eccentric, self.profile_file,
                     self.drawing, self.outline)
            if sum(v is not None for v in given) > 1:
                raise ValueError("give one of profile_file, drawing, outline, eccentric or motion "
                                 "with base_circle_radius")
            if self.follower.kind == "flat" and self.follower.offset != 0.0:
                raise ValueError("a flat follower's offset does not change its motion; leave it 0")
            if self.polydyne is not None:
                raise ValueError("polydyne needs motion segments (a cam given by points or a "
                                 "drawing is cut as given)")
            return self  # the bore and offset are checked against the profile when it is read
        if self.eccentric is not None:
            if self.motion is not None or self.base_circle_radius is not None:
                raise ValueError("give either eccentric or motion with base_circle_radius, not both")
            smallest = self.eccentric.radius - self.eccentric.eccentricity
        else:
            if self.motion is None or self.base_circle_radius is None:
                raise ValueError("a cam needs motion and base_circle_radius (or eccentric)")
            smallest = self.base_circle_radius
        if self.polydyne is not None and (self.eccentric is not None or self.follower.stiffness is None):
            raise ValueError("polydyne needs motion segments and follower.stiffness (an elastic train)")
        if self.bore_radius >= smallest:
            raise ValueError(f"bore_radius must be smaller than the base circle ({smallest * 1e3:g} mm)")
        if self.elastic and self.bore_radius <= 0.0:
            raise ValueError("elastic: true needs bore_radius (the cam plate is held at its bore)")
        if self.follower.offset != 0.0 and abs(self.follower.offset) >= smallest + (
                self.follower.roller_radius or 0.0) and self.follower.kind != "flat":
            raise ValueError("follower offset must be smaller than the prime circle radius")
        return self


def _check_motion(segments) -> None:
    """Raise ValueError unless the segments add up to 360 deg and close (rises = returns)."""
    if not segments:
        raise ValueError("motion needs at least one segment")
    total = sum(s.angle for s in segments)
    if abs(total - 2 * math.pi) > TURN_TOLERANCE:
        raise ValueError(f"motion segments add up to {math.degrees(total):.6g} deg, not 360 deg")
    level = sum(s.height for s in segments)
    scale = max(abs(s.height) for s in segments) or 1.0
    if abs(level) > 1e-9 * scale:
        raise ValueError(f"rises and returns do not cancel (the follower ends {level * 1e3:+.6g} mm "
                         f"from where it started)")
    low = 0.0
    position = 0.0
    for s in segments:
        position += s.height
        low = min(low, position)
    if low < -1e-9 * scale:
        raise ValueError("the motion goes below the base circle (a return before its rise)")


__all__ = ["Angle", "CamSection", "Eccentric", "Follower", "Guide", "LAWS", "Lever", "Rod", "Segment",
           "SwingingArm", "TrainSection", "Wear", "arm_problems"]
