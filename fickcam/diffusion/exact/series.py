"""Crank's series for the two one-dimensional problems every exact solution is built
from, each after a unit step of the surface value at t = 0: the sheet exposed on both
faces (t* = D t / h^2, h the full thickness; positions z/h in [0, 1]) and the infinite
solid cylinder (t* = D t / a^2, a its radius; positions r/a in [0, 1]). Every fraction
is (C - C0) / (Cs - C0): 0 before the step, 1 at saturation. Short times use the erfc
(image) forms, long times the Fourier/Bessel series, each exact to round-off where it
is used.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
  Clarendon Press.
"""
from __future__ import annotations

from functools import cache

import numpy as np
from scipy.special import erfc, gamma, j0, j1, jn_zeros


SQRT_PI = np.sqrt(np.pi)
SHEET_SWITCH = 0.05
"""t* below which the sheet uses the erfc image forms, above the Fourier series;
both are exact to machine precision there with the term counts below."""
SHEET_IMAGES = 6          # images n = 0..5: ierfc(6 / (2 sqrt 0.05)) ~ 1e-315
SHEET_MODES = 12          # modes n = 0..11: exp(-23^2 pi^2 0.05) ~ 1e-113
CYLINDER_SWITCH = 1e-4
"""t* below which the cylinder uptake uses the short-time expansion."""
CYLINDER_SHORT_TERMS = 9
EXP_CUTOFF = 44.0         # exp(-44) ~ 8e-20: a series mode below this is dropped
SATURATION_FOURIER = 8.0  # F = 1 - O(exp(-8 pi^2)) for the sheet, O(exp(-46)) cylinder


# --------------------------------------------------------------------- sheet
def ierfc(x):
    """First integral of erfc: ierfc(x) = exp(-x^2)/sqrt(pi) - x erfc(x)
    (Carslaw & Jaeger 1959, Appendix II).

    Parameters
    ----------
    x : float or array_like
        The argument [-] (0 where x >= 27, below the smallest double).

    Returns
    -------
    numpy.ndarray
        ierfc(x) [-].

    References
    ----------
    H. S. Carslaw and J. C. Jaeger, *Conduction of Heat in Solids*, 2nd ed., Oxford:
    Clarendon Press, 1959, Appendix II.
    """
    x = np.asarray(x, float)
    finite = np.minimum(x, 27.0)  # ierfc(27) < 1e-318: zero beyond, also for x = inf
    return np.where(x < 27.0, np.exp(-finite * finite) / SQRT_PI - finite * erfc(finite), 0.0)


def sheet_interval_mean_images(z1, z2, fourier):
    """Mean of the sheet's fractional concentration over [z1, z2] (units of h),
    short-time image (erfc) form integrated once (Crank 1975 eqs. 4.15, 4.20).

    Parameters
    ----------
    z1, z2 : float or array_like
        The interval's ends as fractions of the thickness, 0 <= z1 < z2 <= 1 [-].
    fourier : float or array_like
        t* = D t / h^2 [-], h the full thickness.

    Returns
    -------
    numpy.ndarray
        The mean of (C - C0) / (Cs - C0) over the interval [-]; accurate for t* < 0.05.

    References
    ----------
    Crank (1975), eqs. 4.15 and 4.20 (see the module docstring).
    """
    s = 2.0 * np.sqrt(fourier)
    total = 0.0
    for n in range(SHEET_IMAGES):
        sign = (-1.0) ** n
        total = total + sign * (ierfc((n + z1) / s) - ierfc((n + z2) / s)
                                + ierfc((n + 1 - z2) / s) - ierfc((n + 1 - z1) / s))
    return s * total / (z2 - z1)


def sheet_interval_mean_series(z1, z2, fourier):
    """Same mean from the Fourier series (Crank 1975 eq. 4.17) integrated over
    [z1, z2]: cos((2n+1) pi u), u = z - 1/2, averages to
    [sin(k pi u2) - sin(k pi u1)] / (k pi (u2 - u1)).

    Parameters
    ----------
    z1, z2 : float or array_like
        Where the interval starts and ends, in units of h [-].
    fourier : float or array_like
        The Fourier number D t / h^2 [-].

    Returns
    -------
    numpy.ndarray
        The interval's fractional mean [-] from ``SHEET_MODES`` modes (for t* >= 0.05).

    References
    ----------
    Crank (1975), eq. 4.17, integrated term by term.
    """
    u1, u2 = z1 - 0.5, z2 - 0.5
    total = 0.0
    for n in range(SHEET_MODES):
        k = 2 * n + 1
        decay = np.exp(-(k * np.pi) ** 2 * fourier)
        average = (np.sin(k * np.pi * u2) - np.sin(k * np.pi * u1)) / (k * np.pi * (u2 - u1))
        total = total + (-1.0) ** n / k * decay * average
    return 1.0 - 4.0 / np.pi * total


