"""The graded planform mesh's building blocks against plain references: a loop resampled at
many spacings from its arc lengths found once, offset normals without a fan, the greedy
thinning of a row, and a mesh's nearest contact distance from a bounded search, each the
same numbers, bit for bit, as the straightforward way."""
from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree

from fickcam.diffusion import CamPlate
from fickcam.diffusion.planform.polygon import (corners_of, loop_resampler, resample_loop,
                                                vertex_normals)
from fickcam.diffusion.planform.triangles import _sparse_enough, fanned, triangulate
from fickcam.diffusion.problem.curves import circle


def per_span(loop: np.ndarray, spacing: float) -> np.ndarray:
    """Resampling span by span between corners, one ``arange`` each (the plain way)."""
    closed = np.vstack([loop, loop[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    corners = corners_of(loop)
    starts = arc[corners] if corners.size else np.array([0.0])
    ends = np.append(starts[1:], starts[0] + arc[-1])
    s = np.concatenate([a + (b - a) * np.arange(n) / n for a, b in zip(starts, ends)
                        for n in [max(1, math.ceil((b - a) / spacing))]]) % arc[-1]
    return np.column_stack([np.interp(s, arc, closed[:, 0]), np.interp(s, arc, closed[:, 1])])


def greedy(candidates: np.ndarray, placed: np.ndarray, gap: float) -> np.ndarray:
    """Candidates kept in index order when at least ``gap`` from all placed and kept ones."""
    kept = list(placed)
    out = []
    for point in candidates:
        if all(np.hypot(*(point - other)) >= gap for other in kept):
            kept.append(point)
            out.append(point)
    return np.array(out).reshape(-1, 2)


LOOPS = st.lists(st.tuples(st.floats(-3, 3), st.floats(-3, 3)), min_size=3, max_size=30)


@settings(max_examples=40, deadline=None)
@given(LOOPS, st.lists(st.floats(1e-3, 2.0), min_size=1, max_size=5))
def test_a_resampler_gives_each_spacing_the_plain_resampling(vertices, spacings):
    loop = np.array(vertices)
    if np.any(np.hypot(*(np.roll(loop, -1, axis=0) - loop).T) == 0):
        loop = loop + np.arange(len(loop))[:, None] * [1.0, 0.5]   # no zero-length edge
    at = loop_resampler(loop)
    for spacing in spacings:
        np.testing.assert_array_equal(at(spacing), per_span(loop, spacing))
        np.testing.assert_array_equal(resample_loop(loop, spacing), per_span(loop, spacing))


def test_offsets_without_reflex_corners_are_the_vertex_bisectors():
    disc = circle(0.0, 0.0, 1.0, 0.05)
    disc = np.column_stack(disc) if isinstance(disc, tuple) else disc
    for loop in (disc, disc[::-1]):   # convex outline and a hole: no fan
        points, normals = fanned(loop)
        np.testing.assert_array_equal(points, loop)
        np.testing.assert_array_equal(normals, vertex_normals(loop))
    ell = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    points, normals = fanned(ell)   # the reflex corner (1, 1) fans out
    fan = np.all(points == [1.0, 1.0], axis=1)
    assert fan.sum() > 1
    np.testing.assert_array_equal(normals[~fan], vertex_normals(ell)[[0, 1, 2, 4, 5]])


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2 ** 31), st.integers(0, 60), st.floats(0.05, 0.5))
def test_thinning_keeps_the_greedy_choice(seed, placed_count, gap):
    rng = np.random.default_rng(seed)
    candidates = rng.uniform(0, 2, (80, 2))
    placed = rng.uniform(0, 2, (placed_count, 2))
    np.testing.assert_array_equal(_sparse_enough(candidates, placed, gap),
                                  greedy(candidates, placed, gap))


def test_the_nearest_contact_distance_is_the_unbounded_searchs():
    x = 0.02 * np.cos(np.linspace(0, 2 * np.pi, 60, endpoint=False))
    plate = CamPlate(x, 0.015 * np.sin(np.linspace(0, 2 * np.pi, 60, endpoint=False)),
                     0.004, 0.004)
    mesh = triangulate(plate, 0.001, growth=0.3, stretch=(1.0, 1.3))
    everywhere = mesh.contact(mesh.points[mesh.triangles].mean(axis=1))
    assert mesh.contact_distance.min() == everywhere.min()
    finite = np.isfinite(mesh.contact_distance)
    np.testing.assert_array_equal(mesh.contact_distance[finite], everywhere[finite])
    assert finite.sum() < 0.8 * finite.size   # the search was bounded
