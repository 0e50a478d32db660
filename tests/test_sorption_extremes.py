"""Extremes of the sorption laws: exchange rates 1e-3..1e3 of the diffusion rate, D
exponents 0..5: bounded, no NaN, mass conserved (free + bound against the exact series,
which conserves it; wet to equilibrium and dry again)."""
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from fickcam.diffusion import DiffusionProblem, solve
from fickcam.diffusion.accuracy.budget import MAX_ACCURACY

LOOSEST = MAX_ACCURACY  # the loosest accuracy a solve accepts
from fickcam.diffusion.exact.two_phase import two_phase_sheet_uptake
from fickcam.diffusion.problem.exposure import Diffusivity, Exposure
from fickcam.diffusion.problem.geometry import CamPlate, Disc, Sheet
from fickcam.diffusion.problem.sorption import ConcentrationDependent, Langmuir, Rate

H, D, MM = 2e-3, 5e-12, 2.0
KAPPA = np.pi ** 2 * D / H ** 2
ISOTROPIC = Diffusivity((D, D, D), 0.0)


def soak_and_dry(end):
    """Wet to Mm for half the time, then dry: absorption and desorption in one history."""
    return Exposure.piecewise([0.0, 0.5 * end, end], [330.0, 330.0], [MM, 0.0])


@settings(max_examples=8, deadline=None)
@given(st.floats(-3, 3), st.floats(-3, 3))
def test_two_phase_extremes_stay_bounded_and_conserve_mass(log_gamma, log_beta):
    gamma, beta = KAPPA * 10 ** log_gamma, KAPPA * 10 ** log_beta
    slowest = min(KAPPA, gamma, beta)
    end = 40.0 / slowest
    times = np.geomspace(1e-3 / KAPPA, 0.5 * end, 25)
    soak = Exposure.piecewise([0.0, end], [330.0], [MM])
    law = Langmuir(Rate(gamma), Rate(beta))
    modes = solve(Sheet(H), ISOTROPIC, soak, times, accuracy=1e-6, sorption=law)
    exact = two_phase_sheet_uptake(times, D, H, gamma, beta)
    assert np.all(np.isfinite(modes.mean)) and np.all(np.isfinite(modes.bound))
    assert np.max(np.abs(modes.mean / MM - exact.total)) < 1e-5
    assert np.max(np.abs(modes.bound / MM - exact.bound)) < 1e-5
    assert np.all(modes.bound >= -1e-9) and np.all(modes.mean <= MM * (1 + 1e-9))
    fv = solve(Sheet(H), ISOTROPIC, soak_and_dry(end), times, accuracy=1e-2, model="slab",
               sorption=law)
    assert np.all(np.isfinite(fv.mean)) and np.all(np.isfinite(fv.bound))
    assert np.all(fv.mean >= -1e-2 * MM) and np.all(fv.mean <= MM * (1 + 1e-2))
    assert np.all(fv.bound >= -1e-2 * MM) and np.all(fv.bound <= fv.mean + 1e-2 * MM)
    assert fv.mean[-1] == pytest.approx(exact.total[-1] * MM, abs=1e-2 * MM)


@pytest.mark.slow
@pytest.mark.parametrize("exponent", [0.0, 5.0])
def test_concentration_dependent_extremes_stay_bounded_and_reach_equilibrium(exponent):
    law = ConcentrationDependent(MM, exponent=exponent)
    end = 4.0 * H ** 2 / D
    times = np.array([0.01, 0.1, 0.5, 1.0, 1.6, 2.5, 4.0]) * H ** 2 / D
    result = solve(Sheet(H), ISOTROPIC, soak_and_dry(end), times, accuracy=1e-2, sorption=law,
                   store_fields=True)
    assert np.all(np.isfinite(result.fields))
    # Richardson's 2 fine - coarse may step outside [0, Mm] by its own error, no more
    assert np.all(result.fields >= -1e-2 * MM) and np.all(result.fields <= MM * (1 + 1e-2))
    wet = times <= 0.5 * end
    assert np.all(np.diff(result.mean[wet]) > -1e-3 * MM) and np.all(np.diff(result.mean[~wet]) < 0)
    assert result.mean[np.flatnonzero(wet)[-1]] == pytest.approx(MM, abs=1e-2 * MM)
    assert result.mean[-1] == pytest.approx(0.0, abs=1e-2 * MM)


