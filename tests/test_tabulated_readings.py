"""The tabulated Duhamel sum's readings (diffusion/superposition/tabulated.py), gathered
for every output at once, against each (output, node) pair's interpolant evaluated on
its own and summed exactly (math.fsum); the ramps' rise past an age against its
definition.

The gathered sums differ from the exact sums of the same interpolants by round-off only:
the bound used is a small multiple of the unit round-off times the sum of the terms'
magnitudes (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM 2002,
§4.2: recursive summation), which is what any order of summation may lose."""
import math

import numpy as np
import pytest
from scipy.special import erf

from fickcam.diffusion.forcing.record import Forcing
from fickcam.diffusion.superposition.tabulated import read, sources, tabulate

EPS = np.finfo(float).eps
SUMMATION = 64 * EPS  # x sum of |terms|: recursive summation's bound, with room


def kernel(w):
    """Two smooth unit-step responses (a sheet's early sqrt(w) rise, an exponential)."""
    w = np.asarray(w, float)
    return np.stack([erf(np.sqrt(w)), 1.0 - np.exp(-w)], axis=-1)


def record(seed: int = 3) -> Forcing:
    """Ms piecewise linear in tau over 600 nodes (a few steps; clusters of close nodes so
    that some ages fall below the grid), read at 40 of them."""
    rng = np.random.default_rng(seed)
    gaps = rng.uniform(0.02, 1.0, 599)
    gaps[rng.random(599) < 0.05] = 1e-7   # nodes nearly on top of each other
    tau = np.concatenate([[0.0], np.cumsum(gaps)])
    left = np.cumsum(rng.normal(0.0, 0.3, 600))
    right = left.copy()
    stepped = rng.random(600) < 0.03
    right[stepped] += rng.normal(0.0, 1.0, stepped.sum())
    outputs = np.unique(np.concatenate([rng.choice(600, 39, replace=False), [599]]))
    return Forcing(tau, right, left, outputs, 0.0, tau)


def lagrange_weights(x, base):
    """Four-point Lagrange weights at x (grid units) on the nodes base..base+3."""
    nodes = base[:, None] + np.arange(4)
    weights = np.ones((x.size, 4))
    for i in range(4):
        for j in range(4):
            if i != j:
                weights[:, i] *= (x - nodes[:, j]) / (nodes[:, i] - nodes[:, j])
    return nodes, weights


def pair_terms(table, where):
    """Per output, the terms c_i I~(a_i) (slope changes) and J_i K~(a_i) (steps) of every
    pair, each interpolant evaluated on its own."""
    size = table.kernel.shape[0]
    w0 = math.exp(table.start)
    slope = table.step * np.exp(table.start + table.step * np.arange(size))[:, None] * table.kernel
    rows, ages, c, logs = where.slopes.block(0, where.outputs)
    x = (logs - table.start) / table.step
    base = np.clip(np.floor(x).astype(int), 0, size - 2)
    t = (x - base)[:, None]
    hermite = ((1 + 2 * t) * (1 - t) ** 2 * table.integral[base] + t * t * (3 - 2 * t)
               * table.integral[base + 1] + t * (1 - t) ** 2 * slope[base]
               + t * t * (t - 1) * slope[base + 1])
    short = table.integral[0][None, :] * ((ages / w0) ** 1.5)[:, None]
    terms = [(rows, c[:, None] * np.where((ages < w0)[:, None], short, hermite))]
    rows, ages, j, logs = where.steps
    x = (logs - table.start) / table.step
    nodes, weights = lagrange_weights(x, np.clip(np.floor(x).astype(int) - 1, 0, size - 4))
    lagrange = np.einsum("kj,kjm->km", weights, table.kernel[nodes])
    short = table.kernel[0][None, :] * np.sqrt(ages / w0)[:, None]
    terms.append((rows, j[:, None] * np.where((ages < w0)[:, None], short, lagrange)))
    return terms


@pytest.mark.parametrize("per_decade", [16, 32, 64, 20], ids=["16", "32", "64", "off-lattice"])
def test_gathered_readings_equal_every_pairs_interpolant_summed_exactly(per_decade):
    force = record()
    where = sources(force)
    first = 1e-4
    last = float(force.tau[force.outputs].max() - force.tau[0])
    table = tabulate(kernel, first, last, per_decade)
    assert table.jumps == ()
    for each, gathered in zip((table, table.coarse()), read(table, where, first)):
        terms = pair_terms(each, where)
        for output in range(where.outputs):
            for column in range(2):
                parts = [value[rows == output, column] for rows, value in terms]
                exact = math.fsum(np.concatenate(parts))
                scale = math.fsum(np.abs(np.concatenate(parts)))
                assert abs(gathered[output, column] - exact) <= SUMMATION * scale + 1e-300


def test_the_ramps_rise_past_an_age_is_the_sum_over_every_pair():
    force = record(5)
    where = sources(force)
    rows, ages, c, _ = where.slopes.block(0, where.outputs)
    for age in (1e-8, 0.3, 7.0, 150.0, 1e4):
        terms = c * np.maximum(ages - age, 0.0)
        rise = where.ramps.rise_past(age)
        for output in range(where.outputs):
            mine = terms[rows == output]
            scale = math.fsum(np.abs(c[rows == output]) * ages[rows == output])
            assert abs(rise[output] - math.fsum(mine)) <= SUMMATION * 4 * scale + 1e-300
