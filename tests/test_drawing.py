"""Parts as drawn: planforms from DXF drawings and scene polygons, their exact area and
moments, the checks that refuse what cannot be a part, and the drawing written back."""
import math

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

from fickcam.drawing.dxfread import read_drawing  # noqa: E402
from fickcam.drawing.dxfwrite import Similarity, write_drawing, write_planform  # noqa: E402
from fickcam.drawing.planform import (  # noqa: E402
    DrawingError, pin_holes, polygon_planform)

TOL = 1e-6  # m, chord tolerance


def ngon(n, radius, centre=(0.0, 0.0), phase=0.0):
    a = phase + 2 * np.pi * np.arange(n) / n
    return np.column_stack([centre[0] + radius * np.cos(a), centre[1] + radius * np.sin(a)])


def rectangle(w, h, cx=0.0, cy=0.0):
    return np.array([[cx - w / 2, cy - h / 2], [cx + w / 2, cy - h / 2],
                     [cx + w / 2, cy + h / 2], [cx - w / 2, cy + h / 2]])


def rect_sums(w, h, cx, cy):
    """(A, Sx, Sy, Ixx, Iyy, Ixy) of a w x h rectangle centred at (cx, cy), about the origin."""
    a = w * h
    return np.array([a, a * cx, a * cy, w * h ** 3 / 12 + a * cy ** 2,
                     h * w ** 3 / 12 + a * cx ** 2, a * cx * cy])


def test_polygon_annulus_area_and_polar_moment_are_the_regular_polygons_exactly():
    n, big, small = 37, 0.04, 0.015
    plan = polygon_planform(ngon(n, big, (0.01, -0.02)), [ngon(n, small, (0.01, -0.02))[::-1]])
    s = math.sin(2 * math.pi / n)
    area = n / 2 * s * (big ** 2 - small ** 2)
    polar = n / 12 * s * (2 + math.cos(2 * math.pi / n)) * (big ** 4 - small ** 4)
    assert plan.area == pytest.approx(area, rel=1e-13)
    assert plan.centroid == pytest.approx((0.01, -0.02), abs=1e-15)
    ixx, iyy, ixy = plan.second_moments()
    assert ixx + iyy == pytest.approx(polar, rel=1e-11)
    assert ixx == pytest.approx(iyy, rel=1e-11) and abs(ixy) < 1e-12 * polar
    mass = plan.mass_properties(0.005, 1400.0)
    assert mass.mass == pytest.approx(1400 * 0.005 * area, rel=1e-13)
    assert mass.inertia == pytest.approx(1400 * 0.005 * polar, rel=1e-11)


def test_the_perimeter_counts_every_edge_the_holes_too():
    """A regular n-gon of circumradius R has sides 2 R sin(pi / n)."""
    n, big, small = 37, 0.04, 0.015
    plan = polygon_planform(ngon(n, big), [ngon(n, small)[::-1], rectangle(0.004, 0.002, 0.025)[::-1]])
    side = 2 * math.sin(math.pi / n)
    assert plan.perimeter == pytest.approx(n * side * (big + small) + 0.012, rel=1e-13)


def test_rectangle_with_off_centre_holes_has_the_exact_moments():
    outer, holes = (0.08, 0.03, 0.01, 0.005), [(0.01, 0.008, -0.02, 0.004), (0.012, 0.01, 0.03, 0.01)]
    plan = polygon_planform(rectangle(*outer), [rectangle(*h) for h in holes])
    sums = rect_sums(*outer) - sum(rect_sums(*h) for h in holes)
    area = sums[0]
    xc, yc = sums[1] / area, sums[2] / area
    assert plan.area == pytest.approx(area, rel=1e-13)
    assert plan.centroid == pytest.approx((xc, yc), rel=1e-12)
    expected = (sums[3] - area * yc ** 2, sums[4] - area * xc ** 2, sums[5] - area * xc * yc)
    assert plan.second_moments() == pytest.approx(expected, rel=1e-11)


def test_round_hole_in_a_scene_polygon_is_flattened_within_the_tolerance():
    plan = polygon_planform(rectangle(0.05, 0.05), [((0.0, 0.0), 0.01)], tolerance=TOL)
    exact = 0.05 ** 2 - math.pi * 0.01 ** 2
    assert 0 < plan.area - exact <= 2 / 3 * TOL * 2 * math.pi * 0.01


def new_drawing(units=4):
    document = ezdxf.new("R2010")
    document.header["$INSUNITS"] = units
    return document, document.modelspace()


def save(document, tmp_path, name="part.dxf"):
    path = tmp_path / name
    document.saveas(path)
    return path


