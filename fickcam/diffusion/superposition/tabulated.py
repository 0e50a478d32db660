r"""Duhamel's sum over a long climate record from a tabulated unit-step response: cost
linear in the rows whatever the kernel (the plane model's planform x sheet, its fields,
an exact field).

With Ms linear in the rescaled time tau between the nodes of the record (``forcing``:
rows cut into pieces where Ms curves in tau), Duhamel's sum (Carslaw & Jaeger 1959
§1.14; Crank 1975 §4.2.1, eq. 4.34) over each piece is exact in closed form in the step
response K and its running integral I(w) = int_0^w K(v) dv; summed by parts over the
pieces,

.. math::

    M(\tau) - M_0 = \sum_i J_i\, K(\tau - \tau_i) + \sum_i (s_i - s_{i-1})\, I(\tau - \tau_i),

J_i the step of Ms at node i, s_i its slope in tau after it. K is tabulated once, on a
grid uniform in x = log w, and I from it (each cell integrates the cubic through four
values of dI/dx = K(e^x) e^x, smooth in x). K is read by four-point Lagrange
interpolation in x, I by cubic Hermite interpolation with its exact slope K e^x (so a
ramp piece, a difference of I at two close ages, is as accurate as K, to O(h^3));
below the grid by the short-time law K ~ sqrt(w) (Crank 1975 eq. 4.20; I ~ w^1.5).
Each output is a weighted sum of the two tables, the weights of every node gathered at
once (``np.bincount``): no work per row in Python, and fields cost one matrix product.
The tabulation error is measured by reading every second grid point alone (the error
falls as h^3: the change, reported, is about 7x the error); the grid is refined until
that change is within its share of the tolerance.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
  Clarendon Press.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..accuracy.budget import TABLE_SHARE, TABULATED_INTERPOLATION_SHARE
from ..forcing.clock import clock_of
from ..forcing.record import Forcing, forcing
from ..problem.cache import RunCache, run_cache
from ..problem.exposure import swing as swing_of

FIRST_PER_DECADE = 16    # grid points per decade of age to start with; doubled while the
MAX_PER_DECADE = 256     #   grid and its every second point read differently
SHORT_TIME = 1e-6        # the grid starts at this share of the fastest diffusion time
#   (below it K = K(w0) sqrt(w / w0), Crank eq. 4.20, relative error ~sqrt(1e-6); the
#   ages there weigh ~w0^1.5)
TABLE_ENTRIES = 20_000_000  # grid points x kernel outputs at most (fields: memory)
SLIVER = 1e-10           # pieces shorter than this share of the span act as steps (round-off)
ROUND_OFF = 1e-12        # a step of Ms smaller than this share of Ms is a ramp's round-off
FIELD_PER_DECADE = 32    # fields (wide kernels): one table at this density, not refined
JUMP_FACTOR = 50.0       # a cubic missing a node by this x the median miss marks a step of K
JUMP_FLOOR = 1e-9        # ... and steps of K below this (of the unit step) are none
SECTIONS = 3             # rounds locating a step, each cutting its interval into
SECTION_POINTS = 15      #   16 (to 16^-3 = 2.4e-4 of a cell: Ms moves little over it)
CHUNK = 4096             # ages per kernel call (fields: memory)
PAIR_CHUNK = 2 ** 17     # (output, node) pairs binned at once (in cache: ~1 MB an array)


@dataclass(frozen=True)
class Table:
    """A unit-step response K and its running integral I, tabulated uniformly in log age.

    The ages are w_j = exp(start + j step) (rescaled seconds); the steps of K
    (``jumps``) are taken out of both and summed exactly.

    Parameters
    ----------
    start : float
        log of the first age, log(w_0 / 1 s) [-].
    end : float
        log of the last age [-]: every grid of a record ends there.
    step : float
        The grid spacing in log age [-].
    kernel : numpy.ndarray
        K [-] at the grid's ages, shape (n, m) for m kernel outputs.
    integral : numpy.ndarray
        I = int_0^w K [s] at the grid's ages, shape (n, m).
    jumps : tuple
        The steps of K: pairs of age [s] and size [-] (shape (m,)).
    raw : numpy.ndarray or None
        K with its steps [-] (what a finer table reuses).
    """

    start: float
    end: float     # log of the last age: every grid of a record ends there
    step: float
    kernel: np.ndarray
    integral: np.ndarray
    jumps: tuple = ()
    raw: np.ndarray | None = None  # K with its steps (what a finer table reuses)

    def coarse(self) -> "Table":
        """Every second grid point: the reading whose difference measures the error."""
        return Table(self.start, self.end, 2.0 * self.step, self.kernel[::2],
                     self.integral[::2], self.jumps)


def _evaluate(kernel, ages: np.ndarray) -> np.ndarray:
    """K at flat ``ages``, shape (ages, m), in chunks (a field kernel is wide)."""
    parts = [np.asarray(kernel(ages[i:i + CHUNK]), float).reshape(ages[i:i + CHUNK].size, -1)
             for i in range(0, ages.size, CHUNK)]
    return np.concatenate(parts, axis=0)


# integral over a grid cell of the cubic through four equally spaced points (spacing 1):
# the middle cell, and the first cell of a one-sided stencil (Newton-Cotes weights)
_MIDDLE_CELL = np.array([-1.0, 13.0, 13.0, -1.0]) / 24.0
_FIRST_CELL = np.array([9.0, 19.0, -5.0, 1.0]) / 24.0


def tabulate(kernel, first: float, last: float, per_decade: int,
             coarser: "Table | None" = None) -> Table:
    """Tabulate a step response K and its running integral I on a grid in log age.

    The grid has an odd number of points from ``first`` or below to ``last`` (so that
    every second point, ``Table.coarse``, also covers it), ``per_decade`` points a decade.
    Steps of K (``_jumps``) are taken out first. I(w0) = (2/3) K(w0) w0 (K ~ sqrt(w)
    below, Crank 1975 eq. 4.20), then each cell integrates the cubic through four grid
    values of K(e^x) e^x (smooth in x): K is evaluated at the grid points only, and not
    again where the ``coarser`` table (half the points a decade) has them; its steps are
    kept.

    Parameters
    ----------
    kernel : callable
        K(w): the unit-step response [-] at rescaled ages w [s].
    first : float
        The youngest age to cover [s] (rescaled).
    last : float
        The oldest age [s] (rescaled), the grid's end.
    per_decade : int
        Grid points per decade of age.
    coarser : Table, optional
        The same kernel's table at half the density, whose values are reused.

    Returns
    -------
    Table
        K [-] and I [s] on the grid.
    """
    step = math.log(10.0) / per_decade
    half = max(3, math.ceil(math.log(max(last / first, 1.0)) / (2.0 * step)))
    back = np.arange(2 * half, -1, -1)  # points counted from the end
    x = math.log(last) - step * back  # ends at ``last``: a step response known up to the
    #   last output (the plane's mesh) is held flat past it, a kink
    if coarser is None:
        values, jumps = _evaluate(kernel, np.exp(x)), None
    else:
        known = (back % 2 == 0) & (back // 2 < coarser.raw.shape[0])
        values = np.empty((x.size, coarser.raw.shape[1]))
        values[known] = coarser.raw[::-1][back[known] // 2]
        values[~known] = _evaluate(kernel, np.exp(x[~known]))
        jumps = list(coarser.jumps)
    raw = values
    jumps = _jumps(kernel, x, values) if jumps is None else jumps
    for age, size in jumps:
        values = values - size[None, :] * (x >= math.log(age))[:, None]
    density = values * np.exp(x)[:, None]      # dI/dx
    windows = np.lib.stride_tricks.sliding_window_view(density, 4, axis=0)  # (n-3, m, 4)
    cells = np.concatenate([(windows[:1] @ _FIRST_CELL), windows @ _MIDDLE_CELL,
                            (windows[-1:, :, ::-1] @ _FIRST_CELL)]) * step
    integral = np.cumsum(np.concatenate([(2.0 / 3.0) * values[:1] * math.exp(x[0]), cells]),
                         axis=0)
    return Table(float(x[0]), float(x[-1]), step, values, integral, tuple(jumps), raw)


def _jumps(kernel, x: np.ndarray, values: np.ndarray) -> list[tuple[float, np.ndarray]]:
    """Steps of K between grid points (the plane model's blend switches from the outline's
    expansion to the mesh; cubic interpolation across a step would not converge): cells
    where the cubic through the four neighbours misses both end nodes, with opposite
    signs, by ``JUMP_FACTOR`` x the median miss; each step located by bisection between
    the cubics extrapolated from either side, its size K(w+) - K(w-). Narrow kernels only
    (fields are taken smooth)."""
    if values.shape[1] > 2 or values.shape[0] < 10:
        return []
    miss = np.zeros(values.shape)
    miss[2:-2] = values[2:-2] - (-values[:-4] + 4 * values[1:-3] + 4 * values[3:-1]
                                 - values[4:]) / 6.0
    column = np.argmax(np.max(np.abs(miss), axis=0))
    m = miss[:, column]
    threshold = max(JUMP_FACTOR * float(np.median(np.abs(m[2:-2]))), JUMP_FLOOR)
    cells = np.flatnonzero((np.abs(m[:-1]) > threshold) & (np.abs(m[1:]) > threshold)
                           & (m[:-1] * m[1:] < 0))
    found = []
    for cell in cells[(cells >= 3) & (cells + 4 < x.size)]:
        low, high = _bisect(kernel, x, values[:, column], column, cell)
        size = (_evaluate(kernel, np.array([math.exp(high)]))
                - _evaluate(kernel, np.array([math.exp(low)])))[0]
        if np.max(np.abs(size)) > JUMP_FLOOR:
            found.append((math.exp(0.5 * (low + high)), size))
    return found


def _bisect(kernel, x, column_values, column: int, cell: int) -> tuple[float, float]:
    """Narrow [x_cell, x_cell+1] to the step: K at ``SECTION_POINTS`` points across the
    interval in one call; the step lies after the last point the cubic from the left
    (nodes cell-3..cell) predicts better than the cubic from the right (cell+1..cell+4)."""
    left = np.polynomial.Polynomial.fit(x[cell - 3:cell + 1], column_values[cell - 3:cell + 1], 3)
    right = np.polynomial.Polynomial.fit(x[cell + 1:cell + 5], column_values[cell + 1:cell + 5], 3)
    low, high = float(x[cell]), float(x[cell + 1])
    for _ in range(SECTIONS):
        points = np.linspace(low, high, SECTION_POINTS + 2)[1:-1]
        values = _evaluate(kernel, np.exp(points))[:, column]
        on_left = np.abs(values - left(points)) <= np.abs(values - right(points))
        before = int(np.argmin(on_left)) if not on_left.all() else points.size
        low, high = (points[before - 1] if before > 0 else low,
                     points[before] if before < points.size else high)
    return low, high


def _lagrange(table: Table, logs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Indices and weights (k, 4) reading K at ages >= the grid's first (their ``logs``):
    four-point Lagrange in log age."""
    size = table.kernel.shape[0]
    x = (logs - table.start) / table.step
    base = np.clip(np.floor(x).astype(int) - 1, 0, size - 4)
    t = (x - base)[:, None]
    weights = np.concatenate([-(t - 1) * (t - 2) * (t - 3) / 6, t * (t - 2) * (t - 3) / 2,
                              -t * (t - 1) * (t - 3) / 2, t * (t - 1) * (t - 2) / 6], axis=1)
    return base[:, None] + np.arange(4), weights


