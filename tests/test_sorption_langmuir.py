"""Two-phase (Langmuir) sorption: the exact modal march against the exact sheet solution
(Carter & Kibler 1978), against Fick (gamma = 0), and the FiPy
finite-volume paths against the exact modes over a history with an RH step down."""
import numpy as np
import pytest

from fickcam.diffusion import solve
from fickcam.diffusion.exposure import Diffusivity, Exposure
from fickcam.diffusion.geometry import Bar, CamPlate, Disc, LinkBar, Sheet
from fickcam.diffusion.langmuir import langmuir_history
from fickcam.diffusion.sorption import Langmuir, Rate
from fickcam.diffusion.two_phase import (carter_kibler_approximation, exchange_propagator,
                                         two_phase_sheet_uptake)

H, D, DAY = 2e-3, 5e-12, 86400.0
KAPPA = np.pi ** 2 * D / H ** 2
ISOTROPIC = Diffusivity((D, D, D), 0.0)
SOAK = Exposure.piecewise([0.0, 200 * DAY], [330.0], [2.0])
STEP_DOWN = Exposure.piecewise([0.0, 40 * DAY, 100 * DAY], [330.0, 330.0], [2.0, 0.5])


def law(gamma, beta):
    return Langmuir(Rate(gamma), Rate(beta))


@pytest.mark.parametrize("gamma, beta", [(2e-7, 6e-7), (1e-5, 1e-5), (1e-9, 3e-9)])
def test_sheet_modes_reproduce_the_exact_two_phase_uptake(gamma, beta):
    times = np.linspace(0.0, 200 * DAY, 41)
    history, estimate = langmuir_history(Sheet(H), ISOTROPIC, law(gamma, beta), SOAK, times, 1e-6)
    exact = two_phase_sheet_uptake(times, D, H, gamma, beta)
    assert np.max(np.abs(history["mean"] / 2.0 - exact.total)) < 1e-6
    assert np.max(np.abs(history["bound"] / 2.0 - exact.bound)) < 1e-6
    assert estimate < 1e-6


def test_no_binding_makes_each_mode_fickian_to_round_off():
    """gamma = 0: the free water of a mode decays as exp(-D lambda t), the bound water
    (none at the start) stays none, the integral is (1 - exp(-D lambda t)) / (D lambda)."""
    rate, t = np.geomspace(1e-9, 1e-3, 40), np.geomspace(1.0, 1e8, 40)[:, None]
    step = exchange_propagator(rate, t, 0.0, 1e-6)
    free, bound = step.apply(1.0, 0.0)
    assert np.allclose(free, np.exp(-rate * t), rtol=1e-13, atol=1e-15)
    assert np.all(bound == 0.0)
    integral, _ = step.apply(1.0, 0.0, integral=True)
    assert np.allclose(integral, -np.expm1(-rate * t) / rate, rtol=1e-13, atol=0.0)


def test_no_binding_reproduces_the_fickian_history_of_a_record():
    record = Exposure.piecewise(np.arange(41) * 5 * DAY, np.full(40, 330.0),
                                2.0 + np.sin(np.arange(40)))
    times = np.linspace(0.0, 200 * DAY, 23)
    bar = Bar(0.03, 0.01, H)
    two_phase, estimate = langmuir_history(bar, ISOTROPIC, law(0.0, 1e-6), record, times, 1e-6)
    fickian = solve(bar, ISOTROPIC, record, times, accuracy=1e-6)
    swing = 3.0  # the largest |Ms - M0| of the record
    assert np.max(np.abs(two_phase["mean"] - fickian.mean)) / swing < 1e-6
    assert np.max(np.abs(two_phase["surface"] - fickian.surface)) / swing < 1e-5
    assert np.all(two_phase["bound"] == 0.0) and estimate < 1e-6


