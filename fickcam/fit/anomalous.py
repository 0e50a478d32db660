r"""Anomalous uptake: does Fick describe a condition's data? Two tests must agree:

1. The Fickian residuals are systematic: Wald & Wolfowitz's runs test (1940; too few
   runs of equal sign in time order, e.g. the curve overshooting the knee and then
   lagging a continued slow rise), one-sided, runs of all specimens pooled.
2. The Carter & Kibler (1978) two-phase model (D, Mm, binding rate gamma, release
   rate beta; gamma = 0 is Fick) removes them: extra-sum-of-squares F test of the
   nested models (Bates & Watts 1988, section 3.10),
   :math:`F = \dfrac{(SSR_F - SSR_L)/2}{SSR_L/(n - 4)}`.

Each at 1 %. Neither alone is trusted: gamma = 0 lies on the boundary with beta then
undefined, so the F test alone is liberal (we measured about 5 % false alarms at a
nominal 0.1 %), and the runs test alone does not say what the anomaly is. The
two-phase fit (exact per-mode solution, ``fickcam.diffusion.exact.two_phase``) is only
made when test 1 fires: it costs about a second per condition.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

from .data import Specimen
from .models import fickian_fraction, two_phase_fraction
from .single import Estimate, FickFit, LeastSquares, solve_least_squares

SIGNIFICANCE = 0.01
RELEASE_STARTS = (3.0, 0.5)       # beta t_end at the starts of the multi-start fit
BOUND_SHARES = (0.15, 0.4)        # gamma/(gamma+beta) at the starts


@dataclass(frozen=True)
class LangmuirFit:
    """Two-phase fit of one condition: free-water D (m^2/s), total Mm (%), binding
    rate gamma and release rate beta (1/s), with 95 % intervals; F test against Fick.

    Parameters
    ----------
    diffusivity : Estimate
        Free-water diffusivity D [m^2/s].
    saturation : Estimate
        Total saturation moisture Mm [weight %].
    binding_rate : Estimate
        gamma [1/s].
    release_rate : Estimate
        beta [1/s].
    covariance : numpy.ndarray
        Covariance of (ln D, Mm [weight %], ln gamma, ln beta).
    ssr : float
        Sum of squared residuals [(weight %)^2].
    f_statistic : float
        Extra-sum-of-squares F against the Fickian fit [-].
    p_value : float
        Its p-value [-].

    References
    ----------
    Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture
    diffusion in composite resins. Journal of Composite Materials 12(2), 118-131.
    """

    diffusivity: Estimate
    saturation: Estimate
    binding_rate: Estimate
    release_rate: Estimate
    covariance: np.ndarray          # of (ln D, Mm, ln gamma, ln beta)
    ssr: float
    f_statistic: float
    p_value: float



@dataclass(frozen=True)
class AnomalyTest:
    """Runs test of the Fickian residuals and, when it fires, the two-phase fit.

    Parameters
    ----------
    runs_p_value : float
        p-value of the runs test [-].
    langmuir : LangmuirFit or None
        The two-phase fit, made only when the runs test fires.
    """

    runs_p_value: float
    langmuir: LangmuirFit | None

    @property
    def non_fickian(self) -> bool:
        return (self.runs_p_value < SIGNIFICANCE and self.langmuir is not None
                and self.langmuir.p_value < SIGNIFICANCE)


def runs_test(residual_groups) -> float:
    """One-sided p-value of too few runs of equal sign (Wald & Wolfowitz 1940): per
    group R runs, E = 2 n+ n- / n + 1, Var = 2 n+ n- (2 n+ n- - n) / (n^2 (n - 1));
    groups pooled by summing R, E and Var; normal approximation. Zeros are dropped.

    Parameters
    ----------
    residual_groups : iterable of numpy.ndarray
        Residuals of each specimen in time order [weight %].

    Returns
    -------
    float
        The p-value [-].

    References
    ----------
    Wald, A. & Wolfowitz, J. (1940). On a test whether two samples are from the same
    population. Annals of Mathematical Statistics 11(2), 147-162.
    doi:10.1214/aoms/1177731909
    """
    runs = expected = variance = 0.0
    for residuals in residual_groups:
        signs = np.sign(residuals[residuals != 0])
        n_plus, n_minus = np.count_nonzero(signs > 0), np.count_nonzero(signs < 0)
        n = n_plus + n_minus
        if n_plus == 0 or n_minus == 0:
            runs, expected, variance = runs + 1.0, expected + 1.0, variance
            continue
        runs += 1.0 + np.count_nonzero(np.diff(signs))
        expected += 2.0 * n_plus * n_minus / n + 1.0
        variance += 2.0 * n_plus * n_minus * (2.0 * n_plus * n_minus - n) / (n * n * (n - 1.0))
    if variance <= 0:
        return 1.0
    return float(stats.norm.cdf((runs - expected) / np.sqrt(variance)))


def check_fickian(specimens: list[Specimen], fick: FickFit, in_plane=(1.0, 1.0)) -> AnomalyTest:
    """Runs test on the Fickian fit's residuals; the two-phase fit and F test if it fires.

    Parameters
    ----------
    specimens : list of Specimen
        Coupons of one condition.
    fick : FickFit
        Their Fickian fit.
    in_plane : tuple of float
        In-plane over through-thickness diffusivity along length and width [-].

    Returns
    -------
    AnomalyTest
        The runs test and, when it fires, the two-phase fit.

    References
    ----------
    Wald & Wolfowitz (1940), see :func:`runs_test`; Carter & Kibler (1978), see
    :class:`LangmuirFit`; Bates, D. M. & Watts, D. G. (1988). Nonlinear Regression
    Analysis and Its Applications, sec. 3.10. New York: Wiley.
    """
    residuals = [fick.saturation.value * fickian_fraction(s, fick.diffusivity.value, in_plane) - s.moisture
                 for s in specimens]
    p_runs = runs_test(residuals)
    langmuir = _fit_langmuir(specimens, fick, in_plane) if p_runs < SIGNIFICANCE else None
    return AnomalyTest(p_runs, langmuir)


def _residual(specimens, in_plane):
    def residual(x):
        d, mm, gamma, beta = np.exp(x[0]), x[1], np.exp(x[2]), np.exp(x[3])
        return np.concatenate([mm * two_phase_fraction(s, d, gamma, beta, in_plane) - s.moisture
                               for s in specimens])
    return residual


def _starts(fick: FickFit, specimens):
    """Starts around the Fickian answer: bound water taking part of Mm and released
    over the test's duration."""
    end = max(s.time[-1] for s in specimens)
    for release in RELEASE_STARTS:
        for share in BOUND_SHARES:
            beta = release / end
            gamma = beta * share / (1.0 - share)
            yield [np.log(fick.diffusivity.value), fick.saturation.value * (1.0 + share),
                   np.log(gamma), np.log(beta)]