@dataclass(frozen=True)
class Lattice:
    """Cells in log age on which the readings of the slope changes are binned.

    Cell j is [end + j step, end + (j + 1) step), j = ``bottom``..-1 (the last age in
    cell -1; younger ages in one more cell before ``bottom``); the short-time law's sums
    are kept below cell ``young``.

    Parameters
    ----------
    end : float
        log of the last age [-] (age in rescaled seconds).
    step : float
        The cells' width in log age [-].
    bottom : int
        Index of the first cell.
    young : int
        Cells below this index are read by the short-time law.
    """

    end: float
    step: float
    bottom: int
    young: int

    @property
    def cells(self) -> int:
        return 1 - self.bottom


def _lattice(table: Table, first: float) -> tuple[Lattice, int]:
    """(the lattice the readings of ``table`` are gathered on, lattice cells per table
    cell). Its points, ``MAX_PER_DECADE`` a decade back from the last age, hold the points
    of every refined grid of the record (each ends at the last age and halves the step of
    the one before), so that the pairs are binned once for all of them; a table off it (a
    capped density) is its own. Cells from 2 decades below the record's ``first`` age
    [rescaled s] (no grid starts lower; every grid starts at or below it)."""
    finest = math.log(10.0) / MAX_PER_DECADE
    ratio = table.step / finest
    if ratio >= 1.0 and ratio == int(ratio) and int(ratio) & (int(ratio) - 1) == 0:
        bottom = math.floor((math.log(first) - table.end) / finest) - 2 * MAX_PER_DECADE
        return Lattice(table.end, finest, bottom, bottom + 2 * MAX_PER_DECADE + 1), int(ratio)
    bottom = 1 - table.kernel.shape[0]
    return Lattice(table.end, table.step, bottom, bottom), 1


