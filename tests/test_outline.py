"""``fickcam outline RESULT --time T``: the cam's aged outline as stored at a stored ageing
time, interpolated in sqrt(t) between them with an error estimate that is exact when the
outline is quadratic in sqrt(t), written as DXF (read back by fickcam's own reader to the
stored points) or CSV, and refused in one line otherwise."""
import numpy as np
import pytest
import xarray as xr

from drawn_scenes import scene
from fickcam.cli.main import main
from fickcam.errors import InputError
from fickcam.results.outline import aged_outline
from fickcam.results.store import open_result, save

DAY = 86400.0
MOTION = [{"rise": "8 mm", "over": "120 deg", "law": "cycloidal"}, {"dwell": "60 deg"},
          {"return": "8 mm", "over": "120 deg", "law": "cycloidal"}, {"dwell": "60 deg"}]


def disc_result(radius, days=(0.0, 20.0, 40.0, 60.0)):
    """A synthetic cam result: a disc of ``radius(t [s])`` [m] about the axis."""
    angle = np.radians(np.arange(0.0, 360.0, 2.0))
    r = np.array([radius(d * DAY) for d in days])[:, None]
    coords = {"time": ("time", np.asarray(days), {"units": "d"}), "cam_angle": np.degrees(angle)}
    dims = ("time", "cam_angle")
    return xr.Dataset({"profile_x": (dims, r * np.cos(angle)), "profile_y": (dims, r * np.sin(angle))},
                      coords=coords, attrs={"time_unit": "d"})


def test_at_a_stored_time_the_outline_is_the_stored_profile():
    ds = disc_result(lambda t: 0.025 * (1 + 1e-3 * np.sqrt(t / DAY)))
    outline = aged_outline(ds, "40 d")
    assert outline.error is None and outline.how == "as stored" and outline.layer == "AGED_40d"
    assert np.array_equal(outline.x, ds["profile_x"].values[2])


def test_an_outline_linear_in_sqrt_t_is_interpolated_exactly():
    radius = lambda t: 0.025 * (1 + 1e-3 * np.sqrt(t / DAY))  # noqa: E731
    outline = aged_outline(disc_result(radius), "45 d")
    assert np.hypot(outline.x, outline.y) == pytest.approx(radius(45 * DAY), rel=1e-14)
    assert outline.error == pytest.approx(0.0, abs=1e-15)
    assert outline.layer == "AGED_45d_INTERPOLATED"


@pytest.mark.parametrize("days", [5.0, 30.0, 45.0])
def test_the_error_estimate_is_the_error_when_the_outline_is_quadratic_in_sqrt_t(days):
    # r linear in t is quadratic in sqrt(t): the three-point quadratic is the truth
    radius = lambda t: 0.025 * (1 + 1e-4 * t / DAY)  # noqa: E731
    outline = aged_outline(disc_result(radius), f"{days} d")
    error = np.max(np.abs(np.hypot(outline.x, outline.y) - radius(days * DAY)))
    assert error > 1e-7
    assert outline.error == pytest.approx(error, rel=1e-6)
    assert "interpolated in sqrt(t) between the stored" in outline.how


def test_times_outside_or_between_two_stored_ones_are_refused_in_one_line():
    ds = disc_result(lambda t: 0.025, days=(0.0, 60.0))
    with pytest.raises(InputError, match=r"--time 70 d: outside the stored ageing times \(0 d to 60 d\)"):
        aged_outline(ds, "70 d")
    with pytest.raises(InputError, match="the stored times are 0 d and 60 d: ask for one"):
        aged_outline(ds, "30 d")
    with pytest.raises(InputError, match="did you mean '45 d'"):
        aged_outline(disc_result(lambda t: 0.025), "45")


@pytest.fixture(scope="module")
def cam_result(tmp_path_factory):
    folder = tmp_path_factory.mktemp("outline")
    path = folder / "cam.h5"
    assert main(["run", str(scene(folder, "cam", motion=MOTION, base_circle_radius="25 mm")),
                 "-o", str(path), "-qq"]) == 0
    return path


def test_the_written_dxf_read_back_is_the_stored_profile_on_its_layer_in_mm(cam_result, capsys):
    ezdxf = pytest.importorskip("ezdxf")
    from fickcam.drawing.dxfread import read_drawing

    out = cam_result.parent / "aged.dxf"
    assert main(["outline", str(cam_result), "--time", "60 d", "-o", str(out)]) == 0
    said = capsys.readouterr().out.strip()
    assert said == (f"wrote {out}: the cam's aged working profile at 60 d, as stored, layer "
                    f"AGED_60d, mm")
    document = ezdxf.readfile(out)
    assert document.header["$INSUNITS"] == 4
    assert {e.dxf.layer for e in document.modelspace()} == {"AGED_60d", "AXIS"}
    drawing = read_drawing(out, 1e-7)
    ds = open_result(cam_result)
    stored = np.c_[ds["profile_x"].values[-1], ds["profile_y"].values[-1]]
    read = drawing.planform.outer.points
    assert len(read) == len(stored)
    nearest = np.min(np.hypot(*(read[:, None, :] - stored[None, :, :]).transpose(2, 0, 1)), axis=0)
    assert nearest.max() < 1e-12  # the vertices as stored, to the DXF's digits
    assert drawing.points == {"AXIS": [(0.0, 0.0)]}


def test_the_csv_between_stored_times_is_in_mm_and_says_how_it_was_found(cam_result, capsys):
    out = cam_result.parent / "aged.csv"
    assert main(["outline", str(cam_result), "--time", "45 d", "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert "interpolated in sqrt(t) between the stored 40 d and 60 d; estimated error" in said
    assert out.read_text().splitlines()[0] == "x [mm],y [mm]"
    xy = np.loadtxt(out, delimiter=",", skiprows=1)
    assert 25.0 < np.hypot(*xy.T).min() < 25.5  # the aged base circle, in mm


def test_a_result_without_a_cam_is_refused_in_one_line_naming_the_command(cam_result, capsys):
    bare = cam_result.parent / "nocam.h5"
    save(open_result(cam_result).drop_vars(["profile_x", "profile_y"]), bare)
    assert main(["outline", str(bare), "--time", "60 d", "-o", str(bare.with_suffix(".dxf"))]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("fickcam: error: outline: the result holds no cam (no profile_x, profile_y): "
                   "only a cam result has an outline")
    assert not bare.with_suffix(".dxf").exists()
