"""A cam given by its DXF drawing (``cam.drawing``): the same moisture and motion as the
cam it draws, the round trip through ``fickcam profile -o cam.dxf``, and the drawings a
scene refuses in one line."""
import sys

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

import fickcam  # noqa: E402
from drawn_scenes import refused as check, scene  # noqa: E402
from fickcam.cli.main import main  # noqa: E402

def disc_drawing(folder, units=4, holes=((0.0, 0.0, 5.0, "BORE"),)):
    document = ezdxf.new("R2010")
    document.header["$INSUNITS"] = units
    space = document.modelspace()
    space.add_circle((0.0, -4.0), 23.0, dxfattribs={"layer": "PROFILE"})
    for x, y, r, layer in holes:
        space.add_circle((x, y), r, dxfattribs={"layer": layer})
    path = folder / "disc.dxf"
    document.saveas(path)
    return path


def same_moisture(a, b, accuracy=1e-3):
    m, n = (np.asarray(r["moisture_content"]) for r in (a, b))
    swing = np.nanmax(np.abs(m))
    assert np.nanmax(np.abs(m - n)) <= accuracy * swing


@pytest.mark.slow  # two runs of a nylon cam (about 10 s)
def test_a_drawn_disc_with_a_bore_ages_as_the_eccentric_cam(tmp_path):
    """On the same terms, its profile scaled by the mean strain (the field's displaced
    outline against the eccentric cam: ``test_cam_aged_profile``)."""
    disc_drawing(tmp_path)
    drawn = fickcam.run(fickcam.load_scene(scene(tmp_path, "drawn", drawing="disc.dxf",
                                                 aged_profile="mean_strain")))
    eccentric = fickcam.run(fickcam.load_scene(scene(
        tmp_path, "eccentric", eccentric={"radius": "23 mm", "eccentricity": "4 mm"},
        bore_radius="5 mm")))
    same_moisture(drawn, eccentric)
    for name in ("lift", "base_circle_radius"):
        assert np.asarray(drawn[name]) == pytest.approx(np.asarray(eccentric[name]), rel=1e-4), name
    # the closed form against a profile's search on the 2-degree grid of the outputs
    assert np.asarray(drawn["jump_speed"]) == pytest.approx(np.asarray(eccentric["jump_speed"]), rel=5e-3)


@pytest.mark.slow  # a run, a profile written, a run of the drawing (about 10 s)
def test_a_profile_written_as_dxf_and_read_back_as_a_drawing_gives_the_same_results(tmp_path):
    motion = [{"rise": "8 mm", "over": "120 deg", "law": "cycloidal"}, {"dwell": "60 deg"},
              {"return": "8 mm", "over": "120 deg", "law": "cycloidal"}, {"dwell": "60 deg"}]
    first = scene(tmp_path, "motion", motion=motion, base_circle_radius="25 mm")
    assert main(["profile", str(first), "-o", str(tmp_path / "cam.dxf"), "--points", "720"]) == 0
    made = fickcam.run(fickcam.load_scene(first))
    again = fickcam.run(fickcam.load_scene(scene(tmp_path, "drawn", drawing="cam.dxf",
                                                 aged_profile="mean_strain")))  # on its terms
    same_moisture(made, again)
    for name in ("lift", "base_circle_radius"):
        assert np.asarray(again[name]) == pytest.approx(np.asarray(made[name]), rel=1e-4), name


def test_a_drawing_without_units_is_refused_at_its_key(tmp_path, capsys):
    disc_drawing(tmp_path, units=0)
    err = check(capsys, scene(tmp_path, "drawn", drawing="disc.dxf"))
    assert "cam.drawing:" in err and "no units:" in err and "likely mm" in err
    assert main(["check", str(scene(tmp_path, "given", drawing={"file": "disc.dxf", "units": "mm"}))]) == 0


def test_a_cam_drawing_with_a_lightening_hole_ages_with_it(tmp_path, capsys):
    disc_drawing(tmp_path, holes=((0.0, 0.0, 5.0, "BORE"), (0.0, -12.0, 3.0, "LIGHTENING")))
    drawn = fickcam.load_scene(scene(tmp_path, "drawn", drawing="disc.dxf"))
    cam = drawn.parts[0]
    assert len(cam.geometry.holes) == 2 and not cam.geometry.contact_holes
    assert main(["check", str(scene(tmp_path, "drawn", drawing="disc.dxf"))]) == 0
    assert main(["check", str(scene(tmp_path, "elastic", drawing="disc.dxf", elastic=True))]) == 0


def test_a_drawn_cams_design_read_from_its_section_alone_is_the_runs(tmp_path):
    """``cam_design`` of a drawn section not handed its profile reads the drawing itself and
    gives the design the run's mechanism holds: the disc of 23 mm radius 4 mm off the bore's
    centre has its base circle at 19 mm (within the arc's flattening)."""
    from fickcam.cam.design import cam_design

    disc_drawing(tmp_path)
    drawn = fickcam.load_scene(scene(tmp_path, "drawn", drawing="disc.dxf"))
    alone, run = cam_design(drawn.model.cam), drawn.mechanisms[0].design
    assert alone.kind == run.kind == "profile"
    assert alone.base_circle_radius == pytest.approx(0.019, abs=1e-6)
    assert alone.base_circle_radius == run.base_circle_radius
    for mine, theirs in zip(alone.profile.radii(), run.profile.radii()):
        np.testing.assert_array_equal(mine, theirs)


def test_a_drawing_scene_without_the_dxf_extra_is_refused_with_the_install_command(
        tmp_path, capsys, monkeypatch):
    disc_drawing(tmp_path)
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    err = check(capsys, scene(tmp_path, "drawn", drawing="disc.dxf"))
    assert "cam.drawing:" in err and 'pip install "fickcam[dxf]"' in err
