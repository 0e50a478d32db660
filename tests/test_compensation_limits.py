"""`fickcam compensate` answers the engineering question: the scene's limits over the life
asked about, as designed and as compensated; the way out when compensating at one time
breaks them (--keep-limits); parametric cams made in their own parameters; every file
written together or none; DXF only when asked, refused at once without its extra.

The scene: the nylon eccentric cam of configs/eccentric_cam.yaml (a solid disc: exact
diffusion series, so the runs are quick) for two years, its motion held within 0.1 mm.
The reports are checked against running the written scene as a user would (fickcam.run).
"""
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.scene.load import read_yaml

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
DAY = 86400.0
TIMES = ["0 d", "7 d", "30 d", "90 d", "180 d", "365 d", "730 d"]


def eccentric_data(days=730, times=TIMES) -> dict:
    data = read_yaml(CONFIGS / "eccentric_cam.yaml").data
    data["environment"]["history"][0]["duration"] = f"{days} d"
    data["outputs"] = {"ageing_times": list(times), "angle_step": "4 deg"}
    data["limits"] = {"follower_displacement": {"deviation": "0.1 mm"}}
    return data


def write(path: Path, data: dict) -> Path:
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def compensate_cli(scene: Path, *options) -> tuple[int, str, str]:
    import contextlib
    import io

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(["compensate", str(scene), *options])
    return status, out.getvalue(), err.getvalue()


@pytest.fixture(scope="module")
def at_half_year(tmp_path_factory):
    """The cam compensated at 180 d by the command line; (scene, written, printed, runs)."""
    folder = tmp_path_factory.mktemp("eccentric")
    scene = write(folder / "cam.yaml", eccentric_data())
    written = folder / "made" / "cam_made.yaml"
    status, printed, err = compensate_cli(scene, "--at", "180 d", "-o", str(written))
    assert status == 0, err
    return scene, written, printed, fickcam.run(scene), fickcam.run(written)


def worst_printed(printed: str, limit: str) -> tuple[float, float]:
    """(as designed, compensated) worst ratio from the limits table's row of ``limit``."""
    row = next(line for line in printed.splitlines() if line.strip().startswith(limit + " ("))
    numbers = [float(word) for word in row.split(")", 1)[1].split() if _is_number(word)]
    return numbers[0], numbers[2]  # ratio, its time, ratio, its time


def _is_number(word: str) -> bool:
    try:
        float(word)
    except ValueError:
        return False
    return True


@pytest.mark.slow
def test_an_eccentric_cam_is_made_as_an_eccentric_cam(at_half_year):
    """Disc radius and eccentricity, no points; both grow back to the design at 180 d
    (isotropic nylon: both with the same strain), so the motion is the design's there."""
    scene, written, printed, before, after = at_half_year
    cam = read_yaml(written).data["cam"]
    assert set(cam["eccentric"]) == {"eccentricity", "radius"}
    assert "profile_file" not in cam and not list(written.parent.glob("*.csv"))
    assert "cam       disc radius" in printed and "cam       eccentricity" in printed
    made = fickcam.load_scene(written).model.cam.eccentric
    strain = after.strain_longitudinal.sel(part="cam").values[4]  # 180 d
    for value, design in ((made.radius, 23e-3), (made.eccentricity, 4e-3)):
        assert value * (1 + strain) == pytest.approx(design, abs=2e-9)  # written to the nm
    drift = np.abs(before.follower_displacement.values[4] - before.follower_displacement_design.values)
    left = np.abs(after.follower_displacement.values[4] - after.follower_displacement_design.values)
    assert drift.max() > 1e-4 and left.max() <= 1e-3 * drift.max()


def test_limits_before_and_after_are_those_of_running_the_scenes(at_half_year):
    """The printed worst ratios over 0-730 d: the design's and the written scene's runs."""
    scene, written, printed, before, after = at_half_year
    assert "limits from 0 d to 730 d" in printed
    old, new = worst_printed(printed, "follower_displacement")
    # printed to 4 significant figures; the written scene differs by its nanometre rounding
    assert old == pytest.approx(float(before.limit_ratio.max()), abs=1e-3)
    assert new == pytest.approx(float(after.limit_ratio.max()), abs=1e-3)
    assert old > 1.4 and new > 1.2  # the design drifts out; compensated it starts out


def test_out_of_spec_at_delivery_is_said_with_the_window_to_use(at_half_year):
    scene, written, printed, before, after = at_half_year
    assert after.limit_ratio.values[0, 0] > 1.0  # new, 0.13 mm off the design motion
    assert "as compensated: follower_displacement out of spec at 0 d, back in spec by 7 d" in printed
    assert f'fickcam compensate {scene} --over "0 d" "730 d"' in printed


