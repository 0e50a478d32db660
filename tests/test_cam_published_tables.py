"""The published cam papers' numbers, reproduced under each paper's own conventions,
with each slip named where it is met.

Singh & Sanyal (2017) Tables 18-19, Yadav et al. (2017) worked example and wear figure,
Madhukar et al. (2023) (eccentric cam, Table 5.3 dial gauge, Table 5.8 contact force).

The papers are cited in full in :mod:`fickcam.cam`.
"""
import logging
import math

import numpy as np
import pytest

from fickcam.cam import CamDesign, CamState, cam_response
from fickcam.cam.geometry import geometric_motion, pieces_of
from fickcam.cam.kinematics import follower_heights
from fickcam.cam import dynamics as dyn
from fickcam.cam.motion import segments_from_spec, simple_harmonic
from fickcam.cam.spec import Segment
from tolerance import roundoff

log = logging.getLogger(__name__)
INCH = 0.0254

# ---------------------------------------------------------------- Singh & Sanyal 2017

# Table 18: angle, y, y1 (hygrothermal), y', y'1, y'', y''1, y''', y'''1 (inch, per normalised angle)
TABLE_18 = [
    (105, 0.9441, 0.9585, 2.2759, 2.3108, -1.915, -1.945, -22.462, -22.806),
    (120, 1.125, 1.1422, 2.0405, 2.0718, -3.701, -3.757, -20.139, -20.447),
    (135, 1.2803, 1.2999, 1.666, 1.6916, -5.234, -5.314, -16.443, -16.695),
    (150, 1.3995, 1.4209, 1.178, 1.1961, -6.410, -6.508, -11.627, -11.805),
    (165, 1.4744, 1.497, 0.6098, 0.6191, -7.149, -7.259, -6.0187, -6.111),
    (180, 1.5, 1.523, 0, 0, -7.402, -7.515, 0, 0),
    (195, 1.4744, 1.497, -0.609, -0.6191, -7.149, -7.259, 6.0187, 6.111),
    (210, 1.3995, 1.4209, -1.178, -1.1961, -6.410, -6.508, 11.627, 11.805),
    (225, 1.2803, 1.2999, -1.666, -1.6916, -5.234, -5.314, 16.443, 16.695),
    (240, 1.125, 1.1422, -2.0405, -2.0718, -3.701, -3.757, 20.139, 20.447),
    (255, 0.9441, 0.9585, -2.2759, -2.318, -1.915, -1.945, 22.462, 22.806),
]
# Table 19: angle, F_i, F_i1, F_s, F_s1, R, R1, T, T1 (N, N, N, "N inch")
TABLE_19 = [
    (105, 3.0653, 3.2057, 1299.7, 1319.6, 1402.8, 1422.9, 51.4953, 53.0329),
    (120, 5.9217, 6.1929, 1548.7, 1572.5, 1654.7, 1678.7, 54.4593, 56.0969),
    (135, 8.3746, 8.7581, 1762.6, 1789.6, 1871.0, 1898.4, 50.2782, 51.7970),
    (150, 10.256, 10.726, 1926.7, 1956.2, 2037.0, 2067.0, 38.7057, 39.8782),
    (165, 11.439, 11.963, 2029.8, 2060.9, 2141.3, 2173.0, 21.0618, 21.7008),
    (180, 11.843, 12.385, 2065.0, 2096.7, 2176.9, 2209.1, 0, 0),
    (195, 11.439, 11.963, 2029.8, 2060.9, 2141.3, 2173.0, -21.061, -21.700),
    (210, 10.256, 10.726, 1926.7, 1956.2, 2037.0, 2067.0, -38.705, -39.878),
    (225, 8.3746, 8.7581, 1762.6, 1789.6, 1871.0, 1898.4, -50.278, -51.797),
    (240, 5.9217, 6.1929, 1548.7, 1572.5, 1654.7, 1678.7, -54.459, -56.097),
    (255, 3.0653, 3.2057, 1299.7, 1319.6, 1402.8, 1422.9, -51.495, -53.033),
]
# The paper's swelling of the pitch circle (p. 281): eps = alpha dT + beta dm
SINGH2017_STRAIN = 70e-6 * 90 + 3.09e-3 * 3  # 0.01557 -> R_p 3.14 -> 3.189 in, h 1.5 -> 1.523 in


