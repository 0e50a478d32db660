"""Diffusion solve: every model against Crank's exact solutions, over whole histories."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from scipy.special import jn_zeros

from fickcam.diffusion import (Bar, CamPlate, Diffusivity, Disc, Exposure, LinkBar, Sheet, plan,
                               solve)
from fickcam.diffusion.forcing.clock import rescaled_time
from fickcam.errors import InputError

DAY = 86400.0
D = 1e-12
ISOTROPIC = Diffusivity((D, D, D), 0.0)


def sheet_uptake(tstar):
    """Crank 1975 eq. 4.18, sheet of thickness h = 2l, tstar = D t / h^2 (M_t / M_inf)."""
    tstar = np.atleast_1d(np.asarray(tstar, float))
    k = (2 * np.arange(3000)[:, None] + 1) * np.pi
    return np.where(tstar > 0, 1 - np.sum(8 / k ** 2 * np.exp(-k ** 2 * tstar[None, :]), axis=0),
                    0.0)


def cylinder_uptake(tstar):
    """Crank 1975 eq. 5.23, infinite cylinder of radius a, tstar = D t / a^2."""
    tstar = np.atleast_1d(np.asarray(tstar, float))
    beta = jn_zeros(0, 400)[:, None]
    return np.where(tstar > 0, 1 - np.sum(4 / beta ** 2 * np.exp(-beta ** 2 * tstar[None, :]),
                                          axis=0), 0.0)


def product_uptake(*fractions):
    """Unsaturated fractions multiply (Crank 1975 eq. 4.51)."""
    return 1 - np.prod([1 - f for f in fractions], axis=0)


def superposed(step_response, exposure_jumps, times):
    """Duhamel: c(t) = c0 + sum_j dg_j F(t - t_j) (Crank 1975 eq. 4.34)."""
    total = np.zeros_like(times)
    for t_j, dg in exposure_jumps:
        total += dg * np.where(times >= t_j, step_response(np.maximum(times - t_j, 0.0)), 0.0)
    return total


STEP_DOWN = Exposure.piecewise([0.0, 20 * DAY, 40 * DAY], 350.0, [1.5, 0.3], 0.0)
STEP_DOWN_JUMPS = [(0.0, 1.5), (20 * DAY, -1.2)]
TIMES = np.linspace(0.0, 40 * DAY, 41)


def relative_error(result, reference, swing=1.5):
    return float(np.max(np.abs(result - reference))) / swing


@pytest.mark.parametrize("accuracy", [1e-3, 1e-4])
def test_sheet_matches_crank_series_through_an_rh_step_down(accuracy):
    h = 2e-3
    result = solve(Sheet(h), ISOTROPIC, STEP_DOWN, TIMES, accuracy=accuracy, model="slab")
    exact = superposed(lambda t: sheet_uptake(D * t / h ** 2), STEP_DOWN_JUMPS, TIMES)
    assert relative_error(result.mean, exact) <= accuracy
    assert result.error_estimate <= 2 * accuracy


def test_sheet_in_two_temperatures_follows_the_rescaled_time():
    """Arrhenius history: the mean equals the isothermal series at tau (Crank 1975 eq. 7.5)."""
    h, diffusivity = 1e-3, Diffusivity((1e-6, 1e-6, 1e-6), 40e3)
    exposure = Exposure.piecewise([0.0, 5 * DAY, 10 * DAY], [330.0, 360.0], [1.0, 1.0], 0.0)
    times = np.linspace(0, 10 * DAY, 21)
    result = solve(Sheet(h), diffusivity, exposure, times, accuracy=1e-3, model="slab")
    tau = rescaled_time(diffusivity, exposure, times, a_ref=1.0)
    exact = sheet_uptake(1e-6 * tau / h ** 2)
    assert relative_error(result.mean, exact, 1.0) <= 1e-3


@pytest.mark.slow
def test_sheet_ramp_matches_duhamel_integral():
    h = 1e-3
    exposure = Exposure.piecewise([0.0, 2 * DAY, 6 * DAY, 8 * DAY], 340.0, [0.5, 2.0, 2.0], 0.0,
                                  ramp=[False, True, False])
    times = np.linspace(0, 8 * DAY, 33)
    result = solve(Sheet(h), ISOTROPIC, exposure, times, accuracy=1e-3, model="slab")
    sub = np.linspace(2 * DAY, 6 * DAY, 2001)
    jumps = [(0.0, 0.5)] + [(0.5 * (a + b), 1.5 / 2000) for a, b in zip(sub[:-1], sub[1:])]
    exact = superposed(lambda t: sheet_uptake(D * t / h ** 2), jumps, times)
    assert relative_error(result.mean, exact, 2.0) <= 1e-3


def test_disc_rz_matches_cylinder_times_sheet_after_a_step_down():
    disc = Disc(outer_radius=5e-3, thickness=2e-3)
    result = solve(disc, ISOTROPIC, STEP_DOWN, TIMES, accuracy=3e-3, model="axisymmetric")

    def step(t):
        return product_uptake(cylinder_uptake(D * t / 5e-3 ** 2), sheet_uptake(D * t / 2e-3 ** 2))
    assert relative_error(result.mean, superposed(step, STEP_DOWN_JUMPS, TIMES)) <= 3e-3


@pytest.mark.slow
def test_bar_3d_matches_product_of_three_sheets_after_a_step_down():
    bar = Bar(8e-3, 6e-3, 3e-3)
    times = np.linspace(0, 40 * DAY, 5)
    result = solve(bar, ISOTROPIC, STEP_DOWN, times, accuracy=2e-2, model="solid")

    def step(t):
        return product_uptake(*(sheet_uptake(D * t / s ** 2) for s in (8e-3, 6e-3, 3e-3)))
    assert relative_error(result.mean, superposed(step, STEP_DOWN_JUMPS, times)) <= 2e-2


def test_rectangular_cam_plate_matches_product_of_three_sheets_after_a_step_down():
    """The planform x sheet construction against the exact 3-D block (Crank eq. 4.51)."""
    length, width, h = 12e-3, 8e-3, 3e-3
    plate = CamPlate(np.array([0, length, length, 0.0]), np.array([0, 0, width, width]), h)
    times = np.linspace(0, 40 * DAY, 5)
    result = solve(plate, ISOTROPIC, STEP_DOWN, times, accuracy=1e-2)

    def step(t):
        return product_uptake(*(sheet_uptake(D * t / s ** 2) for s in (length, width, h)))
    assert relative_error(result.mean, superposed(step, STEP_DOWN_JUMPS, times)) <= 1e-2


@pytest.mark.slow
def test_anisotropic_bar_scales_each_axis():
    """D_x != D_z: the block solution with each side scaled by sqrt(D_z / D_i) (Crank §2.6)."""
    d = (4e-12, 1e-12, 1e-12)
    bar = Bar(8e-3, 4e-3, 2e-3)
    times = np.array([0.0, 2 * DAY, 8 * DAY, 20 * DAY])
    exposure = Exposure.piecewise([0.0, 20 * DAY], 330.0, [1.0])
    result = solve(bar, Diffusivity(d, 0.0), exposure, times, accuracy=3e-2, model="solid")
    exact = product_uptake(*(sheet_uptake(di * times / s ** 2)
                             for di, s in zip(d, (8e-3, 4e-3, 2e-3))))
    assert relative_error(result.mean, exact, 1.0) <= 3e-2


def test_surface_layer_leads_the_mean_during_uptake_and_desorption():
    result = solve(Sheet(2e-3), ISOTROPIC, STEP_DOWN, TIMES, accuracy=1e-3, model="slab",
                   surface_layer_depth=2e-4)
    uptake, drying = TIMES[1:20], TIMES[21:]
    assert np.all(result.surface[1:20] > result.mean[1:20])
    assert np.all(result.surface[21:] < result.mean[21:])
    assert uptake.size and drying.size


# ------------------------------------------------------------- extremes


@pytest.mark.parametrize("diffusivity,thickness", [(1e-16, 0.1), (1e-16, 1e-4), (1e-8, 1e-4),
                                                   (1e-8, 0.1), (1e-12, 5e-3)])
def test_twenty_years_stay_bounded_finite_and_monotone(diffusivity, thickness):
    years = 20 * 365.25 * DAY
    exposure = Exposure.piecewise([0.0, years], 320.0, [2.0], 0.0)
    times = np.linspace(0, years, 21)
    result = solve(Sheet(thickness), Diffusivity((diffusivity,) * 3, 0.0), exposure, times,
                   accuracy=1e-2, model="slab")
    tolerance = 2.0 * result.error_estimate
    assert np.all(np.isfinite(result.mean)) and np.all(np.isfinite(result.surface))
    assert result.mean.min() >= -tolerance and result.mean.max() <= 2.0 * (1 + tolerance)
    assert np.all(np.diff(result.mean) >= -tolerance)
    exact = sheet_uptake(diffusivity * times / thickness ** 2) * 2.0
    assert relative_error(result.mean, exact, 2.0) <= 1e-2


@pytest.mark.parametrize("humidity_values,initial", [([0.0], 2.0), ([3.0, 0.0], 0.0)])
def test_desorption_to_dry_reaches_zero_without_undershoot(humidity_values, initial):
    n = len(humidity_values)
    edges = np.linspace(0, 30 * DAY * n, n + 1)
    exposure = Exposure.piecewise(edges, 330.0, humidity_values, initial)
    times = np.linspace(0, edges[-1], 31)
    result = solve(Sheet(0.5e-3), ISOTROPIC, exposure, times, accuracy=1e-3, model="slab")
    assert result.mean[-1] == pytest.approx(0.0, abs=1e-3)
    assert result.mean.min() >= -1e-3 * max(initial, 3.0)


def test_part_saturates_in_one_step_at_huge_fourier_number():
    exposure = Exposure.piecewise([0.0, 365 * DAY], 330.0, [1.7], 0.0)
    result = solve(Sheet(1e-4), Diffusivity((1e-8,) * 3, 0.0), exposure,
                   np.array([0.0, DAY, 365 * DAY]), accuracy=1e-3, model="slab")
    assert result.mean[1:] == pytest.approx([1.7, 1.7], rel=1e-9)


# ------------------------------------------------------------ plan, auto


def test_annulus_plan_is_axisymmetric_with_reason():
    chosen = plan(Disc(0.02, 0.005, 0.008), ISOTROPIC, STEP_DOWN, TIMES, accuracy=1e-3)
    assert chosen.model == "axisymmetric" and "bore" in chosen.reason
    assert chosen.cells > 0 and chosen.steps > 0 and chosen.error_estimate <= 1e-3


def test_tighter_accuracy_plans_more_cells_and_steps():
    loose, tight = (plan(Sheet(2e-3), ISOTROPIC, STEP_DOWN, TIMES, accuracy=a, model="slab")
                    for a in (1e-2, 1e-4))
    assert tight.cells > loose.cells and tight.steps > loose.steps


def test_model_not_applicable_to_the_geometry_is_an_input_error():
    with pytest.raises(InputError, match="solid"):
        plan(Sheet(1e-3), ISOTROPIC, STEP_DOWN, TIMES, model="solid")
    with pytest.raises(InputError, match="accuracy"):
        plan(Sheet(1e-3), ISOTROPIC, STEP_DOWN, TIMES, accuracy=2.0)


def test_the_model_registry_says_which_parts_each_model_solves_and_why_not():
    """Each model of the registry answers for itself: the parts it applies to, the reason it
    refuses one (the analytic series needs a separable part), and ``auto``'s choice is the
    exact series where it applies, else the first mesh model that does."""
    from fickcam.diffusion.dispatch import FICK_MODELS, MODELS, numerical_model

    outline = np.array([0.0, 0.02, 0.02, 0.0]), np.array([0.0, 0.0, 0.01, 0.01])
    parts = {"sheet": Sheet(1e-3), "disc": Disc(0.02, 0.004), "annulus": Disc(0.02, 0.004, 0.008),
             "bar": Bar(0.04, 0.01, 0.004), "cam": CamPlate(*outline, 0.004),
             "link": LinkBar(0.1, 0.01, 0.004, 0.01, 0.005)}
    solvable = {name: sorted(m for m, model in FICK_MODELS.items()
                             if model.refusal(part) is None)
                for name, part in parts.items()}
    assert solvable == {"sheet": ["analytic", "slab"], "disc": ["analytic", "axisymmetric"],
                        "annulus": ["axisymmetric"], "bar": ["analytic", "solid"],
                        "cam": ["plane", "solid"], "link": ["plane", "solid"]}
    assert FICK_MODELS["analytic"].refusal(parts["annulus"]) == (
        "an annulus has no product solution (use axisymmetric)")
    assert FICK_MODELS["plane"].refusal(parts["sheet"]) == "does not apply to a Sheet"
    assert [numerical_model(p) for p in parts.values()] == [
        "slab", "axisymmetric", "axisymmetric", "solid", "plane", "plane"]
    assert MODELS == ("auto", "analytic", "slab", "axisymmetric", "plane", "solid")
    with pytest.raises(InputError, match="annulus has no product solution"):
        plan(parts["annulus"], ISOTROPIC, STEP_DOWN, TIMES, model="analytic")


def test_auto_takes_the_exact_path_for_a_sheet_when_available():
    chosen = plan(Sheet(1e-3), ISOTROPIC, STEP_DOWN, TIMES, accuracy=1e-3)
    assert chosen.model == "analytic"
    result = solve(Sheet(2e-3), ISOTROPIC, STEP_DOWN, TIMES, accuracy=1e-4)
    exact = superposed(lambda t: sheet_uptake(D * t / 2e-3 ** 2), STEP_DOWN_JUMPS, TIMES)
    assert relative_error(result.mean, exact) <= 1e-4


@pytest.mark.slow
def test_importing_the_diffusion_package_does_not_import_fipy():
    code = "import sys, fickcam.diffusion; print('fipy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_fields_have_cells_and_coordinates():
    link = LinkBar(0.04, 0.01, 0.004, 0.008, 0.003)
    times = np.array([0.0, 10 * DAY, 40 * DAY])
    result = solve(link, ISOTROPIC, STEP_DOWN, times, accuracy=3e-2, store_fields=True)
    n_cells = result.fields.shape[1]
    assert result.fields.shape == (3, n_cells)
    assert set(result.cell_coordinates) == {"x", "y", "z"}
    assert all(v.shape == (n_cells,) for v in result.cell_coordinates.values())
    assert np.all(result.fields[0] == 0.0) and np.all(result.fields[1] > 0)


def test_output_a_hair_after_a_step_boundary_records_that_boundary_not_the_next():
    """An output within round-off above a node is merged into it (``drop_slivers``);
    it must read that node, not the next one (``searchsorted`` alone took the next)."""
    from fickcam.diffusion.stepping.step_plans import drop_slivers, nearest_nodes

    first = 1e-6
    nodes = np.array([0.0, 1e-6, 2e-6, 4e-6, 8e-6])
    outputs = np.array([2e-6 * (1 + 1e-12), 8e-6])
    merged = drop_slivers(np.unique(np.concatenate([nodes, outputs])), first)
    assert merged.size == nodes.size
    assert list(nearest_nodes(merged, outputs)) == [2, 4]
    assert list(nearest_nodes(merged, np.array([0.0, 3.1e-6]))) == [0, 3]