@pytest.mark.slow
def test_keep_limits_makes_the_part_for_its_whole_life(tmp_path):
    """--keep-limits widens to 0-730 d (minimax): in spec at every stored time, as the
    written scene's own run shows; the report says what it did and why."""
    scene = write(tmp_path / "cam.yaml", eccentric_data())
    written = tmp_path / "kept.yaml"
    status, printed, err = compensate_cli(scene, "--at", "180 d", "--keep-limits", "-o", str(written))
    assert status == 0, err
    assert "--keep-limits: compensating at 180 d broke follower_displacement" in printed
    assert "every limit holds from 0 d to 730 d as compensated" in printed
    ratio = fickcam.run(written).limit_ratio.values
    assert np.all(ratio <= 1.0) and ratio.max() > 0.5
    assert worst_printed(printed, "follower_displacement")[1] == pytest.approx(float(ratio.max()), abs=1e-3)


def test_keep_limits_goes_with_at_only(tmp_path):
    scene = write(tmp_path / "cam.yaml", eccentric_data())
    status, _, err = compensate_cli(scene, "--over", "0 d", "730 d", "--keep-limits")
    assert status == 2 and "--keep-limits goes with --at" in err


@pytest.mark.slow
def test_a_cam_given_by_points_is_made_as_points(tmp_path):
    """The same disc given by its points: written as points beside the scene (the scene
    names the file relative to itself), and the written scene runs."""
    from fickcam.cam.profile import write_profile_csv

    angle = np.linspace(0.0, 2 * np.pi, 720, endpoint=False)
    write_profile_csv(tmp_path / "disc.csv", 23e-3 * np.cos(angle), 23e-3 * np.sin(angle) - 4e-3)
    data = eccentric_data(days=60, times=["0 d", "30 d", "60 d"])
    data["cam"].pop("eccentric")
    data["cam"]["profile_file"] = "disc.csv"
    scene = write(tmp_path / "points.yaml", data)
    written = tmp_path / "out" / "made.yaml"
    status, printed, err = compensate_cli(scene, "--at", "60 d", "-o", str(written))
    assert status == 0, err
    cam = read_yaml(written).data["cam"]
    assert cam["profile_file"] == "made_cam_profile.csv"
    assert (written.parent / "made_cam_profile.csv").is_file()
    assert "profile: smallest radius" in printed
    after = fickcam.run(written)
    left = np.abs(after.follower_displacement.values[-1] - after.follower_displacement_design.values)
    assert left.max() < 1e-6  # m: the 60 d drift (0.12 mm) removed


def test_base_circle_and_motion_are_made_in_their_parameters(tmp_path):
    """Base circle radius and every rise and return, scaled alike (so they still cancel);
    dwell and law as designed."""
    data = eccentric_data(days=60, times=["0 d", "60 d"])
    cam = data["cam"]
    cam.pop("eccentric")
    cam.update(base_circle_radius="20 mm", bore_radius="5 mm", motion=[
        {"dwell": "90 deg"}, {"rise": "8 mm", "over": "90 deg", "law": "cycloidal"},
        {"dwell": "90 deg"}, {"return": "8 mm", "over": "90 deg", "law": "cycloidal"}])
    data["diffusion"] = {"accuracy": 1e-2}
    scene = write(tmp_path / "motion.yaml", data)
    written = tmp_path / "made.yaml"
    status, printed, err = compensate_cli(scene, "--at", "60 d", "-o", str(written))
    assert status == 0, err
    assert "cam       base circle radius" in printed and "cam       rise of segment 2" in printed
    made = fickcam.load_scene(written).model.cam
    scale = made.base_circle_radius / 20e-3
    assert scale < 0.995  # nylon at 40 degC / 90 % RH for 60 d
    assert made.motion[1].rise / 8e-3 == pytest.approx(scale, rel=1e-6)
    assert made.motion[3].return_ == made.motion[1].rise
    assert [s.kind for s in made.motion] == ["dwell", "rise", "dwell", "return"]


def test_follower_position_includes_the_grown_base_circle(at_half_year):
    """follower_position: the roller centre above the cam axis; its lowest value is
    (R - e)(1 + eps) + Rf for the swollen disc and its steel roller, while
    follower_displacement starts from 0 at every age."""
    scene, written, printed, before, after = at_half_year
    position = before.follower_position.values
    lowest = position.min(axis=1)
    strain = before.strain_longitudinal.sel(part="cam").values
    assert before.follower_position_design.values.min() == pytest.approx(29e-3, abs=1e-9)
    assert np.allclose(lowest, 19e-3 * (1 + strain) + 10e-3, rtol=0, atol=1e-9)
    assert np.allclose(position - lowest[:, None], before.follower_displacement.values,
                       rtol=0, atol=1e-12)
    assert before.follower_position.attrs["units"] == "m"


