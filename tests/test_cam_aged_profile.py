"""A drawn cam's aged working profile as its outline displaced by its moisture field
(``cam.aged_profile: field``): the displacement of the field's unevenness about the axis
(nothing under a uniform field; exact for a compatible linear field; converging with the
mesh at P2's order on a smooth one), and a drawn disc with a bore against the eccentric
cam it draws."""
import numpy as np
import pytest
import yaml

from drawn_scenes import scene
from fickcam.elastic.displacement import uneven_outline_shifts
from fickcam.elastic.fem import stiffness_matrix
from test_cam_plate_holes import MM, plate_with_holes

BETA = np.array([3e-3, 3e-3])  # 1 / weight %
UD = stiffness_matrix(140e9, 10e9, 5e9, 0.3)  # an orthotropic plate: u does not depend on it


def test_a_uniform_field_moves_the_outline_by_nothing():
    planform = plate_with_holes(1e-5)

    def moisture(points):
        return np.full((2, len(points)), 1.7)

    shifts = uneven_outline_shifts(planform, moisture, BETA, 2 * MM, stiffness=UD)
    # round-off of the field's mean (1e-16 of 1.7 %) times beta times the plate's size
    assert np.max(np.abs(shifts)) < 1e-15 * 1.7 * BETA[0] * 0.06 * 1e3


def test_a_linear_field_gives_the_exact_displacement_about_the_axis():
    """A free strain linear in x, theta = beta c (x - x_m), is compatible: stress-free, with
    u = beta c ((x^2 - y^2) / 2 - x_m x, x y - x_m y), whose rotation beta c y averages
    beta c y_c over the plate; about the axis (the bore's centre stays, the mean rotation
    is taken out) the outline moves by u - beta c y_c (-y, x). P2 holds it exactly (a round
    bore: the mean of the quadratic terms over its regular polygon's vertices is 0)."""
    planform = plate_with_holes(1e-5, keyed=False)
    c = 100.0  # weight % per metre
    _, xc, yc = planform.sums()[:3] / planform.area

    def moisture(points):
        return np.stack([c * points[:, 0], -c * points[:, 0]])

    shifts = uneven_outline_shifts(planform, moisture, BETA, 3 * MM, stiffness=UD)
    x, y = planform.outer.points.T
    for sign, shift in zip((1, -1), shifts):
        k = sign * BETA[0] * c
        exact = k * np.column_stack([(x * x - y * y) / 2 - xc * x + yc * y,
                                     x * y - xc * y - yc * x])
        assert np.max(np.abs(shift - exact)) < 1e-9 * np.max(np.abs(exact))


@pytest.mark.slow  # four meshes down to 0.5 mm (about 10 s)
def test_the_outline_s_displacement_converges_with_the_mesh():
    """A smooth uneven field (wet rim, dry hub) on the plate with a keyway and lightening
    holes, meshes halving from 2 mm: the differences fall as h^p, measured p = 1.9 (P2's
    h^3 on a smooth solution, lowered by the keyway's re-entrant corners, where the
    solution is singular); the run's mesh (1/100 of the extent, 0.6 mm) within 2e-3 of
    the shift of the finest."""
    planform = plate_with_holes(1e-5)

    def moisture(points):
        return np.stack([np.exp(np.hypot(*points.T) / (10 * MM))])

    spacings = (2 * MM, 1 * MM, 0.5 * MM)
    shifts = [uneven_outline_shifts(planform, moisture, BETA, h, stiffness=UD)[0] for h in spacings]
    differences = [np.max(np.abs(a - b)) for a, b in zip(shifts, shifts[1:])]
    assert np.log2(differences[0] / differences[1]) >= 1.7, differences
    run = uneven_outline_shifts(planform, moisture, BETA, planform.extent() / 100, stiffness=UD)[0]
    assert np.max(np.abs(run - shifts[-1])) <= 2e-3 * np.max(np.abs(shifts[-1]))


