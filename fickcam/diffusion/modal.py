"""Exact series advanced through a long climate record mode by mode (recursive
convolution): cost proportional to rows x modes instead of rows x outputs.

The unsaturated fraction of a unit surface step is a sum of decaying modes,
1 - K(tau) = sum_n A_n exp(-lambda_n tau):

- sheet (thickness h, both faces): A_n = 8 / ((2n+1)^2 pi^2), lambda_n = (2n+1)^2 pi^2 D / h^2
  (Crank 1975 eq. 4.18); its mode shape (4 / ((2n+1) pi)) sin((2n+1) pi z / h)
  (Crank eq. 4.17) averaged over the core z/h in [f, 1-f] gives 8 cos((2n+1) pi f) /
  ((2n+1)^2 pi^2 (1 - 2f));
- solid cylinder (radius a): A_n = 4 / alpha_n^2, lambda_n = alpha_n^2 D / a^2, alpha_n the
  zeros of J0 (Crank eq. 5.23); its shape 2 J0(alpha r / a) / (alpha J1(alpha)) (Crank
  eq. 5.22) averaged over r/a < rho gives 4 J1(alpha rho) / (rho alpha^2 J1(alpha));
- a bar or a finite disc is a product of these (Crank §5.3; Carslaw & Jaeger 1959
  §1.16): product modes with multiplied amplitudes and summed rates; the contact layer
  is the part minus its core, (whole - V core) / (1 - V).

Each mode's value y_n obeys dy_n/dtau = lambda_n (Ms - y_n) (Duhamel's integral of one
exponential kernel; Carslaw & Jaeger §1.14) and the mean is M = sum A_n y_n. With Ms
linear in tau over a step dtau the update is exact:
y(tau + dtau) = Ms1 + (y - Ms0) E - s (1 - E) / lambda, E = exp(-lambda dtau), s the slope.
The modes past a count per factor follow Ms at once (the static correction: M = sum_kept
A_n y_n + (1 - sum_kept A_n) Ms); the product modes are lumped into narrow bins of rate
(summed amplitudes at the mean rate: thousands of near-equal fast rates become one); a
step of Ms (a held segment, or the initial moisture) gets the transient of what was left
out or merged back from the closed-form step response (``exact.step_response``), so steps
stay exact. The error of counts and bins is measured by doubling both (twice the modes,
bins half as wide) until the two results agree within the accuracy.

Rows where Ms is not linear in tau (T and RH ramp together, Ms = a (RH/100)^b) are cut
into pieces until the deviation from linear is below its share of the tolerance; the
mean and layer responses are averages of the Ms history with positive weights (the step
response is monotone), so that deviation bounds their error.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import j1, jn_zeros

from .clock import RescaledTime
from .exact import step_response
from .geometry import Disc, Sheet

FIRST_COUNT = 32         # modes per factor to start with (doubled with the bins halved
FIRST_PER_OCTAVE = 4     # rate bins per octave to start with   while the two differ)
MAX_PRODUCT = 300_000    # product modes generated at most (memory, time)
MODAL_SEGMENTS = 32      # records with this many segments go modal; shorter histories keep
#   Duhamel, exact to 1e-8 and under ~0.7 s there (measured: disc 32 ramps, 13 outputs:
#   Duhamel 0.69 s, modal 0.06 s at accuracy 1e-3; 8 ramps: 0.16 s against 0.02 s)
INTERPOLATION_SHARE = 0.25 # share of the tolerance for Ms piecewise linear in tau
MAX_PIECES = 512         # pieces per row at most
CHUNK = 256              # intervals whose decays are computed at once
TRANSIENT_CUTOFF = 50.0  # a step's transient past exp(-50) is nothing


def prefers_modal(exposure) -> bool:
    """Long records (``MODAL_SEGMENTS``): the march costs rows x modes, Duhamel rows x
    outputs x panels."""
    return np.asarray(exposure.ramp).size >= MODAL_SEGMENTS


@dataclass(frozen=True)
class Factor:
    """One separable direction: rates (1/s rescaled), mean and core amplitudes, and the
    share of this direction's extent that lies in the core."""

    rates: np.ndarray
    mean: np.ndarray
    core: np.ndarray
    core_share: float