def _lattice_sums(where: "Sources", lattice: Lattice) -> tuple[np.ndarray, np.ndarray]:
    """Per output and cell of the ``lattice``: the moments sum c u^q (q = 0..3) of the
    slope changes c at u, their place in the cell (0 to 1), shape (4, outputs, cells),
    and below its ``young`` cell sum c a^1.5 (the short-time law's), (outputs, cells).
    One pass over every (output, node) pair for all the grids on the lattice, in blocks
    of about ``PAIR_CHUNK`` pairs (that stay in the processor's cache)."""
    parts = [_lattice_part(lattice, *block) for block in where.slopes.blocks(PAIR_CHUNK)]
    cells = (np.concatenate([np.empty(0, np.intp)] + [part[0] for part in parts]),
             np.concatenate([np.empty((4, 0))] + [part[1] for part in parts], axis=1))
    young = (np.concatenate([np.empty(0, np.intp)] + [part[2] for part in parts]),
             np.concatenate([np.empty(0)] + [part[3] for part in parts]))

    def summed(at, weights):
        # (an empty ``at`` gives integers from bincount: the sums are floats)
        return np.bincount(at, weights, minlength=where.outputs * lattice.cells).astype(
            float, copy=False).reshape(where.outputs, lattice.cells)
    return np.stack([summed(cells[0], moment) for moment in cells[1]]), summed(*young)