@pytest.mark.slow
@settings(max_examples=6, deadline=None)
@given(st.floats(-3, 3), st.floats(-3, 3))
def test_two_phase_extremes_on_a_cam_plate_stay_bounded_and_conserve_mass(log_gamma, log_beta):
    """A circular CamPlate on its planform quadrature (``planform_modes``), wet and dried, against
    the exact disc modes (which conserve free + bound water): rates 1e-3..1e3 of the
    slowest diffusion rate of the plate, within the accuracy, bounded, finite."""
    radius, thickness, d = 0.004, 0.004, 1e-11
    slowest = d * (2.405 ** 2 / radius ** 2 + np.pi ** 2 / thickness ** 2)
    gamma, beta = slowest * 10 ** log_gamma, slowest * 10 ** log_beta
    end = 20.0 / min(slowest, gamma, beta)
    times = np.geomspace(1e-2 / slowest, end, 12)
    angle = np.linspace(0.0, 2.0 * np.pi, 160, endpoint=False)
    plate = CamPlate(radius * np.cos(angle), radius * np.sin(angle), thickness)
    law = Langmuir(Rate(gamma), Rate(beta))
    diffusivity = Diffusivity((d, d, d), 0.0)
    history = soak_and_dry(end)
    modes = solve(plate, diffusivity, history, times, accuracy=1e-2, sorption=law)
    exact = solve(Disc(radius, thickness), diffusivity, history, times, accuracy=1e-6, sorption=law)
    assert modes.model == "plane"
    assert np.all(np.isfinite(modes.mean)) and np.all(np.isfinite(modes.bound))
    assert np.all(modes.bound >= -1e-2 * MM) and np.all(modes.bound <= modes.mean + 1e-2 * MM)
    assert np.all(modes.mean <= MM * (1 + 1e-2)) and np.all(modes.mean >= -1e-2 * MM)
    assert np.max(np.abs(modes.mean - exact.mean)) < 1e-2 * MM
    assert np.max(np.abs(modes.bound - exact.bound)) < 1e-2 * MM



PLATE = CamPlate(np.array([0, 3e-3, 3e-3, 0.0]), np.array([0, 0, 2e-3, 2e-3]), H)
PLATE_TIMES = np.array([0.1, 0.3, 0.6, 0.9]) * H ** 2 / D  # late enough for coarse cells
PLATE_HISTORIES = {  # (initial moisture, surface in the first half, in the second half)
    "absorption": (0.0, MM, MM), "desorption": (MM, 0.0, 0.0), "step down": (0.0, MM, 0.4 * MM)}


@pytest.mark.slow
@settings(max_examples=1, deadline=None)
@given(st.floats(0.0, 5.0), st.sampled_from(sorted(PLATE_HISTORIES)))
@example(5.0, "desorption")
def test_corrected_plate_extremes_stay_bounded_and_agree_with_the_3d_cells(exponent, history):
    """D = D0 exp(k c/Mm), k = 0..5, on a 3 x 2 x 2 mm plate by the corrected product
    (``corrected_product.solve_corrected``, what ``auto`` runs for k > 0) at a loose accuracy:
    finite,
    within the surface values and the initial moisture by its own estimate (Richardson's
    2 fine - coarse may step outside by its error; the layer by LAYER_TOLERANCE times it),
    uptake monotone under absorption, and the mean within both estimates of the 3-D cells'
    own result (``model: solid`` at the loosest accuracy a solve accepts, 0.1: 3-D cells
    marched alone, uncorrected). Few examples: each runs about
    20 swept marches of 300-600 steps; the explicit one is the extreme skin (k = 5, drying)."""
    from fickcam.diffusion.nonfickian.corrected_product import solve_corrected
    from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE

    initial, wet, late = PLATE_HISTORIES[history]
    end = PLATE_TIMES[-1]
    changes = ([0.0, 0.5 * end, end], [wet, late]) if late != wet else ([0.0, end], [wet])
    exposure = Exposure.piecewise(changes[0], [330.0] * len(changes[1]), changes[1],
                                  initial_moisture=initial)
    law = ConcentrationDependent(MM, exponent=exponent)
    corrected = solve_corrected(DiffusionProblem(PLATE, ISOTROPIC, exposure, PLATE_TIMES, 0.3,
                                                 sorption=law))
    alone = solve(PLATE, ISOTROPIC, exposure, PLATE_TIMES, accuracy=LOOSEST,
                  model="solid", sorption=law)
    swing = max(abs(wet - initial), abs(late - initial))
    slack = corrected.error_estimate * swing
    low, high = min(initial, wet, late), max(initial, wet, late)
    assert np.all(np.isfinite(corrected.mean)) and np.all(np.isfinite(corrected.surface))
    assert np.all(corrected.mean >= low - slack) and np.all(corrected.mean <= high + slack)
    assert np.all(corrected.surface >= low - LAYER_TOLERANCE * slack)
    assert np.all(corrected.surface <= high + LAYER_TOLERANCE * slack)
    if history == "absorption":
        assert np.all(np.diff(corrected.mean) >= -2.0 * slack)
    both = (corrected.error_estimate + alone.error_estimate) * swing
    assert np.max(np.abs(corrected.mean - alone.mean)) <= both
