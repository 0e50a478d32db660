"""Compensation: the dry dimensions to make so that the mechanism has its
design geometry at an ageing time, or stays closest to it over a window (minimax).

Checks run the written compensated scene as a user would (fickcam.run on the YAML
file) and compare with the design computed independently: the four-bar's positions
from the design link lengths (fickcam.linkage.fourbar_response) and the cam's motion
from the dry design (fickcam.cam.cam_response at zero strain)."""
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

import fickcam
from fickcam.cli.main import main
from fickcam.cam.design import CamState, cam_design
from fickcam.cam.model import cam_response
from fickcam.compensation import compensate, write_scene
from fickcam.compensation.core import made_value, residual
from fickcam.linkage import FourBarDesign, FourBarState, fourbar_response
from fickcam.scene.load import load_scene, read_yaml

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
DAY = 86400.0


def fourbar_scene(days=90, step="5 deg"):
    """configs/fourbar_r914_humid.yaml cut to ``days`` (resin links, steel frame)."""
    data = read_yaml(CONFIGS / "fourbar_r914_humid.yaml").data
    data["environment"]["history"][0]["duration"] = f"{days} d"
    data["outputs"] = {"ageing_times": ["0 d", f"{days} d"], "angle_step": step}
    return load_scene(data)


def design_rocker(scene, crank_angle):
    design = FourBarDesign.from_section(scene.model.linkage)
    return fourbar_response(design, FourBarState(design.lengths), crank_angle).variables


def wrapped_degrees(change):
    return (np.degrees(change) + 180.0) % 360.0 - 180.0


@pytest.fixture(scope="module")
def fourbar_at_end(tmp_path_factory):
    scene = fourbar_scene()
    comp = fickcam.compensate(scene, at="90 d")
    path = write_scene(comp, comp.scene, tmp_path_factory.mktemp("fourbar") / "compensated.yaml")
    return scene, comp, fickcam.run(scene), fickcam.run(path)


@pytest.mark.slow
def test_compensated_four_bar_has_its_design_link_lengths_at_that_time(fourbar_at_end):
    scene, comp, before, after = fourbar_at_end
    design = np.array(FourBarDesign.from_section(scene.model.linkage).lengths)
    drift = before.link_length.values[-1] - design
    left = after.link_length.values[-1] - design
    assert np.all(np.abs(drift) > 5e-5)  # resin links grow mm, the steel frame 0.07 mm
    assert np.all(np.abs(left) <= 1e-3 * np.abs(drift))
    assert 1 <= comp.iterations <= 5


def test_compensated_four_bar_has_its_design_rocker_angle_at_every_crank_angle(fourbar_at_end):
    scene, _, before, after = fourbar_at_end
    angles = np.radians(after.crank_angle.values)
    design = design_rocker(scene, angles)["rocker_angle"]
    error_before = wrapped_degrees(np.radians(before.rocker_angle.values[-1]) - design)
    error_after = wrapped_degrees(np.radians(after.rocker_angle.values[-1]) - design)
    assert np.max(np.abs(error_before)) > 0.5  # deg: the drift being removed
    assert np.all(np.abs(error_after) <= 1e-3 * np.max(np.abs(error_before)))


def test_compensated_scene_keeps_sections_and_names_itself(fourbar_at_end):
    scene, comp, _, after = fourbar_at_end
    assert after.attrs["scene_name"] == f"{scene.name}-compensated"
    coupler = next(m for t, m in zip(comp.targets, comp.made) if t.part == "coupler")
    point = next(m for t, m in zip(comp.targets, comp.made) if t.name == "coupler point distance")
    assert point / coupler == pytest.approx(80 / 160, rel=1e-9)  # the point grows with the coupler


def test_compensated_scene_measures_its_drift_against_the_design_it_was_made_for(fourbar_at_end):
    """The written scene's ``design:`` section: <name>_design, query.drift and limits see the
    intended design, not the smaller made links."""
    from fickcam.results.query import drift

    scene, _, before, after = fourbar_at_end
    design = FourBarDesign.from_section(scene.model.linkage).lengths
    assert np.allclose(after.link_length_design.values, design, rtol=1e-12)
    assert np.allclose(after.rocker_angle_design.values, before.rocker_angle_design.values)
    left = np.abs(drift(after, "rocker_angle").values[-1]).max()
    assert left <= 1e-3 * np.abs(drift(before, "rocker_angle").values[-1]).max()


