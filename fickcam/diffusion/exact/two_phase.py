r"""Exact solution of the two-phase (Langmuir-type) moisture model in a sheet.

Carter & Kibler (1978), J. Compos. Mater. 12:118-131, eqs. 1-2: free water :math:`n`
diffuses with :math:`D` and is bound at rate :math:`\gamma`; bound water :math:`N` is
released at rate :math:`\beta`:

.. math::

    \frac{\partial n}{\partial t} = D \frac{\partial^2 n}{\partial z^2} - \gamma n + \beta N,
    \qquad \frac{\partial N}{\partial t} = \gamma n - \beta N.

At equilibrium gamma n_inf = beta N_inf, so of the total equilibrium content
Mm = n_inf + N_inf the free share is beta/(gamma+beta) and the bound share
gamma/(gamma+beta); the surfaces hold n = n_inf from t = 0, the sheet starts dry.

Per Fourier mode sin(k pi z/h) (k odd, decay rate D lambda_k, lambda_k =
(k pi/h)^2) the deficits (n_inf - n, N_inf - N) obey a 2x2 linear system
x' = A_k x, A_k = [[-(D lambda_k + gamma), beta], [gamma, -beta]], solved exactly
with the matrix exponential of a 2x2 matrix (Cayley-Hamilton / Sylvester):
exp(A t) = exp(m t) [cosh(s t) I + sinh(s t)/s (A - m I)], m = tr A / 2,
s^2 = ((a11 - a22)/2)^2 + a12 a21 >= 0. The initial deficit expands as
1 = sum 4/(k pi) sin(k pi z/h), whose mode means are 2/(k pi).

For high modes the bound deficit tends to the local relaxation
(gamma/(gamma+beta)) exp(-beta t) instead of decaying; that limit is summed in
closed form (sum 8/(k pi)^2 = 1) and only the O(1/(D lambda_k)) remainder is
summed over modes, so the truncation error falls as 1/N^3 (N modes).

numpy only; imports nothing else from fickcam.

References
----------
- Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture diffusion
  in composite resins. Journal of Composite Materials 12(2):118-131.
  doi:10.1177/002199837801200201
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SERIES_TOLERANCE = 1e-12  # target truncation error of the uptake fractions
MAX_MODES = 200_000
EXP_CUTOFF = 44.0         # a free-water mode with exp(-D lambda t) < exp(-44) is negligible


@dataclass(frozen=True)
class TwoPhaseUptake:
    """Fractions of the total equilibrium content Mm at the requested times:
    ``total`` = ``free`` + ``bound``; at equilibrium free -> beta/(gamma+beta).

    Parameters
    ----------
    total : numpy.ndarray
        The total uptake M/Mm [-].
    free : numpy.ndarray
        The free (mobile) water n/Mm [-].
    bound : numpy.ndarray
        The bound water N/Mm [-].
    """

    total: np.ndarray
    free: np.ndarray
    bound: np.ndarray


def equilibrium_shares(gamma: float, beta: float) -> tuple[float, float]:
    """(free, bound) shares of Mm at equilibrium: beta/(gamma+beta), gamma/(gamma+beta)
    (Carter & Kibler 1978, gamma n_inf = beta N_inf). gamma = 0 is Fickian: (1, 0).

    Parameters
    ----------
    gamma : float
        The binding rate [1/s].
    beta : float
        The release rate [1/s].

    Returns
    -------
    tuple of float
        The free and the bound share of the equilibrium content Mm [-].

    Raises
    ------
    ValueError
        When a rate is negative, or gamma > 0 with beta = 0.

    References
    ----------
    Carter & Kibler (1978), see the module docstring.
    """
    if gamma < 0 or beta < 0:
        raise ValueError("binding and release rates must not be negative")
    if gamma == 0.0:
        return 1.0, 0.0
    if beta == 0.0:
        raise ValueError("a binding rate needs a positive release rate (else nothing saturates)")
    return beta / (gamma + beta), gamma / (gamma + beta)


@dataclass(frozen=True)
class Propagator:
    """exp(A t) = c I + d (A - m I) and its integral int_0^t exp(A u) du = C I + D (A - m I)
    for A = [[-(rate + gamma), beta], [gamma, -beta]] (Cayley-Hamilton / Sylvester for
    2x2 matrices; eigenvalues m +- s <= 0): c = exp(mt) cosh(st), d = exp(mt) sinh(st)/s,
    C and D the same integrated. Arrays broadcast over modes and times.

    Parameters
    ----------
    a11, a12, a21, a22 : numpy.ndarray
        The entries of A [1/s].
    m : numpy.ndarray
        tr A / 2 [1/s].
    c, d : numpy.ndarray
        The coefficients of exp(A t): c [-] and d [s].
    c_int, d_int : numpy.ndarray
        The same of its time integral: C [s] and D [s^2].
    """

    a11: np.ndarray
    a12: np.ndarray
    a21: np.ndarray
    a22: np.ndarray
    m: np.ndarray
    c: np.ndarray
    d: np.ndarray
    c_int: np.ndarray
    d_int: np.ndarray

    def apply(self, x1, x2, integral: bool = False):
        """exp(A t) x (or its integral times x), component-wise."""
        c, d = (self.c_int, self.d_int) if integral else (self.c, self.d)
        return (c * x1 + d * ((self.a11 - self.m) * x1 + self.a12 * x2),
                c * x2 + d * (self.a21 * x1 + (self.a22 - self.m) * x2))


def _phi(rate, t):
    """int_0^t exp(rate u) du for rate <= 0 (t where rate = 0)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(rate < 0, np.expm1(rate * t) / np.where(rate < 0, rate, -1.0), t)


