"""What compensation changes on a cam: the working profile, x by 1/(1 + eps_x) and y by
1/(1 + eps_y) (x = the fibre direction; seeds/000_c9d2754e3bf549ac.txt Table 15's
eps_L, eps_T differ by a factor of ~10 for carbon/epoxy), so a compensated cam is given by
its points (``cam.profile_file``), and the roller radius by 1/(1 + (eps_L + eps_T)/2)
(the roller's mean in-plane strain, as :func:`fickcam.cam.ageing.cam_state` ages it).
Cam thickness and bore are left as designed."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..cam.design import design_from_scene
from ..cam.kinematics import working_profile
from ..cam.profile import write_profile_csv, write_profile_dxf
from .core import Target

#: points of a written compensated profile (0.1 deg apart on average)
PROFILE_POINTS = 3600
PROFILE_NAMES = ("profile x", "profile y")
#: a swinging arm's dimensions that grow with the follower's strain along it
ARM_NAMES = {"length": "arm length", "face_offset": "arm face offset"}


def targets(section, base_dir: Path) -> list[Target]:
    """Working-profile x and y (arrays) and, for an ageing roller, its radius."""
    x, y = working_profile(design_from_scene(section), n=PROFILE_POINTS)
    found = [Target("cam", PROFILE_NAMES[0], "cam", ("strain_longitudinal",), x),
             Target("cam", PROFILE_NAMES[1], "cam", ("strain_transverse",), y)]
    follower = section.follower
    if follower.kind == "roller" and follower.material:
        found.append(Target("follower", "roller radius", "follower",
                            ("strain_longitudinal", "strain_transverse"),
                            float(follower.roller_radius)))
    arm = follower.arm
    if arm is not None and follower.material:  # grows along its length (fickcam.cam.ageing)
        key = "length" if follower.kind == "roller" else "face_offset"
        if getattr(arm, key):
            found.append(Target("follower", ARM_NAMES[key], "follower", ("strain_longitudinal",),
                                float(getattr(arm, key))))
    return found


def _by_name(targets, made) -> dict:
    return dict(zip((t.name for t in targets), made))


def profile_path(folder: Path, stem: str) -> Path:
    return Path(folder) / f"{stem}_cam_profile.csv"


def write(data: dict, targets, made, folder: Path, stem: str) -> None:
    """Write the made profile as CSV and point the scene's ``cam:`` mapping at it."""
    cam = data["cam"]
    shape = _by_name(targets, made)
    path = write_profile_csv(profile_path(folder, stem), shape[PROFILE_NAMES[0]],
                             shape[PROFILE_NAMES[1]])
    for key in ("base_circle_radius", "motion", "eccentric"):
        cam.pop(key, None)
    cam["profile_file"] = str(path.resolve())
    follower = dict(cam["follower"])
    if "roller radius" in shape:
        follower["roller_radius"] = f"{shape['roller radius'] * 1e3:.6f} mm"
    arm = {key: f"{shape[name] * 1e3:.6f} mm" for key, name in ARM_NAMES.items() if name in shape}
    if arm:
        follower["arm"] = dict(follower["arm"]) | arm
    cam["follower"] = follower


def write_dxf(targets, made, path: Path) -> Path:
    """The made profile as DXF, for manufacture."""
    shape = _by_name(targets, made)
    return write_profile_dxf(path, shape[PROFILE_NAMES[0]], shape[PROFILE_NAMES[1]])


def profile_radii(comp) -> list[tuple]:
    """Table rows: the smallest (base circle) and largest radius of the profile."""
    shape = {t.name: (t.design, m) for t, m in zip(comp.targets, comp.made)
             if t.name in PROFILE_NAMES}
    if len(shape) < 2:
        return []
    (x0, x1), (y0, y1) = shape[PROFILE_NAMES[0]], shape[PROFILE_NAMES[1]]
    r0, r1 = np.hypot(x0, y0), np.hypot(x1, y1)
    return [("cam", "base circle radius (smallest)", float(r0.min()), float(r1.min())),
            ("cam", "largest radius", float(r0.max()), float(r1.max())),
            ("cam", "profile extent along x", float(np.ptp(x0)), float(np.ptp(x1))),
            ("cam", "profile extent along y", float(np.ptp(y0)), float(np.ptp(y1)))]


def design_entry(section: dict, targets) -> dict:
    """The ``design:`` entry of a compensated scene: the design's shape (and roller)."""
    from ..scene import CAM_SHAPE_KEYS

    entry = {key: section[key] for key in CAM_SHAPE_KEYS if key in section}
    names = {t.name for t in targets}
    follower = {"roller_radius": section["follower"]["roller_radius"]} if "roller radius" in names else {}
    arm = {key: section["follower"]["arm"][key] for key, name in ARM_NAMES.items() if name in names}
    if arm:
        follower["arm"] = arm
    if follower:
        entry["follower"] = follower
    return entry
