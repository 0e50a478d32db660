"""The outline's inward chords (``short_time.inward_chords``) and the exact ray exits they
are made of (``polygon.first_exits``), against answers known independently: a regular
polygon's diameters through opposite vertices, an annulus's width, a rectangle's sides and
diagonals, rays through and along vertices and edges; and invariants under rotation,
translation, scaling and the loop's start."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.diffusion.planform.polygon import first_exits, vertex_normals
from fickcam.diffusion.planform.short_time import CHORD_RAYS, inward_chords


def regular(count: int, radius: float, turn: float = 0.0) -> np.ndarray:
    """A regular polygon's vertices, counter-clockwise [m]."""
    angle = turn + 2 * np.pi * np.arange(count) / count
    return radius * np.column_stack([np.cos(angle), np.sin(angle)])


def exits(loops, starts, directions):
    return first_exits(np.asarray(starts, float), np.asarray(directions, float),
                       [np.asarray(loop, float) for loop in loops], 1e-9)


@pytest.mark.parametrize("count", [64, 720])
def test_rays_through_opposite_vertices_are_diameters(count):
    """From each vertex of a regular polygon of an even count towards the centre, the ray
    leaves through the opposite vertex: 2 R; of an odd count, through the opposite edge's
    middle: R (1 + cos(pi / n))."""
    for n, chord in ((count, 2.0), (count + 1, 1.0 + np.cos(np.pi / (count + 1)))):
        disc = regular(n, 1.0)
        found = exits([disc], disc, -disc)
        np.testing.assert_allclose(found, chord, rtol=1e-13)


def test_an_annulus_is_its_width_from_either_side():
    """Outer circle counter-clockwise, hole clockwise: rays from either loop's vertices
    along the radius cross the annulus through the other loop's vertex, R2 - R1."""
    outer, hole = regular(96, 3.0), regular(96, 1.0)[::-1]
    assert np.allclose(exits([outer, hole], outer, -outer / 3.0), 2.0, rtol=1e-13)
    assert np.allclose(exits([outer, hole], hole, hole), 2.0, rtol=1e-13)


def test_a_rectangle_sides_and_corners():
    """Rays from a 3 x 1 rectangle's sides cross it (1 or 3); its corners' bisectors reach
    the opposite long side at sqrt 2; a square's diagonal leaves through the far corner."""
    box = np.array([[0, 0], [3, 0], [3, 1], [0, 1]], float)
    chords, lengths = inward_chords([box], 1e-3)
    starts = np.vstack([box, [[1.5, 0], [1.5, 1], [0, 0.5], [3, 0.5]]])
    normals = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1], [0, 1], [0, -1], [1, 0], [-1, 0]])
    np.testing.assert_allclose(exits([box], starts, normals / np.hypot(*normals.T)[:, None]),
                               [np.sqrt(2)] * 4 + [1, 1, 3, 3], rtol=1e-14)
    assert np.all(np.isclose(chords, 1.0) | np.isclose(chords, 3.0)
                  | np.isclose(chords, np.sqrt(2)))
    assert np.isclose(lengths.sum(), 8.0) and len(chords) >= CHORD_RAYS
    square = box * [1 / 3, 1]
    assert np.isclose(exits([square], [[0, 0]], [[np.sqrt(0.5)] * 2])[0], np.sqrt(2))


def test_a_ray_that_touches_a_reflex_corner_goes_on():
    """A notch's apex on the ray, the notch on either side: the ray does not leave there,
    whichever side the notch is on (an entry and an exit at one point, or none)."""
    above = np.array([[0, 0], [4, 0], [4, 2], [3, 2], [2, 1], [1, 2], [0, 2]], float)
    below = np.array([[0, 0], [1, 0], [2, 1], [3, 0], [4, 0], [4, 2], [0, 2]], float)
    for outline in (above, below):
        assert exits([outline], [[0, 1]], [[1, 0]])[0] == 4.0


def test_a_ray_along_an_edge_leaves_where_it_meets_the_outline():
    """An L-shape: up its inner edge's line the ray leaves the open part at the reflex
    corner (1 up); beside it, at the step (1) or the top (2); a ray parallel to the bottom
    edge crosses the far side."""
    ell = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    found = exits([ell], [[1, 0], [1.5, 0], [0.5, 0], [0, 0.5]], [[0, 1]] * 3 + [[1, 0]])
    np.testing.assert_array_equal(found, [1.0, 1.0, 2.0, 2.0])


def test_a_hole_is_met_even_where_the_ray_only_clips_it():
    """A square plate with a small square hole: a ray that clips the hole's corner over a
    short stretch leaves the plate at the hole, not at the far side."""
    plate = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    hole = np.array([[4, 4], [4, 6], [6, 6], [6, 4]], float)   # clockwise
    direction = np.array([[1.0, 1.0]]) / np.sqrt(2)
    found = exits([plate, hole], [[0.1, 2.05]], direction)  # in at x = 4, out 0.05 on
    np.testing.assert_allclose(found, [3.9 * np.sqrt(2)], rtol=1e-14)


def star(radii: list[float], jitter: list[float]) -> np.ndarray:
    """A star-shaped polygon about the origin, counter-clockwise [m]."""
    n = len(radii)
    angle = 2 * np.pi * (np.arange(n) + 0.4 * np.asarray(jitter)) / n
    return np.asarray(radii)[:, None] * np.column_stack([np.cos(angle), np.sin(angle)])


STARS = st.integers(6, 40).flatmap(lambda n: st.tuples(
    st.lists(st.floats(0.4, 1.6), min_size=n, max_size=n),
    st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n)))


@settings(max_examples=40, deadline=None)
@given(STARS, st.floats(0.0, 2 * np.pi), st.floats(-50.0, 50.0), st.integers(-3, 3),
       st.integers(1, 30))
def test_chords_do_not_depend_on_placement_scale_or_the_loops_start(shape, turn, shift,
                                                                    power, roll):
    """Rotated and moved the chords are equal to round-off, scaled by 2^k exactly scaled;
    the exits of given rays do not depend on where the loop starts (bitwise)."""
    loop = star(*shape)
    chords, lengths = inward_chords([loop], 1e-3)
    rotation = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    moved, _ = inward_chords([loop @ rotation.T + shift], 1e-3)
    extent = np.ptp(loop, axis=0).max() + abs(shift)
    np.testing.assert_allclose(np.sort(moved), np.sort(chords), rtol=0, atol=1e-9 * extent)
    scaled, scaled_lengths = inward_chords([loop * 2.0 ** power], 1e-3 * 2.0 ** power)
    np.testing.assert_array_equal(scaled, chords * 2.0 ** power)
    normals = vertex_normals(loop)
    rolled = first_exits(loop, normals, [np.roll(loop, roll % len(loop), axis=0)], 1e-9)
    np.testing.assert_array_equal(rolled, first_exits(loop, normals, [loop], 1e-9))
    assert np.all(chords > 0) and np.all(chords <= 2 * 1.6 + 1e-9)
