"""``DiffusionResult.extend`` of the concentration-dependent marches (``concentration_dependent``,
``corrected_product``): the result at extra times inside its span read between the steps the solve
already took, instead of a new solve (the limit search's times).

Every swept march records its mean and contact layer (and any other weighted sums asked)
at every step, not only at the outputs; the Richardson pair's two marches share the coarse
plan's nodes (the fine plan is the coarse one bisected), so 2 fine - coarse is known at
every coarse node (``StepRecord``). The steps restart at FIRST_STEP after each exposure change
and double every m steps (``step_plans``): in log(age), age = tau* - tau*_change, the nodes
are about evenly spaced (ln 2 / m apart), and the solution, ~sqrt(age) early and
exponential late (Crank 1975 eq. 4.18, 4.17), is smooth there. A new time is read by the
Lagrange cubic through the 4 nodes of its segment about it, in log(age), and by the
quadratics through the first 3 and the last 3 of them; the larger difference, the size of
the cubic's last term, is the estimate of a quadratic's error and so bounds the cubic's (the error of Lagrange
interpolation is the next divided difference times the nodal polynomial: Hildebrand, F. B.
(1956), Introduction to Numerical Analysis, New York: McGraw-Hill, pp. 43-44; Stoer &
Bulirsch, Introduction to Numerical Analysis §2.1.4).
A segment is (change, next change]: the node at a change ends the segment before it (the
state there is the march's at t-, read with g(t-) as the outputs are), and no stencil
reaches past it, so nothing is interpolated across an exposure change.

The combination of several tracks (the corrected product of ``corrected_product``) is done twice,
on
the cubic and on the quadratic values; the difference of the two results, largest over the
mean and the layer / ``LAYER_TOLERANCE`` and relative to the swing, is the interpolation
estimate of each new time. It is added to the result's estimate; where it exceeds
``INTERPOLATION_SHARE`` of the accuracy (or a time has too few nodes about it), the
result is solved again at its times and the new ones together (logged). So is it where a
new time is younger after its change than every stored output (``younger``), or where the
plan of the stored and new times together has other cells (``fits``, set by
``dispatch.solve``: also a skin's cells, sized at the outputs from the skin's start): the cells are sized for the youngest output after a change
(``step_plans.earliest_output``), and a younger new time reads a layer they do not resolve,
which its interpolation estimate cannot see. Measured: ``benchmarks/dc_extend.py`` (README
"Non-Fickian sorption"); tested: tests/test_sorption_extend.py.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, replace
from typing import Callable, Sequence

import numpy as np

from ..accuracy.budget import LAYER_TOLERANCE
from .step_plans import earliest_output

log = logging.getLogger(__name__)

INTERPOLATION_SHARE = 1.0  # of the accuracy: a larger interpolation estimate re-solves
#   (measured: benchmarks/results/tuned_constants.md).
#   The extended estimate (the stored one + this) can pass the accuracy below it: the limit
#   search then says so (``limitsearch.search_notices``)


@dataclass(frozen=True)
class StepRecord:
    """Weighted sums of a Richardson-combined march at every node of its coarse plan.

    The columns are the mean, the layer and any other weighted sums asked; the plan is
    ``step_plans.StepPlan``'s coarse one.

    Parameters
    ----------
    nodes : numpy.ndarray
        The nodes' scaled times tau* [-].
    values : numpy.ndarray
        The weighted sums [weight %], shape (nodes, columns).
    surface : numpy.ndarray
        The surface moisture g(t-) [weight %] at the nodes.
    changes : numpy.ndarray
        The scaled times [-] of the exposure's changes.
    tau_star : callable
        Physical time [s] -> scaled time [-].
    """

    nodes: np.ndarray     # tau* of the nodes
    values: np.ndarray    # (nodes, columns)
    surface: np.ndarray   # g(t-) at the nodes (weight %)
    changes: np.ndarray   # tau* of the exposure's changes
    tau_star: Callable    # tau* of physical times (s)

    @classmethod
    def of(cls, steps, coarse, fine, scales, exposure) -> "StepRecord":
        """From the coarse and the fine (bisected) march of ``steps`` (their ``track``s)."""
        return cls(steps.nodes, 2.0 * fine.track[::2] - coarse.track, steps.surface_before,
                   scales.tau_star(exposure.change_times), scales.tau_star)

    def with_values(self, values: np.ndarray) -> "StepRecord":
        return replace(self, values=np.asarray(values, float))

    def at(self, times) -> tuple[np.ndarray, np.ndarray]:
        """(cubic, quadratic): the columns at physical ``times`` (module docstring); a time
        on a node takes the node's values in both; NaN where a segment has too few nodes."""
        taus = np.asarray(self.tau_star(np.asarray(times, float)), float)
        cubic = np.full((taus.size, self.values.shape[1]), np.nan)
        quadratic = cubic.copy()
        for i, tau in enumerate(taus):
            cubic[i], quadratic[i] = self._read(float(tau))
        return cubic, quadratic

    def _read(self, tau: float):
        nan = np.full(self.values.shape[1], np.nan)
        tolerance = 1e-12 * max(1.0, abs(tau))
        on = np.flatnonzero(np.abs(self.nodes - tau) <= tolerance)
        if on.size:
            return self.values[on[-1]], self.values[on[-1]]
        segment = np.searchsorted(self.changes, tau, side="left") - 1
        if segment < 0 or segment + 1 >= self.changes.size:
            return nan, nan
        start, stop = self.changes[segment], self.changes[segment + 1]
        inside = np.flatnonzero((self.nodes > start + tolerance) & (self.nodes <= stop + tolerance))
        if inside.size < 4:
            return nan, nan
        x = np.log(self.nodes[inside] - start)
        at = np.log(tau - start)
        j = int(np.searchsorted(x, at))
        if j == 0 or j == x.size:   # before the first step's end or past the segment
            return nan, nan
        four = np.arange(4) + min(max(j - 2, 0), x.size - 4)
        cubic = lagrange(x[four], at) @ self.values[inside[four]]
        lower, upper = (lagrange(x[three], at) @ self.values[inside[three]]
                        for three in (four[:3], four[1:]))
        # the quadratic further from the cubic: one alone can meet it by chance
        return cubic, np.where(np.abs(cubic - lower) >= np.abs(cubic - upper), lower, upper)


