"""Aged geometry, Newton along the follower axis, power balance, jump speed, Hertz
contact, the geometric (anisotropic) path against the exact scaled solution."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.cam import CamDesign, CamState, cam_response, working_profile
from fickcam.cam import dynamics as dyn
from fickcam.cam.geometry import geometric_motion, pieces_of
from fickcam.cam.kinematics import dry_lowest_height, follower_heights
from fickcam.cam.motion import follower_motion, segments_from_spec
from fickcam.cam.spec import Segment
from fickcam.materials.bodies import polygon_section
from tolerance import roundoff

THETA = np.radians(np.arange(0.0, 360.0, 0.5))


def design(kind="roller", law="polynomial_345", offset=0.0, **extra):
    segments = segments_from_spec([Segment(dwell=math.radians(60)),
                                   Segment(rise=0.015, over=math.radians(120), law=law),
                                   Segment(dwell=math.radians(40)),
                                   Segment(**{"return": 0.015}, over=math.radians(140), law=law)])
    values = dict(segments=segments, roller_radius=0.012 if kind == "roller" else 0.0,
                  offset=offset, spring_rate=3000.0, spring_preload=40.0, external_load=25.0,
                  gravity=True)
    values.update(extra)
    return CamDesign("motion", 0.05, 0.01, 60.0, kind, 0.8, **values)


STATE = CamState(cam_surface_modulus=5e9, cam_surface_poisson=0.35)


@pytest.mark.parametrize("kind, offset", [("roller", 0.0), ("roller", 0.008), ("knife", 0.005),
                                          ("flat", 0.01)])
def test_dry_follower_reproduces_the_design_motion(kind, offset):
    r = cam_response(design(kind, offset=offset), STATE, THETA).variables
    y, d1, d2, d3 = follower_motion(design(kind).segments, THETA)
    # closed form: equal up to the round-off of the heights (about base radius + lift)
    np.testing.assert_allclose(r["follower_displacement"], y, rtol=0, atol=roundoff(0.05 + y))
    np.testing.assert_allclose(r["follower_velocity"], 60 * d1, rtol=0, atol=roundoff(60 * d1))
    np.testing.assert_allclose(r["follower_jerk"], 60 ** 3 * d3, rtol=0,
                               atol=roundoff(60 ** 3 * d3))


@pytest.mark.parametrize("kind, offset", [("roller", 0.008), ("knife", 0.005), ("flat", 0.0)])
def test_geometric_path_matches_closed_form_when_the_cam_is_dry(kind, offset):
    d = design(kind, offset=offset)
    exact, (low, _) = follower_heights(d, CamState(), THETA)
    geometric, (low_g, _) = geometric_motion(d, pieces_of(d), 0.0, 0.0, d.roller_radius, THETA)
    for k, (a, b) in enumerate(zip(exact, geometric)):
        assert np.allclose(a, b, rtol=0, atol=1e-9 * 10 ** (2 * k) * np.max(np.abs(a))), k
    assert low_g == pytest.approx(low, abs=1e-9 * low)  # the k = 0 spectral bound above


@settings(max_examples=15, deadline=None)
@given(eps=st.floats(-2e-3, 2e-2), kind=st.sampled_from(["roller", "knife", "flat"]))
def test_geometric_path_matches_exact_scaling_for_isotropic_swelling(eps, kind):
    """An isotropic cam (and a roller that swells like it) gives the design motion times
    (1 + eps); the geometric path, which knows only the distorted outline, agrees."""
    d = design(kind)
    state = CamState(eps, eps, eps if kind == "roller" else 0.0)
    exact, low = follower_heights(d, state, THETA)
    geometric, low_g = geometric_motion(d, pieces_of(d), eps, eps, d.roller_radius * (1 + eps), THETA)
    assert low_g == pytest.approx(low, rel=1e-12)  # lowest and highest: lift scales exactly
    for k, (a, b) in enumerate(zip(exact, geometric)):
        assert np.allclose(a, b, rtol=0, atol=1e-9 * 10 ** (2 * k) * np.max(np.abs(a))), k


def test_anisotropic_swelling_distorts_the_motion_between_the_two_scalings():
    d = design("roller")
    wet = cam_response(d, CamState(1e-3, 2e-2, 1e-3, cam_surface_modulus=5e9), THETA).variables
    # the base circle becomes an ellipse (semi-axes Rb (1 + eps_x), Rb (1 + eps_y)): the dwells
    # are no longer dwells and the lift gains part of the ovality
    assert 0.015 * 1.001 < wet["lift"] < (0.015 + 0.05) * 1.02 - 0.05 * 1.001
    y = wet["follower_displacement"]
    dwell = THETA < math.radians(60)
    assert np.ptp(y[dwell]) > 1e-5
    assert 0.0 <= y.min() < 1e-7  # the lowest point now lies between sampled angles
    assert np.all(np.isfinite(wet["follower_jerk"]))
    # the velocity is the derivative of the displacement (periodic, central differences)
    h = THETA[1] - THETA[0]
    numeric = (np.roll(y, -1) - np.roll(y, 1)) / (2 * h) * 60.0
    assert np.allclose(wet["follower_velocity"], numeric, atol=2e-3 * np.max(np.abs(numeric)))


@pytest.mark.parametrize("kind, offset", [("roller", 0.0), ("roller", -0.006), ("knife", 0.004),
                                          ("flat", 0.0)])
@pytest.mark.parametrize("strains", [(0.0, 0.0, 0.0), (0.004, 0.012, 0.002)])
def test_newton_along_the_follower_axis(kind, offset, strains):
    """Fn cos(phi) - k x - F0 - P - m g = m a at every angle (no guide friction)."""
    d = design(kind, offset=offset)
    state = CamState(*strains, follower_mass=0.85, cam_surface_modulus=5e9)
    r = cam_response(d, state, THETA).variables
    dry_floor = follower_heights(d, CamState(), THETA)[1][0]
    height = follower_heights(d, state, THETA)[0][0]
    net = (r["contact_force"] * np.cos(r["pressure_angle"]) - 3000.0 * (height - dry_floor) - 40.0
           - 25.0 - 0.85 * dyn.STANDARD_GRAVITY)
    assert np.allclose(net, 0.85 * r["follower_acceleration"], atol=1e-9 * np.max(r["contact_force"]))


@pytest.mark.parametrize("kind, offset", [("roller", 0.0), ("roller", 0.009), ("knife", -0.004),
                                          ("flat", 0.003)])
@pytest.mark.parametrize("guide", [0.0, 0.12])
def test_power_balance_torque_times_speed_is_force_times_velocity(kind, offset, guide):
    """The geometric moment of the contact force about the cam axis, times omega, equals
    the power delivered along the follower axis, Fn cos(phi) v (no friction losses at
    the contact; guide friction is in Fn)."""
    d = design(kind, offset=offset, guide_factor=guide)
    r = cam_response(d, CamState(0.003, 0.009, 0.001, cam_surface_modulus=5e9), THETA).variables
    power = r["contact_force"] * np.cos(r["pressure_angle"]) * r["follower_velocity"]
    assert np.allclose(r["cam_torque"] * 60.0, power, atol=1e-9 * np.max(np.abs(power)))


def test_guide_friction_raises_the_contact_force_while_rising():
    plain = cam_response(design(offset=0.01), STATE, THETA).variables
    rough = cam_response(design(offset=0.01, guide_factor=0.2), STATE, THETA).variables
    rising = plain["follower_velocity"] > 1e-6
    falling = plain["follower_velocity"] < -1e-6
    tilted = np.abs(np.sin(plain["pressure_angle"])) > 1e-3
    assert np.all(rough["contact_force"][rising & tilted] > plain["contact_force"][rising & tilted])
    assert np.all(rough["contact_force"][falling & tilted] < plain["contact_force"][falling & tilted])
    assert np.all(rough["guide_friction_force"][rising & tilted] > 0)


@pytest.mark.parametrize("kind", ["roller", "flat"])
def test_jump_speed_is_where_the_minimum_contact_force_reaches_zero(kind):
    d = design(kind, law="cycloidal")
    jump = cam_response(d, STATE, THETA).variables["jump_speed"]
    assert 0 < jump < np.inf
    at = {s: cam_response(CamDesign(**{**d.__dict__, "speed": s}), STATE, THETA)
          for s in (jump * (1 - 1e-6), jump, jump * 1.01)}
    forces = [at[s].variables["contact_force"].min() for s in sorted(at)]
    # at the jump speed the force vanishes at the continuous minimum; on the 0.5 deg grid it
    # is up to (-m y'') g'' h^2 / 8 above 0 (g = S / (-m y''), h = 8.7e-3 rad), < 1e-4 F_max
    assert forces[0] > 0 and 0 <= forces[1] < 1e-4 * np.max(at[jump].variables["contact_force"])
    assert forces[2] < 0
    assert not any("jumps" in n for n in at[min(at)].notices)
    assert any("follower jumps at the running speed" in n for n in at[max(at)].notices)


@pytest.mark.parametrize("kind, state", [
    ("roller", STATE), ("flat", STATE), ("knife", STATE),
    ("roller", CamState(0.012, 0.004, 0.0)),    # anisotropic swelling: the geometric path
])
@pytest.mark.parametrize("step_deg", [0.5, 2.0])
def test_jump_speed_is_the_minimum_on_the_continuous_cam_angle(kind, state, step_deg):
    """omega_jump^2 = min S / (-m y'') over the continuous angle, whatever the output grid,
    against a brute-force search on 2e5 angles: there the sampled minimum exceeds the true
    one by at most g'' h^2 / 8 (h = 3.1e-5 rad, g''/g of order 1-10), i.e. < 1e-8 of it."""
    d = design(kind, law="simple_harmonic")
    theta = np.radians(np.arange(0.0, 360.0, step_deg))
    jump = cam_response(d, state, theta).variables["jump_speed"]
    dense = np.linspace(0.0, 2 * np.pi, 200_001)
    (height, _, d2, _), _ = follower_heights(d, state, dense)
    holding = dyn.axial_force(d.follower_mass, 0.0, d.spring_rate, height - dry_lowest_height(d),
                              d.spring_preload, d.external_load, d.gravity)
    brute = dyn.jump_speed(d.follower_mass, d2, holding)
    assert jump == pytest.approx(brute, rel=1e-8)
    assert jump <= brute * (1 + 1e-12)  # the continuous minimum is the infimum


def test_hertz_stress_uses_the_wet_surface_modulus():
    d = design("roller")
    stiff = cam_response(d, CamState(cam_surface_modulus=8e9), THETA).variables
    soft = cam_response(d, CamState(cam_surface_modulus=4e9), THETA).variables
    assert np.all(soft["contact_stress"] < stiff["contact_stress"])
    # p0 = sqrt(F E* (1/rho + 1/R) / (pi L))
    e_star = dyn.effective_modulus(8e9, 0.3, 210e9, 0.3)
    k = 100
    expected = math.sqrt(stiff["contact_force"][k] * e_star *
                         (1 / stiff["radius_of_curvature"][k] + 1 / 0.012) / (math.pi * 0.01))
    assert stiff["contact_stress"][k] == pytest.approx(expected, rel=1e-12)


def test_archard_wear_for_a_flat_follower_and_none_for_a_rolling_roller():
    flat = cam_response(design("flat", archard_coefficient=1e-6, hardness=2e8,
                               friction_coefficient=0.1), STATE, THETA).variables
    roller = cam_response(design("roller", archard_coefficient=1e-6, hardness=2e8), STATE,
                          THETA).variables
    assert np.all(flat["wear_per_revolution"] > 0) and flat["wear_rate"] > 0
    assert np.all(roller["wear_per_revolution"] == 0)
    # on the base-circle dwell rho = Rb, the slide ratio is 1: h = K/H F/L
    k = 10
    assert flat["wear_per_revolution"][k] == pytest.approx(
        1e-6 / 2e8 * flat["contact_force"][k] / 0.01, rel=1e-12)
    assert np.allclose(flat["friction_force"], 0.1 * flat["contact_force"])


def test_undercut_and_cusp_are_warned():
    nose = segments_from_spec([Segment(rise=0.03, over=math.radians(40), law="cycloidal"),
                               Segment(**{"return": 0.03}, over=math.radians(40), law="cycloidal"),
                               Segment(dwell=math.radians(280))])
    sharp = design("roller", roller_radius=0.03, segments=nose)
    notices = cam_response(sharp, STATE, THETA).notices
    assert any("undercut" in n for n in notices)
    assert any("pressure angle" in n for n in notices)
    flat = design("flat")
    cusp = cam_response(CamDesign(**{**flat.__dict__, "base_circle_radius": 0.004}), STATE,
                        THETA).notices
    assert any("cusp" in n for n in cusp)


@pytest.mark.parametrize("kind", ["roller", "knife", "flat"])
def test_working_profile_is_a_closed_counter_clockwise_outline_that_swells(kind):
    d = design(kind)
    x, y = working_profile(d, n=720)
    area = polygon_section(x, y)[0]
    assert area > 0 and (x[0], y[0]) != (x[-1], y[-1])
    assert np.hypot(x, y).min() == pytest.approx(0.05, rel=1e-9)
    xw, yw = working_profile(d, 0.01, 0.03, n=720)
    assert polygon_section(xw, yw)[0] == pytest.approx(area * 1.01 * 1.03, rel=1e-12)
    # the profile point in contact (cam frame) lies on the outline
    r = cam_response(d, STATE, THETA).variables
    assert np.allclose(np.hypot(r["profile_x"], r["profile_y"]).min(), 0.05, rtol=1e-9)


def test_profile_csv_round_trips(tmp_path):
    from fickcam.cam import write_profile_csv

    x, y = working_profile(design("flat"), 0.01, 0.01, n=360)
    path = write_profile_csv(tmp_path / "profile.csv", x, y)
    table = np.loadtxt(path, delimiter=",", skiprows=1)
    assert table.shape == (360, 2)
    assert np.allclose(table * 1e-3, np.c_[x, y], rtol=0, atol=1e-12)  # mm to 9 decimals


def test_a_spring_without_preload_holds_the_follower_where_the_cam_pushes_it():
    """S = k (y - y_low) vanishes at the lowest point, where y'' > 0: the cam's acceleration
    holds the follower there, so the jump speed is where S / (-m y'') is least over y'' < 0
    (at the running speed that gives a vanishing contact force), not 0; a follower pulled
    off (S < 0) or unloaded where y'' < 0 is not held at any speed."""
    d = design("roller", law="cycloidal", spring_preload=0.0, external_load=0.0,
               gravity=False)
    response = cam_response(d, STATE, THETA).variables
    jump = response["jump_speed"]
    assert 0 < jump < np.inf
    at_jump = cam_response(CamDesign(**{**d.__dict__, "speed": jump}), STATE, THETA)
    force = at_jump.variables["contact_force"]
    assert force.min() >= -1e-9 * force.max()
    y2 = np.array([1.0, -2.0, 0.5])
    assert dyn.jump_speed(1.0, y2, np.array([0.0, 4.0, 1.0])) == pytest.approx(math.sqrt(2.0))
    assert dyn.jump_speed(1.0, y2, np.array([-1.0, 4.0, 1.0])) == 0.0
    assert dyn.jump_speed(1.0, y2, np.array([1.0, 0.0, 1.0])) == 0.0
