"""The spline motion law: exact S/V/A/J from the B-spline's derivatives, a quintic
spline through the 3-4-5 boundary conditions is the 3-4-5 polynomial, scene input."""
import math

import numpy as np
import pytest
import yaml

from fickcam.cam import motion
from fickcam.cam.spec import CamSection, Segment
from fickcam.cam.spline import bspline, spline_law, spline_motion

X = np.linspace(0.0, 1.0, 201)


@pytest.mark.parametrize("inner", [[], [0.2, 0.5, 0.7], [0.1, 0.35, 0.4, 0.9]])
def test_quintic_spline_through_345_points_reproduces_polynomial_345(inner):
    """A polynomial is a spline: the quintic spline with S' = S'' = 0 at both ends through
    any points of the 3-4-5 law is the 3-4-5 law, and so are its derivatives."""
    h, span = 0.012, math.radians(80)
    x = np.array([0.0, *inner, 1.0])
    s = motion.polynomial_345(x)[0]
    law = spline_law(list(zip(x * span, s * h)), h, span, 5)
    for k, (a, b) in enumerate(zip(spline_motion(law, X), motion.polynomial_345(X))):
        assert np.max(np.abs(a - b)) <= 1e-9 * np.max(np.abs(b)), k


def test_spline_segment_gives_the_same_follower_motion_as_polynomial_345():
    span = math.radians(90)
    points = [(0.0, 0.0), (span / 3, 0.01 * float(motion.polynomial_345(1 / 3)[0])), (span, 0.01)]
    segments = {law: motion.segments_from_spec(
        [Segment(dwell=math.radians(90)),
         Segment(rise=0.01, over=span, law=law, spline={"points": points} if law == "spline" else None),
         Segment(dwell=math.radians(90)),
         Segment(**{"return": 0.01}, over=span, law="cycloidal")]) for law in ("spline", "polynomial_345")}
    theta = np.radians(np.arange(0, 360, 0.5))
    for a, b in zip(motion.follower_motion(segments["spline"], theta),
                    motion.follower_motion(segments["polynomial_345"], theta)):
        assert np.max(np.abs(a - b)) <= 1e-9 * np.max(np.abs(b))
    assert motion.joint_notices(segments["spline"]) == []


def test_spline_derivatives_match_central_differences():
    """Each derivative against the central difference of the one below it, (f(x+h) -
    f(x-h))/2h, error ~ h^2 f'''/6 (degree 7: smooth enough for three differences)."""
    law = spline_law([(0, 0), (0.3, 0.002), (0.8, 0.009), (1.2, 0.01)], 0.01, 1.2, 7)
    h = 1e-4
    inside = X[1:-1]
    up, down = spline_motion(law, inside + h), spline_motion(law, inside - h)
    exact = spline_motion(law, inside)
    curve = bspline(law)
    for k in range(3):
        central = (up[k] - down[k]) / (2 * h)
        truncation = h ** 2 / 6 * np.max(np.abs(curve.derivative(k + 3)(X)))
        roundoff = 1e-15 * np.max(np.abs(exact[k])) / h
        assert np.max(np.abs(central - exact[k + 1])) < 1.01 * truncation + roundoff, k
    assert spline_motion(law, np.array([0.0, 1.0]))[0] == pytest.approx([0.0, 1.0], abs=1e-14)


def test_cubic_spline_warns_of_its_acceleration_steps():
    seg = Segment(rise=0.01, over=math.radians(180), law="spline",
                  spline={"points": [[0, 0], ["90 deg", "6 mm"], ["180 deg", "10 mm"]], "degree": 3})
    segments = motion.segments_from_spec([seg, Segment(**{"return": 0.01}, over=math.radians(180),
                                                       law="cycloidal")])
    assert any("degree-3 spline" in n for n in motion.joint_notices(segments))


@pytest.mark.parametrize("spline, message", [
    ({"points": [[0, 0], ["40 deg", "5 mm"]]}, "last spline point"),
    ({"points": [[0, 0], ["50 deg", "5 mm"], ["40 deg", "8 mm"], ["90 deg", "10 mm"]]}, "increasing"),
    ({"points": [[0, 0], ["90 deg", "10 mm"]], "degree": 4}, "odd"),
    ({"points": [[0, 0], ["90 deg", "10 mm"]], "end_derivatives": [0]}, "end derivative"),
])
def test_bad_spline_is_refused(spline, message):
    with pytest.raises(ValueError, match=message):
        Segment(rise="10 mm", over="90 deg", law="spline", spline=spline)


def test_scene_spline_segment_parses_with_units():
    section = yaml.safe_load("""
material: steel
base_circle_radius: 30 mm
thickness: 10 mm
speed: 600 rpm
follower: {kind: roller, roller_radius: 8 mm, mass: 0.5 kg}
motion:
  - dwell: 90 deg
  - rise: 10 mm
    over: 90 deg
    law: spline
    spline: {points: [[0 deg, 0 mm], [45 deg, 5 mm], [90 deg, 10 mm]], degree: 5}
  - dwell: 90 deg
  - {return: 10 mm, over: 90 deg, law: polynomial_345}
""")
    cam = CamSection.model_validate(section)
    seg = motion.segments_from_spec(cam.motion)[1]
    assert seg.spline.x == (0.0, 0.5, 1.0) and seg.spline.s == pytest.approx((0.0, 0.5, 1.0))