def test_slow_exchange_reproduces_carter_kibler_within_its_first_order_accuracy():
    gamma, beta = 0.01 * KAPPA / 3, 0.01 * KAPPA
    times = np.linspace(0.0, 400 * DAY, 41)
    soak = Exposure.piecewise([0.0, 400 * DAY], [330.0], [1.0])
    result = solve(Sheet(H), ISOTROPIC, soak, times, accuracy=1e-6, sorption=law(gamma, beta))
    approx = carter_kibler_approximation(times, D, H, gamma, beta)
    assert result.model == "analytic"
    assert np.max(np.abs(result.mean - approx)) < (gamma + beta) / KAPPA


@pytest.mark.parametrize("geometry, model", [(Sheet(H), "slab"), (Disc(0.01, H), "axisymmetric")])
def test_fipy_path_matches_the_exact_modes_after_an_rh_step_down(geometry, model):
    sorption = law(2e-7, 6e-7)
    times = np.linspace(0.0, 100 * DAY, 21)[1:]
    exact = solve(geometry, ISOTROPIC, STEP_DOWN, times, accuracy=1e-7, sorption=sorption)
    errors = []
    for accuracy in (1e-2, 1e-3):
        fv = solve(geometry, ISOTROPIC, STEP_DOWN, times, accuracy=accuracy, model=model,
                   sorption=sorption)
        assert fv.model == model
        error = np.max(np.abs(fv.mean - exact.mean)) / 2.0      # relative to the swing, 2 %
        assert error < accuracy
        assert np.max(np.abs(fv.bound - exact.bound)) / 2.0 < accuracy
        errors.append(error)
    assert errors[1] < errors[0]


def test_bound_water_is_released_slowly_after_the_step_down():
    """After the RH step down the free water leaves at the diffusion rate, the bound water
    at the release rate: the bound share of the total rises above its equilibrium share."""
    times = np.array([40 * DAY, 41 * DAY, 45 * DAY])
    result = solve(Sheet(H), ISOTROPIC, STEP_DOWN, times, accuracy=1e-6, sorption=law(2e-7, 6e-7))
    share = result.bound / result.mean
    assert share[0] < 0.25 + 1e-3
    assert share[2] > 0.3


def test_cam_plate_planform_modes_match_the_exact_disc_after_an_rh_step_down():
    """A circular CamPlate (planform eigenmodes of FiPy's operator x exact sheet modes)
    against the exact two-phase modes of the Disc it approximates (polygon of 160 sides:
    area short by 2.6e-4, within the accuracy)."""
    radius, thickness = 0.005, 0.006
    angle = np.linspace(0.0, 2.0 * np.pi, 160, endpoint=False)
    plate = CamPlate(radius * np.cos(angle), radius * np.sin(angle), thickness)
    diffusivity = Diffusivity((1e-11,) * 3, 0.0)
    times = np.linspace(0.0, 100 * DAY, 11)[1:]
    sorption = law(2e-7, 6e-7)
    exact = solve(Disc(radius, thickness), diffusivity, STEP_DOWN, times, accuracy=1e-7,
                  sorption=sorption)
    modes = solve(plate, diffusivity, STEP_DOWN, times, accuracy=1e-2, sorption=sorption)
    assert modes.model == "plane"
    assert np.max(np.abs(modes.mean - exact.mean)) / 2.0 < 1e-2
    assert np.max(np.abs(modes.bound - exact.bound)) / 2.0 < 1e-2
    assert modes.error_estimate < 1e-2


def test_link_planform_modes_without_binding_match_the_fickian_plane_model():
    link = LinkBar(0.04, 0.01, 0.004, 0.008, 0.003)
    diffusivity = Diffusivity((1e-11,) * 3, 0.0)
    times = np.linspace(0.0, 100 * DAY, 6)[1:]
    modes = solve(link, diffusivity, STEP_DOWN, times, accuracy=1e-2, sorption=law(0.0, 6e-7))
    fickian = solve(link, diffusivity, STEP_DOWN, times, accuracy=1e-3)
    assert modes.model == "plane" and np.isfinite(modes.error_estimate)
    assert np.max(np.abs(modes.mean - fickian.mean)) / 2.0 < 1e-2
    bound = solve(link, diffusivity, STEP_DOWN, times, accuracy=1e-2, sorption=law(2e-7, 6e-7))
    assert np.all(bound.bound > 0) and np.all(bound.bound < bound.mean)
