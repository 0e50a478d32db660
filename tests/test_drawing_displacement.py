"""The free hygrothermal displacement of a drawn part by finite elements: exact under a
uniform free strain (every length times 1 + eps), converging at the element's order under
an uneven one (a dog-bone link whose bosses stay drier than its web)."""
import math

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

from fickcam.drawing.dxfread import read_drawing  # noqa: E402
from fickcam.drawing.planform import pin_holes  # noqa: E402
from fickcam.elastic.displacement import (aged_pin_distance, free_displacements,  # noqa: E402
                                          pin_distance, uneven_pin_shifts)
from fickcam.elastic.fem import PlaneElasticity, stiffness_matrix  # noqa: E402
from fickcam.elastic.mesh import drawn_mesh  # noqa: E402

TOL = 2e-6  # m, the chord tolerance
LENGTH, BOSS, PIN, WEB, FILLET = 60.0, 9.0, 3.0, 2.5, 3.0  # mm: a dog-bone link


def dogbone(space, length=LENGTH, boss=BOSS, pin=PIN, web=WEB, fillet=FILLET, layer="OUTLINE"):
    """A link drawn as a designer would (mm): two bosses joined by a thin web, the joints
    rounded by fillets tangent to both, the pin holes as circles on layer PINS."""
    xf = math.sqrt((boss + fillet) ** 2 - (web + fillet) ** 2)
    alpha = math.degrees(math.atan2(web + fillet, xf))
    attribs = {"layer": layer}
    space.add_arc((0, 0), boss, alpha, 360 - alpha, dxfattribs=attribs)
    space.add_arc((length, 0), boss, 180 + alpha, 180 - alpha, dxfattribs=attribs)
    for sign in (1, -1):
        space.add_line((xf, sign * web), (length - xf, sign * web), dxfattribs=attribs)
        centres = ((xf, sign * (web + fillet)), (length - xf, sign * (web + fillet)))
        if sign > 0:
            spans = ((180 + alpha, 270), (270, 360 - alpha))
        else:
            spans = ((90, 180 - alpha), (alpha, 90))
        for centre, (start, end) in zip(centres, spans):
            space.add_arc(centre, fillet, start, end, dxfattribs=attribs)
    for x in (0.0, length):
        space.add_circle((x, 0), pin, dxfattribs={"layer": "PINS"})


@pytest.fixture(scope="module")
def link(tmp_path_factory):
    document = ezdxf.new("R2010", units=4)
    dogbone(document.modelspace())
    path = tmp_path_factory.mktemp("link") / "link.dxf"
    document.saveas(path)
    return read_drawing(path, tolerance=TOL).planform


def test_the_drawn_dogbone_reads_as_one_outline_with_its_pin_holes(link):
    assert len(link.holes) == 2 and {h.layer for h in link.holes} == {"PINS"}
    discs = 2 * math.pi * (BOSS ** 2 - PIN ** 2) + 2 * WEB * (LENGTH - 2 * BOSS)
    assert link.area == pytest.approx(discs * 1e-6, rel=0.05)  # plus the fillets' corners


@pytest.mark.parametrize("order", [1, 2])
def test_a_uniform_free_strain_moves_the_pins_to_length_times_one_plus_strain(link, order):
    eps = 0.0123
    (isotropic,), (orthotropic,) = (
        free_displacements(link, [lambda x, y: np.full(x.shape, eps)], 1.5e-3, order, stiffness=q)
        for q in (None, stiffness_matrix(140e9, 9e9, 5e9, 0.3)))
    holes = pin_holes(link)
    length = pin_distance(free_displacements(link, [lambda x, y: 0 * x], 1.5e-3, order)[0], holes)
    assert length == pytest.approx(LENGTH * 1e-3, abs=1e-15)
    for moved in (isotropic, orthotropic):
        assert pin_distance(moved, holes) == pytest.approx(LENGTH * 1e-3 * (1 + eps), rel=1e-13)
        assert moved.displaced().area == pytest.approx(link.area * (1 + eps) ** 2, rel=1e-12)


def drier_bosses(x, y, eps=0.01):
    """A smooth free strain: the web at eps, each boss's core at 40 % of it."""
    core = lambda cx: np.exp(-((x - cx) ** 2 + y ** 2) / (BOSS * 1e-3) ** 2)  # noqa: E731
    return eps * (1 - 0.6 * core(0.0) - 0.6 * core(LENGTH * 1e-3))


