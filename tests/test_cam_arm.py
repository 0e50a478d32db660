"""Swinging-arm (oscillating) followers, roller and flat face.

Independent references: the arm angle found by root finding of the contact between the
roller circle (or the face line) and the generated profile, with scipy.optimize at each
cam angle; the profile normal and curvature by finite differences of the generated
profile; virtual work for the torque; the translating follower as the arm grows long.
"""
import math
import textwrap

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from fickcam.cam.geometry import dry_profile, rotate
from fickcam.cam.design import CamState, cam_design
from fickcam.cam.kinematics import motion_function
from fickcam.cam.model import cam_response
from fickcam.cam.motion import follower_motion
from fickcam.cam.oscillating import arm_response
from fickcam.cli.main import main

THETA = np.radians(np.arange(0.0, 360.0, 1.0))
#: a swollen, distorted cam, roller and arm (of the order of a year in humid air)
AGED = CamState(cam_strain_x=0.008, cam_strain_y=0.004, roller_strain=0.012, arm_strain=0.015,
                follower_mass=0.065)
MOTION = [{"dwell": "60 deg"}, {"rise": "20 deg", "over": "120 deg", "law": "cycloidal"},
          {"dwell": "30 deg"}, {"return": "20 deg", "over": "120 deg", "law": "polynomial_345"},
          {"dwell": "30 deg"}]


def arm_section(kind="roller", rises="counter_clockwise", pivot=("90 mm", "40 mm"), swing="20 deg",
                **arm):
    """A cam with a swinging arm whose pivot lies off both axes (an offset pivot)."""
    follower = {"kind": kind, "mass": "0.06 kg",
                "arm": {"pivot": list(pivot), "rises": rises, "inertia": "1.3e-4 kg m^2",
                        "spring_rate": "2 N m/rad", "spring_preload": "0.4 N m", **arm}}
    if kind == "roller":
        follower["roller_radius"] = "8 mm"
        follower["arm"].setdefault("length", "80 mm")
    return {"material": "cfrp", "thickness": "10 mm", "speed": "300 rpm",
            "base_circle_radius": "30 mm", "follower": follower,
            "motion": [with_swing(s, swing) for s in MOTION]}


def with_swing(segment, swing):
    """The segment with its rise or return replaced by ``swing``."""
    return {k: (swing if k in ("rise", "return") else v) for k, v in segment.items()}


def flat_section(**extra):
    """A flat-face arm, 10 deg swing (20 deg would need a cusp on this base circle)."""
    return arm_section("flat", pivot=("100 mm", "-30 mm"), swing="10 deg", face_offset="12 mm",
                       **extra)


def profile_point(design, s, state=CamState()):
    """The generated (aged) working profile at its parameter s (cam frame)."""
    s = float(np.mod(s, 2 * np.pi))
    segment = next(g for g in design.segments if g.start <= s < g.start + g.span)
    wx, wy, _, _ = dry_profile(design, segment, np.array([s]))
    return np.array([(1 + state.cam_strain_x) * wx[0], (1 + state.cam_strain_y) * wy[0]])


def closest(design, state, theta, distance):
    """The smallest of distance(X) over the profile near its point s = theta, X = R(theta) W(s)."""
    def f(s):
        return distance(np.array(rotate(theta, *profile_point(design, s, state))))
    return minimize_scalar(f, bounds=(theta - 0.4, theta + 0.4), method="bounded",
                           options={"xatol": 1e-12}).fun


def root_found_roller_angles(design, state, angles):
    """Arm angle (from the dry base position) at which the roller touches the profile at each
    cam angle: brentq on min distance(roller centre, profile) - roller radius."""
    arm = design.arm
    pivot = np.array([arm.pivot_x, arm.pivot_y])
    length = arm.length * (1 + state.arm_strain)
    roller = design.roller_radius * (1 + state.roller_strain)
    prime = design.base_circle_radius + design.roller_radius
    towards = math.atan2(-arm.pivot_y, -arm.pivot_x)  # from the pivot to the cam axis
    phi0 = brentq(lambda phi: np.hypot(*(pivot + design.arm.length * np.array(
        [math.cos(phi), math.sin(phi)]))) - prime, towards, towards + arm.sense * math.pi)
    out = []
    for theta in angles:
        def gap(psi):
            phi = phi0 + arm.sense * psi
            centre = pivot + length * np.array([math.cos(phi), math.sin(phi)])
            return closest(design, state, theta, lambda x: np.hypot(*(x - centre))) - roller
        out.append(brentq(gap, *bracket(design, theta), xtol=1e-14))
    return np.array(out)