def lagrange(x: np.ndarray, at: float) -> np.ndarray:
    """Weights of the Lagrange interpolating polynomial through ``x``, evaluated at ``at``.

    Parameters
    ----------
    x : numpy.ndarray
        The distinct nodes (here log of the age, [-]).
    at : float
        Where the polynomial is evaluated, in the nodes' scale.

    Returns
    -------
    numpy.ndarray
        w with sum_k w_k y_k the polynomial's value at ``at`` [-].

    References
    ----------
    Hildebrand (1956), pp. 43-44 (module docstring).
    """
    weights = np.ones(x.size)
    for k in range(x.size):
        others = np.delete(x, k)
        weights[k] = np.prod((at - others) / (x[k] - others))
    return weights


@dataclass(frozen=True, eq=False)
class Extension:
    """``DiffusionResult.extend`` read between a march's steps, re-solving when unsure.

    Parameters
    ----------
    result : DiffusionResult
        The stored solve.
    tracks : iterable of StepRecord
        The marches' records.
    combine : callable
        ``combine(values, times)``: the tracks' columns at ``times`` (one (n, columns)
        array per track) -> (mean, layer) [weight %].
    scale : float
        The moisture swing [weight %] the estimate is relative to.
    accuracy : float
        The requested relative accuracy [-].
    resolve : callable
        ``resolve(times)``: the solve at ``times`` [s] (the fallback).
    what : str
        Names the solve in log messages.
    fits : callable, optional
        ``fits(times)``: whether a solve at ``times`` [s] keeps the stored solve's cells
        (None: always).
    """

    result: object
    tracks: Sequence
    combine: Callable
    scale: float
    accuracy: float
    resolve: Callable
    what: str = ""
    fits: Callable[[np.ndarray], bool] | None = None

    def younger(self, times) -> bool:
        """Whether ``times`` have an output younger after its change than the stored ones
        (``step_plans.earliest_output``, the plans' t_lo: every plan's cells would change)."""
        track = self.tracks[0]
        return bool(earliest_output(track.changes, track.tau_star(times))
                    < earliest_output(track.changes, track.tau_star(self.result.times)))

    def interpolated(self, times) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(mean, layer, estimate per time) at ``times`` (module docstring)."""
        times = np.asarray(times, float)
        read = [track.at(times) for track in self.tracks]
        mean, layer = self.combine([cubic for cubic, _ in read], times)
        low_mean, low_layer = self.combine([quadratic for _, quadratic in read], times)
        estimate = np.maximum(np.abs(mean - low_mean),
                              np.abs(layer - low_layer) / LAYER_TOLERANCE) / self.scale
        return mean, layer, np.where(np.isfinite(estimate), estimate, np.inf)

    def __call__(self, at):
        result = self.result
        new = np.setdiff1d(np.asarray(at, float), result.times)
        both = np.union1d(result.times, new)
        if self.younger(both) or (self.fits is not None and not self.fits(both)):
            log.debug("%s: %d new times need other cells than the stored solve's: solved again",
                     self.what or result.model, new.size)
            return self.resolve(both)
        mean, layer, estimate = self.interpolated(new)
        worst = float(np.max(estimate, initial=0.0))
        if worst > INTERPOLATION_SHARE * self.accuracy:
            log.debug("%s: %d new times not read between the steps (interpolation estimate "
                     "%.1e > %.1e): solved again", self.what or result.model, new.size, worst,
                     INTERPOLATION_SHARE * self.accuracy)
            return self.resolve(both)
        return replace(result.merged(new, mean, layer),
                       error_estimate=result.error_estimate + worst,
                       reason=f"{result.reason}; {new.size} times read between the march's "
                              f"steps (interpolation estimate {worst:.1e})")


def held_to_plan(result, chosen, replan, resolve):
    """A result whose ``Extension`` re-solves where the plan for the new times changes cells.

    Parameters
    ----------
    result : DiffusionResult
        The solve.
    chosen : Plan
        The plan ``result`` was solved on.
    replan : callable
        times [s] -> the plan for them.
    resolve : callable
        times [s] -> the solve at them.

    Returns
    -------
    DiffusionResult
        ``result``, its ``extend`` (when an ``Extension``) built again with ``fits`` and
        ``resolve``.
    """
    extension = result.extend
    if not isinstance(extension, Extension):
        return result

    def cells(plan):
        return plan.cells, tuple(plan.cells_per_axis), plan.finest, plan.growth
    stored = cells(chosen)
    return replace(result, extend=replace(
        extension, fits=lambda both: cells(replan(both)) == stored, resolve=resolve))
