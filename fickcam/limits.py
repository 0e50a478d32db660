"""Limits on result variables: the spec a mechanism must hold.

A scene's ``limits:`` section names result variables and, for each, a band
around the as-designed value (``deviation``) and/or bounds (``max``, ``min``),
in any unit pint knows. Each limit reduces its variable to one number per
ageing time (the worst over the cam or crank angle, the parts or the links)
and turns it into a *limit ratio*, 1 at the limit and above 1 out of spec:

- ``deviation`` d:  r = max |x - x_design| / d (the largest deviation over the cycle);
- ``max`` b:        r = 1 + (max x - b) / s,  which is max x / b for b > 0;
- ``min`` b:        r = 1 + (b - min x) / s,  which is 2 - min x / b for b > 0;

with s = |b|, or for a zero bound the size of the as-designed value. With
several entries the ratio is the largest of them. The first ageing time at
which a ratio exceeds 1 is located on the continuous ageing time by re-running
the model inside the bracketing interval (:func:`first_crossings`).
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
from pydantic import Field, model_validator

from .plausibility import ambiguity
from .query import drift
from .schema import VARIABLES, Var, design_name
from .units import StrictModel
from .unit_parsing import number_and_unit, registry, split_number_unit

#: the crossing is located to this fraction of its bracketing interval, or to FLOOR s
TOLERANCE = 0.01
FLOOR = 3600.0
#: model evaluations per bracket in a sampling round (the first, and any after SECANT_ROUNDS)
POINTS = 4
#: rounds after the first that evaluate only two times straddling the secant's root
SECANT_ROUNDS = 3
#: a round's samples close a bracket when the cubic through the four about its crossing and
#: the quadratics through three of them put the crossing within this share of the tolerance
#: of each other (the quadratics' error, which bounds the cubic's: ``_interpolated``)
INTERPOLATION_SHARE = 0.5


class LimitSpec(StrictModel):
    """One entry of the scene's ``limits:`` section (values as written, with units).

    At least one of the three bounds must be given.

    Parameters
    ----------
    deviation : float or str, optional
        The largest allowed change from the as-designed value [unit of the variable, e.g.
        ``"0.05 mm"``].
    max : float or str, optional
        The largest allowed value [unit of the variable].
    min : float or str, optional
        The smallest allowed value [unit of the variable].
    """

    deviation: Any = Field(
        None, description="Largest allowed change from the as-designed value, in the variable's unit")
    max: Any = Field(None, description="Largest allowed value, in the variable's unit")
    min: Any = Field(None, description="Smallest allowed value, in the variable's unit")

    @model_validator(mode="after")
    def _something(self):
        if self.deviation is None and self.max is None and self.min is None:
            raise ValueError("give deviation, max or min")
        return self


@dataclass(frozen=True)
class Limit:
    """A validated limit: bounds in the variable's stored unit (schema ``units``).

    Parameters
    ----------
    variable : str
        The result variable it bounds.
    units : str
        The variable's stored unit (the schema's).
    deviation : float, optional
        The largest allowed change from the as-designed value [``units``].
    max : float, optional
        The largest allowed value [``units``].
    min : float, optional
        The smallest allowed value [``units``].
    text : str
        The limit as the scene wrote it, for messages.
    display_units : str
        The unit the scene wrote, for plots ("" = the stored unit).
    display_scale : float
        Display value / stored value [display unit / stored unit].
    """

    variable: str
    units: str
    deviation: float | None = None
    max: float | None = None
    min: float | None = None
    text: str = ""
    display_units: str = ""  # the unit the scene wrote (plots), "" = stored unit
    display_scale: float = 1.0  # display value = stored value * display_scale

    def as_attrs(self) -> dict:
        return {"deviation": self.deviation, "max": self.max, "min": self.min,
                "units": self.units, "text": self.text, "display_units": self.display_units,
                "display_scale": self.display_scale}


def from_attrs(variable: str, attrs: dict) -> Limit:
    """The Limit stored in a result's ``limits`` attribute.

    Parameters
    ----------
    variable : str
        The variable it bounds.
    attrs : dict
        Its entry of the attribute (``Limit.as_attrs``).

    Returns
    -------
    Limit
        The limit, bounds in the stored unit.
    """
    return Limit(variable, attrs.get("units", ""), attrs.get("deviation"), attrs.get("max"),
                 attrs.get("min"), attrs.get("text", ""), attrs.get("display_units", ""),
                 attrs.get("display_scale", 1.0))


# ------------------------------------------------------------------ parsing


def _pint_units(units: str) -> str:
    """A schema unit ("m s-1", "kg m2", "%", "1") in pint's spelling."""
    if units in ("", "1"):
        return "dimensionless"
    units = units.replace("%", "percent")
    return re.sub(r"([A-Za-z]+)(-?\d+)", r"\1**\2", units)