def obround(space, length, radius, layer="OUTLINE", shuffled=True):
    """A slot outline as separate lines and arcs (mm), out of order and one line reversed."""
    pieces = [lambda: space.add_arc((0, 0), radius, 90, 270, dxfattribs={"layer": layer}),
              lambda: space.add_line((length, radius), (0, radius), dxfattribs={"layer": layer}),
              lambda: space.add_arc((length, 0), radius, -90, 90, dxfattribs={"layer": layer}),
              lambda: space.add_line((0, -radius), (length, -radius), dxfattribs={"layer": layer})]
    for add in (pieces[::-1] if shuffled else pieces):
        add()


def test_lines_and_arcs_drawn_apart_join_into_one_outline_with_circle_holes(tmp_path):
    document, space = new_drawing()
    obround(space, 60.0, 10.0)
    for x in (0.0, 60.0):
        space.add_circle((x, 0), 4.0, dxfattribs={"layer": "PINS"})
    space.add_ellipse((30, 0), major_axis=(8, 0), ratio=0.5, dxfattribs={"layer": "HOLES"})
    drawing = read_drawing(save(document, tmp_path), tolerance=TOL)
    plan = drawing.planform
    exact = (60 * 20 + math.pi * 100 - 2 * math.pi * 16 - math.pi * 8 * 4) * 1e-6
    perimeter = (120 + 2 * math.pi * 10 + 2 * 2 * math.pi * 4 + 2 * math.pi * 6.1) * 1e-3
    assert abs(plan.area - exact) <= 2 / 3 * TOL * perimeter
    assert len(plan.holes) == 3
    a, b = pin_holes(plan)
    assert np.hypot(*np.subtract(plan.hole_centre(b), plan.hole_centre(a))) == pytest.approx(0.06, abs=1e-9)
    assert {a.layer, b.layer} == {"PINS"}


def test_bulged_polyline_and_closed_spline_read_as_curves(tmp_path):
    document, space = new_drawing()
    space.add_lwpolyline([(0, -10, 0, 0, 0), (60, -10, 0, 0, 1), (60, 10, 0, 0, 0), (0, 10, 0, 0, 1)],
                         format="xyseb", close=True)
    fit = ngon(12, 5.0, (30, 0))
    space.add_spline(fit_points=[(x, y) for x, y in np.vstack([fit, fit[:1]])])
    plan = read_drawing(save(document, tmp_path), tolerance=TOL).planform
    slot = (60 * 20 + math.pi * 100) * 1e-6
    assert plan.outer.source == "LWPOLYLINE on layer 0"
    hole = polygon_planform(plan.holes[0].points).area
    assert abs(plan.area + hole - slot) <= 2 / 3 * TOL * (0.12 + math.pi * 0.02)
    assert plan.holes[0].source == "SPLINE on layer 0"
    assert hole == pytest.approx(math.pi * 25e-6, rel=0.03)  # a spline through 12 points of a circle


@pytest.mark.parametrize("code, unit", [(4, 1e-3), (1, 0.0254), (5, 1e-2)])
def test_insunits_sets_the_unit(tmp_path, code, unit):
    document, space = new_drawing(code)
    space.add_lwpolyline(rectangle(2.0, 1.0).tolist(), close=True)
    assert read_drawing(save(document, tmp_path), tolerance=TOL).planform.area == pytest.approx(2 * unit ** 2)


def test_a_drawing_without_units_is_refused_with_the_likely_unit(tmp_path):
    document, space = new_drawing(0)
    space.add_lwpolyline(rectangle(60.0, 20.0).tolist(), close=True)
    path = save(document, tmp_path)
    with pytest.raises(DrawingError, match=r"no units: .*60 units across: likely mm.*add units: mm"):
        read_drawing(path, tolerance=TOL)
    assert read_drawing(path, tolerance=TOL, units="mm").unit == 1e-3
    inches = new_drawing(0)
    inches[1].add_lwpolyline(rectangle(2.4, 0.8).tolist(), close=True)
    with pytest.raises(DrawingError, match="likely in"):
        read_drawing(save(inches[0], tmp_path, "inch.dxf"), tolerance=TOL)


def test_a_unit_the_header_contradicts_is_refused(tmp_path):
    document, space = new_drawing(4)
    space.add_lwpolyline(rectangle(60.0, 20.0).tolist(), close=True)
    with pytest.raises(DrawingError, match=r"says its unit is millimeters .* the scene says in"):
        read_drawing(save(document, tmp_path), tolerance=TOL, units="in")


def test_annotation_and_centre_lines_are_left_out_and_counted(tmp_path):
    document, space = new_drawing()
    document.layers.add("CENTRE", linetype="CENTER")
    space.add_lwpolyline(rectangle(60.0, 20.0).tolist(), close=True)
    space.add_line((-5, 0), (65, 0), dxfattribs={"layer": "CENTRE"})
    space.add_text("PART 7", dxfattribs={"layer": "NOTES"})
    space.add_point((0, 0), dxfattribs={"layer": "AXIS"})
    drawing = read_drawing(save(document, tmp_path), tolerance=TOL)
    assert drawing.planform.area == pytest.approx(1200e-6)
    assert set(drawing.left_out) == {"1 LINE on layer CENTRE", "1 TEXT on layer NOTES"}
    assert drawing.points == {"AXIS": [(0.0, 0.0)]}


