"""Observed orders of the two-phase FiPy finite-volume path, as for Fick
(tests/test_diffusion_convergence.py): the coupled free/bound block operator is second
order in space (sheet and disc), backward Euler on it first order in time and the
Richardson pair second order; the accuracy knob then moves the error in proportion.

Exact in time on a mesh: the block system [[K + gamma M, -beta M], [-gamma M, beta M]]
splits in the eigenvectors of (K, M) into one 2x2 system per discrete mode (the bound
block is M times the identity), solved by ``two_phase.two_phase_mode_deficit``."""
import numpy as np
import pytest
from scipy.linalg import eigh

from fickcam.diffusion import solve
from fickcam.diffusion.exact.two_phase import (equilibrium_shares, two_phase_mode_deficit,
                                               two_phase_sheet_uptake)
from fickcam.diffusion.nonfickian.two_phase_mesh import Exchange, march_coupled
from fickcam.diffusion.stepping.step_plans import StepPlan
from fickcam.diffusion.operators import grids
from fickcam.diffusion.problem.exposure import Diffusivity, Exposure
from fickcam.diffusion.problem.geometry import Disc, Sheet
from fickcam.diffusion.problem.sorption import Langmuir, Rate

pytest.importorskip("fipy")

GAMMA, BETA = 2.0, 5.0        # 1 / scaled time (tau* = D t / h^2): about pi^2 / 5, pi^2 / 2
T_STAR = 0.1


def observed_order(errors):
    return np.log2(np.asarray(errors[:-1]) / np.asarray(errors[1:]))


def semi_discrete_uptake(disc, tstar):
    """Total mean uptake (fraction of Mm) of a soak from dry, exact in time on the mesh."""
    rates, vectors = eigh(disc.stiffness.toarray(), np.diag(disc.volumes))
    amplitudes = (disc.mean_weights @ vectors) * (vectors.T @ disc.volumes)
    free, bound = two_phase_mode_deficit(rates, tstar, GAMMA, BETA)
    return 1.0 - amplitudes @ (free + bound)


def test_two_phase_sheet_operator_is_second_order_in_space():
    exact = two_phase_sheet_uptake(np.array([T_STAR]), 1.0, 1.0, GAMMA, BETA).total[0]
    errors = [abs(semi_discrete_uptake(grids.sheet(1.0, n, 0.1), T_STAR) - exact)
              for n in (10, 20, 40, 80)]
    assert observed_order(errors)[-1] == pytest.approx(2.0, abs=0.1)


@pytest.mark.slow
def test_two_phase_disc_operator_is_second_order_in_space():
    """(r, z) grid of a disc (radius = thickness = 1 in scaled units) against the exact
    two-phase modes of the Disc (``two_phase_modes``)."""
    d, h = 1e-11, 0.004
    soak = Exposure.piecewise([0.0, 1e10], [330.0], [1.0])
    t = T_STAR * h ** 2 / d
    exact = solve(Disc(h, h), Diffusivity((d, d, d), 0.0), soak, np.array([t]), accuracy=1e-7,
                  sorption=Langmuir(Rate(GAMMA * d / h ** 2), Rate(BETA * d / h ** 2))).mean[0]
    errors = [abs(semi_discrete_uptake(grids.disc(h, h, 0.0, n, n, 1e-4, d, d), T_STAR) - exact)
              for n in (6, 12, 24)]
    assert observed_order(errors)[-1] == pytest.approx(2.0, abs=0.2)


def coupled_march(disc, steps):
    """``two_phase_mesh.march_coupled`` of a soak from dry to T_STAR in equal steps."""
    nodes = np.linspace(0.0, T_STAR, steps + 1)
    free_share, _ = equilibrium_shares(GAMMA, BETA)
    surface = np.full(nodes.size, free_share)
    dt = np.diff(nodes)
    run = march_coupled(disc, StepPlan.without_jumps(nodes, surface, np.array([steps])), surface,
                        Exchange(GAMMA * dt, BETA * dt, free_share), 0.0, part="sheet")
    return run.mean[0]


def test_backward_euler_on_the_block_system_is_first_order_and_richardson_second():
    disc = grids.sheet(1.0, 40, 0.1)
    reference = semi_discrete_uptake(disc, T_STAR)
    euler = [abs(coupled_march(disc, n) - reference) for n in (160, 320, 640)]
    pair = [abs(2 * coupled_march(disc, 2 * n) - coupled_march(disc, n) - reference)
            for n in (40, 80, 160)]
    assert observed_order(euler)[-1] == pytest.approx(1.0, abs=0.1)
    assert observed_order(pair)[-1] == pytest.approx(2.0, abs=0.15)
