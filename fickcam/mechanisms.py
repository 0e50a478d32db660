"""Mechanisms over ageing: map each part's material state onto the cam and
four-bar models at every ageing time, and collect their responses.

The physics lives in :mod:`fickcam.cam` and :mod:`fickcam.linkage` (pure
functions of one geometry and state); this module only says which state
variable of which part feeds which input, and gathers the arrays over time.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from .errors import format_duration
from .messages import restated
from .response import Response


def over_ageing(times: np.ndarray, valid: np.ndarray, evaluate: Callable[[int], Response],
                on_step: Callable[[], object] = lambda: None) -> Response:
    """Evaluate ``evaluate(k)`` at every valid ageing time k and stack the results.

    Scalars become arrays over time, arrays over angle become (time, angle); invalid times
    stay NaN (or '' for text). Identical notices at several times are reported once, with
    the first time and how often they recur.

    Parameters
    ----------
    times : numpy.ndarray
        The ageing times [s].
    valid : numpy.ndarray of bool
        Where the mechanism is evaluated (its parts are in their model's domain).
    evaluate : callable
        ``evaluate(k) -> Response`` at ageing index k.
    on_step : callable
        Called after each ageing time (a progress bar's update).

    Returns
    -------
    Response
        The stacked variables [their SI units] and the notices, each with its ageing time.
    """
    stacked: dict[str, np.ndarray] = {}
    seen: dict[str, list[float]] = {}
    for k, t in enumerate(times):
        if valid[k]:
            response = evaluate(k)
            for name, value in response.variables.items():
                value = np.asarray(value)
                if name not in stacked:
                    if value.dtype.kind in "US":
                        stacked[name] = np.full((len(times),) + value.shape, "", dtype=object)
                    else:
                        stacked[name] = np.full((len(times),) + value.shape, np.nan)
                stacked[name][k] = value
            for message in response.notices:
                seen.setdefault(message, []).append(float(t))
        on_step()
    notices = []
    span = float(np.max(times)) if len(times) else None  # one unit of time for the whole run
    for message, when in seen.items():
        tail = f" (and at {len(when) - 1} later ageing time(s))" if len(when) > 1 else ""
        notices.append(restated(message, f"at t = {format_duration(when[0], span)}: "
                                         f"{message}{tail}"))
    variables = {name: (value.astype(str) if value.dtype == object else value)
                 for name, value in stacked.items()}
    return Response(variables, notices)


def first_change(values: np.ndarray, times: np.ndarray, what: str) -> list[str]:
    """Notices where a per-time label (e.g. the Grashof class) changes.

    Parameters
    ----------
    values : numpy.ndarray of str
        The label at each ageing time ("" where unknown: no change is told across it).
    times : numpy.ndarray
        The ageing times [s].
    what : str
        What the label is, for the notice.

    Returns
    -------
    list of str
        ``at t = ...: WHAT changed from A to B``, one per change.
    """
    notices = []
    span = float(np.max(times)) if len(times) else None
    for k in range(1, len(values)):
        if values[k] and values[k - 1] and values[k] != values[k - 1]:
            notices.append(f"at t = {format_duration(times[k], span)}: {what} changed from "
                           f"{values[k - 1]} to {values[k]}")
    return notices
