"""The dry cam and follower (:class:`~fickcam.cam.design.CamDesign`), their state at one
ageing time (:class:`~fickcam.cam.design.CamState`), and
:func:`~fickcam.cam.design.cam_design`, the dry design of a scene's ``cam:`` section."""
from __future__ import annotations

from dataclasses import dataclass

from . import dynamics as dyn
from .motion import segments_from_spec
from .spec import CamSection
from .arm import Arm
from .drawn import drawn_cam, drawn_profile, with_bore
from .profile import load_profile


@dataclass(frozen=True)
class CamDesign:
    """The dry cam and follower (SI, angles in rad, speed in rad/s).

    Parameters
    ----------
    kind : str
        ``"motion"``, ``"eccentric"`` or ``"profile"``.
    base_circle_radius : float
        Base circle radius Rb [m].
    thickness : float
        Cam plate thickness [m].
    speed : float
        Cam speed [rad/s].
    follower_kind : str
        ``"knife"``, ``"roller"`` or ``"flat"``.
    follower_mass : float
        Follower mass [kg].
    segments : tuple of MotionSegment
        The design motion (kind ``"motion"``).
    eccentricity : float
        Eccentric disc's offset from the axis [m].
    disc_radius : float
        Eccentric disc's radius [m].
    bore_radius : float
        Bore radius [m].
    roller_radius : float
        Roller radius Rf [m].
    offset : float
        Follower offset e from the cam axis [m].
    spring_rate : float
        Return spring rate [N/m].
    spring_preload : float
        Spring force at the lowest dry position [N].
    external_load : float
        Constant load on the follower [N].
    follower_width : float or None
        Follower face width [m]; None: the cam's thickness.
    friction_coefficient : float
        Friction coefficient at the contact [-].
    guide_factor : float
        Guide friction factor G [-] (:func:`fickcam.cam.dynamics.normal_force`).
    gravity : bool
        Add the follower's weight to the load.
    archard_coefficient : float
        Archard wear coefficient [-].
    hardness : float or None
        Hardness of the worn surface [Pa]; None: no wear.
    follower_modulus : float
        Follower's Young's modulus [Pa].
    follower_poisson : float
        Follower's Poisson's ratio [-].
    profile : CamProfile or None
        The cam given by points (kind ``"profile"``).
    train : tuple or None
        The elastic follower train: ``("stiffness", k [N/m])``, ``("rod", L [m], d [m])``
        or ``("lever", L [m], w [m], h [m])``; None: rigid.
    damping_ratio : float
        Damping ratio of the train [-].
    polydyne_speed : float or None
        Design speed of a polydyne cam [rad/s].
    arm : Arm or None
        The swinging arm (:class:`fickcam.cam.arm.Arm`); None: translating follower.
    clockwise : bool
        The cam turns clockwise (computed as its mirror image x -> -x).
    """

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
    follower mass (kg), cam surface-layer modulus/Poisson ratio, follower modulus/Poisson.

    Parameters
    ----------
    cam_strain_x, cam_strain_y : float
        Cam plate's in-plane strains along x (fibre) and y [-].
    roller_strain : float
        Roller's strain [-].
    follower_mass : float or None
        Aged follower mass [kg]; None: the design's.
    cam_surface_modulus : float
        Young's modulus of the cam's wet surface layer [Pa].
    cam_surface_poisson : float
        Its Poisson's ratio [-].
    follower_modulus : float or None
        Aged follower modulus [Pa]; None: the design's.
    follower_poisson : float or None
        Aged follower Poisson's ratio [-]; None: the design's.
    follower_train_modulus : float or None
        Aged modulus of a rod or lever train [Pa]; None: the design's.
    arm_strain : float
        Swinging arm's strain along its length and face offset [-].
    """

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


def cam_design(section, profile=None) -> CamDesign:
    """The dry cam and follower (:class:`CamDesign`) of a validated
    :class:`~fickcam.cam.spec.CamSection` (or the dict of a scene's ``cam:`` section,
    validated here).

    Parameters
    ----------
    section : CamSection or dict
        The validated section, or the dict of a scene's ``cam:`` section (validated here).
    profile : CamProfile, optional
        A cam given by points or drawn: its profile as the scene read it (mirrored for a
        clockwise cam); None: read from ``section.profile_file``, ``section.drawing`` or
        ``section.outline``.

    Returns
    -------
    CamDesign
        The dry design at the reference temperature, in SI.
    """
    if isinstance(section, dict):
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
        sense = 1 if f.arm.rises == "counter_clockwise" else -1
        common["arm"] = Arm(mirror * f.arm.pivot[0], f.arm.pivot[1], f.arm.length or 0.0,
                            f.arm.face_offset, int(mirror) * sense, f.arm.inertia,
                            f.arm.spring_rate, f.arm.spring_preload, f.arm.load_torque)
    if section.drawing is not None or section.outline is not None:
        if profile is None:
            profile = drawn_profile(section, with_bore(drawn_cam(section), section.bore_radius))
        return CamDesign("profile", profile.radii()[0], profile=profile, **common)
    if section.profile_file is not None:
        if profile is None:
            profile = load_profile(section.profile_file, f.roller_radius or 0.0, mirror=mirror < 0)
        return CamDesign("profile", profile.radii()[0], profile=profile, **common)
    if section.eccentric is not None:
        e, r = section.eccentric.eccentricity, section.eccentric.radius
        return CamDesign("eccentric", r - e, eccentricity=e, disc_radius=r, **common)
    return CamDesign("motion", section.base_circle_radius,
                     segments=segments_from_spec(section.motion), **common)