def exchange_propagator(rate, t, gamma, beta) -> Propagator:
    """The per-mode 2x2 propagator of free and bound water (module docstring): mode decay
    ``rate`` = D lambda (1/s), exchange rates ``gamma``, ``beta`` (1/s), time ``t`` (s);
    all broadcast. The s -> 0 limits are taken in closed form.

    Parameters
    ----------
    rate : array_like
        The mode's diffusive decay rate D lambda_k [1/s].
    t : array_like
        The times [s].
    gamma, beta : array_like
        The binding and release rates [1/s].

    Returns
    -------
    Propagator
        exp(A t) and its integral over [0, t], broadcast over the inputs.

    References
    ----------
    Carter & Kibler (1978), see the module docstring.
    """
    rate, t, gamma, beta = np.broadcast_arrays(*(np.asarray(v, float) for v in (rate, t, gamma, beta)))
    a11, a22 = -(rate + gamma), -beta
    m = 0.5 * (a11 + a22)
    s = np.sqrt(0.25 * (a11 - a22) ** 2 + beta * gamma)
    slow = np.exp((m + s) * t)                       # slower eigenvalue m + s <= 0
    c = 0.5 * (slow + np.exp((m - s) * t))
    positive = s * t > 1e-5   # below: the series of the divided difference, error (st)^2/6
    safe = np.where(s > 0, s, 1.0)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        d = np.where(s > 0, slow * -np.expm1(-2.0 * s * t) / (2.0 * safe), t * np.exp(m * t))
        phi_slow, phi_fast = _phi(m + s, t), _phi(m - s, t)
        z = m * t
        small = np.abs(z) < 1e-3
        g = np.where(small, 0.5 + z / 3.0,
                     (np.exp(z) * (z - 1.0) + 1.0) / np.where(small, 1.0, z) ** 2)
        d_int = np.where(positive, (phi_slow - phi_fast) / (2.0 * safe), t * t * g)
    return Propagator(a11, beta, gamma, a22, m, c, d, 0.5 * (phi_slow + phi_fast), d_int)


def two_phase_mode_deficit(rate, t, gamma: float, beta: float):
    """(free, bound) deficits of one mode with diffusive decay rate ``rate`` = D lambda
    (1/s) at times ``t`` (s), starting from the equilibrium shares (free, bound):
    exp(A t) x0 with A = [[-(rate + gamma), beta], [gamma, -beta]]. Broadcasts
    ``rate`` against ``t``; usable for any geometry whose Fickian modes are known.

    Parameters
    ----------
    rate : array_like
        The mode's decay rate D lambda [1/s].
    t : array_like
        The times [s].
    gamma : float
        gamma, the rate free water is bound at [1/s].
    beta : float
        beta, the rate bound water is freed at [1/s].

    Returns
    -------
    free, bound : numpy.ndarray
        The free and bound deficits of the mode [-], fractions of Mm.

    Raises
    ------
    ValueError
        From :func:`equilibrium_shares` for rates it refuses.
    """
    free0, bound0 = equilibrium_shares(gamma, beta)
    return exchange_propagator(rate, t, gamma, beta).apply(free0, bound0)


