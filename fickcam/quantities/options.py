"""Quantities given on the command line, read and judged as the same value in a scene.

An option's text is validated by the scene's own type for that value
(:func:`fickcam.quantities.types.quantity`, or a scene model's field): a bare number is read in the
SI unit of its dimension, a bare rotational speed is refused, bounds are the scene's; a
bare angle, which a scene reads in radians, is refused too (:func:`angle`): the command
line shows angles in degrees.
Where a scene judges a bare value against its context (an ageing time against the
history it samples), the option's is judged by the same :class:`fickcam.quantities.plausibility.Reading`:
an almost certain unit slip is refused with the likely unit, an unusual value is warned
about. Every refusal is one line that names the option (``--at 45: ...``).
"""
from __future__ import annotations

from typing import Annotated
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
    # deferred: keeps pydantic off the start-up path
    from pydantic import TypeAdapter, ValidationError

    # deferred: keeps the command's modules off the start-up path
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
    # deferred: keeps the command's modules off the start-up path
    from .plausibility import output_time_reading
    from .types import NonNegativeTime

    return option_value(option, text, NonNegativeTime, output_time_reading("ageing time", end))


def angle(option: str, text, kind=None) -> float:
    """An angle option, read as a scene's angle, except that a bare number other than zero
    is refused: the command line's angles are read and printed in degrees, so a bare
    ``--cam-angle 5`` is as likely 5 deg as 5 rad
    (:data:`fickcam.quantities.plausibility.OPTION_AMBIGUOUS`).

    Parameters
    ----------
    option : str
        The option (``"--cam-angle"``).
    text : str
        The angle as given (``"120 deg"``).
    kind : object, optional
        The scene's type of the value (default ``fickcam.quantities.types.Angle``).

    Returns
    -------
    float
        The angle [rad].

    Raises
    ------
    fickcam.errors.InputError
        One line naming the option: ``--cam-angle 5: 5 without a unit is ambiguous for an
        angle (deg or rad): did you mean '5 deg'? ...``.
    """
    # deferred: keeps pydantic off the start-up path
    from .plausibility import OPTION_AMBIGUOUS, ambiguity
    from .types import Angle

    slip = ambiguity(text, "angle", OPTION_AMBIGUOUS)
    if slip:
        raise InputError(f"{option} {' '.join(str(text).split())}: {slip}")
    return option_value(option, text, Angle if kind is None else kind)


def angle_degrees(option: str, text) -> float | None:
    """An angle option in degrees (the unit of a result's angles), read by :func:`angle`:
    ``"120 deg"``; a bare number other than zero is refused (did you mean '120 deg'?).

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
    return None if text is None else math.degrees(angle(option, text))


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

    if text is None:
        return None
    field = model.model_fields[name]
    return option_value(option, text, Annotated[field.annotation, field])
