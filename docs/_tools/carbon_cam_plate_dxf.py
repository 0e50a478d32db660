"""Write the example cam plate's drawing, configs/carbon_epoxy_cam_plate.dxf (ezdxf).

The working profile is that of a cam given by its motion (base circle 40 mm, a cycloidal
rise of 12 mm over 100 deg, a dwell of 80 deg, a cycloidal return over 100 deg, a dwell),
written as a closed polyline of 720 points on layer PROFILE, as a CAM export would give it.
The bore (16 mm, for a 16 mm shaft) carries a keyway 5 mm wide and 2.3 mm deep (ISO/DIN
6885 for a 5 x 5 key) at +y: an arc and three lines on layer BORE. Three lightening holes
of 7 mm radius on a 25 mm pitch circle, inside the base circle, sit on layer LIGHTENING
(at 30, 150 and 270 deg, clear of the keyway); the axis is a point on layer AXIS. Units:
mm ($INSUNITS 4).

Run from the repository's root: ``python docs/_tools/carbon_cam_plate_dxf.py``.
"""
from pathlib import Path

import ezdxf
import numpy as np

from fickcam.cam.design import cam_design
from fickcam.cam.kinematics import working_profile

ROOT = Path(__file__).resolve().parents[2]
MOTION = [{"rise": "12 mm", "over": "100 deg", "law": "cycloidal"}, {"dwell": "80 deg"},
          {"return": "12 mm", "over": "100 deg", "law": "cycloidal"}, {"dwell": "80 deg"}]
BORE, KEY_WIDTH, KEY_DEPTH = 8.0, 5.0, 2.3        # mm
HOLE_RADIUS, HOLE_PITCH = 7.0, 25.0                # mm
HOLE_ANGLES = (30.0, 150.0, 270.0)                # deg, clear of the keyway at 90 deg


def profile_mm() -> np.ndarray:
    """The dry working profile's 720 points [mm], counter-clockwise about the axis."""
    design = cam_design({"material": "cfrp", "base_circle_radius": "40 mm",
                         "thickness": "10 mm", "speed": "600 rpm", "motion": MOTION,
                         "follower": {"kind": "roller", "roller_radius": "10 mm",
                                      "mass": "0.5 kg", "spring_rate": "2 N/mm"}})
    x, y = working_profile(design, n=720)
    return np.column_stack([x, y]) * 1e3


def main(path: Path = ROOT / "configs" / "carbon_epoxy_cam_plate.dxf") -> Path:
    document = ezdxf.new("R2010", units=ezdxf.units.MM)
    for layer in ("PROFILE", "BORE", "LIGHTENING", "AXIS"):
        document.layers.add(layer)
    space = document.modelspace()
    space.add_lwpolyline(profile_mm().tolist(), close=True, dxfattribs={"layer": "PROFILE"})
    half = np.degrees(np.arcsin(0.5 * KEY_WIDTH / BORE))
    space.add_arc((0.0, 0.0), BORE, 90.0 + half, 90.0 - half, dxfattribs={"layer": "BORE"})
    edge, top = BORE * np.cos(np.radians(half)), BORE * np.cos(np.radians(half)) + KEY_DEPTH
    corners = [(-0.5 * KEY_WIDTH, edge), (-0.5 * KEY_WIDTH, top), (0.5 * KEY_WIDTH, top),
               (0.5 * KEY_WIDTH, edge)]
    for start, end in zip(corners, corners[1:]):
        space.add_line(start, end, dxfattribs={"layer": "BORE"})
    for angle in np.radians(HOLE_ANGLES):
        centre = (HOLE_PITCH * np.cos(angle), HOLE_PITCH * np.sin(angle))
        space.add_circle(centre, HOLE_RADIUS, dxfattribs={"layer": "LIGHTENING"})
    space.add_point((0.0, 0.0), dxfattribs={"layer": "AXIS"})
    document.saveas(path)
    return path


if __name__ == "__main__":
    print(main())
