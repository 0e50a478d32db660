"""Units at the edges: parse user values into SI floats, format SI back out.

Every dimensional scene value is either a bare number, read in the SI unit of
its dimension, or a string with units parsed by pint (``"1.5 in"``,
``"113 degC"``, ``"600 rpm"``). Two documented exceptions to "bare numbers are
SI": relative humidity and moisture content are percentages, so a bare ``80``
means 80 %. Inside fickcam everything is SI (K, m, s, kg, N, Pa, rad, rad/s).
The pydantic types built on these readings are in :mod:`fickcam.quantities.types`.
"""
from __future__ import annotations

import functools
import logging
import math
import re
from typing import Any


log = logging.getLogger(__name__)

_NUMBER_THEN_UNIT = re.compile(
    r"^\s*(?P<number>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(?P<unit>.*?)\s*$"
)

# dimension name -> the SI unit values are converted to (its dimensionality is what we check)
SI_UNITS: dict[str, str] = {
    "length": "m",
    "mass": "kg",
    "time": "s",
    "temperature": "K",
    "angle": "rad",
    "angular_speed": "rad/s",
    "force": "N",
    "stiffness": "N/m",
    "torque": "N*m",
    "moment_of_inertia": "kg*m**2",
    "pressure": "Pa",
    "diffusivity": "m**2/s",
    "molar_energy": "J/mol",
    "density": "kg/m**3",
    "inverse_temperature": "1/K",
    "rate": "1/s",
    "acceleration": "m/s**2",
    "fraction": "",
    "percent": "percent",
}

_HUMAN = {
    "angle": "an angle (e.g. '75 deg')",
    "angular_speed": "a rotational speed (e.g. '600 rpm')",
    "fraction": "a fraction (e.g. 0.6 or '60 %')",
    "percent": "a percentage (e.g. '80 %')",
}


@functools.lru_cache(maxsize=1)
def registry():
    """The one pint registry fickcam uses (created on first use: pint is slow to import)."""
    # deferred: keeps pint off the start-up path
    import pint

    try:  # pint's own cache of its parsed definition files (user cache folder): 0.15 s less
        ureg = pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # noqa: BLE001 - an unwritable or damaged cache: parse the files again
        log.debug("pint's definition cache is unusable: parsing its files", exc_info=True)
        ureg = pint.UnitRegistry()
    ureg.define("percent_moisture = 0.01 = wtpct")
    return ureg


def split_number_unit(text: str) -> tuple[float, str]:
    """The leading number of ``text`` and the unit text after it.

    Parameters
    ----------
    text : str
        A number, optionally followed by a unit: ``"1.5 in"``, ``"30d"``, ``"1e-3"``.

    Returns
    -------
    number : float
        The number, in the unit given.
    unit : str
        The text after the number, stripped ("" when there is none).

    Raises
    ------
    ValueError
        When ``text`` does not start with a number.
    """
    match = _NUMBER_THEN_UNIT.match(text)
    if not match:
        raise ValueError(f"cannot read {text!r} as a number with units")
    return float(match.group("number")), match.group("unit")


def number_and_unit(value: Any) -> tuple[float, str]:
    """(finite number, unit text) of a bare number or a string with units ("" = none).

    Parameters
    ----------
    value : float or str
        A scene value: a number, or a string such as ``"113 degC"``.

    Returns
    -------
    number : float
        The finite number, in the unit given.
    unit : str
        The unit text ("" for a bare number).

    Raises
    ------
    ValueError
        For a boolean, None, another type, text that is not a number, or a non-finite number.
    """
    if isinstance(value, bool) or value is None:
        raise ValueError(f"expected a number or a string with units, got {value!r}")
    if isinstance(value, (int, float)):
        number, unit = float(value), ""
    elif isinstance(value, str):
        number, unit = split_number_unit(value)
    else:
        raise ValueError(f"expected a number or a string with units, got {type(value).__name__}")
    if not math.isfinite(number):
        raise ValueError(f"{value!r} is not a finite number")
    return number, unit


#: spellings of a unit used in workshops that pint does not read as meant, taken as the
#: unit on the right for values of that dimension (one meaning only)
SHOP_UNITS: dict[str, dict[str, str]] = {
    "angular_speed": {"RPM": "rpm", "Rpm": "rpm", "r/min": "rpm", "rev/min": "rpm",
                      "RPS": "rps", "r/s": "rps", "rev/s": "rps"},
    "percent": {"%RH": "%", "% RH": "%", "%rh": "%", "% rh": "%"},
}

#: spellings that pint reads as another dimension (``F`` the farad, ``C`` the coulomb) or not
#: at all, or that are ambiguous for the dimension: suggested, never taken
LIKELY_UNITS: dict[str, dict[str, str]] = {
    "temperature": {"C": "degC", "F": "degF", "c": "degC", "f": "degF", "deg C": "degC",
                    "deg F": "degF", "Celsius": "degC", "Fahrenheit": "degF"},
    "length": {"MM": "mm", '"': "in", "mil": "thou", "mils": "thou"},
    "time": {"wk": "week", "wks": "week", "yrs": "year", "mo": "month", "mos": "month"},
    "force": {"lb": "lbf", "lbs": "lbf", "kg": "kgf"},
    "stiffness": {"lb/in": "lbf/in", "lbs/in": "lbf/in", "kg/mm": "kgf/mm"},
    # a rotational speed in 1/time: pint reads rad per time, a workshop revolutions
    "angular_speed": {"1/min": "rpm", "min^-1": "rpm", "/min": "rpm", "Hz": "rps",
                      "1/s": "rps", "s^-1": "rps", "/s": "rps"},
}