@pytest.mark.parametrize("design, key", [
    ("design: {cam: {base_circle_radius: 40 mm}}", "design.cam: the scene has no cam section"),
    ("design: {linkage: {crank: -5 mm}}", "design.linkage.crank: must be positive"),
    ("design: {linkage: {crank: 100 mm}, gear: {}}", "design.gear: unknown key"),
])
def test_bad_design_sections_are_refused_at_their_line(tmp_path, capsys, design, key):
    text = (CONFIGS / "fourbar_r914_humid.yaml").read_text() + design + "\n"
    (tmp_path / "s.yaml").write_text(text)
    assert main(["check", str(tmp_path / "s.yaml")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and key in err, err


@pytest.mark.slow
def test_demo_cam_compensated_at_60_days_follows_the_design_motion(tmp_path, capsys):
    """Within 1 % of the uncompensated deviation (largest over the cycle) at every cam angle;
    the UD cam swells anisotropically, so it is made as points (--points), x and y apart.
    Done with the command line, as a user would."""
    data = read_yaml(CONFIGS / "singh2017_cam.yaml").data
    data["outputs"] = {"ageing_times": ["0 d", "60 d"], "angle_step": "1 deg"}
    (tmp_path / "demo.yaml").write_text(yaml.safe_dump(data))
    path = tmp_path / "made" / "cam.yaml"
    drawing = path.parent / "cam.dxf"
    assert main(["compensate", str(tmp_path / "demo.yaml"), "--at", "60 d", "--points", "-o",
                 str(path), "--profile", str(drawing)]) == 0
    printed = capsys.readouterr().out
    for line in ("fixed point settled after", "follower  roller radius", "profile: smallest radius",
                 "follower displacement µm", f"wrote {path}", f"wrote {drawing}"):
        assert line in printed
    assert (path.parent / "cam_cam_profile.csv").exists()
    assert drawing.exists()
    scene = load_scene(tmp_path / "demo.yaml")
    before, after = fickcam.run(scene), fickcam.run(path)
    design = cam_response(cam_design(scene.model.cam), CamState(),
                          np.radians(before.cam_angle.values)).variables["follower_displacement"]
    deviation = np.abs(before.follower_displacement.values[-1] - design)
    left = np.abs(after.follower_displacement.values[-1] - design)
    assert deviation.max() > 1e-4  # m: 0.26 mm
    assert np.all(left <= 0.01 * deviation.max())


@pytest.mark.slow
def test_window_compensation_beats_either_end_and_halves_the_drift(tmp_path):
    """Over 30-90 d: the largest deviation (link lengths, rocker angle) of the minimax
    dimensions is no larger than that of the dimensions made for 30 d or for 90 d, and at
    most half the uncompensated one. The end compensations are evaluated on the strain
    history of the run (their own size changes the strain by ~1e-5 of itself)."""
    scene = fourbar_scene(days=90)
    comp = compensate(scene, over=("30 d", "90 d"))
    written = read_yaml(write_scene(comp, scene, tmp_path / "window.yaml")).data
    written["outputs"]["ageing_times"] = [float(t) for t in comp.times]  # the window grid
    after = fickcam.run(written)
    strain = {t.part: after.strain_longitudinal.sel(part=t.part).values for t in comp.targets}
    design = np.array(FourBarDesign.from_section(scene.model.linkage).lengths)
    links = ("crank", "coupler", "rocker", "frame")
    eps = np.array([strain[link] for link in links]).T  # (time, link)
    made = {"window": np.array(comp.made[:4]),
            "start": design / (1 + eps[0]),
            "end": design / (1 + eps[-1]), "none": design}
    angles = np.radians(np.arange(0.0, 360.0, 5.0))
    target = design_rocker(scene, angles)["rocker_angle"]

    def worst(lengths):
        aged = lengths * (1 + eps)
        rocker = [fourbar_response(FourBarDesign(*row), FourBarState(tuple(row)), angles)
                  .variables["rocker_angle"] for row in aged]
        return (np.max(np.abs(aged - design)),
                np.max(np.abs(wrapped_degrees(np.array(rocker) - target))))

    result = {name: worst(lengths) for name, lengths in made.items()}
    for k in (0, 1):
        assert result["window"][k] <= min(result["start"][k], result["end"][k]) * (1 + 1e-6)
        assert result["window"][k] <= 0.5 * result["none"][k]
    assert max(comp.residual) == pytest.approx(result["window"][0], rel=1e-3)


def test_minimax_dimension_is_the_midrange_of_the_strain():
    """|L (1 + eps) - D| is largest at the strain extremes: equal and opposite there."""
    strain = np.array([0.002, 0.011, 0.02, 0.017])
    made = made_value(0.1, strain)
    assert made * (1 + 0.002) - 0.1 == pytest.approx(-(made * (1 + 0.02) - 0.1), rel=1e-12)
    assert residual(0.1, made, strain) == pytest.approx(made * 0.009, rel=1e-12)
    for other in (made * 0.999, made * 1.001):
        assert residual(0.1, other, strain) > residual(0.1, made, strain)


def test_compensation_time_outside_the_history_is_refused(capsys):
    assert main(["compensate", str(CONFIGS / "fourbar_r914_humid.yaml"), "--at", "2 yr"]) == 2
    assert "outside the scene's history" in capsys.readouterr().err


@pytest.mark.slow
def test_compensated_example_scenes_stay_in_their_bands_over_their_windows(example_result):
    """configs/*_compensated.yaml (written by fickcam compensate --over): the demo cam
    inside its 0.25 mm band for all 60 d, the R914 four-bar inside every deviation band
    from 30 d to a year (it cannot be held through its first weeks of uptake)."""
    cam = example_result("singh2017_cam_compensated")
    assert np.all(cam.limit_ratio.sel(limit="follower_displacement").values <= 1.0)
    fourbar = example_result("fourbar_r914_humid_compensated")
    window = fourbar.ageing_time.values >= 30.0
    for name in ("rocker_angle", "coupler_point_x", "coupler_point_y"):
        assert np.all(fourbar.limit_ratio.sel(limit=name).values[window] <= 1.0), name
    assert np.isfinite(fourbar.time_out_of_spec.sel(limit="rocker_angle"))  # at the start


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 0.05), min_size=2, max_size=40),
       st.floats(0.01, 1.0))
def test_minimax_never_loses_to_compensating_at_any_one_time(strains, length):
    """For any strain history with eps >= 0: the minimax dimension's largest deviation is no
    larger than that of a dimension made for any single time, and at most half the
    uncompensated one (max eps L)."""
    strain = np.array(strains)
    best = residual(length, made_value(length, strain), strain)
    for eps in strain:
        assert best <= residual(length, length / (1 + eps), strain) * (1 + 1e-12) + 1e-15
    assert best <= 0.5 * residual(length, length, strain) * (1 + 1e-12) + 1e-15