def sheet_factor(length, d0, depth, count) -> Factor:
    """Crank eqs. 4.17-4.18: modes of a sheet of full thickness ``length``."""
    k = 2 * np.arange(count) + 1.0
    fraction = min(depth / length, 0.5)
    mean = 8.0 / (k * np.pi) ** 2
    core = (8.0 * np.cos(k * np.pi * fraction) / ((k * np.pi) ** 2 * (1.0 - 2.0 * fraction))
            if fraction < 0.5 else mean)
    return Factor((k * np.pi) ** 2 * d0 / length ** 2, mean, core, 1.0 - 2.0 * fraction)


def cylinder_factor(radius, d0, depth, count) -> Factor:
    """Crank eqs. 5.22-5.23: modes of a solid cylinder; the core is r < radius - depth."""
    alpha = jn_zeros(0, count)
    mean = 4.0 / alpha ** 2
    rho = 1.0 - depth / radius
    core = 4.0 * j1(alpha * rho) / (rho * alpha ** 2 * j1(alpha)) if rho > 0 else mean
    return Factor(alpha ** 2 * d0 / radius ** 2, mean, core, max(rho, 0.0) ** 2)


def factors(geometry, d0, depth, counts) -> list[Factor]:
    """The separable directions of a Sheet, a solid Disc (the axial sheet has no core:
    the layer is the rim over the full thickness) or a Bar, with ``counts`` modes each."""
    if isinstance(geometry, Sheet):
        return [sheet_factor(geometry.thickness, d0[2], depth, counts[0])]
    if isinstance(geometry, Disc):
        axial = sheet_factor(geometry.thickness, d0[2], 0.0, counts[1])
        return [cylinder_factor(geometry.outer_radius, d0[0], depth, counts[0]),
                Factor(axial.rates, axial.mean, axial.mean, 1.0)]
    return [sheet_factor(length, d0[axis], depth, count) for length, axis, count in
            zip((geometry.length, geometry.width, geometry.thickness), (0, 1, 2), counts)]


def _dimensions(geometry) -> int:
    return 1 if isinstance(geometry, Sheet) else 2 if isinstance(geometry, Disc) else 3


@dataclass(frozen=True)
class Modes:
    """Product modes: rates, amplitudes of the mean and of the contact-layer mean."""

    rates: np.ndarray
    mean: np.ndarray
    layer: np.ndarray
    tail_rate: float      # the slowest rate of any mode left out or merged


def product_modes(geometry, d0, depth, counts) -> Modes:
    """Outer products of the factors' modes (Crank §5.3: 1 - F multiplies)."""
    parts = factors(geometry, d0, depth, counts)
    rates, mean, core, volume = np.zeros(1), np.ones(1), np.ones(1), 1.0
    for factor in parts:
        rates = (rates[:, None] + factor.rates[None, :]).ravel()
        mean = (mean[:, None] * factor.mean[None, :]).ravel()
        core = (core[:, None] * factor.core[None, :]).ravel()
        volume *= factor.core_share
    layer = mean if volume <= 0.0 else (mean - volume * core) / (1.0 - volume)
    return Modes(rates, mean, layer, min(float(f.rates[-1]) for f in parts))


def lump(modes: Modes, per_octave: int) -> Modes:
    """Modes whose rates lie in one bin of 1/``per_octave`` octave merged into one: summed
    amplitudes at their weighted mean rate (a mode's miss y - Ms changes little across a
    narrow bin of rates; the error is measured by halving the bins, ``modal_history``).
    A bin of one mode is exact; ``tail_rate`` becomes the slowest rate merged."""
    bins = np.floor(np.log2(modes.rates / modes.rates.min()) * per_octave).astype(int)
    _, index, members = np.unique(bins, return_inverse=True, return_counts=True)
    weight = np.abs(modes.mean) + np.abs(modes.layer) + 1e-300
    total = np.bincount(index, weight)
    rates = np.bincount(index, weight * modes.rates) / total
    merged = rates[members > 1]
    return Modes(rates, np.bincount(index, modes.mean), np.bincount(index, modes.layer),
                 min(modes.tail_rate, float(merged.min()) if merged.size else np.inf))