@pytest.mark.slow  # P2 meshes down to 0.4 mm (about 10 s)
def test_pins_under_an_uneven_strain_converge_at_the_elements_order(link):
    """P2 elements: the pin distance converges as h^3 (the L2 order p + 1) or faster."""
    holes = pin_holes(link)
    spacings = 1.6e-3 / 2 ** np.arange(3)
    growth = np.array([pin_distance(free_displacements(link, [drier_bosses], h, 2)[0], holes)
                       for h in spacings]) - LENGTH * 1e-3
    differences = np.abs(np.diff(growth))
    assert math.log2(differences[0] / differences[1]) >= 2.7


def test_an_uneven_strain_moves_the_pins_by_the_strain_along_the_web_not_the_mean(link):
    """Drier bosses: the pins part by about the strain integrated along the line between
    them (the web carries it), well above L x the area's mean strain."""
    from scipy.integrate import quad

    growth = pin_distance(free_displacements(link, [drier_bosses], 0.8e-3, 2)[0],
                          pin_holes(link)) - LENGTH * 1e-3
    along = quad(lambda x: drier_bosses(np.array(x), np.array(0.0)), 0.0, LENGTH * 1e-3)[0]
    assert growth == pytest.approx(along, rel=0.05)
    assert growth < 0.01 * LENGTH * 1e-3  # less than the web's strain everywhere


def drier_moisture(points, m=(0.4, 1.0)):
    """Moisture [weight %] at points (n, 2) at two times: the web at m, each boss's core
    at 40 % of it (the shape of ``drier_bosses``)."""
    x, y = np.asarray(points, float).T
    shape = drier_bosses(x, y, eps=1.0)
    return np.outer(m, shape)


def test_a_uniform_moisture_field_gives_today_s_length_exactly(link):
    """No unevenness, no shift: the aged length is L (1 + eps) to round-off (the field's
    mean taken out of a uniform field leaves a few ulps of it)."""
    holes = pin_holes(link)
    shift = uneven_pin_shifts(link, holes, lambda p: np.outer([0.3, 0.7], np.ones(len(p))),
                              (2e-3, 1e-3), 1.5e-3)
    assert np.max(np.abs(shift)) < 1e-15 * 2e-3 * 0.7 * LENGTH * 1e-3
    eps = np.array([1.4e-3, 2.8e-3])
    assert aged_pin_distance(LENGTH * 1e-3, eps, shift) == pytest.approx(
        LENGTH * 1e-3 * (1 + eps), rel=4e-16)


def test_the_shift_of_the_unevenness_plus_the_mean_strain_is_the_whole_field_s_answer(link):
    """Superposition (the model is linear): the mean strain's L (1 + beta M_mean) plus the
    shift of the field's departure from its mean gives the pins the whole field gives,
    up to the second-order terms of the moved holes' centroids (~ beta M x the shift)."""
    holes, beta, spacing = pin_holes(link), 2e-3, 1.2e-3
    shift = uneven_pin_shifts(link, holes, drier_moisture, (beta, beta), spacing)
    mesh = drawn_mesh([loop.points for loop in link.loops], spacing)
    model = PlaneElasticity(mesh.points, mesh.triangles, 1.0, 2)
    x, y = model.quadrature_points()
    weights = model.quadrature_weights()
    assert weights.sum() == pytest.approx(link.area, rel=1e-12)
    mean = np.einsum("tep,ep->t", drier_moisture(np.column_stack([x.ravel(), y.ravel()]))
                     .reshape(-1, *x.shape), weights) / weights.sum()
    aged = aged_pin_distance(LENGTH * 1e-3, beta * mean, shift)
    whole = [pin_distance(moved, holes) for moved in free_displacements(
        link, [lambda x, y, m=m: beta * m * drier_bosses(x, y, eps=1.0) for m in (0.4, 1.0)],
        spacing, 2)]
    growth = aged - LENGTH * 1e-3 * (1 + beta * mean)
    assert np.all(growth > 0)  # the wetter web parts the pins more than the mean strain
    assert aged == pytest.approx(whole, abs=1e-2 * beta * np.max(np.abs(growth)))


@pytest.mark.slow  # P2 meshes down to 0.4 mm (about 15 s)
def test_the_unevenness_s_shift_converges_at_the_elements_order(link):
    """P2 elements, a smooth field: the shift converges as h^3 (the L2 order p + 1) or faster."""
    holes = pin_holes(link)
    shifts = np.array([uneven_pin_shifts(link, holes, drier_moisture, (2e-3, 2e-3), h)[:, 0]
                       for h in 1.6e-3 / 2 ** np.arange(3)])
    differences = np.abs(np.diff(shifts, axis=0))
    assert np.all(np.log2(differences[0] / differences[1]) >= 2.7)