def _mode_count(fourier_min: float, exchange: float, tolerance: float) -> int:
    """Odd modes k = 1, 3, ... 2N-1 such that (i) the free-water series has converged,
    exp(-(k pi)^2 t*) < exp(-44) at the earliest positive t* (Crank 1975 eq. 4.18), and
    (ii) the O(1/(D lambda_k)) remainder of the exchange terms, about
    8 (gamma + beta) h^2 / (6 pi^4 D (2N)^3), is below ``tolerance``
    (``exchange`` = (gamma + beta) h^2 / D)."""
    free = np.sqrt(EXP_CUTOFF / max(fourier_min, 1e-300)) / (2.0 * np.pi)
    coupled = np.cbrt(8.0 * exchange / (6.0 * np.pi ** 4 * tolerance)) / 2.0
    return int(min(max(free, coupled) + 10, MAX_MODES))


def _sheet_modes(t, diffusivity, thickness, gamma, beta, tolerance):
    t = np.maximum(np.asarray(t, float), 0.0)
    positive = t[t > 0]
    fourier_min = diffusivity * positive.min() / thickness ** 2 if positive.size else 1.0
    exchange = (gamma + beta) * thickness ** 2 / diffusivity
    k = 2.0 * np.arange(_mode_count(fourier_min, exchange, tolerance)) + 1.0
    rate = diffusivity * (k * np.pi / thickness) ** 2
    return t, k, rate


