"""Scatter of a sweep against its limits: the fraction of cases out of spec.

For each ageing time t and limit, a case is out of spec by t when its
``time_out_of_spec`` is at or before t (a part that left its spec once is
rejected, even if its ratio later falls back). Of the n cases that ran, k are
out of spec; the fraction k/n has a Wilson score 95 % interval (Wilson 1927, in
Newcombe's 1998 form, the one ``scipy.stats.binomtest(k, n).proportion_ci(method="wilson")``
gives: written out here on ``scipy.special.ndtri`` because importing ``scipy.stats`` costs
a sweep's client more than a second), which keeps its coverage near 0 and 1, where the
normal approximation fails (Brown, Cai & DasGupta 2001). Failed cases are left out of n.
"""
from __future__ import annotations

import numpy as np

from ..schema import VARIABLES
from scipy.special import ndtri
import xarray as xr

CONFIDENCE = 0.95


def wilson_interval(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """(low, high) of the binomial proportion k/n, Wilson score interval; NaN for n = 0.

    Parameters
    ----------
    k : int
        Successes (cases out of spec) [1].
    n : int
        Trials (cases that ran) [1].
    confidence : float
        The confidence level [-], 0.95 by default.

    Returns
    -------
    low, high : float
        The interval's ends, as fractions [-] (NaN, NaN when n = 0).

    References
    ----------
    E. B. Wilson, "Probable inference, the law of succession, and statistical
    inference", Journal of the American Statistical Association 22 (158), 209-212, 1927,
    doi:10.1080/01621459.1927.10502953.

    R. G. Newcombe, "Two-sided confidence intervals for the single proportion: comparison
    of seven methods", Statistics in Medicine 17 (8), 857-872, 1998,
    doi:10.1002/(SICI)1097-0258(19980430)17:8<857::AID-SIM777>3.0.CO;2-E.

    L. D. Brown, T. T. Cai and A. DasGupta, "Interval estimation for a binomial
    proportion", Statistical Science 16 (2), 101-133, 2001, doi:10.1214/ss/1009213286.
    """

    if n == 0:
        return np.nan, np.nan
    p, z = k / n, float(ndtri(0.5 + 0.5 * confidence))
    centre = (2 * n * p + z ** 2) / (2 * (n + z ** 2))
    half = z / (2 * (n + z ** 2)) * np.sqrt(4 * n * p * (1 - p) + z ** 2)
    return (0.0 if k == 0 else float(centre - half)), (1.0 if k == n else float(centre + half))


def out_of_spec_counts(time_out_of_spec_days: np.ndarray, ages_days: np.ndarray,
                       ran: np.ndarray) -> tuple[np.ndarray, int]:
    """(k over (time, limit), n): cases of ``ran`` out of spec by each age.

    A case is out of spec by age t when its ``time_out_of_spec`` is at or before t (NaN,
    never out of spec, counts as in spec).

    Parameters
    ----------
    time_out_of_spec_days : numpy.ndarray
        (case, limit): when each case first leaves each limit [d], NaN for never.
    ages_days : numpy.ndarray
        The ages counted at [d].
    ran : numpy.ndarray of bool
        (case,): the cases that ran (failed cases are left out of n).

    Returns
    -------
    k : numpy.ndarray of int
        (age, limit): cases out of spec by each age [1].
    n : int
        Cases that ran [1].
    """
    failed_at = np.asarray(time_out_of_spec_days, float)[np.asarray(ran, bool)]  # (case, limit)
    by_age = failed_at[None, :, :] <= np.asarray(ages_days, float)[:, None, None] * (1 + 1e-12)
    return by_age.sum(axis=1), int(failed_at.shape[0])


def fractions(ds):
    """The fraction of cases out of spec with its Wilson 95 % bounds, and the counts.

    Parameters
    ----------
    ds : xarray.Dataset
        A combined sweep result with limits (``time_out_of_spec`` over case and limit).

    Returns
    -------
    xarray.Dataset
        ``fraction_out_of_spec``, ``fraction_out_of_spec_low`` and ``_high`` [%] and
        ``cases_out_of_spec`` [1] over (time, limit); the last carries ``cases`` = n. The
        bounds are :func:`wilson_interval`'s (see its references).
    """

    ages = np.asarray(ds["time"].values, float)
    ran = (np.asarray(ds["case_status"].values) == "ok") if "case_status" in ds.coords else \
        np.ones(ds.sizes["case"], bool)
    failed = ds["time_out_of_spec"].transpose("case", "limit").values
    k, n = out_of_spec_counts(failed, ages, ran)
    bounds = np.array([[wilson_interval(kk, n) for kk in row] for row in k])  # (time, limit, 2)
    values = {"fraction_out_of_spec": k / n if n else np.full(k.shape, np.nan),
              "fraction_out_of_spec_low": bounds[..., 0], "fraction_out_of_spec_high": bounds[..., 1],
              "cases_out_of_spec": k}
    data = {}
    for name, value in values.items():
        var = VARIABLES[name]
        data[name] = xr.Variable(var.dims, np.asarray(value) * var.scale,
                                 {"units": var.units, "long_name": var.long_name,
                                  **({"cases": n} if name == "cases_out_of_spec" else {})})
    return xr.Dataset(data, coords={"time": ds["time"], "limit": ds["limit"]})