def test_a_drawn_cam_keeps_its_field_unless_the_scene_asks_for_the_mean_strain(tmp_path):
    import fickcam

    holes = [{"centre": ["0 mm", "0 mm"], "radius": "5 mm"}]
    outline = [[f"{23 * np.cos(a):.6f} mm", f"{23 * np.sin(a) - 4:.6f} mm"]
               for a in np.linspace(0, 2 * np.pi, 91)[:-1]]
    assert fickcam.load_scene(scene(tmp_path, "field", outline=outline, holes=holes)).field_parts \
        == {"cam"}
    mean = scene(tmp_path, "mean", outline=outline, holes=holes, aged_profile="mean_strain")
    assert fickcam.load_scene(mean).field_parts == frozenset()
    eccentric = yaml.safe_load(scene(tmp_path, "e", eccentric={"radius": "23 mm",
                                                               "eccentricity": "4 mm"}).read_text())
    assert fickcam.load_scene(eccentric).field_parts == frozenset()


@pytest.mark.slow  # two runs of a nylon cam over two years (about 15 s)
def test_a_drawn_disc_s_displaced_outline_is_the_eccentric_cam_s_once_saturated(tmp_path):
    """The drawn disc with a bore (the field's displaced outline) against the eccentric cam
    (scaled by its mean strain), 720 d at 40 degC / 90 % RH: the same moisture, and at 0 d
    and once saturated the same lift and base circle (the polygon's chords: 1.1e-5); the
    jump speed, which reads the profile's curvature, differs by 2.5e-3 already dry, and by
    the same once saturated. In between, the wet skin swells round a dry core, and the
    bore's centre moves from the disc's by the core's smaller strain: measured, the lift 11, 16, 15 and 3.8 um
    below the eccentric cam's at 5, 20, 60 and 180 d (of 40, 74, 112 and 138 um of
    growth), the base circle 6.3, 9.4, 8.9 and 2.4 um above, the follower's displacement
    within 16 um."""
    import fickcam
    from test_drawing_scene import disc_drawing, same_moisture

    disc_drawing(tmp_path)
    longer = {"environment": {"history": [{"duration": "720 d", "temperature": "40 degC",
                                           "relative_humidity": "90 %"}]},
              "outputs": {"ageing_times": ["0 d", "5 d", "20 d", "60 d", "180 d", "720 d"],
                          "angle_step": "2 deg"}}
    runs = []
    for name, cam in (("drawn", {"drawing": "disc.dxf"}),
                      ("eccentric", {"eccentric": {"radius": "23 mm", "eccentricity": "4 mm"},
                                     "bore_radius": "5 mm"})):
        path = scene(tmp_path, name, **cam)
        path.write_text(yaml.safe_dump(yaml.safe_load(path.read_text()) | longer))
        runs.append(fickcam.run(fickcam.load_scene(path)))
    drawn, eccentric = runs
    same_moisture(drawn, eccentric)
    ends = [0, -1]
    for name in ("lift", "base_circle_radius"):
        a, b = (np.asarray(r[name], float) for r in runs)
        assert a[ends] == pytest.approx(b[ends], rel=2e-5), name
    ratio = np.asarray(drawn.jump_speed)[ends] / np.asarray(eccentric.jump_speed)[ends]
    # the jump speed reads the profile's curvature, which the drawing's chords move more than
    # its radius: 2.5e-3 already dry (5e-3 allowed); once saturated, ageing adds nothing to it
    assert abs(ratio[0] - 1) < 5e-3 and ratio[1] == pytest.approx(ratio[0], rel=2e-5)
    lift = [np.asarray(r.lift, float) for r in runs]
    growth = lift[1][1:-1] - lift[1][0]
    below = lift[1][1:-1] - lift[0][1:-1]
    assert np.all(below > 0.02 * growth) and np.all(below < 0.5 * growth), (below, growth)