def _lattice_part(lattice: Lattice, rows, ages, coefficient, logs):
    """(output x lattice cell index, the four moments' sums) of each run of pairs in one
    cell (the pairs of a cell are neighbours: ages fall along an output's row), and
    (index, c a^1.5) of the pairs below the ``young`` cell, of a block of pairs."""
    u = logs - lattice.end        # (in place from here: every array is one per pair)
    u /= lattice.step
    cell = np.floor(u)
    np.minimum(cell, -1.0, out=cell)
    u -= cell
    young = np.flatnonzero(cell < lattice.young)
    np.maximum(cell, lattice.bottom - 1.0, out=cell)
    cell -= lattice.bottom - 1.0
    at = rows * lattice.cells
    at += cell.astype(np.intp)
    powers = np.empty((4, u.size))
    powers[0] = coefficient
    for q in range(1, 4):
        np.multiply(powers[q - 1], u, out=powers[q])
    runs = np.flatnonzero(np.diff(at, prepend=-1))
    short = ages[young]
    return (at[runs], np.add.reduceat(powers, runs, axis=1), at[young],
            coefficient[young] * short * np.sqrt(short))


def _hermite_gathered(table: Table, sums: tuple[np.ndarray, np.ndarray], per: int,
                      bottom: int) -> tuple[np.ndarray, np.ndarray]:
    """(outputs, grid points) weights on I and on K reading I at every slope change's age:
    the cubic Hermite interpolant in x = log age with the exact slopes dI/dx = K e^x, so
    that a difference I(a) - I(b) (a ramp piece) is as accurate as K itself, to O(h^3);
    below the grid I = I(w0) (a / w0)^1.5. Summed from a lattice's ``sums``
    (``_lattice_sums``, ``per`` lattice cells a table cell): in a table cell, t = (o + u)
    / per at the o-th lattice cell, so sum c t^p = sum_q C(p, q) o^(p-q) / per^p
    sum c u^q, and the basis functions are cubics in t."""
    moments, short = sums
    size, outputs = table.kernel.shape[0], moments.shape[1]
    origin = -per * (size - 1) - (bottom - 1)   # the table's first cell on the lattice
    offset = np.arange(per, dtype=float)
    expand = np.zeros((4, 4, per))      # [p, q, o]: C(p, q) o^(p-q) / per^p
    for p in range(4):
        for q in range(p + 1):
            expand[p, q] = math.comb(p, q) * offset ** (p - q) / per ** p
    within = moments[:, :, origin:].reshape(4, outputs, size - 1, per)
    t0, t1, t2, t3 = (expand.reshape(4, 4 * per)
                      @ within.transpose(0, 3, 1, 2).reshape(4 * per, -1)
                      ).reshape(4, outputs, size - 1)
    slope = table.step * np.exp(table.start + table.step * np.arange(size - 1))
    on_i, on_k = np.zeros((outputs, size)), np.zeros((outputs, size))
    on_i[:, :-1] = t0 - 3.0 * t2 + 2.0 * t3               # h00 = (1 + 2t)(1 - t)^2
    on_i[:, 1:] += 3.0 * t2 - 2.0 * t3                    # h01 = t^2 (3 - 2t)
    on_k[:, :-1] = slope * (t1 - 2.0 * t2 + t3)           # h10 = t (1 - t)^2
    on_k[:, 1:] += slope * math.exp(table.step) * (t3 - t2)  # h11 = t^2 (t - 1)
    on_i[:, 0] += np.sum(short[:, :origin], axis=1) / math.exp(1.5 * table.start)
    return on_i, on_k


