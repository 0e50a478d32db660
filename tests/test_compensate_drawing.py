"""``fickcam compensate`` on a drawn cam also writes the drawing to make, beside the made
scene, on the drawing's own layers: under a uniform scale about the axis the circles stay
circles (the bore as drawn), under two scales every entity a polyline; and the made
drawing, run again, meets the design at the time asked."""
import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

import fickcam  # noqa: E402
from drawn_scenes import scene  # noqa: E402
from fickcam.cli.main import main  # noqa: E402
from fickcam.cam.drawn import CHORD_SHARE  # noqa: E402
from fickcam.compensation.drawn import made_drawing_writer  # noqa: E402
from fickcam.drawing.dxfread import read_drawing  # noqa: E402


def disc_drawing(folder):
    """An eccentric disc (radius 23 mm, its centre 4 mm from the axis) with a 5 mm bore
    about the axis, drawn 10 mm away from the drawing's origin, on layers PROFILE and BORE."""
    document = ezdxf.new("R2010", units=4)
    space = document.modelspace()
    space.add_circle((10.0, 6.0), 23.0, dxfattribs={"layer": "PROFILE"})
    space.add_circle((10.0, 10.0), 5.0, dxfattribs={"layer": "BORE"})
    document.saveas(folder / "disc.dxf")


@pytest.mark.slow  # a compensation (three runs) and a run of the made drawing (about 20 s)
def test_the_made_drawing_run_again_meets_the_design_at_the_time_asked(tmp_path, capsys):
    disc_drawing(tmp_path)
    drawn = scene(tmp_path, "drawn", drawing="disc.dxf")
    made = tmp_path / "made.yaml"
    assert main(["compensate", str(drawn), "--at", "60 d", "-o", str(made)]) == 0
    out = capsys.readouterr().out
    drawing = tmp_path / "made_cam.dxf"
    assert f"wrote {drawing}" in out
    document = ezdxf.readfile(drawing)
    circles = {c.dxf.layer: c for c in document.modelspace().query("CIRCLE")}
    assert set(circles) == {"PROFILE", "BORE"}  # a similarity: circles stay circles
    assert circles["BORE"].dxf.radius == pytest.approx(5.0, rel=1e-15)  # the bore as drawn
    assert tuple(circles["BORE"].dxf.center)[:2] == pytest.approx((10.0, 10.0), abs=1e-12)
    scale = circles["PROFILE"].dxf.radius / 23.0
    assert 0.98 < scale < 1.0  # the nylon plate, made smaller to swell into the design
    assert tuple(circles["PROFILE"].dxf.center)[:2] == pytest.approx((10.0, 10.0 - 4.0 * scale))

    # on the compensation's terms: the plate scaled by its mean strain
    again = fickcam.run(fickcam.load_scene(scene(tmp_path, "again", drawing="made_cam.dxf",
                                                 aged_profile="mean_strain")))
    design = fickcam.run(fickcam.load_scene(drawn))
    at = {"time": 60.0}
    for name, value in (("lift", 8e-3), ("base_circle_radius", 19e-3)):
        aged = float(again[name].sel(at))
        drift = abs(float(design[name].sel(at)) - value)
        assert abs(aged - value) <= 1e-4 * value, name  # the drawing's chord tolerance
        assert abs(aged - value) <= 1e-3 * drift, name  # against the design's drift


def test_two_scales_write_every_entity_as_a_polyline_through_its_mapped_points(tmp_path):
    disc_drawing(tmp_path)
    section = fickcam.load_scene(scene(tmp_path, "drawn", drawing="disc.dxf")).model.cam
    made_drawing_writer(section, 1e-3, (0.99, 0.98))(tmp_path / "made.dxf")
    document = ezdxf.readfile(tmp_path / "made.dxf")
    assert {e.dxftype() for e in document.modelspace()} == {"LWPOLYLINE", "CIRCLE"}
    assert {e.dxf.layer for e in document.modelspace().query("LWPOLYLINE")} == {"PROFILE"}
    outline = read_drawing(tmp_path / "made.dxf", 1e-6).planform.outer.points * 1e3 - (10.0, 10.0)
    # the disc about the axis, x by 0.99 and y by 0.98: an ellipse through the mapped points
    u, v = outline[:, 0] / 0.99, outline[:, 1] / 0.98 + 4.0
    chord = CHORD_SHARE * 1e-3 * 46.0  # [mm]: the drawing read at its extent x the accuracy
    assert np.abs(np.hypot(u, v) - 23.0).max() <= chord