def stored_value(value, var: Var, *, difference: bool = False) -> float:
    """``value`` (number or string with units) in ``var``'s stored unit.

    A bare number is SI (as everywhere in a scene; percent for % variables), except a bare
    rotational speed, which is refused (rad/s or rpm?).
    ``difference``: a temperature step, so degC/degF mean kelvin-sized steps.
    Angles are told apart from plain numbers (pint's radian is dimensionless).

    Parameters
    ----------
    value : float or str
        The bound as written: a number (SI, or % for % variables) or a string with
        units ("0.2 mm", "3 deg").
    var : fickcam.schema.Var
        The result variable the bound applies to.
    difference : bool
        A temperature difference [K] (a deviation), not an absolute temperature.

    Returns
    -------
    float
        The value in the variable's stored unit (its schema ``units``).

    Raises
    ------
    ValueError
        When the unit is unknown or of the wrong dimension, or a speed has none.
    """
    number, unit = number_and_unit(value)
    slip = ambiguity(value, "angular_speed") if var.units == "rpm" else None
    if slip:
        raise ValueError(slip)
    if not unit:
        return number * var.scale
    ureg = registry()
    unit = unit.replace("%", "percent")
    if difference:
        unit = re.sub(r"\bdeg([CF])\b", r"delta_deg\1", unit)
    try:
        quantity = ureg.Quantity(number, unit)
    except Exception:  # pint raises several types for unknown/ill-formed units
        raise ValueError(f"unknown unit {unit!r} in {value!r}") from None
    target = ureg.Quantity(1.0, _pint_units(var.units))
    if quantity.to_base_units().units != target.to_base_units().units:
        raise ValueError(f"{value!r} has the wrong dimension (the variable is in {var.units or '1'})")
    return float(quantity.to(target.units).magnitude)


def parse_limit(name: str, spec: LimitSpec, sections: set[str]) -> Limit:
    """Validate one limit against the schema; ValueError(reason) if it cannot apply.

    Parameters
    ----------
    name : str
        The result variable limited.
    spec : LimitSpec
        The scene's entry: ``deviation``, ``max`` and/or ``min`` as written, with units.
    sections : set of str
        The mechanism sections the scene has ("cam", "linkage").

    Returns
    -------
    Limit
        The bounds in the variable's stored unit.

    Raises
    ------
    ValueError
        When the variable does not vary with ageing time, its section is missing, a
        bound is in a wrong unit, a deviation is not positive or min is above max.
    """
    var = VARIABLES.get(name)
    if var is None or "time" not in var.dims or var.section == "fields" or not var.units:
        raise ValueError(f"no result variable {name!r} that varies with ageing time "
                         "(see `fickcam schema`)")
    if var.section in ("cam", "linkage") and var.section not in sections:
        raise ValueError(f"{name} needs a {var.section} section in the scene")
    values = {}
    for key in ("deviation", "max", "min"):
        raw = getattr(spec, key)
        if raw is not None:
            try:
                values[key] = stored_value(raw, var, difference=key == "deviation")
            except ValueError as exc:
                raise ValueError(f"{key}: {exc}") from None
    if values.get("deviation") is not None and not values["deviation"] > 0:
        raise ValueError("deviation must be positive")
    if "deviation" in values and not var.has_design:
        raise ValueError(f"{name} has no as-designed value to deviate from: give max or min")
    if values.get("min") is not None and values.get("max") is not None and values["min"] > values["max"]:
        raise ValueError(f"min ({spec.min}) is above max ({spec.max})")
    text = ", ".join(f"{key} {getattr(spec, key)}" for key in ("deviation", "min", "max")
                     if getattr(spec, key) is not None)
    return Limit(name, var.units, text=text, **values, **_display(spec, var))


def _display(spec: LimitSpec, var: Var) -> dict:
    """The unit the scene wrote its limit in, for plots (not offset units such as degC)."""
    for raw in (spec.deviation, spec.max, spec.min):
        if isinstance(raw, str):
            unit = split_number_unit(raw)[1].replace("%", "percent")
            if unit and "degC" not in unit and "degF" not in unit:
                ureg = registry()
                scale = ureg.Quantity(1.0, _pint_units(var.units)).to(unit).magnitude
                return {"display_units": split_number_unit(raw)[1], "display_scale": float(scale)}
    return {}


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