def bracket(design, theta, width=0.03):
    """Search interval about the design motion (the swelling moves the arm by < 0.01 rad)."""
    psi = float(follower_motion(design.segments, np.array([theta]))[0][0])
    return psi - width, psi + width


def root_found_face_angles(design, state, angles):
    """Arm angle at which the face line touches the profile: brentq on max over the profile of
    X.m - (A.m - f) (the cam's support function minus the face's distance from the axis)."""
    arm = design.arm
    pivot = np.array([arm.pivot_x, arm.pivot_y])
    offset = arm.face_offset * (1 + state.arm_strain)

    def normal(gamma):
        return np.array([math.cos(gamma), math.sin(gamma)])

    towards = math.atan2(arm.pivot_y, arm.pivot_x)  # face normal along the cam-axis-to-pivot line
    gamma0 = brentq(lambda g: pivot @ normal(g) - arm.face_offset - design.base_circle_radius,
                    towards, towards - arm.sense * math.pi / 2)
    out = []
    for theta in angles:
        def gap(psi):
            m = normal(gamma0 + arm.sense * psi)
            return -closest(design, state, theta, lambda x: -(x @ m)) - (pivot @ m - offset)
        out.append(brentq(gap, *bracket(design, theta), xtol=1e-14))
    return np.array(out)


ANGLES = np.radians(np.arange(3.0, 360.0, 11.0))  # 33 cam angles across every segment


@pytest.mark.slow
@pytest.mark.parametrize("rises", ["counter_clockwise", "clockwise"])
@pytest.mark.parametrize("state", [CamState(), AGED], ids=["dry", "aged"])
def test_roller_arm_angle_matches_root_found_contact(rises, state):
    """Within 1e-9 rad, offset pivot, dry and swollen cam/roller/arm."""
    design = cam_design(arm_section("roller", rises,
                                           pivot=("90 mm", "40 mm") if rises == "counter_clockwise"
                                           else ("-60 mm", "75 mm")))
    psi = motion_function(design, state)[0](ANGLES)[0]
    assert np.max(np.abs(psi - root_found_roller_angles(design, state, ANGLES))) < 1e-9


@pytest.mark.parametrize("state", [CamState(), AGED], ids=["dry", "aged"])
def test_flat_face_arm_angle_matches_root_found_contact(state):
    design = cam_design(flat_section())
    psi = motion_function(design, state)[0](ANGLES)[0]
    assert np.max(np.abs(psi - root_found_face_angles(design, state, ANGLES))) < 1e-9


def test_dry_arm_follows_the_design_motion():
    """Without strain the arm angle is the motion program itself (swing 20 deg)."""
    v = arm_response(cam_design(arm_section()), CamState(), THETA).variables
    assert v["arm_swing"] == pytest.approx(math.radians(20.0), rel=1e-12)
    assert v["follower_arm_angle"][120] == pytest.approx(math.radians(10.0), rel=1e-12)


def finite_difference_profile(design, s, h=1e-4):
    """W, W' and W'' of the generated profile at parameter s by central differences."""
    w = [profile_point(design, s + k * h) for k in (-1, 0, 1)]
    return w[1], (w[2] - w[0]) / (2 * h), (w[2] - 2 * w[1] + w[0]) / h ** 2


SMOOTH = np.radians(np.r_[np.arange(65.0, 176.0, 10.0), np.arange(215.0, 326.0, 10.0)])


SECTIONS = {"roller": arm_section, "flat": flat_section}


@pytest.mark.parametrize("kind", ["roller", "flat"])
def test_pressure_angle_matches_the_profile_normal_by_finite_differences(kind):
    """alpha between the direction the arm moves the contact point and the profile normal,
    the normal from a central difference of the generated profile (error ~h^2)."""
    design = cam_design(SECTIONS[kind]())
    v = arm_response(design, CamState(), SMOOTH).variables
    arm = design.arm
    for k, theta in enumerate(SMOOTH):
        w, dw, _ = finite_difference_profile(design, theta, h=1e-6)
        tx, ty = rotate(theta, *dw)
        nx, ny = np.array([-ty, tx]) / np.hypot(tx, ty)  # outward normal (clockwise traversal)
        cx, cy = rotate(theta, *w)
        if kind == "roller":
            cx, cy = cx + design.roller_radius * nx, cy + design.roller_radius * ny
        ux, uy = arm.sense * -(cy - arm.pivot_y), arm.sense * (cx - arm.pivot_x)
        alpha = math.atan2(ux * ny - uy * nx, ux * nx + uy * ny)
        assert v["pressure_angle"][k] == pytest.approx(alpha, abs=1e-7)


