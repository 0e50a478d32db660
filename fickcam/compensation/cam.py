"""What compensation changes on a cam, in the form the cam was given in.

- ``eccentric``: the disc radius R and the eccentricity e. The disc's centre lies on the
  cam frame's y axis (:func:`fickcam.cam.geometry.dry_profile`), so e grows with the
  in-plane strain along y, eps_T; the radius with the mean in-plane strain
  (eps_L + eps_T)/2, the best single scale of a circle that swells into an ellipse
  (its radius R (1 + eps_L cos^2 phi + eps_T sin^2 phi) to first order).
- ``base_circle_radius`` + ``motion``: the base circle radius and every rise and return
  (lengths), all with (eps_L + eps_T)/2, so the rises still cancel the returns.
- ``profile_file`` (points), and any cam driving a swinging arm: the working profile's
  points, x by 1/(1 + eps_x) and y by 1/(1 + eps_y) (x = the fibre direction). An arm's
  cam is drawn about the arm's pivot, which sits on the frame and does not swell, so
  scaling its parameters would not give its motion back; its points do.

A roller that takes up moisture: its radius with its mean in-plane strain, as
:func:`fickcam.cam.mechanism.cam_state` ages it; a swinging arm: its length (roller) or face
offset (flat) with the follower's strain along it. Cam thickness, bore and the follower's
offset from the cam axis (set by the frame) are left as designed.

A cam that swells anisotropically (a unidirectional laminate: eps_T can be tens of times
eps_L) turns a circle into an ellipse, a distortion no choice of its parameters takes up;
the report says so, and ``points`` (``--points``) makes such a cam as points instead.
"""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np

from ..cam.design import cam_design
from ..cam.kinematics import working_profile
from .core import Target, scene_from
from ..quantities.parsing import to_si
from ..scene.load import CAM_SHAPE_KEYS

#: points of a written compensated profile (0.1 deg apart on average)
PROFILE_POINTS = 3600
PROFILE_NAMES = ("profile x", "profile y")
IN_PLANE = ("strain_longitudinal", "strain_transverse")
#: a swinging arm's dimensions that grow with the follower's strain along it
ARM_NAMES = {"length": "arm length", "face_offset": "arm face offset"}


def _given_by_points(section, points: bool = False) -> bool:
    """True when the made cam is written as points: a profile file, a swinging arm's cam,
    or any cam when ``points`` is asked for."""
    return (points or section.profile_file is not None or section.drawing is not None
            or section.outline is not None or section.follower.arm is not None)


def _segment_name(index: int, segment) -> str:
    return f"{segment.kind} of segment {index + 1}"


def _shape_targets(section, points: bool = False) -> list[Target]:
    """The cam's own dimensions, in the form it was given in (module docstring), or its
    points when ``points`` is asked for."""
    if _given_by_points(section, points):
        x, y = working_profile(cam_design(section), n=PROFILE_POINTS)
        return [Target("cam", PROFILE_NAMES[0], "cam", ("strain_longitudinal",), x),
                Target("cam", PROFILE_NAMES[1], "cam", ("strain_transverse",), y)]
    if section.eccentric is not None:
        return [Target("cam", "disc radius", "cam", IN_PLANE, float(section.eccentric.radius)),
                Target("cam", "eccentricity", "cam", ("strain_transverse",),
                       float(section.eccentric.eccentricity))]
    found = [Target("cam", "base circle radius", "cam", IN_PLANE,
                    float(section.base_circle_radius))]
    for index, segment in enumerate(section.motion):
        if segment.kind != "dwell":
            found.append(Target("cam", _segment_name(index, segment), "cam", IN_PLANE,
                                abs(float(segment.height))))
    return found


