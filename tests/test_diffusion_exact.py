"""Properties of the exact series solutions and their Duhamel superposition."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from fickcam.diffusion import Bar, CamPlate, Diffusivity, Disc, Exposure, Sheet
from fickcam.diffusion.exact import series as one_dimensional
from fickcam.diffusion.exact.separable import exact_available, step_field, step_response
from fickcam.diffusion.exact.series import (cylinder_profile, cylinder_uptake, sheet_profile,
                                            sheet_series_remainder, sheet_uptake)
from fickcam.diffusion.forcing.clock import RescaledTime
from fickcam.diffusion.models.analytic import exact_history, exact_history_field


# ------------------------------------------------------------------ helpers
def piecewise(edges, ramp, end_values, start):
    """Right-continuous held/ramped history like fickcam.climate.environment."""
    edges, ramp, end_values = (np.asarray(edges, float), np.asarray(ramp, bool),
                               np.asarray(end_values, float))
    begin = np.concatenate([[start], end_values[:-1]])

    def evaluate(t):
        t = np.asarray(t, float)
        k = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, end_values.size - 1)
        frac = np.clip((t - edges[k]) / (edges[k + 1] - edges[k]), 0.0, 1.0)
        return np.where(ramp[k], begin[k] + (end_values[k] - begin[k]) * frac, end_values[k])
    return evaluate


def exposure(edges, ramp, temperature, moisture, initial=0.0, moisture_map=None):
    surface = piecewise(edges, ramp, moisture, initial)
    if moisture_map is not None:
        surface_linear = surface
        surface = lambda t: moisture_map(surface_linear(t))  # noqa: E731
    return Exposure(np.asarray(edges, float), np.asarray(ramp, bool),
                    piecewise(edges, ramp, temperature, temperature[0]), surface, initial)


def second_difference(cells, spacing, faces=None):
    """Cell-centred diffusion operator (zero flux at the first face, Dirichlet
    ghost at the last) as (A, b): dc/dt = A c + b * boundary(t). ``faces``
    gives the radial weights r at faces for the cylinder (None: plane)."""
    from scipy.sparse import diags
    weights = np.ones(cells + 1) if faces is None else faces
    centres = np.ones(cells) if faces is None else 0.5 * (faces[1:] + faces[:-1])
    upper = weights[1:-1] / (centres[:-1] * spacing ** 2)
    lower = weights[1:-1] / (centres[1:] * spacing ** 2)
    main = -(weights[:-1] * (np.arange(cells) > 0) + weights[1:]) / (centres * spacing ** 2)
    main[-1] -= weights[-1] / (centres[-1] * spacing ** 2)
    b = np.zeros(cells)
    b[-1] = 2.0 * weights[-1] / (centres[-1] * spacing ** 2)
    return diags([lower, main, upper], [-1, 0, 1], format="csr"), b


def lines_solution(matrix, b, boundary, initial, times):
    """BDF solution of dc/dt = A c + b boundary(t) (method-of-lines reference)."""
    sol = solve_ivp(lambda t, c: matrix @ c + b * boundary(t), (0.0, times[-1]), initial,
                    t_eval=times, method="BDF", jac=matrix, rtol=1e-10, atol=1e-12)
    return sol.y


# ------------------------------------------------------------------- sheet
def test_sheet_short_and_series_forms_agree_where_both_converge():
    t = np.geomspace(0.01, 0.2, 30)   # 12 modes converge from t* = 0.01, images up to 0.2
    images = one_dimensional.sheet_interval_mean_images(0.0, 1.0, t)
    series = one_dimensional.sheet_interval_mean_series(0.0, 1.0, t)
    assert np.max(np.abs(images - series)) < 1e-13
    z = np.linspace(0.0, 1.0, 11)[:, None]
    both = [one_dimensional.sheet_interval_mean_images(0.1, 0.7, t), one_dimensional.sheet_interval_mean_series(0.1, 0.7, t)]
    assert np.max(np.abs(both[0] - both[1])) < 1e-13
    assert np.all(sheet_profile(z, t) >= 0.0)


def test_sheet_small_time_limit_and_saturation():
    t = np.geomspace(1e-12, 1e-3, 20)
    assert np.allclose(sheet_uptake(t), 4.0 * np.sqrt(t / np.pi), rtol=1e-13)
    assert sheet_uptake(0.0) == 0.0
    assert np.all(sheet_uptake(np.array([10.0, 1e6, 1e12])) == 1.0)


def test_sheet_half_time_is_crank_value():
    half = brentq(lambda t: sheet_uptake(t) - 0.5, 1e-3, 1.0, xtol=1e-15)
    assert abs(half - 0.04919) < 1e-5          # Crank 1975 §4.3.1: t_1/2 = 0.04919 l^2/D
    assert half > np.pi / 64.0                 # the image terms delay the one-term estimate


def test_sheet_series_remainder_bounds_truncation():
    t = np.array([1e-3, 1e-2, 0.1])
    for terms in (1, 3, 5):
        partial = 1.0 - sum(8.0 / (k * np.pi) ** 2 * np.exp(-(k * np.pi) ** 2 * t)
                            for k in range(1, 2 * terms, 2))
        error = np.abs(partial - sheet_uptake(t))
        assert np.all(error <= sheet_series_remainder(t, terms) * (1 + 1e-12) + 1e-16)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 1e6, allow_nan=False), min_size=2, max_size=30))
def test_sheet_uptake_is_monotone_and_bounded(values):
    t = np.sort(np.asarray(values))
    f = sheet_uptake(t)
    assert np.all(np.diff(f) >= -1e-15)
    assert np.all((f >= 0.0) & (f <= 1.0))


def test_sheet_mass_balance_rate_equals_surface_flux():
    # dF/dt* = 2 x (-dc/dz at z = 0) in units of h (two faces, Crank 1975 eq. 4.21 context)
    for t in (1e-3, 0.02, 0.05, 0.2):
        dt, dz = 1e-6 * t, 1e-6
        rate = (sheet_uptake(t + dt) - sheet_uptake(t - dt)) / (2 * dt)
        gradient = (-sheet_profile(2 * dz, t) + 4 * sheet_profile(dz, t) - 3 * sheet_profile(0.0, t)) / (2 * dz)
        assert rate == pytest.approx(-2.0 * gradient, rel=1e-5)


# ---------------------------------------------------------------- cylinder
def test_cylinder_matches_method_of_lines():
    cells = 400
    dr = 1.0 / cells
    r = (np.arange(cells) + 0.5) * dr
    matrix, b = second_difference(cells, dr, faces=np.arange(cells + 1) * dr)
    times = np.array([0.01, 0.05, 0.2, 0.5])
    y = lines_solution(matrix, b, lambda t: 1.0, np.zeros(cells), times)
    mean = 2.0 * np.sum(y * (r * dr)[:, None], axis=0)
    assert np.allclose(cylinder_uptake(times), mean, atol=2e-4)
    assert np.allclose(cylinder_profile(r[::40, None], times[None, :]), y[::40], atol=3e-4)


def test_cylinder_short_time_expansion_and_limits():
    t = np.array([3e-5, 1e-4, 3e-4])
    roots = one_dimensional.roots_for(1e-5)
    series = 1.0 - one_dimensional.cylinder_core_deficit(np.ones(3), t, roots)
    assert np.allclose(one_dimensional.cylinder_uptake_short(t), series, atol=1e-14)
    tiny = np.geomspace(1e-14, 1e-8, 5)
    assert np.allclose(cylinder_uptake(tiny), 4 * np.sqrt(tiny / np.pi) - tiny, rtol=1e-8)
    assert np.all(cylinder_uptake(np.array([20.0, 1e12])) == 1.0)
    assert cylinder_uptake(0.0) == 0.0
    assert np.all(np.diff(cylinder_uptake(np.geomspace(1e-10, 10, 400))) > -1e-15)


def test_cylinder_profile_short_form_matches_series_at_switch():
    r = 1.0 - np.geomspace(1e-4, 8e-3, 12)[:, None]   # inside the penetration depth
    t = np.array([[one_dimensional.CYLINDER_PROFILE_SWITCH * (1 - 1e-9), one_dimensional.CYLINDER_PROFILE_SWITCH]])
    both = cylinder_profile(r, t)
    assert np.max(np.abs(both[:, 0] - both[:, 1])) < 1e-9   # 3-term form: O(t*^3/2)


# ---------------------------------------------------------------- products
def test_cube_is_three_sheets_and_symmetric():
    tau = np.geomspace(1e-2, 1e4, 20)
    cube = Bar(0.01, 0.01, 0.01)
    mean, _ = step_response(cube, (1e-9, 1e-9, 1e-9), tau)
    f = sheet_uptake(1e-9 * tau / 1e-4)
    assert np.allclose(mean, 1 - (1 - f) ** 3, atol=1e-15)
    points = {"x": np.array([0.002, 0.003, 0.005]), "y": np.array([0.003, 0.002, 0.005]),
              "z": np.array([0.005, 0.005, 0.002])}
    field = step_field(cube, (1e-9, 1e-9, 1e-9), tau, points)
    assert np.allclose(field[:, 0], field[:, 1], atol=1e-15)
    mirrored = dict(points, x=0.01 - points["x"])
    assert np.allclose(field, step_field(cube, (1e-9, 1e-9, 1e-9), tau, mirrored), atol=1e-13)


@pytest.mark.slow
def test_square_product_matches_2d_method_of_lines():
    from scipy.sparse import identity, kron
    n = 40   # quarter of a unit square, D = 1, symmetry at the centre lines
    line, b1 = second_difference(n, 0.5 / n)
    matrix = (kron(line, identity(n)) + kron(identity(n), line)).tocsr()
    b = np.add.outer(b1, b1).ravel()
    times = np.array([0.01, 0.05, 0.2])
    y = lines_solution(matrix, b, lambda t: 1.0, np.zeros(n * n), times)
    mean, _ = step_response(Bar(1.0, 1.0, 1e6), (1.0, 1.0, 0.0), times)
    assert np.allclose(mean, y.mean(axis=0), atol=1e-3)


def test_disc_is_cylinder_times_sheet_and_layer_covers_rim():
    disc = Disc(0.02, 0.004)
    d0 = (1e-9, 1e-9, 2e-9)
    tau = np.geomspace(1.0, 1e7, 25)
    mean, layer = step_response(disc, d0, tau, 5e-4)
    radial = cylinder_uptake(d0[0] * tau / 0.02 ** 2)
    axial = sheet_uptake(d0[2] * tau / 0.004 ** 2)
    assert np.allclose(mean, 1 - (1 - radial) * (1 - axial), atol=1e-15)
    assert np.all(layer >= mean - 1e-14)
    # rim layer mean by quadrature of the field over r in [a - d, a], z in [0, h]
    r = 0.02 - 5e-4 * (0.5 + 0.5 * np.polynomial.legendre.leggauss(40)[0])
    wr = np.polynomial.legendre.leggauss(40)[1] * r
    z = 0.004 * (0.5 + 0.5 * np.polynomial.legendre.leggauss(60)[0])
    wz = np.polynomial.legendre.leggauss(60)[1]
    rr, zz = np.meshgrid(r, z, indexing="ij")
    field = step_field(disc, d0, tau[[5, 15]], {"r": rr.ravel(), "z": zz.ravel()})
    weights = np.outer(wr, wz).ravel()
    assert np.allclose(field @ weights / weights.sum(), layer[[5, 15]], atol=1e-9)


def test_bar_shell_layer_mean_by_quadrature():
    bar = Bar(0.01, 0.006, 0.003)
    d0 = (2e-10, 1e-10, 5e-11)
    tau = np.array([2e3, 5e4])
    _, layer = step_response(bar, d0, tau, 5e-4)
    grid = [(np.arange(n) + 0.5) / n * length for n, length in zip((100, 60, 30), (0.01, 0.006, 0.003))]
    x, y, z = np.meshgrid(*grid, indexing="ij")
    depth = np.minimum.reduce([x, 0.01 - x, y, 0.006 - y, z, 0.003 - z])
    shell = depth < 5e-4
    field = step_field(bar, d0, tau, {"x": x[shell], "y": y[shell], "z": z[shell]})
    assert np.allclose(field.mean(axis=1), layer, atol=3e-3)


def test_exact_available_only_for_separable_parts():
    assert exact_available(Sheet(1e-3)) and exact_available(Bar(1, 1, 1)) and exact_available(Disc(1, 1))
    assert not exact_available(Disc(1.0, 1.0, 0.2))
    assert not exact_available(CamPlate(np.zeros(3), np.zeros(3), 1.0))
    with pytest.raises(ValueError):
        step_response(Disc(1.0, 1.0, 0.2), (1, 1, 1), np.ones(2))


# ----------------------------------------------------------------- Duhamel
ARRHENIUS = Diffusivity((1e-6, 1e-6, 1e-6), 30_000.0)


def test_single_step_equals_direct_step_response():
    sheet = Sheet(2e-3)
    history = exposure([0, 1e6], [False], [330.0], [2.0], initial=0.1)
    t = np.linspace(0, 1e6, 50)
    result = exact_history(sheet, ARRHENIUS, history, t)
    mean, layer = step_response(sheet, ARRHENIUS.pre_exponential, t * ARRHENIUS.arrhenius_factor(330.0))
    assert np.allclose(result["mean"], 0.1 + 1.9 * mean, atol=1e-14)
    assert np.allclose(result["surface"], 0.1 + 1.9 * layer, atol=1e-14)


def test_held_history_is_sum_of_shifted_steps_and_desorbs():
    bar = Bar(0.02, 0.01, 0.003)
    edges = [0, 2e5, 5e5, 2e6]
    history = exposure(edges, [False] * 3, [330.0] * 3, [2.0, 0.0, 1.0], initial=0.0)
    t = np.linspace(0, 2e6, 60)
    result = exact_history(bar, ARRHENIUS, history, t)
    rate = ARRHENIUS.arrhenius_factor(330.0)
    expected = sum(jump * (t >= start) * step_response(bar, ARRHENIUS.pre_exponential,
                                                      np.maximum(t - start, 0) * rate)[0]
                   for jump, start in zip([2.0, -2.0, 1.0], edges[:3]))
    assert np.allclose(result["mean"], expected, atol=1e-13)
    down = (t > 2e5) & (t < 5e5)
    assert np.all(np.diff(result["mean"][down]) < 0)   # desorption after stepping back to 0


def test_ramp_history_matches_method_of_lines():
    thickness, d = 2e-3, 1e-6 * np.exp(-30_000.0 / (8.314462618 * 330.0))
    edges = [0, 1e5, 3e5, 6e5]
    rh = piecewise(edges, [True, False, True], [60.0, 60.0, 20.0], 30.0)
    surface = lambda t: 3.0 * (rh(t) / 100) ** 1.6  # noqa: E731
    history = Exposure(np.asarray(edges, float), np.array([True, False, True]),
                       lambda t: np.full(np.shape(t), 330.0), surface, 0.2)
    t = np.linspace(0, 6e5, 25)
    result = exact_history(Sheet(thickness), ARRHENIUS, history, t)
    cells = 400
    matrix, b = second_difference(cells, 0.5 * thickness / cells)
    y = lines_solution(d * matrix, d * b, lambda s: float(surface(np.array(s))), np.full(cells, 0.2), t)
    assert np.allclose(result["mean"], y.mean(axis=0), atol=2e-6)   # MOL error 6e-7 (400 cells)


def test_temperature_enters_only_through_rescaled_time():
    # a hot-then-cold held history and a linear ramp with the same tau(end)
    edges = [0, 1e5, 2e5]
    held = exposure(edges, [False, False], [340.0, 320.0], [2.0, 2.0])
    clock = RescaledTime(ARRHENIUS, held)
    iso_rate = clock(np.array([2e5]))[0] / 2e5
    iso_temperature = -30_000.0 / (8.314462618 * np.log(iso_rate))
    iso = exposure(edges, [False, False], [iso_temperature] * 2, [2.0, 2.0])
    end = np.array([2e5])
    a = exact_history(Bar(0.01, 0.01, 0.002), ARRHENIUS, held, end)
    b = exact_history(Bar(0.01, 0.01, 0.002), ARRHENIUS, iso, end)
    assert a["mean"] == pytest.approx(b["mean"], abs=1e-13)
    assert a["surface"] == pytest.approx(b["surface"], abs=1e-13)


def test_rescaled_time_on_temperature_ramp_matches_closed_form():
    # integral of exp(-c/T) dT = T E2(c/T)
    from scipy.special import expn
    history = exposure([0, 1e6], [True], [360.0], [1.0])
    history = Exposure(history.change_times, history.ramp, piecewise([0, 1e6], [True], [360.0], 300.0),
                       history.surface_moisture, 0.0)
    c = 30_000.0 / 8.314462618
    slope = 60.0 / 1e6
    exact_tau = (360.0 * expn(2, c / 360.0) - 300.0 * expn(2, c / 300.0)) / slope
    assert RescaledTime(ARRHENIUS, history)(np.array([1e6]))[0] == pytest.approx(exact_tau, rel=1e-13)


@settings(max_examples=15, deadline=None)
@given(st.lists(st.tuples(st.floats(0.0, 3.0), st.booleans(), st.floats(300.0, 360.0)),
                min_size=1, max_size=4), st.floats(0.0, 3.0))
def test_history_bounded_by_boundary_and_initial_values(segments, initial):
    edges = np.linspace(0, 4e5, len(segments) + 1)
    values = [s[0] for s in segments]
    history = exposure(edges, [s[1] for s in segments], [s[2] for s in segments], values, initial=initial)
    result = exact_history(Disc(0.01, 0.003), ARRHENIUS, history, np.linspace(0, 4e5, 12))
    low, high = min(values + [initial]), max(values + [initial])
    for key in ("mean", "surface"):
        assert np.all(result[key] >= low - 1e-9) and np.all(result[key] <= high + 1e-9)


def test_field_history_is_bounded_and_matches_mean_for_sheet():
    sheet = Sheet(1e-3)
    history = exposure([0, 1e5, 3e5], [True, False], [330.0, 330.0], [2.0, 1.0])
    z = (np.arange(200) + 0.5) / 200 * 1e-3
    t = np.linspace(0, 3e5, 7)
    field = exact_history_field(sheet, ARRHENIUS, history, t, {"z": z})
    mean = exact_history(sheet, ARRHENIUS, history, t)["mean"]
    assert np.allclose(field.mean(axis=1), mean, atol=2e-4)


# ---------------------------------------------------------------- extremes
@pytest.mark.parametrize("geometry", [Sheet(1e-4), Sheet(0.1), Bar(0.1, 0.05, 1e-4), Disc(0.1, 1e-4),
                                      Disc(1e-4, 0.1)])
@pytest.mark.parametrize("d", [1e-16, 1e-8])
def test_extreme_parameters_are_finite_and_bounded(geometry, d):
    years = 20 * 365.25 * 86400
    history = exposure([0, years / 2, years], [True, False], [330.0, 330.0], [2.0, 0.5], initial=0.2)
    diffusivity = Diffusivity((d, d, d), 0.0)
    result = exact_history(geometry, diffusivity, history, np.linspace(0, years, 9))
    for value in result.values():
        assert np.all(np.isfinite(value)) and np.all((value >= 0.2 - 1e-9) & (value <= 2.0 + 1e-9))
    fourier = np.geomspace(1e-3, 1e6, 30)
    for f in (sheet_uptake(fourier), cylinder_uptake(fourier)):
        assert np.all(np.isfinite(f)) and np.all((f >= 0) & (f <= 1))


def test_exact_field_at_a_face_is_the_surface_value():
    history = exposure([0, 1e5], [False], [330.0], [2.0])
    t = np.linspace(0, 1e5, 5)
    field = exact_history_field(Sheet(1e-3), ARRHENIUS, history, t, {"z": np.array([0.0, 5e-4])})
    assert np.allclose(field[1:, 0], 2.0)


def test_bessel_roots_from_one_table_equal_scipys_for_each_count():
    """The J0 roots the cylinder series reads come from one table of ROOT_TABLE roots:
    bit for bit what scipy gives when asked for just that many."""
    from scipy.special import jn_zeros

    from fickcam.diffusion.exact.series import ROOT_TABLE, bessel_roots

    for count in (1, 65, 838, ROOT_TABLE, ROOT_TABLE + 3):
        assert np.array_equal(bessel_roots(count), jn_zeros(0, count))
