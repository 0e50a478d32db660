"""A cam plate written in the scene (``cam.outline`` with ``cam.holes``): its mass, centre
of mass and moment of inertia by Green's theorem against closed forms, the same moisture
as the cam it writes out, and the polygons a scene refuses at their key."""
import numpy as np
import pytest

import fickcam
from fickcam.cli.main import main
from drawn_scenes import refused as check, scene as drawn_scene

DENSITY = 1140.0  # kg/m^3, the dry density of the nylon below
THICKNESS = 0.010


def scene(folder, name="outline", **cam):
    return drawn_scene(folder, name, **cam)


def mm(points):
    return [[f"{x:.9g} mm", f"{y:.9g} mm"] for x, y in points]


def circle(radius, n, centre=(0.0, 0.0)):
    angle = 2 * np.pi * np.arange(n) / n
    return np.column_stack([centre[0] + radius * np.cos(angle), centre[1] + radius * np.sin(angle)])


def plate(path):
    loaded = fickcam.load_scene(path)
    cam = loaded.mechanisms[0]
    return loaded, cam, cam.planform.mass_properties(THICKNESS, cam.materials["nylon"].dry_density)


def test_a_disc_with_a_bore_has_the_closed_form_mass_and_inertia(tmp_path):
    n, big, small = 720, 25.0, 5.0  # mm
    loaded, cam, mass = plate(scene(tmp_path, outline=mm(circle(big, n)),
                                    holes=[{"centre": ["0 mm", "0 mm"], "radius": "5 mm"}]))
    rho_t = cam.materials["nylon"].dry_density * THICKNESS
    R, r = big * 1e-3, small * 1e-3
    # inscribed polygons: the area falls short by (2 pi^2 / 3) / n^2 of the circle's, the
    # polar moment by twice that (to leading order); the bore's chords follow the accuracy
    area_share = 2 * np.pi ** 2 / 3 / n ** 2
    assert mass.mass == pytest.approx(rho_t * np.pi * (R ** 2 - r ** 2), rel=1.1 * area_share)
    assert mass.inertia == pytest.approx(rho_t * np.pi * (R ** 4 - r ** 4) / 2,
                                         rel=2.2 * area_share)
    assert np.hypot(*mass.centre) <= 1e-12 * R
    assert cam.section.bore_radius == pytest.approx(r)
    assert loaded.parts[0].dry_mass == pytest.approx(mass.mass, rel=1e-12)


def test_a_rectangle_off_the_axis_has_the_exact_mass_centre_and_inertia(tmp_path):
    a, b, centre = 40.0, 20.0, (6.0, -3.0)  # mm
    corners = np.array([[-a, -b], [a, -b], [a, b], [-a, b]]) / 2 + centre
    _, cam, mass = plate(scene(tmp_path, outline=mm(corners)))
    m = cam.materials["nylon"].dry_density * THICKNESS * a * b * 1e-6
    assert mass.mass == pytest.approx(m, rel=1e-12)
    assert np.asarray(mass.centre) == pytest.approx(np.asarray(centre) * 1e-3, rel=1e-12)
    assert mass.inertia == pytest.approx(m * (a ** 2 + b ** 2) * 1e-6 / 12, rel=1e-12)


def test_check_prints_the_plate_s_mass_centre_and_inertia(tmp_path, capsys):
    corners = np.array([[30.0, 0.0], [0.0, 25.0], [-25.0, 0.0], [0.0, -25.0]])
    assert main(["check", str(scene(tmp_path, outline=mm(corners),
                                    holes=[{"centre": ["0 mm", "0 mm"], "radius": "5 mm"}]))]) == 0
    out = capsys.readouterr().out
    # a rhombus of diagonals 55 and 50 mm less the bore: 1296.46 mm^2, centroid 1.768 mm
    grams = (1375.0 - np.pi * 25.0) * 10.0 * 1e-3 * DENSITY * 1e-3
    line = next(line for line in out.splitlines() if "cam plate:" in line)
    assert f"{grams:.4g} g, centre of mass (1.768, 0) mm from the axis" in line


SQUARE = [[20.0, -20.0], [20.0, 20.0], [-20.0, 20.0], [-20.0, -20.0]]


@pytest.mark.parametrize("cam, key, words", [
    ({"outline": [[20, -20], [20, 20], [-20, 20], [-20, -20]]}, "cam.outline:",
     "likely given in mm"),
    ({"outline": mm([[20, -20], [-20, 20], [20, 20], [-20, -20]])}, "cam.outline:",
     "self-intersection: the loop given as outline crosses itself"),
    ({"outline": mm(SQUARE), "holes": [{"centre": ["0 mm", "0 mm"], "radius": "40 mm"}]},
     "cam.holes.0:", "hole outside the outline"),
    ({"outline": mm(SQUARE), "holes": [mm([[30, 0], [40, 0], [35, 5]])]}, "cam.holes.0:",
     "hole outside the outline: the loop given as holes[0]"),
    ({"outline": mm(SQUARE), "holes": [{"centre": ["10 mm", "0 mm"], "radius": "3 mm"}],
      "elastic": True}, "cam.elastic:", "holes (given as holes[0]) at its bore, and this one "
                                        "has none"),
    ({"holes": [{"centre": ["0 mm", "0 mm"], "radius": "5 mm"}]}, "cam:", "give outline too"),
    ({"outline": mm(SQUARE), "base_circle_radius": "20 mm"}, "cam:", "give one of"),
    ({"outline": mm(SQUARE), "holes": [{"centre": ["0 mm", "0 mm"], "radius": "5 mm"}],
      "bore_radius": "6 mm"}, "cam.bore_radius:", "the plate's bore has radius 5 mm"),
])
def test_a_polygon_that_cannot_be_a_cam_is_refused_at_its_key(tmp_path, capsys, cam, key, words):
    err = check(capsys, scene(tmp_path, **cam))
    assert "outline.yaml:" in err and key in err and words in err, err


def test_a_bore_radius_alone_is_the_bore_of_the_outline(tmp_path):
    _, cam, mass = plate(scene(tmp_path, outline=mm(SQUARE), bore_radius="5 mm"))
    rho_t = cam.materials["nylon"].dry_density * THICKNESS
    area_share = 0.01 * 1e-3  # the bore's chords: CHORD_SHARE x the accuracy of its radius
    bore = np.pi * 0.005 ** 2
    assert mass.mass == pytest.approx(rho_t * (0.04 ** 2 - bore), abs=rho_t * bore * 2 * area_share)


@pytest.mark.slow  # two runs of a nylon cam (about 10 s)
def test_an_outline_disc_with_a_bore_ages_as_the_eccentric_cam(tmp_path):
    disc = circle(23.0, 720, centre=(0.0, -4.0))
    written = fickcam.run(fickcam.load_scene(scene(
        tmp_path, outline=mm(disc), holes=[{"centre": ["0 mm", "0 mm"], "radius": "5 mm"}],
        aged_profile="mean_strain")))  # on the eccentric cam's terms
    eccentric = fickcam.run(fickcam.load_scene(scene(
        tmp_path, "eccentric", eccentric={"radius": "23 mm", "eccentricity": "4 mm"},
        bore_radius="5 mm")))
    m, n = (np.asarray(r["moisture_content"]) for r in (written, eccentric))
    assert np.nanmax(np.abs(m - n)) <= 1e-3 * np.nanmax(np.abs(n))
    for name in ("lift", "base_circle_radius"):
        assert np.asarray(written[name]) == pytest.approx(np.asarray(eccentric[name]), rel=1e-4), name
