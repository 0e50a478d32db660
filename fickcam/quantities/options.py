"""Quantities given on the command line, read and judged as the same value in a scene.

An option's text is validated by the scene's own type for that value
(:func:`fickcam.quantities.types.quantity`, or a scene model's field): a bare number is read in the
SI unit of its dimension, a bare rotational speed is refused, bounds are the scene's.
Where a scene judges a bare value against its context (an ageing time against the
history it samples), the option's is judged by the same :class:`fickcam.quantities.plausibility.Reading`:
an almost certain unit slip is refused with the likely unit, an unusual value is warned
about. Every refusal is one line that names the option (``--at 45: ...``).
"""
from __future__ import annotations

import logging
import math

from ..errors import InputError

log = logging.getLogger("fickcam")


def _reason(error) -> str:
    """pydantic's first reason, as a scene problem gives it (no 'Value error, ')."""
    reason = error.errors(include_url=False)[0]["msg"]
    reason = reason.removeprefix("Value error, ")
    return reason[:1].lower() + reason[1:]


def option_value(option: str, text, kind, reading=None) -> float:
    """The value of a command-line option, validated as the scene validates that value.

    Parameters
    ----------
    option : str
        The option, for messages (``"--at"``).
    text : str or float
        The value as given: a number, or text with a unit (``"45 d"``).
    kind : object
        The scene's type of the value: a :func:`fickcam.quantities.types.quantity` type, or
        ``typing.Annotated[float, FieldInfo]`` of a scene model's field.
    reading : fickcam.quantities.plausibility.Reading, optional
        How a bare value is judged in its context, as the scene judges it; None: only as
        ``kind`` judges it.

    Returns
    -------
    float
        The value [SI unit of its dimension].

    Raises
    ------
    fickcam.errors.InputError
        One line naming the option: not a number, a wrong or ambiguous unit, out of the
        scene's bounds, or a bare number that is almost certainly a unit slip.
    """
    from pydantic import TypeAdapter, ValidationError

    from .plausibility import Verdict, bare_judgement
    from .parsing import is_bare_number

    shown = " ".join(str(text).split())
    try:
        value = float(TypeAdapter(kind).validate_python(text))
    except ValidationError as exc:
        raise InputError(f"{option} {shown}: {_reason(exc)}") from None
    if reading is not None and is_bare_number(text) and value > 0:
        judged = bare_judgement(value, reading)
        if judged is not None and judged[0] is Verdict.IMPLAUSIBLE:
            raise InputError(f"{option} {shown}: {judged[1]}")
        if judged is not None:
            log.warning("%s %s: %s", option, shown, judged[1])
    return value


def ageing_time(option: str, text, end: float) -> float:
    """An ageing time given as an option, read as a scene's ageing time and judged, when
    bare, against the history it samples as the scene's last ageing time is; zero needs
    no unit.

    Parameters
    ----------
    option : str
        The option (``"--at"``, ``"--over"``, ``"--time"``).
    text : str or float
        The time as given (``"45 d"``; a bare number is seconds, as in a scene).
    end : float
        The end of the history (or of the stored ageing times) it samples [s].

    Returns
    -------
    float
        The time [s].

    Raises
    ------
    fickcam.errors.InputError
        One line naming the option: ``--at 45: 45 s is an implausible ageing time (the
        history lasts 60 d): did you mean '45 d'? ...``. Whether the time lies inside
        the history is the caller's to say.
    """
    from .plausibility import output_time_reading
    from .types import NonNegativeTime

    return option_value(option, text, NonNegativeTime, output_time_reading("ageing time", end))


def angle_degrees(option: str, text) -> float | None:
    """An angle option in degrees (the unit of a result's angles), read as a scene's angle:
    ``"120 deg"``, or a bare number in radians judged as the scene judges one (``120`` is
    more than a turn: did you mean '120 deg'?).

    Parameters
    ----------
    option : str
        The option (``"--cam-angle"``).
    text : str or None
        The angle as given; None when the option was not given.

    Returns
    -------
    float or None
        The angle [deg]; None for None.

    Raises
    ------
    fickcam.errors.InputError
        One line naming the option.
    """
    from .types import Angle

    return None if text is None else math.degrees(option_value(option, text, Angle))


def field_value(option: str, text, model, name: str):
    """An option that overrides a scene key, validated by that key's field (its type and
    bounds): ``--accuracy`` as ``diffusion.accuracy``.

    Parameters
    ----------
    option : str
        The option.
    text : str or None
        The value as given; None when the option was not given.
    model : type of pydantic.BaseModel
        The scene section the key belongs to.
    name : str
        The key.

    Returns
    -------
    float or None
        The value [the key's unit]; None for None.

    Raises
    ------
    fickcam.errors.InputError
        One line naming the option.
    """
    from typing import Annotated

    if text is None:
        return None
    field = model.model_fields[name]
    return option_value(option, text, Annotated[field.annotation, field])