@dataclass(frozen=True)
class Sources:
    """Where Duhamel's sum reads the tables, shared by every kernel read on a record.

    Output row, age, coefficient and log age (taken
    once for every table read) of the steps (K), the changes of slope (I) as ``Pairs``
    (many: listed block by block when read), and their prefix sums (``Ramps``).
    ``kept`` keeps (in the run's cache) what depends on the grid and not on the kernel (the
    interpolation weights gathered per output and grid point, the steps of K summed at an
    age), so that
    every kernel read on one grid (mean, contact layer, fields, every part sharing the
    record) costs a matrix product, not a pass over every (output, node) pair.

    Parameters
    ----------
    steps : tuple of numpy.ndarray
        Per (output, step of Ms) pair: output row, age [s], jump [weight %], log age [-].
    slopes : Pairs
        The (output, change of slope) pairs; the coefficients in [weight %/s].
    outputs : int
        The number of outputs.
    ramps : Ramps
        The slope changes' prefix sums.
    cache : RunCache
        The run's cache, which keeps the readings.
    """

    steps: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]
    slopes: "Pairs"
    outputs: int
    ramps: "Ramps"
    cache: RunCache = field(compare=False, repr=False)   # the run's: keeps the readings

    def kept(self, key, build):
        """``build()`` (arrays, read-only) once per ``key`` in the run's cache, as long as
        these sources live."""
        return self.cache.get(("duhamel reading", key), build, owner=self)


@dataclass(frozen=True)
class Ramps:
    """The slope changes c_i at their rescaled times r_i (from the record's first node),
    with the prefix sums C_n = sum_{i<n} c_i and S_n = sum_{i<n} c_i r_i, and the outputs'
    times R_k: the ramps' rise past an age w at output k, sum_{r_i < R_k - w} c_i (R_k - w
    - r_i) = (R_k - w) C_n - S_n, is read without a pass over the (output, node) pairs.

    Parameters
    ----------
    times : numpy.ndarray
        r_i, the slope changes' rescaled times from the first node [s].
    changes : numpy.ndarray
        C_n, prefix sums of the slope changes [weight %/s].
    moments : numpy.ndarray
        S_n, prefix sums of c_i r_i [weight %].
    outputs : numpy.ndarray
        R_k, the outputs' rescaled times from the first node [s].
    """

    times: np.ndarray
    changes: np.ndarray
    moments: np.ndarray
    outputs: np.ndarray

    @classmethod
    def of(cls, tau: np.ndarray, change: np.ndarray, outputs: np.ndarray) -> "Ramps":
        nodes = np.flatnonzero(change)
        times = tau[nodes] - tau[0]

        def prefix(values):
            return np.concatenate([[0.0], np.cumsum(values)])
        return cls(times, prefix(change[nodes]), prefix(change[nodes] * times),
                   tau[outputs] - tau[0])

    def rise_past(self, age: float) -> np.ndarray:
        """Per output: sum_i c_i (a_i - ``age``)+ over the slope changes, a_i their ages."""
        before = self.outputs - age
        n = np.searchsorted(self.times, before, side="left")
        return before * self.changes[n] - self.moments[n]