@dataclass(frozen=True)
class Forcing:
    """Ms at the nodes of the march: its right values, left limits, rescaled times, and
    where the outputs sit."""

    tau: np.ndarray
    right: np.ndarray
    left: np.ndarray
    outputs: np.ndarray   # node index of each requested time
    interpolation: float  # bound of |Ms - its piecewise-linear-in-tau stand-in|


def _pieces(exposure, clock, tolerance) -> tuple[np.ndarray, float]:
    """Pieces per row so that Ms is linear in tau within ``tolerance``: the deviation from
    linear, largest of three interior samples (the rate may change several-fold along a
    row, so the tau-midpoint is not the t-midpoint), falls as 1 / pieces^2 (smooth Ms)."""
    edges = clock.edges
    start, end = edges[:-1], edges[1:]
    rows = np.arange(start.size)
    span = np.maximum(clock.cumulative[1:] - clock.cumulative[:-1], 1e-300)
    first = np.asarray(exposure.surface_moisture(start), float)
    last = np.asarray(exposure.surface_before(end), float)
    deviation = np.zeros(start.size)
    for where in (0.25, 0.5, 0.75):
        inside = start + where * (end - start)
        share = clock.partial(rows, start, inside) / span
        linear = first + (last - first) * share
        deviation = np.maximum(deviation, np.abs(
            np.asarray(exposure.surface_moisture(inside), float) - linear))
    deviation = np.where(clock.ramp, deviation, 0.0)
    pieces = np.clip(np.ceil(np.sqrt(deviation / tolerance)), 1, MAX_PIECES).astype(int)
    return pieces, float(np.max(deviation / pieces ** 2, initial=0.0))


def forcing(exposure, clock: RescaledTime, times, tolerance) -> Forcing:
    """Nodes: the rows' edges, rows cut into pieces (``_pieces``), and the output times."""
    edges = clock.edges
    pieces, interpolation = _pieces(exposure, clock, tolerance)
    row = np.repeat(np.arange(pieces.size), pieces)
    within = np.arange(row.size) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    cuts = edges[row] + (edges[row + 1] - edges[row]) * within / pieces[row]
    nodes = np.unique(np.concatenate([cuts, edges[-1:], times]))
    return Forcing(clock(nodes), np.asarray(exposure.surface_moisture(nodes), float),
                   np.asarray(exposure.surface_before(nodes), float),
                   np.searchsorted(nodes, times), interpolation)


def relax(rates, force: Forcing, projection, keep) -> np.ndarray:
    """Misses e_n = y_n - Ms(tau-) of dy/dtau = rates (Ms - y), y = Ms(0-) at the start,
    advanced by the exact update for Ms linear in tau between nodes (kept relative to Ms
    against round-off), projected (``@ projection``) at the ``keep`` nodes."""
    values = np.zeros((force.tau.size, projection.shape[1]))
    e = np.zeros(rates.size)
    wanted = np.zeros(force.tau.size, bool)
    wanted[keep] = True
    dtau = np.diff(force.tau)
    slope = (force.left[1:] - force.right[:-1]) / np.maximum(dtau, 1e-300)
    step_at = force.left - force.right   # minus the step of Ms at each node
    for begin in range(0, dtau.size, CHUNK):
        step = dtau[begin:begin + CHUNK, None] * rates[None, :]
        decay = np.exp(-step)
        lag = -np.expm1(-step) / rates[None, :]
        for i in range(step.shape[0]):
            k = begin + i
            e = (e + step_at[k]) * decay[i] - slope[k] * lag[i]
            if wanted[k + 1]:
                values[k + 1] = e @ projection
    return values[keep]


