"""Two-phase exchange across temperature ramps: Arrhenius binding, release and diffusion
rates vary along a ramp, so a mode's 2x2 system has time-varying coefficients; the march
cuts ramps into pieces (rates frozen at each piece's middle, the second-order exponential
midpoint rule) until that is within the tolerance. Reference: solve_ivp (Radau, tight
tolerances) of the same mode's equations with the rates evaluated at every instant."""
from functools import lru_cache

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fickcam.diffusion.nonfickian.two_phase_modes import march_modes, march_nodes
from fickcam.diffusion.problem.exposure import Diffusivity, Exposure
from fickcam.diffusion.problem.sorption import Langmuir, Rate

DAY = 86400.0
R = 8.314462618
# 300 K held 5 d, ramp to 360 K over 10 d, held 15 d; surface 1 % held (RH constant)
RAMP = Exposure.piecewise([0.0, 5 * DAY, 15 * DAY, 30 * DAY], [300.0, 360.0, 360.0],
                          [1.0, 1.0, 1.0], ramp=[False, True, False])
DIFFUSIVITY = Diffusivity((1.0, 1.0, 1.0), 40e3)
LAW = Langmuir(Rate(2e-7 * np.exp(60e3 / (R * 330.0)), 60e3),   # gamma(330 K) = 2e-7 1/s
               Rate(5e-7 * np.exp(20e3 / (R * 330.0)), 20e3))   # beta(330 K) = 5e-7 1/s


TIMES = np.linspace(0.0, 30 * DAY, 31)


@lru_cache(maxsize=4)
def reference(rate):
    """One mode (rescaled decay ``rate``), free and bound at ``TIMES``, by solve_ivp."""
    times = TIMES
    def rhs(t, y):
        temperature = float(RAMP.temperature(np.array([t]))[0])
        gamma, beta = (float(v) for v in LAW.rates(temperature))
        decay = rate * float(DIFFUSIVITY.arrhenius_factor(temperature))
        surface = float(LAW.free_share(temperature)) * float(RAMP.surface_moisture(np.array([t]))[0])
        exchange = gamma * y[0] - beta * y[1]
        return [decay * (surface - y[0]) - exchange, exchange]
    solution = solve_ivp(rhs, (0.0, times[-1]), [0.0, 0.0], method="Radau", t_eval=times,
                         rtol=1e-11, atol=1e-13, max_step=DAY)
    return solution.y.T


@pytest.mark.slow
@pytest.mark.parametrize("tolerance, physical_rate", [(1e-3, 3e-6), (1e-5, 3e-6), (1e-5, 3e-7)])
def test_a_mode_follows_solve_ivp_across_an_arrhenius_ramp(tolerance, physical_rate):
    times = TIMES
    rate = physical_rate / float(DIFFUSIVITY.arrhenius_factor(330.0))
    nodes = march_nodes(LAW, DIFFUSIVITY, RAMP, times, tolerance)
    marched = march_modes(np.array([rate]), np.ones((1, 1)), nodes)[:, :, 0]
    error = np.max(np.abs(marched - reference(rate)))
    assert error < tolerance


def test_frozen_rates_err_at_second_order_in_the_piece_length():
    """The exponential midpoint rule is second order: 10 times more pieces on the ramp
    (tolerance 100 times smaller) cut the error 100 times (band 30..300)."""
    times = TIMES
    rate = 3e-7 / float(DIFFUSIVITY.arrhenius_factor(330.0))
    exact = reference(rate)
    errors, pieces = [], []
    for tolerance in (1e-3, 1e-5):
        nodes = march_nodes(LAW, DIFFUSIVITY, RAMP, times, tolerance)
        marched = march_modes(np.array([rate]), np.ones((1, 1)), nodes)[:, :, 0]
        errors.append(np.max(np.abs(marched - exact)))
        pieces.append(np.count_nonzero((nodes.t > 5 * DAY) & (nodes.t < 15 * DAY)))
    order = np.log(errors[0] / errors[1]) / np.log(pieces[1] / pieces[0])
    assert order == pytest.approx(2.0, abs=0.3)
