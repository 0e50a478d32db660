"""Observed order of accuracy by successive refinement (space 2, backward Euler 1).

The space error is isolated by solving the semi-discrete system exactly in
time (eigen-decomposition of M^-1 K); the time error by comparing backward
Euler with that exact-in-time solution on the same mesh.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import eigh

from fickcam.diffusion.operators import grids
from fickcam.diffusion.stepping import march
from fickcam.diffusion.stepping.step_plans import StepPlan

pytest.importorskip("fipy")

T_STAR = 0.05


def sheet_uptake(tstar):
    """Crank 1975 eq. 4.18 (h = 2l, tstar = D t / h^2)."""
    k = (2 * np.arange(2000) + 1) * np.pi
    return 1 - np.sum(8 / k ** 2 * np.exp(-k ** 2 * tstar))


def exact_in_time_mean(disc, tstar):
    """c(t) = c_inf - exp(-M^-1 K t) c_inf with c_inf = K^-1 f = 1 (M u' = -K u, u = c - 1)."""
    values, vectors = eigh(disc.stiffness.toarray(), np.diag(disc.volumes))
    start = -np.ones(disc.cells)
    coefficients = vectors.T @ (disc.volumes * start)
    u = vectors @ (np.exp(-values * tstar) * coefficients)
    return float(disc.mean_weights @ (1.0 + u))


def observed_order(errors):
    return np.log2(np.asarray(errors[:-1]) / np.asarray(errors[1:]))


def test_space_error_is_second_order():
    errors = [abs(exact_in_time_mean(grids.sheet(1.0, n, 0.1), T_STAR) - sheet_uptake(T_STAR))
              for n in (10, 20, 40, 80)]
    assert observed_order(errors)[-1] == pytest.approx(2.0, abs=0.1)


def test_backward_euler_time_error_is_first_order():
    disc = grids.sheet(1.0, 40, 0.1)
    reference = exact_in_time_mean(disc, T_STAR)
    start = 0.01  # first order holds away from the initial jump: start from the exact state
    errors = []
    for steps in (20, 40, 80, 160):
        nodes = np.linspace(start, T_STAR, steps + 1)
        values, vectors = eigh(disc.stiffness.toarray(), np.diag(disc.volumes))
        u0 = vectors @ (np.exp(-values * start) * (vectors.T @ (-disc.volumes)))
        stepper = march.ThetaStepper(disc)
        c = 1.0 + u0
        for k, dt in enumerate(np.diff(nodes), start=1):
            c = stepper.step(c, dt, 1.0, 1.0, k, nodes[k])
        errors.append(abs(float(disc.mean_weights @ c) - reference))
    assert observed_order(errors)[-1] == pytest.approx(1.0, abs=0.1)


def test_richardson_pair_in_time_is_second_order():
    """2 c(dt/2) - c(dt) cancels the first-order term: observed order 2."""
    disc = grids.sheet(1.0, 40, 0.1)
    reference = exact_in_time_mean(disc, T_STAR)

    def backward_euler(steps):
        nodes = np.linspace(0.0, T_STAR, steps + 1)
        plan = StepPlan.without_jumps(nodes, np.ones(steps + 1), np.array([steps]))
        return march.march(disc, plan, 0.0).mean[0]
    errors = [abs(2 * backward_euler(2 * n) - backward_euler(n) - reference)
              for n in (40, 80, 160, 320)]
    assert observed_order(errors)[-1] == pytest.approx(2.0, abs=0.1)
