"""A long climate record as the surface forcing of a linear response: Ms piecewise
linear in the rescaled time tau between nodes (the rows, cut where Ms curves in tau, and
the output times), for the tabulated Duhamel sum (``tabulated``), whose cost grows with
the nodes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .clock import RescaledTime

LONG_RECORD = 32         # records with this many segments take the tabulated sum; shorter
#   histories keep Duhamel's panels, exact to 1e-8 (measured: benchmarks/results/tuned_constants.md)
MAX_PIECES = 512         # pieces per row at most


def is_long_record(exposure) -> bool:
    """Tell whether an exposure is a long record (hourly weather, chamber logs).

    Parameters
    ----------
    exposure : Exposure
        The history.

    Returns
    -------
    bool
        True for ``LONG_RECORD`` segments or more.
    """
    return np.asarray(exposure.ramp).size >= LONG_RECORD


@dataclass(frozen=True)
class Forcing:
    """The surface moisture Ms at the nodes of the tabulated sum, and where outputs sit.

    Parameters
    ----------
    tau : numpy.ndarray
        The nodes' rescaled times [s].
    right : numpy.ndarray
        Ms at the nodes [weight %] (right values).
    left : numpy.ndarray
        Ms just before the nodes [weight %] (left limits).
    outputs : numpy.ndarray of int
        The node index of each requested time.
    interpolation : float
        Bound of |Ms - its piecewise-linear-in-tau stand-in| [weight %].
    nodes : numpy.ndarray or None
        The nodes' physical times [s], where known.
    """

    tau: np.ndarray
    right: np.ndarray
    left: np.ndarray
    outputs: np.ndarray   # node index of each requested time
    interpolation: float  # bound of |Ms - its piecewise-linear-in-tau stand-in|
    nodes: np.ndarray | None = None  # the nodes' physical times (s), where known

    def with_outputs(self, exposure, clock: RescaledTime, times) -> "Forcing":
        """The same forcing with ``times`` (inside its span) added as nodes, and the outputs
        at ``times`` only: the nodes a solve at the stored and the new times together would
        have, each evaluated where it is new (tau, Ms are functions of the node alone)."""
        times = np.asarray(times, float)
        new = np.setdiff1d(times, self.nodes)
        nodes = np.concatenate([self.nodes, new])
        order = np.argsort(nodes, kind="stable")

        def merged(old, value):
            return np.concatenate([old, np.asarray(value, float)])[order]
        return Forcing(merged(self.tau, clock(new)),
                       merged(self.right, exposure.surface_moisture(new)),
                       merged(self.left, exposure.surface_before(new)),
                       np.searchsorted(nodes[order], times), self.interpolation, nodes[order])


def linear_pieces(exposure, clock, tolerance) -> tuple[np.ndarray, float]:
    """Pieces per row so that Ms is linear in the rescaled time within ``tolerance``.

    The deviation from linear, the largest of three interior samples (the rate may change
    several-fold along a row, so the tau-midpoint is not the t-midpoint), falls as
    1 / pieces^2 for a smooth Ms.

    Parameters
    ----------
    exposure : Exposure
        The record (surface moisture [weight %] against time [s]).
    clock : RescaledTime
        Its rescaled clock.
    tolerance : float
        The deviation from linear allowed [weight %].

    Returns
    -------
    pieces : numpy.ndarray of int
        Pieces per row, 1 to ``MAX_PIECES``.
    interpolation : float
        The bound of the deviation left [weight %].
    """
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
    """The forcing of a long record on its nodes, for the tabulated Duhamel sum.

    The nodes are the rows' edges, the rows cut into pieces (``linear_pieces``), and the
    output times; rows past the last output are left out (nothing there reaches an
    output).

    Parameters
    ----------
    exposure : Exposure
        The long record: its rows' times [s] and surface moisture [weight %].
    clock : RescaledTime
        t [s] -> tau [s] for that record.
    times : numpy.ndarray
        The output times [s].
    tolerance : float
        The deviation from linear in tau allowed [weight %].

    Returns
    -------
    Forcing
        Ms and the rescaled time at the nodes.
    """
    edges = clock.edges
    pieces, interpolation = linear_pieces(exposure, clock, tolerance)
    row = np.repeat(np.arange(pieces.size), pieces)
    within = np.arange(row.size) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    cuts = edges[row] + (edges[row + 1] - edges[row]) * within / pieces[row]
    nodes = np.unique(np.concatenate([cuts, edges[-1:], times]))
    nodes = nodes[nodes <= np.max(times)]
    return Forcing(clock(nodes), np.asarray(exposure.surface_moisture(nodes), float),
                   np.asarray(exposure.surface_before(nodes), float),
                   np.searchsorted(nodes, times), interpolation, nodes)
