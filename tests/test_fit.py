"""fickcam fit on SYNTHETIC weight-gain data (exact series, seeded Gaussian scatter of
0.5 % of Mm on each weighing, D5229-like weighing times): recovery, interval coverage,
laws across conditions, non-Fickian detection and the two-phase fit."""
import numpy as np
import pytest
from scipy import stats

from fickcam.diffusion.problem.exposure import GAS_CONSTANT
from fickcam.fit import fit_weight_gain
from fickcam.fit.anomalous import check_fickian, runs_test
from fickcam.fit.models import edge_factor, fickian_fraction
from fickcam.fit.single import fit_fickian, initial_slope_diffusivity, reached_equilibrium
from fickcam.fit.synthetic import d5229_times, synthetic_specimen

H = 2e-3
D_TRUE, MM_TRUE = 3e-12, 2.0
NOISE = 0.005 * MM_TRUE
TIMES = d5229_times(70.0)            # D t_end / h^2 = 4.5: the plateau is weighed too


def coupon(rng, name="c", temperature=333.15, rh=85.0, diffusivity=D_TRUE, saturation=MM_TRUE,
           noise=None, **kw):
    noise = 0.005 * saturation if noise is None else noise
    return synthetic_specimen(name, temperature, rh, H, kw.pop("times", TIMES), saturation,
                              diffusivity, rng, noise, **kw)


def test_single_coupon_recovers_d_within_5_percent_and_mm_within_1_percent():
    rng = np.random.default_rng(12)
    for _ in range(20):
        fit = fit_fickian([coupon(rng)])
        assert fit.diffusivity.value == pytest.approx(D_TRUE, rel=0.05)
        assert fit.saturation.value == pytest.approx(MM_TRUE, rel=0.01)


def test_95_percent_intervals_cover_the_true_values_about_95_percent_of_draws():
    """With right intervals the number of covering draws is Binomial(60, 0.95); the
    acceptance band [q_0.0005, q_0.9995] of that distribution is missed with
    probability < 0.1 % (and the generator is seeded)."""
    draws = 60
    low, high = (int(q) for q in stats.binom.ppf([0.0005, 0.9995], draws, 0.95))
    rng = np.random.default_rng(2026)
    d_hits = mm_hits = 0
    for _ in range(draws):
        fit = fit_fickian([coupon(rng)])
        d_hits += fit.diffusivity.contains(D_TRUE)
        mm_hits += fit.saturation.contains(MM_TRUE)
    assert low <= d_hits <= high
    assert low <= mm_hits <= high


def test_coupon_with_exposed_edges_is_fitted_with_the_exact_box():
    rng = np.random.default_rng(3)
    specimen = coupon(rng, width=20e-3, length=20e-3)
    fit = fit_fickian([specimen])
    assert fit.diffusivity.value == pytest.approx(D_TRUE, rel=0.05)
    # D5229's slope sees the edges; Shen & Springer's factor takes most of them out
    assert fit.initial_slope_diffusivity > 1.1 * D_TRUE
    assert fit.edge_corrected_diffusivity == pytest.approx(D_TRUE, rel=0.12)
    assert edge_factor(specimen) == pytest.approx((1 + 2 * H / 20e-3) ** 2)


def test_initial_slope_estimate_is_exact_on_noiseless_short_time_data():
    """Crank 1975 eq. 4.20: M/Mm = 4 sqrt(D t / (pi h^2)) while M < Mm/2."""
    rng = np.random.default_rng(0)
    specimen = coupon(rng, noise=0.0, times=np.linspace(0, 0.04, 9) * H ** 2 / D_TRUE)
    assert initial_slope_diffusivity(specimen, MM_TRUE) == pytest.approx(D_TRUE, rel=1e-6)


def test_d5229_equilibrium_needs_two_quiet_weekly_periods():
    rng = np.random.default_rng(0)
    assert reached_equilibrium(coupon(rng, noise=0.001))
    early = coupon(rng, noise=0.001, diffusivity=3e-13, times=d5229_times(28.0))  # still rising
    assert not reached_equilibrium(early)
    fit = fit_fickian([early])
    assert fit.extrapolated and fit.fraction_reached < 0.99