def _by_regime(switch, short_form, long_form, fourier, *positions):
    """Evaluate ``short_form`` where t* < switch and ``long_form`` elsewhere,
    each only on its own elements (broadcast arrays of positions and t*)."""
    arrays = np.broadcast_arrays(np.maximum(np.asarray(fourier, float), 0.0),
                                 *(np.asarray(p, float) for p in positions))
    fourier, positions = arrays[0], arrays[1:]
    short = fourier < switch
    out = np.empty(fourier.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        out[short] = short_form(*(p[short] for p in positions), fourier[short])
    out[~short] = long_form(*(p[~short] for p in positions), fourier[~short])
    return np.clip(out, 0.0, 1.0)


def sheet_interval_mean(z1, z2, fourier):
    """Fractional mean concentration over z in [z1, z2] (fractions of the
    thickness h, 0 <= z1 < z2 <= 1) of a sheet with both faces stepped to 1 at
    t = 0; t* = D t / h^2. Image form below t* = 0.05, series above.

    Parameters
    ----------
    z1, z2 : float or array_like
        z/h at the interval's two ends, z1 < z2, both in [0, 1] [-].
    fourier : float or array_like
        Scaled time t* of the sheet [-] (both faces exposed, h the whole thickness).

    Returns
    -------
    numpy.ndarray
        The fractional mean concentration over [z1, z2] [-], clipped to [0, 1].
    """
    def images(a, b, t):
        return np.where(t > 0, sheet_interval_mean_images(a, b, t), 0.0)
    return _by_regime(SHEET_SWITCH, images, sheet_interval_mean_series, fourier, z1, z2)


def _sheet_uptake_images(fourier):
    """Crank 1975 eq. 4.20 with l = h/2."""
    root = np.sqrt(fourier)
    images = sum((-1.0) ** n * ierfc(n / (2.0 * root)) for n in range(1, SHEET_IMAGES))
    return 4.0 * root * (1.0 / SQRT_PI + 2.0 * images)


def _sheet_uptake_series(fourier):
    """Crank 1975 eq. 4.18."""
    return 1.0 - sum(8.0 / (k * np.pi) ** 2 * np.exp(-(k * np.pi) ** 2 * fourier)
                     for k in range(1, 2 * SHEET_MODES, 2))


def sheet_uptake(fourier):
    """F(t*) = (M - M0)/(Ms - M0) of a sheet exposed on both faces,
    t* = D t / h^2. Short times: F = 4 sqrt(t*) [pi^-1/2 + 2 sum (-1)^n
    ierfc(n / (2 sqrt t*))] (Crank 1975 eq. 4.20 with l = h/2); long times:
    F = 1 - sum 8/((2n+1)^2 pi^2) exp(-(2n+1)^2 pi^2 t*) (Crank 1975 eq. 4.18).

    Parameters
    ----------
    fourier : float or array_like
        The Fourier number t* = D t / h^2 [-], h the full thickness.

    Returns
    -------
    numpy.ndarray
        The fractional uptake F [-].

    References
    ----------
    J. Crank, *The Mathematics of Diffusion*, 2nd ed., Oxford: Clarendon Press, 1975,
    eqs. 4.18 and 4.20.
    """
    return _by_regime(SHEET_SWITCH, _sheet_uptake_images, _sheet_uptake_series, fourier)


def sheet_series_remainder(fourier, n_terms):
    """Bound on the error of truncating Crank eq. 4.18 after ``n_terms`` modes:
    sum_{n >= N} 8/((2n+1)^2 pi^2) exp(-(2n+1)^2 pi^2 t*) <= first omitted term
    / (1 - exp(-8 pi^2 t*)) (geometric majorant).

    Parameters
    ----------
    fourier : float or array_like
        t* = D t / h^2 [-].
    n_terms : int
        The modes kept, N [-].

    Returns
    -------
    numpy.ndarray
        An upper bound of the truncation error of the uptake F [-] (inf at t* = 0).
    """
    fourier = np.asarray(fourier, float)
    k = 2 * n_terms + 1
    first = 8.0 / (k * np.pi) ** 2 * np.exp(-(k * np.pi) ** 2 * fourier)
    with np.errstate(divide="ignore"):
        return first / -np.expm1(-8.0 * np.pi ** 2 * fourier)


def _sheet_profile_images(z, fourier):
    """Sum of erfc images of both faces (Crank 1975 eq. 4.15); at t* = 0 the
    faces are at 1 and the interior at 0."""
    s = 2.0 * np.sqrt(fourier)
    images = sum((-1.0) ** n * (erfc((n + z) / s) + erfc((n + 1 - z) / s)) for n in range(SHEET_IMAGES))
    return np.where(fourier > 0, images, np.where((z <= 0) | (z >= 1), 1.0, 0.0))


def _sheet_profile_series(z, fourier):
    """Crank 1975 eq. 4.17 (origin moved to a face)."""
    return 1.0 - 4.0 / np.pi * sum(
        (-1.0) ** n / (2 * n + 1) * np.exp(-((2 * n + 1) * np.pi) ** 2 * fourier)
        * np.cos((2 * n + 1) * np.pi * (z - 0.5)) for n in range(SHEET_MODES))


def sheet_profile(z, fourier):
    """Fractional concentration at z/h in [0, 1] (broadcast with t*). Short
    times: erfc images (Crank 1975 eq. 4.15); long times: Crank eq. 4.17.

    Parameters
    ----------
    z : float or array_like
        The depth as a fraction of the thickness, z/h [-].
    fourier : float or array_like
        t* = D t / h^2 [-].

    Returns
    -------
    numpy.ndarray
        The fractional concentration (c - c0)/(cs - c0) [-].
    """
    return _by_regime(SHEET_SWITCH, _sheet_profile_images, _sheet_profile_series, fourier, z)


# ------------------------------------------------------------------ cylinder
ROOT_TABLE = 4096  # J0 roots made at once for every smaller count asked for (measured:
#   benchmarks/results/tuned_constants.md)


def bessel_roots(count: int) -> np.ndarray:
    """First ``count`` positive roots beta_n of J0 (the first ``ROOT_TABLE`` from one table:
    scipy's roots do not depend on how many are asked for; more are made on each call).
    Read-only.

    Parameters
    ----------
    count : int
        How many roots [-].

    Returns
    -------
    numpy.ndarray
        beta_1 < ... < beta_count, J0(beta_n) = 0 [-], read-only.
    """
    if count <= ROOT_TABLE:
        return _root_table()[:count]   # a view of a read-only table: read-only
    roots = jn_zeros(0, count)
    roots.setflags(write=False)
    return roots


@cache   # a constant of mathematics made on first use (32 kB), not a run's state
def _root_table() -> np.ndarray:
    table = jn_zeros(0, ROOT_TABLE)
    table.setflags(write=False)
    return table


def roots_for(fourier_min: float) -> np.ndarray:
    """Enough J0 roots that exp(-beta_N^2 t*) < exp(-EXP_CUTOFF) for t* >= fourier_min.

    Parameters
    ----------
    fourier_min : float
        The least t* = D t / a^2 the series is summed at [-].

    Returns
    -------
    numpy.ndarray
        The first roots of J0 [-] (at most 200 000), read-only.
    """
    count = int(np.sqrt(EXP_CUTOFF / max(fourier_min, 1e-12)) / np.pi) + 2
    return bessel_roots(min(count, 200_000))


@cache   # constants of mathematics made on first use, not a run's state
def cylinder_short_coefficients() -> np.ndarray:
    """Coefficients of F(t*) = sum_k b_k t*^((k+1)/2) for the solid cylinder.

    The Laplace transform of the uptake is 2 I1(q)/(q^3 I0(q)), q = sqrt(p)
    (Crank 1975 §5.3.2, transform of eq. 5.22). With the Hankel
    expansions I_nu(q) ~ e^q/sqrt(2 pi q) sum (-1)^k a_k(nu) q^-k,
    I1/I0 = sum c_k q^-k and term-by-term inversion gives
    b_k = 2 c_k / Gamma((k + 3)/2); the first three are Crank eq. 5.24.

    Returns
    -------
    numpy.ndarray
        b_0 ... b_8 [-], read-only.

    References
    ----------
    Crank (1975), §5.3.2 and eq. 5.24: the first three coefficients.
    """
    n = CYLINDER_SHORT_TERMS

    def hankel(nu):
        coefficient, out = 1.0, [1.0]
        for k in range(1, n):
            coefficient *= -(4 * nu * nu - (2 * k - 1) ** 2) / (k * 8.0)
            out.append(coefficient)
        return np.array(out)

    numerator, denominator = hankel(1), hankel(0)
    ratio = np.zeros(n)
    for k in range(n):  # power-series division numerator / denominator
        ratio[k] = numerator[k] - np.dot(ratio[:k], denominator[k:0:-1])
    coefficients = 2.0 * ratio / gamma((np.arange(n) + 3) / 2.0)
    coefficients.setflags(write=False)   # cached: shared by every caller
    return coefficients


def cylinder_uptake_short(fourier):
    """Short-time expansion (Crank 1975 eq. 5.24 continued).

    Parameters
    ----------
    fourier : float or array_like
        t* = D t / a^2 [-], a the radius; meant for t* < ``CYLINDER_SWITCH``.

    Returns
    -------
    numpy.ndarray
        The solid cylinder's fractional uptake sum_k b_k t*^((k+1)/2) [-].
    """
    b = cylinder_short_coefficients()
    root = np.sqrt(fourier)
    return sum(b[k] * root ** (k + 1) for k in range(b.size))


def cylinder_core_deficit(rho, fourier, roots):
    """1 - (mean concentration over r/a < rho), from Crank 1975 eq. 5.22
    integrated over the core: 4 sum exp(-b^2 t) J1(b rho)/(b^2 rho J1(b));
    for rho = 1 this is Crank eq. 5.23.

    Parameters
    ----------
    rho : numpy.ndarray
        The core's radius as a fraction of the cylinder's, in (0, 1] [-].
    fourier : numpy.ndarray
        t* = D t / a^2 [-], broadcast with ``rho``.
    roots : numpy.ndarray
        The roots beta_n of J0 summed over [-].

    Returns
    -------
    numpy.ndarray
        1 - the core's fractional mean concentration [-].

    References
    ----------
    Crank (1975), eq. 5.22 integrated over the core; eq. 5.23 at rho = 1.
    """
    b = roots
    decay = np.exp(-np.multiply.outer(fourier, b * b))
    weight = 4.0 * j1(np.multiply.outer(rho, b)) / (b * b * rho[..., None] * j1(b))
    return np.sum(decay * weight, axis=-1)


def cylinder_uptake(fourier_r):
    """Fractional uptake of an infinite solid cylinder, t* = D t / a^2:
    F = 1 - sum 4/(a^2 alpha_n^2) exp(-D alpha_n^2 t) (Crank 1975 eq. 5.23) for
    t* >= 1e-4, the short-time expansion (Crank eq. 5.24, carried to
    9 terms, error < 1e-17) below.

    Parameters
    ----------
    fourier_r : float or array_like
        t* = D t / a^2 [-], a the radius.

    Returns
    -------
    numpy.ndarray
        The fractional uptake [-], in [0, 1].

    References
    ----------
    J. Crank, *The Mathematics of Diffusion*, 2nd ed., Oxford: Clarendon Press, 1975,
    eqs. 5.23 and 5.24.
    """
    fourier = np.maximum(np.asarray(fourier_r, float), 0.0)
    short = fourier < CYLINDER_SWITCH
    long_t = np.where(short, CYLINDER_SWITCH, fourier)
    deficit = cylinder_core_deficit(np.ones_like(long_t), long_t, roots_for(CYLINDER_SWITCH))
    value = np.where(short, cylinder_uptake_short(np.where(short, fourier, 0.0)), 1.0 - deficit)
    return np.clip(value, 0.0, 1.0)


def cylinder_core_mean(rho, fourier_r):
    """Fractional mean concentration over the core r/a < rho of a solid
    cylinder (rho in (0, 1]). Before the front reaches the core
    ((1 - rho)/(2 sqrt t*) > 6.5) the core is dry to 1e-19.

    Parameters
    ----------
    rho : float or array_like
        The core's relative radius r/a in (0, 1] [-].
    fourier_r : float or array_like
        t* = D t / a^2 [-], broadcast with ``rho``.

    Returns
    -------
    numpy.ndarray
        The core's fractional mean concentration [-], in [0, 1].
    """
    rho, fourier = np.broadcast_arrays(np.asarray(rho, float),
                                       np.maximum(np.asarray(fourier_r, float), 0.0))
    if rho.size == 0:
        return np.zeros(rho.shape)
    start = ((1.0 - rho) / 13.0) ** 2
    dry = fourier < start
    active = np.where(dry, np.maximum(start, 1e-12), fourier)
    value = np.empty(rho.shape)
    flat_rho, flat_t, flat_out = rho.ravel(), active.ravel(), value.reshape(-1)
    for chunk in _decade_chunks(flat_t):
        roots = roots_for(float(flat_t[chunk].min()))
        flat_out[chunk] = 1.0 - cylinder_core_deficit(flat_rho[chunk], flat_t[chunk], roots)
    return np.clip(np.where(dry, 0.0, value), 0.0, 1.0)


def _decade_chunks(fourier):
    """Index groups of t* by decade (each group gets its own root count)."""
    decade = np.floor(np.log10(np.maximum(fourier, 1e-300)))
    return [np.flatnonzero(decade == d) for d in np.unique(decade)]


def _cylinder_profile_short(r, fourier):
    """Three-term short-time form (Crank 1975 §5.3.2, the small-time series;
    re-derived here from the transform I0(q r)/(p I0(q)) with the Hankel
    expansion of I0): (a/r)^1/2 erfc(x) + (a-r) sqrt(Dt)/(4 a^1/2 r^3/2) ierfc(x) +
    (9a^2 - 2ar - 7r^2) Dt/(32 a^3/2 r^5/2) i2erfc(x), x = (a-r)/(2 sqrt(Dt))."""
    r = np.maximum(r, 0.5)
    root = np.sqrt(fourier)
    x = (1.0 - r) / (2.0 * root)
    i2erfc = 0.25 * (erfc(x) - 2.0 * x * ierfc(x))
    return (r ** -0.5 * erfc(x) + (1.0 - r) * root / (4.0 * r ** 1.5) * ierfc(x)
            + (9.0 - 2.0 * r - 7.0 * r * r) * fourier / (32.0 * r ** 2.5) * i2erfc)


CYLINDER_PROFILE_SWITCH = 1e-6


def cylinder_profile(r, fourier_r):
    """Fractional concentration at r/a in [0, 1] of a solid cylinder
    (broadcast with t*): C = 1 - 2 sum exp(-b^2 t*) J0(b r)/(b J1(b))
    (Crank 1975 eq. 5.22) for t* >= 1e-6; below, the short-time form
    (error O(t*^3/2) < 1e-9).

    Parameters
    ----------
    r : float or array_like
        The radius as a fraction of the cylinder's, r/a [-].
    fourier_r : float or array_like
        t* = D t / a^2 [-].

    Returns
    -------
    numpy.ndarray
        The fractional concentration (C - C0) / (Cs - C0) [-], in [0, 1].

    References
    ----------
    Crank (1975), eq. 5.22 (the Bessel series) and §5.3.2 (the short-time form).
    """
    r, fourier = np.broadcast_arrays(np.asarray(r, float),
                                     np.maximum(np.asarray(fourier_r, float), 0.0))
    short = fourier < CYLINDER_PROFILE_SWITCH
    value = np.empty(r.shape)
    flat_r, flat_t, flat_out = r.ravel(), fourier.ravel(), value.reshape(-1)
    short_flat = short.ravel()
    with np.errstate(divide="ignore", invalid="ignore"):
        flat_out[short_flat] = np.where(flat_t[short_flat] > 0,
                                        _cylinder_profile_short(flat_r[short_flat], flat_t[short_flat]),
                                        (flat_r[short_flat] >= 1).astype(float))
    long_index = np.flatnonzero(~short_flat)
    for chunk in _decade_chunks(flat_t[long_index]):
        index = long_index[chunk]
        b = roots_for(float(flat_t[index].min()))
        decay = np.exp(-np.multiply.outer(flat_t[index], b * b))
        flat_out[index] = 1.0 - 2.0 * np.sum(decay * j0(np.multiply.outer(flat_r[index], b))
                                             / (b * j1(b)), axis=-1)
    return np.clip(value, 0.0, 1.0)
