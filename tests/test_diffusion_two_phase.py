"""The exact two-phase (Carter & Kibler 1978) sheet solution against Crank's
Fickian series, Carter & Kibler's closed form and an independent method of lines."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import simpson, solve_ivp
from scipy.sparse import diags

from fickcam.diffusion.exact.separable import sheet_uptake
from fickcam.diffusion.exact.two_phase import (carter_kibler_approximation, equilibrium_shares,
                                               two_phase_mode_deficit, two_phase_sheet_profile,
                                               two_phase_sheet_uptake)

H = 2e-3
D = 5e-12
KAPPA = np.pi ** 2 * D / H ** 2
TIMES = np.concatenate([[0.0], np.logspace(1, 8.5, 60)])


def test_no_binding_reproduces_cranks_series_to_round_off():
    uptake = two_phase_sheet_uptake(TIMES, D, H, 0.0, 3e-7)
    assert np.max(np.abs(uptake.total - sheet_uptake(D * TIMES / H ** 2))) < 1e-13
    assert np.all(uptake.bound == 0.0)


def test_shares_at_equilibrium_follow_the_rates():
    uptake = two_phase_sheet_uptake([1e12], D, H, 2e-7, 6e-7)
    assert uptake.free[0] == pytest.approx(0.75, abs=1e-12)
    assert uptake.bound[0] == pytest.approx(0.25, abs=1e-12)
    assert equilibrium_shares(0.0, 0.0) == (1.0, 0.0)
    with pytest.raises(ValueError):
        equilibrium_shares(1e-7, 0.0)


@pytest.mark.parametrize("scale", [0.04, 0.01, 0.0025])
def test_small_rates_reproduce_carter_kibler_within_its_first_order_accuracy(scale):
    """Their closed form neglects terms of order (gamma + beta)/kappa."""
    gamma, beta = scale * KAPPA / 3, scale * KAPPA
    exact = two_phase_sheet_uptake(TIMES, D, H, gamma, beta).total
    approx = carter_kibler_approximation(TIMES, D, H, gamma, beta)
    error = np.max(np.abs(exact - approx))
    assert error < (gamma + beta) / KAPPA
    assert error > 0.05 * (gamma + beta) / KAPPA   # first order, not better: the forms differ


def _method_of_lines(gamma, beta, nodes, times):
    """Second-order central differences on nodes 0..n (faces held at the free
    equilibrium share), Radau in time; mean by the trapezoid rule."""
    free0, bound0 = equilibrium_shares(gamma, beta)
    n = nodes
    dz = H / n
    laplacian = diags([1.0, -2.0, 1.0], [-1, 0, 1], shape=(n - 1, n - 1)) * (D / dz ** 2)
    boundary = np.zeros(n - 1)
    boundary[[0, -1]] = D * free0 / dz ** 2

    def rhs(_, y):
        free, bound = y[: n - 1], y[n - 1:]
        exchange = gamma * free - beta * bound
        return np.concatenate([laplacian @ free + boundary - exchange, exchange])

    from scipy.sparse import bmat, identity
    eye = identity(n - 1)
    jacobian = bmat([[laplacian - gamma * eye, beta * eye], [gamma * eye, -beta * eye]]).tocsc()
    sol = solve_ivp(rhs, (0, times[-1]), np.zeros(2 * (n - 1)), method="Radau", t_eval=times,
                    jac=jacobian, rtol=1e-9, atol=1e-12)
    free = np.vstack([np.full(times.size, free0), sol.y[: n - 1], np.full(times.size, free0)])
    bound = np.vstack([np.zeros(times.size), sol.y[n - 1:], np.zeros(times.size)])
    bound[[0, -1]] = bound[[1, -2]]  # the faces carry no volume in the limit; edge cells follow
    weights = np.full(n + 1, 1.0 / n)
    weights[[0, -1]] = 0.5 / n
    return weights @ free, weights @ bound


def test_an_independent_method_of_lines_agrees_to_its_discretisation_error():
    gamma, beta = 0.3 * KAPPA, 0.5 * KAPPA      # far outside Carter & Kibler's regime
    times = np.linspace(0.0, 3.0, 31)[1:] * H ** 2 / D
    exact = two_phase_sheet_uptake(times, D, H, gamma, beta)
    errors = []
    for nodes in (40, 80):
        free, bound = _method_of_lines(gamma, beta, nodes, times)
        errors.append(max(np.max(np.abs(free - exact.free)), np.max(np.abs(bound - exact.bound))))
    assert errors[1] < 2e-3
    assert errors[1] < 0.5 * errors[0]          # the gap closes with the grid: it is the grid's


def test_profile_integrates_to_the_uptake():
    times = np.array([0.02, 0.2, 1.0]) * H ** 2 / D
    z = np.linspace(0.0, 1.0, 401)
    profile = two_phase_sheet_profile(z[None, :], times[:, None], D, H, 0.4 * KAPPA, 0.2 * KAPPA,
                                      tolerance=1e-8)
    uptake = two_phase_sheet_uptake(times, D, H, 0.4 * KAPPA, 0.2 * KAPPA)
    assert np.allclose(simpson(profile.free, x=z, axis=1), uptake.free, atol=1e-6)
    assert np.allclose(simpson(profile.bound, x=z, axis=1), uptake.bound, atol=1e-6)


def test_a_mode_without_diffusion_relaxes_like_first_order_kinetics():
    """rate = 0: the 2x2 system alone; the total deficit is conserved and the free
    share relaxes at gamma + beta (closed form of a reversible reaction)."""
    gamma, beta, t = 2e-7, 6e-7, np.linspace(0, 2e7, 9)
    free, bound = two_phase_mode_deficit(0.0, t, gamma, beta)
    assert np.allclose(free + bound, 1.0)
    assert np.allclose(free, 0.75, atol=1e-14)  # starts at its equilibrium share: stays there


@settings(max_examples=25, deadline=None)
@given(st.floats(-2.0, 1.0), st.floats(-3.0, 1.0), st.floats(-3.0, 1.0))
def test_uptake_rises_monotonically_from_zero_to_the_equilibrium_shares(log_d, log_gamma, log_beta):
    """The two-phase system is cooperative (exchange rates >= 0) and starts below its
    steady state, so every uptake fraction rises monotonically (comparison principle)
    and free + bound = total with free <= beta/(gamma+beta)."""
    d = D * 10 ** log_d
    kappa = np.pi ** 2 * d / H ** 2
    gamma, beta = kappa * 10 ** log_gamma, kappa * 10 ** log_beta
    slowest = kappa * beta / (kappa + gamma + beta)   # |slow eigenvalue| of mode 1 is above this
    t = np.sort(np.concatenate([[0.0], np.logspace(-4, 0, 20) / max(kappa, gamma + beta),
                                np.logspace(-3, np.log10(40.0), 20) / slowest]))
    uptake = two_phase_sheet_uptake(t, d, H, gamma, beta)
    free0, bound0 = equilibrium_shares(gamma, beta)
    assert np.all(np.diff(uptake.total) >= -1e-10)
    assert np.all(np.diff(uptake.bound) >= -1e-10)
    assert np.allclose(uptake.free + uptake.bound, uptake.total)
    assert np.all(uptake.free <= free0 + 1e-10) and np.all(uptake.bound <= bound0 + 1e-10)
    assert uptake.total[-1] == pytest.approx(1.0, abs=1e-6)
