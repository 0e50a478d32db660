"""What a limit is: a scene's ``limits:`` entry
(:class:`~fickcam.scene.limits.LimitSpec`), read against the variable table into a
:class:`~fickcam.scene.limits.Limit` (bounds in the variable's stored unit), and a result's
stored ``limits`` attribute read back.

A limit names a result variable and, for it, a band around the as-designed value
(``deviation``) and/or bounds (``max``, ``min``), in any unit pint knows. How a result
is judged against it, and when it first fails, is :mod:`fickcam.results.limits`.
"""
from __future__ import annotations

import functools
import re
from dataclasses import dataclass
from typing import Any

from pydantic import Field, model_validator

from ..quantities.parsing import number_and_unit, registry, split_number_unit
from ..quantities.plausibility import ambiguity
from ..quantities.types import StrictModel
from ..schema import VARIABLES, Var


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
    return _stored_value(value, var, difference)


@functools.lru_cache(maxsize=256)
def _stored_value(value, var: Var, difference: bool) -> float:
    """:func:`stored_value`, once per bound as written (a sweep's cases share their
    limits; pint takes about a millisecond a conversion)."""
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
                return {"display_units": split_number_unit(raw)[1],
                        "display_scale": _display_scale(var.units, unit)}
    return {}


@functools.lru_cache(maxsize=256)
def _display_scale(units: str, unit: str) -> float:
    """One ``units`` (the schema's spelling) in ``unit`` (pint's)."""
    return float(registry().Quantity(1.0, _pint_units(units)).to(unit).magnitude)
