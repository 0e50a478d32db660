"""The error budget: the accuracy a user may ask for, checked in one place
(``check_accuracy``), and how each solve shares the accuracy it is asked between the errors
it makes (the mesh, the steps in time, the interpolation of a tabulated response, a
quadrature...). Every share and margin of the engine is here, named for what it divides and
documented with why it has its value; the modules that spend a share import it from here.

A share ``s`` of the accuracy ``a`` means the part of the error that one approximation may
make is ``s a``; the shares of one solve add up to at most 1. A margin ``m`` (> 1) means a
plan aims at ``a / m`` where its own error model is known to be optimistic.

This module imports nothing of fickcam but the errors, so the scene (which checks
``diffusion.accuracy`` with ``check_accuracy``) loads no part of the engine with it.
"""
from __future__ import annotations

import math

from ...errors import InputError

#: The accuracy a run may ask for: a relative error of the mean moisture [-], a fraction of
#: the moisture swing, in (0, ``MAX_ACCURACY``]. Coarser than 10 % is not an estimate of a
#: moisture any more (the error models behind the plans are measured up to a few %).
MAX_ACCURACY = 0.1


def accuracy_problem(value) -> str | None:
    """Why ``value`` is not an accuracy a run may ask for, or None when it is.

    Parameters
    ----------
    value : float
        The relative accuracy asked [-].

    Returns
    -------
    str or None
        The reason, one phrase ("must lie in (0, 0.1] ..."); None: accepted.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value) or not 0 < value <= MAX_ACCURACY:
        return (f"must lie in (0, {MAX_ACCURACY:g}], a fraction of the moisture swing "
                f"(e.g. 1e-3)")
    return None


def check_accuracy(value, name: str = "accuracy") -> float:
    """The accuracy a run asks for, refused outside (0, ``MAX_ACCURACY``] with one line:
    the one check of the accepted range (the scene's ``diffusion.accuracy``, the command
    line's ``--accuracy``, ``fickcam.run(accuracy=...)`` and ``solve`` all apply it).

    Parameters
    ----------
    value : float
        The relative accuracy asked [-], a fraction of the moisture swing.
    name : str
        What the value was given as, for the message (``accuracy``, ``--accuracy``,
        ``diffusion.accuracy``).

    Returns
    -------
    float
        ``value`` as a float [-].

    Raises
    ------
    fickcam.errors.InputError
        One line naming ``name``, the value and the accepted range.
    """
    why = accuracy_problem(value)
    if why is not None:
        raise InputError(f"{name} {value!r}: {why}")
    return float(value)
