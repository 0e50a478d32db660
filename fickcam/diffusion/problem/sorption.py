r"""Sorption laws beyond Fick: the two-phase (Langmuir-type) model and a diffusivity
that depends on the moisture already absorbed. Plain data and small functions of
numpy arrays; no solver here (``two_phase_modes`` / ``two_phase_mesh`` /
``concentration_dependent`` solve).

- Two-phase: Carter & Kibler (1978), J. Compos. Mater. 12:118-131, eqs. 1-2: free water
  n diffuses, is bound at rate :math:`\gamma` and released at rate :math:`\beta`,
  :math:`\partial n/\partial t = \nabla \cdot (D \nabla n) - \gamma n + \beta N`,
  :math:`\partial N/\partial t = \gamma n - \beta N`. The saturation law gives the TOTAL
  equilibrium content :math:`M_m = n_\infty + N_\infty`; the surface holds the free share
  :math:`\beta/(\gamma + \beta)` of it (:math:`\gamma n_\infty = \beta N_\infty`). Each rate
  may follow Arrhenius, :math:`r(T) = r_0 \exp(-E_a/(R T))`.
- Concentration-dependent: :math:`D(c, T) = D(T)\, f(c/M_{m,ref})`,
  :math:`f = \exp(k\, c/M_{m,ref})` (Crank 1975 §9.3, the exponential diffusion
  coefficient) or a table of f against :math:`c/M_{m,ref}`, :math:`M_{m,ref}` the
  material's saturation at 100 % RH (a material constant, so that D depends
  on the local moisture only, never on the climate).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture diffusion
  in composite resins. Journal of Composite Materials 12(2):118-131.
  doi:10.1177/002199837801200201
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .exposure import GAS_CONSTANT

TABLE_WIDTH = 1e-7  # c/Mm intervals narrower than this take the table's f at their middle


@dataclass(frozen=True)
class Rate:
    """An Arrhenius rate, rate(T) = pre_exponential exp(-activation_energy / (R T)).

    Parameters
    ----------
    pre_exponential : float
        The rate at infinite temperature [1/s].
    activation_energy : float
        Its activation energy [J/mol]; 0 makes the rate constant.
    """

    pre_exponential: float
    activation_energy: float = 0.0

    def __call__(self, temperature) -> np.ndarray:
        t = np.asarray(temperature, float)
        return self.pre_exponential * np.exp(-self.activation_energy / (GAS_CONSTANT * t))


@dataclass(frozen=True)
class Langmuir:
    """Carter & Kibler's two-phase (Langmuir-type) sorption law.

    Parameters
    ----------
    binding : Rate
        gamma(T), the rate [1/s] at which free water is bound.
    release : Rate
        beta(T), the rate [1/s] at which bound water is released.

    References
    ----------
    Carter & Kibler (1978), cited in the module docstring.
    """

    binding: Rate
    release: Rate

    def rates(self, temperature) -> tuple[np.ndarray, np.ndarray]:
        """(gamma, beta) at T (K), 1/s."""
        return self.binding(temperature), self.release(temperature)

    def free_share(self, temperature) -> np.ndarray:
        """beta/(gamma + beta): the free share of the total at equilibrium (1 if gamma = 0)."""
        gamma, beta = self.rates(temperature)
        total = gamma + beta
        return np.where(gamma > 0, beta / np.where(total > 0, total, 1.0), 1.0)


@dataclass(frozen=True)
class ConcentrationDependent:
    """A diffusivity that depends on the local moisture: D(c, T) = D(T) f(c/Mm_ref).

    f is exp(k c/Mm_ref) when ``exponent`` k is given (Crank 1975 §9.3), else the table
    ``factors`` against ``ratios``, interpolated linearly and held beyond its ends.

    Parameters
    ----------
    reference_moisture : float
        Mm_ref, the material's saturation at 100 % RH [weight %].
    exponent : float or None
        k of the exponential law [-]; None for the table.
    ratios : tuple of float
        The table's c/Mm_ref [-], increasing.
    factors : tuple of float
        The table's D/D(T) [-] at those ratios.

    References
    ----------
    Crank (1975), cited in the module docstring.
    """

    reference_moisture: float            # Mm_ref, weight %
    exponent: float | None = None
    ratios: tuple[float, ...] = ()
    factors: tuple[float, ...] = ()

    def factor(self, moisture) -> np.ndarray:
        """D/D(T) at the local moisture (weight %)."""
        ratio = np.asarray(moisture, float) / self.reference_moisture
        if self.exponent is not None:
            return np.exp(self.exponent * ratio)
        return np.interp(ratio, self.ratios, self.factors)

    def mean_factor(self, low, high) -> np.ndarray:
        """The mean of D/D(T) over the moisture between ``low`` and ``high`` (weight %):
        (Phi(high) - Phi(low)) / (high - low), Phi = integral of f (the Kirchhoff
        potential): the two-point flux T (Phi(c_j) - Phi(c_i)) = T mean (c_j - c_i) of
        the finite-volume scheme for u_t = laplacian Phi(u) (Eymard, Gallouet & Herbin
        2000, Handbook of Numerical Analysis VII, ch. 4). The exponential:
        f((low + high)/2) sinh(x)/x, x = k (high - low)/(2 Mm_ref)."""
        low, high = (np.asarray(v, float) / self.reference_moisture
                     for v in np.broadcast_arrays(low, high))
        middle = self.factor(0.5 * (low + high) * self.reference_moisture)
        if self.exponent is not None:
            return middle * _sinh_ratio(0.5 * self.exponent * (high - low))
        width = high - low
        wide = np.abs(width) > TABLE_WIDTH
        out = np.array(middle, float)
        out[wide] = (self._potential(high[wide]) - self._potential(low[wide])) / width[wide]
        return out

    def _potential(self, ratio: np.ndarray) -> np.ndarray:
        """Integral of the table's piecewise-linear f (held beyond its ends) from its first
        ratio to ``ratio`` (trapezoids between the knots are exact)."""
        x, y = np.asarray(self.ratios, float), np.asarray(self.factors, float)
        at_knots = np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(x))])
        inside = np.clip(ratio, x[0], x[-1])
        k = np.clip(np.searchsorted(x, inside, side="right") - 1, 0, x.size - 2)
        within = at_knots[k] + 0.5 * (y[k] + np.interp(inside, x, y)) * (inside - x[k])
        return within + y[0] * np.minimum(ratio - x[0], 0.0) + y[-1] * np.maximum(ratio - x[-1], 0.0)

    def largest_factor(self, moisture) -> float:
        """The largest D/D(T) met for moisture in [0, ``moisture``] (the stiffest operator)."""
        return float(np.max(self.factor(np.linspace(0.0, float(moisture), 65))))


def _sinh_ratio(x: np.ndarray) -> np.ndarray:
    """sinh(x)/x, 1 + x^2/6 near 0 (its Taylor series, error below x^4/120)."""
    small = np.abs(x) < 1e-4
    return np.where(small, 1.0 + x * x / 6.0, np.sinh(x) / np.where(small, 1.0, x))


def is_langmuir(sorption) -> bool:
    """Tell whether a sorption law is the two-phase (Langmuir-type) one.

    Parameters
    ----------
    sorption : Langmuir, ConcentrationDependent or None
        The material's sorption law (None: Fickian).

    Returns
    -------
    bool
        True for a ``Langmuir`` law.
    """
    return isinstance(sorption, Langmuir)


def is_nonlinear(sorption) -> bool:
    """Tell whether a sorption law makes the diffusion equation nonlinear.

    Parameters
    ----------
    sorption : Langmuir, ConcentrationDependent or None
        A law of the material, or None for plain Fick.

    Returns
    -------
    bool
        Whether D depends on the moisture (a ``ConcentrationDependent`` law).
    """
    return isinstance(sorption, ConcentrationDependent)


def describe(sorption) -> str:
    """Describe a sorption law in one line, as ``fickcam check`` prints it.

    Parameters
    ----------
    sorption : Langmuir, ConcentrationDependent or None
        The law to describe (None: Fickian diffusion).

    Returns
    -------
    str
        The law and its constants (rates in 1/s).
    """
    if isinstance(sorption, Langmuir):
        return (f"two-phase (Langmuir) sorption, gamma0 {sorption.binding.pre_exponential:.3g} 1/s, "
                f"beta0 {sorption.release.pre_exponential:.3g} 1/s")
    if isinstance(sorption, ConcentrationDependent):
        law = (f"exp({sorption.exponent:g} c/Mm)" if sorption.exponent is not None
               else f"table of {len(sorption.ratios)} points")
        return f"concentration-dependent D = D(T) {law}"
    return "Fickian"
