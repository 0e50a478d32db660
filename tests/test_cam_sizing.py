"""Cam sizing: the smallest base circle meets the limits and anything smaller does not;
a roller's radius of curvature defaults to the roller's radius (Norton); a size that a
bound makes degenerate says so; `fickcam size` sizes dry and aged in at most five runs
of the scene, and says how much the moisture depends on the size."""
import math
from collections import Counter
from dataclasses import replace

import numpy as np
import pytest

import fickcam.compensation.base_circle
import fickcam.simulation.ageing
from fickcam.cam import CamDesign
from fickcam.cam.motion import segments_from_spec
from fickcam.cam.sizing import (Limits, contact_stress_radius, degenerate_notes,
                                smallest_base_circle, worst)
from fickcam.compensation.base_circle import MAX_RUNS
from fickcam.cam.spec import Segment
from fickcam.cli.main import main


def design(kind="roller", offset=0.0):
    segments = segments_from_spec([Segment(dwell=math.radians(90)),
                                   Segment(rise=0.02, over=math.radians(90), law="cycloidal"),
                                   Segment(dwell=math.radians(90)),
                                   Segment(**{"return": 0.02}, over=math.radians(90), law="polynomial_345")])
    return CamDesign("motion", 0.05, 0.01, 60.0, kind, 0.5, segments=segments,
                     roller_radius=0.008 if kind == "roller" else 0.0, offset=offset)


@pytest.mark.parametrize("kind, offset, limits", [
    ("roller", 0.0, Limits(math.radians(30), 0.0)),
    ("roller", 0.006, Limits(math.radians(25), 0.004)),
    ("roller", 0.0, Limits(math.radians(30))),
    ("flat", 0.0, Limits(math.radians(30), 0.01)),
])
def test_smallest_base_circle_is_the_boundary_of_the_limits(kind, offset, limits):
    d = design(kind, offset)
    size = smallest_base_circle(d, limits)["base_circle_radius"]
    least = limits.for_design(d).radius_of_curvature
    phi, rho = worst(replace(d, base_circle_radius=size))
    assert phi <= limits.pressure_angle + 1e-12 and rho >= least and rho > 0
    phi, rho = worst(replace(d, base_circle_radius=size - 2e-6))
    assert phi > limits.pressure_angle or rho < least or rho <= 0


def test_a_roller_s_radius_of_curvature_defaults_to_the_roller_s_radius():
    d = design()
    size = smallest_base_circle(d, Limits(math.radians(30)))["radius_of_curvature"]
    assert worst(replace(d, base_circle_radius=size))[1] >= d.roller_radius
    assert worst(replace(d, base_circle_radius=size - 2e-6))[1] < d.roller_radius
    assert Limits().for_design(design("flat")).radius_of_curvature == 0.0


def test_a_size_that_no_limit_sets_says_which_bound_and_what_to_set():
    over = math.radians(150)  # 2 mm rise and return over 150 deg each, 6 mm roller
    segments = segments_from_spec([Segment(rise=0.002, over=over, law="cycloidal"),
                                   Segment(dwell=math.radians(30)),
                                   Segment(**{"return": 0.002}, over=over, law="cycloidal"),
                                   Segment(dwell=math.radians(30))])
    gentle = CamDesign("motion", 0.03, 0.01, 30.0, "roller", 0.3, segments=segments, roller_radius=0.006)
    sizes = smallest_base_circle(gentle, Limits(math.radians(25), 0.0))
    assert sizes["base_circle_radius"] == sizes["floor"] < 1e-6
    notes = degenerate_notes(gentle, sizes)
    assert len(notes) == 1 and "no limit sets this size" in notes[0]
    assert "cam.bore_radius" in notes[0] and "--radius-of-curvature" in notes[0]
    sized = smallest_base_circle(gentle, Limits(math.radians(25)))  # the designer's default
    assert sized["base_circle_radius"] > 1e-3 and degenerate_notes(gentle, sized) == []


def test_a_nearly_pointed_profile_is_told():
    flat = design("flat")
    sizes = smallest_base_circle(flat, Limits(math.radians(30)))
    notes = degenerate_notes(flat, sizes)
    assert len(notes) == 1 and "nearly pointed" in notes[0] and "--radius-of-curvature" in notes[0]
    wider = smallest_base_circle(flat, Limits(math.radians(30), 0.005))
    assert degenerate_notes(flat, wider) == []


SCENE = """
name: sized
environment: {history: [{duration: 60 d, temperature: 40 degC, relative_humidity: 85 %}]}
materials: {pom: {plastic: acetal}}
cam:
  material: pom
  base_circle_radius: 30 mm
  thickness: 10 mm
  speed: 300 rpm
  follower: {kind: roller, roller_radius: 8 mm, mass: 0.5 kg, spring_rate: 2 N/mm, spring_preload: 20 N}
  motion:
    - dwell: 90 deg
    - {rise: 20 mm, over: 90 deg, law: cycloidal}
    - dwell: 90 deg
    - {return: 20 mm, over: 90 deg, law: polynomial_345}
outputs: {ageing_times: {every: 10 d}, angle_step: 2 deg}
limits:
  follower_position: {deviation: 0.01 mm}
"""