def _design_size(ds, variable: str, kind: str) -> float:
    """|as-designed value| (first stored time without a design state): the scale of a 0 bound."""
    name = design_name(variable)
    if name in ds:
        values = np.asarray(ds[name].values, float)
        return float(np.nanmax(np.abs(values))) if np.isfinite(values).any() else 1.0
    first = worst_value(ds, variable, kind)
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
    ratios = []
    if limit.deviation is not None:
        ratios.append(worst_value(ds, limit.variable, "deviation") / limit.deviation)
    for kind, sign in (("max", 1.0), ("min", -1.0)):
        bound = getattr(limit, kind)
        if bound is not None:
            scale = abs(bound) or _design_size(ds, limit.variable, kind)
            ratios.append(1.0 + sign * (worst_value(ds, limit.variable, kind) - bound) / scale)
    stacked = np.vstack(ratios)
    out = np.full(stacked.shape[1], np.nan)
    known = np.isfinite(stacked).any(axis=0)
    out[known] = np.nanmax(stacked[:, known], axis=0)
    return out


# ----------------------------------------------------------------- crossing


def _first_above(ratio: np.ndarray) -> int | None:
    above = np.flatnonzero(np.asarray(ratio, float) > 1.0)  # NaN compares False
    return int(above[0]) if above.size else None


@dataclass
class _Bracket:
    """An ageing-time interval [lo, hi] whose end is out of spec and whose start is not."""

    lo: float
    hi: float
    r_lo: float
    r_hi: float
    tolerance: float
    #: Illinois weights (Dowell & Jarratt 1971) of the ends' distances from 1 in the secant:
    #: halved each round an end is kept while the other moves, so the secant cannot stall
    #: on one side of a curved ratio (plain regula falsi does)
    w_lo: float = 1.0
    w_hi: float = 1.0
    #: every time evaluated in the stored interval and its ratio (its ends included)
    samples: dict = field(default_factory=dict)
    #: the crossing read off the samples' interpolants (``_interpolated``), which closes it
    read: float | None = None

    def __post_init__(self):
        self.samples.update({float(self.lo): float(self.r_lo), float(self.hi): float(self.r_hi)})

    def open(self) -> bool:
        return self.read is None and self.hi - self.lo > self.tolerance

    def narrow(self, inner: np.ndarray, values: np.ndarray) -> None:
        """Keep the sub-interval of the first crossing among ``inner`` times; close the
        bracket where the samples' interpolants agree on the crossing (``_interpolated``)."""
        grid = np.concatenate([[self.lo], inner, [self.hi]])
        ratio = np.concatenate([[self.r_lo], values, [self.r_hi]])
        k = _first_above(ratio[1:]) + 1  # the last value (r_hi) is above 1
        kept_lo, kept_hi = k == 1, k == grid.size - 1
        self.w_lo = 0.5 * self.w_lo if kept_lo and not kept_hi else 1.0
        self.w_hi = 0.5 * self.w_hi if kept_hi and not kept_lo else 1.0
        self.lo, self.hi, self.r_lo, self.r_hi = grid[k - 1], grid[k], ratio[k - 1], ratio[k]
        self.samples.update(zip(np.asarray(inner, float).tolist(),
                                np.asarray(values, float).tolist()))
        if self.open():
            self.read = _interpolated(self.samples, self.lo, self.hi,
                                      INTERPOLATION_SHARE * self.tolerance)

    def inner(self, round_: int) -> np.ndarray:
        """The times to evaluate this round: POINTS equally spaced ones (the first round,
        which looks for the first crossing inside the bracket, and once secant rounds have
        not closed it), else two times 0.45 tolerance either side of the secant's root, so
        a ratio that is nearly linear over the bracket closes it in one round."""
        if round_ == 0 or round_ > SECANT_ROUNDS or not np.isfinite(self.r_lo):
            return np.linspace(self.lo, self.hi, POINTS + 2)[1:-1]
        half = 0.45 * self.tolerance
        low, high = 1.0 - self.w_lo * (1.0 - self.r_lo), 1.0 + self.w_hi * (self.r_hi - 1.0)
        secant = self.lo + (1.0 - low) / (high - low) * (self.hi - self.lo)
        around = np.clip(secant + np.array([-half, half]), self.lo, self.hi)
        return np.unique(around[(around > self.lo) & (around < self.hi)])

    def root(self) -> float:
        """The crossing read off the interpolants where they closed the bracket, else the
        linear interpolant's root in the bracket (error below its width)."""
        if self.read is not None:
            return self.read
        if not np.isfinite(self.r_lo) or self.r_hi == self.r_lo:
            return float(self.hi)
        return float(self.lo + (1.0 - self.r_lo) / (self.r_hi - self.r_lo) * (self.hi - self.lo))


