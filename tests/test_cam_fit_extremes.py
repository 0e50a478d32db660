"""The lowest and highest follower height of a fitted motion's pieces: the bracketed
turning points of each piece's series against the real roots of its derivative found
independently (numpy's companion-matrix ``chebroots``)."""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import chebyshev

from fickcam.cam.geometry import _piece_extremes, _series_table


def _by_companion(coef: np.ndarray) -> tuple[float, float]:
    """(lowest, highest) of one series on [-1, 1]: its ends and every real root of its
    derivative inside."""
    roots = chebyshev.chebroots(chebyshev.chebder(coef))
    inside = roots.real[(np.abs(roots.imag) < 1e-9) & (np.abs(roots.real) < 1.0)]
    values = chebyshev.chebval(np.r_[-1.0, 1.0, inside], coef)
    return float(values.min()), float(values.max())


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), degree=st.sampled_from([3, 12, 40, 96]),
       pieces=st.integers(1, 5))
def test_piece_extremes_are_those_at_the_derivatives_real_roots(seed, degree, pieces):
    rng = np.random.default_rng(seed)
    # coefficients decaying as a smooth motion's do, each piece its own
    coef = rng.normal(size=(degree + 1, pieces)) / (1.0 + np.arange(degree + 1))[:, None] ** 2
    lowest, highest = _piece_extremes(_series_table(coef, np.ones(pieces)))
    for p in range(pieces):
        low, high = _by_companion(coef[:, p])
        size = np.abs(coef[:, p]).sum()
        assert abs(lowest[p] - low) <= 1e-13 * size
        assert abs(highest[p] - high) <= 1e-13 * size


def test_a_dwell_has_its_height_at_both_extremes():
    """A constant height with round-off in its slope's coefficients (a dwell's fit): its
    noise brackets are not searched, and both extremes are the height."""
    coef = np.zeros((41, 1))
    coef[0] = 0.05
    coef[1:] = 1e-19 * np.random.default_rng(1).normal(size=(40, 1))
    lowest, highest = _piece_extremes(_series_table(coef, np.ones(1)))
    np.testing.assert_allclose([lowest[0], highest[0]], 0.05, rtol=4e-16)