@pytest.mark.slow
def test_size_sizes_dry_and_aged_in_at_most_five_runs(tmp_path, capsys, monkeypatch):
    scene = tmp_path / "cam.yaml"
    scene.write_text(SCENE)
    counts = Counter()

    def counted(name, function):
        def call(*args, **kwargs):
            counts[name] += 1
            return function(*args, **kwargs)
        return call

    monkeypatch.setattr(fickcam.compensation.base_circle, "run",
                        counted("runs", fickcam.compensation.base_circle.run))
    monkeypatch.setattr(fickcam.simulation.ageing, "solve_problem",
                        counted("solves", fickcam.simulation.ageing.solve_problem))
    assert main(["size", str(scene), "--pressure-angle", "30 deg"]) == 0
    out = capsys.readouterr().out
    assert 2 <= counts["runs"] <= MAX_RUNS and counts["solves"] == counts["runs"]  # the cam alone absorbs
    dry = smallest_base_circle(replace(design(), base_circle_radius=0.03),
                               Limits(math.radians(30)))["base_circle_radius"]
    assert f"dry alone {math.ceil(dry * 1e6 - 1e-6) / 1e3:.3f} mm" in out
    assert "moisture: the cam's mean moisture at" in out and "runs of the scene" in out
    assert "aged, with the sized cam's own moisture" in out and "meets the limits" in out
    assert "NOT" not in out and "note:" not in out
    assert main(["size", str(scene), "--pressure-angle", "30 kg"]) == 2


def test_a_flat_face_s_contact_stress_radius_keeps_the_hertz_pressure_at_first_yield():
    """rho = F E* / (pi L (S / 0.30)^2): at that radius Johnson's p0 = sqrt(F E*/(pi L rho))
    is S / 0.30, where the largest shear stress below the surface reaches S."""
    from fickcam.cam.dynamics import hertz_line_pressure, subsurface_shear

    force, e_star, length, strength = 40.0, 3.1e9, 0.01, 55e6
    radius = contact_stress_radius(np.array([[0.5, 1.0], [0.25, np.nan]]) * force * e_star, length,
                                   np.array([[strength], [strength]]))
    p0 = hertz_line_pressure(force, length, radius, None, e_star)
    shear, _ = subsurface_shear(p0, 1.0)
    assert shear == pytest.approx(strength, rel=1e-12)
    assert contact_stress_radius(np.zeros(3), length, strength) == 0.0


FLAT = SCENE.replace("kind: roller, roller_radius: 8 mm", "kind: flat").replace(
    "{ageing_times: {every: 10 d}", "{ageing_times: [0 d, 30 d, 60 d]").replace("20 mm", "8 mm")


def test_a_flat_face_is_sized_for_its_contact_stress_and_a_pointed_answer_is_not_run(
        tmp_path, capsys, monkeypatch):
    """A flat face asked only a convex profile: the answer was a nearly pointed cam, whose
    plate the run at the answer meshed with 140k cells. The default is now the radius the
    contact stress asks, and a degenerate answer is told without a run there."""
    import fickcam

    scene = tmp_path / "flat.yaml"
    scene.write_text(FLAT)
    ds = fickcam.run(fickcam.load_scene(str(scene)))
    runs = []
    monkeypatch.setattr(fickcam.compensation.base_circle, "run", lambda *a, **k: runs.append(1) or ds)
    assert main(["size", str(scene)]) == 0
    out = capsys.readouterr().out
    assert len(runs) == 1  # the scene's own run only
    cam = ds.sel(part="cam")  # an independent E*: the surface modulus and a steel face
    e_star = 1 / ((1 - 0.35 ** 2) / cam["surface_modulus"] + (1 - 0.3 ** 2) / 210e9)
    allowable = 55e6 * cam["surface_property_retention"] / 0.30
    expected = float((ds["contact_force"].max("cam_angle") * e_star
                      / (np.pi * 0.01 * allowable ** 2)).max())
    assert f"radius of curvature >= {expected * 1e3:.4g} mm (the flat face's Hertz contact " \
           f"stress: 0.30 p0 within the cam's shear strength, 55 MPa)" in out, out
    assert "no run at a degenerate size" in out and "nearly pointed" in out


def test_a_cam_that_cannot_be_sized_is_refused_before_any_run(tmp_path, capsys, monkeypatch):
    scene = tmp_path / "cam.yaml"
    scene.write_text(SCENE.replace("base_circle_radius: 30 mm", "eccentric: {eccentricity: 4 mm, radius: 23 mm}")
                     .split("  motion:")[0] + "outputs: {ageing_times: [0 d, 60 d]}\n")
    counts = Counter()
    monkeypatch.setattr(fickcam.compensation.base_circle, "run", lambda *a, **k: counts.update(["runs"]))
    assert main(["size", str(scene)]) == 2
    assert counts["runs"] == 0 and "motion segments" in capsys.readouterr().err