def test_a_limit_on_follower_position_sees_the_growth(tmp_path):
    data = eccentric_data(days=180, times=["0 d", "180 d"])
    data["limits"] = {"follower_position": {"deviation": "0.2 mm"}}
    ds = fickcam.run(data)
    growth = ds.follower_position.values.min(axis=1)[-1] - 29e-3  # about 0.34 mm
    assert ds.limit_ratio.values[-1, 0] >= growth / 0.2e-3 > 1.0


def test_dxf_is_refused_at_once_without_its_extra(tmp_path, monkeypatch):
    """Before the scene is even read (a missing scene file would be the other error), one
    line with the install command, and nothing written."""
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    status, out, err = compensate_cli(tmp_path / "no_such_scene.yaml", "--at", "1 d",
                                      "--profile", str(tmp_path / "cam.dxf"))
    assert status == 2 and out == ""
    assert err.strip().count("\n") == 0
    assert 'pip install "fickcam[dxf]"' in err
    assert not list(tmp_path.iterdir())


@pytest.mark.slow
def test_nothing_is_written_when_the_command_fails(tmp_path):
    """A drawing that cannot be written (its folder is a file): the command fails after
    computing, and neither the scene nor the points beside it are left behind."""
    from fickcam.cam.profile import write_profile_csv

    angle = np.linspace(0.0, 2 * np.pi, 360, endpoint=False)
    write_profile_csv(tmp_path / "disc.csv", 23e-3 * np.cos(angle), 23e-3 * np.sin(angle) - 4e-3)
    data = eccentric_data(days=30, times=["0 d", "30 d"])
    data["cam"].pop("eccentric")
    data["cam"]["profile_file"] = "disc.csv"
    scene = write(tmp_path / "points.yaml", data)
    (tmp_path / "blocked").write_text("a file where a folder is asked for\n")
    before = sorted(p.name for p in tmp_path.iterdir())
    status, _, err = compensate_cli(scene, "--at", "30 d", "-o", str(tmp_path / "made.yaml"),
                                    "--profile", str(tmp_path / "blocked" / "cam.csv"))
    assert status != 0 and err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_dxf_is_written_when_asked(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    scene = write(tmp_path / "cam.yaml", eccentric_data(days=30, times=["0 d", "30 d"]))
    drawing = tmp_path / "made.dxf"
    status, printed, err = compensate_cli(scene, "--at", "30 d", "-o", str(tmp_path / "made.yaml"),
                                          "--profile", str(drawing))
    assert status == 0, err
    assert f"wrote {drawing}" in printed
    outline = next(iter(ezdxf.readfile(drawing).modelspace().query("LWPOLYLINE")))
    x, y = np.array([point[:2] for point in outline.get_points()]).T
    made = fickcam.load_scene(tmp_path / "made.yaml").model.cam.eccentric
    radius = np.hypot(x, y + made.eccentricity * 1e3)  # mm, about the disc's centre
    assert np.allclose(radius, made.radius * 1e3, rtol=0, atol=1e-6)


def test_each_stretch_out_of_spec_is_named():
    from fickcam.compensation.report import out_of_spec_spans

    times = np.array([0.0, 7.0, 30.0, 90.0, 180.0]) * DAY
    assert out_of_spec_spans(np.array([1.3, 0.9, 0.8, 1.1, 1.2]), times) == \
        ["at 0 d, back in spec by 7 d", "from 90 d to the end"]
    assert out_of_spec_spans(np.array([0.5, 1.2, 1.1, 0.9, 1.01]), times) == \
        ["from 7 d to 30 d, back in spec by 90 d", "at 180 d"]
    assert out_of_spec_spans(np.array([0.5, 1.0, np.nan, 0.9, 0.2]), times) == []


@pytest.mark.slow
def test_a_four_bar_made_for_half_a_year_is_said_to_be_worse_when_new(tmp_path):
    """The R914 four-bar compensated at 180 d: its links are 2 % short when dry, so it is
    further out of spec than the design at its first ageing times; the report names them,
    as running the design and the written scene shows."""
    scene = CONFIGS / "fourbar_r914_humid.yaml"
    written = tmp_path / "fourbar.yaml"
    status, printed, err = compensate_cli(scene, "--at", "180 d", "-o", str(written))
    assert status == 0, err
    before, after = fickcam.run(scene), fickcam.run(written)
    old, new = before.limit_ratio.max("limit").values, after.limit_ratio.max("limit").values
    worse = np.flatnonzero((new > old) & (new > 1.0))
    assert worse.size >= 2  # at least delivery and the first week
    from fickcam.quantities.parsing import parse_duration

    stored = [parse_duration(t) / DAY for t in read_yaml(scene).data["outputs"]["ageing_times"]]
    times = ", ".join(f"{stored[k]:.4g} d" for k in worse)
    assert (f"further out of spec than as designed at {worse.size} of {new.size} ageing times "
            f"({times})") in printed
    assert '--over "0 d" "365 d"' in printed