def two_phase_sheet_uptake(t, diffusivity: float, thickness: float, gamma: float,
                           beta: float, tolerance: float = SERIES_TOLERANCE) -> TwoPhaseUptake:
    """Mean uptake of a sheet of thickness h (both faces exposed, edges sealed) under
    the Carter & Kibler two-phase model, as fractions of Mm, at times ``t`` (s).

    ``diffusivity`` D (m^2/s) of the free water, ``gamma`` binding rate and
    ``beta`` release rate (1/s). gamma = 0 gives Crank's Fickian series (Crank 1975
    eq. 4.18). Exact per mode (module docstring); the series is truncated where its
    remainder falls below ``tolerance`` (a fraction of Mm; a fit to data of 1e-3
    scatter may pass 1e-7 and run much faster).

    Parameters
    ----------
    t : float or array_like
        The times [s].
    diffusivity : float
        D of the free water [m^2/s].
    thickness : float
        h [m].
    gamma, beta : float
        The binding and release rates [1/s].
    tolerance : float
        The series' truncation error [-], a fraction of Mm.

    Returns
    -------
    TwoPhaseUptake
        Total, free and bound uptake [-], fractions of Mm.

    Raises
    ------
    ValueError
        When D or h is not positive.

    References
    ----------
    H. G. Carter and K. G. Kibler, "Langmuir-type model for anomalous moisture diffusion
    in composite resins", *Journal of Composite Materials* 12(2), 118-131, 1978,
    doi:10.1177/002199837801200201.
    """
    if diffusivity <= 0 or thickness <= 0:
        raise ValueError("diffusivity and thickness must be positive")
    free0, bound0 = equilibrium_shares(gamma, beta)
    t, k, rate = _sheet_modes(t, diffusivity, thickness, gamma, beta, tolerance)
    weight = 8.0 / (k * np.pi) ** 2                  # mean of the sine expansion of 1
    relaxed = bound0 * np.exp(-beta * t)             # high-mode limit of the bound deficit
    free_sum = np.zeros(t.shape)
    bound_sum = np.zeros(t.shape)
    for chunk in np.array_split(np.arange(k.size), max(1, k.size // 4000)):
        free_k, bound_k = two_phase_mode_deficit(rate[chunk][None, :], t.reshape(-1, 1), gamma, beta)
        free_sum += (free_k @ weight[chunk]).reshape(t.shape)
        bound_sum += ((bound_k - relaxed.reshape(-1, 1)) @ weight[chunk]).reshape(t.shape)
    dry = t == 0                                     # the series of the step needs every mode
    free = np.where(dry, 0.0, free0 - free_sum)
    bound = np.where(dry, 0.0, bound0 - (relaxed + bound_sum))
    return TwoPhaseUptake(total=free + bound, free=free, bound=bound)


def two_phase_sheet_profile(z, t, diffusivity: float, thickness: float, gamma: float,
                            beta: float, tolerance: float = SERIES_TOLERANCE) -> TwoPhaseUptake:
    """Local free and bound water (fractions of Mm) at z/h in [0, 1] and times ``t``
    (s): ``z`` and ``t`` broadcast, e.g. z[None, :] against t[:, None]. Same modes
    as :func:`two_phase_sheet_uptake` with sin(k pi z/h) 4/(k pi) in place of the
    mode means; the bound limit is summed in closed form.

    Parameters
    ----------
    z : float or array_like
        The depth as a fraction of the thickness, z/h [-].
    t : float or array_like
        The times [s], broadcast with ``z``.
    diffusivity : float
        The free water's diffusivity D [m^2/s].
    thickness : float
        The sheet's full thickness h [m].
    gamma, beta : float
        Binding rate gamma and release rate beta [1/s].
    tolerance : float
        Where the mode sums stop: their remainder [-], as a fraction of Mm.

    Returns
    -------
    TwoPhaseUptake
        The local total, free and bound water [-], fractions of Mm, shaped as the
        broadcast of ``z`` and ``t``.

    References
    ----------
    Carter & Kibler (1978), eqs. 1-2 (see the module docstring).
    """
    free0, bound0 = equilibrium_shares(gamma, beta)
    z, t = np.broadcast_arrays(np.asarray(z, float), np.maximum(np.asarray(t, float), 0.0))
    _, k, rate = _sheet_modes(t, diffusivity, thickness, gamma, beta, tolerance)
    shape = z.shape
    z, t = z.reshape(-1, 1), t.reshape(-1, 1)
    relaxed = bound0 * np.exp(-beta * t)  # also at the faces: N there relaxes to N_inf at beta
    free_sum = np.zeros(z.shape)
    bound_sum = np.zeros(z.shape)
    for chunk in np.array_split(np.arange(k.size), max(1, k.size // 4000)):
        kc = k[chunk][None, :]
        shape_k = 4.0 / (kc * np.pi) * np.sin(kc * np.pi * z)
        free_k, bound_k = two_phase_mode_deficit(rate[chunk][None, :], t, gamma, beta)
        free_sum += np.sum(free_k * shape_k, axis=1, keepdims=True)
        bound_sum += np.sum((bound_k - bound0 * np.exp(-beta * t)) * shape_k, axis=1, keepdims=True)
    face = (z <= 0) | (z >= 1)
    free = np.where(t == 0, np.where(face, free0, 0.0), free0 - free_sum).reshape(shape)
    bound = np.where(t == 0, 0.0, bound0 - relaxed - bound_sum).reshape(shape)
    return TwoPhaseUptake(total=free + bound, free=free, bound=bound)


def carter_kibler_approximation(t, diffusivity: float, thickness: float, gamma: float,
                                beta: float, terms: int = 200):
    """Carter & Kibler (1978) closed-form approximation of the total uptake fraction,
    valid for 2 gamma, 2 beta << kappa = pi^2 D / h^2:

    M/Mm = beta/(gamma+beta) exp(-gamma t) [1 - 8/pi^2 sum exp(-kappa k^2 t)/k^2]
           + beta/(gamma+beta) (exp(-beta t) - exp(-gamma t)) + (1 - exp(-beta t)),

    k odd. Kept as a check of the exact solution in its regime, not used for fitting.

    Parameters
    ----------
    t : float or array_like
        Times since the exposure began [s].
    diffusivity, thickness : float
        D [m^2/s] and h [m].
    gamma, beta : float
        Binding and release rates [1/s], each much below kappa / 2.
    terms : int
        The odd modes summed.

    Returns
    -------
    numpy.ndarray
        M/Mm [-].
    """
    t = np.maximum(np.asarray(t, float), 0.0)
    kappa = np.pi ** 2 * diffusivity / thickness ** 2
    k = 2.0 * np.arange(terms) + 1.0
    fickian = 1.0 - 8.0 / np.pi ** 2 * np.sum(np.exp(-kappa * np.multiply.outer(t, k * k)) / (k * k), axis=-1)
    share = beta / (gamma + beta)
    return (share * np.exp(-gamma * t) * fickian + share * (np.exp(-beta * t) - np.exp(-gamma * t))
            + (1.0 - np.exp(-beta * t)))
