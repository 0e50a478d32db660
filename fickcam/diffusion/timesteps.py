"""Rescaled time and the backward-Euler step plan.

Every direction shares one Arrhenius factor a(T) = exp(-Ea/RT), so with
tau(t) = integral_0^t a(T(s)) / a_ref ds Fick's law dc/dt = div(D(T) grad c)
becomes dc/dtau = div(D(T_ref) grad c) with a constant operator (Crank 1975,
§7.2, eq. 7.5: a diffusion coefficient depending on time only).

Step plan: from each environment change the steps restart at ``first_step``
and double every ``steps_per_doubling`` steps (geometric growth in blocks of
equal size, so one factorisation serves a whole block); requested output
times are step boundaries.
"""
from __future__ import annotations

import numpy as np

from .exposure import Diffusivity, Exposure

_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(8)
_RAMP_PANELS = 64


def reference_factor(diffusivity: Diffusivity, exposure: Exposure) -> float:
    """a_ref = the largest Arrhenius factor met in the history (the hottest segment)."""
    t = _sample_times(exposure)
    return float(np.max(diffusivity.arrhenius_factor(exposure.temperature(t))))


def _sample_times(exposure: Exposure) -> np.ndarray:
    edges = np.asarray(exposure.change_times, float)
    inner = [np.linspace(a, b, 9)[:-1] for a, b in zip(edges[:-1], edges[1:])]
    return np.concatenate(inner + [edges[-1:]]) if inner else edges


def rescaled_time(diffusivity: Diffusivity, exposure: Exposure, t: np.ndarray,
                  a_ref: float | None = None) -> np.ndarray:
    """tau(t) = integral_0^t a(T(s))/a_ref ds in seconds at the reference temperature.

    Held segments have constant T (exact); ramps are integrated with 8-point
    Gauss-Legendre on 64 panels per segment (T(t) is smooth inside a ramp).
    """
    a_ref = reference_factor(diffusivity, exposure) if a_ref is None else a_ref
    edges = np.asarray(exposure.change_times, float)
    t = np.asarray(t, float)
    cumulative = np.zeros(edges.size)
    for k in range(edges.size - 1):
        cumulative[k + 1] = cumulative[k] + _segment_integral(
            diffusivity, exposure, edges[k], edges[k + 1], bool(exposure.ramp[k]), a_ref)
    segment = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, edges.size - 2)
    tau = np.empty_like(t)
    for k in np.unique(segment):
        sel = segment == k
        inside = np.minimum(t[sel], edges[k + 1])
        if exposure.ramp[k]:
            tau[sel] = cumulative[k] + np.array([
                _segment_integral(diffusivity, exposure, edges[k], ti, True, a_ref)
                for ti in inside])
        else:  # held: constant factor, tau linear in t
            factor = float(diffusivity.arrhenius_factor(
                exposure.temperature(edges[k:k + 1]))[0]) / a_ref
            tau[sel] = cumulative[k] + (inside - edges[k]) * factor
        beyond = t[sel] > edges[k + 1]  # past the end of the history: hold the last state
        if beyond.any():
            factor = diffusivity.arrhenius_factor(exposure.temperature(edges[-1:]))[0] / a_ref
            tau[np.flatnonzero(sel)[beyond]] += (t[sel][beyond] - edges[k + 1]) * factor
    return tau


def _segment_integral(diffusivity, exposure, start, stop, ramp, a_ref) -> float:
    if stop <= start:
        return 0.0
    if not ramp:
        return (stop - start) * float(diffusivity.arrhenius_factor(
            exposure.temperature(np.array([start])))[0]) / a_ref
    panels = np.linspace(start, stop, _RAMP_PANELS + 1)
    half = 0.5 * np.diff(panels)
    nodes = (panels[:-1] + half)[:, None] + half[:, None] * _GAUSS_NODES[None, :]
    values = diffusivity.arrhenius_factor(exposure.temperature(nodes.ravel())).reshape(nodes.shape)
    return float(np.sum(half[:, None] * _GAUSS_WEIGHTS[None, :] * values) / a_ref)


def geometric_steps(start: float, stop: float, first_step: float,
                    steps_per_doubling: int, max_step: float = np.inf) -> np.ndarray:
    """Step boundaries from ``start`` to ``stop``: ``first_step`` doubling every
    ``steps_per_doubling`` steps, at most ``max_step``; the last step is cut to end at ``stop``."""
    nodes = [start]
    dt, k = first_step, 0
    while nodes[-1] < stop:
        nodes.append(min(nodes[-1] + min(dt, max_step), stop))
        k += 1
        if k % steps_per_doubling == 0:
            dt *= 2.0
    return np.asarray(nodes)


def step_nodes(change_taus: np.ndarray, output_taus: np.ndarray, first_step: float,
               steps_per_doubling: int, ramp: np.ndarray | None = None,
               ramp_steps: int = 32) -> np.ndarray:
    """All step boundaries in tau: geometric from each change, with the outputs inserted.

    Inside a ramp segment the step is also limited to 1/``ramp_steps`` of the
    ramp so that the moving surface value is followed.
    """
    change_taus = np.asarray(change_taus, float)
    pieces = []
    for k in range(change_taus.size - 1):
        start, stop = change_taus[k], change_taus[k + 1]
        limit = (stop - start) / ramp_steps if ramp is not None and ramp[k] else np.inf
        pieces.append(geometric_steps(start, stop, first_step, steps_per_doubling, limit))
    nodes = np.concatenate(pieces + [np.asarray(output_taus, float)])
    nodes = np.unique(nodes[(nodes >= change_taus[0]) & (nodes <= max(change_taus[-1],
                                                                       np.max(output_taus)))])
    return _drop_slivers(nodes, first_step)


def _drop_slivers(nodes: np.ndarray, first_step: float) -> np.ndarray:
    """Merge step boundaries closer than 1e-9 of the first step (round-off duplicates)."""
    keep = np.concatenate([[True], np.diff(nodes) > 1e-9 * first_step])
    return nodes[keep]


def nearest_nodes(nodes: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Index of the node nearest each value (an output merged into a node by
    ``_drop_slivers`` maps to that node, not to the next one)."""
    nodes, values = np.asarray(nodes, float), np.asarray(values, float)
    upper = np.clip(np.searchsorted(nodes, values), 1, max(nodes.size - 1, 1))
    lower = upper - 1
    closer_below = np.abs(values - nodes[lower]) <= np.abs(nodes[upper] - values)
    return np.where(closer_below, lower, upper) if nodes.size > 1 else np.zeros(values.size, int)


def inverse_time(tau_nodes: np.ndarray, tau_of_t, change_times: np.ndarray) -> np.ndarray:
    """t(tau) by interpolating tau(t) sampled at 257 points per segment (exact on held
    segments, where tau is linear in t; tau is strictly increasing)."""
    edges = np.asarray(change_times, float)
    samples = np.unique(np.concatenate([np.linspace(a, b, 257) for a, b in
                                        zip(edges[:-1], edges[1:])]))
    taus = tau_of_t(samples)
    return np.interp(tau_nodes, taus, samples)