def march(modes: Modes, force: Forcing) -> np.ndarray:
    """(mean, layer) at the outputs, shape (n_outputs, 2): the kept modes advanced exactly,
    the dropped ones at Ms (static correction)."""
    amplitudes = np.stack([modes.mean, modes.layer], axis=1)
    kept = amplitudes.sum(axis=0)
    misses = relax(modes.rates, force, amplitudes, force.outputs)
    at = force.outputs
    return (misses + kept[None, :] * force.left[at, None]
            + (1.0 - kept)[None, :] * force.right[at, None])


def step_corrections(geometry, d0, depth, modes: Modes, force: Forcing,
                     response=None) -> np.ndarray:
    """Each step J of Ms (the initial one, held segments): J times the transient of the
    modes left out or merged, -J (u_exact - u_modes)(age), for the outputs it reaches;
    ``response(age)`` -> (mean, layer) replaces ``exact.step_response`` (a planform's
    own modes times the sheet, ``planmodes``)."""
    response = response or (lambda age: step_response(geometry, d0, age, depth))
    jumps = force.right - force.left
    jumps[np.abs(jumps) <= 1e-12 * np.max(np.abs(force.right))] = 0.0  # round-off of ramps
    out_tau = force.tau[force.outputs]
    correction = np.zeros((out_tau.size, 2))
    reach = TRANSIENT_CUTOFF / modes.tail_rate
    for k in np.flatnonzero(jumps):
        age = out_tau - force.tau[k]
        near = (force.outputs >= k) & (age < reach)
        if not near.any():
            continue
        exact = 1.0 - np.stack(response(age[near]), axis=1)
        kept = np.exp(-np.outer(age[near], modes.rates)) @ np.stack([modes.mean, modes.layer], 1)
        correction[near] -= jumps[k] * (exact - kept)
    return correction


def modal_history(geometry, diffusivity, exposure, times, accuracy, surface_layer_depth=5e-4):
    """Mean and contact-layer mean (weight %) at ``times`` (s), and the error estimate
    (relative to the largest swing |Ms - M0| of the record, as ``accuracy`` is): the
    interpolation bound plus the change when modes and bins are doubled."""
    times = np.asarray(times, float)
    d0 = diffusivity.pre_exponential
    clock = RescaledTime(diffusivity, exposure)
    swing = _swing(exposure, clock)
    if swing == 0.0:
        flat = np.full(times.size, exposure.initial_moisture)
        return {"mean": flat, "surface": flat.copy()}, 0.0
    tolerance = accuracy * swing
    force = forcing(exposure, clock, times, INTERPOLATION_SHARE * tolerance)
    counts, per_octave = [FIRST_COUNT] * _dimensions(geometry), FIRST_PER_OCTAVE
    values = _lumped_history(geometry, d0, surface_layer_depth, force, counts, per_octave)
    while True:
        coarse = values
        counts, per_octave = [2 * c for c in counts], 2 * per_octave
        values = _lumped_history(geometry, d0, surface_layer_depth, force, counts, per_octave)
        change = float(np.max(np.abs(values - coarse)))
        if (change <= (1.0 - INTERPOLATION_SHARE) * tolerance
                or np.prod(counts) * 2 ** len(counts) > MAX_PRODUCT):
            break
    error = (change + force.interpolation) / swing
    return {"mean": values[:, 0], "surface": values[:, 1]}, error


def _lumped_history(geometry, d0, depth, force: Forcing, counts, per_octave) -> np.ndarray:
    """(mean, layer) at the outputs from ``counts`` modes per factor lumped into bins of
    1/``per_octave`` octave, the rest following Ms at once, steps corrected exactly."""
    modes = lump(product_modes(geometry, d0, depth, counts), per_octave)
    return march(modes, force) + step_corrections(geometry, d0, depth, modes, force)


def _swing(exposure, clock) -> float:
    """The largest |Ms - M0| over the record (the scale ``accuracy`` is relative to)."""
    edges = clock.edges
    values = np.concatenate([np.asarray(exposure.surface_moisture(edges), float),
                             np.asarray(exposure.surface_before(edges), float)])
    return float(np.max(np.abs(values - exposure.initial_moisture)))