def bad(tmp_path, build, match):
    document, space = new_drawing()
    build(space)
    with pytest.raises(DrawingError, match=match) as caught:
        read_drawing(save(document, tmp_path), tolerance=TOL)
    assert "\n" not in str(caught.value) and str(tmp_path) in str(caught.value)


def test_an_open_loop_names_the_entity_layer_and_point(tmp_path):
    def build(space):
        space.add_line((0, 0), (60, 0), dxfattribs={"layer": "EDGE"})
        space.add_line((60, 0), (60, 20), dxfattribs={"layer": "EDGE"})
        space.add_line((60, 20), (0, 20), dxfattribs={"layer": "EDGE"})
        space.add_line((0, 20), (0, 0.5), dxfattribs={"layer": "EDGE"})
    bad(tmp_path, build, r"open loop: the LINE on layer EDGE and what joins it end at \(0, 0.5\) mm")


def test_a_self_intersecting_outline_is_refused(tmp_path):
    bad(tmp_path, lambda s: s.add_lwpolyline([(0, 0), (60, 20), (60, 0), (0, 20)], close=True,
                                             dxfattribs={"layer": "BOWTIE"}),
        "self-intersection: the loop LWPOLYLINE on layer BOWTIE crosses itself near")


def test_a_hole_crossing_the_outline_is_refused(tmp_path):
    def build(space):
        space.add_lwpolyline(rectangle(60.0, 20.0).tolist(), close=True)
        space.add_circle((30, 10), 3.0, dxfattribs={"layer": "HOLES"})
    bad(tmp_path, build, "self-intersection: the loop LWPOLYLINE on layer 0 crosses the loop "
                         "CIRCLE on layer HOLES")


def test_a_hole_outside_the_outline_is_refused(tmp_path):
    def build(space):
        space.add_lwpolyline(rectangle(60.0, 20.0).tolist(), close=True)
        space.add_circle((80, 0), 3.0, dxfattribs={"layer": "HOLES"})
    bad(tmp_path, build, "hole outside the outline: the loop CIRCLE on layer HOLES")


def test_an_island_in_a_hole_is_refused(tmp_path):
    def build(space):
        space.add_circle((0, 0), 30.0)
        space.add_circle((0, 0), 20.0, dxfattribs={"layer": "BORE"})
        space.add_circle((0, 0), 5.0, dxfattribs={"layer": "ISLAND"})
    bad(tmp_path, build, "CIRCLE on layer ISLAND lies inside the hole CIRCLE on layer BORE")


def test_an_entity_that_cannot_be_read_is_named_by_type_and_layer(tmp_path):
    bad(tmp_path, lambda s: s.add_3dface([(0, 0, 0), (9, 0, 0), (9, 9, 1)], dxfattribs={"layer": "SOLIDS"}),
        "cannot read the 3DFACE on layer SOLIDS")


def test_a_link_without_pin_holes_is_refused():
    plan = polygon_planform(rectangle(0.06, 0.02), [rectangle(0.01, 0.005)])
    with pytest.raises(DrawingError, match="no pin holes: a link needs two round holes .* has 0"):
        pin_holes(plan)
    with pytest.raises(DrawingError, match="no pin holes: a link needs two holes on layer PINS"):
        pin_holes(plan, layer="PINS")


def test_a_file_that_is_not_dxf_is_refused(tmp_path):
    path = tmp_path / "part.dxf"
    path.write_text("not a drawing\n")
    with pytest.raises(DrawingError, match="not a readable DXF drawing"):
        read_drawing(path, tolerance=TOL)


def test_round_trip_written_planform_reads_back_within_the_chord_tolerance(tmp_path):
    plan = polygon_planform(rectangle(0.08, 0.02), [((-0.02, 0.0), 0.004), ((0.02, 0.0), 0.003)],
                            tolerance=TOL)
    again = read_drawing(write_planform(tmp_path / "out.dxf", plan), tolerance=TOL).planform
    assert again.area == pytest.approx(plan.area, rel=1e-12)
    assert [h.layer for h in again.holes] == ["HOLES", "HOLES"]


