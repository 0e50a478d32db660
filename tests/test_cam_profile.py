"""A cam given by its profile points (cam.profile_file): the periodic quintic spline of
the points, the follower motion found from the contact geometrically, the CSV/DXF files.

Reference: the same cam given by its motion program (closed form, or the geometric
path of fickcam.cam.geometry for a swollen, distorted cam)."""
import textwrap

import numpy as np
import pytest
import yaml

from fickcam.cam import dynamics as dyn
from fickcam.cam.geometry import rotate, working_outline
from fickcam.cam.design import CamState, cam_design
from fickcam.cam.model import cam_response
from fickcam.cam.profile import (make_profile, profile_motion, read_profile_csv,
                                 write_profile_csv, write_profile_dxf)
from fickcam.cli.main import main

THETA = np.radians(np.arange(0.0, 360.0, 0.5))


def cam_section(kind="roller", law="cycloidal", offset="0 mm", lift="1.5 in", base="1.94 in",
                **extra):
    """Singh & Sanyal 2017's cam (1.94 in base circle, 1.5 in rise/return over 75 deg) with a
    continuous-acceleration law unless told otherwise."""
    follower = {"kind": kind, "offset": offset, "mass": "1.6 kg", "spring_rate": "1376.7 N/in",
                "external_load": "100 N"}
    if kind == "roller":
        follower["roller_radius"] = "0.6 in"
    section = {"material": "cfrp", "thickness": "12 mm", "speed": "600 rpm", "follower": follower,
               "base_circle_radius": base,
               "motion": [{"dwell": "105 deg"}, {"rise": lift, "over": "75 deg", "law": law},
                          {"return": lift, "over": "75 deg", "law": law}, {"dwell": "105 deg"}]}
    section.update(extra)
    return section


def as_points(section, tmp_path, n, name="profile.csv"):
    """The same cam given by n working-profile points written to a CSV."""
    design = cam_design(section)
    path = write_profile_csv(tmp_path / name, *working_outline(design, n=n))
    points = {k: v for k, v in section.items() if k not in ("motion", "base_circle_radius")}
    return design, cam_design(points | {"profile_file": str(path)})


def kinematics(design, state=CamState()):
    v = cam_response(design, state, THETA).variables
    return v["follower_displacement"], v["pressure_angle"], v["lift"]


@pytest.mark.slow
@pytest.mark.parametrize("kind, offset", [("roller", "0 mm"), ("roller", "8 mm"), ("knife", "0 mm")])
def test_cam_from_points_reproduces_the_motion_program_cam(tmp_path, kind, offset):
    """720 points (0.5 deg apart): displacement within 1e-6 of the lift, pressure angle
    within 0.01 deg, at every cam angle."""
    motion, points = as_points(cam_section(kind, offset=offset), tmp_path, 720)
    y0, phi0, lift = kinematics(motion)
    y1, phi1, lift1 = kinematics(points)
    assert np.max(np.abs(y1 - y0)) < 1e-6 * lift
    assert lift1 == pytest.approx(lift, abs=1e-6 * lift)
    assert np.degrees(np.max(np.abs(phi1 - phi0))) < 0.01


def test_flat_follower_on_points_matches_its_motion_program(tmp_path):
    """A flat face needs a convex cam: 10 mm rise on a 40 mm base circle."""
    motion, points = as_points(cam_section("flat", lift="10 mm", base="40 mm"), tmp_path, 720)
    y0, _, lift = kinematics(motion)
    y1, _, _ = kinematics(points)
    assert np.max(np.abs(y1 - y0)) < 1e-6 * lift


def test_swollen_cam_from_points_matches_the_geometric_motion_cam(tmp_path):
    """Anisotropic swelling (eps_x != eps_y) of the points gives the follower motion the
    motion-program cam gives along its own geometric path."""
    motion, points = as_points(cam_section(), tmp_path, 720)
    state = CamState(cam_strain_x=-2e-4, cam_strain_y=4e-3, roller_strain=1e-3)
    y0, phi0, lift = kinematics(motion, state)
    y1, phi1, _ = kinematics(points, state)
    assert np.max(np.abs(y1 - y0)) < 1e-6 * lift
    assert np.degrees(np.max(np.abs(phi1 - phi0))) < 0.01


def test_profile_spline_converges_at_sixth_order_between_its_points():
    """Interpolation error of the quintic spline of an ellipse, midway between points,
    falls as h^6 (de Boor 2001, ch. XIII); measured as the distance to the ellipse."""
    def worst_gap(n):
        t = 2 * np.pi * np.arange(n) / n
        profile = make_profile(0.05 * np.cos(t), 0.04 * np.sin(t))
        u = (np.arange(n) + 0.5) / n
        x, y = profile.at(u)
        return np.max(np.abs((x / 0.05) ** 2 + (y / 0.04) ** 2 - 1.0))  # ~ 2 distance / radius
    order = np.log2(worst_gap(64) / worst_gap(128))
    assert 5.5 < order < 7.0


