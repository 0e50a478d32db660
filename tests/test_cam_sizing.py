"""Cam sizing: the smallest base circle meets the limits and anything smaller does not;
`fickcam size` reports it and the aged check."""
import math
from dataclasses import replace

import pytest

from fickcam.cam import CamDesign
from fickcam.cam.motion import segments_from_spec
from fickcam.cam.sizing import Limits, smallest_base_circle, worst
from fickcam.cam.spec import Segment
from fickcam.cli import main


def design(kind="roller", offset=0.0):
    segments = segments_from_spec([Segment(dwell=math.radians(90)),
                                   Segment(rise=0.02, over=math.radians(90), law="cycloidal"),
                                   Segment(dwell=math.radians(60)),
                                   Segment(**{"return": 0.02}, over=math.radians(120), law="polynomial_345")])
    return CamDesign("motion", 0.05, 0.01, 60.0, kind, 0.5, segments=segments,
                     roller_radius=0.008 if kind == "roller" else 0.0, offset=offset)


@pytest.mark.parametrize("kind, offset, limits", [
    ("roller", 0.0, Limits(math.radians(30), 0.0)),
    ("roller", 0.006, Limits(math.radians(25), 0.004)),
    ("flat", 0.0, Limits(math.radians(30), 0.01)),
])
def test_smallest_base_circle_is_the_boundary_of_the_limits(kind, offset, limits):
    d = design(kind, offset)
    size = smallest_base_circle(d, limits)["base_circle_radius"]
    phi, rho = worst(replace(d, base_circle_radius=size))
    assert phi <= limits.pressure_angle + 1e-12 and rho >= limits.radius_of_curvature and rho > 0
    phi, rho = worst(replace(d, base_circle_radius=size - 2e-6))
    assert phi > limits.pressure_angle or rho < limits.radius_of_curvature or rho <= 0


def test_size_command_reports_the_radius_and_the_aged_check(tmp_path, capsys):
    scene = tmp_path / "cam.yaml"
    scene.write_text("""
name: sized
environment: {history: [{duration: 30 d, temperature: 60 degC, relative_humidity: 50 %}]}
materials: {steel: {metal: steel}}
cam:
  material: steel
  base_circle_radius: 30 mm
  thickness: 10 mm
  speed: 300 rpm
  follower: {kind: roller, roller_radius: 8 mm, mass: 0.5 kg, spring_rate: 2 N/mm, spring_preload: 20 N}
  motion:
    - dwell: 90 deg
    - {rise: 20 mm, over: 90 deg, law: cycloidal}
    - dwell: 60 deg
    - {return: 20 mm, over: 120 deg, law: polynomial_345}
outputs: {ageing_times: [0 d, 30 d], angle_step: 2 deg}
""")
    assert main(["size", str(scene), "--pressure-angle", "30 deg"]) == 0
    out = capsys.readouterr().out
    expected = smallest_base_circle(design(), Limits(math.radians(30), 0.0))["base_circle_radius"]
    assert f"smallest base circle radius {expected * 1e3:.4f} mm" in out
    assert "aged at t = 30 d" in out and "meets the limits" in out
    assert main(["size", str(scene), "--pressure-angle", "30 kg"]) == 2
