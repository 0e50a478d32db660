"""Two-phase (Langmuir) sorption: the exact modal march against the exact sheet solution
(Carter & Kibler 1978), against Fick (gamma = 0), and the FiPy
finite-volume paths against the exact modes over a history with an RH step down."""
import numpy as np
import pytest

from fickcam.diffusion import plan, solve
from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE
from fickcam.diffusion.exact.two_phase import (carter_kibler_approximation, exchange_propagator,
                                               two_phase_sheet_uptake)
from fickcam.diffusion.nonfickian.planform_modes import (lanczos_spectrum, planform_operator,
                                                         planform_source)
from fickcam.diffusion.nonfickian.two_phase_modes import langmuir_history
from fickcam.diffusion.problem.exposure import Diffusivity, Exposure
from fickcam.diffusion.problem.geometry import Bar, CamPlate, Disc, LinkBar, Sheet
from fickcam.diffusion.problem.sorption import Langmuir, Rate

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


def circular_plate(radius=0.005, thickness=0.006, sides=160):
    """A CamPlate whose outline is a 160-gon of the disc (area short by 2.6e-4)."""
    angle = np.linspace(0.0, 2.0 * np.pi, sides, endpoint=False)
    return CamPlate(radius * np.cos(angle), radius * np.sin(angle), thickness)


PLATE_DIFFUSIVITY = Diffusivity((1e-11,) * 3, 0.0)
PLATE_TIMES = np.linspace(0.0, 100 * DAY, 11)[1:]


@pytest.mark.parametrize("accuracy", [1e-3, 1e-4])
def test_cam_plate_planform_modes_match_the_exact_disc_after_an_rh_step_down(accuracy):
    """A circular CamPlate (the planform's Lanczos quadrature x exact sheet modes, the mesh
    refined from its measured error) against the exact two-phase modes of the Disc it
    approximates: within the accuracy, and the estimate is honest (at least half the
    error actually made)."""
    sorption = law(2e-7, 6e-7)
    exact = solve(Disc(0.005, 0.006), PLATE_DIFFUSIVITY, STEP_DOWN, PLATE_TIMES, accuracy=1e-7,
                  sorption=sorption)
    modes = solve(circular_plate(), PLATE_DIFFUSIVITY, STEP_DOWN, PLATE_TIMES, accuracy=accuracy,
                  sorption=sorption)
    assert modes.model == "plane"
    error = max(np.max(np.abs(modes.mean - exact.mean)), np.max(np.abs(modes.bound - exact.bound)))
    assert error / 2.0 < accuracy
    assert error / 2.0 < 2.0 * modes.error_estimate < 2.0 * accuracy
    assert np.max(np.abs(modes.surface - exact.surface)) / 2.0 < LAYER_TOLERANCE * accuracy


@pytest.mark.slow
def test_cam_plate_planform_mesh_converges_at_second_order():
    """The two-phase history on the planform meshes w0, w0/2, w0/4 (finest width and growth
    halved together): differences fall by 4, observed order log2(d01/d12) = 2 +- 0.3 for
    the total and the bound water (FiPy's two-point flux, as for Fick)."""
    plate, sorption = circular_plate(), law(2e-7, 6e-7)
    chosen = plan(plate, PLATE_DIFFUSIVITY, STEP_DOWN, PLATE_TIMES, accuracy=1e-2, sorption=sorption)
    d = PLATE_DIFFUSIVITY.pre_exponential
    levels = []
    for refinement in (1, 2, 4):
        operator = planform_operator(plate, d, 5e-4, chosen.finest / refinement,
                                     chosen.growth / refinement)
        source = planform_source(plate, d, lanczos_spectrum(operator, 64))
        history, _ = langmuir_history(plate, PLATE_DIFFUSIVITY, sorption, STEP_DOWN, PLATE_TIMES,
                                      1e-6, 5e-4, source)
        levels.append(np.stack([history["mean"], history["bound"]]))
    first, second = (np.max(np.abs(a - b), axis=1) for a, b in zip(levels, levels[1:]))
    assert np.log2(first / second) == pytest.approx([2.0, 2.0], abs=0.3)


def test_lanczos_quadrature_reproduces_the_moments_of_the_planform_spectrum():
    """m shift-and-invert Lanczos steps from M^1/2 1 are the m-point Gauss quadrature of
    the planform's spectral measure; the mean and the layer, each a bilinear form w^T
    S^-k v of their gradient-corrected weights (``cell_moments``) against the start v,
    are exact for k < m (Golub & Meurant 2010 §§6.2, 7.1); with m = cells it is the
    whole spectrum (dense eigh)."""
    plate = circular_plate()
    operator = planform_operator(plate, PLATE_DIFFUSIVITY.pre_exponential, 5e-4, 0.2, 0.25)
    rates, mean, layer = lanczos_spectrum(operator, 6)
    matrix = operator.operator.toarray()
    vector, moments_mean, moments_layer = operator.start.copy(), [], []
    for _ in range(12):
        moments_mean.append(operator.mean @ vector)
        moments_layer.append(operator.layer @ vector)
        vector = np.linalg.solve(matrix, vector)
    powers = rates[None, :] ** -np.arange(12)[:, None]
    assert (powers @ mean)[:6] == pytest.approx(moments_mean[:6], rel=1e-9)
    assert (powers @ layer)[:6] == pytest.approx(moments_layer[:6], rel=1e-9)
    whole, _, _ = lanczos_spectrum(operator, operator.cells)
    assert np.sort(whole) == pytest.approx(np.linalg.eigvalsh(matrix), rel=1e-8)


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


@pytest.mark.slow
def test_cam_plate_fipy_prisms_match_the_exact_disc_after_an_rh_step_down():
    """``solid``: FiPy prisms of the circular plate with the coupled free/bound block
    operator (``two_phase_mesh``), against the exact two-phase disc modes: within the accuracy,
    and the error falls with it (about first order in the accuracy, as for Fick: the plan
    sizes cells and steps so that the estimate is proportional to it)."""
    sorption = law(2e-7, 6e-7)
    times = PLATE_TIMES[1::2]
    exact = solve(Disc(0.005, 0.006), PLATE_DIFFUSIVITY, STEP_DOWN, times, accuracy=1e-7,
                  sorption=sorption)
    errors = []
    for accuracy in (3e-2, 1e-2, 3e-3):
        prisms = solve(circular_plate(), PLATE_DIFFUSIVITY, STEP_DOWN, times, accuracy=accuracy,
                       model="solid", sorption=sorption)
        assert prisms.model == "solid"
        error = max(np.max(np.abs(prisms.mean - exact.mean)),
                    np.max(np.abs(prisms.bound - exact.bound))) / 2.0
        assert error < prisms.error_estimate <= accuracy
        errors.append(error)
    orders = np.log(np.array(errors[:-1]) / errors[1:]) / np.log([3.0, 10.0 / 3.0])
    assert np.all((0.6 < orders) & (orders < 1.4)), orders
