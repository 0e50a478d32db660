"""A quantity on the command line is read and judged as the same value in a scene: a bare
number is SI, an almost certain unit slip is refused with the likely unit in one line
naming the option (never an internal document), zero needs no unit, and the same number
gets the same verdict in a scene and on the command line."""
import re
from pathlib import Path

import pytest

from fickcam.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
DEMO = ROOT / "configs" / "singh2017_cam.yaml"          # 60 d history
ECCENTRIC = ROOT / "configs" / "eccentric_cam.yaml"     # 180 d history, every 30 d


def _refused(capsys, argv) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "<" not in err, err
    return err.strip()


@pytest.fixture(scope="module")
def eccentric_result(tmp_path_factory):
    path = tmp_path_factory.mktemp("eccentric") / "eccentric.h5"
    assert main(["run", str(ECCENTRIC), "-o", str(path), "-qq"]) == 0
    return path


@pytest.mark.parametrize("argv, option, number", [
    (["compensate", str(DEMO), "--at", "45"], "--at", "45"),
    (["compensate", str(DEMO), "--over", "0", "60"], "--over", "60"),
    (["compensate", str(DEMO), "--over", "30", "60 d"], "--over", "30"),
])
def test_a_bare_compensation_time_is_refused_naming_the_option(tmp_path, capsys, argv, option,
                                                               number):
    """`--at 45` made a part 'at 0.0005208 d'; `--over 0 60` was refused at an ageing
    time of an internal document."""
    err = _refused(capsys, argv + ["-o", str(tmp_path / "made.yaml")])
    assert err.startswith(f"fickcam: error: {option} {number}: {number} s is an implausible "
                          f"ageing time (the history lasts 60 d): did you mean '{number} d'?"), err
    assert not (tmp_path / "made.yaml").exists()


def test_a_window_given_with_units_is_taken_as_given(tmp_path, capsys):
    """A minute after delivery, written with its unit: no judgement of the window's times
    as bare numbers (they were judged again inside, as an internal document's)."""
    made = tmp_path / "made.yaml"
    assert main(["compensate", str(ECCENTRIC), "--over", "0", "60 s", "-o", str(made)]) == 0, \
        capsys.readouterr().err
    assert made.exists()


def test_a_compensation_time_after_the_history_names_the_option(tmp_path, capsys):
    err = _refused(capsys, ["compensate", str(DEMO), "--at", "100 d",
                            "-o", str(tmp_path / "made.yaml")])
    assert err == "fickcam: error: --at 100 d: 100 d is outside the scene's history (0 to 60 d)"


def test_a_bare_query_time_is_refused_and_zero_needs_no_unit(eccentric_result, capsys):
    err = _refused(capsys, ["query", str(eccentric_result), "lift", "--time", "45"])
    assert err.startswith("fickcam: error: --time 45: 45 s is an implausible ageing time "
                          "(the history lasts 180 d): did you mean '45 d'?")
    assert main(["query", str(eccentric_result), "lift", "--time", "0"]) == 0
    assert capsys.readouterr().out.startswith("lift at time = 0 d (stored)")


@pytest.mark.parametrize("option", ["--cam-angle", "--crank-angle"])
@pytest.mark.parametrize("bare", ["120", "5", "-0.5", "2e-3"])
def test_a_bare_angle_is_refused_with_degrees_suggested(eccentric_result, capsys, option, bare):
    """A bare 5 was taken as 5 rad (286 deg) without a word; the command line shows angles
    in degrees, so a bare angle is refused like a bare rotational speed. Zero needs no unit."""
    argv = ["query", str(eccentric_result), "contact_force", "--time", "30 d"]
    err = _refused(capsys, argv + [option, bare])  # the cam result has no crank: judged first
    number = f"{float(bare):g}"
    assert err == (f"fickcam: error: {option} {bare}: {number} without a unit is ambiguous for "
                   f"an angle (deg or rad): did you mean '{number} deg'? Give the unit "
                   f"('{number} deg' or '{number} rad')")
    if option == "--cam-angle":
        assert main(argv + [option, "120 deg"]) == 0
        assert "cam_angle = 120 deg (stored)" in capsys.readouterr().out
        assert main(argv + [option, "2 rad"]) == 0
        assert "cam_angle = 114.592 deg" in capsys.readouterr().out
        assert main(argv + [option, "0"]) == 0


@pytest.mark.parametrize("argv, expected", [
    (["size", str(DEMO), "--pressure-angle", "25"],
     "--pressure-angle 25: 25 without a unit is ambiguous for an angle (deg or rad): did "
     "you mean '25 deg'?"),
    (["size", str(DEMO), "--pressure-angle", "0.4"],
     "--pressure-angle 0.4: 0.4 without a unit is ambiguous for an angle (deg or rad)"),
    (["size", str(DEMO), "--radius-of-curvature", "5"],
     "--radius-of-curvature 5: 5 m is an implausible smallest radius of curvature (its base "
     "circle radius is 49.28 mm): did you mean '5 mm'?"),
    (["size", str(DEMO), "--pressure-angle", "30 kg"], "--pressure-angle 30 kg: '30 kg' has the "
     "wrong dimension: expected an angle (e.g. '75 deg')"),
    (["run", str(DEMO), "--accuracy", "0.5"],
     "--accuracy 0.5: must lie in (0, 0.1]"),
    (["run", str(DEMO), "--accuracy", "x"], "--accuracy x: input should be a valid number"),
    (["compensate", str(DEMO), "--at", "30 d", "--accuracy", "0"],
     "--accuracy 0: must lie in (0, 0.1]"),
    (["fit", "coupons.csv", "--matrix", "8551-7", "--fiber", "T300", "--fiber-volume-fraction",
      "60", "-o", "fitted.yaml"], "--fiber-volume-fraction 60: must not exceed 1"),
])
def test_every_quantity_option_is_refused_in_one_line_naming_it(tmp_path, monkeypatch, capsys,
                                                                 argv, expected):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "coupons.csv").write_text((ROOT / "configs" / "weight_gain_synthetic_epoxy.csv")
                                          .read_text())
    err = _refused(capsys, argv)
    assert err.startswith(f"fickcam: error: {expected}"), err
    assert not any(tmp_path.glob("*.h5")) and not (tmp_path / "fitted.yaml").exists()


@pytest.mark.parametrize("number", ["45", "0.5", "1e3", "120", "3888000", "15552000"])
def test_the_same_bare_time_gets_the_same_verdict_in_a_scene_and_on_the_command_line(
        tmp_path, eccentric_result, capsys, number):
    """The eccentric cam's history lasts 180 d, as its result's last ageing time: the same
    number as the scene's last ageing time and as `--time` is refused alike, suggesting the
    same unit, or accepted alike (3888000 s is 45 d)."""
    scene = tmp_path / "scene.yaml"
    scene.write_text(ECCENTRIC.read_text().replace("{every: 30 d}", f"[0 d, {number}]"))
    in_scene = main(["check", str(scene)])
    scene_err = capsys.readouterr().err
    on_line = main(["query", str(eccentric_result), "lift", "--time", number])
    line_err = capsys.readouterr().err
    assert in_scene == on_line
    meant = [re.findall(r"did you mean '([^']+)'", err) for err in (scene_err, line_err)]
    assert meant[0] == meant[1]
    assert (in_scene == 2) == bool(meant[0])