def singh2017_kinematics(lift_inch):
    """Table 18's convention: SHM y = h/2 (1 - cos(pi k)) with k = theta/180 deg taken from
    the absolute cam angle (not (theta - 105)/75 as its text says), derivatives per k, inch."""
    angles = np.array([row[0] for row in TABLE_18], float)
    s, s1, s2, s3 = simple_harmonic(angles / 180.0)
    return lift_inch * s, lift_inch * s1, lift_inch * s2, lift_inch * s3


def test_singh2017_pitch_circle_swelling_gives_the_aged_lift():
    assert 3.14 * SINGH2017_STRAIN == pytest.approx(0.04889, abs=1e-5)
    assert 1.5 * (1 + SINGH2017_STRAIN) == pytest.approx(1.523, abs=5e-4)


@pytest.mark.parametrize("column, aged", [(0, False), (0, True), (1, False), (1, True),
                                          (2, False), (2, True), (3, False), (3, True)])
def test_singh2017_table18_reproduced_per_normalised_angle(column, aged):
    lift = 1.5 * (1 + SINGH2017_STRAIN) if aged else 1.5
    ours = singh2017_kinematics(lift)[column]
    paper = np.array([row[1 + 2 * column + aged] for row in TABLE_18])
    # slips in the table: y' (normal) at 195 deg is printed -0.609 (truncated -0.6098), y'
    # (aged) at 255 deg -2.318 (transposed digits of -2.3108); its text prints the SHM
    # acceleration without the factor h (0.5 pi^2 cos(pi k)) although the table includes it
    slips = {(1, False, 195): -0.6098, (1, True, 255): -2.3108}
    for k, row in enumerate(TABLE_18):
        paper[k] = slips.get((column, aged, row[0]), paper[k])
    assert np.allclose(ours, paper, rtol=2e-3, atol=2e-3), np.c_[ours, paper]


def test_singh2017_table19_reproduced_with_its_sign_and_speed_slips():
    """Table 19: F_i = -m y'' (the cam must supply +m y''; the paper flips the inertia
    term), F_s = k y with k in N/inch and y in inch, R = P + F_i + F_s and T = R y'/omega
    with omega = 62 rad/s (its inputs say 62.83; 62 reproduces every row), in 'N inch'
    although y' is per normalised angle. Masses 1.6 kg dry, 1.648 kg aged (3 % gain)."""
    for aged in (False, True):
        y, y1, y2, _ = singh2017_kinematics(1.5 * (1 + SINGH2017_STRAIN) if aged else 1.5)
        mass = 1.648 if aged else 1.6
        inertia = -mass * y2
        spring = 1376.7 * y
        resultant = 100.0 + inertia + spring
        torque = resultant * y1 / 62.0
        paper = np.array(TABLE_19)[:, 1 + aged::2]
        assert np.allclose(inertia, paper[:, 0], rtol=2e-3)
        assert np.allclose(spring, paper[:, 1], rtol=1e-3)
        assert np.allclose(resultant, paper[:, 2], rtol=1e-3)
        assert np.allclose(torque, paper[:, 3], rtol=2e-3, atol=1e-3)
        assert not np.allclose(resultant * y1 / 62.83, paper[:, 3], rtol=5e-3, atol=1e-3)