def test_a_similarity_keeps_lines_and_arcs_and_layers(tmp_path):
    document, space = new_drawing()
    obround(space, 60.0, 10.0, layer="EDGE")
    space.add_circle((0, 0), 4.0, dxfattribs={"layer": "PINS"})
    drawing = read_drawing(save(document, tmp_path), tolerance=TOL)
    move = Similarity(1.01, 0.3, (0.005, -0.002))
    out = write_drawing(tmp_path / "made.dxf", drawing, move)
    written = ezdxf.readfile(out)
    kinds = sorted((e.dxftype(), e.dxf.layer) for e in written.modelspace())
    assert kinds == [("ARC", "EDGE")] * 2 + [("CIRCLE", "PINS")] + [("LINE", "EDGE")] * 2
    assert written.units == 4
    again = read_drawing(out, tolerance=TOL).planform
    perimeter = 1.01 * (0.12 + 2 * math.pi * 0.014)
    assert abs(again.area - 1.01 ** 2 * drawing.planform.area) <= 2 * 2 / 3 * TOL * perimeter
    assert again.centroid == pytest.approx(tuple(move([drawing.planform.centroid])[0]), abs=TOL)


def test_any_other_map_writes_polylines_on_the_same_layers(tmp_path):
    document, space = new_drawing()
    obround(space, 60.0, 10.0, layer="EDGE")
    drawing = read_drawing(save(document, tmp_path), tolerance=TOL)
    stretch = np.array([1.02, 0.99])
    out = write_drawing(tmp_path / "made.dxf", drawing, lambda p: p * stretch)
    assert {(e.dxftype(), e.dxf.layer) for e in ezdxf.readfile(out).modelspace()} == {("LWPOLYLINE", "EDGE")}
    again = read_drawing(out, tolerance=TOL).planform
    assert again.area == pytest.approx(np.prod(stretch) * drawing.planform.area, rel=1e-12)


def test_reading_a_drawing_without_ezdxf_is_the_one_line_refusal(tmp_path, monkeypatch):
    import sys

    from fickcam.extras import MissingExtra

    monkeypatch.setitem(sys.modules, "ezdxf", None)
    with pytest.raises(MissingExtra, match=r'^reading or writing DXF drawings needs ezdxf: pip install "fickcam\[dxf\]"$'):
        read_drawing(tmp_path / "part.dxf", tolerance=TOL)


# ------------------------------------------------------------------ what a drawing means


def test_a_cam_drawn_as_an_eccentric_disc_turns_about_its_bore():
    from fickcam.drawing.parts import cam_of

    plan = polygon_planform(ngon(720, 0.023, (0.004, 0.0)), [((0.0, 0.0), 0.005)], tolerance=TOL)
    cam = cam_of(plan)
    assert cam.bore_radius == pytest.approx(0.005, rel=1e-12) and cam.other_holes == ()
    x, y = cam.profile
    assert np.hypot(x - 0.004, y).max() == pytest.approx(0.023, rel=1e-12)


def test_a_cam_profile_written_by_fickcam_turns_about_its_axis_point(tmp_path):
    from fickcam.cam.profile import write_profile_dxf
    from fickcam.drawing.parts import cam_of

    a = 2 * np.pi * np.arange(360) / 360
    r = 0.03 + 0.005 * np.sin(a) ** 2
    path = write_profile_dxf(tmp_path / "cam.dxf", r * np.cos(a), r * np.sin(a))
    drawing = read_drawing(path, tolerance=TOL)
    cam = cam_of(drawing.planform, drawing.points)
    assert cam.bore_radius == 0.0
    assert np.hypot(*cam.profile).max() == pytest.approx(0.035, rel=1e-9)


def test_a_cam_without_an_axis_is_refused():
    from fickcam.drawing.parts import cam_of

    with pytest.raises(DrawingError, match="no axis: draw the bore as a circle, or a point on layer AXIS"):
        cam_of(polygon_planform(ngon(40, 0.02)))


def test_a_link_is_put_in_its_frame_first_pin_at_the_origin_second_on_x():
    from fickcam.drawing.parts import link_of

    angle, shift = 0.7, np.array([0.01, 0.02])
    c, s = math.cos(angle), math.sin(angle)
    place = lambda p: np.asarray(p) @ np.array([[c, s], [-s, c]]) + shift  # noqa: E731
    outline = place(np.vstack([ngon(90, 0.008, (0.0, 0.0), 0.5 * np.pi)[:46],
                               ngon(90, 0.008, (0.05, 0.0), -0.5 * np.pi)[:46]]))
    plan = polygon_planform(outline, [(tuple(place([[0.0, 0.0]])[0]), 0.003),
                                      (tuple(place([[0.05, 0.0]])[0]), 0.003)], tolerance=TOL)
    link = link_of(plan)
    assert link.length == pytest.approx(0.05, rel=1e-12)
    first, second = (link.planform.hole_centre(h) for h in link.pins)
    assert first == pytest.approx((0.0, 0.0), abs=1e-15)
    assert second == pytest.approx((0.05, 0.0), abs=1e-15)
    assert link.planform.area == pytest.approx(plan.area, rel=1e-12)