def targets(section, points: bool = False, mechanism=None) -> list[Target]:
    """The cam's dimensions (``_shape_targets``) and, for an ageing follower, its roller
    radius and its arm's length or face offset.

    Parameters
    ----------
    section : CamSection
        The design's validated ``cam`` section.
    points : bool
        Compensate the working profile's points (x and y apart) instead of the parameters.
    mechanism : CamMechanism, optional
        The design's cam (unused: its section says all).

    Returns
    -------
    list of Target
        The dimensions, design values [m].
    """
    found = _shape_targets(section, points)
    follower = section.follower
    if follower.kind == "roller" and follower.material:
        found.append(Target("follower", "roller radius", "follower", IN_PLANE,
                            float(follower.roller_radius)))
    arm = follower.arm
    if arm is not None and follower.material:  # grows along its length (fickcam.cam.mechanism)
        key = "length" if follower.kind == "roller" else "face_offset"
        if getattr(arm, key):
            found.append(Target("follower", ARM_NAMES[key], "follower", ("strain_longitudinal",),
                                float(getattr(arm, key))))
    return found


def _by_name(targets, made) -> dict:
    return dict(zip((t.name for t in targets), made))


def profile_path(folder: Path, stem: str) -> Path:
    """Where the made points of a cam given by points go: beside the scene.

    Parameters
    ----------
    folder : pathlib.Path
        The made scene's folder.
    stem : str
        The made scene's file name without suffix.

    Returns
    -------
    pathlib.Path
        ``folder/<stem>_cam_profile.csv``.
    """
    return Path(folder) / f"{stem}_cam_profile.csv"


def _motion(section, segments: list, shape: dict, length_text) -> list:
    """The scene's motion segments with the made rises and returns (to the picometre, so
    that they still cancel), a spline law's distances scaled with its segment's lift."""

    made = copy.deepcopy(segments)
    for index, (given, segment) in enumerate(zip(section.motion, made)):
        name = _segment_name(index, given)
        if name not in shape:
            continue
        segment[given.kind] = length_text(shape[name], digits=9)
        spline = segment.get("spline")
        if spline:
            scale = shape[name] / abs(given.height)
            spline["points"] = [[angle, length_text(to_si(distance, "length") * scale, digits=9)]
                                for angle, distance in spline["points"]]
    return made


def write(data: dict, section, targets, made, stem, length_text) -> np.ndarray | None:
    """Put the made cam into the scene's ``cam:`` mapping (in place; ``section`` is the
    design's validated ``cam``): its parameters, or for a cam given by points the file
    :func:`profile_path` of ``stem`` (the points, returned as an
    (n, 2) array in m, are the caller's to write there); the roller radius and arm.

    Parameters
    ----------
    data : dict
        The made scene's YAML mapping, changed in place.
    section : CamSection
        The design's validated ``cam`` section.
    targets : list of Target
        The dimensions.
    made : list
        Their made values [m].
    stem : pathlib.Path
        The made scene's path without its suffix (relative to its folder, or absolute).
    length_text : callable
        Length [m] -> the text the scene stores.

    Returns
    -------
    numpy.ndarray or None
        The made points, shape (n, 2) [m], or None for a parametric cam.
    """
    cam = data["cam"]
    shape = _by_name(targets, made)
    points = None
    if PROFILE_NAMES[0] in shape:
        points = np.c_[shape[PROFILE_NAMES[0]], shape[PROFILE_NAMES[1]]]
        for key in ("base_circle_radius", "motion", "eccentric", "drawing", "outline", "holes"):
            cam.pop(key, None)
        cam["profile_file"] = str(profile_path(stem.parent, stem.name))
        if section.drawing is not None or section.outline is not None:  # the drawn bore
            cam["bore_radius"] = length_text(section.bore_radius)
    elif "eccentricity" in shape:
        cam["eccentric"] = {"eccentricity": length_text(shape["eccentricity"]),
                            "radius": length_text(shape["disc radius"])}
    else:
        cam["base_circle_radius"] = length_text(shape["base circle radius"])
        cam["motion"] = _motion(section, cam["motion"], shape, length_text)
    follower = dict(cam["follower"])
    if "roller radius" in shape:
        follower["roller_radius"] = length_text(shape["roller radius"])
    arm = {key: length_text(shape[name]) for key, name in ARM_NAMES.items() if name in shape}
    if arm:
        follower["arm"] = dict(follower["arm"]) | arm
    cam["follower"] = follower
    return points