def test_singh2017_scene_in_si_scales_lift_and_follower_motion_by_the_strain():
    """The same cam in SI (configs/singh2017_cam.yaml): dwell 105, SHM rise/return 1.5 in over
    75 deg, roller 0.6 in, Rb 1.94 in; isotropic swelling by the paper's 1.557 % scales the
    lift to 1.523 in and every derivative by the same factor."""
    segments = segments_from_spec([Segment(dwell=math.radians(105)),
                                   Segment(rise=1.5 * INCH, over=math.radians(75), law="simple_harmonic"),
                                   Segment(**{"return": 1.5 * INCH}, over=math.radians(75),
                                           law="simple_harmonic"),
                                   Segment(dwell=math.radians(105))])
    design = CamDesign("motion", 1.94 * INCH, 0.012, 62.83, "roller", 1.6, segments=segments,
                       roller_radius=0.6 * INCH, spring_rate=1376.7 / INCH, external_load=100.0)
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    dry = cam_response(design, CamState(cam_surface_modulus=8e9), theta).variables
    eps = SINGH2017_STRAIN
    wet = cam_response(design, CamState(eps, eps, eps, 1.648, 8e9), theta).variables
    assert wet["lift"] / INCH == pytest.approx(1.523, abs=5e-4)
    for name in ("follower_displacement", "follower_velocity", "follower_acceleration"):
        np.testing.assert_allclose(wet[name], (1 + eps) * dry[name], rtol=0,
                                   atol=roundoff(dry[name], 0.05 * (name == "follower_displacement")))
    # at the top of the rise (180 deg) the SI acceleration is -h pi^2/(2 beta^2) omega^2
    beta = math.radians(75)
    assert dry["follower_acceleration"][180] == pytest.approx(
        -1.5 * INCH * math.pi ** 2 / (2 * beta ** 2) * 62.83 ** 2, rel=1e-12)


# ---------------------------------------------------------------- Yadav et al. 2017

YADAV2017 = dict(h=0.0254, beta=math.radians(100), rpm=900.0, k=19345.95, preload_travel=0.009,
               weight=8.896, mu=0.05, l1=0.00785, l2=0.074, d=0.0157, alpha=math.radians(10))


def yadav2017_design():
    s = YADAV2017
    segments = segments_from_spec([Segment(rise=s["h"], over=s["beta"], law="cycloidal"),
                                   Segment(**{"return": s["h"]}, over=s["beta"], law="cycloidal"),
                                   Segment(dwell=2 * math.pi - 2 * s["beta"])])
    return CamDesign("motion", 0.024 - s["h"], 0.01, s["rpm"] * math.pi / 30, "flat",
                     s["weight"] / 9.81, segments=segments, spring_rate=s["k"],
                     spring_preload=s["k"] * s["preload_travel"], friction_coefficient=s["mu"],
                     guide_factor=dyn.guide_friction_factor(s["mu"], s["l1"], s["l2"], s["d"]))


def test_yadav2017_worked_example_at_75_deg_of_the_cycloidal_rise():
    """y = 0.0230 m, v = 1.3716 m/s, a = -464.82 m/s^2, F_s = 619.0 N, P = 197.56 N,
    F_n = 202.75 N, T = 2.905 N m, F_f = 10.14 N, all within 1 %. The paper: spring rate
    19345.95 N/m is printed as 773/0.040, which is 19325 N/m (we keep the rate it uses);
    it leaves out the follower's weight (gravity off); its 'y = 0.0230 m/s' is a length;
    the 10 deg in F_n and T is an assumed obliquity: a flat face perpendicular to its axis
    has pressure angle 0, so the full model gives F_n = P (shown at the end)."""
    s = YADAV2017
    design = yadav2017_design()
    theta = np.array([math.radians(75)])
    r = cam_response(design, CamState(cam_surface_modulus=110e9), theta).variables
    y, v, a = (r[n][0] for n in ("follower_displacement", "follower_velocity",
                                 "follower_acceleration"))
    assert y == pytest.approx(0.0230, rel=1e-2)
    assert v == pytest.approx(1.3716, rel=1e-2)
    assert a == pytest.approx(-464.82, rel=1e-2)
    mass = s["weight"] / 9.81
    spring = s["k"] * (s["preload_travel"] + y)
    assert spring == pytest.approx(619.007, rel=1e-2)
    axial = dyn.axial_force(mass, a, s["k"], y, s["k"] * s["preload_travel"], 0.0, False)
    assert axial == pytest.approx(197.56, rel=1e-2)
    normal = dyn.normal_force(axial, s["alpha"], v, design.guide_factor)
    assert normal == pytest.approx(202.75, rel=1e-2)
    omega = s["rpm"] * math.pi / 30
    torque = dyn.power_torque(normal, s["alpha"], v / omega)
    assert torque == pytest.approx(2.905, rel=1e-2)
    assert s["mu"] * normal == pytest.approx(10.1375, rel=1e-2)
    # the full flat-follower model: pressure angle 0, F_n = axial force, T = F_n y'
    assert r["pressure_angle"][0] == 0.0
    assert r["contact_force"][0] == pytest.approx(axial, rel=1e-12)
    assert r["cam_torque"][0] == pytest.approx(axial * v / omega, rel=1e-12)
    assert r["friction_force"][0] == pytest.approx(s["mu"] * axial, rel=1e-12)


