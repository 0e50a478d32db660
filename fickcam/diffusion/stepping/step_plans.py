"""The backward-Euler step plan in scaled time.

From each environment change the steps restart at ``first_step`` and double every
``steps_per_doubling`` steps (geometric growth in blocks of equal size, so one
factorisation serves a whole block); requested output times are step boundaries.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..accuracy.error_model import FIRST_STEP
from ..problem.cache import RunCache, run_cache


@dataclass(frozen=True)
class StepPlan:
    """Step boundaries in scaled time with the surface value at each and the outputs.

    Parameters
    ----------
    nodes : numpy.ndarray
        The step boundaries in scaled time tau* [-].
    times : numpy.ndarray
        The physical time of each node [s].
    surface : numpy.ndarray
        g(t) at each node, right-continuous [weight %].
    surface_before : numpy.ndarray
        g(t-) at each node, the value a step ending there sees [weight %].
    outputs : numpy.ndarray
        The node index of each requested time [-].
    restarts : numpy.ndarray
        The node index of each environment change [-].
    """

    nodes: np.ndarray
    times: np.ndarray       # s, the physical time of each node
    surface: np.ndarray     # weight %, g(t) at each node (right-continuous)
    surface_before: np.ndarray  # weight %, g(t-) at each node (left limit: a step ending there)
    outputs: np.ndarray     # node index of each requested time
    restarts: np.ndarray    # node index of each environment change

    @classmethod
    def without_jumps(cls, nodes: np.ndarray, surface: np.ndarray, outputs: np.ndarray,
                      times: np.ndarray | None = None) -> "StepPlan":
        """A plan whose surface value has no jumps at the nodes, restarted only at 0.

        Parameters
        ----------
        nodes : numpy.ndarray
            The step boundaries in scaled time tau* [-], rising.
        surface : numpy.ndarray
            The surface moisture at each node [weight %].
        outputs : numpy.ndarray of int
            The node indices recorded [-].
        times : numpy.ndarray, optional
            The physical times of the nodes [s]; None: the nodes themselves label errors.

        Returns
        -------
        StepPlan
            The plan, its left limits its surface values.
        """
        return cls(nodes, nodes if times is None else times, surface, surface, outputs,
                   np.array([0]))


def geometric_steps(start: float, stop: float, first_step: float,
                    steps_per_doubling: int, max_step: float = np.inf) -> np.ndarray:
    """Step boundaries from ``start`` to ``stop`` with geometrically growing steps.

    The step begins at ``first_step`` and doubles every ``steps_per_doubling`` steps,
    capped at ``max_step``; the last step is cut to end at ``stop``.

    Parameters
    ----------
    start, stop : float
        The first and the last boundary, in scaled time tau* [-].
    first_step : float
        The first step [-] (scaled time).
    steps_per_doubling : int
        Steps of equal size before the step doubles.
    max_step : float
        The largest step allowed [-] (scaled time).

    Returns
    -------
    numpy.ndarray
        The boundaries [-], rising from ``start`` to ``stop``.
    """
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
    """All step boundaries in scaled time: geometric from each change, outputs inserted.

    Inside a ramp segment the step is also limited to 1/``ramp_steps`` of the
    ramp so that the moving surface value is followed.

    Parameters
    ----------
    change_taus : numpy.ndarray
        The environment's change times, scaled (tau*) [-], rising.
    output_taus : numpy.ndarray
        The requested output times, scaled [-].
    first_step : float
        The step [-] each geometric sequence starts from.
    steps_per_doubling : int
        Steps of equal size before the step doubles.
    ramp : numpy.ndarray of bool, optional
        Per segment, whether the surface value ramps over it (None: all held).
    ramp_steps : int
        The least number of steps across a ramp segment.

    Returns
    -------
    numpy.ndarray
        The unique step boundaries [-], rising, round-off slivers merged.
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
    return drop_slivers(nodes, first_step)