@dataclass(frozen=True)
class Pairs:
    """Every (output, node) pair of a node older than the output and a nonzero
    coefficient, listed by blocks of outputs (``block``, ``blocks``) rather than kept
    (there are outputs x nodes / 2 of them).

    Parameters
    ----------
    tau : numpy.ndarray
        The nodes' rescaled times [s], rising.
    coefficient : numpy.ndarray
        Their coefficients (none zero): jumps [weight %] or slope changes [weight %/s].
    at : numpy.ndarray
        The outputs' rescaled times [s].
    older : numpy.ndarray of int
        Per output, how many of the nodes are older (a leading run).
    """

    tau: np.ndarray          # the nodes' rescaled times (rising)
    coefficient: np.ndarray  # and their coefficients (none zero)
    at: np.ndarray           # the outputs' rescaled times
    older: np.ndarray        # per output: how many of the nodes are older (a leading run)

    @classmethod
    def of(cls, tau: np.ndarray, coefficient: np.ndarray, at: np.ndarray) -> "Pairs":
        nodes = np.flatnonzero(coefficient)
        return cls(tau[nodes], coefficient[nodes], at,
                   np.searchsorted(tau[nodes], at, side="left"))

    def block(self, first: int, last: int):
        """(output row, age, coefficient, log age) of the pairs of outputs first..last-1,
        by output, then by node."""
        older = self.older[first:last]
        rows = np.repeat(np.arange(first, last), older)
        node = np.arange(rows.size) - np.repeat(np.cumsum(older) - older, older)
        ages = self.at[rows] - self.tau[node]
        return rows, ages, self.coefficient[node], np.log(ages)

    def blocks(self, size: int):
        """``block`` of successive outputs, about ``size`` pairs each (an output's pairs
        together)."""
        pairs = np.cumsum(self.older)
        total = int(pairs[-1]) if pairs.size else 0
        cuts = np.searchsorted(pairs, np.arange(size, total, size), side="right")
        edges = np.unique(np.concatenate([[0], cuts, [self.at.size]]))
        return (self.block(first, last) for first, last in zip(edges[:-1], edges[1:]))


def sources(force: Forcing, cache: RunCache | None = None) -> Sources:
    """The steps and slope changes of Ms that Duhamel's sum reads, at each output.

    J_i = Ms(tau_i) - Ms(tau_i-) and s_i - s_i-1 at every node older than each output
    (tau rises with the nodes: the nodes older than an output are a leading run).
    Pieces shorter than ``SLIVER`` of the span act as steps.

    Parameters
    ----------
    force : Forcing
        Ms [weight %] and the rescaled time [s] at the record's nodes.
    cache : RunCache, optional
        The run's cache, which keeps the readings (None: a fresh one).

    Returns
    -------
    Sources
        The jumps [weight %] and slope changes [weight %/s] per output.
    """
    tau = force.tau
    dtau = np.diff(tau)
    rise = force.left[1:] - force.right[:-1]
    sliver = dtau <= SLIVER * max(float(tau[-1] - tau[0]), 1e-300)
    jumps = force.right - force.left
    jumps[np.abs(jumps) <= ROUND_OFF * np.max(np.abs(force.right))] = 0.0  # ramps' left limits
    jumps[1:] += np.where(sliver, rise, 0.0)
    slope = np.concatenate([np.where(sliver, 0.0, rise / np.where(sliver, 1.0, dtau)), [0.0]])
    change = np.diff(np.concatenate([[0.0], slope]))
    at = tau[force.outputs]
    return Sources(Pairs.of(tau, jumps, at).block(0, at.size), Pairs.of(tau, change, at),
                   force.outputs.size, Ramps.of(tau, change, force.outputs),
                   run_cache(cache))


def _gather(rows, index, weights, outputs: int, size: int) -> np.ndarray:
    """(outputs, size): the weights summed per output row and grid point (``index`` (k, j)
    of grid points)."""
    flat = (rows[:, None] * size + index).ravel()
    summed = np.bincount(flat, weights.ravel(), minlength=outputs * size).astype(float, copy=False)
    return summed.astype(float, copy=False).reshape(outputs, size)  # float even when empty


def _split(reading, w0: float, power: float):
    """(the reading on the grid; its weight on the first grid point per output row, by the
    short-time law (age / w0)^power for ages below the grid)."""
    rows, ages, coefficient, logs = reading
    below = ages < w0
    return ((rows[~below], logs[~below], coefficient[~below, None]),
            (rows[below], coefficient[below] * (ages[below] / w0) ** power))


