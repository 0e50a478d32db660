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
- ``drawing`` or ``outline`` (a drawn plate): the vertices of its drawn outline, about the
  axis, made so that they age onto the drawn ones. Where its aged profile is its outline
  displaced by its moisture field (``aged_profile: field``, the default), a vertex D ages
  from the made m to (1 + eps) m + s, s the displacement of the field's unevenness on
  the made plate (:func:`fickcam.cam.drawn.outline_shifts`), and m = (D - s) / (1 + eps):
  the outline pre-distorted by minus that displacement, found with the rest of the fixed
  point (:mod:`fickcam.compensation.core`). The made plate is written as a drawing
  (:mod:`fickcam.compensation.drawn`) or, for an outline written in the scene, as its
  ``outline:`` and ``holes:``, which the made scene gives; the bore (with its keyway) is
  kept as drawn, and the other holes are scaled about the axis with the made outline.

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
from ..cam.drawn import CHORD_SHARE, DEFAULT_ACCURACY, outline_shifts
from ..cam.kinematics import working_profile
from .core import OUTLINE_SHIFT, OUTLINE_VERTEX, PROFILE_NAMES, Target, scene_from
from .drawn import ANISOTROPY, best_scales, made_cam_writer, made_outline_holes
from ..quantities.parsing import to_si
from ..scene.load import CAM_SHAPE_KEYS

#: points of a written compensated profile (0.1 deg apart on average)
PROFILE_POINTS = 3600
IN_PLANE = ("strain_longitudinal", "strain_transverse")
#: a swinging arm's dimensions that grow with the follower's strain along it
ARM_NAMES = {"length": "arm length", "face_offset": "arm face offset"}


def drawn(section) -> bool:
    """True for a drawn plate: a cam given by its ``drawing`` or its ``outline``."""
    return section.drawing is not None or section.outline is not None


def _given_by_points(section, points: bool = False) -> bool:
    """True when the made cam is written as points: a profile file, a swinging arm's cam,
    or any cam when ``points`` is asked for."""
    return (points or section.profile_file is not None or section.follower.arm is not None)


def _outline_targets(section, planform) -> list[Target]:
    """A drawn plate's outline vertices about the axis (module docstring), shifted by the
    field's unevenness where its aged profile is its displaced outline."""
    x, y = planform.outer.points.T
    field = section.aged_profile == "field"
    return [Target("cam", name, "cam", (strain,), np.array(values), shifted=axis if field else -1)
            for axis, (name, strain, values) in enumerate(zip(PROFILE_NAMES, IN_PLANE, (x, y)))]


def _segment_name(index: int, segment) -> str:
    return f"{segment.kind} of segment {index + 1}"


def _shape_targets(section, points: bool = False, planform=None) -> list[Target]:
    """The cam's own dimensions, in the form it was given in (module docstring), or its
    points when ``points`` is asked for; a drawn plate's outline (``planform``, about the
    axis)."""
    if planform is not None:
        return _outline_targets(section, planform)
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
        The design's cam (a drawn plate's outline, about the axis [m]).

    Returns
    -------
    list of Target
        The dimensions, design values [m].
    """
    planform = getattr(mechanism, "planform", None) if drawn(section) else None
    found = _shape_targets(section, points, planform)
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
    (n, 2) array in m, are the caller's to write there), or for a drawn plate its made
    drawing :func:`drawing_path` of ``stem`` (:func:`made_drawings` writes it) or its made
    ``outline:`` and ``holes:``; the roller radius and arm.

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
        The made points, shape (n, 2) [m] (a drawn plate's outline, about the axis), or
        None for a parametric cam.
    """
    cam = data["cam"]
    shape = _by_name(targets, made)
    points = None
    if PROFILE_NAMES[0] in shape:
        points = np.c_[shape[PROFILE_NAMES[0]], shape[PROFILE_NAMES[1]]]
    if drawn(section):
        _made_plate(cam, section, targets, points, stem, length_text)
    elif points is not None:
        for key in ("base_circle_radius", "motion", "eccentric"):
            cam.pop(key, None)
        cam["profile_file"] = str(profile_path(stem.parent, stem.name))
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


def drawing_path(stem: Path) -> Path:
    """Where a drawn cam's made drawing goes: ``<stem>_cam.dxf``.

    Parameters
    ----------
    stem : pathlib.Path
        The made scene's path without its suffix (relative to its folder, or absolute).

    Returns
    -------
    pathlib.Path
        The drawing's path, as ``stem`` is (relative or absolute).
    """
    return stem.with_name(f"{stem.name}_cam.dxf")


def _made_plate(cam: dict, section, targets, points, stem: Path, length_text) -> None:
    """A drawn plate's made shape in the scene's ``cam:`` mapping (in place): its made
    drawing named, or its outline and holes written (module docstring)."""
    if section.drawing is not None:
        given = cam["drawing"]
        cam["drawing"] = {**({"file": given} if isinstance(given, str) else given),
                          "file": str(drawing_path(stem))}
        return
    design = np.column_stack([t.design for t in targets if t.name in PROFILE_NAMES])
    scales = best_scales(design, points)
    extent = max(max(abs(v) for v in point) for point in section.outline)
    holes = made_outline_holes(section, scales, CHORD_SHARE * DEFAULT_ACCURACY * extent)

    def text(values):
        return [length_text(float(v), digits=9) for v in values]
    cam["outline"] = [text(point) for point in points]
    cam["holes"] = [{"centre": text(hole[0]), "radius": text([hole[1]])[0]}
                    if isinstance(hole, tuple) else [text(point) for point in hole]
                    for hole in holes]


def made_drawings(scene, targets: list[Target], made: list, stem: Path) -> dict:
    """The made drawing of the design's drawn cam: path -> writer (``tmp path -> None``).

    Parameters
    ----------
    scene : Scene
        The design scene (its ``cam`` section with the drawing's path absolute, and its
        accuracy).
    targets : list of Target
        The dimensions.
    made : list
        Their made values [m].
    stem : pathlib.Path
        The made scene's path without its suffix; the drawing is :func:`drawing_path` of it.

    Returns
    -------
    dict
        The drawing's path -> its writer; empty without a drawn cam.
    """
    if not scene.has("cam") or scene.model.cam.drawing is None:
        return {}
    shape = _by_name(targets, made)
    design = np.column_stack([t.design for t in targets if t.name in PROFILE_NAMES])
    points = np.column_stack([shape[name] for name in PROFILE_NAMES])
    return {drawing_path(stem): made_cam_writer(scene.model.cam, scene.model.diffusion.accuracy,
                                                design, points)}


def outline_shift_values(scene, histories: list) -> dict:
    """A drawn cam's ``OUTLINE_SHIFT`` and ``OUTLINE_VERTEX`` in a compensation's part
    states (:func:`fickcam.compensation.core.target_shifts`): the displacement of its
    moisture field's unevenness at its outline's vertices, about the axis.

    Parameters
    ----------
    scene : Scene
        The scene run (its cam's drawn plate).
    histories : list of PartHistory
        The parts' ageing, with their sheets (the cam's fields kept).

    Returns
    -------
    dict
        Variable name -> (dimensions, values [m]); empty where the cam holds no field.
    """
    planform = scene.mechanism("cam").planform
    history = next(h for h in histories if h.part.name == "cam")
    shifts = outline_shifts(planform, history)
    if shifts is None:
        return {}
    return {OUTLINE_SHIFT: (("time", "vertex", "axis"), shifts),
            OUTLINE_VERTEX: (("vertex", "axis"), np.array(planform.outer.points))}


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