def drop_slivers(nodes: np.ndarray, first_step: float) -> np.ndarray:
    """Merge step boundaries closer than 1e-9 of the first step (round-off duplicates).

    Parameters
    ----------
    nodes : numpy.ndarray
        Rising step boundaries in scaled time [-].
    first_step : float
        The first step [-], the scale of what counts as a duplicate.

    Returns
    -------
    numpy.ndarray
        ``nodes`` with each boundary too close to its predecessor removed [-].
    """
    keep = np.concatenate([[True], np.diff(nodes) > 1e-9 * first_step])
    return nodes[keep]


def nearest_nodes(nodes: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Find the index of the node nearest each value.

    An output merged into a node by ``drop_slivers`` maps to that node, not to the next.

    Parameters
    ----------
    nodes : numpy.ndarray
        Rising step boundaries [-] (scaled time).
    values : numpy.ndarray
        The times to locate [-], in the same scale.

    Returns
    -------
    numpy.ndarray of int
        For each value, the index of its nearest node.
    """
    nodes, values = np.asarray(nodes, float), np.asarray(values, float)
    upper = np.clip(np.searchsorted(nodes, values), 1, max(nodes.size - 1, 1))
    lower = upper - 1
    closer_below = np.abs(values - nodes[lower]) <= np.abs(nodes[upper] - values)
    return np.where(closer_below, lower, upper) if nodes.size > 1 else np.zeros(values.size, int)


def inverse_time(tau_nodes: np.ndarray, tau_of_t, change_times: np.ndarray) -> np.ndarray:
    """Physical times of scaled-time nodes: t(tau*), the inverse of the clock.

    tau*(t) is sampled at 257 points per segment and interpolated linearly (exact on
    held segments, where tau* is linear in t; tau* is strictly increasing).

    Parameters
    ----------
    tau_nodes : numpy.ndarray
        The scaled times to map back [-].
    tau_of_t : callable
        The clock: physical time [s] -> scaled time [-].
    change_times : numpy.ndarray
        The environment's change times [s], the segments' edges.

    Returns
    -------
    numpy.ndarray
        The physical times [s] of ``tau_nodes``.
    """
    edges = np.asarray(change_times, float)
    samples = np.unique(np.concatenate([np.linspace(a, b, 257) for a, b in
                                        zip(edges[:-1], edges[1:])]))
    taus = tau_of_t(samples)
    return np.interp(tau_nodes, taus, samples)



def earliest_output(change_stars: np.ndarray, output_stars: np.ndarray) -> float:
    """Shortest time from an environment change to a later output.

    Parameters
    ----------
    change_stars : numpy.ndarray
        The change times in scaled time [-], rising.
    output_stars : numpy.ndarray
        The output times in scaled time [-].

    Returns
    -------
    float
        The least positive gap [-], at least 1000 first steps; 1 if no output follows a
        change.
    """
    gaps = []
    for tau in output_stars:
        before = change_stars[change_stars < tau]
        if before.size:
            gaps.append(tau - before[-1])
    return max(min(gaps), 1e3 * FIRST_STEP) if gaps else 1.0


AGES_PER_DECADE = 64  # more than MAX_AGES ages (a long record) are thinned to the least and
MAX_AGES = 2048       # the largest in each bin of 1/AGES_PER_DECADE decade


def output_ages(change_stars: np.ndarray, output_stars: np.ndarray, ramp: np.ndarray,
                ramp_points: int = 17, cache: RunCache | None = None) -> np.ndarray:
    """The ages at which the outputs read the response to each surface change.

    An age is tau*_out - tau*_change > 0 (the terms of Duhamel's sum, Crank 1975 eq.
    4.34): one per step, ``ramp_points`` spread over each ramp segment; a long record's
    ages are thinned to the least and largest of each 1/64 decade. Computed once per run
    for the plan and the solve of every part with the same scaled history (the links of
    a four-bar; a year of rows costs ~0.05 s).

    Parameters
    ----------
    change_stars : numpy.ndarray
        tau* of the exposure's changes [-], rising.
    output_stars : numpy.ndarray
        tau* of the outputs [-].
    ramp : numpy.ndarray of bool
        Per segment, whether the surface value ramps over it.
    ramp_points : int
        Sources spread over each ramp segment.
    cache : RunCache, optional
        The run's cache (None: a fresh one).

    Returns
    -------
    numpy.ndarray
        The distinct ages [-], rising, read-only.

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    """
    arrays = (np.asarray(change_stars, float), np.asarray(output_stars, float),
              np.asarray(ramp, bool))
    return run_cache(cache).get(("output ages", *(a.tobytes() for a in arrays), ramp_points),
                                lambda: _output_ages(*arrays, ramp_points))


def _output_ages(change_stars: np.ndarray, output_stars: np.ndarray, ramp: np.ndarray,
                 ramp_points: int = 17) -> np.ndarray:
    """The ages tau*_out - tau*_change > 0 at which the outputs read the response to each
    surface change (Duhamel's sum, Crank 1975 eq. 4.34): one per step, ``ramp_points``
    spread over each ramp segment (a ramp is a continuum of small steps). A long record's
    ages fill the span densely: past ``MAX_AGES`` only the least and the largest of each
    bin of 1/``AGES_PER_DECADE`` decade are kept (what the error models read is smooth in
    age)."""
    change_stars = np.asarray(change_stars, float)
    start, stop = change_stars[:-1], change_stars[1:]
    spread = np.asarray(ramp, bool) & (np.arange(start.size) > 0)
    share = np.linspace(0.0, 1.0, ramp_points)[None, :] * spread[:, None]
    sources = np.unique(start[:, None] + (stop - start)[:, None] * share)
    outputs = np.asarray(output_stars, float)
    older = np.searchsorted(sources, outputs, side="left")  # each output's ages > 0
    if older.max(initial=0) > MAX_AGES:
        # more than MAX_AGES distinct ages in one output's row alone: thin each row (its
        # ages fall along it) to its bins' ends, then those (the same least and largest)
        return _thinned(np.unique(np.concatenate(
            [np.empty(0)] + [_bin_ends(out, sources[:n]) for out, n in zip(outputs, older)])))
    found = np.unique(np.concatenate(
        [np.empty(0)] + [out - sources[:n] for out, n in zip(outputs, older)]))
    if found.size == 0:
        return np.array([1.0])
    return found if found.size <= MAX_AGES else _thinned(found)


def _bins(ages: np.ndarray) -> np.ndarray:
    return np.floor(np.log10(ages) * AGES_PER_DECADE)


def _thinned(found: np.ndarray) -> np.ndarray:
    """The least and the largest of sorted ``found`` in each bin of 1/AGES_PER_DECADE decade."""
    bins = _bins(found)
    first = np.flatnonzero(np.diff(bins, prepend=-np.inf) > 0)
    last = np.flatnonzero(np.diff(bins, append=np.inf) > 0)
    return np.unique(found[np.concatenate([first, last])])


def _bin_ends(output: float, sources: np.ndarray) -> np.ndarray:
    """The first and the last of the ages ``output - sources`` (``sources`` rising, all
    before the output: the ages fall along them) in each bin they cross, without reading
    every age: each bin's edge is located among the sources by bisection, the bins are
    read at the sources either side of it, and between two read sources whose bins differ
    but which are not neighbours every source is read (so the ends are those the bins of
    every age give)."""
    size = sources.size
    if size == 0:
        return np.empty(0)

    def ages(at):
        return output - sources[at]

    ends = np.array([0, size - 1])
    newest, oldest = _bins(ages(ends))
    edges = 10.0 ** (np.arange(oldest + 1.0, newest + 1.0) / AGES_PER_DECADE)
    near = np.searchsorted(sources, output - edges, side="right")
    probe = np.unique(np.clip(np.concatenate([near - 1, near, ends]), 0, size - 1))
    gaps = np.flatnonzero(np.diff(_bins(ages(probe))))
    apart = probe[gaps + 1] > probe[gaps] + 1
    turns = np.concatenate([probe[gaps[~apart]]] + [
        probe[g] + np.flatnonzero(np.diff(_bins(ages(np.arange(probe[g], probe[g + 1] + 1)))))
        for g in gaps[apart]])
    return ages(np.concatenate([ends, turns, turns + 1]))
