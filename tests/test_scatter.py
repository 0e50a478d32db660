"""Scatter of a sweep against its limits: fraction out of spec with a Wilson 95 % interval."""
import math

import numpy as np
import pytest
import xarray as xr

from fickcam.cli.reporting import sweep_limit_lines
from fickcam.sweep.scatter import fractions, out_of_spec_counts, wilson_interval

Z = 1.959963984540054  # standard normal 97.5 % quantile


@pytest.mark.parametrize("k, n", [(0, 10), (3, 100), (50, 100), (99, 100), (7, 7)])
def test_wilson_interval_matches_its_closed_form(k, n):
    """(p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n) (Wilson 1927)."""
    p = k / n
    centre = (p + Z ** 2 / (2 * n)) / (1 + Z ** 2 / n)
    half = Z * math.sqrt(p * (1 - p) / n + Z ** 2 / (4 * n * n)) / (1 + Z ** 2 / n)
    low, high = wilson_interval(k, n)
    assert low == pytest.approx(max(centre - half, 0.0), abs=1e-12)
    assert high == pytest.approx(min(centre + half, 1.0), abs=1e-12)


@pytest.mark.parametrize("confidence", [0.9, 0.95, 0.99])
def test_wilson_interval_is_scipys_binomial_interval(confidence):
    """The interval scipy.stats.binomtest gives (method "wilson"), to round-off."""
    from scipy.stats import binomtest

    for n in (1, 2, 7, 100, 1000, 12345):
        for k in sorted({0, 1, n // 3, n // 2, n - 1, n}):
            ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
            assert wilson_interval(k, n, confidence) == pytest.approx((ci.low, ci.high),
                                                                      rel=1e-14, abs=1e-15)


def test_wilson_interval_covers_the_true_fraction_95_percent_of_the_time():
    """3 % of parts out of spec, samples of 200: the interval holds the truth in
    about 95 % of 4000 repeated sweeps (binomial spread of the coverage: ±0.7 %)."""
    rng = np.random.default_rng(3)
    draws = rng.binomial(200, 0.03, size=4000)
    table = {k: wilson_interval(k, 200) for k in np.unique(draws)}
    covered = np.mean([table[k][0] <= 0.03 <= table[k][1] for k in draws])
    assert 0.925 <= covered <= 0.975


def test_a_case_counts_from_its_first_time_out_of_spec_and_failed_cases_are_left_out():
    failed_at = np.array([[5.0, np.nan], [20.0, 0.0], [np.nan, np.nan], [1.0, 1.0]])  # (case, limit)
    ran = np.array([True, True, True, False])
    k, n = out_of_spec_counts(failed_at, np.array([0.0, 5.0, 30.0]), ran)
    assert n == 3
    np.testing.assert_array_equal(k, [[0, 1], [1, 1], [2, 1]])


def test_combined_sweep_gets_fractions_and_a_summary():
    days = np.array([0, 30, 60])
    ds = xr.Dataset(
        {"time_out_of_spec": (("case", "limit"), [[10.0, np.nan], [45.0, 0.0], [np.nan, np.nan],
                                                  [50.0, np.nan]])},
        coords={"time": np.asarray(days, float),
                "limit": ["rocker_angle", "transmission_angle"],
                "case_status": ("case", np.array(["ok"] * 4, dtype=object))})
    out = fractions(ds)
    np.testing.assert_allclose(out["fraction_out_of_spec"].sel(limit="rocker_angle"), [0, 25, 75])
    low, high = wilson_interval(3, 4)
    assert float(out["fraction_out_of_spec_low"].isel(time=2, limit=0)) == pytest.approx(100 * low)
    assert float(out["fraction_out_of_spec_high"].isel(time=2, limit=0)) == pytest.approx(100 * high)
    assert out["fraction_out_of_spec"].attrs["units"] == "%"
    ds = ds.merge(out)
    ds["time_out_of_spec_error"] = xr.full_like(ds["time_out_of_spec"], 0.0021)  # 3 min [d]
    ds.attrs["time_unit"] = "h"
    lines = sweep_limit_lines(ds)
    assert lines[0] == "out of spec (of 4 case(s) that ran; Wilson 95 % interval):"
    high = f"{100 * wilson_interval(3, 4)[1]:.3g}"
    assert lines[1] == (f"  rocker_angle: 3 of 4 by 1440 h (75 % [{100 * low:.3g}, {high}]); "
                        f"first at 240.0 h (case 0), last at 1200.0 h (case 3)")
    assert lines[2].startswith("  transmission_angle: 1 of 4 by 1440 h (25 % [") and \
        lines[2].endswith("]); first at 0.0 h (case 1)")
    assert lines[3].endswith("fickcam query RESULT fraction_out_of_spec)")
    assert all(len(line) < 120 for line in lines)