def read(table: Table, where: Sources, first: float) -> tuple[np.ndarray, np.ndarray]:
    """Duhamel's sum M - M0 at the outputs, from a table and from its every second point.

    Steps of Ms read K (four-point Lagrange in log age), slope changes read I (cubic
    Hermite, with K as its slope); the coarse reading (``Table.coarse``, the same first
    age: the readings share their split) measures the tabulation error.

    Parameters
    ----------
    table : Table
        The tabulated step response.
    where : Sources
        Where the sum reads it.
    first : float
        The record's first age [s] (rescaled), where its lattice starts.

    Returns
    -------
    fine, coarse : numpy.ndarray
        M - M0 [weight %], shape (outputs, m), from the table and its every second point.
    """
    return tuple(_read_one(each, where, first) for each in (table, table.coarse()))


def _read_one(table: Table, where: Sources, first: float) -> np.ndarray:
    on_kernel, on_integral = where.kept(
        ("grid", table.start, table.step, table.kernel.shape[0]),
        lambda: _gathered_weights(table, where, first))
    return on_kernel @ table.kernel + on_integral @ table.integral + _read_jumps(table, where)


def _gathered_weights(table: Table, where: Sources, first: float) -> tuple[np.ndarray, np.ndarray]:
    """(outputs, grid points) weights on K and on I: every (output, node) pair's
    interpolation weights summed per output row and grid point (the slope changes through
    the record's lattice, ``_lattice``; ``first`` [rescaled s] the record's first age)."""
    size, n = table.kernel.shape[0], where.outputs
    w0 = math.exp(table.start)
    (rows, logs, coefficient), (low_rows, low) = _split(where.steps, w0, 0.5)
    index, weights = _lagrange(table, logs)
    on_kernel = _gather(rows, index, coefficient * weights, n, size)
    on_kernel[:, 0] += np.bincount(low_rows, low, minlength=n)
    lattice, per = _lattice(table, first)
    sums = where.kept(("lattice", lattice), lambda: _lattice_sums(where, lattice))
    on_integral, on_k = _hermite_gathered(table, sums, per, lattice.bottom)
    on_kernel += on_k
    return on_kernel, on_integral


def _read_jumps(table: Table, where: Sources) -> np.ndarray:
    """The steps of K summed exactly: J_b H(a - w_b) for each step of Ms, J_b (a - w_b)+
    for each change of slope (the integral of a step)."""
    total = np.zeros((where.outputs, table.kernel.shape[1]))
    for age, size in table.jumps:
        total += where.kept(("jump", age), lambda age=age: _past_step(age, where))[:, None] \
            * size[None, :]
    return total


def _past_step(age: float, where: Sources) -> np.ndarray:
    """Per output: the steps of Ms older than ``age`` plus the ramps' rise past it."""
    rows, ages, coefficient, _ = where.steps
    after = np.bincount(rows, coefficient * (ages > age), minlength=where.outputs)
    return after + where.ramps.rise_past(age)