def _conditions(rng, temperatures, humidities, d0=1e-5, ea=40e3, a=5.0, b=1.4, specimens=2):
    coupons = []
    for t, rh in zip(temperatures, humidities):
        tk = t + 273.15
        d = d0 * np.exp(-ea / (GAS_CONSTANT * tk))
        for k in range(specimens):
            coupons.append(coupon(rng, f"{t}-{rh}-{k}", tk, rh, d, a * (rh / 100) ** b,
                                  times=d5229_times(84.0)))
    return coupons


def test_three_temperatures_recover_ea_and_three_humidities_recover_a_and_b_within_5_percent():
    rng = np.random.default_rng(7)
    coupons = _conditions(rng, [40, 60, 80, 80, 80], [85, 85, 85, 50, 70])
    report = fit_weight_gain(coupons, "3502")
    assert report.arrhenius.second.value == pytest.approx(40e3, rel=0.05)
    assert report.arrhenius.second.contains(40e3)
    assert report.saturation.first.value == pytest.approx(5.0, rel=0.05)
    assert report.saturation.second.value == pytest.approx(1.4, rel=0.05)
    assert report.arrhenius.second_from == report.saturation.second_from == "data"
    assert report.non_fickian == []
    # ln D0 and Ea are strongly correlated: the record keeps their covariance
    c = report.arrhenius.covariance
    assert c[0, 1] / np.sqrt(c[0, 0] * c[1, 1]) > 0.95


def test_one_temperature_takes_the_activation_energy_from_the_library_and_says_so():
    from fickcam.materials.library import entry

    rng = np.random.default_rng(8)
    report = fit_weight_gain(_conditions(rng, [60], [85]), "3502")
    library = entry("matrices", "3502")
    assert report.arrhenius.second_from == "library"
    assert report.arrhenius.second.value == library["diffusivity"]["activation_energy"]
    assert report.saturation.second_from == "library"
    assert any("activation energy" in note and "library" in note for note in report.notes)
    d60 = report.arrhenius.first.value * np.exp(-report.arrhenius.second.value / (GAS_CONSTANT * 333.15))
    assert d60 == pytest.approx(report.conditions[0].diffusivity.value, rel=1e-9)


def test_two_phase_data_are_flagged_and_the_langmuir_fit_recovers_d_gamma_beta_within_10_percent():
    rng = np.random.default_rng(13)
    d, gamma, beta = 5e-12, 3e-7, 1e-6      # gamma, beta < pi^2 D / h^2 = 1.2e-5 1/s
    specimens = [coupon(rng, f"s{k}", diffusivity=d, gamma=gamma, beta=beta, times=d5229_times(140.0))
                 for k in range(3)]
    test = check_fickian(specimens, fit_fickian(specimens))
    assert test.non_fickian
    fit = test.langmuir
    assert fit.diffusivity.value == pytest.approx(d, rel=0.10)
    assert fit.binding_rate.value == pytest.approx(gamma, rel=0.10)
    assert fit.release_rate.value == pytest.approx(beta, rel=0.10)
    assert fit.saturation.value == pytest.approx(MM_TRUE, rel=0.02)


def test_fickian_data_are_not_flagged():
    rng = np.random.default_rng(21)
    for _ in range(20):
        specimens = [coupon(rng, "a"), coupon(rng, "b")]
        assert not check_fickian(specimens, fit_fickian(specimens)).non_fickian


def test_runs_test_counts_runs_like_wald_and_wolfowitz():
    alternating = np.tile([1.0, -1.0], 10)
    blocked = np.repeat([1.0, -1.0], 10)
    assert runs_test([alternating]) > 0.99
    assert runs_test([blocked]) < 1e-4
    assert runs_test([np.zeros(5)]) == 1.0


def test_fickian_fraction_of_a_sealed_sheet_is_cranks_series():
    from fickcam.diffusion.exact.separable import sheet_uptake

    rng = np.random.default_rng(0)
    specimen = coupon(rng)
    assert np.allclose(fickian_fraction(specimen, D_TRUE), sheet_uptake(D_TRUE * TIMES / H ** 2))
