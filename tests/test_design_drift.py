"""The as-designed state (dry, reference temperature) beside the ageing times, and the
drift against it and against t = 0 in results, queries and the run summary."""
from pathlib import Path

import numpy as np
import pytest
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.results.query import drift
from fickcam.cli.reporting import peak, summary
from fickcam.schema import DESIGN_NOTE, VARIABLES, design_name

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
INCH = 0.0254


def cam_scene(history=None) -> dict:
    scene = yaml.safe_load((CONFIGS / "singh2017_cam.yaml").read_text())
    scene["outputs"].pop("file")
    scene["outputs"]["angle_step"] = "2 deg"
    if history is not None:
        scene["environment"]["history"] = history
        scene["outputs"]["ageing_times"] = ["0 d", "10 d", "30 d", "40 d", "60 d"]
    return scene


@pytest.fixture(scope="module")
def cam():
    return fickcam.run(cam_scene())


@pytest.fixture(scope="module")
def fourbar():
    scene = yaml.safe_load((CONFIGS / "fourbar_r914_humid.yaml").read_text())
    scene["outputs"].pop("file", None)
    scene["outputs"]["ageing_times"] = ["0 d", "30 d", "365 d"]
    scene["outputs"]["angle_step"] = "5 deg"
    return fickcam.run(scene)


def test_every_time_dependent_state_and_mechanism_variable_has_a_design_row():
    for name, var in VARIABLES.items():
        if var.section in ("parts", "cam", "linkage") and "time" in var.dims and var.design is None:
            row = VARIABLES[design_name(name)]
            assert row.dims == tuple(d for d in var.dims if d != "time")
            assert row.units == var.units and row.long_name == var.long_name + DESIGN_NOTE


def test_design_geometry_is_the_drawn_geometry_dry_at_the_reference_temperature(cam):
    assert float(cam.lift_design) == pytest.approx(1.5 * INCH, rel=1e-12)
    assert float(cam.base_circle_radius_design) == pytest.approx(1.94 * INCH, rel=1e-12)
    assert np.all(cam.moisture_content_design.values == 0)
    assert np.all(cam.strain_longitudinal_design.values == 0)
    assert np.all(cam.property_retention_design.values == pytest.approx(1.0))
    assert np.allclose(cam.mass_design.values, cam.mass.isel(time=0).values)  # dry at t = 0
    assert "time" not in cam.follower_displacement_design.dims
    assert cam.lift_design.attrs["long_name"].endswith(DESIGN_NOTE)


def test_linkage_design_lengths_are_the_scene_lengths(fourbar):
    assert np.allclose(fourbar.link_length_design.values, [0.1, 0.16, 0.16, 0.2], rtol=1e-12)
    assert str(fourbar.grashof_class_design.values) == str(fourbar.grashof_class.values[0])


def test_drift_is_the_value_minus_the_design_or_the_start(cam):
    against_design = drift(cam, "lift", "design")
    assert np.allclose(against_design.values, cam.lift.values - 1.5 * INCH, rtol=0, atol=1e-15)
    # the thermal growth at t = 0 (113 degC against 23 degC) is most of the drift
    assert against_design.values[0] == pytest.approx(cam.lift.values[0] - 1.5 * INCH)
    assert against_design.values[0] > 3 * (cam.lift.values[-1] - cam.lift.values[0])
    against_start = drift(cam, "follower_displacement", "start")
    assert np.all(against_start.isel(time=0).values == 0)
    assert against_start.dims == cam.follower_displacement.dims
    assert against_start.attrs["units"] == "m"


def test_angle_drift_wraps_into_half_a_turn(fourbar):
    change = drift(fourbar, "coupler_angle", "design").values
    assert np.nanmax(np.abs(change)) < 180


def test_summary_shows_design_start_end_and_both_drifts(cam):
    text = summary(cam)
    row = next(line for line in text.splitlines() if line.strip().startswith("lift [mm]"))
    cells = row.split()
    assert cells[2:5] == ["38.1", f"{cam.lift.values[0] * 1e3:.5g}", f"{cam.lift.values[-1] * 1e3:.5g}"]
    assert cells[5] == f"{(cam.lift.values[-1] - 1.5 * INCH) * 1e3:+.3g}"
    assert cells[6] == f"{(cam.lift.values[-1] - cam.lift.values[0]) * 1e3:+.3g}"


def test_summary_shows_the_peak_of_a_history_that_goes_up_and_down():
    wet_then_dry = [{"duration": "30 d", "temperature": "113 degC", "relative_humidity": "80 %"},
                    {"duration": "30 d", "temperature": "113 degC", "relative_humidity": "0 %"}]
    ds = fickcam.run(cam_scene(wet_then_dry))
    moisture = ds.moisture_content.sel(part="follower").values
    top = int(np.argmax(moisture))
    assert 0 < top < len(moisture) - 1
    row = next(line for line in summary(ds).splitlines() if "moisture follower" in line)
    assert f"{moisture[top]:.5g} (+{moisture[top]:.3g}) at 30 d" in row


def test_peak_only_for_histories_beyond_both_ends():
    assert peak(np.array([0.0, 1.0, 2.0, 3.0])) is None
    assert peak(np.array([0.0, 0.3, 0.1, 0.0])) == 1
    assert peak(np.array([1.0, 0.2, 0.5, 0.9])) == 1
    assert peak(np.array([0.0, 1.0, 1.0 + 1e-6, 1.0])) is None  # a wiggle, not a peak


@pytest.mark.slow
def test_query_drift_option_answers_against_design_and_start(tmp_path, cam, capsys):
    path = tmp_path / "cam.h5"
    fickcam.save(cam, path)
    assert main(["query", str(path), "lift", "--drift", "design", "--format", "csv"]) == 0
    rows = capsys.readouterr().out.splitlines()[1:]
    assert [float(r.split(",")[1]) for r in rows] == pytest.approx(
        (cam.lift.values - 1.5 * INCH) * 1e3, abs=1e-12)  # in mm, the display unit
    assert main(["query", str(path), "lift", "--drift", "start"]) == 0
    out = capsys.readouterr().out
    assert "lift drift vs start [mm]" in out