@dataclass(frozen=True)
class LongRecord:
    """One long record's forcing at the outputs, shared by every kernel superposed over it.

    The kernels are the mean, the contact layer and the fields.

    Parameters
    ----------
    force : Forcing
        Ms and the rescaled time at the record's nodes.
    where : Sources
        Where the sum reads the tables.
    swing : float
        The record's moisture swing [weight %].
    tolerance : float
        The error allowed [weight %] (accuracy x swing).
    first : float
        The youngest age tabulated [s] (rescaled).
    last : float
        The oldest age the outputs read [s] (rescaled), the tables' end.
    exposure : Exposure
        The record.
    clock : RescaledTime
        Its rescaled clock.
    cache : RunCache
        The run's cache: tables and readings.
    """

    force: Forcing
    where: Sources
    swing: float
    tolerance: float
    first: float
    last: float
    exposure: object
    clock: object
    cache: RunCache = field(compare=False, repr=False)   # the run's: tables and readings

    @classmethod
    def of(cls, diffusivity, exposure, times, fastest: float, accuracy: float,
           cache: RunCache) -> "LongRecord":
        """``fastest``: the part's shortest diffusion time L^2 / D0 (rescaled s); ``cache``:
        the run's."""
        force, where, swing, tolerance = cache.get(
            ("long record", diffusivity, exposure, np.asarray(times, float).tobytes(), accuracy),
            lambda: _forced(diffusivity, exposure, np.asarray(times, float), accuracy, cache))
        first = SHORT_TIME * fastest
        last = float(np.max(force.tau[force.outputs] - force.tau[0], initial=0.0))
        return cls(force, where, swing, tolerance, first, max(last, 10.0 * first),
                   exposure, clock_of(diffusivity, exposure, cache), cache)

    def at(self, times) -> "LongRecord":
        """This record read at other ``times`` inside its outputs' span (the limit search):
        the nodes gain ``times`` as a solve at both sets would have them, the tables keep
        their grid (``last``), and the sum reads the new outputs only."""
        force = self.force.with_outputs(self.exposure, self.clock, times)
        return replace(self, force=force, where=sources(force, self.cache))

    def superpose(self, kernel, per_decade: int = FIRST_PER_DECADE, refine: bool = True,
                  looser: float = 1.0, same: "KernelKey | None" = None,
                  start: int = 0) -> tuple[np.ndarray, float, int]:
        """(M - M0 at the outputs, shape (outputs, ...kernel outputs); the error relative
        to the swing (tabulation change + Ms interpolation); the points per decade used).
        ``refine``: double the grid while the change exceeds ``TABLE_SHARE`` x tolerance
        (x ``looser``). ``same``: says which kernel this is, so that its tables are taken
        from earlier solves (the same grid gives the same table: results do not change).
        ``start``: a grid density an earlier solve at other outputs refined to; coarser
        grids are built (or taken) as before but not read, the outputs of that solve
        having needed this one (its tables are then reused, not rebuilt)."""
        shape = np.shape(kernel(np.zeros(1)))[1:]
        width = max(int(np.prod(shape)), 1)
        decades = math.log10(self.last / self.first) + 1.0
        cap = max(4, int(TABLE_ENTRIES / (width * decades)) // 2)
        per_decade = min(per_decade, cap)
        table = None
        while True:
            table = self._kept(same, (self.first, self.last, per_decade),
                          lambda coarser=table: tabulate(kernel, self.first, self.last,
                                                         per_decade, coarser))
            if per_decade < start and 2 * per_decade <= min(MAX_PER_DECADE, cap):
                per_decade *= 2
                continue
            fine, coarse = read(table, self.where, self.first)
            change = float(np.max(np.abs(fine - coarse), initial=0.0))
            if (not refine or change <= TABLE_SHARE * looser * self.tolerance
                    or 2 * per_decade > min(MAX_PER_DECADE, cap)):
                break
            per_decade *= 2
        error = (change + self.force.interpolation) / max(self.swing, 1e-300)
        return fine.reshape((fine.shape[0],) + shape), error, per_decade

    def _kept(self, same: "KernelKey | None", grid: tuple, build) -> Table:
        """The table of kernel ``same`` on ``grid`` from an earlier solve of the run, else
        ``build()`` (kept in the run's cache, read-only)."""
        if same is None:
            return build()
        return self.cache.get(("duhamel table", same.key, grid), build, holds=same.holds)

    def field(self, kernel) -> np.ndarray:
        """M - M0 of a wide kernel (a field's cells): one table at ``FIELD_PER_DECADE``,
        not refined (a run's estimate is the mean's)."""
        return self.superpose(kernel, FIELD_PER_DECADE, refine=False)[0]


def _forced(diffusivity, exposure, times: np.ndarray, accuracy: float, cache: RunCache):
    """(Forcing, Sources, swing, tolerance) of a record at ``times``, made once per run for
    the parts that share a material and its exposure (the links of a four-bar)."""
    clock = clock_of(diffusivity, exposure, cache)
    swing = swing_of(exposure)
    tolerance = accuracy * max(swing, 1e-300)
    force = forcing(exposure, clock, times, TABULATED_INTERPOLATION_SHARE * tolerance)
    return force, sources(force, cache), swing, tolerance


@dataclass(frozen=True, eq=False)
class KernelKey:
    """Names a kernel across solves, so that its tables are reused.

    Parameters
    ----------
    key : tuple
        Hashable: what the kernel is and what it depends on.
    holds : tuple
        The objects whose ids ``key`` holds, kept alive with the tables so that no id is
        reused while they are kept.
    """

    key: tuple
    holds: tuple = ()