def test_yadav2017_wear_figure_does_not_follow_from_its_inputs():
    """Z = l a0 (P0/H1)^a1 (H2/H1)^a2 mu^a3 with l = 0.07 m, a0 = 1.13e-5, P0 = 255.3e6,
    H1 = 450, H2 = 370, mu = 0.05 and Table 2.1's exponents gives 16.63 um; the paper prints
    14.68 um (13 % lower; its formula also shows mu^a1 for mu^a3)."""
    z = dyn.empirical_wear_depth(0.07, 255.3e6, 450.0, 370.0, 0.05)
    log.info("Yadav et al. 2017 wear: %.4g um (paper 14.68 um)", z * 1e6)
    assert z * 1e6 == pytest.approx(16.634, rel=1e-3)
    assert abs(z * 1e6 - 14.68) / 14.68 > 0.1


# ---------------------------------------------------------------- Madhukar et al. 2023

TABLE_5_3 = np.array([0.1, 0.325, 0.64, 1.15, 1.72, 2.45, 3.31, 4.4, 4.83, 5.65, 6.41, 7.12, 7.8,
                      8.39, 8.78, 9.06, 9.19, 9.21, 9.03, 8.79, 8.48, 7.92, 7.3, 6.64, 6.0, 5.28,
                      4.55, 3.72, 3.03, 2.32, 1.69, 1.08, 0.63, 0.27, 0.17, 0.1]) * 1e-3  # 10..360 deg


def madhukar2023_design(kind="roller", speed=1.0, offset=0.0):
    return CamDesign("eccentric", 0.023 - 0.004, 0.01, speed, kind, 0.737, eccentricity=0.004,
                     disc_radius=0.023, roller_radius=0.010 if kind == "roller" else 0.0,
                     offset=offset, spring_rate=660.02, gravity=True)


def test_madhukar2023_eccentric_cam_follows_the_exact_geometry():
    """Radial roller: y = -e cos(theta) + sqrt((R + r)^2 - e^2 sin^2 theta) - (R + r - e),
    flat face: y = e (1 - cos theta) (pure SHM), both with their derivatives."""
    e, big, r = 0.004, 0.023, 0.010
    theta = np.radians(np.arange(0.0, 360.0, 5.0))
    roller = cam_response(madhukar2023_design(), CamState(cam_surface_modulus=3e9), theta).variables
    exact = -e * np.cos(theta) + np.sqrt((big + r) ** 2 - (e * np.sin(theta)) ** 2) - (big + r - e)
    # the geometric path: Chebyshev fit of degree N = 96, round-off N eps |Y| in Y and
    # N^2 eps |Y| in dY/dtheta (Trefethen, Spectral Methods in MATLAB, ch. 6)
    size = big + r
    np.testing.assert_allclose(roller["follower_displacement"], exact, rtol=0,
                               atol=roundoff(size, operations=10 * 96))
    u = e * np.sin(theta)
    slope = e * np.sin(theta) - u * e * np.cos(theta) / np.sqrt((big + r) ** 2 - u ** 2)
    np.testing.assert_allclose(roller["follower_velocity"], slope, rtol=0,
                               atol=roundoff(size, operations=10 * 96 ** 2))