def _nested_fick_ssr(specimens, fick: FickFit, in_plane) -> float:
    """SSR of the two-phase model's own Fickian limit (gamma = 0). For sealed sheets this
    is the Fickian fit; coupons with exposed edges use the same edge approximation as
    the two-phase model, so that the F test compares nested models."""
    if all(s.width is None for s in specimens):
        return fick.ssr
    two_phase = _residual(specimens, in_plane)
    null = solve_least_squares(lambda x: two_phase([x[0], x[1], -np.inf, 0.0]),
                               [np.log(fick.diffusivity.value), fick.saturation.value],
                               [1.0, max(fick.saturation.value, 1e-3)])
    return null.ssr


def _fit_langmuir(specimens: list[Specimen], fick: FickFit, in_plane=(1.0, 1.0)) -> LangmuirFit:
    """Least-squares two-phase fit (best of a few starts) and the F test against Fick."""
    residual = _residual(specimens, in_plane)
    best: LeastSquares | None = None
    for start in _starts(fick, specimens):
        trial = solve_least_squares(residual, start, [1.0, max(fick.saturation.value, 1e-3), 1.0, 1.0])
        if best is None or trial.ssr < best.ssr:
            best = trial
    dof = best.dof
    extra = max(_nested_fick_ssr(specimens, fick, in_plane) - best.ssr, 0.0)
    f_statistic = (extra / 2.0) / (best.ssr / max(dof, 1)) if best.ssr > 0 else np.inf
    p_value = float(stats.f.sf(f_statistic, 2, max(dof, 1)))
    return LangmuirFit(diffusivity=best.logarithmic(0), saturation=best.linear(1),
                       binding_rate=best.logarithmic(2), release_rate=best.logarithmic(3),
                       covariance=best.covariance, ssr=best.ssr, f_statistic=float(f_statistic),
                       p_value=p_value)