CUSP = FLAT.replace("8 mm", "20 mm").replace(
    "limits:\n  follower_position: {deviation: 0.01 mm}\n", "")
UNDERCUT = SCENE.replace("base_circle_radius: 30 mm", "base_circle_radius: 5 mm").replace(
    "roller_radius: 8 mm", "roller_radius: 15 mm").replace(
    "rise: 20 mm, over: 90 deg", "rise: 30 mm, over: 60 deg").replace(
    "return: 20 mm, over: 90 deg", "return: 30 mm, over: 120 deg")


def cycloidal_cusp_radius(h: float, beta: float) -> float:
    """The base circle [m] below which a flat face's cycloidal rise h [m] over beta [rad]
    has a cusp: rho = Rb + s + s'' (Norton 2012, eq. 8.31) at its least, found by a bounded
    scalar search on the closed form rather than the cam's sampled response."""
    from scipy.optimize import minimize_scalar

    def rho_less_rb(x):
        return h * (x - math.sin(2 * math.pi * x) / (2 * math.pi)) \
            + 2 * math.pi * h / beta ** 2 * math.sin(2 * math.pi * x)

    found = minimize_scalar(rho_less_rb, bounds=(0.5, 1.0), method="bounded",
                            options={"xatol": 1e-10})
    return -found.fun


def test_a_profile_with_a_cusp_is_refused_at_the_base_circle_with_the_size_without_one(
        tmp_path, capsys):
    """A flat face's 20 mm cycloidal rise over 90 deg on a 30 mm base circle: the profile
    crosses itself. `check` and `run` refuse it in one line at the base circle's line,
    naming the smallest base circle with a convex profile (the closed form's, to the
    0.25 deg sampling of the check and the micrometre the message prints)."""
    scene = tmp_path / "cusp.yaml"
    scene.write_text(CUSP)
    threshold = cycloidal_cusp_radius(0.02, math.pi / 2)
    assert 0.0325 < threshold < 0.0330  # above the scene's 30 mm: a cusp
    for command in (["check", str(scene)], ["run", str(scene), "-o", str(tmp_path / "x.nc")]):
        assert main(command) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1, err
        assert err.startswith(f"{scene}:7 cam.base_circle_radius: 30 mm gives the flat face's "
                              f"profile a cusp"), err
        said = float(err.split("the smallest without one is ")[1].split(" mm")[0]) * 1e-3
        assert threshold <= said <= threshold + 2e-6
    assert not (tmp_path / "x.nc").exists()


def test_a_roller_s_undercut_is_refused_like_a_cusp(tmp_path, capsys):
    scene = tmp_path / "undercut.yaml"
    scene.write_text(UNDERCUT)
    assert main(["check", str(scene)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "cam.base_circle_radius: 5 mm gives the roller's " \
                                          "profile an undercut" in err, err
    segments = segments_from_spec([
        Segment(dwell=math.radians(90)), Segment(rise=0.03, over=math.radians(60), law="cycloidal"),
        Segment(dwell=math.radians(90)),
        Segment(**{"return": 0.03}, over=math.radians(120), law="polynomial_345")])
    d = replace(design(), base_circle_radius=0.005, roller_radius=0.015, segments=segments)
    said = float(err.split("the smallest without one is ")[1].split(" mm")[0]) * 1e-3
    _, rho = worst(replace(d, base_circle_radius=said))
    assert rho > 0
    _, rho = worst(replace(d, base_circle_radius=said - 2e-6))
    assert rho <= 0


def test_size_sizes_a_cam_whose_own_profile_has_a_cusp(tmp_path, capsys):
    """`size` is how a cusp is mended: it runs from a convex cam, not the scene's own."""
    scene = tmp_path / "cusp.yaml"
    scene.write_text(CUSP)
    assert main(["size", str(scene)]) == 0
    out = capsys.readouterr().out
    answer = float(out.split("smallest base circle radius ")[1].split(" mm")[0]) * 1e-3
    assert answer >= cycloidal_cusp_radius(0.02, math.pi / 2)
    assert "meets the limits" in out and "NOT" not in out


def test_a_scene_with_another_model_has_its_mechanisms_rebuilt(tmp_path):
    """The sizing's runs at other base circles age the cam at that base circle."""
    import fickcam

    path = tmp_path / "cam.yaml"
    path.write_text(SCENE)
    scene = fickcam.load_scene(str(path))
    cam = scene.model.cam.model_copy(update={"base_circle_radius": 0.045})
    other = scene.with_model(scene.model.model_copy(update={"cam": cam}))
    assert other.mechanism("cam").design.base_circle_radius == 0.045
    assert scene.mechanism("cam").design.base_circle_radius == 0.03
