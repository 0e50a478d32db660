"""Single-condition fits: Mm and D of one specimen or one condition group by nonlinear
least squares on Crank's full series (scipy.optimize.least_squares), with 95 %
intervals from the covariance s^2 (J^T J)^-1; ASTM D5229's initial-slope estimate
and Shen & Springer's edge correction beside it; D5229's effective-equilibrium check.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats
from scipy.optimize import least_squares

from .data import Specimen, condition_label
from .models import edge_factor, fickian_fraction

CONFIDENCE = 0.95
EQUILIBRIUM_CHANGE = 0.020          # weight %, D5229 effective moisture equilibrium
REFERENCE_PERIOD = 7 * 86400.0      # s, D5229 reference time period (7 d)
PERIOD_TOLERANCE = 0.5 * 86400.0    # s, D5229 allows 7 +/- 0.5 d
SLOPE_LIMIT = 0.5                   # initial-slope points: M below this share of Mm


@dataclass(frozen=True)
class Estimate:
    """A fitted value with its 95 % interval (same units).

    Parameters
    ----------
    value : float
        The estimate [unit of the quantity].
    low, high : float
        The ends of its 95 % interval [unit of the quantity].
    """

    value: float
    low: float
    high: float

    def contains(self, x: float) -> bool:
        return self.low <= x <= self.high


LOG_LIMIT = 700.0   # |ln| of the interval ends: exp stays finite and nonzero (1e-304 .. 1e304)


def log_estimate(centre: float, half: float) -> Estimate:
    """exp of a value estimated as a logarithm, interval symmetric in the log (ends
    clipped to exp(+-700) so that a useless interval still prints as numbers).

    Parameters
    ----------
    centre : float
        The estimate of the logarithm [-].
    half : float
        Half-width of its interval [-].

    Returns
    -------
    Estimate
        exp(centre) and its interval [unit of the quantity].
    """
    def bounded(x):
        return float(np.exp(np.clip(x, -LOG_LIMIT, LOG_LIMIT)))
    return Estimate(bounded(centre), bounded(centre - half), bounded(centre + half))


@dataclass(frozen=True)
class LeastSquares:
    """Solution x, covariance of x, sum of squared residuals, points, dof, residuals.

    Parameters
    ----------
    x : numpy.ndarray
        The parameters found [their units].
    covariance : numpy.ndarray
        Their covariance [products of their units]; NaN when not determined.
    ssr : float
        Sum of squared residuals [unit of the residuals squared].
    points : int
        Residuals that carry information.
    residuals : numpy.ndarray
        The residuals at the solution [unit of the data].
    """

    x: np.ndarray
    covariance: np.ndarray
    ssr: float
    points: int
    residuals: np.ndarray

    @property
    def dof(self) -> int:
        return self.points - self.x.size

    def quantile(self) -> float:
        """Student t quantile of the two-sided 95 % interval (s estimated from the residuals)."""
        return float(stats.t.ppf(0.5 + CONFIDENCE / 2, max(self.dof, 1)))

    def standard_error(self, index: int) -> float:
        return float(np.sqrt(max(self.covariance[index, index], 0.0)))

    def linear(self, index: int) -> Estimate:
        half = self.quantile() * self.standard_error(index)
        return Estimate(float(self.x[index]), float(self.x[index] - half), float(self.x[index] + half))

    def logarithmic(self, index: int) -> Estimate:
        """exp of a parameter fitted as a logarithm (interval symmetric in the log)."""
        return log_estimate(float(self.x[index]), self.quantile() * self.standard_error(index))


def solve_least_squares(residual, x0, x_scale) -> LeastSquares:
    """scipy.optimize.least_squares (trust region reflective) and the covariance
    s^2 (J^T J)^-1, s^2 = SSR/(n - p) (Bates & Watts 1988, eq. 2.14), n the residuals that
    carry information: a residual that is zero and does not depend on the parameters (the
    dry weighing at t = 0, where every model gives M = 0) is not an observation of the
    scatter. With n <= p nothing is left to estimate s from: the covariance is NaN (the
    parameters are not determined, and the report says so), not the zero that an exact fit
    through p points gives (or, by round-off, a negative variance on one machine and a
    tiny positive one on another).

    Parameters
    ----------
    residual : callable
        Parameters -> residuals.
    x0 : array_like
        Starting parameters [their units].
    x_scale : array_like
        Typical size of each parameter [its unit].

    Returns
    -------
    LeastSquares
        The solution and its covariance.

    References
    ----------
    Bates, D. M. & Watts, D. G. (1988). Nonlinear Regression Analysis and Its
    Applications. New York: Wiley.
    """
    result = least_squares(residual, np.asarray(x0, float), x_scale=np.asarray(x_scale, float),
                           method="trf", xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=400)
    r = result.fun
    p = result.x.size
    n = int(np.count_nonzero(np.any(result.jac != 0.0, axis=1) | (r != 0.0)))
    ssr = float(r @ r)
    try:
        covariance = (ssr / (n - p) * np.linalg.inv(result.jac.T @ result.jac) if n > p else
                      np.full((p, p), np.nan))
    except np.linalg.LinAlgError:
        covariance = np.full((p, p), np.inf)
    return LeastSquares(result.x, covariance, ssr, n, r)


@dataclass(frozen=True)
class FickFit:
    """Fickian fit of one specimen or one condition group (several specimens).

    Parameters
    ----------
    label : str
        The specimen's name or the condition's label.
    specimens : tuple of str
        The specimens fitted.
    temperature : float
        Exposure temperature [K].
    relative_humidity : float
        Exposure relative humidity [%].
    diffusivity : Estimate
        Through-thickness diffusivity D, edges exact [m^2/s].
    saturation : Estimate
        Saturation moisture Mm [weight %].
    covariance : numpy.ndarray
        Covariance of (ln D [-], Mm [weight %]).
    residual_sd : float
        Standard deviation of the residuals [weight %].
    points : int
        Weighings fitted.
    ssr : float
        Sum of squared residuals [(weight %)^2].
    initial_slope_diffusivity : float
        ASTM D5229 apparent D, no edge correction [m^2/s].
    edge_corrected_diffusivity : float
        The same after the Shen & Springer edge correction [m^2/s].
    at_equilibrium : bool
        Whether every specimen reached D5229 effective equilibrium.
    fraction_reached : float
        Smallest fitted M/Mm at the last weighing [-].
    """

    label: str
    specimens: tuple[str, ...]
    temperature: float                  # K
    relative_humidity: float            # %
    diffusivity: Estimate               # m^2/s, through the thickness, edges exact
    saturation: Estimate                # weight %
    covariance: np.ndarray              # of (ln D, Mm)
    residual_sd: float                  # weight %
    points: int
    ssr: float
    initial_slope_diffusivity: float    # m^2/s, D5229 apparent value (no edge correction)
    edge_corrected_diffusivity: float   # m^2/s, the same after Shen & Springer
    at_equilibrium: bool                # D5229 effective equilibrium reached (every specimen)
    fraction_reached: float             # fitted M/Mm at the last weighing (smallest)

    @property
    def extrapolated(self) -> bool:
        """Mm comes from the fitted curve, not from a plateau the data reached."""
        return not self.at_equilibrium


def reached_equilibrium(specimen: Specimen) -> bool:
    """D5229 procedure A: the moisture content changes by less than 0.020 % over each
    of two consecutive reference time periods (7 +/- 0.5 d) ending at the last weighing.

    Parameters
    ----------
    specimen : Specimen
        The coupon (weighing times [s], moisture [weight %]).

    Returns
    -------
    bool
        Whether it reached effective moisture equilibrium.

    References
    ----------
    ASTM D5229/D5229M, Standard Test Method for Moisture Absorption Properties and
    Equilibrium Conditioning of Polymer Matrix Composite Materials, procedure A.
    """
    t, m = specimen.time, specimen.moisture
    index = [t.size - 1]
    for _ in range(2):
        earlier = np.flatnonzero(t <= t[index[-1]] - REFERENCE_PERIOD + PERIOD_TOLERANCE)
        if earlier.size == 0:
            return False
        index.append(int(earlier[-1]))
    changes = np.abs(np.diff(m[index]))
    return bool(np.all(changes < EQUILIBRIUM_CHANGE))


def initial_slope_diffusivity(specimen: Specimen, saturation: float) -> float:
    """ASTM D5229 eq. 4: D = pi (h / (4 Mm))^2 ((M2 - M1)/(sqrt t2 - sqrt t1))^2, the
    slope taken by least squares over the weighings below half of Mm (NaN if fewer
    than two). Apparent: it includes the edges' uptake.

    Parameters
    ----------
    specimen : Specimen
        The coupon (thickness h [m], weighing times [s], moisture [weight %]).
    saturation : float
        Its saturation moisture Mm [weight %].

    Returns
    -------
    float
        The apparent diffusivity [m^2/s].

    References
    ----------
    ASTM D5229/D5229M, eq. 4 (see :func:`reached_equilibrium`).
    """
    early = (specimen.moisture <= SLOPE_LIMIT * saturation) & (specimen.time > 0)
    if np.count_nonzero(early) < 2:
        return float("nan")
    slope = stats.linregress(np.sqrt(specimen.time[early]), specimen.moisture[early]).slope
    return float(np.pi * (specimen.thickness / (4.0 * saturation)) ** 2 * slope ** 2)


def _start(specimens, in_plane) -> tuple[float, float]:
    """Starting values: Mm = the highest weighing; D from the initial slope."""
    saturation = max(float(np.max(s.moisture)) for s in specimens)
    guesses = [initial_slope_diffusivity(s, saturation) / edge_factor(s, in_plane) for s in specimens]
    guesses = [g for g in guesses if np.isfinite(g) and g > 0]
    if guesses:
        return float(np.log(np.mean(guesses))), saturation
    thickness = specimens[0].thickness
    return float(np.log(0.05 * thickness ** 2 / max(specimens[0].time.max(), 1.0))), saturation


def fit_fickian(specimens: list[Specimen], in_plane=(1.0, 1.0), label: str | None = None) -> FickFit:
    """Fit M(t) = Mm F(D t) to every weighing of ``specimens`` (same condition), one D
    and one Mm shared; F is the exact sheet or box series (``models.fickian_fraction``).

    Parameters
    ----------
    specimens : list of Specimen
        Coupons of one condition (dimensions [m], times [s], moisture [weight %]).
    in_plane : tuple of float
        In-plane over through-thickness diffusivity along length and width [-].
    label : str, optional
        The fit's label; default the specimen's name or the condition.

    Returns
    -------
    FickFit
        The fit.
    """
    def residual(x):
        diffusivity, saturation = np.exp(x[0]), x[1]
        return np.concatenate([saturation * fickian_fraction(s, diffusivity, in_plane) - s.moisture
                               for s in specimens])

    log_d, saturation = _start(specimens, in_plane)
    fit = solve_least_squares(residual, [log_d, saturation], [1.0, max(saturation, 1e-3)])
    diffusivity, mm = float(np.exp(fit.x[0])), float(fit.x[1])
    slopes = [initial_slope_diffusivity(s, mm) for s in specimens]
    corrected = [d / edge_factor(s, in_plane) for d, s in zip(slopes, specimens)]
    reached = min(float(fickian_fraction(s, diffusivity, in_plane, s.time[-1:])[0]) for s in specimens)
    first = specimens[0]
    return FickFit(
        label=label or (first.name if len(specimens) == 1 else condition_label(first.condition)),
        specimens=tuple(s.name for s in specimens), temperature=first.temperature,
        relative_humidity=first.relative_humidity, diffusivity=fit.logarithmic(0),
        saturation=fit.linear(1), covariance=fit.covariance, residual_sd=float(np.sqrt(fit.ssr / max(fit.dof, 1))),
        points=fit.points, ssr=fit.ssr, initial_slope_diffusivity=_nanmean(slopes),
        edge_corrected_diffusivity=_nanmean(corrected),
        at_equilibrium=all(reached_equilibrium(s) for s in specimens), fraction_reached=reached)


def _nanmean(values) -> float:
    finite = [v for v in values if np.isfinite(v)]
    return float(np.mean(finite)) if finite else float("nan")
