"""Motion laws: closed forms against numerical differentiation, the known peak
coefficients, continuity at joints, monotone rise, joint warnings, scene validation."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pydantic import ValidationError

from fickcam.cam.motion import (LAW_FUNCTIONS, follower_motion, joint_notices, segments_from_spec,
                                time_derivatives)
from fickcam.cam.spec import LAWS, CamSection, Segment
from tolerance import roundoff

LAW_NAMES = sorted(LAW_FUNCTIONS)

# peak |S''| of the normalised laws (Norton, Design of Machinery 5th ed., Table 8-2)
PEAK_ACCELERATION = {"constant_acceleration": 4.0, "simple_harmonic": math.pi ** 2 / 2,
                     "cycloidal": 2 * math.pi, "polynomial_345": 5.7735, "polynomial_4567": 7.5132,
                     "modified_trapezoidal": 4.8881, "modified_sine": 5.5280}


def test_every_scene_law_has_a_function():
    assert set(LAWS) == set(LAW_FUNCTIONS) | {"spline"}  # spline: fickcam.cam.spline


@pytest.mark.parametrize("law", LAW_NAMES)
def test_law_starts_at_zero_ends_at_one(law):
    s = LAW_FUNCTIONS[law](np.array([0.0, 1.0]))[0]
    assert s == pytest.approx([0.0, 1.0], abs=roundoff(1.0))


@pytest.mark.parametrize("law", LAW_NAMES)
def test_law_derivatives_match_numerical_differentiation(law):
    f = LAW_FUNCTIONS[law]
    x = np.linspace(0.01, 0.99, 197)
    # keep away from the piecewise laws' breakpoints (derivatives jump there)
    x = x[np.min(np.abs(x[:, None] - np.arange(1, 8)[None, :] / 8), axis=1) > 2e-3]
    h = 1e-5
    for k in range(3):
        numeric = (f(x + h)[k] - f(x - h)[k]) / (2 * h)
        assert np.allclose(f(x)[k + 1], numeric, rtol=1e-6, atol=1e-5), (law, k)


@pytest.mark.parametrize("law", sorted(PEAK_ACCELERATION))
def test_peak_acceleration_coefficients_match_norton_table_8_2(law):
    a = LAW_FUNCTIONS[law](np.linspace(0, 1, 200001))[2]
    assert np.max(np.abs(a)) == pytest.approx(PEAK_ACCELERATION[law], rel=2e-4)


def _motion(law, rise_deg=90.0, dwell_deg=90.0, lift=0.02):
    return segments_from_spec([Segment(dwell=math.radians(dwell_deg)),
                               Segment(rise=lift, over=math.radians(rise_deg), law=law),
                               Segment(dwell=math.radians(360 - 2 * rise_deg - dwell_deg)),
                               Segment(**{"return": lift}, over=math.radians(rise_deg), law=law)])


@pytest.mark.parametrize("law", LAW_NAMES)
def test_time_derivatives_are_derivatives_of_displacement_in_time(law):
    omega = 40.0
    segments = _motion(law)
    t = np.linspace(0.1, 2 * math.pi - 0.1, 301) / omega
    t = t[np.min(np.abs(np.mod(t * omega, 2 * math.pi)[:, None] -
                        np.radians([90, 180, 180.0 - 90 / 2, 90 + 45, 270, 315])), axis=1) > 0.02]
    h = 1e-6
    exact = time_derivatives(follower_motion(segments, omega * t), omega)
    for k in range(3):
        ahead = time_derivatives(follower_motion(segments, omega * (t + h)), omega)[k]
        behind = time_derivatives(follower_motion(segments, omega * (t - h)), omega)[k]
        scale = np.max(np.abs(exact[k + 1])) or 1.0
        assert np.allclose(exact[k + 1], (ahead - behind) / (2 * h), atol=1e-5 * scale), (law, k)


@settings(max_examples=40, deadline=None)
@given(law=st.sampled_from(LAW_NAMES), rise=st.floats(20, 170), dwell=st.floats(1, 170),
       lift=st.floats(1e-4, 0.1))
def test_rise_is_monotone_and_displacement_velocity_are_continuous(law, rise, dwell, lift):
    if 2 * rise + dwell >= 359:
        return
    segments = _motion(law, rise, dwell, lift)
    theta = np.linspace(0, 2 * math.pi, 4001)
    y = follower_motion(segments, theta)[0]
    on_rise = (theta >= math.radians(dwell)) & (theta <= math.radians(dwell + rise))
    assert np.all(np.diff(y[on_rise]) >= -1e-15 * lift)
    assert y.min() >= -1e-12 * lift and y.max() <= lift * (1 + 1e-12)
    for s in segments:
        joint = np.array([s.start])
        before = follower_motion(segments, joint - 1e-9)
        after = follower_motion(segments, joint)
        assert after[0][0] == pytest.approx(before[0][0], abs=1e-7 * lift)
        if law != "uniform_velocity":  # the only law with a velocity step at a dwell
            assert after[1][0] == pytest.approx(before[1][0], abs=1e-6 * lift)


@pytest.mark.parametrize("law, warns", [("simple_harmonic", "acceleration jumps"),
                                        ("uniform_velocity", "velocity jumps"),
                                        ("constant_acceleration", "mid-segment"),
                                        ("cycloidal", None), ("polynomial_345", None),
                                        ("polynomial_4567", None), ("modified_sine", None),
                                        ("modified_trapezoidal", None)])
def test_infinite_jerk_at_a_joint_is_warned_not_failed(law, warns):
    notices = joint_notices(_motion(law))
    if warns is None:
        assert notices == []
    else:
        assert any(warns in n for n in notices)


SCENE_CAM = {"material": "cfrp", "base_circle_radius": "40 mm", "thickness": "10 mm",
             "speed": "300 rpm",
             "follower": {"kind": "roller", "roller_radius": "10 mm", "mass": "0.5 kg",
                          "spring_rate": "2 N/mm"},
             "motion": [{"dwell": "90 deg"}, {"rise": "10 mm", "over": "90 deg", "law": "cycloidal"},
                        {"dwell": "90 deg"}, {"return": "10 mm", "over": "90 deg", "law": "cycloidal"}]}


def _with(**changes):
    cam = {**SCENE_CAM, **changes}
    return cam


@pytest.mark.parametrize("cam, fragment", [
    (_with(motion=SCENE_CAM["motion"][:3]), "360"),
    (_with(motion=[{"dwell": "90 deg"}, {"rise": "10 mm", "over": "90 deg", "law": "cycloidal"},
                   {"dwell": "90 deg"}, {"return": "5 mm", "over": "90 deg", "law": "cycloidal"}]),
     "cancel"),
    (_with(motion=[{"rise": "10 mm", "over": "180 deg", "law": "wobbly"},
                   {"return": "10 mm", "over": "180 deg", "law": "cycloidal"}]), "law"),
    (_with(follower={"kind": "roller", "mass": "1 kg"}), "roller_radius"),
    (_with(eccentric={"eccentricity": "4 mm", "radius": "23 mm"}), "either"),
    (_with(bore_radius="45 mm"), "bore"),
])
def test_scene_section_refuses_what_cannot_be_a_cam(cam, fragment):
    with pytest.raises(ValidationError) as caught:
        CamSection.model_validate(cam)
    assert fragment in str(caught.value)


def test_scene_section_parses_units_to_si():
    cam = CamSection.model_validate(SCENE_CAM)
    assert cam.speed == pytest.approx(10 * math.pi)
    assert cam.follower.spring_rate == pytest.approx(2000.0)
    assert cam.motion[3].height == pytest.approx(-0.01)
    eccentric = CamSection.model_validate({**{k: v for k, v in SCENE_CAM.items()
                                              if k not in ("motion", "base_circle_radius")},
                                           "eccentric": {"eccentricity": "4 mm", "radius": "23 mm"}})
    assert eccentric.eccentric.eccentricity == pytest.approx(0.004)
