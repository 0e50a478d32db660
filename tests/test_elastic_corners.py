"""Re-entrant corners and the meshes graded toward them: Williams' exponents of free wedges
against their published values, the corners a drawn outline has (and the chords of its
arcs have not), and a P1 field carried exactly through uniform and graded refinement."""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fickcam.elastic.corners import (CORNER_TURN, SPLIT_ABOVE, reentrant_corners,
                                     target_sizes, williams_exponent)
from fickcam.elastic.mesh import drawn_mesh
from fickcam.elastic.nodal import NodalField


@pytest.mark.parametrize("degrees, exponent", [
    (360.0, 0.5),            # a crack (Williams 1952)
    (270.0, 0.5444837),      # the right-angled re-entrant corner (Williams 1952, Fig. 2)
    (180.0, 1.0),            # a straight edge: nothing singular
    (90.0, 1.0),             # a convex corner
])
def test_williams_exponents_of_free_wedges(degrees, exponent):
    assert williams_exponent(math.radians(degrees)) == pytest.approx(exponent, abs=5e-7)


def test_the_exponent_is_a_root_of_williams_equation_and_falls_as_the_wedge_opens():
    angles = np.radians(np.linspace(185.0, 359.0, 40))
    exponents = np.array([williams_exponent(a) for a in angles])
    residual = np.minimum(np.abs(np.sin(exponents * angles) + exponents * np.sin(angles)),
                          np.abs(np.sin(exponents * angles) - exponents * np.sin(angles)))
    assert np.all(residual < 1e-12)
    assert np.all(np.diff(exponents) < 0) and np.all((exponents > 0.5) & (exponents < 1.0))


def l_shape():
    """An L of 20 mm legs, 10 mm wide, counter-clockwise: one re-entrant corner at (10, 10) mm."""
    return np.array([[0, 0], [20, 0], [20, 10], [10, 10], [10, 20], [0, 20]], float) * 1e-3


def circle(radius, count, clockwise=False):
    angle = np.linspace(0.0, 2 * np.pi, count, endpoint=False)
    loop = radius * np.column_stack([np.cos(angle), np.sin(angle)])
    return loop[::-1] if clockwise else loop


def test_an_l_has_one_reentrant_corner_and_a_flattened_hole_none():
    found = reentrant_corners([l_shape(), circle(3e-3, 64, clockwise=True) + 5e-3])
    assert len(found) == 1
    corner, exponent = found[0]
    assert np.allclose(corner, [10e-3, 10e-3]) and exponent == pytest.approx(0.5444837, abs=1e-6)
    assert 2 * np.pi / 64 < CORNER_TURN  # the hole's chords turn by less than a corner


def linear(points):
    return np.stack([1.0 + 30.0 * points[:, 0] - 70.0 * points[:, 1], 2.0 * points[:, 1]])


def test_a_p1_field_is_carried_exactly_through_uniform_and_graded_refinement():
    mesh = drawn_mesh([l_shape()], 2e-3)
    field = NodalField(mesh.points, mesh.triangles, linear(mesh.points))
    corners = reentrant_corners([l_shape()])
    for finer in (field.refined(), field.graded_toward(corners, 5e-3, 2)):
        assert np.array_equal(finer.points[:len(mesh.points)], mesh.points)
        assert np.allclose(finer.values, linear(finer.points), rtol=0, atol=1e-14)
        (ax, ay), (bx, by) = ((finer.points[finer.triangles[:, k]] - finer.points[finer.triangles[:, 0]]).T
                              for k in (1, 2))
        assert np.sum(0.5 * np.abs(ax * by - ay * bx)) == pytest.approx(3e-4, rel=1e-12)


def test_the_graded_mesh_meets_its_target_sizes_and_refines_toward_the_corner():
    mesh = drawn_mesh([l_shape()], 2e-3)
    field = NodalField(mesh.points, mesh.triangles, linear(mesh.points))
    corners = reentrant_corners([l_shape()])
    graded = field.graded_toward(corners, 5e-3, 2)
    centroids = graded.points[graded.triangles].mean(axis=1)
    size = field.longest_edges()[np.hypot(*(mesh.points[mesh.triangles].mean(axis=1)
                                            - corners[0][0]).T) < 5e-3].max()
    assert np.all(graded.longest_edges() <= SPLIT_ABOVE * target_sizes(centroids, corners, size,
                                                                       5e-3, 2))
    distance = np.hypot(*(centroids - corners[0][0]).T)
    edges = graded.longest_edges()
    # the corner's own triangles stop near h^(1/beta) R^(1 - 1/beta) (beta = 0.9 x 0.544 / 2)
    assert edges.min() < 0.15 * size
    assert np.median(edges[distance < 0.5e-3]) < 0.5 * np.median(edges[(distance > 2e-3)
                                                                        & (distance < 5e-3)])
    assert len(graded.triangles) < 4 * len(field.triangles)  # the zone grows slowly


@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 2 * np.pi), st.floats(1.0, 5.0))
def test_corners_do_not_depend_on_where_the_loop_starts_or_its_size(turn, scale):
    loop = l_shape() * scale
    rotated = loop @ np.array([[np.cos(turn), np.sin(turn)], [-np.sin(turn), np.cos(turn)]])
    for start in range(len(loop)):
        found = reentrant_corners([np.roll(rotated, start, axis=0)])
        assert len(found) == 1 and np.allclose(found[0][0], rotated[3], atol=1e-15)
        assert found[0][1] == pytest.approx(0.5444837, abs=1e-6)