def _interpolated(samples: dict, lo: float, hi: float, within: float) -> float | None:
    """The crossing of 1 in [lo, hi] (r(lo) <= 1 < r(hi)) of the cubic through the four
    samples about it, when the quadratics through three of them that hold both ends put
    it within ``within`` of the cubic's (the next term's size: it estimates the quadratic's
    error, which bounds the cubic's; Hildebrand 1956 pp. 43-44, as ``dense_output``); else
    None (too few or unknown samples, or they disagree).

    The samples are a round's model evaluations (the first round's equally spaced ones
    about the first crossing), so this closes a bracket a round or more before it narrows
    to the tolerance, where the ratio is smooth on the scale of the samples' spacing."""
    times = np.array(sorted(samples))
    k = int(np.searchsorted(times, lo))
    if times.size < 4 or times[k] != lo or times[k + 1] != hi:
        return None
    four = np.arange(4) + min(max(k - 1, 0), times.size - 4)
    t = times[four]
    r = np.array([samples[v] for v in t])
    if not np.isfinite(r).all():
        return None
    cubic = _crossing(t, r, lo, hi)
    estimates = [abs(_crossing(t[three], r[three], lo, hi) - cubic)
                 for three in (slice(0, 3), slice(1, 4)) if lo in t[three] and hi in t[three]]
    return cubic if estimates and max(estimates) <= within else None


def _crossing(t: np.ndarray, r: np.ndarray, lo: float, hi: float) -> float:
    """Where the polynomial through (t, r) crosses 1 in [lo, hi] (it interpolates r(lo) <=
    1 < r(hi): a sign change), by Brent's method on the scaled time."""
    from scipy.optimize import brentq

    x = (t - lo) / (hi - lo)
    coefficients = np.polynomial.polynomial.polyfit(x, r - 1.0, x.size - 1)
    ends = np.polynomial.polynomial.polyval([0.0, 1.0], coefficients)
    if not ends[0] <= 0.0 < ends[1]:   # the fit's round-off at a sample on 1: the ends
        return float(lo if ends[0] > 0.0 else hi)
    root = brentq(lambda u: np.polynomial.polynomial.polyval(u, coefficients), 0.0, 1.0,
                  xtol=1e-12)
    return float(lo + root * (hi - lo))


def first_crossings(times: np.ndarray, ratios: np.ndarray,
                    evaluate: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """The first ageing time (s) at which each column of ``ratios`` (time, limit)
    exceeds 1; NaN where it never does, the first stored time where it already does.

    The stored times bracket each crossing; ``evaluate(ts)`` re-runs the model at
    ageing times ``ts`` and returns the ratios there (len(ts), limit). Each round
    evaluates the model once for all open brackets, at the times ``_Bracket.inner``
    picks (POINTS equally spaced first, then two straddling the secant's root), and
    keeps the sub-interval of the first crossing, until each bracket is no wider than
    TOLERANCE of its stored interval or FLOOR seconds; the crossing is then
    interpolated linearly inside it (a guarded regula falsi: the model is re-run about
    2 + 2 times per limit instead of 2 x 9).

    Parameters
    ----------
    times : numpy.ndarray
        The stored ageing times [s], increasing.
    ratios : numpy.ndarray
        The limit ratios [-] at ``times``, shape (time, limit).
    evaluate : callable
        ``evaluate(ts)`` with ``ts`` ageing times [s]: the ratios [-] there, shape
        (len(ts), limit).

    Returns
    -------
    numpy.ndarray
        Per limit, the first ageing time out of spec [s]; NaN where it stays in spec.
    """
    times = np.asarray(times, float)
    ratios = np.asarray(ratios, float).reshape(len(times), -1)
    found = np.full(ratios.shape[1], np.nan)
    brackets: dict[int, _Bracket] = {}
    for j in range(ratios.shape[1]):
        index = _first_above(ratios[:, j])
        if index == 0:
            found[j] = times[0]
        elif index is not None:
            lo, hi = times[index - 1], times[index]
            brackets[j] = _Bracket(lo, hi, ratios[index - 1, j], ratios[index, j],
                                   max(TOLERANCE * (hi - lo), FLOOR))
    round_ = 0
    while any(b.open() for b in brackets.values()):
        inner = {j: b.inner(round_) for j, b in brackets.items() if b.open()}
        round_ += 1
        at = np.unique(np.concatenate(list(inner.values())))
        values = np.asarray(evaluate(at), float).reshape(len(at), -1)
        for j, ts in inner.items():
            brackets[j].narrow(ts, values[np.searchsorted(at, ts), j])
    for j, bracket in brackets.items():
        found[j] = bracket.root()
    return found


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
