r"""Duhamel superposition of unit-step responses over an exposure history: the one
implementation every model that superposes (exact series, the plane model) uses.

Duhamel's theorem (Carslaw & Jaeger 1959 §1.14, time-dependent surface
conditions; Crank 1975 §4.2.1, eq. 4.34): with the rescaled time tau(t) (``clock``),

.. math::

    M(t) = M_0 + \sum_k \Delta M_{s,k}\, K\big(\tau(t) - \tau(t_k)\big)
    + \int_{\text{ramps}} K\big(\tau(t) - \tau(s)\big)\, dM_s(s)

where K is the unit-step response (mean, contact-layer mean, or a field).
The ramp integral is taken against the measure dMs (so the kernel K, bounded,
is never differentiated), on panels geometric in the age w = t - s, each
mapped by w = v^2 (v linear), which makes K ~ sqrt(tau) smooth in v. The
derivative of Ms along each panel is the spectral derivative of its values at
the Gauss-Legendre nodes (exact for a polynomial of degree < GAUSS_NODES).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
  Clarendon Press.
"""
from __future__ import annotations

import numpy as np

from ..exact.series import SATURATION_FOURIER
from ..forcing.clock import clock_of
from ..problem.cache import RunCache, run_cache

GAUSS_NODES = 16
PANEL_RATIO = 8.0
FIRST_PANEL = 1e-2   # first panel: 1e-2 of the fastest diffusion time (quadrature error ~1e-12 relative)

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(GAUSS_NODES)


def _differentiation_matrix(nodes: np.ndarray) -> np.ndarray:
    """Spectral differentiation at distinct nodes (barycentric form,
    Berrut & Trefethen 2004, SIAM Rev. 46:501, eq. 9.4)."""
    difference = nodes[:, None] - nodes[None, :]
    np.fill_diagonal(difference, 1.0)
    weights = 1.0 / np.prod(difference, axis=1)
    matrix = (weights[None, :] / weights[:, None]) / difference
    np.fill_diagonal(matrix, 0.0)
    np.fill_diagonal(matrix, -matrix.sum(axis=1))
    return matrix


_DIFF = _differentiation_matrix(_NODES)


def surface_jumps(exposure) -> np.ndarray:
    """The jumps of the surface moisture, dMs_k = Ms(t_k) - Ms(t_k-), at each segment start.

    Parameters
    ----------
    exposure : Exposure
        The history; Ms(0-) is its initial moisture M0.

    Returns
    -------
    numpy.ndarray
        One jump per segment [weight %] (0 where Ms is continuous).
    """
    edges = np.asarray(exposure.change_times, float)[:-1]
    after = np.asarray(exposure.surface_moisture(edges), float)
    return after - exposure.surface_before(edges)


def _panel_edges(age_low, age_high, first):
    """Panel boundaries in the age w: the geometric grid 0, w1, 4 w1, 16 w1 ...
    (graded toward the kernel's sqrt singularity at w = 0) clipped to
    [w_lo, w_hi]; shape (n_times, n_panels + 1)."""
    count = int(np.ceil(np.log(max(float(age_high.max()) / first, 1.0)) / np.log(PANEL_RATIO))) + 2
    grid = np.concatenate([[0.0], first * PANEL_RATIO ** np.arange(count)])
    return np.clip(grid[None, :], age_low[:, None], age_high[:, None])


def _surface_before(exposure, s, end):
    """Ms(s) for s in a ramp [start, end], its left limit at s = end."""
    s = np.asarray(s, float)
    value = np.asarray(exposure.surface_moisture(s.ravel()), float).reshape(s.shape)
    return np.where(s >= end, float(exposure.surface_before(end)), value)


def _ramp_integral(kernel, clock, exposure, start, end, times, first_age, saturated_age):
    """integral over s in [start, min(end, t)] of K(tau(t) - tau(s)) dMs(s).

    Ages w = t - s run over [w_lo, w_hi]; past ``saturated_age`` K = 1 and the
    integral is a difference of Ms. Below it each panel is mapped by w = v^2,
    v linear, so that K ~ sqrt(w) is smooth in v."""
    low = np.maximum(times - end, 0.0)
    high = np.maximum(times - start, 0.0)
    cap = np.clip(saturated_age, low, high)
    edges = np.sqrt(_panel_edges(low, cap, first_age))
    a, b = edges[:, :-1, None], edges[:, 1:, None]
    v = a + (b - a) * 0.5 * (_NODES + 1.0)
    s = np.clip(times[:, None, None] - v * v, start, end)
    moisture = _surface_before(exposure, s, end)
    # x in [-1, 1] increases with age, s decreases: the measure dMs is -dMs/dx dx
    slope = -moisture @ _DIFF.T
    response = kernel(clock.between(s, np.broadcast_to(times[:, None, None], s.shape)))
    body = np.einsum("tpn...,tpn,n->t...", response, slope, _WEIGHTS)
    tail = (_surface_before(exposure, np.clip(times - cap, start, end), end)
            - _surface_before(exposure, np.full_like(times, start), end))
    tail = np.where(high > cap, tail, 0.0)
    return body + tail.reshape(tail.shape + (1,) * (body.ndim - 1))


def duhamel(kernel, diffusivity, exposure, times, diffusion_times, chunk=64,
            cache: RunCache | None = None):
    """Duhamel's sum of unit-step responses over an exposure: M(t) - M0.

    Parameters
    ----------
    kernel : callable
        K(tau): the unit-step response [-] at rescaled ages tau [s] of any shape.
    diffusivity : Diffusivity
        The material's diffusivity (its activation energy [J/mol]).
    exposure : Exposure
        The history (times [s], temperature [K], surface moisture [weight %]).
    times : numpy.ndarray
        The output times [s].
    diffusion_times : tuple of float
        (fastest, slowest) L^2 / D0 of the part [s] (rescaled): the first panel's scale
        and the age past which K = 1.
    chunk : int
        Output times summed at once (bounds the memory).
    cache : RunCache, optional
        The run's cache (None: a fresh one).

    Returns
    -------
    numpy.ndarray
        M(t) - M0 [weight %], shape (n_times, ...kernel outputs).

    References
    ----------
    Carslaw & Jaeger (1959) §1.14; Crank (1975) eq. 4.34 (module docstring).
    """
    times = np.asarray(times, float)
    clock = clock_of(diffusivity, exposure, run_cache(cache))
    edges = clock.edges
    fastest, slowest = diffusion_times
    rate = diffusivity.arrhenius_factor(exposure.temperature(np.linspace(edges[0], edges[-1], 257)))
    rate = np.concatenate([rate, clock.held_rate])
    first_age = FIRST_PANEL * fastest / max(float(rate.max()), 1e-300)
    saturated_age = SATURATION_FOURIER * slowest / max(float(rate.min()), 1e-300)
    jumps = surface_jumps(exposure)
    parts = []
    for begin in range(0, times.size, chunk):
        t = times[begin:begin + chunk]
        total = np.zeros_like(kernel(np.zeros(t.size)))
        for k in np.flatnonzero(jumps):
            started = t >= edges[k]
            response = kernel(clock.between(np.minimum(edges[k], t), t))
            total = total + jumps[k] * response * started.reshape((-1,) + (1,) * (response.ndim - 1))
        for k in np.flatnonzero(clock.ramp):
            total = total + _ramp_integral(kernel, clock, exposure, edges[k], edges[k + 1], t,
                                           first_age, saturated_age)
        parts.append(total)
    return np.concatenate(parts, axis=0)

