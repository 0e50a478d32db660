"""The shared algorithms of the diffusion package, each against its exact reference:
the left limit of the surface history, point in polygon, triangle areas, the corner
threshold and the anisotropy scaling (rescaled time and Duhamel's sum are checked against
closed forms and the method of lines in test_diffusion_exact.py)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.diffusion import Diffusivity, Exposure
from fickcam.diffusion.planform.polygon import CORNER_TURN, corners_of, triangle_areas
from fickcam.diffusion.problem.curves import inside_polygon, polygon_segments
from fickcam.diffusion.problem import scaling


def test_left_limit_is_the_value_held_before_each_jump_and_the_initial_value_at_zero():
    history = Exposure.piecewise([0.0, 10.0, 20.0, 30.0], 300.0, [1.0, 2.0, 5.0], 0.25,
                                 ramp=[False, False, True])
    before = history.surface_before(np.array([0.0, 10.0, 20.0, 25.0, 30.0]))
    # g(0-) = c0; held 1 then 2 before the steps; a ramp 2 -> 5 is continuous inside
    assert before == pytest.approx([0.25, 1.0, 2.0, 3.5, 5.0], rel=1e-14)


@settings(max_examples=25, deadline=None)
@given(st.integers(3, 40), st.floats(0.1, 10.0), st.floats(0.0, 6.3))
def test_point_in_polygon_against_the_inscribed_and_circumscribed_circles(sides, radius, turn):
    """A regular polygon of circumradius R holds every point within R cos(pi/n) of its
    centre and none beyond R."""
    angle = turn + 2 * np.pi * np.arange(sides) / sides
    segments = polygon_segments(radius * np.cos(angle), radius * np.sin(angle))
    rng = np.random.default_rng(sides)
    directions = rng.uniform(0, 2 * np.pi, 200)
    inner = radius * math.cos(math.pi / sides) * rng.uniform(0, 0.999, 200)
    outer = radius * rng.uniform(1.001, 3.0, 200)
    unit = np.column_stack([np.cos(directions), np.sin(directions)])
    assert inside_polygon(inner[:, None] * unit, segments).all()
    assert not inside_polygon(outer[:, None] * unit, segments).any()


def test_triangle_areas_are_half_the_cross_product_and_tile_a_square():
    points = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 3.0], [0.0, 3.0]])
    triangles = np.array([[0, 1, 2], [0, 2, 3]])
    assert list(triangle_areas(points, triangles)) == [3.0, 3.0]
    assert list(triangle_areas(points, triangles[:, ::-1])) == [3.0, 3.0]  # either orientation


def test_corner_threshold_separates_a_square_from_a_finely_sampled_circle():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert list(corners_of(square)) == [0, 1, 2, 3]
    sides = math.ceil(2 * math.pi / CORNER_TURN) + 1  # each vertex turns 2 pi / n < 0.2 rad
    angle = 2 * np.pi * np.arange(sides) / sides
    assert corners_of(np.column_stack([np.cos(angle), np.sin(angle)])).size == 0


def test_anisotropic_scaling_makes_the_diffusion_times_of_every_axis_equal():
    """x' = x sqrt(D_z / D_i) / L (Crank 1975 eq. 2.13): an axis of length x with D_i
    diffuses in x^2 / D_i, which in scaled units is x'^2 L^2 / D_z."""
    diffusivity = Diffusivity((4e-12, 1e-12, 2.5e-13), 40_000.0)
    d = diffusivity.pre_exponential
    length, thickness = 0.03, 0.004
    for axis in (0, 1):
        scaled = length * scaling.axis_scale(thickness, d[axis], d[2])
        assert scaled ** 2 * thickness ** 2 / d[2] == pytest.approx(length ** 2 / d[axis])
    assert scaling.stretch_of(d) == pytest.approx((0.25, 0.5))
