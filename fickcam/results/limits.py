"""Limits on result variables: the spec a mechanism must hold, and when it first fails.

A scene's ``limits:`` section names result variables and, for each, a band
around the as-designed value (``deviation``) and/or bounds (``max``, ``min``),
in any unit pint knows (:mod:`fickcam.scene.limits` reads them). Each limit reduces its variable to one number per
ageing time (the worst over the cam or crank angle, the parts or the links)
and turns it into a *limit ratio*, 1 at the limit and above 1 out of spec:

- ``deviation`` d:  r = max |x - x_design| / d (the largest deviation over the cycle);
- ``max`` b:        r = 1 + (max x - b) / s,  which is max x / b for b > 0;
- ``min`` b:        r = 1 + (b - min x) / s,  which is 2 - min x / b for b > 0;

with s = |b|, or for a zero bound the size of the as-designed value. With
several entries the ratio is the largest of them. The first ageing time at
which a ratio exceeds 1 is located on the continuous ageing time by re-running
the model inside the bracketing interval (:func:`first_crossings`), in the square
root of the time, to the crossing's own tolerance (:class:`Tolerance`: 0.1 % of it
or 1 h), with an error bound beside it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..diffusion.accuracy.budget import CROSSING_INTERPOLATION_SHARE
from ..errors import format_time
from ..schema import design_name
from ..scene.limits import Limit, from_attrs
from .dataset import report_time_unit
from .query import drift, wrapped_degrees

#: a crossing time's own tolerance: this share of the crossing time, or FLOOR s,
#: whichever is larger (both scaled down where the scene asks a finer diffusion accuracy)
RELATIVE = 1e-3
FLOOR = 3600.0
#: model evaluations per bracket in a sampling round (the first, and any after SECANT_ROUNDS)
POINTS = 4
#: rounds after the first that evaluate only two times straddling the secant's root
SECANT_ROUNDS = 3
#: the times evaluated either side of a guessed crossing are at least and at most these
#: shares of the tolerance away from it (twice the guess's error estimate, within them)
STRADDLE = (0.05, 0.45)
#: the crossing's stated error (``_Bracket.root``): SAFETY times the distance between the
#: cubic's crossing and the closed bracket's chord's, but not below FLOOR_SHARE of the
#: tolerance, nor above the bracket's bound
SAFETY = 2.0
FLOOR_SHARE = 0.1
#: at most this many of the climate's change times inside a bracket are sampled in its
#: first round (evenly chosen where there are more)
CLIMATE_NODES = 256


# ------------------------------------------------------------------- ratios


def _per_time(values: np.ndarray, reduce) -> np.ndarray:
    """Reduce every axis but the first (time); NaN (not a warning) for all-NaN rows."""
    values = np.asarray(values, float).reshape(values.shape[0], -1)
    out = np.full(values.shape[0], np.nan)
    rows = np.isfinite(values).any(axis=1)
    out[rows] = reduce(values[rows], axis=1)
    return out


def _time_first(array) -> np.ndarray:
    return array.transpose("time", ...).values


def worst_value(ds, variable: str, kind: str) -> np.ndarray:
    """Over ageing time: the largest (``max``) or smallest (``min``) value over the
    other dimensions, or the largest |x - x_design| (``deviation``).

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    variable : str
        A variable with a ``time`` dimension.
    kind : {"max", "min", "deviation"}
        Which extreme.

    Returns
    -------
    numpy.ndarray
        One value per ageing time, in the variable's stored unit.
    """
    if kind == "deviation":
        return _per_time(np.abs(_time_first(drift(ds, variable, "design"))), np.nanmax)
    return _per_time(_time_first(ds[variable]), np.nanmax if kind == "max" else np.nanmin)


def _design_size(design, worst: Callable[[str], np.ndarray], kind: str) -> float:
    """|as-designed value| (``design``, or without one the first stored time's ``worst``
    value of ``kind``): the scale of a 0 bound."""
    if design is not None:
        values = np.asarray(design, float)
        return float(np.nanmax(np.abs(values))) if np.isfinite(values).any() else 1.0
    first = worst(kind)
    finite = first[np.isfinite(first)]
    return float(abs(finite[0])) if finite.size and finite[0] != 0 else 1.0


def limit_ratio(ds, limit: Limit) -> np.ndarray:
    """The limit ratio over ageing time (1 at the limit, above 1 out of spec).

    Parameters
    ----------
    ds : xarray.Dataset
        A result.
    limit : Limit
        The limit, bounds in the variable's stored unit.

    Returns
    -------
    numpy.ndarray
        The ratio [-] per ageing time: the worst of |deviation| / allowed deviation and
        1 + (value - bound) / |bound| for max and min; NaN where the value is unknown.
    """
    name = design_name(limit.variable)
    design = ds[name].values if name in ds else None
    return _ratio(lambda kind: worst_value(ds, limit.variable, kind), design, limit)


def values_ratio(values: np.ndarray, design, limit: Limit, degrees: bool = False) -> np.ndarray:
    """:func:`limit_ratio` of a variable's values given as an array, not in a result (the
    limit search's evaluations build none).

    Parameters
    ----------
    values : numpy.ndarray
        The variable over (time, ...) in its stored unit.
    design : numpy.ndarray or None
        Its as-designed value over (...) in its stored unit; None where it has none (a
        ``deviation`` then needs one).
    limit : Limit
        The limit, bounds in the variable's stored unit.
    degrees : bool
        The values are angles in degrees: a deviation is wrapped into [-180, 180).

    Returns
    -------
    numpy.ndarray
        The ratio [-] per ageing time, as :func:`limit_ratio` gives it.
    """
    values = np.asarray(values, float)

    def worst(kind: str) -> np.ndarray:
        if kind != "deviation":
            return _per_time(values, np.nanmax if kind == "max" else np.nanmin)
        change = values - np.asarray(design, float)
        if degrees:
            change = wrapped_degrees(change)
        return _per_time(np.abs(change), np.nanmax)

    return _ratio(worst, design, limit)


def _ratio(worst: Callable[[str], np.ndarray], design, limit: Limit) -> np.ndarray:
    """The limit ratio from ``worst(kind)``, the variable's worst value per ageing time of
    each kind (``deviation``, ``max``, ``min``), and its as-designed value (or None)."""
    ratios = []
    if limit.deviation is not None:
        ratios.append(worst("deviation") / limit.deviation)
    for kind, sign in (("max", 1.0), ("min", -1.0)):
        bound = getattr(limit, kind)
        if bound is not None:
            scale = abs(bound) or _design_size(design, worst, kind)
            ratios.append(1.0 + sign * (worst(kind) - bound) / scale)
    stacked = np.vstack(ratios)
    out = np.full(stacked.shape[1], np.nan)
    known = np.isfinite(stacked).any(axis=0)
    out[known] = np.nanmax(stacked[:, known], axis=0)
    return out


# ----------------------------------------------------------------- crossing


@dataclass(frozen=True)
class Tolerance:
    """The error a crossing time may carry: ``relative`` of the crossing time or ``floor``,
    whichever is larger.

    Parameters
    ----------
    relative : float
        Share of the crossing time [-].
    floor : float
        The smallest tolerance [s].
    """

    relative: float = RELATIVE
    floor: float = FLOOR

    @classmethod
    def for_accuracy(cls, accuracy: float | None) -> "Tolerance":
        """RELATIVE and FLOOR, both scaled by ``accuracy`` / RELATIVE where the accuracy
        asked of the diffusion is finer than RELATIVE.

        Parameters
        ----------
        accuracy : float or None
            The relative accuracy asked of the diffusion [-]; None: the defaults.

        Returns
        -------
        Tolerance
            The crossing's tolerance.
        """
        scale = min(1.0, accuracy / RELATIVE) if accuracy else 1.0
        return cls(RELATIVE * scale, FLOOR * scale)

    def at(self, time: float) -> float:
        """The tolerance of a crossing at ``time`` [s], in s."""
        return max(self.relative * float(time), self.floor)


def _first_above(ratio: np.ndarray) -> int | None:
    above = np.flatnonzero(np.asarray(ratio, float) > 1.0)  # NaN compares False
    return int(above[0]) if above.size else None


def _root_time(times):
    """The search's variable, the square root of the ageing time [s^0.5]: moisture uptake
    goes as its square root at first (Crank 1975, eq. 4.20), so a ratio driven by it is
    nearly linear in it where it is far from linear in the time itself."""
    return np.sqrt(np.maximum(np.asarray(times, float), 0.0))


@dataclass
class _Bracket:
    """An ageing-time interval [lo, hi] whose end is out of spec and whose start is not."""

    lo: float
    hi: float
    r_lo: float
    r_hi: float
    tolerance: Tolerance
    #: Illinois weights (Dowell & Jarratt 1971) of the ends' distances from 1 in the secant:
    #: halved each round an end is kept while the other moves, so the secant cannot stall
    #: on one side of a curved ratio (plain regula falsi does)
    w_lo: float = 1.0
    w_hi: float = 1.0
    #: every time evaluated or stored about the bracket and its ratio (its ends included)
    samples: dict = field(default_factory=dict)
    #: the rounds of model evaluations that narrowed it
    rounds: int = 0
    #: the climate's change times inside the bracket, sampled in its first round
    nodes: np.ndarray = field(default_factory=lambda: np.empty(0))

    def __post_init__(self):
        self.samples.update({float(self.lo): float(self.r_lo), float(self.hi): float(self.r_hi)})

    def open(self) -> bool:
        return self.hi - self.lo > self.tolerance.at(self.lo)

    def narrow(self, inner: np.ndarray, values: np.ndarray) -> None:
        """Keep the sub-interval of the first crossing among ``inner`` times."""
        grid = np.concatenate([[self.lo], inner, [self.hi]])
        ratio = np.concatenate([[self.r_lo], values, [self.r_hi]])
        k = _first_above(ratio[1:]) + 1  # the last value (r_hi) is above 1
        kept_lo, kept_hi = k == 1, k == grid.size - 1
        self.w_lo = 0.5 * self.w_lo if kept_lo and not kept_hi else 1.0
        self.w_hi = 0.5 * self.w_hi if kept_hi and not kept_lo else 1.0
        self.lo, self.hi, self.r_lo, self.r_hi = grid[k - 1], grid[k], ratio[k - 1], ratio[k]
        self.samples.update(zip(np.asarray(inner, float).tolist(),
                                np.asarray(values, float).tolist()))
        self.rounds += 1

    def inner(self) -> np.ndarray:
        """The times to evaluate this round: two times either side of the best guess at
        the crossing (``guess``), twice its error estimate away but within STRADDLE of the
        tolerance, so a good guess closes the bracket in one round, narrow; POINTS equally spaced in the square root of the time instead in the first
        round, which looks for the first crossing inside the bracket, with the climate's
        change times inside it (a ratio that a climate record drives up and down peaks
        there), unless the stored times about it already agree on the crossing
        (``_interpolated``) in a steady climate, and once SECANT_ROUNDS of guesses have not
        closed it."""
        agreed = self.nodes.size == 0 and _interpolated(
            self.samples, self.lo, self.hi,
            CROSSING_INTERPOLATION_SHARE * self.tolerance.at(self.lo))
        if (self.rounds == 0 and not agreed) or self.rounds > SECANT_ROUNDS \
                or not np.isfinite(self.r_lo):
            even = np.linspace(*_root_time([self.lo, self.hi]), POINTS + 2)[1:-1] ** 2
            return np.union1d(even, self.nodes) if self.rounds == 0 else even
        guess, estimate = self.guess()
        tolerance = self.tolerance.at(self.lo)
        half = np.clip(2.0 * estimate, *np.multiply(STRADDLE, tolerance))
        around = np.clip(guess + np.array([-half, half]), self.lo, self.hi)
        return np.unique(around[(around > self.lo) & (around < self.hi)])

    def guess(self) -> tuple[float, float]:
        """(crossing [s], its error estimate [s]): read off the cubic through the samples
        about it where the quadratics put it within a quarter of the bracket of the
        cubic's, else the root of the Illinois secant in the square root of the time (its
        estimate infinite)."""
        read = _interpolated(self.samples, self.lo, self.hi, 0.25 * (self.hi - self.lo))
        if read is not None:
            return read
        ends = _root_time([self.lo, self.hi])
        low, high = 1.0 - self.w_lo * (1.0 - self.r_lo), 1.0 + self.w_hi * (self.r_hi - 1.0)
        return float((ends[0] + (1.0 - low) / (high - low) * (ends[1] - ends[0])) ** 2), np.inf

    def root(self) -> tuple[float, float]:
        """(crossing [s], its error [s]) in the closed bracket: read off the cubic through
        the samples about it (else linear in the square root of the time).

        The error is at most the larger of its distances to the bracket's ends, a bound.
        Inside the closed bracket the ratio is smooth (the climate's change times were
        sampled, so none lies inside it), and the line through its two ends misses the
        crossing by about r'' w^2 / (8 r') (w its width); the cubic, which also reads the
        curvature, moves the crossing by about that much from the line's, and is itself
        closer: SAFETY times that move is the error, but not below FLOOR_SHARE of the
        crossing's tolerance, the share of it the model's own accuracy is taken to support."""
        if not np.isfinite(self.r_lo) or self.r_hi == self.r_lo:
            return float(self.hi), float(self.hi - self.lo)
        ends = _root_time([self.lo, self.hi])
        share = (1.0 - self.r_lo) / (self.r_hi - self.r_lo)
        line = float((ends[0] + share * (ends[1] - ends[0])) ** 2)
        read = _interpolated(self.samples, self.lo, self.hi, np.inf)
        crossing = float(np.clip(line if read is None else read[0], self.lo, self.hi))
        bound = max(crossing - self.lo, self.hi - crossing)
        if read is not None:
            move = abs(crossing - line)
            bound = min(bound, max(SAFETY * move, FLOOR_SHARE * self.tolerance.at(crossing)))
        return crossing, bound


def _interpolated(samples: dict, lo: float, hi: float,
                  within: float) -> tuple[float, float] | None:
    """(crossing, error estimate) of 1 in [lo, hi] (r(lo) <= 1 < r(hi)) of the cubic in
    the square root of the time through the four samples about it, when the quadratics
    through three of them that hold both ends put it within ``within`` of the cubic's;
    the larger distance is the estimate (the next term's size: it estimates the
    quadratic's error, which bounds the cubic's; Hildebrand 1956 pp. 43-44, as
    ``dense_output``); else None (too few or unknown samples, or they disagree).

    An estimate, not a bound (samples far apart about a crossing near 0 can agree on a
    wrong one), so it only picks where the model is evaluated next."""
    times = np.array(sorted(samples))
    k = int(np.searchsorted(times, lo))
    if times.size < 4 or times[k] != lo or times[k + 1] != hi:
        return None
    four = np.arange(4) + min(max(k - 1, 0), times.size - 4)
    t = times[four]
    r = np.array([samples[v] for v in t])
    if not np.isfinite(r).all():
        return None
    u, ends = _root_time(t), _root_time([lo, hi])
    cubic = polynomial_crossing(u, r, *ends) ** 2
    estimates = [abs(polynomial_crossing(u[three], r[three], *ends) ** 2 - cubic)
                 for three in (slice(0, 3), slice(1, 4)) if lo in t[three] and hi in t[three]]
    if not estimates or max(estimates) > within:
        return None
    return float(cubic), float(max(estimates))


def polynomial_crossing(x: np.ndarray, r: np.ndarray, lo: float, hi: float) -> float:
    """Where the polynomial through (x, r) crosses 1 in [lo, hi], which it meets as
    r(lo) <= 1 < r(hi): its first root there.

    The roots are the eigenvalues of the polynomial's companion matrix (on x scaled to
    [0, 1]; numpy.polynomial.polynomial.polyroots). A simple real root is computed real (a
    real matrix's complex eigenvalues come in conjugate pairs), so the root of the sign
    change is among the real ones; one that round-off moved just outside the bracket is
    taken at its end.

    Parameters
    ----------
    x : numpy.ndarray
        The abscissae of the samples [any unit], two to four of them.
    r : numpy.ndarray
        The ratios at them [-].
    lo, hi : float
        The bracket [unit of x].

    Returns
    -------
    float
        The crossing [unit of x]; an end of the bracket when the fit, by its round-off,
        does not change sign across it.
    """
    x = (x - lo) / (hi - lo)
    coefficients = np.polynomial.polynomial.polyfit(x, r - 1.0, x.size - 1)
    ends = np.polynomial.polynomial.polyval([0.0, 1.0], coefficients)
    if not ends[0] <= 0.0 < ends[1]:   # the fit's round-off at a sample on 1: the ends
        return float(lo if ends[0] > 0.0 else hi)
    roots = np.polynomial.polynomial.polyroots(coefficients)
    real = np.sort(roots.real[roots.imag == 0.0])
    if not real.size:  # not met with a sign change; the line through the ends then
        return float(lo + ends[0] / (ends[0] - ends[1]) * (hi - lo))
    held = np.clip(real, 0.0, 1.0)
    root = held[np.argmin(np.abs(real - held))]  # the first inside, else the nearest
    return float(lo + root * (hi - lo))


def _brackets(times: np.ndarray, ratios: np.ndarray, tolerance: Tolerance, nodes: np.ndarray):
    """(crossings found at the first stored time, {limit: _Bracket}): the stored interval
    of each limit's first crossing, its samples the stored times either side of it, its
    nodes the climate's change times inside it (at most CLIMATE_NODES)."""
    found = np.full((2, ratios.shape[1]), np.nan)
    brackets: dict[int, _Bracket] = {}
    for j in range(ratios.shape[1]):
        index = _first_above(ratios[:, j])
        if index == 0:
            found[:, j] = times[0], 0.0
        elif index is not None:
            near = [i for i in (index - 2, index + 1) if 0 <= i < times.size
                    and np.isfinite(ratios[i, j])]
            lo, hi = times[index - 1], times[index]
            inside = nodes[(nodes > lo) & (nodes < hi)]
            if inside.size > CLIMATE_NODES:
                inside = inside[np.linspace(0, inside.size - 1, CLIMATE_NODES).astype(int)]
            brackets[j] = _Bracket(lo, hi, ratios[index - 1, j], ratios[index, j], tolerance,
                                   samples={float(times[i]): float(ratios[i, j]) for i in near},
                                   nodes=inside)
    return found, brackets


def first_crossings(times: np.ndarray, ratios: np.ndarray,
                    evaluate: Callable[[np.ndarray], np.ndarray],
                    tolerance: Tolerance = Tolerance(),
                    nodes=()) -> tuple[np.ndarray, np.ndarray]:
    """The first ageing time (s) at which each column of ``ratios`` (time, limit)
    exceeds 1, and its error estimate; NaN where it never does, the first stored time
    (error 0) where it already does.

    The stored times bracket each crossing; ``evaluate(ts)`` re-runs the model at
    ageing times ``ts`` and returns the ratios there (len(ts), limit). The search runs
    in the square root of the time, in which a ratio driven by moisture uptake is nearly
    linear. Each round evaluates the model once for all open brackets, at the times
    ``_Bracket.inner`` picks (POINTS equally spaced and the climate's change times inside
    the bracket first, then two straddling the best guess), and keeps the sub-interval of
    the first crossing, until each bracket is no wider than its ``tolerance``; the
    crossing is read inside it, its error bound the larger distance to the ends.

    Parameters
    ----------
    times : numpy.ndarray
        The stored ageing times [s], increasing.
    ratios : numpy.ndarray
        The limit ratios [-] at ``times``, shape (time, limit).
    evaluate : callable
        ``evaluate(ts)`` with ``ts`` ageing times [s]: the ratios [-] there, shape
        (len(ts), limit).
    tolerance : Tolerance
        The error each crossing may carry (by default 0.1 % of it, or 1 h).
    nodes : array_like
        The climate's change times [s] (a record's rows, a history's segment ends): the
        first round samples those inside a bracket too, where a ratio the climate drives up
        and down peaks, so a first crossing between stored times is not passed over.

    Returns
    -------
    tuple of numpy.ndarray
        Per limit, the first ageing time out of spec [s] (NaN where it stays in spec) and
        its error estimate [s] (never above the tolerance).
    """
    times = np.asarray(times, float)
    ratios = np.asarray(ratios, float).reshape(len(times), -1)
    found, brackets = _brackets(times, ratios, tolerance, np.asarray(nodes, float))
    while any(b.open() for b in brackets.values()):
        inner = {j: b.inner() for j, b in brackets.items() if b.open()}
        at = np.unique(np.concatenate(list(inner.values())))
        values = np.asarray(evaluate(at), float).reshape(len(at), -1)
        for j, ts in inner.items():
            brackets[j].narrow(ts, values[np.searchsorted(at, ts), j])
    for j, bracket in brackets.items():
        found[:, j] = bracket.root()
    return found[0], found[1]


# ------------------------------------------------------------------ reading


def stored_limits(ds) -> dict[str, Limit]:
    """The limits recorded in a result (``limits`` attribute), by variable.

    Parameters
    ----------
    ds : xarray.Dataset
        A result.

    Returns
    -------
    dict of str to Limit
        Empty when the scene set none.
    """
    recorded = ds.attrs.get("limits") or {}
    return {name: from_attrs(name, attrs) for name, attrs in recorded.items()}


def crossing(ds, name: str) -> tuple[float, float | None]:
    """When a limit of a result first fails and that time's error estimate [s] (NaN: it
    holds; the estimate None in a result written before it was stored).

    Parameters
    ----------
    ds : xarray.Dataset
        A result with ``time_out_of_spec``.
    name : str
        The limited variable.

    Returns
    -------
    tuple of (float, float or None)
        The time [s] and its error estimate [s].
    """
    failed = float(ds["time_out_of_spec"].sel(limit=name)) * 86400.0
    if "time_out_of_spec_error" not in ds:
        return failed, None
    return failed, float(ds["time_out_of_spec_error"].sel(limit=name)) * 86400.0


def crossing_text(ds, name: str) -> str:
    """When a limit first fails, in the result's time unit, with only the digits its error
    estimate supports (``"20.0 d"``); "never" where it holds.

    Parameters
    ----------
    ds : xarray.Dataset
        A result with ``time_out_of_spec``.
    name : str
        The limited variable.

    Returns
    -------
    str
        The time's text.
    """
    failed, error = crossing(ds, name)
    if math.isnan(failed):
        return "never"
    unit = report_time_unit(ds)
    return format_time(failed, unit, error) if error is not None else \
        f"{failed / unit[1]:.4g} {unit[0]}"