def profile_radii(comp) -> list[tuple]:
    """Table rows of a cam given by points: its smallest and largest radius and extents.

    Parameters
    ----------
    comp : Compensation
        The compensation: design and made profile points [m].

    Returns
    -------
    list of tuple
        (group, name, design [m], made [m]) rows; empty for a parametric cam.
    """
    shape = {t.name: (t.design, m) for t, m in zip(comp.targets, comp.made)
             if t.name in PROFILE_NAMES}
    if len(shape) < 2:
        return []
    (x0, x1), (y0, y1) = shape[PROFILE_NAMES[0]], shape[PROFILE_NAMES[1]]
    r0, r1 = np.hypot(x0, y0), np.hypot(x1, y1)
    return [("cam", "profile: smallest radius", float(r0.min()), float(r1.min())),
            ("cam", "profile: largest radius", float(r0.max()), float(r1.max())),
            ("cam", "profile: extent along x", float(np.ptp(x0)), float(np.ptp(x1))),
            ("cam", "profile: extent along y", float(np.ptp(y0)), float(np.ptp(y1)))]


def design_entry(section: dict, targets) -> dict:
    """The ``design:`` entry of a compensated scene: the design's shape (and roller).

    Parameters
    ----------
    section : dict
        The design scene's ``cam`` mapping.
    targets : list of Target
        The dimensions compensated.

    Returns
    -------
    dict
        The entry, lengths as the scene gives them.
    """

    entry = {key: section[key] for key in CAM_SHAPE_KEYS if key in section}
    names = {t.name for t in targets}
    follower = {"roller_radius": section["follower"]["roller_radius"]} if "roller radius" in names else {}
    arm = {key: section["follower"]["arm"][key] for key, name in ARM_NAMES.items() if name in names}
    if arm:
        follower["arm"] = arm
    if follower:
        entry["follower"] = follower
    return entry


def made_outline(data: dict, base_dir: Path, points: int):
    """(x, y) of the made cam's dry working profile, from the made scene mapping.

    Parameters
    ----------
    data : dict
        The made scene's YAML mapping.
    base_dir : pathlib.Path
        The folder its relative paths start from.
    points : int
        Number of outline points.

    Returns
    -------
    tuple of numpy.ndarray
        x and y [m].
    """
    section = scene_from(data, base_dir, "<compensated scene>").model.cam
    return working_profile(cam_design(section), n=points)


#: a parametric cam's in-plane strains differ by more than this fraction of the larger:
#: the report suggests making it as points
ANISOTROPY = 0.1


def anisotropy_note(comp) -> list[str]:
    """A line when a cam made in its parameters swells anisotropically over the life.

    Parameters
    ----------
    comp : Compensation
        The compensation: its run as designed (in-plane strains [-]).

    Returns
    -------
    list of str
        The line, or nothing.
    """
    if comp.before is None or "cam" not in getattr(comp.before, "part", []) or \
            any(t.name in PROFILE_NAMES for t in comp.targets) or \
            not any(t.group == "cam" for t in comp.targets):
        return []
    along, across = (comp.before[name].sel(part="cam").values for name in IN_PLANE)
    larger = float(np.max(np.maximum(np.abs(along), np.abs(across))))
    apart = float(np.max(np.abs(across - along)))
    if larger == 0.0 or apart <= ANISOTROPY * larger:
        return []
    return [f"the cam swells anisotropically (in-plane strains up to {larger:.3g}, apart by up "
            f"to {apart:.3g}): a parametric cam cannot take up that distortion; --points makes "
            f"it as points instead (x and y compensated apart)"]