@pytest.mark.parametrize("kind", ["roller", "flat"])
def test_radius_of_curvature_matches_finite_difference_curvature(kind):
    """rho of the working profile vs kappa = (x'y'' - y'x'')/|W'|^3 of the generated profile."""
    design = cam_design(SECTIONS[kind]())
    rho = arm_response(design, CamState(), SMOOTH).variables["radius_of_curvature"]
    for k, theta in enumerate(SMOOTH):
        _, d1, d2 = finite_difference_profile(design, theta)
        kappa = (d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3
        assert rho[k] == pytest.approx(-1.0 / kappa, rel=1e-5)


@pytest.mark.parametrize("kind", ["roller", "flat"])
@pytest.mark.parametrize("state", [CamState(), AGED], ids=["dry", "aged"])
def test_cam_torque_times_cam_speed_is_arm_torque_times_arm_speed(kind, state):
    """Virtual work (no friction): T omega = T_arm psi_dot; the cam torque is the moment of
    the contact force about the cam axis, the arm torque its moment about the pivot."""
    design = cam_design(SECTIONS[kind]())
    v = arm_response(design, state, THETA).variables
    power_in = v["cam_torque"] * design.speed
    power_out = v["arm_torque"] * v["follower_arm_angular_velocity"]
    assert np.max(np.abs(power_in - power_out)) < 1e-9 * np.max(np.abs(power_in))


def test_arm_torque_is_inertia_spring_and_preload():
    """T_arm = I psi'' omega^2 + k_t psi + T_0 on the dry cam; the contact force is T_arm over
    the lever l cos(alpha)."""
    design = cam_design(arm_section())
    v = arm_response(design, CamState(), THETA).variables
    psi, acc = v["follower_arm_angle"], v["follower_arm_angular_acceleration"]
    assert np.allclose(v["arm_torque"], 1.3e-4 * acc + 2.0 * psi + 0.4, rtol=1e-12)
    lever = 0.08 * np.cos(v["pressure_angle"])
    assert np.allclose(v["contact_force"] * lever, v["arm_torque"], rtol=1e-12)


def long_arm_errors(length):
    """Largest differences between a swinging roller arm of ``length`` and the radial
    translating roller follower with the same lift (10 mm): pressure angle (rad) and cam
    torque (N m), the arm perpendicular to the follower line at mid-lift, I = m L^2,
    k_t = k L^2, T_0 = F_0 L so that the forces at the roller match."""
    lift, mass, rate, preload = 10e-3, 0.1, 2000.0, 20.0
    motion = [{"dwell": "60 deg"}, {"rise": lift, "over": "120 deg", "law": "cycloidal"},
              {"dwell": "30 deg"}, {"return": lift, "over": "120 deg", "law": "cycloidal"},
              {"dwell": "30 deg"}]
    translating = {"material": "cfrp", "thickness": "10 mm", "speed": "300 rpm",
                   "base_circle_radius": "30 mm", "motion": motion,
                   "follower": {"kind": "roller", "roller_radius": "8 mm", "mass": mass,
                                "spring_rate": rate, "spring_preload": preload}}
    swing = 2 * math.asin(lift / (2 * length))
    arm_motion = [dict(s, **({"rise": swing} if "rise" in s else {"return": swing}))
                  if "dwell" not in s else s for s in motion]
    arm = {"kind": "roller", "roller_radius": "8 mm", "mass": mass,
           "arm": {"pivot": [length, 38e-3 + lift / 2], "length": length, "rises": "clockwise",
                   "inertia": mass * length ** 2, "spring_rate": rate * length ** 2,
                   "spring_preload": preload * length}}
    a = cam_response(cam_design(translating), CamState(), THETA).variables
    b = arm_response(cam_design(translating | {"motion": arm_motion, "follower": arm}),
                     CamState(), THETA).variables
    return (np.max(np.abs(a["pressure_angle"] - b["pressure_angle"])),
            np.max(np.abs(a["cam_torque"] - b["cam_torque"])))


def test_very_long_arm_tends_to_the_translating_follower():
    """The arm's tilt from the follower line is O(lift/L): the pressure angle converges as 1/L
    (the torque, whose first-order terms cancel, at least as fast)."""
    short, long = long_arm_errors(1.0), long_arm_errors(10.0)
    assert long[0] < 1e-3 and long[1] < 1e-5 * 0.6  # 0.03 deg; N m against a ~0.6 N m peak
    assert 7 < short[0] / long[0] < 13 and short[1] / long[1] > 7


# ------------------------------------------------------------------ scene errors


SCENE = textwrap.dedent("""\
    name: arm
    description: swinging arm
    environment:
      reference_temperature: 23 degC
      history:
        - {duration: 30 d, temperature: 30 degC, relative_humidity: 85 %}
    materials:
      acetal: {plastic: acetal}
    cam:
      material: acetal
      base_circle_radius: 30 mm
      thickness: 10 mm
      speed: 300 rpm
      follower:
        kind: roller
        roller_radius: 8 mm
        mass: 0.06 kg
        arm:
          pivot: [90 mm, 40 mm]
          length: 80 mm
          inertia: 1.3e-4 kg m^2
      motion:
        - dwell: 180 deg
        - {rise: 20 deg, over: 90 deg, law: cycloidal}
        - {return: 20 deg, over: 90 deg, law: cycloidal}
    outputs:
      ageing_times: {every: 30 d}
    """)


@pytest.mark.parametrize("changes, where, reason", [
    ({"length: 80 mm": "length: 30 mm"}, "20 cam.follower.arm.length", "cannot reach the prime circle"),
    ({"rise: 20 deg": "rise: 5 mm", "return: 20 deg": "return: 5 mm"}, "24 cam.motion.1.rise",
     "rises by an angle"),
    ({"kind: roller": "kind: knife", "    roller_radius: 8 mm\n": ""}, "14 cam.follower",
     "carries a roller or a flat face"),
    ({"mass: 0.06 kg": "mass: 0.06 kg\n    offset: 5 mm"}, "14 cam.follower", "offset does not apply"),
    ({"rise: 20 deg": "rise: 170 deg", "return: 20 deg": "return: 170 deg"},
     "19 cam.follower.arm.pivot", "swing through the line"),
])
def test_impossible_arms_are_one_line_errors(tmp_path, capsys, changes, where, reason):
    text = SCENE
    for old, new in changes.items():
        text = text.replace(old, new, 1)
    path = tmp_path / "scene.yaml"
    path.write_text(text)
    assert main(["check", str(path)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 + ("return: 5 mm" in text)  # one line per problem
    file_line, key = where.split(" ")
    assert lines[0].startswith(f"{path}:{file_line} {key}: ") and reason in lines[0]


def test_clockwise_cam_touches_the_arm_where_it_says():
    """A cam turning clockwise: the reported contact points (cam frame, seen from the front)
    turned by R(-theta) lie on the roller, whose centre is on the arm about the real pivot
    (base arm angle by root finding, arm turning clockwise on the rise)."""
    section = arm_section("roller", "clockwise", pivot=("-60 mm", "75 mm")) | {"direction": "clockwise"}
    design = cam_design(section)
    v = arm_response(design, CamState(), THETA).variables
    x, y = rotate(-THETA, v["profile_x"], v["profile_y"])
    pivot = np.array([-60e-3, 75e-3])
    towards = math.atan2(-pivot[1], -pivot[0])
    phi0 = brentq(lambda phi: np.hypot(*(pivot + 0.08 * np.array([math.cos(phi), math.sin(phi)])))
                  - 0.038, towards, towards - math.pi)
    phi = phi0 - v["follower_arm_angle"]  # clockwise on the rise (dry: lowest = base)
    cx, cy = pivot[0] + 0.08 * np.cos(phi), pivot[1] + 0.08 * np.sin(phi)
    assert np.max(np.abs(np.hypot(x - cx, y - cy) - 8e-3)) < 1e-12


def test_clockwise_cam_touches_the_translating_follower_where_it_says():
    """Knife edge at x = offset: the contact point turned by R(-theta) is (offset, s0 + y)."""
    section = {"material": "cfrp", "thickness": "10 mm", "speed": "300 rpm", "direction": "clockwise",
               "base_circle_radius": "30 mm",
               "follower": {"kind": "knife", "offset": "7 mm", "mass": "0.1 kg"},
               "motion": [dict(s, **{k: "10 mm" for k in ("rise", "return") if k in s})
                          for s in MOTION]}
    v = cam_response(cam_design(section), CamState(), THETA).variables
    x, y = rotate(-THETA, v["profile_x"], v["profile_y"])
    assert np.max(np.abs(x - 7e-3)) < 1e-12
    height = math.sqrt(30e-3 ** 2 - 7e-3 ** 2) + v["follower_displacement"]
    assert np.max(np.abs(y - height)) < 1e-12


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["roller", "flat"])
def test_arm_on_a_cam_given_by_points_follows_the_motion_program(kind, tmp_path):
    """The same cam as 1440 working-profile points (a CSV): the arm angle found from the
    points' periodic quintic spline (arm angle from the contact, slope from the normal-velocity
    condition) matches the motion program within 1e-6 of the swing, dry and aged."""
    from fickcam.cam.geometry import working_outline
    from fickcam.cam.profile import write_profile_csv

    section = SECTIONS[kind]()
    design = cam_design(section)
    path = write_profile_csv(tmp_path / "arm.csv", *working_outline(design, n=1440))
    points = cam_design({k: v for k, v in section.items()
                                if k not in ("motion", "base_circle_radius")} |
                               {"profile_file": str(path)})
    swing = design.segments[1].height
    for state in (CamState(), AGED):
        exact = arm_response(design, state, THETA).variables
        found = arm_response(points, state, THETA).variables
        assert np.max(np.abs(found["follower_arm_angle"] - exact["follower_arm_angle"])) < 1e-6 * swing
        assert np.max(np.abs(found["pressure_angle"] - exact["pressure_angle"])) < 1e-5


def test_sized_arm_cam_sits_on_the_pressure_angle_limit():
    """`fickcam size` for an arm: at the radius found the largest pressure angle is within
    the limit, 1 um below it is not (the limit is crossed there, found by bisection)."""
    from dataclasses import replace

    from fickcam.cam.sizing import Limits, arm_reach, smallest_base_circle, worst

    design = cam_design(arm_section())
    limits = Limits(math.radians(30.0), 5e-3)
    radius = smallest_base_circle(design, limits)["pressure_angle"]
    low, high = arm_reach(design)
    assert low < radius < high
    assert worst(replace(design, base_circle_radius=radius))[0] <= limits.pressure_angle + 1e-12
    assert worst(replace(design, base_circle_radius=radius - 1e-6))[0] > limits.pressure_angle


def test_check_describes_the_arm(tmp_path, capsys):
    path = tmp_path / "scene.yaml"
    path.write_text(SCENE)
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "follower: swinging roller arm 80 mm long, roller 8 mm, pivot 98.49 mm" in out
    assert "swings 20 deg counter-clockwise on the rise" in out


@pytest.mark.slow
def test_compensated_swinging_arm_follows_the_design_motion(tmp_path, capsys):
    """`fickcam compensate` on the nylon arm config at 180 d: the made cam (points), roller and
    arm length bring the arm angle back to the design within 1 % of its uncompensated drift."""
    import yaml

    import fickcam
    from fickcam.scene.load import load_scene, read_yaml

    configs = __import__("pathlib").Path(__file__).resolve().parents[1] / "configs"
    data = read_yaml(configs / "nylon_swinging_arm.yaml").data
    data["outputs"] = {"ageing_times": ["0 d", "180 d"], "angle_step": "2 deg"}
    (tmp_path / "arm.yaml").write_text(yaml.safe_dump(data))
    path = tmp_path / "made.yaml"
    assert main(["compensate", str(tmp_path / "arm.yaml"), "--at", "180 d", "-o", str(path)]) == 0
    printed = capsys.readouterr().out
    assert "follower  arm length" in printed and "arm angle deg" in printed
    scene = load_scene(tmp_path / "arm.yaml")
    before, after = fickcam.run(scene), fickcam.run(path)
    design = before.follower_arm_angle_design.values
    deviation = np.abs(before.follower_arm_angle.values[-1] - design)
    left = np.abs(after.follower_arm_angle.values[-1] - design)
    assert deviation.max() > 0.3  # deg
    assert np.all(left <= 0.01 * deviation.max())