@pytest.mark.slow
def test_acceleration_jump_limits_the_pressure_angle_to_first_order_in_the_spacing(tmp_path):
    """Simple harmonic rise after a dwell: the profile's curvature jumps at the joint, so
    the spline's tangent there is off by O(h); halving the spacing halves the error."""
    errors = []
    for n in (720, 1440):
        motion, points = as_points(cam_section(law="simple_harmonic"), tmp_path, n, f"p{n}.csv")
        errors.append(np.max(np.abs(kinematics(points)[1] - kinematics(motion)[1])))
    assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.1)


def test_pitch_curve_file_gives_the_cam_of_its_working_profile(tmp_path):
    section = cam_section()
    design = cam_design(section)
    psi = 2 * np.pi * np.arange(720) / 720
    from fickcam.cam.motion import follower_motion

    rise = follower_motion(design.segments, psi)[0]
    s0 = design.base_circle_radius + design.roller_radius
    px, py = rotate(-psi, 0.0, s0 + rise)  # pitch point in the cam frame (Norton eq. 8.32)
    path = write_profile_csv(tmp_path / "pitch.csv", px, py, curve="pitch")
    points = cam_design({k: v for k, v in section.items()
                                if k not in ("motion", "base_circle_radius")} | {"profile_file": str(path)})
    y0, phi0, lift = kinematics(design)
    y1, phi1, _ = kinematics(points)
    assert np.max(np.abs(y1 - y0)) < 1e-6 * lift
    assert np.degrees(np.max(np.abs(phi1 - phi0))) < 0.01


def test_units_in_the_header_are_honoured(tmp_path):
    x, y = working_outline(cam_design(cam_section()), n=100)
    (tmp_path / "in.csv").write_text("# inches\nx [in],y [in]\n" + "\n".join(
        f"{float(a) / 0.0254!r},{float(b) / 0.0254!r}" for a, b in zip(x, y)))
    x1, y1, curve = read_profile_csv(tmp_path / "in.csv")
    assert curve == "working" and np.allclose(x1, x, rtol=1e-12) and np.allclose(y1, y, rtol=1e-12)


def test_dxf_holds_the_closed_profile_in_millimetres(tmp_path):
    import ezdxf

    x, y = working_outline(cam_design(cam_section()), n=360)
    doc = ezdxf.readfile(write_profile_dxf(tmp_path / "cam.dxf", x, y))
    (polyline,) = doc.modelspace().query("LWPOLYLINE")
    points = np.array([p[:2] for p in polyline.get_points()])
    assert polyline.closed and np.allclose(points, np.c_[x, y] * 1e3, atol=1e-9)


SCENE = textwrap.dedent("""\
    name: points
    environment:
      history: [{duration: 1 d, temperature: 60 degC, relative_humidity: 50 %}]
    materials:
      resin: {matrix: R914}
    cam:
      material: resin
      thickness: 12 mm
      speed: 600 rpm
      profile_file: PROFILE
      follower: {kind: roller, roller_radius: 0.6 in, mass: 1.6 kg, spring_rate: 1376.7 N/in}
    """)


@pytest.mark.parametrize("profile, extra, key", [
    ("missing.csv", "", "cam.profile_file: profile file"),
    ("bad.csv", "", "cam.profile_file: profile file"),
    ("good.csv", "  base_circle_radius: 40 mm\n", "cam: give one of profile_file"),
    ("good.csv", "  bore_radius: 60 mm\n", "cam.bore_radius: must be smaller than the profile"),
])
def test_bad_profile_files_are_refused_at_their_line(tmp_path, capsys, profile, extra, key):
    x, y = working_outline(cam_design(cam_section()), n=100)
    write_profile_csv(tmp_path / "good.csv", x, y)
    (tmp_path / "bad.csv").write_text("u [mm],v [mm]\n1,2\n")
    scene = tmp_path / "scene.yaml"
    scene.write_text(SCENE.replace("PROFILE", profile) + extra)
    assert main(["check", str(scene)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and key in err and err.startswith(f"{scene}:")


def test_profile_scene_runs_and_names_the_profile_cam(tmp_path, capsys):
    x, y = working_outline(cam_design(cam_section()), n=720)
    write_profile_csv(tmp_path / "good.csv", x, y)
    scene = tmp_path / "scene.yaml"
    scene.write_text(SCENE.replace("PROFILE", "good.csv").replace(
        "kind: roller, roller_radius: 0.6 in", "kind: knife") + "outputs: {ageing_times: [0 d, 1 d]}\n")
    import fickcam

    ds = fickcam.run(scene)
    strain = ds.hygrothermal_strain.sel(part="cam").values  # isotropic resin: lift scales
    assert np.allclose(ds.lift.values, 1.5 * 0.0254 * (1 + strain), rtol=1e-7)
    assert yaml.safe_load(ds.attrs["scene_text"])["cam"]["profile_file"] == "good.csv"