def _likely_unit(unit: str, dimension: str) -> str | None:
    """The unit a misread spelling most likely meant for ``dimension``, or None."""
    return LIKELY_UNITS.get(dimension, {}).get(" ".join(unit.split()))


def _human(dimension: str) -> str:
    return _HUMAN.get(dimension, "a " + dimension.replace("_", " "))


def to_si(value: Any, dimension: str) -> float:
    """Convert a scene value to a float in the SI unit of ``dimension``.

    Strings such as ``"1e-3"`` (which YAML leaves as text) are accepted as numbers; a bare
    number is taken as SI (percent for ``"percent"``). Workshop spellings (``RPM``, ``%RH``)
    are read as meant (:data:`SHOP_UNITS`).

    Parameters
    ----------
    value : float or str
        A bare number [SI unit of ``dimension``] or a string with units (``"600 rpm"``).
    dimension : str
        A key of ``SI_UNITS`` (``"length"``, ``"temperature"``, ``"angular_speed"``...).

    Returns
    -------
    float
        The value in the SI unit of ``dimension`` [``SI_UNITS``].

    Raises
    ------
    ValueError
        With a one-line reason (wrong dimension, unknown unit, not a number), naming the
        unit a misread or ambiguous spelling most likely meant (:data:`LIKELY_UNITS`).
    """
    si_unit = SI_UNITS[dimension]
    if isinstance(value, bool) or value is None:
        raise ValueError(f"expected {_human(dimension)}, got {value!r}")
    number, unit = number_and_unit(value)
    if not unit:
        return number  # bare numbers are SI (percent for 'percent')
    unit = SHOP_UNITS.get(dimension, {}).get(" ".join(unit.split()), unit)
    likely = _likely_unit(unit, dimension)
    meant = f": did you mean '{number:g} {likely}'?" if likely else ""
    ureg = registry()
    try:
        quantity = ureg.Quantity(number, unit.replace("%", "percent"))
    except Exception:  # pint raises several types for unknown/ill-formed units
        raise ValueError(f"unknown unit {unit!r} in {value!r}{meant}") from None
    wanted = ureg.Quantity(1, si_unit) if si_unit else ureg.Quantity(1, "")
    if quantity.dimensionality != wanted.dimensionality:
        read = f" (pint reads {unit!r} as {quantity.units:P})" if likely else ""
        raise ValueError(f"{value!r} has the wrong dimension{read}: expected "
                         f"{_human(dimension)}{meant}")
    if likely:  # the dimension agrees, but the spelling is ambiguous for it
        si = float(quantity.to(si_unit).magnitude)
        raise ValueError(f"{value!r} is ambiguous for {_human(dimension)}: did you mean "
                         f"'{number:g} {likely}'? (pint reads it as {si:g} {si_unit})")
    return float(quantity.to(si_unit if si_unit else "").magnitude)


def is_bare_number(value: Any) -> bool:
    """True for a number without units (a YAML number, or text such as ``'1e-3'``).

    Parameters
    ----------
    value : object
        A scene value.

    Returns
    -------
    bool
        False for booleans, strings with a unit and every other type.
    """
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return True
    if isinstance(value, str):
        match = _NUMBER_THEN_UNIT.match(value)
        return bool(match) and not match.group("unit")
    return False


def temperature_difference(value: Any) -> float:
    """A temperature difference in K.

    ``"95 K"``, ``"95 degC"`` or ``"171 degF"`` are read as differences (a rise of 95 degC is
    95 K, not 368.15 K); a bare number is K.

    Parameters
    ----------
    value : float or str
        The difference, bare [K] or with units.

    Returns
    -------
    float
        The difference [K].

    Raises
    ------
    ValueError
        As :func:`to_si` (not a temperature, unknown unit).
    """
    if isinstance(value, str):
        value = re.sub(r"(?<![A-Za-z_])(deg_?C|degC|°C|celsius|deg_?F|degF|°F|fahrenheit)\b",
                       lambda m: "delta_degF" if "F" in m.group(1) or "fahr" in m.group(1)
                       else "delta_degC", value)
    return to_si(value, "temperature")


def parse_duration(text: Any) -> float:
    """A duration such as ``"6 months"``, ``"30d"`` or ``3600`` (s) in seconds.

    Parameters
    ----------
    text : float or str
        The duration, bare [s] or with a time unit (a unit written against the number, as in
        ``"30d"``, is accepted).

    Returns
    -------
    float
        The duration [s].

    Raises
    ------
    ValueError
        As :func:`to_si` (not a time, unknown unit).
    """
    if isinstance(text, str):
        text = re.sub(r"^\s*([-+]?[\d.eE+-]+)\s*([A-Za-z])", r"\1 \2", text)
    return to_si(text, "time")


_PINT_NAMES = {"%": "percent", "1": "dimensionless", "": "dimensionless"}


def convert(values, unit: str, to: str):
    """``values`` from ``unit`` to ``to`` for display (``K`` to ``degC``, ``m`` to ``mm``).

    ``%`` and ``1`` are understood; the values are returned unchanged when the units agree or
    ``to`` is empty.

    Parameters
    ----------
    values : float or array_like
        The values [``unit``].
    unit : str
        Their unit, a pint expression (``"K"``, ``"m"``, ``"%"``, ``"1"``).
    to : str
        The unit wanted.

    Returns
    -------
    numpy.ndarray
        The values [``to``].

    Raises
    ------
    pint.errors.DimensionalityError
        When ``unit`` cannot be converted to ``to``.
    """
    # deferred: keeps numpy off the start-up path
    import numpy as np

    values = np.asarray(values, float)
    if not to or to == unit:
        return values
    quantity = registry().Quantity(values, _PINT_NAMES.get(unit, unit))
    return quantity.to(_PINT_NAMES.get(to, to)).magnitude