def test_madhukar2023_eccentric_flat_face_is_exact_simple_harmonic_motion():
    """Flat face on the eccentric disc: y = e (1 - cos theta) (pure SHM) with its exact
    derivatives, equal up to round-off of the terms (no spectral differentiation)."""
    e = 0.004
    theta = np.radians(np.arange(0.0, 360.0, 5.0))
    flat = cam_response(madhukar2023_design("flat", speed=10.0), CamState(cam_surface_modulus=3e9),
                        theta).variables
    exact = {"follower_displacement": e * (1 - np.cos(theta)),
             "follower_velocity": 10 * e * np.sin(theta),
             "follower_acceleration": 100 * e * np.cos(theta),
             "follower_jerk": -1000 * e * np.sin(theta)}
    radius_scale = {"follower_displacement": 0.023, "follower_velocity": 10 * e,
                    "follower_acceleration": 100 * e, "follower_jerk": 1000 * e}
    for name, value in exact.items():
        np.testing.assert_allclose(flat[name], value, rtol=0,
                                   atol=roundoff(radius_scale[name]), err_msg=name)


@pytest.mark.parametrize("strain_x, strain_y", [(0.01, 0.003), (0.003, 0.01), (0.02, 0.0)])
def test_swollen_eccentric_flat_face_matches_the_geometric_route(strain_x, strain_y):
    """The closed-form support function of the swollen (elliptical) disc against the
    independent geometric route (Newton contact + Chebyshev fit of degree N = 96). The
    spectral k-th derivative carries round-off about eps N^(2k) |Y| (N |Y| eps for the
    least-squares fit itself; Trefethen, Spectral
    Methods in MATLAB, ch. 6), which sets the tolerance; extremes agree to round-off."""
    design = madhukar2023_design("flat", speed=1.0)
    state = CamState(cam_strain_x=strain_x, cam_strain_y=strain_y)
    theta = np.linspace(0.0, 2 * np.pi, 73)
    closed, closed_extremes = follower_heights(design, state, theta)
    nodes = 96
    spectral, spectral_extremes = geometric_motion(design, pieces_of(design), strain_x,
                                                   strain_y, 0.0, theta, nodes=nodes)
    size = float(np.max(closed[0]))
    for k in range(4):
        np.testing.assert_allclose(closed[k], spectral[k], rtol=0,
                                   atol=roundoff(size, operations=10 * nodes ** max(1, 2 * k)))
    np.testing.assert_allclose(closed_extremes, spectral_extremes, rtol=0, atol=roundoff(size))


def test_madhukar2023_dial_gauge_rms_against_the_exact_geometry():
    """Table 5.3 (hand-turned, dial gauge zeroed at the lowest position) against the exact
    eccentric-roller geometry: the gauge overshoots the 2e = 8 mm stroke (9.21 mm at
    180 deg), so the RMS is about 0.8 mm; we require < 1 mm and report it."""
    theta = np.radians(np.arange(10.0, 361.0, 10.0))
    y = cam_response(madhukar2023_design(), CamState(cam_surface_modulus=3e9),
                     theta).variables["follower_displacement"]
    rms = float(np.sqrt(np.mean((y - TABLE_5_3) ** 2)))
    log.warning("Madhukar et al. 2023 Table 5.3 RMS vs exact geometry: %.4f mm (max |diff| %.3f mm)",
                rms * 1e3, np.max(np.abs(y - TABLE_5_3)) * 1e3)
    assert 0.3e-3 < rms < 1.0e-3


def test_madhukar2023_contact_force_extremes_at_hand_speed():
    """F_c = m y'' + s y + m g (sec. 5.5) at omega = 1 rad/s (its code's w = 1): from m g =
    7.23 N at the lowest point to m g + s 2e = 12.51 N at 180 deg. The paper's Table 5.8
    gives 7.35 / 12.74 N (its code's y passes degrees to sin/cos, which expect radians);
    within 2 %."""
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    force = cam_response(madhukar2023_design(), CamState(cam_surface_modulus=3e9),
                         theta).variables["contact_force"]
    axial_min = 0.737 * dyn.STANDARD_GRAVITY
    assert force.min() == pytest.approx(axial_min, rel=1e-3)  # + m e omega^2 (R + r)/(R + r - e)
    assert np.argmax(force) == 180
    assert force.min() == pytest.approx(7.3485, rel=0.02)
    assert force.max() == pytest.approx(12.74, rel=0.02)
