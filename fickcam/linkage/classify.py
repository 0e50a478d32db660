"""Grashof classification (Norton, Design of Machinery 5th ed., ch. 2:
S + L <= P + Q) with the crank (link 2) as input and link 1 as the frame."""
from __future__ import annotations

import numpy as np

from ..mechanisms.ageing import first_change
from ..errors import format_duration
from ..messages import note

CRANK_ROCKER = "crank-rocker"
DOUBLE_CRANK = "double-crank"
DOUBLE_ROCKER = "double-rocker"
CHANGE_POINT = "change-point"
NON_GRASHOF = "non-Grashof"
#: classes in which the input crank turns through a full revolution
FULL_ROTATION = {CRANK_ROCKER, DOUBLE_CRANK, CHANGE_POINT}


def grashof_condition(a, b, c, d) -> float:
    """(P + Q) - (S + L), relative to the sum of the lengths: > 0 Grashof, = 0 change
    point, < 0 non-Grashof (Norton ch. 2).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and frame lengths [m] (any one length unit).

    Returns
    -------
    float
        (P + Q - S - L) / (S + L + P + Q) [-].

    References
    ----------
    Norton (2012), ch. 2; in full in :mod:`fickcam.linkage`.
    """
    s = np.sort(np.array([a, b, c, d], float))
    return float((s[1] + s[2] - s[0] - s[3]) / s.sum())


def grashof_class(a, b, c, d, tolerance: float = 1e-9) -> str:
    """Class of the four-bar with crank a, coupler b, rocker c, frame d (Norton ch. 2):
    Grashof with the crank shortest -> crank-rocker, frame shortest -> double-crank,
    coupler or rocker shortest -> double-rocker; S + L = P + Q -> change-point;
    S + L > P + Q -> non-Grashof (triple rocker).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and frame lengths [m] (any one length unit).
    tolerance : float
        A margin :func:`grashof_condition` within this of zero is a change point [-]
        (relative to the sum of the lengths).

    Returns
    -------
    str
        "crank-rocker", "double-crank", "double-rocker", "change-point" or "non-Grashof".

    References
    ----------
    Norton (2012), ch. 2; in full in :mod:`fickcam.linkage`.
    """
    margin = grashof_condition(a, b, c, d)
    if abs(margin) <= tolerance:
        return CHANGE_POINT
    if margin < 0:
        return NON_GRASHOF
    shortest = int(np.argmin([a, b, c, d]))
    return {0: CRANK_ROCKER, 3: DOUBLE_CRANK}.get(shortest, DOUBLE_ROCKER)


def class_changes(classes, times) -> list[str]:
    """Notices where ageing changes the Grashof class, and a warning when the crank
    loses (or regains) its full rotation.

    Parameters
    ----------
    classes : sequence of str
        The class at each ageing time ('' where not computed).
    times : array_like
        The ageing times [s].

    Returns
    -------
    list of str
        The notices, in time order; a regained rotation is a note
        (:func:`fickcam.messages.note`).
    """

    classes = [str(c) for c in classes]
    span = float(np.max(times)) if len(times) else None
    notices = first_change(np.asarray(classes, dtype=object), np.asarray(times, float),
                           "the Grashof class")
    previous = None
    for k, label in enumerate(classes):
        if not label:
            continue
        rotates = label in FULL_ROTATION
        if previous is not None and previous != rotates:
            said = f"at t = {format_duration(times[k], span)}: the crank can"
            notices.append(f"{said} no longer make a full revolution ({label})" if previous
                           else note(f"{said} make a full revolution again ({label})"))
        previous = rotates
    return notices
