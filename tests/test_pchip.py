"""The step response's interpolant (fickcam.diffusion.stepping.pchip): SciPy's
PchipInterpolator, the same operations in the same order, and the shape it preserves
(Fritsch & Butland 1984): through every node, monotone where the data are, no overshoot."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import PchipInterpolator

from fickcam.diffusion.stepping.pchip import Pchip

EPS = np.finfo(float).eps


def _data(rng, n, columns, kind):
    x = np.cumsum(rng.uniform(0.05, 1.0, n)) - 2.0
    shape = (n,) if columns == 0 else (n, columns)
    y = rng.normal(size=shape)
    if kind == "monotone":
        y = np.cumsum(np.abs(y), axis=0)
    elif kind == "flat":  # repeated values: zero secants and turns
        y = np.round(y, 0)
    return x, y


@pytest.mark.parametrize("columns", [0, 1, 3])
@pytest.mark.parametrize("kind", ["any", "monotone", "flat"])
@pytest.mark.parametrize("n", [2, 3, 4, 17])
def test_the_interpolant_is_scipys(n, kind, columns):
    rng = np.random.default_rng(n * 100 + columns)
    x, y = _data(rng, n, columns, kind)
    at = np.concatenate([x, rng.uniform(x[0] - 1.0, x[-1] + 1.0, 200), [np.nan]])
    ours, theirs = Pchip.through(x, y)(at), PchipInterpolator(x, y, axis=0)(at)
    assert ours.shape == theirs.shape
    # the same operations in the same order: equal, but for a compiler that contracts a
    # multiply-add in SciPy's build (a few units of round-off of the cubic's four terms)
    scale = np.max(np.abs(y)) * (1.0 + np.max(np.abs(at[:-1] - x[0]))) ** 3
    np.testing.assert_allclose(ours, theirs, rtol=0.0, atol=16 * EPS * scale)
    assert np.isnan(ours[-1]).all()


def test_a_table_of_values_keeps_its_shape():
    x = np.log(np.geomspace(1e-4, 1.0, 9))
    y = np.linspace(0.0, 1.0, 9)[:, None] * np.array([1.0, 2.0])
    out = Pchip.through(x, y)(np.array([[x[0], x[4]], [x[8], x[2]]]))
    assert out.shape == (2, 2, 2)
    np.testing.assert_array_equal(out[0, 1], y[4])


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(0.01, 1.0), min_size=2, max_size=12),
       st.lists(st.floats(-1.0, 1.0), min_size=13, max_size=13))
def test_monotone_data_give_a_monotone_interpolant_through_them(widths, steps):
    x = np.cumsum([0.0] + widths)
    y = np.cumsum(np.abs(steps[:x.size]))  # nondecreasing
    spline = Pchip.through(x, y)
    slack = 8 * EPS * max(np.max(np.abs(y)), 1.0)
    np.testing.assert_array_equal(spline(x[:-1]), y[:-1])  # each cubic's constant term
    assert abs(spline(x[-1]) - y[-1]) <= slack  # the last cubic at its right end
    fine = spline(np.linspace(x[0], x[-1], 2001))
    assert np.all(np.diff(fine) >= -slack)
    assert fine.min() >= y[0] - slack and fine.max() <= y[-1] + slack


def test_two_nodes_give_the_straight_line():
    spline = Pchip.through([1.0, 3.0], [2.0, 6.0])
    np.testing.assert_allclose(spline([0.0, 2.0, 4.0]), [0.0, 4.0, 8.0], rtol=4 * EPS)
