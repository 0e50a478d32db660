r"""Two-phase (Langmuir-type) moisture in the parts whose Fickian solution is a modal
series (Sheet, Bar, solid Disc), advanced exactly mode by mode through the history.

Carter & Kibler (1978) eqs. 1-2 (``sorption``): free water n diffuses, N is bound.
Expanding n - n_s(t) and N in the Fickian eigenfunctions psi_k of the part (zero on the
exposed surfaces, decay rates D lambda_k; ``modes.product_modes``), Green's identity
gives for the coefficients (p_k, q_k) of n and N, relative to those of the constant 1:

.. math::

    \frac{d}{dt} \begin{bmatrix} p \\ q \end{bmatrix}
    = \begin{bmatrix} -(D \lambda_k + \gamma) & \beta \\ \gamma & -\beta \end{bmatrix}
    \begin{bmatrix} p \\ q \end{bmatrix}
    + \begin{bmatrix} D \lambda_k\, n_s(t) \\ 0 \end{bmatrix},

one 2x2 linear system per mode (gamma = 0: the Fickian mode equation);
the volume and contact-layer means are sum A_k p_k, sum A_k q_k with the Fickian
amplitudes. Between nodes of the history the coefficients are constant (T held, or a
ramp cut into pieces; D from the exact rescaled clock, gamma and beta at the piece's
middle) and n_s = beta/(gamma + beta) Ms is linear, so the update is exact: with the
equilibrium x* = n_s (1, gamma/beta) and e = x - x*, e(t + h) = exp(A h) e(t) -
(dn_s/dt) int_0^h exp(A u) du (1, gamma/beta) (``two_phase.exchange_propagator``).

The modes left out (or merged into rate bins, ``modes.lump``) are the infinite-rate
limit: their free water follows n_s at once and their bound water relaxes locally,
dN/dt = gamma n_s - beta N; each step of n_s gets the exact Fickian transient of what
was left out (``modes.step_corrections``). Counts and bins are doubled until the result
changes less than the accuracy.

References
----------
- Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture diffusion
  in composite resins. Journal of Composite Materials 12(2):118-131.
  doi:10.1177/002199837801200201
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..accuracy.budget import TWO_PHASE_INTERPOLATION_SHARE
from ..exact.modes import (FIRST_COUNT, FIRST_PER_OCTAVE, MAX_PRODUCT, dimensions, lump,
                           product_modes, step_corrections)
from ..exact.separable import step_response
from ..exact.two_phase import exchange_propagator
from ..forcing.clock import RescaledTime
from ..forcing.record import Forcing, linear_pieces
from ..problem.exposure import swing as swing_of
from ..problem.geometry import LAYER_DEPTH

MAX_EXCHANGE_PIECES = 100_000  # pieces per ramp row at most (exchange frozen per piece)


@dataclass(frozen=True)
class Nodes:
    """Where the modal two-phase march stops, and the forcing between its stops.

    Parameters
    ----------
    t : numpy.ndarray
        The nodes' physical times [s].
    tau : numpy.ndarray
        Their rescaled times [s].
    free_right : numpy.ndarray
        The free surface moisture n_s at the nodes [weight %] (right values).
    free_left : numpy.ndarray
        n_s just before the nodes [weight %] (left limits).
    gamma, beta : numpy.ndarray
        The binding and release rates of each interval [1/s].
    ratio : numpy.ndarray
        w2 = gamma/beta of each interval [-].
    outputs : numpy.ndarray of int
        The node index of each requested time.
    initial_bound : float
        The bound moisture at t = 0 [weight %].
    interpolation : float
        The bound of the error of Ms linear between nodes and rates frozen [weight %].
    """

    t: np.ndarray
    tau: np.ndarray
    free_right: np.ndarray
    free_left: np.ndarray
    gamma: np.ndarray
    beta: np.ndarray
    ratio: np.ndarray
    outputs: np.ndarray
    initial_bound: float
    interpolation: float


def march_nodes(law, diffusivity, exposure, times, tolerance) -> Nodes:
    """The stops of the modal two-phase march: edges, cut ramp rows, and the outputs.

    Ramp rows are cut where Ms departs from linear (``record.linear_pieces``) or where
    freezing the exchange rates over a piece would err by more than ``tolerance``.

    Parameters
    ----------
    law : Langmuir
        The two-phase law (rates [1/s]).
    diffusivity : Diffusivity
        The material's diffusivity (its activation energy [J/mol]).
    exposure : Exposure
        The history (times [s], temperature [K], moisture [weight %]).
    times : numpy.ndarray
        The output times [s].
    tolerance : float
        The error allowed for the piecewise forcing [weight %].

    Returns
    -------
    Nodes
        The stops and the forcing.
    """
    clock = RescaledTime(diffusivity, exposure)
    edges = clock.edges
    pieces, interpolation = linear_pieces(exposure, clock, tolerance)
    exchange, frozen = _exchange_pieces(law, clock, exposure, tolerance)
    pieces = np.maximum(pieces, exchange)
    interpolation += float(np.max(frozen / pieces ** 2, initial=0.0))
    cuts = [np.linspace(a, b, n + 1)[:-1] for a, b, n in zip(edges[:-1], edges[1:], pieces)]
    t = np.unique(np.concatenate(cuts + [edges[-1:], times]))
    share_right = law.free_share(exposure.temperature(t))
    share_left = law.free_share(exposure.temperature(np.nextafter(t, -np.inf)))
    left = share_left * np.asarray(exposure.surface_before(t), float)
    share0 = float(law.free_share(exposure.temperature(t[:1]))[0])
    left[0] = share0 * exposure.initial_moisture
    gamma, beta = law.rates(exposure.temperature(0.5 * (t[1:] + t[:-1])))
    ratio = np.where(gamma > 0, gamma / np.where(beta > 0, beta, 1.0), 0.0)
    return Nodes(t, clock(t), share_right * np.asarray(exposure.surface_moisture(t), float),
                 left, gamma, beta, ratio, np.searchsorted(t, times),
                 (1.0 - share0) * exposure.initial_moisture, interpolation)


def _exchange_pieces(law, clock, exposure, tolerance) -> tuple[np.ndarray, np.ndarray]:
    """Pieces per ramp row so that freezing gamma, beta, the Arrhenius factor of D and the
    free share at each piece's middle (the exponential midpoint rule, second order: Blanes,
    Casas, Oteo & Ros 2009, Phys. Rep. 470:151, §4.1, local error O(h^3) from A'' and
    [A, A']) stays within ``tolerance``. A row of length L whose rates change by a log
    spread Delta, exchange scale a = max(gamma + beta), cut into n pieces (h = L/n,
    spread Delta/n each) errs by about L a (Delta/n)^2 / 24 + (L a)^2 Delta / (12 n^2);
    returns n and that error times n^2 (held rows: 1 piece, no error)."""
    start, end = clock.edges[:-1], clock.edges[1:]
    first = exposure.temperature(start)
    last = exposure.temperature(np.nextafter(end, -np.inf))
    spread = np.zeros(start.size)
    for rate in (lambda t: law.rates(t)[0], lambda t: law.rates(t)[1], clock.rate,
                 law.free_share):
        a, b = np.asarray(rate(first), float), np.asarray(rate(last), float)
        positive = (a > 0) & (b > 0)
        spread = np.maximum(spread, np.abs(np.log(np.where(positive, b, 1.0)
                                                  / np.where(positive, a, 1.0))))
    scale = sum(np.maximum(x, y) for x, y in zip(law.rates(first), law.rates(last)))
    exchange = scale * (end - start)
    frozen = np.where(clock.ramp, exchange * spread ** 2 / 24.0 + exchange ** 2 * spread / 12.0,
                      0.0)
    pieces = np.ceil(np.sqrt(frozen / max(tolerance, 1e-300)))
    return np.clip(pieces, 1, MAX_EXCHANGE_PIECES).astype(int), frozen


def march_modes(rates, amplitudes, nodes: Nodes) -> np.ndarray:
    """Advance the free and bound water's modal coefficients exactly through the history.

    The kept modes are advanced by the exact 2x2 propagator of each interval; the rest
    are taken in the infinite-rate limit (free water at n_s, bound water relaxing
    locally).

    Parameters
    ----------
    rates : numpy.ndarray
        The modes' decay rates D0 lambda_k per rescaled second [1/s].
    amplitudes : numpy.ndarray
        The modes' amplitudes in k weighted means (volume, layer), shape (modes, k) [-].
    nodes : Nodes
        The stops and the forcing.

    Returns
    -------
    numpy.ndarray
        (free, bound) means [weight %] at the outputs, shape (n_outputs, 2, k).

    References
    ----------
    Carter & Kibler (1978), cited in the module docstring.
    """
    kept = amplitudes.sum(axis=0)
    p = np.full(rates.size, nodes.free_left[0])
    q = np.full(rates.size, nodes.initial_bound)
    q_rest = nodes.initial_bound
    out = np.zeros((nodes.outputs.size, 2, amplitudes.shape[1]))
    want = {int(k): i for i, k in enumerate(nodes.outputs)}
    dt, dtau = np.diff(nodes.t), np.diff(nodes.tau)
    for i in range(dt.size):
        if i in want:
            _record(out, want, i, p, q, q_rest, amplitudes, kept, nodes.free_right[i])
        slope = (nodes.free_left[i + 1] - nodes.free_right[i]) / dt[i]
        w2 = nodes.ratio[i]
        step = exchange_propagator(rates * dtau[i] / dt[i], dt[i], nodes.gamma[i], nodes.beta[i])
        e1, e2 = step.apply(p - nodes.free_right[i], q - w2 * nodes.free_right[i])
        i1, i2 = step.apply(1.0, w2, integral=True)
        p = e1 - slope * i1 + nodes.free_left[i + 1]
        q = e2 - slope * i2 + w2 * nodes.free_left[i + 1]
        q_rest = _relax_bound(q_rest, nodes, i, slope, w2)
    last = dt.size
    if last in want:
        _record(out, want, last, p, q, q_rest, amplitudes, kept, nodes.free_right[last])
    return out


def _relax_bound(q, nodes: Nodes, i: int, slope: float, w2: float) -> float:
    """The infinite-rate limit over interval i: dN/dt = gamma n_s - beta N, exact for n_s
    linear (e = N - w2 n_s decays at beta and is driven by -w2 dn_s/dt)."""
    h, beta = nodes.t[i + 1] - nodes.t[i], nodes.beta[i]
    decay = np.exp(-beta * h)
    integral = -np.expm1(-beta * h) / beta if beta > 0 else h
    e = (q - w2 * nodes.free_right[i]) * decay - w2 * slope * integral
    return float(e + w2 * nodes.free_left[i + 1])


def _record(out, want, node, p, q, q_rest, amplitudes, kept, free_now) -> None:
    row = want[node]
    out[row, 0] = p @ amplitudes + (1.0 - kept) * free_now
    out[row, 1] = q @ amplitudes + (1.0 - kept) * q_rest


@dataclass(frozen=True)
class ModeSource:
    """Where the Fickian modes of a part come from.

    Parameters
    ----------
    modes : callable
        ``modes(counts)``: the product modes, ``counts`` per doubled direction, before
        lumping (``exact.modes.Modes``, rates in [1/s]).
    response : callable
        ``response(age)``: the exact unit-step mean and layer uptake [-] at a rescaled age
        [s], for the step corrections.
    directions : int
        The number of directions whose mode counts are doubled.
    fixed : int
        Modes of a direction kept whole (a planform's), multiplying the counts.
    """

    modes: object
    response: object
    directions: int
    fixed: int = 1     # modes of a direction kept whole (a planform's), times the counts


def separable_source(geometry, d0, depth) -> ModeSource:
    """The mode source of a separable part (Sheet, Bar, solid Disc).

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        The part (lengths [m]).
    d0 : sequence of float
        The principal pre-exponential diffusivities (D_x, D_y, D_z) [m^2/s].
    depth : float
        The surface layer's depth [m].

    Returns
    -------
    ModeSource
        ``modes.product_modes`` and ``separable.step_response`` of the part.
    """
    return ModeSource(lambda counts: product_modes(geometry, d0, depth, counts),
                      lambda age: step_response(geometry, d0, age, depth), dimensions(geometry))


def _history(source: ModeSource, nodes: Nodes, counts, per_octave) -> np.ndarray:
    """(n_outputs, 3): free mean, bound mean, total contact-layer mean."""
    modes = lump(source.modes(counts), per_octave)
    values = march_modes(modes.rates, np.stack([modes.mean, modes.layer], axis=1), nodes)
    force = Forcing(nodes.tau, nodes.free_right, nodes.free_left, nodes.outputs, 0.0)
    values[:, 0, :] += step_corrections(None, None, None, modes, force, source.response)
    return np.stack([values[:, 0, 0], values[:, 1, 0], values[:, 0, 1] + values[:, 1, 1]], axis=1)


def langmuir_history(geometry, diffusivity, law, exposure, times, accuracy,
                     surface_layer_depth=LAYER_DEPTH, source: ModeSource | None = None):
    """Two-phase (Langmuir-type) moisture of a part over an exposure, by exact modes.

    Mode counts and rate bins are doubled until the result changes by less than the
    accuracy's share.

    Parameters
    ----------
    geometry : Sheet, Bar, Disc, CamPlate or LinkBar
        The part (lengths [m]).
    diffusivity : Diffusivity
        D0 [m^2/s] and Ea [J/mol] of the free water's diffusion.
    law : Langmuir
        The two-phase law (rates [1/s]).
    exposure : Exposure
        Times [s], temperatures [K] and total surface moisture [weight %].
    times : numpy.ndarray
        Where the history is read [s].
    accuracy : float
        The requested error relative to the swing [-].
    surface_layer_depth : float
        The contact layer's depth [m].
    source : ModeSource, optional
        The part's modes (None: the separable Sheet, Bar or solid Disc).

    Returns
    -------
    dict
        "mean" (total), "surface" (contact-layer total) and "bound" [weight %] at
        ``times``.
    float
        The error estimate relative to the largest swing |Ms - M0| [-] (the change when
        modes and bins are doubled plus the interpolation bound of ramps).

    References
    ----------
    Carter & Kibler (1978), cited in the module docstring.
    """
    times = np.asarray(times, float)
    source = source or separable_source(geometry, diffusivity.pre_exponential, surface_layer_depth)
    swing = swing_of(exposure)
    if swing == 0.0:
        flat = np.full(times.size, exposure.initial_moisture)
        bound = flat * (1.0 - law.free_share(exposure.temperature(times)))
        return {"mean": flat, "surface": flat.copy(), "bound": bound}, 0.0
    tolerance = accuracy * swing
    nodes = march_nodes(law, diffusivity, exposure, times,
                        TWO_PHASE_INTERPOLATION_SHARE * tolerance)
    counts, per_octave = [FIRST_COUNT] * source.directions, FIRST_PER_OCTAVE
    values = _history(source, nodes, counts, per_octave)
    while True:
        coarse = values
        counts, per_octave = [2 * c for c in counts], 2 * per_octave
        values = _history(source, nodes, counts, per_octave)
        change = float(np.max(np.abs(values - coarse)))
        if (change <= (1.0 - TWO_PHASE_INTERPOLATION_SHARE) * tolerance
                or source.fixed * np.prod(counts) * 2 ** len(counts) > MAX_PRODUCT):
            break
    free, bound, layer = values.T
    return {"mean": free + bound, "surface": layer, "bound": bound}, \
        (change + nodes.interpolation) / swing
