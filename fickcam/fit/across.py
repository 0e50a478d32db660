"""Across conditions: Arrhenius D(T) = D0 exp(-Ea/(R T)) (Shen & Springer 1976 eq. 9)
from the conditions' D, and the saturation law Mm = a (RH/100)^b (Shen & Springer 1976
eq. 10) from their Mm. Weighted least squares
(scipy.optimize.curve_fit) with the single-condition standard errors as sigma; when
the points scatter more than those errors allow (chi^2/dof > 1) the covariance is
scaled by chi^2/dof (Birge ratio) and the t quantile is used.
With one temperature (humidity) only, Ea (b) is taken from the library and said so.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats
from scipy.optimize import curve_fit

from ..diffusion.problem.exposure import GAS_CONSTANT
from .single import CONFIDENCE, Estimate, FickFit, log_estimate

Z95 = float(stats.norm.ppf(0.5 + CONFIDENCE / 2))
SIGMA_FLOOR = 1e-9   # a condition fitted without residual (noiseless data) still gets a weight


@dataclass(frozen=True)
class LawFit:
    """Two parameters of a law across conditions, their covariance and where they
    came from (``first_from``/``second_from``: 'data' or 'library').

    Parameters
    ----------
    first : Estimate
        D0 [m^2/s] or a [weight %].
    second : Estimate
        Ea [J/mol] or b [-].
    covariance : numpy.ndarray
        Covariance of (ln D0 [-], Ea [J/mol]) or of (a [weight %], b [-]).
    first_from, second_from : str
        ``"data"`` or ``"library"``.
    points : int
        Conditions fitted.
    """

    first: Estimate
    second: Estimate
    covariance: np.ndarray      # (ln D0 [-], Ea [J/mol]) or (a [%], b [-]), SI
    first_from: str
    second_from: str
    points: int


def _weighted_fit(model, x, y, sigma, start):
    """curve_fit with absolute sigma, Birge-scaled when the scatter exceeds sigma."""
    sigma = np.where(np.isfinite(sigma), np.maximum(sigma, SIGMA_FLOOR), 1e300)
    params, covariance = curve_fit(model, x, y, p0=start, sigma=sigma, absolute_sigma=True,
                                   maxfev=10000)
    dof = x.size - len(params)
    quantile = Z95
    if dof > 0:
        chi2 = float(np.sum(((y - model(x, *params)) / sigma) ** 2))
        if chi2 / dof > 1.0:
            covariance = covariance * chi2 / dof
            quantile = float(stats.t.ppf(0.5 + CONFIDENCE / 2, dof))
    return params, covariance, quantile


def _interval(value, se, quantile) -> Estimate:
    return Estimate(float(value), float(value - quantile * se), float(value + quantile * se))


def _log_interval(log_value, se, quantile) -> Estimate:
    return log_estimate(float(log_value), float(quantile * se))


def _weighted_mean(values, sigma) -> tuple[float, float]:
    """(inverse-variance weighted mean, its variance 1 / sum 1/sigma^2); where no value has
    a known sigma (no condition determined: NaN), the plain mean and a NaN variance."""
    weights = 1.0 / np.asarray(sigma, float) ** 2
    if not np.any(weights > 0.0):
        return float(np.mean(values)), float("nan")
    return float(np.sum(weights * values) / np.sum(weights)), 1.0 / float(np.sum(weights))


def _log_d_se(fit: FickFit) -> float:
    return float(np.sqrt(fit.covariance[0, 0]))


def arrhenius(conditions: list[FickFit], library_activation_energy: float) -> LawFit:
    """ln D = ln D0 - Ea/(R T) through the conditions' D; one temperature: Ea from the
    library, D0 = D exp(Ea/(R T)) (its interval from D's alone).

    Parameters
    ----------
    conditions : list of FickFit
        The conditions' fits (temperature [K], D [m^2/s]).
    library_activation_energy : float
        Ea to use with one temperature [J/mol].

    Returns
    -------
    LawFit
        D0 [m^2/s] and Ea [J/mol].

    References
    ----------
    Shen, C.-H. & Springer, G. S. (1976). Moisture absorption and desorption of composite
    materials. Journal of Composite Materials 10(1), 2-20, eq. 9.
    """
    inverse_t = np.array([1.0 / c.temperature for c in conditions])
    log_d = np.log([c.diffusivity.value for c in conditions])
    sigma = np.maximum([_log_d_se(c) for c in conditions], SIGMA_FLOOR)
    if np.unique(np.round(inverse_t, 9)).size < 2:
        ea = library_activation_energy
        log_d0, variance = _weighted_mean(log_d + ea * inverse_t / GAS_CONSTANT, sigma)
        covariance = np.array([[variance, 0.0], [0.0, 0.0]])
        return LawFit(_log_interval(log_d0, np.sqrt(variance), Z95), Estimate(ea, ea, ea),
                      covariance, "data", "library", len(conditions))

    def model(x, log_d0, ea_kj):
        return log_d0 - ea_kj * 1e3 * x / GAS_CONSTANT

    slope = np.polyfit(inverse_t, log_d, 1)
    start = (slope[1], -slope[0] * GAS_CONSTANT / 1e3)
    params, cov_kj, q = _weighted_fit(model, inverse_t, log_d, sigma, start)
    scale = np.diag([1.0, 1e3])
    covariance = scale @ cov_kj @ scale            # to (ln D0, Ea in J/mol)
    return LawFit(_log_interval(params[0], np.sqrt(covariance[0, 0]), q),
                  _interval(params[1] * 1e3, np.sqrt(covariance[1, 1]), q),
                  covariance, "data", "data", len(conditions))


def saturation_law(conditions: list[FickFit], library_exponent: float) -> LawFit:
    """Mm = a (RH/100)^b through the conditions' Mm (temperature-independent, as in the
    library); one humidity: b from the library, a = Mm / (RH/100)^b.

    Parameters
    ----------
    conditions : list of FickFit
        The conditions' fits (relative humidity [%], Mm [weight %]).
    library_exponent : float
        b to use with one humidity [-].

    Returns
    -------
    LawFit
        a [weight %] and b [-].

    References
    ----------
    Shen & Springer (1976), eq. 10 (see :func:`arrhenius`).
    """
    rh = np.array([c.relative_humidity / 100.0 for c in conditions])
    mm = np.array([c.saturation.value for c in conditions])
    sigma = np.maximum([np.sqrt(c.covariance[1, 1]) for c in conditions], SIGMA_FLOOR)
    if np.unique(np.round(rh, 6)).size < 2:
        b = library_exponent
        scale = rh ** -b
        a, variance = _weighted_mean(mm * scale, sigma * scale)
        return LawFit(_interval(a, np.sqrt(variance), Z95), Estimate(b, b, b),
                      np.array([[variance, 0.0], [0.0, 0.0]]), "data", "library", len(conditions))

    def model(x, a, b):
        return a * x ** b

    params, covariance, q = _weighted_fit(model, rh, mm, sigma, (float(mm.max()), 1.0))
    return LawFit(_interval(params[0], np.sqrt(covariance[0, 0]), q),
                  _interval(params[1], np.sqrt(covariance[1, 1]), q),
                  covariance, "data", "data", len(conditions))
